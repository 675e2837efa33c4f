//! Mesh partitioning for cfrd.
//!
//! * [`partition_elements`]: k-way partition of the element dual graph with METIS (feature
//!   `metis`). Zero-thickness interface and joint cells are ordinary cells here: they share
//!   their 4 face nodes with the volume cell on each side, so with `ncommon = 3` they are
//!   adjacent to both, and METIS keeps them cheap to cut. Whatever the cut, the rank that owns
//!   such a cell sees both faces, because every rank gets the nodes of the cells it owns as
//!   owned or ghost nodes ([`Partition::ghost_nodes`]).
//! * [`partition_for_assembly`]: the partition `cfrd run` uses. Each rank evaluates its own
//!   cells and those of other parts around the nodes it owns ([`Partition::evaluated_cells`]),
//!   so a partition balanced by owned cells leaves the lower ranks busier; this one balances
//!   the evaluated cells (METIS again with target weights).
//! * [`Partition`]: element ownership, node ownership (the lowest rank among the cells that
//!   touch the node), owned and ghost lists, and the rank-count-independent DOF numbering.
//! * [`PartitionFile`]: the file `cfrd partition` writes and `cfrd run` reads (JSON).
//!
//! Everything is deterministic: METIS runs once (on rank 0 in a parallel run) with fixed
//! options, and all lists are sorted by global input index.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Partitioning failures.
#[derive(Debug, Error)]
pub enum PartitionError {
    /// METIS returned an error.
    #[error("METIS failed: {0}")]
    Metis(String),
    /// The partition does not fit the mesh.
    #[error("partition file {path}: {reason}")]
    Mismatch {
        /// File path.
        path: String,
        /// What does not match.
        reason: String,
    },
    /// Reading or writing the partition file failed.
    #[error("partition file {path}: {source}")]
    Io {
        /// File path.
        path: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// More parts (ranks) than cells: a part would own no cell.
    #[error("{parts} parts for a mesh of {cells} elements: at most one part (MPI rank) per element")]
    TooManyParts {
        /// Parts asked for.
        parts: usize,
        /// Cells of the mesh.
        cells: usize,
    },
    /// The partition file is not valid JSON of the expected format.
    #[error("partition file {path}: {reason}")]
    Format {
        /// File path.
        path: String,
        /// Parser message.
        reason: String,
    },
}

/// Cells as a CSR list: the nodes of cell `c` are `cell_nodes[cell_ptr[c]..cell_ptr[c + 1]]`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Cells {
    /// Offsets, length = number of cells + 1.
    pub cell_ptr: Vec<usize>,
    /// Node indices.
    pub cell_nodes: Vec<u32>,
}

impl Cells {
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.cell_ptr.len().saturating_sub(1)
    }
    /// Whether there are no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Nodes of cell `c`.
    pub fn nodes(&self, c: usize) -> &[u32] {
        &self.cell_nodes[self.cell_ptr[c]..self.cell_ptr[c + 1]]
    }
    /// A row of `n` unit hexahedra along x and its number of nodes: node (i, j, k), i in 0..=n,
    /// j and k in 0..=1, has index 4i + 2j + k. A small mesh for tests and examples.
    pub fn hex_row(n: usize) -> (Cells, usize) {
        let id = |i: usize, j: usize, k: usize| (i * 4 + j * 2 + k) as u32;
        let mut cells = Cells::default();
        for i in 0..n {
            cells.push(&[
                id(i, 0, 0),
                id(i + 1, 0, 0),
                id(i + 1, 1, 0),
                id(i, 1, 0),
                id(i, 0, 1),
                id(i + 1, 0, 1),
                id(i + 1, 1, 1),
                id(i, 1, 1),
            ]);
        }
        (cells, (n + 1) * 4)
    }

    /// Appends a cell.
    pub fn push(&mut self, nodes: &[u32]) {
        if self.cell_ptr.is_empty() {
            self.cell_ptr.push(0);
        }
        self.cell_nodes.extend_from_slice(nodes);
        self.cell_ptr.push(self.cell_nodes.len());
    }
}

