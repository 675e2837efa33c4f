//! Prescribed DOFs of a stage: the scene's displacement conditions and the nodes that no
//! placed element touches yet (held where they are), with the values they move between.

use super::discretization::Discretization;

/// The fixed DOFs owned by this rank.
#[derive(Debug, Clone, Default)]
pub struct Constraints {
    /// The scene's displacement conditions on owned DOFs: (global dof, prescribed value).
    scene_fixed: Vec<(i32, f64)>,
    /// Fixed DOFs of the current stage: (global dof, value at the stage's end), sorted.
    pub(super) fixed: Vec<(i32, f64)>,
    /// Values of the fixed DOFs at the start of the stage (same order as `fixed`).
    fixed_start: Vec<f64>,
}

impl Constraints {
    /// The scene's conditions `(node, component, value)` on the DOFs this rank owns.
    pub(super) fn new(disc: &Discretization, fixed: &[(u32, u8, f64)]) -> Self {
        let me = disc.rank as u32;
        let scene_fixed = fixed
            .iter()
            .filter(|(n, _, _)| disc.partition.node_owner[*n as usize] == me)
            .map(|&(n, c, v)| (disc.dof(n, c as usize), v))
            .collect();
        Constraints {
            scene_fixed,
            ..Default::default()
        }
    }

    /// The fixed DOFs of a stage: the scene's conditions and the nodes not yet placed
    /// (`node_active` false), held at their displacement at the stage's start; that replaces
    /// any scene condition on them. Start values from `u_stage_start` (owned DOFs).
    pub(super) fn for_stage(&mut self, disc: &Discretization, node_active: &[bool], u_stage_start: &[f64]) {
        let lo = disc.dof_lo;
        let mut held: Vec<(i32, f64)> = Vec::new();
        for &n in &disc.owned_nodes {
            if !node_active[n as usize] {
                for c in 0..3 {
                    let d = disc.dof(n, c);
                    held.push((d, u_stage_start[d as usize - lo]));
                }
            }
        }
        held.sort_by_key(|f| f.0);
        let mut fixed: Vec<(i32, f64)> = self
            .scene_fixed
            .iter()
            .copied()
            .filter(|f| held.binary_search_by_key(&f.0, |h| h.0).is_err())
            .collect();
        fixed.extend(held);
        fixed.sort_by_key(|f| f.0);
        fixed.dedup_by_key(|f| f.0);
        self.fixed_start = fixed
            .iter()
            .map(|&(d, _)| u_stage_start[d as usize - lo])
            .collect();
        self.fixed = fixed;
    }

    /// The prescribed values at load factor `lambda`: (local index of the owned DOF,
    /// start + λ·(end − start)).
    pub(super) fn targets(&self, dof_lo: usize, lambda: f64) -> Vec<(usize, f64)> {
        self.fixed
            .iter()
            .zip(&self.fixed_start)
            .map(|(&(d, v), &v0)| (d as usize - dof_lo, v0 + lambda * (v - v0)))
            .collect()
    }

    /// The fixed DOFs (global rows).
    pub(super) fn rows(&self) -> Vec<i32> {
        self.fixed.iter().map(|f| f.0).collect()
    }

    /// Per owned DOF: whether it is fixed.
    pub(super) fn mask(&self, disc: &Discretization) -> Vec<bool> {
        let mut is_fixed = vec![false; disc.n_owned_dofs];
        for &(d, _) in &self.fixed {
            is_fixed[d as usize - disc.dof_lo] = true;
        }
        is_fixed
    }
}
