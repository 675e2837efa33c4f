//! Solvers: integration-point storage, solid blocks, the rank-local discretization and the
//! static Newton solver.

pub mod interface;
pub mod qp_store;
pub mod solid;

#[cfg(feature = "native")]
pub mod discretization;
#[cfg(feature = "native")]
pub mod statics;
