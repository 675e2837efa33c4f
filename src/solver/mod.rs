//! Solvers: integration-point storage (and its checkpoint encoding), solid and interface
//! blocks, the rank-local discretization, and the one Newton machinery that statics and
//! dynamics share, split along the seams of spec architecture:
//!
//! | module | what it holds |
//! |---|---|
//! | [`model`], `assembly` | material states, K_t and f_int of the placed elements, commit/revert |
//! | [`constraints`] | fixed DOFs of a stage and their ramped values |
//! | [`loads`] | f_ext of a stage's terms, ramped from the previous stage; placement forces |
//! | [`integrator`] | what a time integrator adds: load factor, inertia and damping forces, Jacobian shifts ([`integrator::QuasiStatic`] for statics) |
//! | [`newton`] | the Newton step on PETSc SNES, for any integrator |
//! | [`step_control`] | (t, dt) of a stage: targets, cut-back and regrowth |
//! | [`problem`], `staging`, `results` | the composition: stages, steps, checkpointed state, results |
//! | [`exact_sum`] | the order-independent sums every Newton decision rests on |
//! | [`modal`] | natural frequencies and mode shapes of K₀·φ = ω²·M·φ at a stage's start (SLEPc) |
//!
//! Checkpoint I/O lives in the `io` room above; the solver does not depend on it.

pub mod exact_sum;
pub mod interface;
pub mod qp_store;
pub mod solid;
pub mod state_codec;

#[cfg(feature = "native")]
mod assembly;
#[cfg(feature = "native")]
mod committed_forces;
#[cfg(feature = "native")]
pub mod constraints;
#[cfg(feature = "native")]
mod diagnostics;
#[cfg(feature = "native")]
pub mod discretization;
#[cfg(feature = "native")]
pub mod error;
#[cfg(feature = "native")]
pub mod integrator;
#[cfg(feature = "native")]
pub mod loads;
#[cfg(feature = "native")]
mod mass;
#[cfg(feature = "native")]
pub mod modal;
#[cfg(feature = "native")]
pub mod model;
#[cfg(feature = "native")]
pub mod newton;
#[cfg(feature = "native")]
pub mod problem;
#[cfg(feature = "native")]
pub mod report;
#[cfg(feature = "native")]
mod results;
#[cfg(feature = "native")]
mod staging;
#[cfg(feature = "native")]
pub mod state;
#[cfg(feature = "native")]
pub mod step_control;
#[cfg(feature = "native")]
mod tangent_slots;

#[cfg(feature = "native")]
pub use error::SolveError;
#[cfg(feature = "native")]
pub use modal::Modes;
#[cfg(feature = "native")]
pub use model::mesh_cells;
#[cfg(feature = "native")]
pub use problem::Problem;
#[cfg(feature = "native")]
pub use report::{InterfaceCounts, LocalResults, NodeMotion, SolveReport, StageSeconds, ELEMENT_STATE};
#[cfg(feature = "native")]
pub use state::{ProblemState, StageProgress};
#[cfg(feature = "native")]
pub use step_control::{Resumed, StepControl};