/// METIS keeps its random-number state in globals, so two partitions computed at once in one
/// process (tests run in threads) could disturb each other and differ from run to run; every
/// METIS call holds this lock.
#[cfg(feature = "metis")]
fn metis_lock() -> std::sync::MutexGuard<'static, ()> {
    static LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());
    LOCK.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Partitions the cells into `nparts` parts with METIS k-way on the dual graph (cells that
/// share at least 3 nodes, i.e. a face, are neighbours). Returns the part of every cell.
#[cfg(feature = "metis")]
pub fn partition_elements(cells: &Cells, n_nodes: usize, nparts: usize) -> Result<Vec<u32>, PartitionError> {
    let _ = n_nodes;
    kway(cells, nparts, 1, None, None)
}

/// Partitions the cells like [`partition_elements`], balancing each construction band on its
/// own: `band[c]` (below `n_bands`) is the band of cell `c`, e.g. the group of fill layers it is
/// placed with. METIS balances every band's cells across the parts (multi-constraint k-way), so
/// at every stage of a staged construction the placed cells are spread over all ranks, where a
/// partition balanced over the whole mesh may leave the first layers on one rank while the
/// others wait. With fewer than two bands this is [`partition_elements`].
#[cfg(feature = "metis")]
pub fn partition_elements_by_band(
    cells: &Cells,
    n_nodes: usize,
    nparts: usize,
    band: &[u32],
    n_bands: usize,
) -> Result<Vec<u32>, PartitionError> {
    if n_bands < 2 {
        return partition_elements(cells, n_nodes, nparts);
    }
    kway_by_band(cells, nparts, band, n_bands, None)
}

/// METIS k-way with one balance constraint per construction band (one band: a plain k-way),
/// each part's share of every band given by `shares` (equal shares when `None`).
#[cfg(feature = "metis")]
fn kway_by_band(
    cells: &Cells,
    nparts: usize,
    band: &[u32],
    n_bands: usize,
    shares: Option<&[metis::Real]>,
) -> Result<Vec<u32>, PartitionError> {
    if n_bands < 2 {
        return kway(cells, nparts, 1, None, shares);
    }
    assert_eq!(band.len(), cells.len(), "one band per cell");
    let mut vwgt = vec![0 as metis::Idx; cells.len() * n_bands];
    for (c, &b) in band.iter().enumerate() {
        vwgt[c * n_bands + b as usize] = 1;
    }
    let tpwgts: Option<Vec<metis::Real>> =
        shares.map(|t| t.iter().flat_map(|&x| std::iter::repeat_n(x, n_bands)).collect());
    kway(cells, nparts, n_bands, Some(&vwgt), tpwgts.as_deref())
}

/// Partitions the cells like [`partition_elements_by_band`] and then balances what each rank
/// evaluates in an assembly rather than what it owns. The owner of a node assembles its rows
/// whole, so it also evaluates the cells of other parts around it
/// ([`Partition::evaluated_cells`]), and as the lowest part owns every shared node, the lower
/// parts carry their neighbours' boundary cells on top of their own. METIS runs again, up to
/// three times, each with every part's target share lowered by the cells of other parts it
/// evaluated in the partition before (target weights `tpwgts`); of all the partitions the
/// first whose busiest part evaluates the fewest cells is returned.
#[cfg(feature = "metis")]
pub fn partition_for_assembly(
    cells: &Cells,
    n_nodes: usize,
    nparts: usize,
    band: &[u32],
    n_bands: usize,
) -> Result<Vec<u32>, PartitionError> {
    let first = partition_elements_by_band(cells, n_nodes, nparts, band, n_bands)?;
    if nparts < 2 || cells.len() < 2 {
        return Ok(first);
    }
    let load = |part: Vec<u32>| {
        let evaluated = Partition::new(cells, n_nodes, nparts, part.clone()).evaluated_cells(cells);
        (evaluated.iter().copied().max().unwrap_or(0), evaluated, part)
    };
    let mut last = load(first);
    let mut best = (last.0, last.2.clone());
    for _ in 0..ASSEMBLY_BALANCE_ROUNDS {
        let shares = assembly_shares(&last.1, &last.2, cells.len());
        last = load(kway_by_band(cells, nparts, band, n_bands, Some(&shares))?);
        if last.0 < best.0 {
            best = (last.0, last.2.clone());
        }
    }
    Ok(best.1)
}

/// METIS runs of [`partition_for_assembly`] after the first, each with the target shares
/// measured on the partition before it.
#[cfg(feature = "metis")]
const ASSEMBLY_BALANCE_ROUNDS: usize = 3;

/// Target share of the `n_cells` cells for every part such that owned plus evaluated foreign
/// cells come out equal if the foreign cells stay as they are in the partition `part`, whose
/// parts evaluate `evaluated` cells ([`Partition::evaluated_cells`]); but at least half an
/// equal share (on meshes too small for the part count the foreign cells outnumber the owned
/// ones, and a part must not be left empty). The shares add up to 1 in the precision METIS
/// checks (the last one takes the rest).
#[cfg(feature = "metis")]
fn assembly_shares(evaluated: &[usize], part: &[u32], n_cells: usize) -> Vec<metis::Real> {
    let nparts = evaluated.len();
    let mut foreign: Vec<f64> = evaluated.iter().map(|&e| e as f64).collect();
    for &p in part {
        foreign[p as usize] -= 1.0;
    }
    let equal = n_cells as f64 / nparts as f64;
    let level = equal + foreign.iter().sum::<f64>() / nparts as f64;
    let wanted: Vec<f64> = foreign.iter().map(|&f| (level - f).max(0.5 * equal)).collect();
    let total: f64 = wanted.iter().sum();
    let mut shares: Vec<metis::Real> = wanted.iter().map(|&w| (w / total) as metis::Real).collect();
    let last = nparts - 1;
    shares[last] = 1.0 - shares[..last].iter().sum::<metis::Real>();
    shares
}

/// METIS k-way on the dual graph of `cells` with `ncon` balance constraints and, when given,
/// the cell weights `vwgt` (`ncon` per cell) and the target weights `tpwgts` (`ncon` per
/// part; every constraint's add up to 1).
#[cfg(feature = "metis")]
fn kway(
    cells: &Cells,
    nparts: usize,
    ncon: usize,
    vwgt: Option<&[metis::Idx]>,
    tpwgts: Option<&[metis::Real]>,
) -> Result<Vec<u32>, PartitionError> {
    if nparts > 1 && nparts > cells.len() {
        return Err(PartitionError::TooManyParts {
            parts: nparts,
            cells: cells.len(),
        });
    }
    if nparts <= 1 || cells.len() <= 1 {
        return Ok(vec![0; cells.len()]);
    }
    let metis_error = |e: &dyn std::fmt::Debug| PartitionError::Metis(format!("{e:?}"));
    let eptr: Vec<metis::Idx> = cells.cell_ptr.iter().map(|&v| v as metis::Idx).collect();
    let eind: Vec<metis::Idx> = cells.cell_nodes.iter().map(|&v| v as metis::Idx).collect();
    let _serial = metis_lock();
    let dual = metis::mesh_to_dual(&eptr, &eind, 3).map_err(|e| metis_error(&e))?;
    let mut graph = metis::Graph::new(
        ncon as metis::Idx,
        nparts as metis::Idx,
        dual.xadj(),
        dual.adjncy(),
    )
    .map_err(|e| metis_error(&e))?;
    if let Some(w) = vwgt {
        graph = graph.set_vwgt(w);
    }
    if let Some(t) = tpwgts {
        graph = graph.set_tpwgts(t);
    }
    let mut part = vec![0 as metis::Idx; cells.len()];
    graph.part_kway(&mut part).map_err(|e| metis_error(&e))?;
    Ok(part.into_iter().map(|p| p as u32).collect())
}

/// Ownership of cells and nodes on every rank, derived from a cell partition.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Partition {
    /// Number of parts (ranks).
    pub nparts: usize,
    /// Part of every cell.
    pub cell_part: Vec<u32>,
    /// Owner of every node: the lowest part among the cells that touch it (nodes that no cell
    /// touches belong to part 0).
    pub node_owner: Vec<u32>,
    /// Position of every node in the partition-ordered numbering: nodes sorted by (owner, input
    /// index). DOF `3·dof_node[n] + c` is component `c` of node `n`. Part `r` owns the
    /// contiguous range `node_offsets[r]..node_offsets[r+1]`.
    pub dof_node: Vec<u32>,
    /// Start of each part's node range in the partition-ordered numbering (length nparts + 1).
    pub node_offsets: Vec<usize>,
}

