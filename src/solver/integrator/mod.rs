//! Time integrators: what a step adds to the Newton problem besides f_int and f_ext.
//!
//! The Newton step ([`super::newton`]) solves, for the DOFs that are not prescribed,
//!
//! ```text
//! r(x) = f_int(x) − λ(t₁)-scaled f_ext + g(x) = 0,     J(x) = K_t(x) + G
//! ```
//!
//! where an integrator supplies the load factor λ(t₁) of the step's end time, the inertia and
//! damping forces g(x) (for Newmark g = M·a(x) + C·v(x) + M·ι·a_g(t₁)) and the shifts
//! G = shift_v·C + shift_a·M of the Jacobian (PETSc TS's I2Jacobian seam, spec
//! architecture). Statics is the [`QuasiStatic`] integrator: λ = t, g = 0, G = 0. The solver
//! itself never asks which integrator it has.

pub mod newmark;
pub mod quasi_static;

pub use newmark::{Newmark, NewmarkParameters, Rayleigh};
pub use quasi_static::QuasiStatic;

use crate::linalg::petsc::{Matrix, PetscError, Vector};

/// What a time integrator adds to one step's nonlinear problem.
pub trait TimeIntegrator {
    /// The load factor λ at the step's end time `t1`: f_ext = f_prev + λ·(f_stage − f_prev),
    /// and prescribed displacements move by the same fraction.
    fn load_factor(&self, t1: f64) -> f64;

    /// Prepares the step from the converged time `t0` to `t1` (the shifts depend on dt).
    fn begin_step(&mut self, t0: f64, t1: f64);

    /// The Newton iterations' initial guess of the step begun by
    /// [`TimeIntegrator::begin_step`]: `x` holds the converged displacement on entry (owned
    /// DOFs); an integrator that predicts changes it (the prescribed DOFs are set afterwards).
    fn predict(&mut self, _x: &mut Vector) -> Result<(), PetscError> {
        Ok(())
    }

    /// Forgets what the predictor learnt from earlier steps (after a step checkpoint, so that
    /// a restart from it, which starts without that history, repeats the same steps).
    fn forget(&mut self) {}

    /// The inertia and damping forces g(x) of the iterate `x` (owned rows; the Newton step adds
    /// them to the residual and counts their norm in its reference), `None` when there are
    /// none.
    fn inertia(&self, x: &Vector) -> Result<Option<Vector>, PetscError>;

    /// Adds the shifts G = shift_v·C + shift_a·M to the assembled tangent `j` (before the
    /// prescribed rows and columns are replaced).
    fn add_shifts(&self, j: &mut Matrix) -> Result<(), PetscError>;

    /// Accepts the converged displacement `u1` at the step's end: updates the integrator's
    /// own state (velocity, acceleration).
    fn accept(&mut self, u1: &Vector) -> Result<(), PetscError>;

    /// The committed velocity and acceleration relative to the base (owned DOFs), and the
    /// ground acceleration at the last step's end; `None` for an integrator without them
    /// (statics stores no velocity).
    fn rates(&self) -> Result<Option<Rates>, PetscError>;

    /// Restores the committed velocity and acceleration of a checkpoint (owned DOFs) at the
    /// displacement `u`; an integrator without rates ignores them.
    fn restore_rates(&mut self, u: &Vector, rates: &Rates) -> Result<(), PetscError>;
}

/// Velocity and acceleration of the owned DOFs, relative to the base, and the ground
/// acceleration at the same time.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Rates {
    /// Velocity (m/s), 3 values per owned node.
    pub velocity: Vec<f64>,
    /// Acceleration relative to the base (m/s²), 3 values per owned node.
    pub acceleration: Vec<f64>,
    /// Ground acceleration (m/s², x, y, z).
    pub ground: [f64; 3],
    /// HHT-α's force history h = C·v + f_int(u) − f_ext of the committed step, 3 values per
    /// owned node; empty for Newmark ([`Newmark`]).
    pub history: Vec<f64>,
}
