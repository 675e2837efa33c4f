//! Resolution of the scene's stages: [`Stage`], a generated schedule and the earthquake as
//! stages, and the loads of each stage.

use super::dynamic;
use super::error::SceneError;
use super::modal;
use super::schema::{HydrostaticSpec, LoadsSpec, MeshSource, SceneFile, StageSpec};
use super::term::Term;
use crate::mesh::dam_stages::CfrdStage;
use crate::mesh::Mesh;
use std::path::Path;

/// The stages of the scene with their terms; a scene without stages has one stage `static`
/// that places every block.
pub(super) fn resolve_stages(
    file: &SceneFile,
    mesh: &Mesh,
    base: &Path,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Vec<Stage>, SceneError> {
    let mut stages = Vec::new();
    if file.stages.is_empty() {
        stages.push(Stage {
            name: "static".into(),
            activate: (0..mesh.blocks.len() as u32).collect(),
            terms: resolve_loads(&file.loads, None, mesh, "loads", inv)?,
            load_steps: file.solver.load_steps,
            step_growth: file.solver.step_growth,
            dynamic: None,
            modal: None,
        });
    } else {
        let mut placed = vec![None::<usize>; mesh.blocks.len()];
        for k in 0..file.stages.len() {
            let stage = resolve_stage(file, mesh, base, k, &mut placed, &stages, inv)?;
            stages.push(stage);
        }
    }
    Ok(stages)
}

/// Resolves `file.stages[k]` after the stages `before`; `placed` holds the stage that placed
/// each block so far. A name used twice, an unknown block, a block placed twice, `load_steps`
/// on a dynamic stage, a second modal analysis, a modal or dynamic stage before any block is
/// placed and a dynamic stage directly after another are errors.
pub(super) fn resolve_stage(
    file: &SceneFile,
    mesh: &Mesh,
    base: &Path,
    k: usize,
    placed: &mut [Option<usize>],
    before: &[Stage],
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Stage, SceneError> {
    let st = &file.stages[k];
    if file.stages[..k].iter().any(|o| o.name == st.name) {
        return Err(inv(
            &format!("stages[{k}].name"),
            format!("stage name '{}' is used twice", st.name),
        ));
    }
    let mut activate = Vec::new();
    for (i, b) in st.activate.iter().enumerate() {
        let path = format!("stages[{k}].activate[{i}]");
        let Some(bi) = mesh.block_index(b) else {
            return Err(inv(&path, format!("the mesh has no block '{b}'")));
        };
        if let Some(first) = placed[bi as usize] {
            return Err(inv(
                &path,
                format!("block '{b}' is already placed in stage {first}"),
            ));
        }
        placed[bi as usize] = Some(k);
        activate.push(bi);
    }
    let dynamic = match &st.dynamic {
        Some(d) => Some(dynamic::resolve(d, base, &format!("stages[{k}].dynamic"), inv)?),
        None => None,
    };
    let (load_steps, step_growth) = match &dynamic {
        Some(d) if st.load_steps.is_some() => {
            return Err(inv(
                &format!("stages[{k}].load_steps"),
                format!(
                    "a dynamic stage steps in time: its {} steps are `dynamic.duration` over \
                     `dynamic.dt`; `load_steps` is for static stages only",
                    d.steps
                ),
            ))
        }
        Some(d) => (d.steps, 1),
        None => (
            st.load_steps.unwrap_or(file.solver.load_steps),
            file.solver.step_growth,
        ),
    };
    let stage_path = format!("stages[{k}]");
    let modal = modal::resolve(st.modal.as_ref(), dynamic.as_ref(), &stage_path, inv)?;
    let kind = StageKind {
        name: &st.name,
        modal: modal.is_some(),
        dynamic: dynamic.is_some(),
    };
    check_stage_kind(&kind, &stage_path, placed, before, inv)?;
    Ok(Stage {
        name: st.name.clone(),
        activate,
        terms: resolve_loads(
            &file.loads,
            Some(&st.loads),
            mesh,
            &format!("stages[{k}].loads"),
            inv,
        )?,
        load_steps,
        step_growth,
        dynamic,
        modal,
    })
}

/// What [`check_stage_kind`] checks of a stage: its name and whether it runs a modal analysis
/// and steps in time.
struct StageKind<'a> {
    name: &'a str,
    modal: bool,
    dynamic: bool,
}

/// A second modal analysis, a modal or dynamic stage before any block is placed (`placed`:
/// the stage that placed each block so far) and a dynamic stage directly after another are
/// errors naming `stage_path`.
fn check_stage_kind(
    st: &StageKind<'_>,
    stage_path: &str,
    placed: &[Option<usize>],
    before: &[Stage],
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<(), SceneError> {
    if let (true, Some(first)) = (st.modal, before.iter().position(|s: &Stage| s.modal.is_some())) {
        return Err(inv(
            stage_path,
            format!(
                "a modal analysis runs already in stage {} '{}'; a scene runs at most one",
                first + 1,
                before[first].name
            ),
        ));
    }
    if (st.modal || st.dynamic) && placed.iter().all(Option::is_none) {
        let what = if st.modal {
            "modal analysis"
        } else {
            "dynamic stage"
        };
        return Err(inv(
            stage_path,
            format!(
                "a {what} needs placed blocks, but no block is placed by stage '{}': list the \
                 blocks in `activate` of this stage or of a stage before it",
                st.name
            ),
        ));
    }
    if let (true, Some(previous)) = (st.dynamic, before.last().filter(|s| s.dynamic.is_some())) {
        return Err(inv(
            &format!("{stage_path}.dynamic"),
            format!(
                "a dynamic stage directly after the dynamic stage '{}' would start at rest (each \
                 dynamic stage starts with zero velocity relative to the base) and cut its \
                 motion off; make them one stage (a `duration` beyond the record gives a quiet \
                 tail after it), or put a static stage between them",
                previous.name
            ),
        ));
    }
    Ok(())
}

/// Appends the scene's `earthquake` as a dynamic stage after the last stage, with that
/// stage's own loads (the scene-wide loads apply to every stage anyway).
pub(super) fn append_earthquake(
    file: &mut SceneFile,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<(), SceneError> {
    let Some(quake) = file.earthquake.clone() else {
        return Ok(());
    };
    let Some(last) = file.stages.last() else {
        return Err(inv(
            "earthquake",
            "needs stages before it (`stages`, or the schedule of `mesh.cfrd`)".into(),
        ));
    };
    let loads = last.loads.clone();
    file.stages.push(StageSpec {
        name: "earthquake".into(),
        activate: Vec::new(),
        loads,
        load_steps: None,
        dynamic: Some(quake),
        modal: None,
    });
    Ok(())
}

/// The stages of a generated schedule as scene stages (impoundment levels become hydrostatic
/// loads on the slab face set `slab_upstream`).
pub(super) fn schedule_stages(schedule: &[CfrdStage], src: &MeshSource) -> Vec<StageSpec> {
    let unit_weight = src.cfrd.as_ref().map_or(9810.0, |c| c.water_unit_weight);
    schedule
        .iter()
        .map(|st| StageSpec {
            name: st.name.clone(),
            activate: st.activate.clone(),
            loads: LoadsSpec {
                hydrostatic: st
                    .water_level
                    .map(|level| HydrostaticSpec {
                        faces: "slab_upstream".into(),
                        level,
                        unit_weight,
                    })
                    .into_iter()
                    .collect(),
                ..LoadsSpec::default()
            },
            load_steps: st.load_steps,
            dynamic: None,
            modal: None,
        })
        .collect()
}

/// One resolved stage: blocks placed at its start, the loads at its end, and its load steps.
///
/// Within a stage the external force goes linearly from the force at the end of the previous
/// stage to the force of this stage's terms on every active element (load factor λ ∈ (0, 1]).
#[derive(Debug, Clone, PartialEq)]
pub struct Stage {
    /// Stage name.
    pub name: String,
    /// Block indices placed (activated, strain-free) at the start of the stage.
    pub activate: Vec<u32>,
    /// The physics terms at the end of the stage (besides the internal force, always present).
    pub terms: Vec<Term>,
    /// Number of equal load steps (time steps of a dynamic stage).
    pub load_steps: u32,
    /// How far an easy load step may grow over the nominal one (`solver.step_growth`; 1 for a
    /// dynamic stage, whose time steps stay equal).
    pub step_growth: u32,
    /// How a dynamic stage is integrated in time; `None` for a static stage.
    pub dynamic: Option<super::dynamic::DynamicStage>,
    /// The modal analysis at the stage's start, if any ([`super::modal`]).
    pub modal: Option<super::modal::ModalRequest>,
}

impl Stage {
    /// The end of the stage's time: 1 for a static stage (its time is the load factor), the
    /// duration (s) of a dynamic one.
    pub fn t_end(&self) -> f64 {
        self.dynamic.as_ref().map_or(1.0, |d| d.duration)
    }
}

/// The terms of the scene-wide loads plus a stage's own loads; face sets are checked.
pub(super) fn resolve_loads(
    base: &LoadsSpec,
    stage: Option<&LoadsSpec>,
    mesh: &Mesh,
    path: &str,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Vec<Term>, SceneError> {
    let mut terms = Vec::new();
    for (which, loads) in [(String::from("loads"), Some(base)), (path.to_string(), stage)] {
        let Some(loads) = loads else { continue };
        if let Some(g) = &loads.gravity {
            if terms.iter().any(|t| matches!(t, Term::Gravity { .. })) {
                return Err(inv(
                    &format!("{which}.gravity"),
                    "gravity is already given in the scene's loads".into(),
                ));
            }
            terms.push(Term::Gravity { g: g.g });
        }
        for (i, p) in loads.pressure.iter().enumerate() {
            if !mesh.face_sets.contains_key(&p.faces) {
                return Err(inv(
                    &format!("{which}.pressure[{i}].faces"),
                    format!("the mesh has no face set '{}'", p.faces),
                ));
            }
            terms.push(Term::Pressure {
                faces: p.faces.clone(),
                value: p.value,
            });
        }
        for (i, h) in loads.hydrostatic.iter().enumerate() {
            if !mesh.face_sets.contains_key(&h.faces) {
                return Err(inv(
                    &format!("{which}.hydrostatic[{i}].faces"),
                    format!("the mesh has no face set '{}'", h.faces),
                ));
            }
            terms.push(Term::Hydrostatic {
                faces: h.faces.clone(),
                level: h.level,
                unit_weight: h.unit_weight,
            });
        }
    }
    Ok(terms)
}
