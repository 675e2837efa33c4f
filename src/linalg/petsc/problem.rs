//! [`SnesProblem`]: what a nonlinear problem gives PETSc's SNES.

use super::error::PetscError;
use super::matrix::Matrix;
use super::vector::Vector;

/// What a nonlinear problem gives PETSc's SNES: the residual F(x), the Jacobian J(x) and the
/// convergence test. Every method is called collectively (on all ranks, in the same order).
pub trait SnesProblem {
    /// Evaluates F(x) into `f`. `Ok(false)` reports a (collectively decided) failure to evaluate
    /// at `x`, e.g. a material update that failed on some rank; SNES then stops with
    /// [`SnesOutcome::DomainError`](super::SnesOutcome::DomainError) (or its line search backs off).
    fn residual(&mut self, x: &Vector, f: &mut Vector) -> Result<bool, PetscError>;
    /// Evaluates J(x) into [`SnesProblem::jacobian_matrix`].
    fn jacobian(&mut self, x: &Vector) -> Result<bool, PetscError>;
    /// The matrix the Jacobian is assembled into (also the preconditioning matrix).
    fn jacobian_matrix(&self) -> &Matrix;
    /// Convergence test after `it` Newton iterations with PETSc's residual norm `fnorm` (the
    /// problem may use its own, rank-count-independent norm of the last residual instead) and
    /// the iterations of the last linear solve: `Some(true)` converged, `Some(false)` diverged,
    /// `None` go on.
    fn converged(&mut self, it: u32, fnorm: f64, linear_iterations: u32) -> Option<bool>;
    /// The line search's merit function at `x`, ‖F(x)‖², or `Ok(None)` when F cannot be
    /// evaluated there. Given to SNES as its objective, so that the `l2` and `bt` line searches
    /// rest on the problem's own (rank-count-independent) norm rather than on `VecNorm`, whose
    /// partial sums depend on the partition.
    fn objective(&mut self, x: &Vector) -> Result<Option<f64>, PetscError>;
    /// The dot product aᵀb of two vectors laid out like x, independent of the rank count
    /// (the residual secant line search's decisions rest on it).
    fn dot(&mut self, a: &Vector, b: &Vector) -> Result<f64, PetscError>;
    /// Whether the last residual evaluated already meets the convergence test (the same on
    /// every rank): [`LineSearch::ResidualSecant`](super::LineSearch::ResidualSecant) then keeps the full step rather than
    /// extending it, and Newton ends there. The default: never.
    fn last_residual_converged(&self) -> bool {
        false
    }
    /// The norm of the linearized residual at which the correction of the Newton iteration
    /// whose Jacobian was just evaluated is solved closely enough (an absolute tolerance the
    /// direct solvers' GMRES of a dynamic stage also stops at), or `None`: their relative
    /// tolerance alone. The default: `None`.
    fn correction_tolerance(&self) -> Option<f64> {
        None
    }
}
