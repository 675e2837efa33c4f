//! Checkpoint pacing: when a run writes `checkpoint.h5`. Stage checkpoints come at the end of a
//! stage when the pacing says the run has computed long enough since the last write
//! ([`crate::io::pacing`]), and always after the stage a run ends with; step checkpoints
//! (`--checkpoint step`) after every N-th converged step, unpaced. With the default checkpoints
//! of a staged scene (`output.checkpoint` left out) a dynamic stage also writes a step
//! checkpoint every [`DYNAMIC_STEPS_PER_CHECKPOINT`] of its time steps, counted from the
//! stage's start, so that a long quake killed midway loses at most that many steps. Every
//! step checkpoint follows the publication of the results written so far, so the results a
//! restart finds beside its checkpoint hold every step before it.

use super::observer::{Halt, Observer, Run, StepAt};
use super::options::{input, io_failure, RunFailure, RunOptions, StopAfter};
use super::schedule::Plan;
use crate::io::checkpoint::{self, CHECKPOINT_FILE};
use crate::io::pacing::StageEndWrites;
use crate::io::summary::Phase;
use crate::parallel::any_error;
use crate::scene::schema::CheckpointMode;
use crate::scene::Scene;
use crate::solver::StepControl;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Time steps of a dynamic stage between two of its step checkpoints under the default
/// checkpoints: on the fine seed quake some 6 min of computing against a few seconds of
/// writing; a count of steps, not a time, so that where checkpoints fall (each starts a fresh
/// preconditioner) and thus the results do not depend on the machine's speed.
pub const DYNAMIC_STEPS_PER_CHECKPOINT: u32 = 100;

/// What the run was asked about checkpoints, and the pacing of its stage-end writes.
pub struct CheckpointPacer {
    /// Whether the run writes checkpoints at all.
    enabled: bool,
    /// Whether it writes them after steps too.
    steps: bool,
    /// Step checkpoints after every `every`-th converged step of the run.
    every: u32,
    /// Step checkpoints inside dynamic stages after every this many of their steps (the
    /// default checkpoints).
    dynamic_every: Option<u32>,
    /// The stage (1-based) after which the run ends on `--stop-after-stage`.
    stop_after: Option<usize>,
    path: PathBuf,
    writes: StageEndWrites,
}

impl CheckpointPacer {
    /// The checkpoint settings of `opts` over the scene's, for a run that starts at stage index
    /// `first_stage`; a `--stop-after-stage` that the run could not honour is an input error.
    pub fn new(
        scene: &Scene,
        opts: &RunOptions,
        first_stage: usize,
        out_dir: &Path,
    ) -> Result<Self, RunFailure> {
        let mode = opts.checkpoint.or(scene.file.output.checkpoint);
        let enabled = match mode {
            Some(mode) => mode != CheckpointMode::None,
            None => !scene.file.stages.is_empty(),
        };
        let n = scene.stages.len();
        let stop_after = opts.stop_after_stage.map(|s| match s {
            StopAfter::Stage(k) => k,
            StopAfter::Stages(count) => (first_stage + count).min(n),
        });
        if let Some(stop) = stop_after {
            if !enabled {
                return Err(input(format!(
                    "--stop-after-stage {stop}: the run writes no checkpoints (output.checkpoint or \
                     --checkpoint), so it could not be continued"
                )));
            }
            if stop <= first_stage || stop > n {
                return Err(input(format!(
                    "--stop-after-stage {stop}: not one of the stages this run runs ({} to {n})",
                    first_stage + 1
                )));
            }
        }
        Ok(CheckpointPacer {
            enabled,
            steps: mode == Some(CheckpointMode::Step),
            every: opts.checkpoint_every.unwrap_or(1).max(1),
            dynamic_every: (enabled && mode.is_none()).then_some(DYNAMIC_STEPS_PER_CHECKPOINT),
            stop_after,
            path: out_dir.join(CHECKPOINT_FILE),
            writes: StageEndWrites::new(),
        })
    }

    /// The schedule of a run that starts at stage index `first_stage` (inside it at `resume`,
    /// from a step checkpoint) and ends where `--stop-after-stage` says, naming this
    /// checkpoint to continue from.
    pub fn plan(&self, first_stage: usize, resume: Option<StepControl>, verbose: bool) -> Plan {
        Plan {
            first_stage,
            resume,
            stop_after: self.stop_after,
            verbose,
            checkpoint: self.path.clone(),
        }
    }

    /// Writes the checkpoint (`within`: inside a stage) and counts its seconds. Collective.
    fn write(&self, run: &mut Run<'_, '_>, within: Option<StepControl>) -> Result<(), RunFailure> {
        let t0 = Instant::now();
        let written = checkpoint::write(run.world, &self.path, run.scene, run.problem, run.report, within);
        any_error(run.world, written)
            .map_err(|m| io_failure(&format!("writing the checkpoint {}", self.path.display()), m))?;
        run.record.checkpoint_seconds += t0.elapsed().as_secs_f64();
        Ok(())
    }
}

impl Observer for CheckpointPacer {
    fn on_step(&mut self, run: &mut Run<'_, '_>, step: &StepAt<'_>) -> Result<(), Halt> {
        let asked = self.steps && run.report.steps.is_multiple_of(self.every);
        let dynamic = step.stage.stage.dynamic.is_some()
            && self
                .dynamic_every
                .is_some_and(|n| step.path.steps.is_multiple_of(n));
        if (asked || dynamic) && !step.path.done() {
            run.timer.start(Phase::Output);
            // the results before the checkpoint are published with it (module docs)
            run.publish_results()?;
            self.write(run, Some(*step.path))?;
            run.timer.stop();
            // the restart starts with a fresh preconditioner here; so does this run
            run.problem.fresh_preconditioner()?;
        }
        Ok(())
    }

    fn on_stage_end(&mut self, run: &mut Run<'_, '_>, end: &StepAt<'_>) -> Result<(), Halt> {
        let must = self.steps || end.stage.last;
        run.timer.start(Phase::Output);
        if self.enabled && self.writes.due(run.world, must) {
            let began = Instant::now();
            // the results of the completed stages are published before the checkpoint that
            // follows them: a run killed later leaves both (a stage in both a killed part's and
            // the next part's results is one run again after a kill between the two writes)
            run.publish_results()?;
            self.write(run, None)?;
            self.writes.wrote(run.world, began);
        }
        run.timer.stop();
        Ok(())
    }
}
