//! The construction and impoundment schedule of the generated CFRD: one stage per fill layer,
//! the slab stages and the impoundment stages (the generator's "Schedule").

use super::dam_spec::{CfrdSpec, Layout, ZONES};

/// One stage of the generated schedule.
#[derive(Debug, Clone, PartialEq)]
pub struct CfrdStage {
    /// Stage name (`fill_KKK`, `slab_S`, `impound_N`).
    pub name: String,
    /// Blocks placed at the start of the stage.
    pub activate: Vec<String>,
    /// Reservoir level (m, elevation) on the face set `slab_upstream` at the end of the stage
    /// (impoundment stages only).
    pub water_level: Option<f64>,
    /// Load steps of the stage (`None`: the scene's `solver.load_steps`).
    pub load_steps: Option<u32>,
}

/// The stages: one per fill layer with slab stage 1 after the cast layer, the other slab
/// stages, then the impoundment stages; `stage_blocks` are the blocks of each slab stage.
pub(super) fn schedule(spec: &CfrdSpec, lay: &Layout, stage_blocks: &[Vec<String>]) -> Vec<CfrdStage> {
    let zb = spec.base_elevation;
    let mut stages = Vec::new();
    let slab_stage = |s: usize| CfrdStage {
        name: format!("slab_{}", s + 1),
        activate: stage_blocks[s].clone(),
        water_level: None,
        load_steps: None,
    };
    for k in 0..spec.fill_layers {
        stages.push(CfrdStage {
            name: format!("fill_{:03}", k + 1),
            activate: ZONES.iter().map(|z| format!("fill_{:03}_{z}", k + 1)).collect(),
            water_level: None,
            load_steps: spec.fill_load_steps,
        });
        if k + 1 == lay.cast_layer {
            stages.push(slab_stage(0));
        }
    }
    for s in 1..lay.stage_rows.len() {
        stages.push(slab_stage(s));
    }
    let n_imp = spec.impoundment_stages;
    for n in 1..=n_imp {
        stages.push(CfrdStage {
            name: format!("impound_{n}"),
            activate: Vec::new(),
            water_level: Some(zb + (spec.impoundment_level - zb) * n as f64 / n_imp as f64),
            load_steps: None,
        });
    }
    stages
}