impl Partition {
    /// Builds ownership from the part of every cell.
    pub fn new(cells: &Cells, n_nodes: usize, nparts: usize, cell_part: Vec<u32>) -> Partition {
        assert_eq!(cell_part.len(), cells.len());
        let mut node_owner = vec![u32::MAX; n_nodes];
        for c in 0..cells.len() {
            for &n in cells.nodes(c) {
                let o = &mut node_owner[n as usize];
                *o = (*o).min(cell_part[c]);
            }
        }
        for o in node_owner.iter_mut() {
            if *o == u32::MAX {
                *o = 0;
            }
        }
        let mut counts = vec![0usize; nparts + 1];
        for &o in &node_owner {
            counts[o as usize + 1] += 1;
        }
        for r in 0..nparts {
            counts[r + 1] += counts[r];
        }
        let node_offsets = counts.clone();
        let mut next = counts;
        let mut dof_node = vec![0u32; n_nodes];
        for (n, &o) in node_owner.iter().enumerate() {
            dof_node[n] = next[o as usize] as u32;
            next[o as usize] += 1;
        }
        Partition {
            nparts,
            cell_part,
            node_owner,
            dof_node,
            node_offsets,
        }
    }

    /// Cells owned by `rank`, in input order.
    pub fn owned_cells(&self, rank: usize) -> Vec<u32> {
        (0..self.cell_part.len() as u32)
            .filter(|&c| self.cell_part[c as usize] == rank as u32)
            .collect()
    }

