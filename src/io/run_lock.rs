//! The output directory's lock taken for a run on every rank alike ([`crate::dir_lock`]: the
//! lock itself, which needs no MPI and is fuzzed with the other readers).

pub use crate::dir_lock::{RunLock, LOCK_FILE};
use crate::parallel::any_error;
use mpi::topology::{Communicator, SimpleCommunicator};
use std::path::Path;

/// Takes the lock of `dir` on rank 0 and shares the outcome, so every rank fails alike when
/// another run holds it. Collective; rank 0 gets the lock to hold for the run.
pub fn acquire_collective(world: &SimpleCommunicator, dir: &Path) -> Result<Option<RunLock>, String> {
    let local = match world.rank() {
        0 => RunLock::acquire(dir).map(Some),
        _ => Ok(None),
    };
    any_error(world, local)
}
