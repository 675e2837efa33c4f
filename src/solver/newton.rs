//! The Newton step that serves every time integrator: PETSc SNES with a line search on
//! the distributed system, our residual and Jacobian, exact norms.
//!
//! ```text
//! F(x) = f_int(x) − f_ext + g(x)   on free DOFs,     F_i = d·(x_i − ū_i)   on fixed DOFs,
//! J(x) = K_t(x) + G                with the fixed rows and columns replaced by d·I
//! ```
//! (g, G the integrator's inertia/damping forces and shifts, zero in statics,
//! [`super::integrator`]; d the mean stiffness diagonal, set by the last assembly of K). The
//! initial guess already holds the prescribed values ū, so the fixed entries of F stay zero
//! and zeroing the fixed columns of J is exact. Every evaluation integrates the materials from
//! the committed states with the step increment x − u_committed (spec models §8.1); only the
//! Jacobian assembles K (the line search's residual evaluations do not pay for tangents). The
//! convergence test is on ‖F‖ / max(‖f_ext‖, ‖f_int‖, ‖g‖) with exact, order-independent sums, so
//! every decision is the same at any rank count; the states are committed only on convergence.

use super::error::SolveError;
use super::integrator::TimeIntegrator;
use super::model::Model;
use super::report::SolveReport;
use crate::linalg::petsc::{Matrix, PetscError, Snes, SnesOutcome, SnesProblem, Vector};
use crate::parallel::{any_error, any_true, exact_norm2, exact_sum};
use mpi::traits::Communicator;
use std::time::Instant;

/// What one step solves for besides the model: the external force and the prescribed values.
pub(super) struct StepTarget {
    /// f_ext of the step (stage loads at the step's load factor and placement forces).
    pub f_ext: Vector,
    /// Fixed DOFs: (local index, prescribed value at the step's end).
    pub targets: Vec<(usize, f64)>,
    /// Fixed DOFs (global rows).
    pub rows: Vec<i32>,
    /// The step's end, "λ = …" or "t = … s" (printed by the monitor).
    pub at: String,
    /// Whether the initial guess is the integrator's prediction (then checked against
    /// [`PREDICTION_REJECTED_AT`]).
    pub predicted: bool,
    /// The relative residual at which the step has converged (the stage's `newton_tol`).
    pub tolerance: f64,
}

/// A predicted start whose relative residual (‖F‖ / max(‖f_ext‖, ‖f_int‖, ‖g‖)) reaches this
/// is no prediction: its internal forces are out of all proportion to the loads (the
/// extrapolation overshot a material's stiffening, e.g. a GP interface closing, and
/// ‖f_int‖ reached 3.8e26 N on the medium seed mesh), and Newton cannot bring them back. The
/// step starts again from the last converged state ([`SolveError::AtStart`]); a start from
/// there has a residual of at most the step's load increment.
pub const PREDICTION_REJECTED_AT: f64 = 0.5;

/// A Newton correction is solved until its linearized residual is at most this share of the
/// step's tolerance, ‖F‖ ≤ share · tolerance · max(‖f_ext‖, ‖f_int‖, ‖g‖) (the direct
/// solvers' GMRES in a dynamic stage, [`SnesProblem::correction_tolerance`]; their relative
/// tolerance still applies where it is looser): a linear solve then leaves no more error than
/// a tenth of what the convergence test accepts, and is not solved further for nothing.
pub const CORRECTION_SHARE: f64 = 0.1;

