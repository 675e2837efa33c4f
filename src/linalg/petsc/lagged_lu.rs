//! Factors kept across Jacobians: the inner solver of both direct solvers
//! ([`super::CanonicalLu`] on every rank's gathered block, [`DistributedLu`] on the
//! distributed matrix), and the distributed LU's preconditioner shell.
//!
//! **Static stages: lagged LU.** Within a stage the Jacobian changes little from one Newton
//! iteration or load step to the next. With reuse the factors of an earlier Jacobian are kept as
//! the preconditioner of right-preconditioned GMRES on the current matrix (relative tolerance
//! 1e-9 on the true residual); the matrix is factored again at the next Jacobian once a solve
//! needed more than 8 GMRES iterations, and at once when GMRES does not converge in 30 (the
//! solve is then repeated with the new factors), so a changed tangent (an interface opening,
//! rockfill yielding) costs a factorization, not a failed step. `-<prefix>refactor_after N`,
//! `-<prefix>ksp_max_it N` and `-<prefix>ksp_rtol R` change the three numbers.
//!
//! **Dynamic stages: incomplete LU.** The Jacobian of a time step, K_t + shift_v·C +
//! shift_a·M (Newmark's effective stiffness), is dominated by the mass term, so an incomplete
//! factorization of the current Jacobian (ILU(0); on a distributed matrix, additive Schwarz
//! with ILU(0) on subdomains overlapping by [`SCHWARZ_OVERLAP`] layers) preconditions GMRES
//! well: it is factored afresh at every Jacobian, costs
//! a few matrix products, and GMRES (restart [`INCOMPLETE_RESTART`], at most
//! [`INCOMPLETE_MAX_ITERATIONS`] iterations) solves to the relative tolerance 1e-6, or only
//! until the linearized residual is a tenth of what the Newton step's convergence test accepts
//! where that is looser (the Newton step gives that tolerance with each Jacobian): a step's first
//! correction, from a residual near the inertia forces, is solved to about 1e-6, the later
//! ones to 1e-3–1e-1. The distributed solver factors and multiplies a copy of the Jacobian in
//! 3×3 node blocks (`MATMPIBAIJ`, `blocked.rs`; `-distributed_dynamic_blocked false`
//! keeps the scalar matrix; `cfrd::performance`, "The seed quake (medium mesh)"). A solve that
//! does not converge fails the Newton step, which is cut back (a shorter step is more strongly
//! mass-dominated). The options of a dynamic stage take the prefix `<prefix>dynamic_`, so the
//! static stages' choice of package (`-canonical_pc_factor_mat_solver_type mumps`) does not
//! reach them; `-canonical_dynamic_pc_type lu` restores lagged LU factors in dynamic stages,
//! refactored after solves of more than 30 GMRES iterations, to the same tolerance
//! (`cfrd::performance`, "The seed quake (medium mesh)", compares the two).
//!
//! **Kept factors: a linear scene's time steps.** Where the Jacobian is built once and kept
//! ([`super::Snes::set_kept_jacobian`]), the distributed solver ([`DistributedLu::kept`])
//! factors it completely and applies the factors alone (`preonly`): they are those of the very
//! matrix solved. On one rank it factors the matrix converted to 3×3 node blocks
//! (`MATSEQBAIJ`) with PETSc's own LU, whose substitution took 2.8–2.9 ms on the linear
//! embankment of `cfrd::performance` against 4.6–5.7 ms for the scalar matrix and 7.1 ms with
//! MUMPS; on several ranks MUMPS factors the distributed matrix.
#![allow(unsafe_code)]

