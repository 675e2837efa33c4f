//! The linear solver of the Newton corrections: the scene's choice ([`LinearMethod`]) and
//! the solver built from it on each SNES ([`LinearSolver`]): cfrd's Krylov defaults, or one of
//! the preconditioner shells (canonical LU, distributed LU, reduced multigrid) with their
//! states and counts.
#![allow(unsafe_code)]

use super::canonical_lu::CanonicalLu;
use super::error::{call, to_petsc_int, PetscError};
use super::lagged_lu::DistributedLu;
use super::options::default_option;
use super::pc_shell::{self, PcShell};
use super::reduced_amg::ReducedAmg;
use crate::linalg::ffi as p;
use std::ffi::c_char;
use std::ptr::null_mut;

/// The linear solver of the Newton corrections (the scene's `solver.linear_solver`).
#[derive(Debug, Clone)]
pub enum LinearMethod {
    /// cfrd's Krylov defaults (see `configure_ksp`): CG or GMRES with GAMG.
    Krylov,
    /// The same Krylov method preconditioned on the coupled rows only: LU of the structure,
    /// GAMG on the fill ([`ReducedAmg`]).
    ReducedAmg {
        /// The owned DOFs of the stiff structure (slab, interfaces, joints), increasing: the
        /// split factored apart from the fill.
        structure: Vec<i32>,
    },
    /// The canonical direct solver ([`CanonicalLu`]): results independent of the rank count.
    Canonical(CanonicalSettings),
    /// MUMPS's LU on the distributed matrix, factored by all ranks together
    /// ([`DistributedLu`]): each rank holds its share of the factors, so memory and work are
    /// split; results agree between rank counts, and between runs, to the factorization's
    /// rounding only.
    DistributedLu {
        /// Keep the factors of an earlier Jacobian as the preconditioner of GMRES while it
        /// converges quickly (`solver.reuse_factorization`); `false` factors every Jacobian.
        reuse_factorization: bool,
    },
}

/// Settings of the canonical direct solver ([`CanonicalLu`]).
#[derive(Debug, Clone)]
pub struct CanonicalSettings {
    /// The PETSc index of every DOF in the mesh's own order.
    pub dofs: Vec<i32>,
    /// Keep the factors of an earlier Jacobian as the preconditioner of GMRES while it converges
    /// quickly (`solver.reuse_factorization`); `false` factors every Jacobian.
    pub reuse_factorization: bool,
}

/// cfrd's Krylov defaults on `ksp`: CG + GAMG for a symmetric operator, GMRES(200) with right
/// preconditioning + GAMG otherwise; relative tolerance `rtol` on the unpreconditioned residual,
/// at most `max_it` iterations; PETSc options (`-ksp_type`, `-pc_type`, ...) override them.
///
/// For a non-symmetric operator the multigrid levels are smoothed by Richardson + SOR instead of
/// GAMG's default Chebyshev + Jacobi: Chebyshev needs a real spectrum and eigenvalue estimates
/// that stay valid as the tangent changes; with the non-associated rockfill tangent it made the
/// preconditioner so far from a fixed linear operator that right-preconditioned GMRES reported
/// convergence (rtol 1e-10) on a wrong Newton correction. Measured on a GP column under gravity
/// and a 10 MPa surcharge (the scene of `tests/step_control.rs` with 10 MPa), relative residual
/// after the first Newton iteration of the second load step: 2.2e-1 with Chebyshev (2.4e-1 even
/// with `-ksp_rtol 1e-14`), 6.34e-2 with Richardson + SOR, 6.34e-2 with LU. It is the likely cause
/// of the GMRES breakdowns (PETSc reason −5) seen earlier on staged dams.
fn configure_ksp(ksp: p::KSP, rtol: f64, max_it: u32, symmetric: bool) -> Result<(), PetscError> {
    if symmetric {
        call!(KSPSetType(ksp, p::KSPCG.as_ptr() as *const c_char))?;
    } else {
        default_option("-mg_levels_ksp_type", "richardson")?;
        default_option("-mg_levels_pc_type", "sor")?;
        call!(KSPSetType(ksp, p::KSPGMRES.as_ptr() as *const c_char))?;
        call!(KSPGMRESSetRestart(ksp, 200))?;
        // GMRES cannot use the unpreconditioned norm with left preconditioning
        call!(KSPSetPCSide(ksp, p::PC_RIGHT))?;
    }
    let mut pc: p::PC = null_mut();
    call!(KSPGetPC(ksp, &mut pc))?;
    call!(PCSetType(pc, p::PCGAMG.as_ptr() as *const c_char))?;
    let max_it = to_petsc_int(max_it, "Krylov iteration limit")?;
    call!(KSPSetTolerances(ksp, rtol, 1e-300, 1e30, max_it))?;
    call!(KSPSetNormType(ksp, p::KSP_NORM_UNPRECONDITIONED))
}

