//! Moving distributed data between METIS ownership and contiguous input-order blocks.
//!
//! The solver distributes the mesh with METIS: each rank owns an arbitrary, non-contiguous set of
//! global items (nodes, elements, integration points), named by their 0-based input-order index.
//! Files are written in input order, whatever the rank count, so before a collective write the
//! data moves (one all-to-all with variable counts) to a **balanced block distribution**: rank `r`
//! holds the contiguous rows `[lo_r, hi_r)` of [`BlockDistribution`]. Reading a checkpoint back
//! does the reverse.
//!
//! A [`Redistribution`] is the communication plan for one ownership pattern. Building it checks,
//! collectively, that every item is owned by exactly one rank; the plan is then reused for every
//! field with that ownership (every step's displacement, stress, ...), so each later transfer
//! moves only the values.
//!
//! The result is deterministic: a block row depends only on the item's index, never on the rank
//! count or on the order in which a rank lists its items.

use std::ops::Range;

use mpi::datatype::{Partition, PartitionMut};
use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, CommunicatorCollectives, Equivalence};
use mpi::Count;

use super::error::{agree, IoError};

/// A balanced block distribution of `n_global` items over `n_ranks` ranks.
///
/// ```text
/// n_global = q·n_ranks + r  (0 ≤ r < n_ranks)
/// rank k holds q+1 items if k < r, else q;   lo_k = k·q + min(k, r)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlockDistribution {
    n_global: u64,
    n_ranks: u64,
}

impl BlockDistribution {
    /// The distribution of `n_global` items over `n_ranks` ranks (`n_ranks ≥ 1`).
    pub fn new(n_global: u64, n_ranks: usize) -> Self {
        assert!(n_ranks >= 1, "a block distribution needs at least one rank");
        BlockDistribution {
            n_global,
            n_ranks: n_ranks as u64,
        }
    }

    /// Number of items.
    pub fn n_global(&self) -> u64 {
        self.n_global
    }

    /// Number of ranks.
    pub fn n_ranks(&self) -> usize {
        self.n_ranks as usize
    }

    /// The rows `[lo, hi)` held by `rank`.
    pub fn range(&self, rank: usize) -> Range<u64> {
        let k = rank as u64;
        let q = self.n_global / self.n_ranks;
        let r = self.n_global % self.n_ranks;
        let lo = k * q + k.min(r);
        let hi = lo + q + u64::from(k < r);
        lo..hi
    }

    /// The rank holding row `index` (`index < n_global`).
    pub fn owner(&self, index: u64) -> usize {
        let q = self.n_global / self.n_ranks;
        let r = self.n_global % self.n_ranks;
        let big = r * (q + 1);
        if index < big {
            (index / (q + 1)) as usize
        } else {
            (r + (index - big) / q) as usize
        }
    }
}

/// The communication plan between one ownership pattern and the block distribution.
///
/// Built collectively by [`Redistribution::new`] (exclusive ownership, for writing) or
/// [`Redistribution::for_reading`] (any requested indices, repeats allowed, for reading back).
#[derive(Debug, Clone)]
pub struct Redistribution {
    what: String,
    distribution: BlockDistribution,
    block: Range<u64>,
    n_local: usize,
    exclusive: bool,
    /// Items sent to each rank, and their offsets in the send buffer.
    send_counts: Vec<Count>,
    send_displs: Vec<Count>,
    /// Items received from each rank, and their offsets in the receive buffer.
    recv_counts: Vec<Count>,
    recv_displs: Vec<Count>,
    /// `send_order[k]` is the local item placed at position `k` of the send buffer.
    send_order: Vec<u32>,
    /// `recv_rows[k]` is the block row (relative to `block.start`) of received item `k`.
    recv_rows: Vec<u32>,
}

