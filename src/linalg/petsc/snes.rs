//! [`Snes`], PETSc's nonlinear solver driven by a [`SnesProblem`], and the callbacks through
//! which PETSc calls the problem.
#![allow(unsafe_code)]

use super::error::{call, callback_code, convert, to_petsc_int, PetscError};
use super::init::Petsc;
use super::line_search::{shell_function, LineSearch};
use super::method::{set_shell_absolute_tolerance, shell_iterations, LinearMethod, LinearSolver};
use super::problem::SnesProblem;
use super::vector::Vector;
use crate::linalg::ffi as p;
use std::ffi::c_char;
use std::ptr::{null, null_mut};

/// How a SNES solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SnesOutcome {
    /// The problem's convergence test was met.
    Converged,
    /// The residual or Jacobian could not be evaluated (material failure).
    DomainError,
    /// The linear solver failed (PETSc's KSP reason).
    LinearSolve(i32),
    /// The line search failed to decrease the residual.
    LineSearch,
    /// The problem's convergence test declared divergence, or the iteration limit was hit.
    Diverged(i32),
}

/// PETSc's nonlinear solver (Newton with a line search, `newtonls` with the `l2` line search by
/// default), driven by a [`SnesProblem`]; `-snes_*` options override the defaults.
pub struct Snes {
    raw: p::SNES,
    comm: mpi::ffi::MPI_Comm,
    settings: (u32, f64, u32, bool),
    /// The linear solver of the Newton corrections and its shell states (dropped after the
    /// SNES).
    solver: LinearSolver,
    /// The direct solvers are set for the Jacobians of a dynamic stage ([`Snes::set_time_stepping`]).
    time_stepping: bool,
    /// The linear solver of the next [`Snes::reset`] on, if it changes there
    /// ([`Snes::set_linear_method`]).
    next_method: Option<LinearMethod>,
    /// The Jacobian and its preconditioner are built once and kept ([`Snes::set_kept_jacobian`]).
    kept_jacobian: bool,
    /// How a Newton correction is scaled ([`Snes::set_line_search`]).
    line_search: LineSearch,
}

impl Snes {
    /// A Newton solver with at most `max_it` iterations and, for the linearized systems, the
    /// linear solver `method` ([`LinearMethod`]); then PETSc options are applied.
    pub fn new(
        petsc: &Petsc,
        max_it: u32,
        rtol: f64,
        ksp_max_it: u32,
        symmetric: bool,
        method: LinearMethod,
    ) -> Result<Snes, PetscError> {
        let mut raw: p::SNES = null_mut();
        call!(SNESCreate(petsc.comm(), &mut raw))?;
        let mut s = Snes {
            raw,
            comm: petsc.comm(),
            settings: (max_it, rtol, ksp_max_it, symmetric),
            solver: LinearSolver::new(method),
            time_stepping: false,
            next_method: None,
            kept_jacobian: false,
            line_search: LineSearch::Secant,
        };
        s.configure()?;
        Ok(s)
    }

    /// Sets the direct solvers up for the Jacobians of a dynamic stage (`true`) or of a static
    /// one from the next [`Snes::reset`] on (refactoring threshold and tolerance of
    /// [`super::lagged_lu`]).
    pub fn set_time_stepping(&mut self, on: bool) {
        self.time_stepping = on;
    }

    /// The linear solver of the Newton corrections from the next [`Snes::reset`] on (a dynamic
    /// stage's own, or the static stages').
    pub fn set_linear_method(&mut self, method: LinearMethod) {
        self.next_method = Some(method);
    }

    /// From the next [`Snes::reset`] on (`true`): the Jacobian and its preconditioner are built
    /// at the first Newton iteration and kept for every later iteration and solve, for a
    /// problem whose Jacobian does not change (a linear scene's time steps of one Δt), until
    /// [`Snes::rebuild_jacobian`].
    pub fn set_kept_jacobian(&mut self, on: bool) {
        self.kept_jacobian = on;
    }

