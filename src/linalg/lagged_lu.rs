//! LU factors kept across Jacobians: the inner solver of both direct solvers
//! ([`super::petsc::CanonicalLu`] on every rank's gathered block, [`DistributedLu`] on the
//! distributed matrix), and the distributed LU's preconditioner shell.
//!
//! Within a stage the Jacobian changes little from one Newton iteration or load step to the
//! next. With reuse the factors of an earlier Jacobian are kept as the preconditioner of
//! right-preconditioned GMRES on the current matrix (relative tolerance 1e-9 on the true
//! residual); the matrix is factored again at the next Jacobian once a solve needed more than 8
//! GMRES iterations, and at once when GMRES does not converge in 30 (the solve is then repeated
//! with the new factors), so a changed tangent (an interface opening, rockfill yielding) costs a
//! factorization, not a failed step. In a dynamic stage the two numbers are 30 iterations and
//! 1e-6. `-<prefix>refactor_after N`, `-<prefix>ksp_max_it N` and
//! `-<prefix>ksp_rtol R` change the three numbers.
#![allow(unsafe_code)]

use super::ffi as p;
use super::petsc::{chk, PetscError, CALLBACK_FAILED};
use std::ffi::{c_char, CString};
use std::ptr::null_mut;

macro_rules! call {
    ($f:ident ( $($arg:expr),* $(,)? )) => {
        chk(unsafe { p::$f($($arg),*) }, stringify!($f))
    };
}

/// Lagged factors are replaced at the next Jacobian once a solve needed more than this many
/// GMRES iterations (each costs a forward and a backward substitution and a matrix product);
/// `-<prefix>refactor_after N` overrides.
const REFACTOR_AFTER_ITERATIONS: i32 = 8;
/// GMRES with lagged factors gives up after this many iterations; the current matrix is then
/// factored and the solve repeated (`-<prefix>ksp_max_it` overrides).
const LAGGED_MAX_ITERATIONS: i32 = 30;
/// Relative tolerance of GMRES with lagged factors on the unpreconditioned residual
/// (`-<prefix>ksp_rtol` overrides): well below the Newton tolerances of spec §8.1 (1e-4
/// typical, 1e-5 in the seed scenes), so Newton converges as with exact corrections.
const LAGGED_RTOL: f64 = 1e-9;
/// In a dynamic stage: refactor only after solves of more GMRES iterations than this, to the
/// relative tolerance [`TIME_STEPPING_RTOL`]. The GP rockfill switches between loading and
/// unloading from one time step to the next all over the dam, so factors of the last step's
/// Jacobian take 18–27 GMRES iterations to 1e-9 and were renewed at every other step; on the
/// medium seed quake these two settings took its first 1.56 s in 309 s instead of 406 s with
/// the same Newton iterations (`cfrd::performance`, "The seed quake (medium mesh)").
const TIME_STEPPING_REFACTOR_AFTER: i32 = 30;
/// GMRES's relative tolerance with lagged factors in a dynamic stage: still ten times below the
/// seed scenes' Newton tolerance.
const TIME_STEPPING_RTOL: f64 = 1e-6;

/// An LU solver (PETSc `KSP` + `PCLU`) whose factors may serve later matrices.
pub(crate) struct LaggedLu {
    pub(super) ksp: p::KSP,
    /// Keep the factors of an earlier matrix as the preconditioner of GMRES on the current
    /// one; `false`: factor every matrix.
    reuse: bool,
    /// The factors in use are those of an earlier matrix.
    lagged: bool,
    /// Factor at the next set-up (the last solve with lagged factors was slow, or the last
    /// factorization failed).
    pub(super) refactor: bool,
    /// Numeric factorizations not yet taken by [`LaggedLu::take_factorizations`].
    factorizations: u64,
    /// Krylov iterations of the last solve (1 for a direct solve).
    pub(super) last_iterations: u32,
    /// Refactor at the next matrix after a solve with more GMRES iterations than this.
    refactor_after: i32,
}