impl Redistribution {
    /// Plans the transfer of items owned exclusively by the ranks, `owned` listing this rank's
    /// items by global index, in the order in which this rank stores their values.
    ///
    /// Collective. Fails on every rank unless every index in `0..n_global` is owned by exactly
    /// one rank; the error names how many items are owned twice or not at all, with an example.
    /// `what` names the items in messages (e.g. `"nodes"`).
    pub fn new(comm: &SimpleCommunicator, what: &str, n_global: u64, owned: &[u32]) -> Result<Self, IoError> {
        let plan = Self::build(comm, what, n_global, owned, true)?;
        let mut dup_missing = [0u64; 2];
        let mut example = [u64::MAX; 2];
        let mut hits = vec![0u8; plan.block_len()];
        for &row in &plan.recv_rows {
            let slot = &mut hits[row as usize];
            if *slot > 0 {
                dup_missing[0] += 1;
                example[0] = example[0].min(plan.block.start + u64::from(row));
            }
            *slot = slot.saturating_add(1);
        }
        for (row, &h) in hits.iter().enumerate() {
            if h == 0 {
                dup_missing[1] += 1;
                example[1] = example[1].min(plan.block.start + row as u64);
            }
        }
        let mut total = [0u64; 2];
        comm.all_reduce_into(
            &dup_missing[..],
            &mut total[..],
            mpi::collective::SystemOperation::sum(),
        );
        let mut first = [0u64; 2];
        comm.all_reduce_into(
            &example[..],
            &mut first[..],
            mpi::collective::SystemOperation::min(),
        );
        if total == [0, 0] {
            return Ok(plan);
        }
        let mut parts = Vec::new();
        if total[0] > 0 {
            parts.push(format!(
                "{} item(s) owned by more than one rank (first: index {})",
                total[0], first[0]
            ));
        }
        if total[1] > 0 {
            parts.push(format!(
                "{} item(s) owned by no rank (first: index {})",
                total[1], first[1]
            ));
        }
        Err(IoError::Ownership {
            what: what.to_string(),
            reason: parts.join("; "),
        })
    }

    /// Plans reading block data back to arbitrary indices (owned items plus ghosts, repeats
    /// allowed). Only [`Redistribution::from_block`] may be used with such a plan. Collective.
    pub fn for_reading(
        comm: &SimpleCommunicator,
        what: &str,
        n_global: u64,
        wanted: &[u32],
    ) -> Result<Self, IoError> {
        Self::build(comm, what, n_global, wanted, false)
    }

    /// Checks the arguments collectively and exchanges the index lists.
    fn build(
        comm: &SimpleCommunicator,
        what: &str,
        n_global: u64,
        indices: &[u32],
        exclusive: bool,
    ) -> Result<Self, IoError> {
        let n_ranks = comm.size() as usize;
        let rank = comm.rank() as usize;
        let local = check_indices(what, n_global, indices);
        agree(comm, local)?;
        let (lo_n, hi_n) = min_max(comm, n_global);
        if lo_n != hi_n {
            return Err(IoError::Usage(format!(
                "{what}: ranks disagree on the global count ({lo_n} to {hi_n})"
            )));
        }
        let distribution = BlockDistribution::new(n_global, n_ranks);
        let block = distribution.range(rank);

        let mut send_counts = vec![0 as Count; n_ranks];
        let owners: Vec<usize> = indices
            .iter()
            .map(|&i| distribution.owner(u64::from(i)))
            .collect();
        for &o in &owners {
            send_counts[o] += 1;
        }
        let send_displs = displacements(&send_counts);
        let mut next: Vec<usize> = send_displs.iter().map(|&d| d as usize).collect();
        let mut send_order = vec![0u32; indices.len()];
        let mut send_index = vec![0u32; indices.len()];
        for (item, (&o, &index)) in owners.iter().zip(indices).enumerate() {
            let k = next[o];
            next[o] += 1;
            send_order[k] = item as u32;
            send_index[k] = index;
        }

        let mut recv_counts = vec![0 as Count; n_ranks];
        comm.all_to_all_into(&send_counts[..], &mut recv_counts[..]);
        let recv_total: i64 = recv_counts.iter().map(|&c| i64::from(c)).sum();
        let local = if recv_total > i64::from(Count::MAX) {
            Err(IoError::Usage(format!(
                "{what}: {recv_total} items for one rank exceed the MPI count limit"
            )))
        } else {
            Ok(())
        };
        agree(comm, local)?;
        let recv_displs = displacements(&recv_counts);
        let mut recv_index = vec![0u32; recv_total as usize];
        {
            let send = Partition::new(&send_index[..], &send_counts[..], &send_displs[..]);
            let mut recv = PartitionMut::new(&mut recv_index[..], &recv_counts[..], &recv_displs[..]);
            comm.all_to_all_varcount_into(&send, &mut recv);
        }
        let recv_rows = recv_index
            .iter()
            .map(|&i| (u64::from(i) - block.start) as u32)
            .collect();
        Ok(Redistribution {
            what: what.to_string(),
            distribution,
            block,
            n_local: indices.len(),
            exclusive,
            send_counts,
            send_displs,
            recv_counts,
            recv_displs,
            send_order,
            recv_rows,
        })
    }

