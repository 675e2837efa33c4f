//! What a solve reports: counters and timings, counts of open and slipping interface points,
//! and the rank-local results of the committed state.

use super::interface::InterfaceElementOutput;
use crate::tensor::{Strain6, Stress6};

/// Counters and timings of a solve.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct SolveReport {
    /// Newton iterations.
    pub newton_iterations: u32,
    /// Evaluations of the residual F (each an integration of every material point): one per
    /// Newton iteration and step start, plus the line search's trial points.
    #[serde(default)]
    pub residual_evaluations: u64,
    /// Element loops (integrations of every placed element): the residual evaluations less
    /// those that took the forces kept at the committed state of a linear scene, plus the
    /// Jacobians and the re-evaluations at a converged point.
    #[serde(default)]
    pub element_loops: u64,
    /// KSP iterations of each linear solve.
    pub ksp_iterations: Vec<u32>,
    /// Relative residual after each Newton iteration.
    pub residuals: Vec<f64>,
    /// Wall time in assembly (s).
    pub assembly_seconds: f64,
    /// Wall time in linear solves (s).
    pub solve_seconds: f64,
    /// Converged load steps.
    pub steps: u32,
    /// Step cut-backs (a failed step retried with half the increment).
    pub cutbacks: u32,
    /// Newton iterations of each converged step.
    pub newton_per_step: Vec<u32>,
    /// Predicted starts of steps dropped because a material update failed there (Newton then
    /// started from the last converged state; [`crate::solver::Problem::solve_step`]).
    #[serde(default)]
    pub predictions_dropped: u32,
    /// Numeric factorizations of the direct solvers (the reduced multigrid: of its structure).
    #[serde(default)]
    pub factorizations: u64,
    /// Set-ups of the reduced multigrid's multigrid ([`crate::linalg::petsc::reduced_amg`], "Lagged").
    #[serde(default)]
    pub multigrid_builds: u64,
    /// The most matrix rows this rank's direct solver held at once in this run (its factors'
    /// or its Schwarz subdomains'; [`crate::linalg::petsc::Snes::held_rows`]); 0 with the
    /// Krylov solvers.
    #[serde(default)]
    pub solver_rows_held: u64,
    /// Wall-clock seconds of each completed stage, for the run summary.
    #[serde(default)]
    pub stage_seconds: Vec<StageSeconds>,
    /// The crest's motion at every converged time step of every dynamic stage (recorded by
    /// the run's quake observer): `[t, u_x, u_y, u_z, a_x, a_y, a_z, ag_x, ag_y, ag_z]`, t on
    /// the quake's clock (`post::quake_clock`), u relative to the base and to the
    /// state before the first dynamic stage (m), a absolute and a_g the ground's (m/s²). Kept
    /// in step checkpoints, so a restarted run has the whole history.
    #[serde(default)]
    pub crest: Vec<[f64; 10]>,
    /// The crest's displacement relative to the base at the start of the first dynamic stage
    /// (m), from which [`SolveReport::crest`] counts its displacement in later dynamic stages.
    #[serde(default)]
    pub crest_quake_start: Option<[f64; 3]>,
    /// The probes' state at t = 0 of the first dynamic stage and at every converged time step
    /// of every dynamic stage (recorded by the run's quake observer, for the seed's Figs. 14,
    /// 18–20): the time on the quake's clock (s), then the values of each probe in the order
    /// the observer found them. Kept in step checkpoints like [`SolveReport::crest`].
    #[serde(default)]
    pub probes: Vec<Vec<f64>>,
}

/// Values per element of [`crate::solver::Problem::element_states`]: mean stress (6), interface
/// traction (3), mean jump (3), opening (1).
pub const ELEMENT_STATE: usize = 13;

/// Counts of interface points in the committed state (all ranks).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct InterfaceCounts {
    /// Interface and joint points of placed elements.
    pub points: u64,
    /// Points that are open.
    pub open: u64,
    /// Points on the plastic (slipping) branch.
    pub slipping: u64,
}

/// Rank-local results in input order of the owned nodes and elements.
#[derive(Debug, Clone, Default)]
pub struct LocalResults {
    /// Owned nodes (input indices).
    pub nodes: Vec<u32>,
    /// Displacement of each owned node (m).
    pub displacement: Vec<[f64; 3]>,
    /// Reaction force of each owned node (N), zero where no component is fixed.
    pub reaction: Vec<[f64; 3]>,
    /// Owned elements (input indices).
    pub elements: Vec<u32>,
    /// Mean stress of each owned element (Pa, tension positive).
    pub stress: Vec<Stress6>,
    /// Mean strain of each owned element (engineering shear, tension positive).
    pub strain: Vec<Strain6>,
    /// Interface output of each owned element (zero for solid elements).
    pub interface: Vec<InterfaceElementOutput>,
    /// Mean local jump (δ_s, δ_a, δ_n) of each owned interface element since its placement (m;
    /// zero for solid elements), spec (E4), (E9).
    pub jump: Vec<[f64; 3]>,
    /// In a dynamic stage: velocity relative to the base (m/s) and absolute acceleration
    /// (relative plus ground, m/s²) of each owned node; `None` in a static stage.
    pub motion: Option<NodeMotion>,
}

/// Velocities and accelerations of the owned nodes in a dynamic stage.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NodeMotion {
    /// Velocity relative to the base (m/s).
    pub velocity: Vec<[f64; 3]>,
    /// Absolute acceleration, relative plus ground (m/s²).
    pub acceleration: Vec<[f64; 3]>,
}

/// The wall time and solver counts of one completed stage, for the run summary;
/// the counts are those of the run (or part of a run) that completed the stage.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StageSeconds {
    /// Stage name.
    pub stage: String,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Converged load or time steps.
    #[serde(default)]
    pub steps: u32,
    /// Newton iterations, of converged and of cut-back steps.
    #[serde(default)]
    pub newton_iterations: u32,
    /// Krylov iterations of all linear solves.
    #[serde(default)]
    pub ksp_iterations: u64,
}