    /// Nodes owned by `rank`, in input order (which is also their partition order).
    pub fn owned_nodes(&self, rank: usize) -> Vec<u32> {
        (0..self.node_owner.len() as u32)
            .filter(|&n| self.node_owner[n as usize] == rank as u32)
            .collect()
    }

    /// Nodes that cells owned by `rank` touch but another rank owns (sorted, unique).
    pub fn ghost_nodes(&self, cells: &Cells, rank: usize) -> Vec<u32> {
        let mut g: Vec<u32> = (0..cells.len())
            .filter(|&c| self.cell_part[c] == rank as u32)
            .flat_map(|c| cells.nodes(c).iter().copied())
            .filter(|&n| self.node_owner[n as usize] != rank as u32)
            .collect();
        g.sort_unstable();
        g.dedup();
        g
    }

    /// Cells every part evaluates in an assembly: its own and every cell of another part that
    /// touches a node it owns (the rows of a node are assembled whole by its owner; the same
    /// rule as the solver's discretization).
    pub fn evaluated_cells(&self, cells: &Cells) -> Vec<usize> {
        let mut count = vec![0usize; self.nparts];
        let mut parts: Vec<u32> = Vec::with_capacity(8);
        for c in 0..cells.len() {
            parts.clear();
            parts.push(self.cell_part[c]);
            for &n in cells.nodes(c) {
                let o = self.node_owner[n as usize];
                if !parts.contains(&o) {
                    parts.push(o);
                }
            }
            for &r in &parts {
                count[r as usize] += 1;
            }
        }
        count
    }

    /// Number of cells cut by the partition (edges of the node-sharing graph are not counted;
    /// this is the number of cells having at least one node owned elsewhere), for reports.
    pub fn boundary_cells(&self, cells: &Cells) -> usize {
        (0..cells.len())
            .filter(|&c| {
                cells
                    .nodes(c)
                    .iter()
                    .any(|&n| self.node_owner[n as usize] != self.cell_part[c])
            })
            .count()
    }
}

