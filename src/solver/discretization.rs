//! Rank-local view of the distributed problem: owned elements, owned and ghost nodes, and the
//! DOF numbering.
//!
//! DOF numbering (rank-count independent in meaning, contiguous per rank for PETSc): nodes are
//! sorted by (owner rank, input index); DOF `3·k + c` is component `c` of the `k`-th node in
//! that order ([`partition::Partition::dof_node`]). Each rank owns the DOFs of its nodes.
//!
//! Rank-count-independent assembly: a rank evaluates every element it owns **and** every
//! element that touches one of its nodes ([`Discretization::elements`]), and adds to its own
//! rows only. Each entry of a global vector or matrix is then summed on one rank, over the same
//! elements in the same (input) order at any rank count, so the assembled system is the same
//! bit for bit. The price is the evaluation of the elements along the partition boundary on
//! both sides; their states are kept in step because both ranks integrate them from the same
//! committed state with the same increment.

use partition::{Cells, Partition};

/// Rank-local indexing of the mesh.
#[derive(Debug, Clone)]
pub struct Discretization {
    /// This rank.
    pub rank: usize,
    /// The partition (same on every rank).
    pub partition: Partition,
    /// Elements this rank owns (stores in results and checkpoints), in input order.
    pub owned_elements: Vec<u32>,
    /// Elements this rank evaluates, in input order: the owned ones and every element touching
    /// an owned node (module docs).
    pub elements: Vec<u32>,
    /// Whether each of [`Discretization::elements`] is owned by this rank.
    pub element_owned: Vec<bool>,
    /// Nodes this rank owns, in input order.
    pub owned_nodes: Vec<u32>,
    /// Nodes the evaluated elements touch plus the owned nodes (sorted input indices): the
    /// rank's local node list, gathered from the distributed vectors.
    pub local_nodes: Vec<u32>,
    /// For every evaluated element ([`Discretization::elements`]), the positions of its 8 nodes
    /// in `local_nodes`.
    pub element_local: Vec<[u32; 8]>,
    /// Global (PETSc) DOF index of each local DOF (3 per local node).
    pub local_dofs: Vec<i32>,
    /// First global DOF this rank owns.
    pub dof_lo: usize,
    /// Number of DOFs this rank owns.
    pub n_owned_dofs: usize,
    /// Total number of DOFs.
    pub n_dofs: usize,
}

impl Discretization {
    /// Builds the rank-local indexing of `cells` (each with 8 nodes) for `rank`.
    pub fn new(cells: &Cells, n_nodes: usize, partition: Partition, rank: usize) -> Discretization {
        let owned_elements = partition.owned_cells(rank);
        let owned_nodes = partition.owned_nodes(rank);
        let me = rank as u32;
        let elements: Vec<u32> = (0..cells.len())
            .filter(|&c| {
                partition.cell_part[c] == me
                    || cells
                        .nodes(c)
                        .iter()
                        .any(|&n| partition.node_owner[n as usize] == me)
            })
            .map(|c| c as u32)
            .collect();
        let element_owned = elements
            .iter()
            .map(|&c| partition.cell_part[c as usize] == me)
            .collect();
        let mut local_nodes: Vec<u32> = owned_nodes.clone();
        for &c in &elements {
            local_nodes.extend_from_slice(cells.nodes(c as usize));
        }
        local_nodes.sort_unstable();
        local_nodes.dedup();
        let mut pos = vec![u32::MAX; n_nodes];
        for (i, &n) in local_nodes.iter().enumerate() {
            pos[n as usize] = i as u32;
        }
        let element_local = elements
            .iter()
            .map(|&e| {
                let nodes = cells.nodes(e as usize);
                std::array::from_fn(|a| pos[nodes[a] as usize])
            })
            .collect();
        let local_dofs = local_nodes
            .iter()
            .flat_map(|&n| {
                let k = partition.dof_node[n as usize] as i32;
                [3 * k, 3 * k + 1, 3 * k + 2]
            })
            .collect();
        let dof_lo = 3 * partition.node_offsets[rank];
        let n_owned_dofs = 3 * owned_nodes.len();
        Discretization {
            rank,
            owned_elements,
            elements,
            element_owned,
            owned_nodes,
            local_nodes,
            element_local,
            local_dofs,
            dof_lo,
            n_owned_dofs,
            n_dofs: 3 * n_nodes,
            partition,
        }
    }

    /// Global DOF of component `c` of node `n`.
    pub fn dof(&self, n: u32, c: usize) -> i32 {
        3 * self.partition.dof_node[n as usize] as i32 + c as i32
    }

