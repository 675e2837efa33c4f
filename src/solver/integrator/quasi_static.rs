//! The quasi-static integrator: a static stage's time is its load factor.

use super::{Rates, TimeIntegrator};
use crate::linalg::petsc::{Matrix, PetscError, Vector};

/// Statics as a time integrator: λ = t over the stage's time [0, 1], no inertia, no damping,
/// no shifts. With extrapolation ([`QuasiStatic::extrapolating`], `solver.predictor:
/// extrapolate`) the initial guess of a load step from λ₀ to λ₁ is
///
/// ```text
/// x⁰ = u(λ₀) + (λ₁ − λ₀)·(u(λ₀) − u(λ₋₁)) / (λ₀ − λ₋₁)
/// ```
///
/// from the stage's second converged step on (the first has no rate; a new stage places new
/// elements and loads, so the rate of the last one does not carry over). Every Newton
/// iteration still integrates the materials from the committed state over the whole increment
/// (spec models §8.1), so the guess changes the iterations, not the path-dependent solution
/// they converge to. Entry by entry on the owned DOFs: the same at any rank count.
#[derive(Debug, Clone, Default)]
pub struct QuasiStatic {
    /// Extrapolate the last step's rate (`solver.predictor: extrapolate`).
    extrapolate: bool,
    /// The step in progress: its start λ₀, its end λ₁ and u(λ₀) (owned DOFs).
    step: Option<(f64, f64, Vec<f64>)>,
    /// du/dλ of the last converged step (owned DOFs).
    rate: Option<Vec<f64>>,
}

impl QuasiStatic {
    /// Statics with the extrapolating predictor.
    pub fn extrapolating() -> Self {
        QuasiStatic {
            extrapolate: true,
            ..QuasiStatic::default()
        }
    }
}

impl TimeIntegrator for QuasiStatic {
    fn load_factor(&self, t1: f64) -> f64 {
        t1
    }

    fn begin_step(&mut self, t0: f64, t1: f64) {
        self.step = Some((t0, t1, Vec::new()));
    }

    fn predict(&mut self, x: &mut Vector) -> Result<(), PetscError> {
        if !self.extrapolate {
            return Ok(());
        }
        let Some((t0, t1, u0)) = self.step.as_mut() else {
            return Ok(());
        };
        *u0 = x.read(|s| s.to_vec())?;
        if let Some(rate) = &self.rate {
            let d = *t1 - *t0;
            x.write(|s| s.iter_mut().zip(rate).for_each(|(v, r)| *v += d * r))?;
        }
        Ok(())
    }

    fn forget(&mut self) {
        self.rate = None;
    }

    fn inertia(&self, _x: &Vector) -> Result<Option<Vector>, PetscError> {
        Ok(None)
    }

    fn add_shifts(&self, _j: &mut Matrix) -> Result<(), PetscError> {
        Ok(())
    }

    fn accept(&mut self, u1: &Vector) -> Result<(), PetscError> {
        if let Some((t0, t1, u0)) = self.step.take().filter(|(_, _, u0)| !u0.is_empty()) {
            let d = t1 - t0;
            self.rate = Some(u1.read(|s| s.iter().zip(&u0).map(|(a, b)| (a - b) / d).collect())?);
        }
        Ok(())
    }

    fn rates(&self) -> Result<Option<Rates>, PetscError> {
        Ok(None)
    }

    fn restore_rates(&mut self, _u: &Vector, _rates: &Rates) -> Result<(), PetscError> {
        Ok(())
    }
}
