//! The quasi-static integrator: a static stage's time is its load factor.

use super::{Rates, TimeIntegrator};
use crate::linalg::petsc::{Matrix, PetscError, Vector};

/// Statics as a time integrator: λ = t over the stage's time [0, 1], no inertia, no damping,
/// no shifts, no state of its own.
#[derive(Debug, Clone, Copy, Default)]
pub struct QuasiStatic;

impl TimeIntegrator for QuasiStatic {
    fn load_factor(&self, t1: f64) -> f64 {
        t1
    }

    fn begin_step(&mut self, _t0: f64, _t1: f64) {}

    fn inertia(&self, _x: &Vector) -> Result<Option<Vector>, PetscError> {
        Ok(None)
    }

    fn add_shifts(&self, _j: &mut Matrix) -> Result<(), PetscError> {
        Ok(())
    }

    fn accept(&mut self, _u1: &Vector) -> Result<(), PetscError> {
        Ok(())
    }

    fn rates(&self) -> Result<Option<Rates>, PetscError> {
        Ok(None)
    }

    fn restore_rates(&mut self, _u: &Vector, _rates: &Rates) -> Result<(), PetscError> {
        Ok(())
    }
}