/// Solves one step to equilibrium from the initial guess `x` (the committed state or the
/// integrator's prediction; Newton on SNES with `snes`) and commits the states on
/// convergence. On failure the model's trial state is left where the last iterate was; the
/// caller reverts it.
pub(super) fn solve(
    model: &mut Model,
    snes: &mut Snes,
    integrator: &dyn TimeIntegrator,
    (target, mut x): (StepTarget, Vector),
    report: &mut SolveReport,
) -> Result<(), SolveError> {
    // the prescribed values of this step
    x.write(|s| {
        for &(l, v) in &target.targets {
            s[l] = v;
        }
    })?;
    let mut r = model.u.duplicate()?;
    let f_int = model.u.duplicate()?;
    let f_last = Some(model.u.duplicate()?);
    let t0 = Instant::now();
    let mut step = NewtonStep {
        model,
        integrator,
        target,
        f_int,
        ref_norm: 1e-300,
        residual_norm: f64::NAN,
        residual_at: None,
        f_last,
        failure: None,
        evaluations: 0,
        start_failed: false,
        report,
        assembly_seconds: 0.0,
        last_linear_iterations: 0,
    };
    let solved = snes.solve(&mut step, &mut r, &mut x);
    step.report.factorizations += snes.take_factorizations();
    step.report.multigrid_builds += snes.take_multigrid_builds();
    if let Some(rows) = snes.held_rows()? {
        step.report.solver_rows_held = step.report.solver_rows_held.max(rows);
    }
    step.report.solve_seconds += (t0.elapsed().as_secs_f64() - step.assembly_seconds).max(0.0);
    let (outcome, iterations) = solved?;
    step.conclude(outcome, iterations, &x)
}

/// One step's nonlinear problem as SNES sees it (module docs).
struct NewtonStep<'s, 'a> {
    model: &'s mut Model<'a>,
    integrator: &'s dyn TimeIntegrator,
    target: StepTarget,
    f_int: Vector,
    /// max(‖f_ext‖, ‖f_int‖, ‖g‖) of the last residual evaluation.
    ref_norm: f64,
    /// ‖F‖ of the last residual evaluation (exact sum: the same at any rank count).
    residual_norm: f64,
    /// This rank's entries of the x of the last residual evaluation (`None`: it failed).
    residual_at: Option<Vec<f64>>,
    /// F of the last residual evaluation (at `residual_at`); `None` only while it is filled.
    f_last: Option<Vector>,
    /// Message of the last failed material update.
    failure: Option<String>,
    /// Residual evaluations of this step.
    evaluations: u32,
    /// Whether the first residual evaluation, at the initial guess, failed.
    start_failed: bool,
    report: &'s mut SolveReport,
    assembly_seconds: f64,
    last_linear_iterations: u32,
}

impl NewtonStep<'_, '_> {
    /// ‖F‖ / max(‖f_ext‖, ‖f_int‖, ‖g‖) of the last residual evaluation (the exact norm at the
    /// iterate SNES accepted, not VecNorm's), which `newton_tol` bounds.
    fn relative_residual(&self) -> f64 {
        self.residual_norm / self.ref_norm
    }

    /// After SNES ended with `outcome` at `x`: commits the states of the solution (evaluated
    /// there again if the last residual was not at x; collective), or names the failure.
    fn conclude(self, outcome: SnesOutcome, iterations: u32, x: &Vector) -> Result<(), SolveError> {
        let model = self.model;
        let residual = self.report.residuals.last().copied().unwrap_or(f64::NAN);
        // a material failure at a trial iterate (rejected by the line search) is often the cause
        let rejected = self.failure.as_ref().map_or(String::new(), |m| {
            format!("; a material update failed at a trial iterate: {m}")
        });
        let worst = |model: &Model| {
            model
                .worst_node(&self.f_int, &self.target.f_ext, &self.target.targets)
                .map(|w| w + &rejected)
        };
        match outcome {
            SnesOutcome::Converged => {
                let same = model.u.read(|u| x.read(|s| u == s))??;
                let mut f_int = self.f_int;
                if any_true(model.comm, !same) {
                    model.u.copy_from(x)?;
                    self.report.element_loops += 1;
                    let assembled = model.assemble(&mut f_int, false, false);
                    any_error(model.comm, assembled).map_err(SolveError::Collective)?;
                }
                self.report.newton_iterations += iterations;
                model.commit_at(&f_int)
            }
            SnesOutcome::DomainError => {
                let m = self
                    .failure
                    .unwrap_or_else(|| "the residual could not be evaluated".into());
                Err(match self.start_failed {
                    true => SolveError::AtStart(m),
                    false => SolveError::Collective(m),
                })
            }
            SnesOutcome::LinearSolve(reason) => Err(SolveError::Linear {
                reason,
                iterations: self.last_linear_iterations,
            }),
            SnesOutcome::LineSearch => Err(SolveError::LineSearch {
                iterations,
                residual,
                worst: worst(model)?,
            }),
            SnesOutcome::Diverged(_) => Err(SolveError::Newton {
                iterations,
                residual,
                worst: worst(model)?,
                hint: model.stall_hint(residual, self.target.tolerance),
            }),
        }
    }

