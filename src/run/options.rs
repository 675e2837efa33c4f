//! What `cfrd run` is asked on its command line ([`RunOptions`]) and how a run fails
//! ([`RunFailure`]: a message and the process's exit code).

use crate::parallel::{EXIT_INPUT, EXIT_IO};
use crate::scene::schema::CheckpointMode;
use std::path::PathBuf;

/// A failed run: message and process exit code.
#[derive(Debug)]
pub struct RunFailure {
    /// Exit code (2 input, 3 solver).
    pub code: i32,
    /// Message (printed by rank 0).
    pub message: String,
}

/// An input failure (exit code 2).
pub(crate) fn input(message: String) -> RunFailure {
    RunFailure {
        code: EXIT_INPUT,
        message,
    }
}

/// Options of `cfrd run`.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Scene file; `None` runs the embedded default scene.
    pub scene: Option<PathBuf>,
    /// Output directory overriding the scene's.
    pub out_dir: Option<PathBuf>,
    /// PETSc options from the command line (override the scene's).
    pub petsc_options: Vec<String>,
    /// Print progress (rank 0).
    pub verbose: bool,
    /// Checkpoint to restart from (`--restart`): the run continues after its last stage.
    pub restart: Option<PathBuf>,
    /// End the run cleanly after a stage, once its results and checkpoint are written
    /// (`--stop-after-stage`): a run in parts under a job time limit.
    pub stop_after_stage: Option<StopAfter>,
    /// When to write checkpoints, overriding the scene's `output.checkpoint` (`--checkpoint`;
    /// not part of the scene's hash, so a run continued with step checkpoints still restarts
    /// from its stage checkpoints).
    pub checkpoint: Option<CheckpointMode>,
    /// With step checkpoints: write them after every N-th converged load step of the run only
    /// (`--checkpoint-every`; counted by the run's converged steps, which a checkpoint keeps,
    /// so a restarted run writes them where the uninterrupted one does). `None`: every step.
    pub checkpoint_every: Option<u32>,
    /// Print every Newton iteration's residual and the reason and place of every cut-back
    /// (`--monitor`), as the scene's `solver.monitor` does, without changing the scene (its
    /// hash), so a run restarted from a checkpoint can be watched.
    pub monitor: bool,
    /// Cap the substepping tolerance of every GP material at this multiple of the Newton
    /// tolerance (`--integration-tol-ratio`, see
    /// [`crate::scene::schema::SolverSpec::integration_tol_ratio`]), without changing the scene
    /// (its hash), so a run stalled at the integration noise continues from its checkpoint.
    pub integration_tol_ratio: Option<f64>,
    /// The linear solver of every stage instead of the scene's `solver.linear_solver` and the
    /// dynamic stages' `linear_solver` (`--linear-solver`),
    /// without changing the scene (its hash), so a run continues from its checkpoint on
    /// another solver.
    pub linear_solver: Option<crate::scene::schema::LinearSolver>,
    /// Input files of the scene a restart accepts although they changed since the
    /// checkpoint (`--accept-changed`).
    pub accept_changed: Vec<std::path::PathBuf>,
}

/// Where a run in parts ends (`--stop-after-stage K` or `+N`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopAfter {
    /// After stage K of the schedule (1-based).
    Stage(usize),
    /// After the N-th stage this run runs (counted from the restart's stage, if any), or at the
    /// end of the schedule if that comes first.
    Stages(usize),
}

/// An I/O failure (exit code 4): `what` failed with `m`.
pub(crate) fn io_failure(what: &str, m: impl std::fmt::Display) -> RunFailure {
    RunFailure {
        code: EXIT_IO,
        message: format!("{what}: {m}"),
    }
}
