//! Errors of the I/O layer, and the rule that makes them collective.
//!
//! Every public operation of [`crate::io`] that takes a communicator is collective: either every
//! rank returns `Ok`, or every rank returns `Err`. A rank whose own input was wrong returns its own
//! error; the other ranks return [`IoError::OnOtherRank`] carrying the same message, so the caller
//! can bail out on every rank without a hang in the next collective call.

use std::path::PathBuf;

use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, CommunicatorCollectives, Root};
use thiserror::Error;

/// An error of the results / checkpoint I/O layer.
#[derive(Debug, Error)]
pub enum IoError {
    /// The HDF5 library reported an error.
    #[error("HDF5 error while {context}: {source}")]
    Hdf5 {
        /// What was being done (names the file or dataset).
        context: String,
        /// The library's message.
        #[source]
        source: hdf5::Error,
    },
    /// A plain file-system error (rename, XDMF or JSON write).
    #[error("{path}: {source}")]
    File {
        /// The file concerned.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The ownership of distributed items is not a partition of `0..n_global` (an item owned by
    /// two ranks or by none, an index out of range).
    #[error("ownership of {what}: {reason}")]
    Ownership {
        /// What is distributed (e.g. "nodes", "field 'stress'").
        what: String,
        /// The violation, with an example index.
        reason: String,
    },
    /// Less space is free on the output file system than a write needs
    /// ([`super::guard::ensure_space`]).
    #[error(
        "no space left for {path}: {free} bytes free on its file system, {need} needed \
         (the write and a reserve for the file's metadata); free space, then restart from the \
         last checkpoint or run again"
    )]
    NoSpace {
        /// The file that was to be written.
        path: PathBuf,
        /// Bytes free.
        free: u64,
        /// Bytes needed.
        need: u64,
    },
    /// The caller's arguments are inconsistent (lengths, component counts, names, order of calls).
    #[error("{0}")]
    Usage(String),
    /// The file does not have the expected layout (missing dataset, wrong shape).
    #[error("{0}")]
    Layout(String),
    /// Another rank failed; this rank's part of the operation was fine.
    #[error("rank {rank} failed: {message}")]
    OnOtherRank {
        /// The lowest rank that failed.
        rank: i32,
        /// That rank's error message.
        message: String,
    },
}

impl IoError {
    /// Wraps an HDF5 error with what was being done.
    pub fn hdf5(context: impl Into<String>, source: hdf5::Error) -> Self {
        IoError::Hdf5 {
            context: context.into(),
            source,
        }
    }
}

/// Makes a local outcome collective: every rank learns whether any rank failed.
///
/// If no rank failed, returns this rank's value. Otherwise the lowest failing rank broadcasts its
/// message; every failing rank returns its own error and every other rank returns
/// [`IoError::OnOtherRank`] with the lowest failing rank's message. Collective over `comm`.
pub fn agree<T>(comm: &SimpleCommunicator, local: Result<T, IoError>) -> Result<T, IoError> {
    let rank = comm.rank();
    let mine = if local.is_err() { rank } else { i32::MAX };
    let mut first = i32::MAX;
    comm.all_reduce_into(&mine, &mut first, mpi::collective::SystemOperation::min());
    if first == i32::MAX {
        return local;
    }
    let mut text = match &local {
        Err(e) if rank == first => e.to_string().into_bytes(),
        _ => Vec::new(),
    };
    let mut len = text.len() as u64;
    let root = comm.process_at_rank(first);
    root.broadcast_into(&mut len);
    text.resize(len as usize, 0);
    root.broadcast_into(&mut text[..]);
    match local {
        Err(e) => Err(e),
        Ok(_) => Err(IoError::OnOtherRank {
            rank: first,
            message: String::from_utf8_lossy(&text).into_owned(),
        }),
    }
}

/// Writes `bytes` to `path` through a temporary file in the same directory that is renamed into
/// place, so an existing file is replaced only by a complete one (call on one rank only).
pub fn write_atomic(path: &std::path::Path, bytes: &[u8]) -> Result<(), IoError> {
    if path.file_name().is_none() {
        return Err(IoError::Usage(format!("{}: not a file path", path.display())));
    }
    crate::input::write_replacing(path, bytes).map_err(|source| IoError::File {
        path: path.to_path_buf(),
        source,
    })
}