    /// With a kept Jacobian: builds it (and its preconditioner) again at the next Newton
    /// iteration, then keeps that one.
    pub fn rebuild_jacobian(&mut self) -> Result<(), PetscError> {
        call!(SNESSetLagJacobian(self.raw, -2))?;
        call!(SNESSetLagPreconditioner(self.raw, -2))
    }

    /// The line search of the Newton corrections from the next [`Snes::reset`] on
    /// (`-snes_linesearch_type` still overrides it).
    pub fn set_line_search(&mut self, line_search: LineSearch) {
        self.line_search = line_search;
    }

    /// Replaces the solver by a new one with the same settings: the next solve builds the
    /// preconditioner afresh (smoothed-aggregation GAMG otherwise keeps state from its earlier
    /// set-ups that `KSPReset` does not clear). Called at the start of every stage, so a stage's
    /// solves do not depend on the earlier stages and a restart from a checkpoint repeats them
    /// bitwise.
    pub fn reset(&mut self) -> Result<(), PetscError> {
        let mut raw: p::SNES = null_mut();
        call!(SNESCreate(self.comm, &mut raw))?;
        // SAFETY: created by SNESCreate, destroyed once; replaced by the new solver below.
        unsafe {
            p::SNESDestroy(&mut self.raw);
        }
        self.raw = raw;
        // the old shell context goes only now that no PC refers to it
        self.solver.release();
        if let Some(method) = self.next_method.take() {
            self.solver.set_method(method);
        }
        self.configure()
    }

    /// cfrd's settings on a new SNES.
    fn configure(&mut self) -> Result<(), PetscError> {
        let (max_it, rtol, ksp_max_it, symmetric) = self.settings;
        self.solver
            .create(self.comm, symmetric, (self.time_stepping, self.kept_jacobian))?;
        let s = &*self;
        call!(SNESSetType(s.raw, p::SNESNEWTONLS.as_ptr() as *const c_char))?;
        // the problem's convergence test decides; only the iteration limit is SNES's own
        let max_it = to_petsc_int(max_it, "Newton iteration limit")?;
        call!(SNESSetTolerances(s.raw, 0.0, 0.0, 0.0, max_it, -1))?;
        // the secant line search minimizing ‖F‖² along the Newton direction: on the GP column
        // of tests/step_control.rs with a 10 MPa surcharge and at most 6 Newton iterations it
        // needs no cut-back ([4]) where the full step (`basic`) needs one ([6, 4]) and
        // backtracking (`bt`) two ([6, 4, 4]); `-snes_linesearch_type` overrides
        // (`LineSearch::FullStepFirst`: a shell whose function `solve` sets)
        let mut ls: p::SNESLineSearch = null_mut();
        call!(SNESGetLineSearch(s.raw, &mut ls))?;
        let kind = s.line_search.petsc_type();
        call!(SNESLineSearchSetType(ls, kind.as_ptr() as *const c_char))?;
        let mut ksp: p::KSP = null_mut();
        call!(SNESGetKSP(s.raw, &mut ksp))?;
        s.solver.install(ksp, rtol, ksp_max_it, symmetric)?;
        if s.kept_jacobian {
            // -2: built at the next chance, then never again; persisting across solves
            call!(SNESSetLagJacobian(s.raw, -2))?;
            call!(SNESSetLagJacobianPersists(s.raw, p::PETSC_TRUE))?;
            call!(SNESSetLagPreconditioner(s.raw, -2))?;
            call!(SNESSetLagPreconditionerPersists(s.raw, p::PETSC_TRUE))?;
        }
        // options (scene and command line) are applied here, so a bad one is an input error
        call!(SNESSetFromOptions(s.raw))
    }

    /// Set-ups of the reduced multigrid's multigrid since the last call (0 with other solvers).
    pub fn take_multigrid_builds(&mut self) -> u64 {
        self.solver.take_multigrid_builds()
    }

    /// Rows of the matrices this rank's direct solver holds (its factors' or its Schwarz
    /// subdomains'; the whole system for the canonical solver); `None` for the other solvers
    /// and before the first solve.
    pub fn held_rows(&self) -> Result<Option<u64>, PetscError> {
        self.solver.held_rows()
    }