impl LaggedLu {
    /// A solver on communicator `comm` whose PETSc options take `prefix` (e.g. `canonical_`);
    /// `package`, if given, is the factorization package (options may override it);
    /// `time_stepping`: for the Jacobians of a dynamic stage (the refactoring threshold and
    /// tolerance of the module docs become 30 iterations and 1e-6; options still override).
    pub(crate) fn new(
        comm: mpi::ffi::MPI_Comm,
        prefix: &str,
        reuse: bool,
        package: Option<&[u8]>,
        time_stepping: bool,
    ) -> Result<LaggedLu, PetscError> {
        let (refactor_after, rtol) = match time_stepping {
            true => (TIME_STEPPING_REFACTOR_AFTER, TIME_STEPPING_RTOL),
            false => (REFACTOR_AFTER_ITERATIONS, LAGGED_RTOL),
        };
        let mut lu = LaggedLu {
            ksp: null_mut(),
            reuse,
            lagged: false,
            refactor: false,
            factorizations: 0,
            last_iterations: 0,
            refactor_after,
        };
        let c_prefix = CString::new(prefix).expect("no NUL");
        let (name, mut set) = (CString::new("-refactor_after").expect("no NUL"), p::PETSC_FALSE);
        call!(PetscOptionsGetInt(
            null_mut(),
            c_prefix.as_ptr(),
            name.as_ptr(),
            &mut lu.refactor_after,
            &mut set
        ))?;
        call!(KSPCreate(comm, &mut lu.ksp))?;
        call!(KSPSetOptionsPrefix(lu.ksp, c_prefix.as_ptr()))?;
        if reuse {
            call!(KSPSetType(lu.ksp, p::KSPGMRES.as_ptr() as *const c_char))?;
            call!(KSPGMRESSetRestart(lu.ksp, LAGGED_MAX_ITERATIONS))?;
            call!(KSPSetPCSide(lu.ksp, p::PC_RIGHT))?;
            call!(KSPSetNormType(lu.ksp, p::KSP_NORM_UNPRECONDITIONED))?;
            call!(KSPSetTolerances(
                lu.ksp,
                rtol,
                1e-300,
                1e30,
                LAGGED_MAX_ITERATIONS
            ))?;
        } else {
            call!(KSPSetType(lu.ksp, p::KSPPREONLY.as_ptr() as *const c_char))?;
        }
        let mut pc: p::PC = null_mut();
        call!(KSPGetPC(lu.ksp, &mut pc))?;
        call!(PCSetType(pc, p::PCLU.as_ptr() as *const c_char))?;
        if let Some(package) = package {
            call!(PCFactorSetMatSolverType(pc, package.as_ptr() as *const c_char))?;
        }
        call!(KSPSetFromOptions(lu.ksp))?;
        Ok(lu)
    }

    /// Whether the next set-up factors the matrix (reuse off, or a refactor is due).
    pub(crate) fn wants_factors(&self) -> bool {
        !self.reuse || self.refactor
    }

    /// Sets up on the current matrix: keeps the factors of an earlier matrix when `lagged`,
    /// factors it otherwise. Returns PETSc's failure reason of the factorization (0: none).
    pub(crate) fn factor(&mut self, lagged: bool) -> Result<p::PCFailedReason, PetscError> {
        let mut inner: p::PC = null_mut();
        call!(KSPGetPC(self.ksp, &mut inner))?;
        let keep = if lagged { p::PETSC_TRUE } else { p::PETSC_FALSE };
        call!(PCSetReusePreconditioner(inner, keep))?;
        call!(KSPSetUp(self.ksp))?;
        let mut failed: p::PCFailedReason = 0;
        if !lagged {
            self.factorizations += 1;
            self.refactor = false;
            call!(PCGetFailedReason(inner, &mut failed))?;
        }
        self.lagged = lagged;
        // factors that failed are never kept for a later matrix
        self.refactor |= failed != 0;
        Ok(failed)
    }

    /// Solves into `solution` from `rhs`: with lagged factors, GMRES preconditioned by them;
    /// when it does not converge, the current matrix is factored and the solve repeated.
    /// Returns whether the solve succeeded.
    pub(crate) fn solve(&mut self, rhs: p::Vec, solution: p::Vec) -> Result<bool, PetscError> {
        let (mut reason, mut its) = (0, 0);
        call!(KSPSolve(self.ksp, rhs, solution))?;
        call!(KSPGetConvergedReason(self.ksp, &mut reason))?;
        call!(KSPGetIterationNumber(self.ksp, &mut its))?;
        let mut total = its;
        if reason < 0 && self.lagged {
            if self.factor(false)? != 0 {
                self.last_iterations = total as u32;
                return Ok(false);
            }
            call!(KSPSolve(self.ksp, rhs, solution))?;
            call!(KSPGetConvergedReason(self.ksp, &mut reason))?;
            call!(KSPGetIterationNumber(self.ksp, &mut its))?;
            total += its;
        } else if self.lagged && its > self.refactor_after {
            self.refactor = true;
        }
        self.last_iterations = total.max(1) as u32;
        Ok(reason >= 0)
    }

    /// Numeric factorizations since the last call.
    pub(crate) fn take_factorizations(&mut self) -> u64 {
        std::mem::take(&mut self.factorizations)
    }
}

impl Drop for LaggedLu {
    fn drop(&mut self) {
        // SAFETY: created by KSPCreate (or null, which KSPDestroy accepts), destroyed once.
        unsafe {
            p::KSPDestroy(&mut self.ksp);
        }
    }
}

