//! Mass and initial stiffness of the placed model, built only for a dynamic stage (spec
//! seismic §3.1): the consistent mass M = Σ_e ∫ ρ NᵀN dV of the solid elements (or its
//! row-sum lumped diagonal), and K₀, the stiffness at the committed state, for Rayleigh
//! damping. Interface and joint elements carry no mass.

use super::error::SolveError;
use super::model::{BlockStates, Model};
use crate::element::hex8::{consistent_mass, lumped_mass};
use crate::linalg::petsc::{Matrix, Vector};
use crate::parallel::any_error;

impl Model<'_> {
    /// The mass matrix of the placed solid elements (owned rows, in the tangent's pattern):
    /// consistent, or lumped (row sums on the diagonal) with `lumped`.
    pub(super) fn assemble_mass(&self, lumped: bool) -> Result<Matrix, SolveError> {
        let mesh = &self.scene.mesh;
        let mut m = self.k.duplicate()?;
        m.zero()?;
        let mut values = [0.0f64; 576];
        for (i, &e) in self.disc.elements.iter().enumerate() {
            let (b, _) = self.elem_block[i];
            if !self.active_block[b] || !matches!(self.blocks[b], BlockStates::Solid(_)) {
                continue;
            }
            let e = e as usize;
            let rho = self.scene.block_materials[b].density();
            let x = mesh.element_coords(e);
            let me = if lumped {
                nalgebra::SMatrix::<f64, 24, 24>::from_diagonal(&lumped_mass(&x, rho))
            } else {
                consistent_mass(&x, rho)
            };
            let rows = self.element_dofs(e);
            let mut owned = Vec::with_capacity(24);
            for (r, &d) in rows.iter().enumerate() {
                if self.disc.owns_dof(d) {
                    for c in 0..24 {
                        values[24 * owned.len() + c] = me[(r, c)];
                    }
                    owned.push(d);
                }
            }
            if !owned.is_empty() {
                m.add_values(&owned, &rows, &values[..24 * owned.len()])?;
            }
        }
        m.assemble()?;
        Ok(m)
    }

    /// K₀: the stiffness of every placed element at the committed state (the tangent of a zero
    /// increment), a copy frozen for Rayleigh damping. Collective; leaves the trial states at
    /// the committed ones.
    pub(super) fn initial_stiffness(&mut self) -> Result<Matrix, SolveError> {
        self.u.copy_from(&self.u_committed)?;
        let mut f: Vector = self.u.duplicate()?;
        let assembled = self.assemble(&mut f, true, false);
        any_error(self.comm, assembled).map_err(SolveError::Collective)?;
        Ok(self.k.duplicate()?)
    }
}
