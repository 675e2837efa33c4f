//! The results file: one HDF5 file written collectively by every rank through MPI-IO.
//!
//! [`ResultsFile`] creates the file on all ranks of a communicator (the `mpio` driver), writes the
//! mesh, then one group per output step with node and element fields. Every dataset is in global
//! input order, whatever the rank count: each rank moves its owned rows to its contiguous block
//! ([`super::redistribute`]) and the blocks are written with one **collective** MPI-IO transfer
//! (`H5Pset_dxpl_mpio(COLLECTIVE)`). The layout is documented in [`crate::io`].
//!
//! The file is written under a temporary name in the target directory and renamed over the
//! target only by [`ResultsFile::close`], after the HDF5 file was closed successfully; the XDMF
//! file is written then. [`ResultsFile::publish`] (called by a staged run at every stage
//! checkpoint) puts a complete copy of the steps written so far at the target and continues
//! writing the temporary file, so a run killed later leaves the results of its completed stages.
//! A writer dropped without `close` (an error, a failed step) deletes its temporary file, so an
//! existing results file is never lost or left half-written.
//!
//! [`ResultsReader`] opens a results or checkpoint file collectively and reads datasets back:
//! each rank its block, every row, or the rows of a given ownership (for restarts).
//!
//! All methods that take or hold a communicator are collective: every rank calls them in the
//! same order with the same names, sizes and metadata (this is checked), and every rank gets the
//! same `Ok`/`Err` outcome ([`super::error::agree`]).

mod attrs;
mod carry;
mod checksum;
mod mesh;
mod names;
mod publish;
#[allow(unsafe_code)]
mod raw;
mod reader;
mod step;
mod writer;

pub use checksum::{rows_checksum, CHECKSUM_ATTR};
pub use mesh::{OwnedMesh, COORDINATES, ELEMENT_BLOCK, ELEMENT_IDS, NODE_IDS, TOPOLOGY};
pub use reader::{ResultsReader, TableBlock};
pub use step::{component_labels, strain_output_components, FieldRecord, StepInfo, StepRecord};
pub use writer::ResultsFile;

use hdf5::H5Type;
use mpi::traits::Equivalence;

use super::error::IoError;

/// Value of the root attribute `format`.
pub const FORMAT_NAME: &str = "cfrd-results";
/// Value of the root attribute `format_version`; raised when the layout changes incompatibly.
pub const FORMAT_VERSION: u32 = 1;

/// Types that can be stored in a table: plain numbers with an HDF5 and an MPI type
/// (`f64`, `i64`, `u64`, `i32`, `u32`, ...).
pub trait TableValue: H5Type + Equivalence + Copy + Default {}
impl<T: H5Type + Equivalence + Copy + Default> TableValue for T {}

impl From<IoError> for hdf5::Error {
    fn from(e: IoError) -> Self {
        hdf5::Error::from(e.to_string())
    }
}