    /// Sets u = x and assembles f_int (and K if `want_k`) there; a material failure on any rank
    /// is reported on all (collective). With `trial_is_current` the trial states are
    /// already those of x ([`Model::assemble`]).
    fn evaluate_at(&mut self, x: &Vector, want_k: bool, trial_is_current: bool) -> Result<bool, PetscError> {
        if !trial_is_current {
            // the trial states move to x: they are no longer those of the last residual
            self.residual_at = None;
        }
        self.model.u.copy_from(x)?;
        if !want_k && !trial_is_current && self.model.kept_forces_at(x, &mut self.f_int)? {
            return Ok(true);
        }
        let t0 = Instant::now();
        self.report.element_loops += 1;
        let assembled = self.model.assemble(&mut self.f_int, want_k, trial_is_current);
        let dt = t0.elapsed().as_secs_f64();
        self.report.assembly_seconds += dt;
        self.assembly_seconds += dt;
        match any_error(self.model.comm, assembled) {
            Ok(()) => Ok(true),
            Err(m) => {
                self.failure = Some(m);
                Ok(false)
            }
        }
    }

    /// Whether `x` is (on every rank) the iterate of the last successful residual evaluation,
    /// whose trial states and norm are still current. Collective.
    fn at_last_residual(&self, x: &Vector) -> Result<bool, PetscError> {
        let here = match &self.residual_at {
            Some(at) => x.read(|s| s == at.as_slice())?,
            None => false,
        };
        Ok(!any_true(self.model.comm, !here))
    }

    /// F(x) into the kept vector of the last residual (see [`NewtonStep::evaluate_residual`]).
    fn evaluate_last(&mut self, x: &Vector) -> Result<bool, PetscError> {
        let mut f = self.f_last.take().expect("F of the last residual is kept");
        let ok = self.evaluate_residual(x, &mut f);
        self.f_last = Some(f);
        ok
    }

    /// F(x) into `f` and its norm, with the norms of f_ext and f_int (exact sums, so every
    /// Newton decision is the same at any rank count). `Ok(false)`: a material update failed.
    fn evaluate_residual(&mut self, x: &Vector, f: &mut Vector) -> Result<bool, PetscError> {
        self.residual_at = None;
        self.report.residual_evaluations += 1;
        self.evaluations += 1;
        if !self.evaluate_at(x, false, false)? {
            self.start_failed = self.evaluations == 1;
            return Ok(false);
        }
        f.copy_from(&self.f_int)?;
        f.axpy(-1.0, &self.target.f_ext)?;
        let inertia = self.integrator.inertia(x)?;
        if let Some(g) = &inertia {
            f.axpy(1.0, g)?;
        }
        let d = self.model.dirichlet_diag;
        let xs: Vec<f64> = x.read(|s| s.to_vec())?;
        f.write(|s| {
            for &(l, v) in &self.target.targets {
                s[l] = d * (xs[l] - v);
            }
        })?;
        let comm = self.model.comm;
        let norm = |v: &Vector| v.read(|s| exact_norm2(comm, s));
        let g_norm = match &inertia {
            Some(g) => norm(g)?,
            None => 0.0,
        };
        self.ref_norm = norm(&self.target.f_ext)?
            .max(norm(&self.f_int)?)
            .max(g_norm)
            .max(1e-300);
        self.residual_norm = norm(f)?;
        if self.evaluations == 1 && self.target.predicted && !self.plausible_start() {
            return Ok(false);
        }
        self.residual_at = Some(xs);
        Ok(true)
    }

