//! Solvers: integration-point storage (and its checkpoint encoding), solid blocks, the
//! rank-local discretization, the static Newton solver and its checkpoints, and the
//! order-independent sums its decisions rest on.

pub mod exact_sum;
pub mod interface;
pub mod qp_store;
pub mod solid;
pub mod state_codec;

#[cfg(feature = "native")]
pub mod checkpoint;
#[cfg(feature = "native")]
pub mod discretization;
#[cfg(feature = "native")]
pub mod statics;