use super::blocked::BlockedCopy;
use super::error::{call, chk, convert, PetscError};
use super::options::{bool_option, default_option};
use super::pc_shell::{self, PcShell};
use crate::linalg::ffi as p;
use std::ffi::{c_char, CStr, CString};
use std::ptr::null_mut;

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
/// Jacobian take 18–27 GMRES iterations to 1e-9 and were renewed at every other step; these
/// two settings renew them only where GMRES needs it.
const TIME_STEPPING_REFACTOR_AFTER: i32 = 30;
/// GMRES's relative tolerance in a dynamic stage (lagged or incomplete factors), unless the
/// Newton step asks for less ([`LaggedLu::set_absolute_tolerance`]): still ten times below
/// the seed scenes' Newton tolerance.
const TIME_STEPPING_RTOL: f64 = 1e-6;
/// Overlap of the subdomains of the distributed solver's additive Schwarz preconditioner in a
/// dynamic stage (`-distributed_dynamic_pc_asm_overlap` overrides). On the small GP-interface
/// dam of `tests/dynamics.rs` on 2 ranks, GMRES took 231 iterations per solve with block
/// Jacobi (no overlap), 31 with overlap 1 and 18.6 with overlap 2, against 12 with ILU(0)
/// of the whole matrix on 1 rank.
pub const SCHWARZ_OVERLAP: i32 = 2;
/// GMRES's restart with incomplete factors (`-<prefix>dynamic_ksp_gmres_restart` overrides).
pub const INCOMPLETE_RESTART: i32 = 100;
/// GMRES's iteration limit with incomplete factors (`-<prefix>dynamic_ksp_max_it` overrides).
pub const INCOMPLETE_MAX_ITERATIONS: i32 = 300;
/// Most levels of fill the incomplete factors are raised to when a solve with them fails
/// (ILU(0), then ILU(1), ILU(2)). On 4 ranks the small GP-interface dam of `tests/dynamics.rs` has Schwarz subdomains of some 250 DOFs, on which GMRES with ILU(0)
/// took 40-140 iterations and broke down at t = 0.13 s whatever the step; with ILU(1) it took
/// 11.7 on average. On the coarse seed quake on 2 ranks ILU(1) throughout cost 162.5 s against
/// 123.8 s (15 % fewer GMRES iterations), so fill is added only where a solve needs it.
pub const MAX_FILL_LEVELS: i32 = 2;

/// A factored solver (PETSc `KSP` with `PCLU`, or `PCILU` / `PCASM` in a dynamic stage)
/// whose complete factors may serve later matrices (the module docs).
pub(crate) struct LaggedLu {
    pub(super) ksp: p::KSP,
    /// Keep the factors of an earlier matrix as the preconditioner of GMRES on the current
    /// one; `false`: factor every matrix.
    reuse: bool,
    /// The factors are incomplete (a dynamic stage's default): made afresh for every matrix.
    incomplete: bool,
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
    /// The solver has been set up on a matrix.
    set_up: bool,
    /// Levels of fill of the incomplete factors (raised when a solve fails, for the rest of
    /// the stage).
    fill_levels: i32,
    /// For the Jacobians of a dynamic stage.
    time_stepping: bool,
}