    /// The block distribution.
    pub fn distribution(&self) -> BlockDistribution {
        self.distribution
    }

    /// This rank's block of rows `[lo, hi)`.
    pub fn block(&self) -> Range<u64> {
        self.block.clone()
    }

    /// Number of rows in this rank's block.
    pub fn block_len(&self) -> usize {
        (self.block.end - self.block.start) as usize
    }

    /// Number of items this rank listed (owned items, or wanted items for a reading plan).
    pub fn n_local(&self) -> usize {
        self.n_local
    }

    /// Moves values from the owners to the blocks: `values` holds `ncomp` values per owned item,
    /// in the order of `owned`; returns this rank's block, `ncomp` values per row, rows in input
    /// order. Collective; `ncomp` must be the same on every rank.
    pub fn to_block<T: Equivalence + Copy + Default>(
        &self,
        comm: &SimpleCommunicator,
        ncomp: usize,
        values: &[T],
    ) -> Result<Vec<T>, IoError> {
        let local = if !self.exclusive {
            Err(IoError::Usage(format!(
                "{}: a reading plan cannot send values to the blocks",
                self.what
            )))
        } else {
            self.check_len(values.len(), self.n_local, ncomp, "owned items")
        };
        agree(comm, local)?;
        agree_ncomp(comm, &self.what, ncomp)?;
        let mut send = vec![T::default(); values.len()];
        for (k, &item) in self.send_order.iter().enumerate() {
            let src = item as usize * ncomp;
            send[k * ncomp..(k + 1) * ncomp].copy_from_slice(&values[src..src + ncomp]);
        }
        let mut recv = vec![T::default(); self.recv_rows.len() * ncomp];
        self.exchange(
            comm,
            ncomp,
            &send,
            &self.send_counts,
            &self.send_displs,
            &mut recv,
            true,
        )?;
        let mut block = vec![T::default(); self.block_len() * ncomp];
        for (k, &row) in self.recv_rows.iter().enumerate() {
            let dst = row as usize * ncomp;
            block[dst..dst + ncomp].copy_from_slice(&recv[k * ncomp..(k + 1) * ncomp]);
        }
        Ok(block)
    }

    /// The reverse of [`Redistribution::to_block`]: from this rank's block (`ncomp` values per
    /// row), returns the values of the items this rank listed, in the listed order. Collective.
    pub fn from_block<T: Equivalence + Copy + Default>(
        &self,
        comm: &SimpleCommunicator,
        ncomp: usize,
        block: &[T],
    ) -> Result<Vec<T>, IoError> {
        let local = self.check_len(block.len(), self.block_len(), ncomp, "block rows");
        agree(comm, local)?;
        agree_ncomp(comm, &self.what, ncomp)?;
        let mut reply = vec![T::default(); self.recv_rows.len() * ncomp];
        for (k, &row) in self.recv_rows.iter().enumerate() {
            let src = row as usize * ncomp;
            reply[k * ncomp..(k + 1) * ncomp].copy_from_slice(&block[src..src + ncomp]);
        }
        let mut back = vec![T::default(); self.n_local * ncomp];
        self.exchange(
            comm,
            ncomp,
            &reply,
            &self.recv_counts,
            &self.recv_displs,
            &mut back,
            false,
        )?;
        let mut out = vec![T::default(); self.n_local * ncomp];
        for (k, &item) in self.send_order.iter().enumerate() {
            let dst = item as usize * ncomp;
            out[dst..dst + ncomp].copy_from_slice(&back[k * ncomp..(k + 1) * ncomp]);
        }
        Ok(out)
    }

    /// One all-to-all with `ncomp` values per item; `forward` sends owner → block.
    fn exchange<T: Equivalence>(
        &self,
        comm: &SimpleCommunicator,
        ncomp: usize,
        send: &[T],
        send_counts: &[Count],
        send_displs: &[Count],
        recv: &mut [T],
        forward: bool,
    ) -> Result<(), IoError> {
        let (recv_counts, recv_displs) = if forward {
            (&self.recv_counts, &self.recv_displs)
        } else {
            (&self.send_counts, &self.send_displs)
        };
        let too_big = |n: usize| n.checked_mul(ncomp).is_none_or(|v| v > Count::MAX as usize);
        let local = if too_big(send.len() / ncomp.max(1)) || too_big(recv.len() / ncomp.max(1)) {
            Err(IoError::Usage(format!(
                "{}: {} values per rank exceed the MPI count limit; use more ranks",
                self.what,
                send.len().max(recv.len())
            )))
        } else {
            Ok(())
        };
        agree(comm, local)?;
        let scale = |v: &[Count]| v.iter().map(|&c| c * ncomp as Count).collect::<Vec<Count>>();
        let (sc, sd, rc, rd) = (
            scale(send_counts),
            scale(send_displs),
            scale(recv_counts),
            scale(recv_displs),
        );
        let send = Partition::new(send, &sc[..], &sd[..]);
        let mut recv = PartitionMut::new(recv, &rc[..], &rd[..]);
        comm.all_to_all_varcount_into(&send, &mut recv);
        Ok(())
    }