    /// Whether the relative residual at a predicted start stays below
    /// [`PREDICTION_REJECTED_AT`] (the same decision on every rank: exact norms); if not,
    /// the start counts as failed, with the reason.
    fn plausible_start(&mut self) -> bool {
        let rel = self.relative_residual();
        if rel < PREDICTION_REJECTED_AT {
            return true;
        }
        self.failure = Some(format!(
            "the relative residual there is {rel:.3e} (at most {PREDICTION_REJECTED_AT} is taken)"
        ));
        self.start_failed = true;
        false
    }
}

impl SnesProblem for NewtonStep<'_, '_> {
    fn residual(&mut self, x: &Vector, f: &mut Vector) -> Result<bool, PetscError> {
        // a line search that accepts the point of its last merit evaluation asks for F there
        // again: it is known
        if !self.at_last_residual(x)? && !self.evaluate_last(x)? {
            return Ok(false);
        }
        f.copy_from(self.f_last.as_ref().expect("F of the last residual is kept"))?;
        Ok(true)
    }

    fn objective(&mut self, x: &Vector) -> Result<Option<f64>, PetscError> {
        // the line search first asks at the current iterate, where F is already known
        if !self.at_last_residual(x)? && !self.evaluate_last(x)? {
            return Ok(None);
        }
        Ok(Some(self.residual_norm * self.residual_norm))
    }

    fn jacobian(&mut self, x: &Vector) -> Result<bool, PetscError> {
        // SNES asks for J where the line search left its last residual: the trial states are
        // those of x already, and need no second integration
        let current = self.at_last_residual(x)?;
        if !self.evaluate_at(x, true, current)? {
            return Ok(false);
        }
        self.integrator.add_shifts(&mut self.model.k)?;
        let d = self.model.dirichlet_diag;
        self.model.k.zero_rows_columns_only(&self.target.rows, d)?;
        Ok(true)
    }

    fn jacobian_matrix(&self) -> &Matrix {
        &self.model.k
    }

    fn dot(&mut self, a: &Vector, b: &Vector) -> Result<f64, PetscError> {
        let comm = self.model.comm;
        a.read(|sa| b.read(|sb| exact_sum(comm, sa.iter().zip(sb).map(|(x, y)| x * y))))?
    }

    fn last_residual_converged(&self) -> bool {
        self.residual_at.is_some() && self.relative_residual() <= self.target.tolerance
    }

    fn correction_tolerance(&self) -> Option<f64> {
        Some(CORRECTION_SHARE * self.target.tolerance * self.ref_norm)
    }

    fn converged(&mut self, it: u32, _fnorm: f64, linear_iterations: u32) -> Option<bool> {
        let rel = self.relative_residual();
        if it > 0 {
            self.report.ksp_iterations.push(linear_iterations);
            self.last_linear_iterations = linear_iterations;
        }
        self.report.residuals.push(rel);
        let opts = &self.model.scene.file.solver;
        if opts.monitor && self.model.comm.rank() == 0 {
            eprintln!(
                "newton {} iteration {it}: relative residual {rel:.3e}{}",
                self.target.at,
                if it > 0 {
                    format!(" ({linear_iterations} linear iterations)")
                } else {
                    String::new()
                }
            );
        }
        if !rel.is_finite() {
            return Some(false);
        }
        (it > 0 && rel <= self.target.tolerance).then_some(true)
    }
}