    /// Numeric factorizations of the direct solvers since the last call (0 with the Krylov
    /// defaults; the reduced multigrid's: of its structure).
    pub fn take_factorizations(&mut self) -> u64 {
        self.solver.take_factorizations()
    }

    /// Solves F(x) = 0 from the initial guess in `x`, with `r` as the residual work vector.
    /// Returns the outcome and the Newton iterations.
    pub fn solve<P: SnesProblem>(
        &mut self,
        problem: &mut P,
        r: &mut Vector,
        x: &mut Vector,
    ) -> Result<(SnesOutcome, u32), PetscError> {
        let j = problem.jacobian_matrix().raw;
        let ctx = problem as *mut P as *mut std::ffi::c_void;
        call!(SNESSetFunction(self.raw, r.raw, Some(snes_residual::<P>), ctx))?;
        call!(SNESSetJacobian(self.raw, j, j, Some(snes_jacobian::<P>), ctx))?;
        call!(SNESSetConvergenceTest(
            self.raw,
            Some(snes_converged::<P>),
            ctx,
            None
        ))?;
        call!(SNESSetObjective(self.raw, Some(snes_objective::<P>), ctx))?;
        let mut ls: p::SNESLineSearch = null_mut();
        call!(SNESGetLineSearch(self.raw, &mut ls))?;
        // a no-op unless the line search is the shell (options may have chosen another)
        let shell = shell_function::<P>(self.line_search);
        call!(SNESLineSearchShellSetUserFunc(ls, Some(shell), ctx))?;
        call!(SNESSolve(self.raw, null_mut(), x.raw))?;
        let (mut reason, mut its) = (0, 0);
        call!(SNESGetConvergedReason(self.raw, &mut reason))?;
        call!(SNESGetIterationNumber(self.raw, &mut its))?;
        let outcome = match reason {
            r if r > 0 => SnesOutcome::Converged,
            p::SNES_DIVERGED_FUNCTION_DOMAIN => SnesOutcome::DomainError,
            p::SNES_DIVERGED_LINEAR_SOLVE => {
                let mut ksp: p::KSP = null_mut();
                let mut kr = 0;
                call!(SNESGetKSP(self.raw, &mut ksp))?;
                call!(KSPGetConvergedReason(ksp, &mut kr))?;
                SnesOutcome::LinearSolve(kr)
            }
            p::SNES_DIVERGED_LINE_SEARCH => SnesOutcome::LineSearch,
            r => SnesOutcome::Diverged(r),
        };
        Ok((outcome, convert(its, "Newton iterations")?))
    }
}

impl Drop for Snes {
    fn drop(&mut self) {
        // SAFETY: created by SNESCreate, destroyed once.
        unsafe {
            p::SNESDestroy(&mut self.raw);
        }
    }
}

unsafe extern "C" fn snes_objective<P: SnesProblem>(
    snes: p::SNES,
    x: p::Vec,
    obj: *mut p::PetscReal,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual; `obj` is a valid out-pointer.
    let problem = unsafe { &mut *(ctx as *mut P) };
    let value = match problem.objective(&Vector::borrowed(x)) {
        Ok(Some(v)) => v,
        // an infinite merit value makes the line search back off (or fail)
        Ok(None) => f64::INFINITY,
        Err(e) => return callback_code(Err(e)),
    };
    let _ = snes;
    unsafe {
        *obj = value;
    }
    0
}

unsafe extern "C" fn snes_residual<P: SnesProblem>(
    snes: p::SNES,
    x: p::Vec,
    f: p::Vec,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: ctx is the `&mut P` given to Snes::solve, alive for the whole SNESSolve.
    let problem = unsafe { &mut *(ctx as *mut P) };
    let (x, mut f) = (Vector::borrowed(x), Vector::borrowed(f));
    match problem.residual(&x, &mut f) {
        Ok(true) => 0,
        Ok(false) => unsafe { p::SNESSetFunctionDomainError(snes) },
        Err(e) => callback_code(Err(e)),
    }
}