impl LaggedLu {
    /// A solver on communicator `comm` whose PETSc options take `prefix` (e.g. `canonical_`);
    /// `package`, if given, is the package of complete factors (options may override it);
    /// `time_stepping`: for the Jacobians of a dynamic stage, with the options prefix
    /// `<prefix>dynamic_` and incomplete factors unless the options ask for `lu` (the module
    /// docs).
    pub(crate) fn new(
        comm: mpi::ffi::MPI_Comm,
        prefix: &str,
        reuse: bool,
        package: Option<&[u8]>,
        time_stepping: bool,
    ) -> Result<LaggedLu, PetscError> {
        let (refactor_after, rtol, prefix) = match time_stepping {
            true => (
                TIME_STEPPING_REFACTOR_AFTER,
                TIME_STEPPING_RTOL,
                format!("{prefix}dynamic_"),
            ),
            false => (REFACTOR_AFTER_ITERATIONS, LAGGED_RTOL, prefix.to_string()),
        };
        let mut lu = LaggedLu {
            ksp: null_mut(),
            reuse,
            incomplete: false,
            lagged: false,
            refactor: false,
            factorizations: 0,
            last_iterations: 0,
            refactor_after,
            set_up: false,
            fill_levels: 0,
            time_stepping,
        };
        let c_prefix = CString::new(prefix.as_str()).expect("no NUL");
        lu.read_refactor_after(&c_prefix)?;
        call!(KSPCreate(comm, &mut lu.ksp))?;
        call!(KSPSetOptionsPrefix(lu.ksp, c_prefix.as_ptr()))?;
        lu.set_krylov(rtol, time_stepping)?;
        let mut pc: p::PC = null_mut();
        call!(KSPGetPC(lu.ksp, &mut pc))?;
        let kind = match (time_stepping, comm_size(comm)? > 1) {
            (false, _) => p::PCLU.as_slice(),
            (true, false) => p::PCILU.as_slice(),
            (true, true) => p::PCASM.as_slice(),
        };
        call!(PCSetType(pc, kind.as_ptr() as *const c_char))?;
        // a zero pivot of the incomplete factors is shifted rather than failing the step (on 4
        // ranks a subdomain of the small GP-interface dam of tests/dynamics.rs met one at
        // t = 0.13 s and no cut-back passed it); a complete factorization still fails on one
        if kind == p::PCILU.as_slice() {
            call!(PCFactorSetShiftType(pc, p::MAT_SHIFT_NONZERO))?;
        }
        if kind == p::PCASM.as_slice() {
            call!(PCASMSetOverlap(pc, SCHWARZ_OVERLAP))?;
            default_option(&format!("-{prefix}sub_pc_factor_shift_type"), "nonzero")?;
        }
        if let (Some(package), false) = (package, time_stepping) {
            call!(PCFactorSetMatSolverType(pc, package.as_ptr() as *const c_char))?;
        }
        call!(KSPSetFromOptions(lu.ksp))?;
        lu.incomplete = !is_complete_lu(pc)?;
        if let (Some(package), true, false) = (package, time_stepping, lu.incomplete) {
            call!(PCFactorSetMatSolverType(pc, package.as_ptr() as *const c_char))?;
        }
        Ok(lu)
    }

    /// `-<prefix>refactor_after N`, if given.
    fn read_refactor_after(&mut self, c_prefix: &CString) -> Result<(), PetscError> {
        let (name, mut set) = (CString::new("-refactor_after").expect("no NUL"), p::PETSC_FALSE);
        call!(PetscOptionsGetInt(
            null_mut(),
            c_prefix.as_ptr(),
            name.as_ptr(),
            &mut self.refactor_after,
            &mut set
        ))
    }

    /// The Krylov method before the options: right-preconditioned GMRES on the true residual
    /// when factors may be lagged, and in a dynamic stage (longer there, for incomplete
    /// factors); `preonly` when every matrix of a static stage is factored.
    fn set_krylov(&mut self, rtol: f64, time_stepping: bool) -> Result<(), PetscError> {
        if !self.reuse && !time_stepping {
            return call!(KSPSetType(self.ksp, p::KSPPREONLY.as_ptr() as *const c_char));
        }
        let (restart, max_it) = match time_stepping {
            true => (INCOMPLETE_RESTART, INCOMPLETE_MAX_ITERATIONS),
            false => (LAGGED_MAX_ITERATIONS, LAGGED_MAX_ITERATIONS),
        };
        call!(KSPSetType(self.ksp, p::KSPGMRES.as_ptr() as *const c_char))?;
        call!(KSPGMRESSetRestart(self.ksp, restart))?;
        call!(KSPSetPCSide(self.ksp, p::PC_RIGHT))?;
        call!(KSPSetNormType(self.ksp, p::KSP_NORM_UNPRECONDITIONED))?;
        call!(KSPSetTolerances(self.ksp, rtol, 1e-300, 1e30, max_it))
    }

    /// Whether the next set-up factors the matrix (reuse off, incomplete factors, or a refactor
    /// is due).
    pub(crate) fn wants_factors(&self) -> bool {
        !self.reuse || self.incomplete || self.refactor
    }