/// The reduced multigrid's inexact-Newton defaults (`cfrd::linalg::petsc::reduced_amg`, "Inexact
/// Newton"): PETSc's Eisenstat–Walker forcing terms, none looser than 0.03.
const EISENSTAT_WALKER: [(&str, &str); 3] = [
    ("-snes_ksp_ew", "true"),
    ("-snes_ksp_ew_rtol0", "0.03"),
    ("-snes_ksp_ew_rtolmax", "0.03"),
];

/// The linear solver of a SNES built from a [`LinearMethod`]: the states of its preconditioner
/// shell (the shell's context, so dropped only after the SNES that refers to it) and the
/// counts of the states already dropped.
pub(super) struct LinearSolver {
    /// The scene's choice.
    method: LinearMethod,
    /// The canonical direct solver's state (the PC shell's context).
    canonical_lu: Option<Box<CanonicalLu>>,
    /// The distributed direct solver's state (the PC shell's context).
    distributed_lu: Option<Box<DistributedLu>>,
    /// The reduced multigrid's state (the PC shell's context).
    reduced_amg: Option<Box<ReducedAmg>>,
    /// Factorizations of canonical solvers already dropped, not yet taken.
    factorizations: u64,
    /// Multigrid set-ups of reduced multigrids already dropped, not yet taken.
    multigrid_builds: u64,
}

impl LinearSolver {
    /// The solver of `method`, its shell states not yet made ([`LinearSolver::create`]).
    pub(super) fn new(method: LinearMethod) -> LinearSolver {
        LinearSolver {
            method,
            canonical_lu: None,
            distributed_lu: None,
            reduced_amg: None,
            factorizations: 0,
            multigrid_builds: 0,
        }
    }

    /// Makes the shell state of the method on communicator `comm` (for a dynamic stage with
    /// `time_stepping`), before the SNES reads its options; with the reduced multigrid, its
    /// inexact-Newton defaults. With `kept` (the Jacobian is built once and kept,
    /// [`super::Snes::set_kept_jacobian`]) a direct solver applies the complete factors of the
    /// kept matrix alone, with no Krylov iteration around them ([`super::lagged_lu`]).
    pub(super) fn create(
        &mut self,
        comm: mpi::ffi::MPI_Comm,
        symmetric: bool,
        (time_stepping, kept): (bool, bool),
    ) -> Result<(), PetscError> {
        if let LinearMethod::Canonical(canonical) = &self.method {
            let reuse = canonical.reuse_factorization && !kept;
            self.canonical_lu = Some(CanonicalLu::new(canonical.dofs.clone(), reuse, time_stepping)?);
        }
        if let LinearMethod::DistributedLu { reuse_factorization } = &self.method {
            self.distributed_lu = Some(match kept {
                true => DistributedLu::kept(comm)?,
                false => DistributedLu::new(comm, *reuse_factorization, time_stepping)?,
            });
        }
        if let LinearMethod::ReducedAmg { structure } = &self.method {
            self.reduced_amg = Some(ReducedAmg::new(comm, symmetric, structure.clone())?);
            // inexact Newton (Eisenstat–Walker, reduced_amg module docs): a correction is
            // solved to 0.03, or as much more tightly as Newton converges fast
            for (name, value) in EISENSTAT_WALKER {
                default_option(name, value)?;
            }
        }
        Ok(())
    }

    /// Makes `ksp` (the SNES's) solve with this solver: a direct solver's shell, or cfrd's
    /// Krylov defaults (relative tolerance `rtol`, at most `max_it` iterations), the reduced
    /// multigrid's shell as their preconditioner.
    pub(super) fn install(
        &self,
        ksp: p::KSP,
        rtol: f64,
        max_it: u32,
        symmetric: bool,
    ) -> Result<(), PetscError> {
        match (&self.canonical_lu, &self.distributed_lu) {
            (Some(lu), _) => lu.install(ksp)?,
            (None, Some(lu)) => lu.install(ksp)?,
            (None, None) => configure_ksp(ksp, rtol, max_it, symmetric)?,
        }
        if let Some(amg) = &self.reduced_amg {
            let mut pc: p::PC = null_mut();
            call!(KSPGetPC(ksp, &mut pc))?;
            amg.install(pc)?;
        }
        Ok(())
    }

    /// Changes the method of the next [`LinearSolver::create`] (after [`LinearSolver::release`]).
    pub(super) fn set_method(&mut self, method: LinearMethod) {
        self.method = method;
    }

    /// Drops the shell states, keeping their counts; for after the SNES that refers to them
    /// was destroyed.
    pub(super) fn release(&mut self) {
        self.factorizations = self.take_factorizations();
        self.multigrid_builds = self.take_multigrid_builds();
        self.canonical_lu = None;
        self.distributed_lu = None;
        self.reduced_amg = None;
    }

