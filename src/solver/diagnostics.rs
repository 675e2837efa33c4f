//! What a failed step says about itself: where the out-of-balance force is largest, and
//! whether the residual may be stuck at the noise of the stress integration.

use super::error::SolveError;
use super::model::Model;
use crate::linalg::petsc::Vector;
use crate::parallel::{broadcast_vec, max_f64};
use mpi::collective::{CommunicatorCollectives, SystemOperation};
use mpi::traits::Communicator;

impl Model<'_> {
    /// A hint for a Newton solve that ended at `residual` (relative) without converging: when
    /// the largest substepping tolerance STOL of the scene's GP materials lies above
    /// `newton_tol` and the residual within a decade of it, the residual may be the noise of
    /// the stress integration (spec models §8.2; `solver.integration_tol_ratio`). Empty
    /// otherwise. `tol` is the stage's `newton_tol`.
    pub(super) fn stall_hint(&self, residual: f64, tol: f64) -> String {
        let stol = self
            .scene
            .block_materials
            .iter()
            .filter_map(|m| m.gp_integration().map(|o| o.stol))
            .reduce(f64::max);
        match stol {
            Some(stol) if stol > tol && residual < 10.0 * stol => format!(
                "; the residual is within a decade of the GP substepping tolerance STOL = {stol:.1e}, \
                 which lies above newton_tol = {tol:.1e}: Newton may be stalled at the integration \
                 noise (cap STOL with `solver.integration_tol_ratio: 0.1` or `cfrd run \
                 --integration-tol-ratio 0.1`)"
            ),
            _ => String::new(),
        }
    }

    /// Names the node where the out-of-balance force f_int − f_ext of the last evaluated
    /// iterate is largest (free components only), with its coordinates and the placed blocks
    /// around it, for the report of a failed step (collective). Non-finite forces are skipped.
    pub(super) fn worst_node(
        &self,
        f_int: &Vector,
        f_ext: &Vector,
        targets: &[(usize, f64)],
    ) -> Result<String, SolveError> {
        let mut r: Vec<f64> =
            f_int.read(|a| f_ext.read(|b| a.iter().zip(b).map(|(p, q)| p - q).collect()))??;
        for &(l, _) in targets {
            r[l] = 0.0;
        }
        let (mut best, mut node) = (-1.0f64, 0usize);
        for (i, &n) in self.disc.owned_nodes.iter().enumerate() {
            let v = (r[3 * i].powi(2) + r[3 * i + 1].powi(2) + r[3 * i + 2].powi(2)).sqrt();
            if v > best {
                (best, node) = (v, n as usize);
            }
        }
        let top = max_f64(self.comm, best);
        let holder = if best == top { self.comm.rank() } else { i32::MAX };
        let mut root = i32::MAX;
        self.comm
            .all_reduce_into(&holder, &mut root, SystemOperation::min());
        if top < 0.0 {
            return Ok("no node has a finite out-of-balance force".into());
        }
        let mut msg: Vec<u8> = if self.comm.rank() == root {
            self.describe_node(node, top).into_bytes()
        } else {
            Vec::new()
        };
        broadcast_vec(self.comm, root, &mut msg);
        Ok(String::from_utf8_lossy(&msg).into_owned())
    }

    /// "largest out-of-balance force … at node … (x, y, z) in <placed blocks around it>".
    fn describe_node(&self, node: usize, force: f64) -> String {
        let mesh = &self.scene.mesh;
        let mut blocks: Vec<&str> = mesh
            .elements
            .iter()
            .filter(|el| self.active_block[el.block as usize] && el.nodes.contains(&(node as u32)))
            .map(|el| mesh.blocks[el.block as usize].name.as_str())
            .collect();
        blocks.sort_unstable();
        blocks.dedup();
        let [x, y, z] = mesh.coords[node];
        format!(
            "largest out-of-balance force {force:.3e} N at node {} ({x:.2}, {y:.2}, {z:.2}) in {}",
            mesh.node_ids[node],
            blocks.join(", ")
        )
    }
}
