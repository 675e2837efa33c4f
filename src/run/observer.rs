//! The observers of a run: what the schedule tells at its events, and the one trait through
//! which the results writer, checkpoint pacing, the quake recorder, the profiles, the progress
//! lines and the summary hear it.
//!
//! The schedule ([`super::schedule`]) owns the stage and step loop and calls every observer,
//! in the order it was given them, at the start of a stage, after every converged step, at the
//! end of a stage and when the run ends. The solver reports numbers into the run's
//! [`SolveReport`]; the observers decide what is written.

use super::options::RunFailure;
use crate::io::hdf5_out::ResultsFile;
use crate::io::summary::{ModalSummary, PhaseTimer};
use crate::scene::{Scene, Stage};
use crate::solver::{Problem, SolveError, SolveReport, StepControl};
use mpi::topology::SimpleCommunicator;
use std::path::PathBuf;

/// What a run shares with its observers at every event.
pub struct Run<'r, 'p> {
    /// The ranks of the run.
    pub world: &'p SimpleCommunicator,
    /// The scene.
    pub scene: &'p Scene,
    /// The rank-local problem.
    pub problem: &'r mut Problem<'p>,
    /// The solver's counters and histories.
    pub report: &'r mut SolveReport,
    /// Wall time by phase.
    pub timer: &'r mut PhaseTimer,
    /// The run's results file, open until the run ends.
    pub results: Option<ResultsFile>,
    /// Its path (`results.h5` of the output directory).
    pub results_path: PathBuf,
    /// The output directory.
    pub out_dir: PathBuf,
    /// What the run has done so far, for the summary.
    pub record: RunRecord,
}

/// What a run has done so far, beyond the solver's report: kept by the observers that know
/// it, read by the summary.
#[derive(Debug, Default)]
pub struct RunRecord {
    /// Stages whose results are written.
    pub stages_written: usize,
    /// Seconds spent writing checkpoints on this rank.
    pub checkpoint_seconds: f64,
    /// The modal analysis of the run, if a stage asked for one.
    pub modal: Option<ModalSummary>,
    /// The stage (1-based) after which the run stopped on `--stop-after-stage`.
    pub stopped_after: Option<u64>,
    /// The stage index the run started from (a restart's), 0 otherwise.
    pub first_stage: usize,
    /// Input files that changed since the restart's checkpoint and were accepted
    /// (`--accept-changed`), as `key: path`.
    pub accepted_changed: Vec<String>,
}

/// A stage as the schedule reports it to the observers.
pub struct StageAt<'s> {
    /// Index of the stage in the scene's schedule.
    pub k: usize,
    /// The stage.
    pub stage: &'s Stage,
    /// Whether the stage starts afresh (not resumed inside from a step checkpoint).
    pub fresh: bool,
    /// Whether the run ends after this stage (the last of the schedule, or of a run in parts).
    pub last: bool,
}

/// A converged step as the schedule reports it (at a stage's end: its last step).
pub struct StepAt<'s> {
    /// The stage of the step.
    pub stage: &'s StageAt<'s>,
    /// Where the stage stands (time or load factor after the step).
    pub path: &'s StepControl,
    /// Steps converged in this stage since its start (with those before the step checkpoint a
    /// restart continues from).
    pub steps_in_stage: u32,
    /// Wall-clock seconds since the stage began.
    pub stage_seconds: f64,
}

/// How a run ended, for [`Observer::on_finish`].
pub struct RunEnd<'s> {
    /// The failure of a stage, if one failed (the results of the completed stages are kept).
    pub failure: Option<&'s str>,
}

/// Why an observer stops the schedule.
#[derive(Debug)]
pub enum Halt {
    /// The stage fails as a solver failure would: the run ends after writing what it has.
    Solver(SolveError),
    /// The run ends at once with this failure (a write that failed).
    Failure(RunFailure),
}

impl From<RunFailure> for Halt {
    fn from(f: RunFailure) -> Self {
        Halt::Failure(f)
    }
}

impl From<SolveError> for Halt {
    fn from(e: SolveError) -> Self {
        Halt::Solver(e)
    }
}

/// One part of what a run does besides solving; every method defaults to doing nothing.
pub trait Observer {
    /// A stage begins (after the problem has begun it, or resumed it from a checkpoint).
    fn on_stage_start(&mut self, _run: &mut Run<'_, '_>, _stage: &StageAt<'_>) -> Result<(), Halt> {
        Ok(())
    }

    /// A step of the stage has converged.
    fn on_step(&mut self, _run: &mut Run<'_, '_>, _step: &StepAt<'_>) -> Result<(), Halt> {
        Ok(())
    }

    /// The stage has ended with its last step, `end`, and its end state is committed.
    fn on_stage_end(&mut self, _run: &mut Run<'_, '_>, _end: &StepAt<'_>) -> Result<(), Halt> {
        Ok(())
    }

    /// The run ends, after its last stage or a failed one.
    fn on_finish(&mut self, _run: &mut Run<'_, '_>, _end: &RunEnd<'_>) -> Result<(), RunFailure> {
        Ok(())
    }
}

impl Run<'_, '_> {
    /// Closes the results file (collective): the stages completed so far are kept, also when
    /// a later one failed, and the observers' `on_finish` read it back.
    pub fn close_results(&mut self) -> Result<(), RunFailure> {
        let closed = match self.results.take() {
            Some(f) => f.close(),
            None => Ok(()),
        };
        crate::parallel::any_error(self.world, closed)
            .map_err(|m| super::options::io_failure("writing results", m))
    }

    /// Publishes the results steps written so far (collective).
    pub fn publish_results(&mut self) -> Result<(), RunFailure> {
        let published = match self.results.as_mut() {
            Some(f) => f.publish(),
            None => Ok(()),
        };
        crate::parallel::any_error(self.world, published)
            .map_err(|m| super::options::io_failure("writing results", m))
    }
}