/// What `cfrd partition` writes: the cell partition of one mesh for a given rank count.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartitionFile {
    /// Always `"cfrd-partition"`.
    pub format: String,
    /// Format version (1).
    pub version: u32,
    /// Number of parts.
    pub nparts: usize,
    /// Number of cells of the mesh it was made for.
    pub n_cells: usize,
    /// Number of nodes of the mesh it was made for.
    pub n_nodes: usize,
    /// A fingerprint of the mesh connectivity ([`mesh_fingerprint`]).
    pub mesh_fingerprint: String,
    /// Part of every cell, in input order.
    pub cell_part: Vec<u32>,
}

/// FNV-1a fingerprint of the connectivity, so a partition file is never applied to another mesh.
pub fn mesh_fingerprint(cells: &Cells, n_nodes: usize) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |v: u64| {
        for b in v.to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    eat(n_nodes as u64);
    for &p in &cells.cell_ptr {
        eat(p as u64);
    }
    for &n in &cells.cell_nodes {
        eat(n as u64);
    }
    format!("{h:016x}")
}

impl PartitionFile {
    /// Wraps a partition for writing.
    pub fn new(cells: &Cells, n_nodes: usize, nparts: usize, cell_part: Vec<u32>) -> Self {
        PartitionFile {
            format: "cfrd-partition".into(),
            version: 1,
            nparts,
            n_cells: cells.len(),
            n_nodes,
            mesh_fingerprint: mesh_fingerprint(cells, n_nodes),
            cell_part,
        }
    }

    /// Writes the file (to a temporary name first, then renamed, so nothing is half-written).
    pub fn write(&self, path: &std::path::Path) -> Result<(), PartitionError> {
        let io = |source| PartitionError::Io {
            path: path.display().to_string(),
            source,
        };
        let tmp = path.with_extension("partition.tmp");
        let text = serde_json::to_string(self).expect("serializable");
        std::fs::write(&tmp, text).map_err(io)?;
        std::fs::rename(&tmp, path).map_err(io)
    }

    /// Reads a file and checks it against the mesh and the rank count.
    pub fn read(
        path: &std::path::Path,
        cells: &Cells,
        n_nodes: usize,
        nparts: usize,
    ) -> Result<Vec<u32>, PartitionError> {
        let p = path.display().to_string();
        let text = read_bounded(path, cells.len()).map_err(|source| PartitionError::Io {
            path: p.clone(),
            source,
        })?;
        let f: PartitionFile = serde_json::from_str(&text).map_err(|e| PartitionError::Format {
            path: p.clone(),
            reason: e.to_string(),
        })?;
        let bad = |reason: String| PartitionError::Mismatch {
            path: p.clone(),
            reason,
        };
        if f.format != "cfrd-partition" || f.version != 1 {
            return Err(bad(format!("unknown format {} version {}", f.format, f.version)));
        }
        if f.nparts != nparts {
            return Err(bad(format!("made for {} ranks, the run has {nparts}", f.nparts)));
        }
        if f.n_cells != cells.len()
            || f.n_nodes != n_nodes
            || f.mesh_fingerprint != mesh_fingerprint(cells, n_nodes)
        {
            return Err(bad(
                "made for another mesh (cell/node counts or connectivity differ)".into(),
            ));
        }
        if f.cell_part.len() != cells.len() || f.cell_part.iter().any(|&q| q as usize >= nparts) {
            return Err(bad("cell_part has the wrong length or a part out of range".into()));
        }
        Ok(f.cell_part)
    }
}

