//! The fields of a run's earthquake (its dynamic stages, on the quake's clock) read back from
//! its results files: the state before the quake, every results step of it, and the residual
//! state (after − before) that the dynamic figures draw ([`crate::post::quake_figures`]).

use crate::io::results_reader::{open, stage_name, step_names};
use crate::post::profiles::StageFields;
use crate::post::quake_clock::QuakeClock;
use crate::scene::dynamic::DynamicStage;
use crate::scene::Scene;
use std::path::PathBuf;

/// The fields of an earthquake stage as written to the results file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct QuakeFields {
    /// Names of the dynamic stages, joined by ", ".
    pub stage: String,
    /// Time steps between two results steps (the first dynamic stage's `output_every`, 0: its
    /// end only).
    pub output_every: u32,
    /// Time step of the first dynamic stage (s).
    pub dt: f64,
    /// The state before the quake (the last results step of the stage before).
    pub before: StageFields,
    /// Time on the quake's clock (s) of each results step of the quake.
    pub t: Vec<f64>,
    /// The fields of each results step of the quake, in order; the last one is the state after
    /// the quake when the stage completed.
    pub steps: Vec<StageFields>,
}

impl QuakeFields {
    /// The state after the quake (the last results step).
    pub fn after(&self) -> &StageFields {
        self.steps.last().unwrap_or(&self.before)
    }

    /// The sampling note of the history tables (module docs).
    pub(crate) fn sampling(&self) -> String {
        let every = match self.output_every {
            0 => "at the stage's end only".to_string(),
            n => format!(
                "every {n} time step(s) ({} s where no step was cut back)",
                n as f64 * self.dt
            ),
        };
        format!(
            "# sampled at the results steps of {} '{}': {every}; t = 0 is the state before the quake",
            stage_word(&self.stage),
            self.stage
        )
    }

    /// Times with t = 0 (before the quake) first.
    pub(crate) fn times(&self) -> impl Iterator<Item = f64> + '_ {
        std::iter::once(0.0).chain(self.t.iter().copied())
    }

    /// States with the one before the quake first.
    pub(crate) fn states(&self) -> impl Iterator<Item = &StageFields> + '_ {
        std::iter::once(&self.before).chain(self.steps.iter())
    }
}

/// Reads the earthquake stages (every dynamic stage, on the quake's clock, [`QuakeClock`]) of
/// the closed results files `h5s`, the parts of one run in the order they ran (one file for a
/// run in one go). A step found again in a later part (a run killed after it and restarted
/// from an earlier checkpoint) replaces the earlier part's steps from its time on. `None` when
/// the scene has no dynamic stage after another stage, or the files lack the state before the
/// quake or any step of it.
pub fn read_quake_fields(scene: &Scene, h5s: &[PathBuf]) -> Result<Option<QuakeFields>, String> {
    let clock = QuakeClock::new(scene);
    let Some(first) = clock.first() else {
        return Ok(None);
    };
    let Some(previous) = first.checked_sub(1).map(|p| scene.stages[p].name.as_str()) else {
        return Ok(None);
    };
    let dynamic = scene.stages[first].dynamic.as_ref().expect("a dynamic stage");
    let mut before = None;
    let mut q = QuakeFields {
        stage: clock.names(scene),
        output_every: dynamic.output_every,
        dt: dynamic.dt(),
        ..Default::default()
    };
    for h5 in h5s {
        let file = open(h5)?;
        for name in step_names(&file, h5)? {
            let g = file.group(&format!("/steps/{name}")).map_err(|e| e.to_string())?;
            let this = stage_name(&g).unwrap_or_default();
            if this == previous {
                before = Some(StageFields::read(&g, h5, this)?);
                continue;
            }
            let Some((d, t0, local)) = quake_step(&clock, scene, &g, &this)? else {
                continue;
            };
            let t = t0 + on_time_grid(local, d.dt());
            while q.t.last().is_some_and(|&last| last >= t) {
                q.t.pop();
                q.steps.pop();
            }
            q.t.push(t);
            q.steps.push(StageFields::read(&g, h5, this)?);
        }
    }
    let Some(before) = before else {
        return Ok(None);
    };
    q.before = before;
    Ok((!q.steps.is_empty()).then_some(q))
}

/// The dynamic stage of the results step `g` of stage `stage` with its start on the quake's
/// clock and the step's time in the stage (s); `None` for a step of a static stage.
pub(crate) fn quake_step<'s>(
    clock: &'s QuakeClock,
    scene: &'s Scene,
    g: &hdf5::Group,
    stage: &str,
) -> Result<Option<(&'s DynamicStage, f64, f64)>, String> {
    let Some((k, _, d, t0)) = clock.stages(scene).find(|(_, s, _, _)| s.name == stage) else {
        return Ok(None);
    };
    let time: f64 = g
        .attr("time")
        .and_then(|a| a.read_scalar())
        .map_err(|e| e.to_string())?;
    Ok(Some((d, t0, (time - k as f64) * d.duration)))
}

/// "stage" for one stage name, "stages" for names joined by ", " ([`QuakeClock::names`]).
pub(crate) fn stage_word(names: &str) -> &'static str {
    if names.contains(", ") {
        "stages"
    } else {
        "stage"
    }
}

/// `t` snapped to the nearest multiple of `dt` when within 1e-6·dt of it (a step's time is
/// stored as a fraction of the stage).
pub(crate) fn on_time_grid(t: f64, dt: f64) -> f64 {
    let n = (t / dt).round();
    if (t - n * dt).abs() <= 1e-6 * dt {
        n * dt
    } else {
        t
    }
}

/// `after − before` of every field (the residual state); a field
/// missing from either is empty.
pub fn residual(before: &StageFields, after: &StageFields) -> StageFields {
    let diff = |a: &[f64], b: &[f64]| -> Vec<f64> {
        if a.len() != b.len() {
            return Vec::new();
        }
        a.iter().zip(b).map(|(x, y)| x - y).collect()
    };
    StageFields {
        name: format!("{} - {}", after.name, before.name),
        displacement: diff(&after.displacement, &before.displacement),
        stress: diff(&after.stress, &before.stress),
        interface_traction: diff(&after.interface_traction, &before.interface_traction),
        interface_jump: diff(&after.interface_jump, &before.interface_jump),
        interface_opening: diff(&after.interface_opening, &before.interface_opening),
    }
}