unsafe extern "C" fn snes_jacobian<P: SnesProblem>(
    snes: p::SNES,
    x: p::Vec,
    _a: p::Mat,
    _b: p::Mat,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual.
    let problem = unsafe { &mut *(ctx as *mut P) };
    match problem.jacobian(&Vector::borrowed(x)) {
        Ok(true) => match problem.correction_tolerance() {
            // SAFETY: `snes` is live during its callback; its PC is a shell of cfrd's or not.
            Some(atol) => callback_code(unsafe { correction_tolerance_to_solver(snes, atol) }),
            None => 0,
        },
        Ok(false) => unsafe { p::SNESSetJacobianDomainError(snes) },
        Err(e) => callback_code(Err(e)),
    }
}

/// Gives the linear solver of `snes` the absolute tolerance `atol` of the next correction
/// ([`SnesProblem::correction_tolerance`]).
///
/// # Safety
/// `snes` must be live, its linear solver installed by [`LinearSolver::install`].
unsafe fn correction_tolerance_to_solver(snes: p::SNES, atol: f64) -> Result<(), PetscError> {
    let (mut ksp, mut pc): (p::KSP, p::PC) = (null_mut(), null_mut());
    call!(SNESGetKSP(snes, &mut ksp))?;
    call!(KSPGetPC(ksp, &mut pc))?;
    // SAFETY: the caller's contract.
    unsafe { set_shell_absolute_tolerance(pc, atol) }
}

unsafe extern "C" fn snes_converged<P: SnesProblem>(
    snes: p::SNES,
    it: p::PetscInt,
    _xnorm: p::PetscReal,
    _gnorm: p::PetscReal,
    fnorm: p::PetscReal,
    reason: *mut p::SNESConvergedReason,
    ctx: *mut std::ffi::c_void,
) -> p::PetscErrorCode {
    // SAFETY: as in snes_residual; `reason` is a valid out-pointer.
    let problem = unsafe { &mut *(ctx as *mut P) };
    // SAFETY: `snes` is the SNES of the running SNESSolve.
    let verdict = unsafe { linear_iterations(snes, it) }.and_then(|linear| {
        let it = convert(it, "Newton iterations")?;
        Ok(match problem.converged(it, fnorm, linear) {
            Some(true) => p::SNES_CONVERGED_FNORM_ABS,
            Some(false) => p::SNES_DIVERGED_DTOL,
            None => p::SNES_CONVERGED_ITERATING,
        })
    });
    match verdict {
        Ok(r) => {
            unsafe {
                *reason = r;
            }
            0
        }
        Err(e) => callback_code(Err(e)),
    }
}

/// The Krylov iterations of the last linear solve of `snes` after `it` Newton iterations (0
/// before the first): of cfrd's direct solvers, their inner iterations.
///
/// # Safety
/// `snes` is the SNES of a running `SNESSolve` whose shell states are alive.
unsafe fn linear_iterations(snes: p::SNES, it: p::PetscInt) -> Result<u32, PetscError> {
    if it <= 0 {
        return Ok(0);
    }
    let mut lin = 0;
    let (mut ksp, mut pc, mut kind): (p::KSP, p::PC, p::PCType) = (null_mut(), null_mut(), null());
    unsafe {
        p::SNESGetKSP(snes, &mut ksp);
        p::KSPGetIterationNumber(ksp, &mut lin);
        p::KSPGetPC(ksp, &mut pc);
        p::PCGetType(pc, &mut kind);
    }
    // SAFETY: PETSc's type name, a NUL-terminated string while the PC lives.
    let shell =
        !kind.is_null() && unsafe { std::ffi::CStr::from_ptr(kind) }.to_bytes_with_nul() == p::PCSHELL;
    // cfrd's shells (the direct solvers): their inner Krylov iterations
    if shell {
        // SAFETY: a shell installed by `LinearSolver::install`, alive for the whole SNESSolve;
        // its name tells which.
        if let Some(its) = unsafe { shell_iterations(pc) } {
            return Ok(its);
        }
    }
    convert(lin, "Krylov iterations")
}