    /// Sets up on the current matrix: keeps the factors of an earlier matrix when `lagged`,
    /// factors it otherwise. Returns PETSc's failure reason of the factorization (0: none).
    pub(crate) fn factor(&mut self, lagged: bool) -> Result<p::PCFailedReason, PetscError> {
        let mut inner: p::PC = null_mut();
        call!(KSPGetPC(self.ksp, &mut inner))?;
        let keep = if lagged { p::PETSC_TRUE } else { p::PETSC_FALSE };
        call!(PCSetReusePreconditioner(inner, keep))?;
        call!(KSPSetUp(self.ksp))?;
        self.set_up = true;
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
        while reason < 0 && self.incomplete && self.fill_levels < MAX_FILL_LEVELS {
            self.more_fill()?;
            call!(KSPSolve(self.ksp, rhs, solution))?;
            call!(KSPGetConvergedReason(self.ksp, &mut reason))?;
            call!(KSPGetIterationNumber(self.ksp, &mut its))?;
            total += its;
        }
        if reason < 0 && self.lagged {
            if self.factor(false)? != 0 {
                self.last_iterations = convert(total, "Krylov iterations")?;
                return Ok(false);
            }
            call!(KSPSolve(self.ksp, rhs, solution))?;
            call!(KSPGetConvergedReason(self.ksp, &mut reason))?;
            call!(KSPGetIterationNumber(self.ksp, &mut its))?;
            total += its;
        } else if self.lagged && its > self.refactor_after {
            self.refactor = true;
        }
        self.last_iterations = convert(total.max(1), "Krylov iterations")?;
        Ok(reason >= 0)
    }

    /// Numeric factorizations since the last call.
    pub(crate) fn take_factorizations(&mut self) -> u64 {
        std::mem::take(&mut self.factorizations)
    }

    /// In a dynamic stage: GMRES stops too once the residual's norm is at most `atol`, the
    /// share of the Newton tolerance a correction needs (module docs, "Dynamic stages");
    /// a static stage's solves keep their relative tolerance alone.
    pub(crate) fn set_absolute_tolerance(&mut self, atol: f64) -> Result<(), PetscError> {
        if !self.time_stepping {
            return Ok(());
        }
        let (mut rtol, mut old, mut dtol, mut max_it) = (0.0, 0.0, 0.0, 0);
        call!(KSPGetTolerances(
            self.ksp,
            &mut rtol,
            &mut old,
            &mut dtol,
            &mut max_it
        ))?;
        call!(KSPSetTolerances(self.ksp, rtol, atol, dtol, max_it))
    }

    /// Factors the current matrix again with one more level of fill ([`MAX_FILL_LEVELS`]):
    /// every factored solver's preconditioner is reset, given the new level and set up again
    /// on the matrix it had.
    fn more_fill(&mut self) -> Result<(), PetscError> {
        self.fill_levels += 1;
        for ksp in self.factored_solvers()? {
            let (mut a, mut pmat): (p::Mat, p::Mat) = (null_mut(), null_mut());
            call!(KSPGetOperators(ksp, &mut a, &mut pmat))?;
            // hold the matrix while the preconditioner that refers to it is reset
            call!(PetscObjectReference(pmat as p::PetscObject))?;
            let mut pc: p::PC = null_mut();
            let set = call!(KSPGetPC(ksp, &mut pc))
                .and_then(|_| call!(PCReset(pc)))
                .and_then(|_| call!(PCFactorSetLevels(pc, self.fill_levels)))
                .and_then(|_| call!(KSPSetOperators(ksp, pmat, pmat)));
            // SAFETY: the reference taken above, given back once.
            unsafe {
                p::MatDestroy(&mut pmat);
            }
            set?;
            call!(KSPSetUp(ksp))?;
        }
        self.factorizations += 1;
        Ok(())
    }

