//! A small safe layer over SLEPc's EPS: the lowest eigenpairs of a generalized symmetric
//! problem A·x = λ·B·x (B positive semi-definite), the modal analysis
//! (A = K₀, B = M, λ = ω²).
//!
//! SLEPc is initialized with PETSc by [`super::petsc::Petsc::initialize`] and finalized by its
//! guard; an [`Eps`] must be dropped before that guard, like every PETSc object. The spectral
//! transformation is shift-and-invert about σ = 0 with a direct factorization of A inside it
//! (`preonly` + LU by MUMPS, which runs on any number of ranks), so the eigenvalues nearest
//! zero converge first. Options with the prefix given to [`Eps::lowest_generalized`] (e.g.
//! `-modal_eps_tol 1e-12`, `-modal_st_pc_factor_mat_solver_type superlu_dist`) override these
//! settings.
#![allow(unsafe_code)]

use super::ffi as p;
use super::petsc::error::{to_petsc_int, to_usize};
use super::petsc::{call, Matrix, PetscError, Vector};
use std::ffi::{c_char, CString};
use std::ptr::null_mut;

/// Converged relative residual ‖A·x − λ·B·x‖/(|λ|·‖x‖) of each eigenpair (SLEPc's default
/// convergence test), far below the 0.1 % to which the modal verification compares frequencies.
pub const EIGEN_TOLERANCE: f64 = 1e-10;

/// One eigenpair: the eigenvalue λ and the eigenvector's owned entries (B-normalized:
/// xᵀ·B·x = 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Eigenpair {
    /// λ (ω² in rad²/s² for the modal problem).
    pub value: f64,
    /// The eigenvector's entries owned by this rank, in the matrices' row order.
    pub vector: Vec<f64>,
}

/// A SLEPc eigensolver (EPS), destroyed on drop.
pub struct Eps {
    raw: p::EPS,
}

impl Drop for Eps {
    fn drop(&mut self) {
        // SAFETY: created by EPSCreate, destroyed once.
        unsafe {
            p::EPSDestroy(&mut self.raw);
        }
    }
}

impl Eps {
    /// The `count` eigenpairs of A·x = λ·B·x with the smallest |λ| (ascending), for symmetric
    /// `a` (nonsingular) and symmetric positive semi-definite `b` of the same layout
    /// (collective). Fails if fewer than `count` pairs converge; `prefix` is the options
    /// prefix of the solver (e.g. `modal_`).
    pub fn lowest_generalized(
        a: &Matrix,
        b: &Matrix,
        count: usize,
        prefix: &str,
    ) -> Result<Vec<Eigenpair>, PetscError> {
        let eps = Eps::shift_invert(a, b, count, prefix)?;
        call!(EPSSolve(eps.raw))?;
        let mut converged: p::PetscInt = 0;
        call!(EPSGetConverged(eps.raw, &mut converged))?;
        if to_usize(converged.max(0), "converged eigenpairs")? < count {
            return Err(PetscError {
                code: -1,
                call: "EPSSolve",
                message: format!("{converged} of {count} eigenpairs converged"),
            });
        }
        (0..count).map(|i| eps.pair(a, i)).collect()
    }

    /// The solver for the generalized Hermitian problem about the target 0 by shift-and-invert
    /// with a direct solve, then the options database under `prefix`.
    fn shift_invert(a: &Matrix, b: &Matrix, count: usize, prefix: &str) -> Result<Eps, PetscError> {
        let mut comm: mpi::ffi::MPI_Comm = unsafe { mpi::ffi::RSMPI_COMM_NULL };
        call!(PetscObjectGetComm(a.raw() as p::PetscObject, &mut comm))?;
        let mut raw: p::EPS = null_mut();
        call!(EPSCreate(comm, &mut raw))?;
        let eps = Eps { raw };
        call!(EPSSetOperators(eps.raw, a.raw(), b.raw()))?;
        call!(EPSSetProblemType(eps.raw, p::EPS_GHEP))?;
        let count = to_petsc_int(count, "eigenpairs")?;
        call!(EPSSetDimensions(
            eps.raw,
            count,
            p::PETSC_DEFAULT,
            p::PETSC_DEFAULT
        ))?;
        call!(EPSSetTarget(eps.raw, 0.0))?;
        call!(EPSSetWhichEigenpairs(eps.raw, p::EPS_TARGET_MAGNITUDE))?;
        call!(EPSSetTolerances(eps.raw, EIGEN_TOLERANCE, p::PETSC_DEFAULT))?;
        eps.direct_shift_invert()?;
        let prefix = CString::new(prefix).map_err(|_| PetscError {
            code: -1,
            call: "EPSSetOptionsPrefix",
            message: "prefix contains a NUL byte".into(),
        })?;
        call!(EPSSetOptionsPrefix(eps.raw, prefix.as_ptr()))?;
        call!(EPSSetFromOptions(eps.raw))?;
        Ok(eps)
    }

    /// Shift-and-invert with `preonly` + LU (MUMPS) as the inner solve.
    fn direct_shift_invert(&self) -> Result<(), PetscError> {
        let name = |s: &[u8]| s.as_ptr() as *const c_char;
        let mut st: p::ST = null_mut();
        call!(EPSGetST(self.raw, &mut st))?;
        call!(STSetType(st, name(p::STSINVERT)))?;
        let mut ksp: p::KSP = null_mut();
        call!(STGetKSP(st, &mut ksp))?;
        call!(KSPSetType(ksp, name(p::KSPPREONLY)))?;
        let mut pc: p::PC = null_mut();
        call!(KSPGetPC(ksp, &mut pc))?;
        call!(PCSetType(pc, name(p::PCLU)))?;
        call!(PCFactorSetMatSolverType(pc, name(p::MATSOLVERMUMPS)))
    }

    /// The converged pair `i` (vector laid out like `a`'s columns).
    fn pair(&self, a: &Matrix, i: usize) -> Result<Eigenpair, PetscError> {
        let x: Vector = a.column_vector()?;
        let i = to_petsc_int(i, "eigenpair")?;
        let (mut re, mut im) = (0.0, 0.0);
        call!(EPSGetEigenpair(
            self.raw,
            i,
            &mut re,
            &mut im,
            x.raw(),
            null_mut()
        ))?;
        Ok(Eigenpair {
            value: re,
            vector: x.read(|s| s.to_vec())?,
        })
    }
}
