//! The internal forces at the committed state of a linear scene, kept from the evaluation
//! that converged there.
//!
//! A time step starts its Newton iterations at the committed displacement (without a
//! predictor), where f_int is the one of the evaluation the last step converged at: the
//! committed states are that evaluation's trial states. In a linear scene (every block linear
//! elastic) a new evaluation there would give those forces again bit for bit (the increment is
//! zero), so the first residual of every step takes them instead of integrating every element
//! once more: half the element loops of a linear quake, whose steps converge in one Newton
//! iteration. Other scenes always integrate: a plastic model's update at a zero increment
//! need not return its committed state bit for bit.

use super::error::SolveError;
use super::model::Model;
use crate::linalg::petsc::{PetscError, Vector};
use crate::parallel::any_true;

impl Model<'_> {
    /// Accepts the trial states and the current displacement, `f_int` being the internal
    /// forces there: kept for the next evaluation at the committed state in a linear scene.
    pub(super) fn commit_at(&mut self, f_int: &Vector) -> Result<(), SolveError> {
        self.commit()?;
        if self.is_linear() {
            let mut kept = f_int.duplicate()?;
            kept.copy_from(f_int)?;
            self.f_int_committed = Some(kept);
        }
        Ok(())
    }

    /// Writes into `f_int` the kept internal forces when `x` is the committed displacement on
    /// every rank and the trial states are the committed ones; `false` (nothing written) when
    /// they have to be integrated. Collective.
    pub(super) fn kept_forces_at(&self, x: &Vector, f_int: &mut Vector) -> Result<bool, PetscError> {
        let Some(kept) = &self.f_int_committed else {
            return Ok(false);
        };
        let here = x.read(|s| self.u_committed.read(|u| s == u))??;
        if any_true(self.comm, !here) {
            return Ok(false);
        }
        f_int.copy_from(kept)?;
        Ok(true)
    }
}