    /// Set-ups of the reduced multigrid's multigrid since the last call (0 with other solvers).
    pub(super) fn take_multigrid_builds(&mut self) -> u64 {
        let reduced = self
            .reduced_amg
            .as_mut()
            .map_or(0, |amg| amg.take_multigrid_builds());
        std::mem::take(&mut self.multigrid_builds) + reduced
    }

    /// Numeric factorizations of the direct solvers since the last call (0 with the Krylov
    /// defaults; the reduced multigrid's: of its structure).
    pub(super) fn take_factorizations(&mut self) -> u64 {
        let canonical = self
            .canonical_lu
            .as_mut()
            .map_or(0, |lu| lu.take_factorizations());
        let distributed = self
            .distributed_lu
            .as_mut()
            .map_or(0, |lu| lu.take_factorizations());
        let reduced = self.reduced_amg.as_mut().map_or(0, |amg| amg.take_builds());
        std::mem::take(&mut self.factorizations) + canonical + distributed + reduced
    }
}

impl LinearSolver {
    /// Rows of the matrices this rank's direct solver holds once set up (its factors' or its
    /// Schwarz subdomains'); `None` for the other solvers and before the first set-up.
    pub(super) fn held_rows(&self) -> Result<Option<u64>, PetscError> {
        match (&self.canonical_lu, &self.distributed_lu) {
            (Some(lu), _) => lu.held_rows(),
            (None, Some(lu)) => lu.held_rows(),
            (None, None) => Ok(None),
        }
    }
}

/// The state of a direct solver's shell, told apart by the name the shell reports.
enum DirectShell<'a> {
    /// [`DistributedLu`]'s.
    Distributed(&'a mut DistributedLu),
    /// [`CanonicalLu`]'s.
    Canonical(&'a mut CanonicalLu),
}

/// The direct solver whose shell `pc` is; `None` for the reduced multigrid's shell.
///
/// # Safety
/// `pc` must be a shell installed by [`LinearSolver::install`], whose context is alive.
unsafe fn direct_shell<'a>(pc: p::PC) -> Option<DirectShell<'a>> {
    // SAFETY: a shell (caller's contract)
    let name = unsafe { pc_shell::name(pc) }?;
    if name == ReducedAmg::NAME {
        None
    } else if name == DistributedLu::NAME {
        // SAFETY: the distributed LU's shell (its name), caller's contract.
        let lu = unsafe { pc_shell::context::<DistributedLu>(pc) }.ok()?;
        Some(DirectShell::Distributed(lu))
    } else {
        // SAFETY: the only other shell cfrd installs is the canonical solver.
        let lu = unsafe { pc_shell::context::<CanonicalLu>(pc) }.ok()?;
        Some(DirectShell::Canonical(lu))
    }
}

/// Krylov iterations of the last solve of one of cfrd's preconditioner shells: a direct
/// solver's inner iterations; `None` for the reduced multigrid, an ordinary preconditioner of
/// the outer Krylov solve, whose iterations count.
///
/// # Safety
/// `pc` must be a shell installed by [`LinearSolver::install`], whose context is alive.
pub(super) unsafe fn shell_iterations(pc: p::PC) -> Option<u32> {
    // SAFETY: the caller's contract.
    match unsafe { direct_shell(pc) }? {
        DirectShell::Distributed(lu) => Some(lu.last_iterations()),
        DirectShell::Canonical(lu) => Some(lu.last_iterations()),
    }
}

/// Gives the direct solvers' inner GMRES of a dynamic stage the absolute tolerance `atol`
/// ([`super::SnesProblem::correction_tolerance`]); other preconditioners are left as they are.
///
/// # Safety
/// `pc` must be a live `PC`; if a shell, one installed by [`LinearSolver::install`], whose
/// context is alive.
pub(super) unsafe fn set_shell_absolute_tolerance(pc: p::PC, atol: f64) -> Result<(), PetscError> {
    let mut kind: p::PCType = std::ptr::null();
    call!(PCGetType(pc, &mut kind))?;
    // SAFETY: PETSc returns its own NUL-terminated type name (null before a type is set).
    if kind.is_null() || unsafe { std::ffi::CStr::from_ptr(kind) }.to_bytes_with_nul() != p::PCSHELL {
        return Ok(());
    }
    // SAFETY: a shell (checked above), caller's contract.
    match unsafe { direct_shell(pc) } {
        Some(DirectShell::Distributed(lu)) => lu.set_absolute_tolerance(atol),
        Some(DirectShell::Canonical(lu)) => lu.set_absolute_tolerance(atol),
        None => Ok(()),
    }
}
