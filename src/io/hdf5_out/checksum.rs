//! Checksums of tables: every rank hashes its own rows, the sums add up.

use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, CommunicatorCollectives};

use super::raw;
use super::TableValue;

/// Name of the attribute that every table carries: [`rows_checksum`] of its values.
pub const CHECKSUM_ATTR: &str = "checksum";

/// Checksum of the rows `first_row, first_row + 1, ...` of a table (`ncomp` values each):
/// the wrapping sum over the rows of XXH3-64 of the row's bytes seeded with its global row
/// index. Sums of the blocks of any partition of the rows add up to the whole table's, so
/// every rank hashes only its own rows whatever the rank count; a changed byte changes its
/// row's hash and so the sum (up to a 2^-64 chance), and rows swapped are caught by the seeds.
pub fn rows_checksum<T: TableValue>(first_row: u64, ncomp: usize, values: &[T]) -> u64 {
    values
        .chunks(ncomp.max(1))
        .zip(first_row..)
        .fold(0u64, |sum, (row, i)| {
            sum.wrapping_add(xxhash_rust::xxh3::xxh3_64_with_seed(raw::as_bytes(row), i))
        })
}

/// The sum of every rank's partial [`rows_checksum`]. Collective.
pub(super) fn sum_over_ranks(comm: &SimpleCommunicator, partial: u64) -> u64 {
    let mut all = vec![0u64; comm.size() as usize];
    comm.all_gather_into(&partial, &mut all[..]);
    all.iter().fold(0u64, |s, &x| s.wrapping_add(x))
}