/// MUMPS's LU on the distributed matrix, factored by all ranks together, as a preconditioner
/// shell under `preonly` (`solver.linear_solver: distributed_lu`). Each rank holds its share of
/// the matrix and of the factors, so memory and work are split between ranks. With
/// `solver.reuse_factorization` (the default) the factors serve later Jacobians of the same
/// stage as described in the module docs; a new stage starts with a factorization. Its options
/// take the prefix `distributed_` (e.g. `-distributed_mat_mumps_icntl_14 50`,
/// `-distributed_refactor_after 4`). MUMPS's parallel sums follow message timing, so two runs
/// agree to the factorization's rounding, not bit for bit.
pub struct DistributedLu {
    inner: LaggedLu,
    /// The shell has factored a matrix of this stage.
    factored: bool,
}

/// The name the distributed LU's shell reports (`-ksp_view`), and by which it is recognised.
pub const DISTRIBUTED_LU_NAME: &[u8] = b"distributed LU (MUMPS on all ranks)\0";

impl DistributedLu {
    /// The shell's state on communicator `comm`.
    /// `time_stepping`: for a dynamic stage (the module docs).
    pub fn new(
        comm: mpi::ffi::MPI_Comm,
        reuse: bool,
        time_stepping: bool,
    ) -> Result<Box<DistributedLu>, PetscError> {
        Ok(Box::new(DistributedLu {
            inner: LaggedLu::new(
                comm,
                "distributed_",
                reuse,
                Some(p::MATSOLVERMUMPS),
                time_stepping,
            )?,
            factored: false,
        }))
    }

    /// Makes `ksp` apply this solver (`preonly` with the shell preconditioner).
    pub(crate) fn install(&self, ksp: p::KSP) -> Result<(), PetscError> {
        call!(KSPSetType(ksp, p::KSPPREONLY.as_ptr() as *const c_char))?;
        let mut pc: p::PC = null_mut();
        call!(KSPGetPC(ksp, &mut pc))?;
        call!(PCSetType(pc, p::PCSHELL.as_ptr() as *const c_char))?;
        let ctx = self as *const DistributedLu as *mut std::ffi::c_void;
        call!(PCShellSetContext(pc, ctx))?;
        call!(PCShellSetSetUp(pc, Some(distributed_lu_setup)))?;
        call!(PCShellSetApply(pc, Some(distributed_lu_apply)))?;
        call!(PCShellSetName(pc, DISTRIBUTED_LU_NAME.as_ptr() as *const c_char))
    }

    /// Krylov iterations of the last solve (1 for a direct solve).
    pub fn last_iterations(&self) -> u32 {
        self.inner.last_iterations
    }

    /// Numeric factorizations since the last call.
    pub fn take_factorizations(&mut self) -> u64 {
        self.inner.take_factorizations()
    }

    /// Factors the preconditioning matrix of `pc`, or keeps the earlier factors.
    fn setup(&mut self, pc: p::PC) -> Result<(), PetscError> {
        let (mut a, mut pmat): (p::Mat, p::Mat) = (null_mut(), null_mut());
        call!(PCGetOperators(pc, &mut a, &mut pmat))?;
        if !self.factored {
            call!(KSPSetOperators(self.inner.ksp, pmat, pmat))?;
        }
        let fresh = !self.factored || self.inner.wants_factors();
        let failed = self.inner.factor(!fresh)?;
        self.factored = true;
        if failed != 0 {
            // a zero pivot: the Newton step fails as a linear solve and is cut back
            call!(PCSetFailedReason(pc, p::PC_SUBPC_ERROR))?;
        }
        Ok(())
    }

    /// y = A⁻¹ x.
    fn apply(&mut self, pc: p::PC, x: p::Vec, y: p::Vec) -> Result<(), PetscError> {
        if !self.inner.solve(x, y)? {
            call!(PCSetFailedReason(pc, p::PC_SUBPC_ERROR))?;
        }
        Ok(())
    }
}

/// The shell context of `pc` as the distributed LU.
///
/// # Safety
/// `pc` must be a shell installed by [`DistributedLu::install`], whose context is alive.
pub(super) unsafe fn distributed_context<'a>(pc: p::PC) -> Result<&'a mut DistributedLu, PetscError> {
    let mut ctx: *mut std::ffi::c_void = null_mut();
    call!(PCShellGetContext(
        pc,
        &mut ctx as *mut *mut std::ffi::c_void as *mut std::ffi::c_void
    ))?;
    // SAFETY: the context is the boxed DistributedLu owned by the Snes (caller's contract).
    Ok(unsafe { &mut *(ctx as *mut DistributedLu) })
}

unsafe extern "C" fn distributed_lu_setup(pc: p::PC) -> p::PetscErrorCode {
    // SAFETY: installed by DistributedLu::install with its context.
    match unsafe { distributed_context(pc) }.and_then(|lu| lu.setup(pc)) {
        Ok(()) => 0,
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}

unsafe extern "C" fn distributed_lu_apply(pc: p::PC, x: p::Vec, y: p::Vec) -> p::PetscErrorCode {
    // SAFETY: installed by DistributedLu::install with its context.
    match unsafe { distributed_context(pc) }.and_then(|lu| lu.apply(pc, x, y)) {
        Ok(()) => 0,
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}