    /// Whether global DOF `d` is owned by this rank.
    pub fn owns_dof(&self, d: i32) -> bool {
        (d as usize).wrapping_sub(self.dof_lo) < self.n_owned_dofs
    }

    /// The global DOFs in the mesh's own order: entry `3·n + c` is the PETSc index of component
    /// `c` of node `n` (input index). The same list describes the same unknowns at any rank count.
    pub fn canonical_dofs(&self) -> Vec<i32> {
        (0..self.partition.dof_node.len() as u32)
            .flat_map(|n| (0..3).map(move |c| (n, c)))
            .map(|(n, c)| self.dof(n, c))
            .collect()
    }

    /// Exact preallocation for the owned rows: for every owned DOF, the number of coupled
    /// DOFs in the owned (diagonal) block and outside it. Rows couple through every element
    /// that touches the node, whichever rank owns the element.
    pub fn preallocation(&self, cells: &Cells, n_nodes: usize) -> (Vec<i32>, Vec<i32>) {
        // node -> elements (CSR) for the owned nodes only
        let mut is_owned = vec![false; n_nodes];
        for &n in &self.owned_nodes {
            is_owned[n as usize] = true;
        }
        let mut count = vec![0usize; n_nodes + 1];
        for c in 0..cells.len() {
            for &n in cells.nodes(c) {
                if is_owned[n as usize] {
                    count[n as usize + 1] += 1;
                }
            }
        }
        for i in 0..n_nodes {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut adj = vec![0u32; count[n_nodes]];
        for c in 0..cells.len() {
            for &n in cells.nodes(c) {
                if is_owned[n as usize] {
                    adj[fill[n as usize]] = c as u32;
                    fill[n as usize] += 1;
                }
            }
        }
        let me = self.rank as u32;
        let mut d_nnz = Vec::with_capacity(self.n_owned_dofs);
        let mut o_nnz = Vec::with_capacity(self.n_owned_dofs);
        let mut neigh: Vec<u32> = Vec::new();
        for &n in &self.owned_nodes {
            neigh.clear();
            for &c in &adj[count[n as usize]..count[n as usize + 1]] {
                neigh.extend_from_slice(cells.nodes(c as usize));
            }
            neigh.sort_unstable();
            neigh.dedup();
            // a node no element touches still gets its diagonal entry (it is fixed by the solver)
            let d = neigh
                .iter()
                .filter(|&&m| self.partition.node_owner[m as usize] == me)
                .count()
                .max(1);
            let o = neigh.len() - d;
            for _ in 0..3 {
                d_nnz.push(3 * d as i32);
                o_nnz.push(3 * o as i32);
            }
        }
        (d_nnz, o_nnz)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every DOF row is owned by exactly one rank, and that rank evaluates every element that
    /// touches it: the assembled rows are complete without any off-rank contribution.
    #[test]
    fn each_row_is_assembled_completely_by_its_owner() {
        let (cells, nn) = Cells::hex_row(7);
        for part in [vec![0, 0, 0, 1, 1, 1, 1], vec![0, 1, 0, 1, 2, 2, 1]] {
            let nparts = *part.iter().max().unwrap() as usize + 1;
            let p = Partition::new(&cells, nn, nparts, part.clone());
            let discs: Vec<_> = (0..nparts)
                .map(|r| Discretization::new(&cells, nn, p.clone(), r))
                .collect();
            let mut owners = vec![0; 3 * nn];
            for d in &discs {
                for dof in 0..3 * nn as i32 {
                    if d.owns_dof(dof) {
                        owners[dof as usize] += 1;
                    }
                }
                for c in 0..cells.len() {
                    let touches = cells.nodes(c).iter().any(|&n| d.owns_dof(d.dof(n, 0)));
                    let evaluated = d.elements.contains(&(c as u32));
                    assert_eq!(
                        evaluated,
                        touches || part[c] as usize == d.rank,
                        "cell {c}, {part:?}"
                    );
                }
                let owned: Vec<u32> = d
                    .elements
                    .iter()
                    .zip(&d.element_owned)
                    .filter(|(_, &o)| o)
                    .map(|(&e, _)| e)
                    .collect();
                assert_eq!(owned, d.owned_elements);
                // the canonical list names every DOF once
                let mut canon = d.canonical_dofs();
                canon.sort_unstable();
                assert_eq!(canon, (0..3 * nn as i32).collect::<Vec<_>>());
            }
            assert!(owners.iter().all(|&k| k == 1), "{owners:?}");
        }
    }
}