    fn check_len(&self, len: usize, items: usize, ncomp: usize, of: &str) -> Result<(), IoError> {
        if ncomp == 0 {
            return Err(IoError::Usage(format!("{}: ncomp must be at least 1", self.what)));
        }
        if len != items * ncomp {
            return Err(IoError::Usage(format!(
                "{}: {len} values given for {items} {of} × {ncomp} components",
                self.what
            )));
        }
        Ok(())
    }
}

/// Local checks of an index list: every index below `n_global`, `n_global` representable.
fn check_indices(what: &str, n_global: u64, indices: &[u32]) -> Result<(), IoError> {
    if n_global > u64::from(u32::MAX) + 1 {
        return Err(IoError::Usage(format!(
            "{what}: {n_global} items exceed the u32 index range"
        )));
    }
    if let Some(&bad) = indices.iter().find(|&&i| u64::from(i) >= n_global) {
        return Err(IoError::Ownership {
            what: what.to_string(),
            reason: format!("index {bad} is out of range 0..{n_global}"),
        });
    }
    Ok(())
}

/// Exclusive prefix sum of counts.
fn displacements(counts: &[Count]) -> Vec<Count> {
    let mut displs = Vec::with_capacity(counts.len());
    let mut acc: Count = 0;
    for &c in counts {
        displs.push(acc);
        acc += c;
    }
    displs
}

/// The minimum and maximum of `value` over the ranks.
fn min_max(comm: &SimpleCommunicator, value: u64) -> (u64, u64) {
    let (mut lo, mut hi) = (0u64, 0u64);
    comm.all_reduce_into(&value, &mut lo, mpi::collective::SystemOperation::min());
    comm.all_reduce_into(&value, &mut hi, mpi::collective::SystemOperation::max());
    (lo, hi)
}

/// Fails on every rank unless `ncomp` is the same everywhere.
fn agree_ncomp(comm: &SimpleCommunicator, what: &str, ncomp: usize) -> Result<(), IoError> {
    let (lo, hi) = min_max(comm, ncomp as u64);
    if lo != hi {
        return Err(IoError::Usage(format!(
            "{what}: ranks disagree on the number of components ({lo} to {hi})"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_ranges_tile_the_items_and_owner_inverts_range() {
        for n_ranks in 1..=7usize {
            for n_global in [0u64, 1, 2, 5, 6, 7, 13, 100, 1001] {
                let d = BlockDistribution::new(n_global, n_ranks);
                let mut next = 0u64;
                let mut sizes = Vec::new();
                for r in 0..n_ranks {
                    let range = d.range(r);
                    assert_eq!(range.start, next, "n={n_global} p={n_ranks} r={r}");
                    sizes.push(range.end - range.start);
                    for i in range.clone() {
                        assert_eq!(d.owner(i), r, "n={n_global} p={n_ranks} i={i}");
                    }
                    next = range.end;
                }
                assert_eq!(next, n_global);
                let (min, max) = (sizes.iter().min().unwrap(), sizes.iter().max().unwrap());
                assert!(max - min <= 1, "unbalanced {sizes:?}");
                assert!(
                    sizes.windows(2).all(|w| w[0] >= w[1]),
                    "larger blocks first: {sizes:?}"
                );
            }
        }
    }

    #[test]
    fn displacements_are_exclusive_prefix_sums() {
        assert_eq!(displacements(&[3, 0, 2, 5]), vec![0, 3, 3, 5]);
        assert!(displacements(&[]).is_empty());
    }

    #[test]
    fn out_of_range_index_is_rejected_with_its_value() {
        let err = check_indices("nodes", 10, &[1, 9, 10, 3]).unwrap_err();
        let text = err.to_string();
        assert!(text.contains("index 10") && text.contains("nodes"), "{text}");
        assert!(check_indices("nodes", 10, &[0, 9]).is_ok());
        assert!(check_indices("nodes", u64::from(u32::MAX) + 2, &[]).is_err());
    }
}