    /// The solvers whose preconditioner factors a matrix: the subdomains' with additive
    /// Schwarz (after set-up), else this one.
    fn factored_solvers(&self) -> Result<Vec<p::KSP>, PetscError> {
        let mut pc: p::PC = null_mut();
        call!(KSPGetPC(self.ksp, &mut pc))?;
        let mut kind: p::PCType = std::ptr::null();
        call!(PCGetType(pc, &mut kind))?;
        // SAFETY: PETSc returns its own NUL-terminated type name.
        if unsafe { CStr::from_ptr(kind) }.to_bytes_with_nul() != p::PCASM.as_slice() {
            return Ok(vec![self.ksp]);
        }
        let (mut n, mut first, mut sub) = (0, 0, null_mut());
        call!(PCASMGetSubKSP(pc, &mut n, &mut first, &mut sub))?;
        let n: usize = convert(n, "Schwarz subdomains")?;
        // SAFETY: PETSc returns an array of n sub-solvers it owns.
        Ok(unsafe { std::slice::from_raw_parts(sub, n) }.to_vec())
    }

    /// Rows of the matrices this rank's preconditioner holds, once set up: of its overlapping
    /// subdomains with additive Schwarz, else this rank's rows of the factored matrix (all of
    /// them for the canonical solver's gathered copy). `None` before the first set-up.
    pub(crate) fn held_rows(&self) -> Result<Option<u64>, PetscError> {
        if !self.set_up {
            return Ok(None);
        }
        let mut rows = 0u64;
        for ksp in self.factored_solvers()? {
            let (mut a, mut pmat) = (null_mut(), null_mut());
            call!(KSPGetOperators(ksp, &mut a, &mut pmat))?;
            let (mut m, mut n) = (0, 0);
            call!(MatGetLocalSize(pmat, &mut m, &mut n))?;
            rows += convert::<_, u64>(m, "matrix rows")?;
        }
        Ok(Some(rows))
    }
}

/// The size of communicator `comm`.
fn comm_size(comm: mpi::ffi::MPI_Comm) -> Result<i32, PetscError> {
    let mut size = 0;
    // SAFETY: a valid communicator and out-pointer.
    let rc = unsafe { mpi::ffi::MPI_Comm_size(comm, &mut size) };
    chk(rc, "MPI_Comm_size")?;
    Ok(size)
}

/// Whether `pc`, after the options, factors completely, so that its factors may serve later
/// matrices: a complete LU (`PCLU`), or additive Schwarz whose subdomains are factored
/// completely (`-<prefix>pc_type asm -<prefix>sub_pc_type lu`), each rank holding the factors
/// of its overlapping subdomain only.
fn is_complete_lu(pc: p::PC) -> Result<bool, PetscError> {
    let mut kind: p::PCType = std::ptr::null();
    call!(PCGetType(pc, &mut kind))?;
    // SAFETY: PETSc returns its own NUL-terminated type name.
    let kind = unsafe { std::ffi::CStr::from_ptr(kind) }.to_bytes_with_nul();
    Ok(kind == p::PCLU || (kind == p::PCASM && subdomain_pc_type(pc)? == b"lu"))
}

/// The subdomain preconditioner `-<prefix>sub_pc_type` of a Schwarz `pc` as given in the
/// options (empty when not given: PETSc's default, ILU(0)).
fn subdomain_pc_type(pc: p::PC) -> Result<Vec<u8>, PetscError> {
    let mut prefix: *const c_char = std::ptr::null();
    call!(PCGetOptionsPrefix(pc, &mut prefix))?;
    let name = CString::new("-sub_pc_type").expect("no NUL");
    let mut value = [0 as c_char; 64];
    let mut set = p::PETSC_FALSE;
    call!(PetscOptionsGetString(
        null_mut(),
        prefix,
        name.as_ptr(),
        value.as_mut_ptr(),
        value.len(),
        &mut set
    ))?;
    // SAFETY: PETSc writes a NUL-terminated string into `value` (or leaves it zeroed).
    Ok(unsafe { std::ffi::CStr::from_ptr(value.as_ptr()) }
        .to_bytes()
        .to_vec())
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
    /// The matrix in 3×3 node blocks, which the factors are of and GMRES multiplies by: with
    /// kept factors on one rank ([`DistributedLu::kept`]) and with a dynamic stage's
    /// incomplete factors (module docs).
    blocked: Option<BlockedCopy>,
}