/// Reads the partition file of a mesh of `n_cells` cells: a regular file of at most
/// 4 KiB + 32 bytes per cell (a part number and its separators take at most 11), so a device
/// or a FIFO is refused instead of being read without end (opened non-blocking, so a FIFO
/// without a writer does not hang the open either).
fn read_bounded(path: &std::path::Path, n_cells: usize) -> Result<String, std::io::Error> {
    use std::io::Read;
    use std::os::unix::fs::OpenOptionsExt;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)?;
    let kind = file.metadata()?.file_type();
    if !kind.is_file() {
        use std::os::unix::fs::FileTypeExt;
        let what = match () {
            _ if kind.is_dir() => "a directory",
            _ if kind.is_fifo() => "a FIFO",
            _ if kind.is_socket() => "a socket",
            _ => "a device",
        };
        return Err(std::io::Error::other(format!("not a regular file ({what})")));
    }
    let cap = 4096 + 32 * n_cells as u64;
    let mut text = String::new();
    file.take(cap + 1).read_to_string(&mut text)?;
    if text.len() as u64 > cap {
        return Err(std::io::Error::other(format!(
            "larger than {cap} bytes, the most a partition of {n_cells} cells takes"
        )));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_device_is_not_read_as_a_partition_file() {
        let (cells, nn) = Cells::hex_row(2);
        let err =
            PartitionFile::read(std::path::Path::new("/dev/zero"), &cells, nn, 1).expect_err("a device");
        assert!(err.to_string().contains("not a regular file"), "{err}");
    }

    #[test]
    fn ownership_is_consistent_and_numbering_contiguous() {
        let (cells, nn) = Cells::hex_row(6);
        let part = vec![0, 0, 0, 1, 1, 1];
        let p = Partition::new(&cells, nn, 2, part);
        // nodes of the shared face x = 3 go to the lower rank
        assert_eq!(p.node_owner[12], 0);
        assert_eq!(p.node_offsets, vec![0, 16, 28]);
        assert_eq!(p.owned_nodes(0).len() + p.owned_nodes(1).len(), nn);
        assert_eq!(p.ghost_nodes(&cells, 1), vec![12, 13, 14, 15]);
        assert!(p.ghost_nodes(&cells, 0).is_empty());
        let mut seen = p.dof_node.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..nn as u32).collect::<Vec<_>>());
    }

    #[cfg(feature = "metis")]
    #[test]
    fn metis_partition_is_balanced_and_deterministic() {
        let (cells, nn) = Cells::hex_row(40);
        let a = partition_elements(&cells, nn, 2).unwrap();
        let b = partition_elements(&cells, nn, 2).unwrap();
        assert_eq!(a, b);
        let n0 = a.iter().filter(|&&q| q == 0).count();
        assert!((15..=25).contains(&n0), "unbalanced: {n0} of 40");
        // a row splits with a single cut: parts form two contiguous runs
        let changes = a.windows(2).filter(|w| w[0] != w[1]).count();
        assert_eq!(changes, 1);
    }

    #[cfg(feature = "metis")]
    /// An `nx × ny × nz` block of unit hexahedra (node `i + (nx+1)·(j + (ny+1)·k)`).
    fn hex_block(nx: usize, ny: usize, nz: usize) -> (Cells, usize) {
        let node = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
        let mut cells = Cells::default();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let (a, b) = (k, k + 1);
                    cells.push(&[
                        node(i, j, a),
                        node(i + 1, j, a),
                        node(i + 1, j + 1, a),
                        node(i, j + 1, a),
                        node(i, j, b),
                        node(i + 1, j, b),
                        node(i + 1, j + 1, b),
                        node(i, j + 1, b),
                    ]);
                }
            }
        }
        (cells, (nx + 1) * (ny + 1) * (nz + 1))
    }

    /// The busiest part's evaluated cells over the mean of all parts' evaluated cells.
    fn assembly_imbalance(cells: &Cells, nn: usize, nparts: usize, part: Vec<u32>) -> f64 {
        let evaluated = Partition::new(cells, nn, nparts, part).evaluated_cells(cells);
        let mean = evaluated.iter().sum::<usize>() as f64 / nparts as f64;
        *evaluated.iter().max().unwrap() as f64 / mean
    }

    #[test]
    fn the_lowest_part_evaluates_its_neighbours_boundary_cells() {
        // two cells, one per part: part 0 owns the shared face and evaluates both cells
        let (cells, nn) = Cells::hex_row(2);
        let p = Partition::new(&cells, nn, 2, vec![0, 1]);
        assert_eq!(p.evaluated_cells(&cells), vec![2, 1]);
    }

    #[test]
    #[cfg(feature = "metis")]
    fn more_parts_than_cells_are_refused_by_every_partitioner() {
        let (cells, nn) = Cells::hex_row(2);
        let band = vec![0, 1];
        let refused = |r: Result<Vec<u32>, PartitionError>| {
            matches!(r, Err(PartitionError::TooManyParts { parts: 3, cells: 2 }))
        };
        assert!(refused(partition_elements(&cells, nn, 3)));
        assert!(refused(partition_elements_by_band(&cells, nn, 3, &band, 2)));
        assert!(refused(partition_for_assembly(&cells, nn, 3, &band, 2)));
        assert_eq!(partition_for_assembly(&cells, nn, 2, &band, 2).unwrap().len(), 2);
    }

    #[test]
    fn the_partition_for_assembly_balances_the_evaluated_cells() {
        let (cells, nn) = hex_block(24, 24, 4);
        let band: Vec<u32> = (0..cells.len())
            .map(|c| u32::from(c >= cells.len() / 2))
            .collect();
        for (nparts, n_bands) in [(2, 1), (2, 2), (4, 1)] {
            let plain = partition_elements_by_band(&cells, nn, nparts, &band, n_bands).unwrap();
            let balanced = partition_for_assembly(&cells, nn, nparts, &band, n_bands).unwrap();
            assert_eq!(
                balanced,
                partition_for_assembly(&cells, nn, nparts, &band, n_bands).unwrap()
            );
            let before = assembly_imbalance(&cells, nn, nparts, plain);
            let after = assembly_imbalance(&cells, nn, nparts, balanced);
            // METIS does not always meet the shifted targets of several balance constraints
            // (the two-band case); then the first partition stays
            let improved = if n_bands == 1 {
                after < before && after < 1.03
            } else {
                after <= before
            };
            assert!(
                improved,
                "{nparts} parts, {n_bands} bands: evaluated cells max / mean {before:.3} -> {after:.3}"
            );
        }
    }

    #[test]
    fn banded_partition_spreads_every_band_over_the_parts() {
        // two bands of 20 cells along a row: a partition of the whole row cuts it once, in the
        // middle, and leaves each band on one part; the banded one splits both bands
        let (cells, nn) = Cells::hex_row(40);
        let band: Vec<u32> = (0..40).map(|c| u32::from(c >= 20)).collect();
        let whole = partition_elements(&cells, nn, 2).unwrap();
        let on_part_0 = |p: &[u32], b: u32| (0..40).filter(|&c| band[c] == b && p[c] == 0).count();
        assert!(
            [0, 20].contains(&on_part_0(&whole, 0)),
            "the plain partition keeps band 0 together: {whole:?}"
        );
        let banded = partition_elements_by_band(&cells, nn, 2, &band, 2).unwrap();
        assert_eq!(
            banded,
            partition_elements_by_band(&cells, nn, 2, &band, 2).unwrap()
        );
        for b in 0..2 {
            let n0 = on_part_0(&banded, b);
            assert!(
                (7..=13).contains(&n0),
                "band {b}: {n0} of 20 on part 0: {banded:?}"
            );
        }
    }

    #[test]
    fn partition_file_round_trip_and_mismatch() {
        let (cells, nn) = Cells::hex_row(4);
        let dir = std::env::temp_dir().join(format!("cfrd-part-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("p.json");
        PartitionFile::new(&cells, nn, 2, vec![0, 0, 1, 1])
            .write(&path)
            .unwrap();
        assert_eq!(
            PartitionFile::read(&path, &cells, nn, 2).unwrap(),
            vec![0, 0, 1, 1]
        );
        let err = PartitionFile::read(&path, &cells, nn, 3).unwrap_err().to_string();
        assert!(err.contains("made for 2 ranks"), "{err}");
        let (other, nn2) = Cells::hex_row(5);
        let err = PartitionFile::read(&path, &other, nn2, 2)
            .unwrap_err()
            .to_string();
        assert!(err.contains("another mesh"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