/// The name the distributed LU's shell reports (`-ksp_view`), and by which it is recognised.
pub const DISTRIBUTED_LU_NAME: &CStr = c"distributed LU (MUMPS on all ranks)";

impl DistributedLu {
    /// The shell's state on communicator `comm`.
    /// `time_stepping`: for a dynamic stage (the module docs).
    pub fn new(
        comm: mpi::ffi::MPI_Comm,
        reuse: bool,
        time_stepping: bool,
    ) -> Result<Box<DistributedLu>, PetscError> {
        let inner = LaggedLu::new(
            comm,
            "distributed_",
            reuse,
            Some(p::MATSOLVERMUMPS),
            time_stepping,
        )?;
        let blocked = inner.incomplete && bool_option("-distributed_dynamic_blocked", true)?;
        Ok(Box::new(DistributedLu {
            inner,
            factored: false,
            blocked: match blocked {
                true => Some(BlockedCopy::new(comm_size(comm)?)),
                false => None,
            },
        }))
    }

    /// The shell's state for a matrix that is built once and kept (a linear scene's time
    /// steps, [`super::Snes::set_kept_jacobian`]): its complete factors applied alone
    /// (`preonly`), every set-up a factorization. On one rank the factors are PETSc's own
    /// LU, whose substitutions are quicker than MUMPS's there (`cfrd::performance`, "A linear
    /// scene's quake against OpenSees").
    pub fn kept(comm: mpi::ffi::MPI_Comm) -> Result<Box<DistributedLu>, PetscError> {
        let one = comm_size(comm)? == 1;
        let package = match one {
            true => p::MATSOLVERPETSC,
            false => p::MATSOLVERMUMPS,
        };
        Ok(Box::new(DistributedLu {
            inner: LaggedLu::new(comm, "distributed_", false, Some(package), false)?,
            factored: false,
            blocked: one.then(|| BlockedCopy::new(1)),
        }))
    }

    /// Makes `ksp` apply this solver (`preonly` with the shell preconditioner).
    pub(crate) fn install(&self, ksp: p::KSP) -> Result<(), PetscError> {
        pc_shell::install_preonly(ksp, self)
    }

    /// Rows of the matrices this rank's solver holds ([`LaggedLu::held_rows`]).
    pub(super) fn held_rows(&self) -> Result<Option<u64>, PetscError> {
        self.inner.held_rows()
    }

    /// Krylov iterations of the last solve (1 for a direct solve).
    pub fn last_iterations(&self) -> u32 {
        self.inner.last_iterations
    }

    /// Numeric factorizations since the last call.
    pub fn take_factorizations(&mut self) -> u64 {
        self.inner.take_factorizations()
    }

    /// The absolute tolerance of a dynamic stage's solves ([`LaggedLu::set_absolute_tolerance`]).
    pub(super) fn set_absolute_tolerance(&mut self, atol: f64) -> Result<(), PetscError> {
        self.inner.set_absolute_tolerance(atol)
    }
}

impl PcShell for DistributedLu {
    const NAME: &'static CStr = DISTRIBUTED_LU_NAME;

    /// Factors the preconditioning matrix of `pc`, or keeps the earlier factors.
    fn setup(&mut self, pc: p::PC) -> Result<(), PetscError> {
        let (mut a, mut pmat): (p::Mat, p::Mat) = (null_mut(), null_mut());
        call!(PCGetOperators(pc, &mut a, &mut pmat))?;
        if let Some(blocked) = &mut self.blocked {
            blocked.update(pmat)?;
            call!(KSPSetOperators(self.inner.ksp, blocked.mat, blocked.mat))?;
        } else if !self.factored {
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
