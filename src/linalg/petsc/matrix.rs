//! [`Matrix`], the distributed sparse matrix, and the guard of one of its rows lent by PETSc
//! ([`MatRow`]).
#![allow(unsafe_code)]

use super::error::{call, to_petsc_int, to_usize, PetscError};
use super::init::Petsc;
use super::loan::{lent_slice, Lent, Loan};
use super::vector::Vector;
use crate::linalg::ffi as p;
use std::ffi::c_char;
use std::ptr::{null, null_mut};

/// A distributed sparse matrix (MPIAIJ with block size) with exact preallocation.
pub struct Matrix {
    pub(super) raw: p::Mat,
}

impl Matrix {
    /// Square AIJ matrix with `n_local` rows on this rank, `d_nnz`/`o_nnz` nonzeros per local
    /// row in the diagonal/off-diagonal blocks. New nonzeros outside the pattern are an error.
    pub fn aij(
        petsc: &Petsc,
        n_local: usize,
        block_size: usize,
        d_nnz: &[i32],
        o_nnz: &[i32],
    ) -> Result<Matrix, PetscError> {
        let nl = to_petsc_int(n_local, "local matrix rows")?;
        let block_size = to_petsc_int(block_size, "matrix block size")?;
        let mut raw: p::Mat = null_mut();
        call!(MatCreate(petsc.comm(), &mut raw))?;
        let m = Matrix { raw };
        call!(MatSetSizes(m.raw, nl, nl, p::PETSC_DETERMINE, p::PETSC_DETERMINE))?;
        call!(MatSetType(m.raw, p::MATAIJ.as_ptr() as *const c_char))?;
        call!(MatSetBlockSize(m.raw, block_size))?;
        call!(MatSeqAIJSetPreallocation(m.raw, 0, d_nnz.as_ptr()))?;
        call!(MatMPIAIJSetPreallocation(
            m.raw,
            0,
            d_nnz.as_ptr(),
            0,
            o_nnz.as_ptr()
        ))?;
        call!(MatSetOption(
            m.raw,
            p::MAT_NEW_NONZERO_ALLOCATION_ERR,
            p::PETSC_TRUE
        ))?;
        Ok(m)
    }

    /// Sets all stored entries to zero (keeps the pattern).
    pub fn zero(&mut self) -> Result<(), PetscError> {
        call!(MatZeroEntries(self.raw))
    }

    /// Adds a dense **row-major** block `values[i*cols.len()+j]` at (`rows[i]`, `cols[j]`);
    /// negative indices are skipped.
    pub fn add_values(&mut self, rows: &[i32], cols: &[i32], values: &[f64]) -> Result<(), PetscError> {
        assert_eq!(rows.len() * cols.len(), values.len());
        let n_rows = to_petsc_int(rows.len(), "rows of a block")?;
        let n_cols = to_petsc_int(cols.len(), "columns of a block")?;
        call!(MatSetValues(
            self.raw,
            n_rows,
            rows.as_ptr(),
            n_cols,
            cols.as_ptr(),
            values.as_ptr(),
            p::ADD_VALUES
        ))
    }

    /// Final assembly (communicates off-process entries).
    pub fn assemble(&mut self) -> Result<(), PetscError> {
        call!(MatAssemblyBegin(self.raw, p::MAT_FINAL_ASSEMBLY))?;
        call!(MatAssemblyEnd(self.raw, p::MAT_FINAL_ASSEMBLY))
    }

    /// Zeroes the given global rows and columns, puts `diag` on the diagonal and adjusts `b`
    /// so that the solution takes the values of `x` at those rows (Dirichlet conditions).
    pub fn zero_rows_columns(
        &mut self,
        rows: &[i32],
        diag: f64,
        x: &Vector,
        b: &mut Vector,
    ) -> Result<(), PetscError> {
        let n = to_petsc_int(rows.len(), "rows to zero")?;
        call!(MatZeroRowsColumns(self.raw, n, rows.as_ptr(), diag, x.raw, b.raw))
    }

    /// Zeroes the given global rows and columns and puts `diag` on the diagonal (no right-hand
    /// side to adjust: the Jacobian of a residual whose constrained entries are already zero).
    pub fn zero_rows_columns_only(&mut self, rows: &[i32], diag: f64) -> Result<(), PetscError> {
        let n = to_petsc_int(rows.len(), "rows to zero")?;
        call!(MatZeroRowsColumns(
            self.raw,
            n,
            rows.as_ptr(),
            diag,
            null_mut(),
            null_mut()
        ))
    }

    /// Attaches the six rigid-body modes computed from nodal `coords` (a vector with block size
    /// 3 laid out like the DOFs) as the near-null space for algebraic multigrid.
    pub fn set_rigid_body_near_null_space(&mut self, coords: &Vector) -> Result<(), PetscError> {
        let mut ns: p::MatNullSpace = null_mut();
        call!(MatNullSpaceCreateRigidBody(coords.raw, &mut ns))?;
        let r = call!(MatSetNearNullSpace(self.raw, ns));
        // SAFETY: the matrix keeps its own reference.
        unsafe {
            p::MatNullSpaceDestroy(&mut ns);
        }
        r
    }

    /// `y ← A x`.
    pub fn mult(&self, x: &Vector, y: &mut Vector) -> Result<(), PetscError> {
        call!(MatMult(self.raw, x.raw, y.raw))
    }

    /// The raw handle, for the other safe layers of [`crate::linalg`] (SLEPc).
    pub(in crate::linalg) fn raw(&self) -> p::Mat {
        self.raw
    }

    /// A vector laid out like this matrix's columns (values not set).
    pub fn column_vector(&self) -> Result<Vector, PetscError> {
        let mut raw: p::Vec = null_mut();
        call!(MatCreateVecs(self.raw, &mut raw, null_mut()))?;
        Ok(Vector { raw })
    }

    /// The square submatrix of the global rows and columns `owned` (this rank's owned indices of
    /// the new matrix, ascending; collective). Its rows are distributed as `owned` is: the
    /// i-th owned row of the result is `owned[i]`.
    pub fn submatrix(&self, owned: &[i32]) -> Result<Matrix, PetscError> {
        let n = to_petsc_int(owned.len(), "rows of a submatrix")?;
        // SAFETY: a constant handle of the MPI library.
        let mut comm: mpi::ffi::MPI_Comm = unsafe { mpi::ffi::RSMPI_COMM_NULL };
        call!(PetscObjectGetComm(self.raw as p::PetscObject, &mut comm))?;
        let mut is: p::IS = null_mut();
        call!(ISCreateGeneral(
            comm,
            n,
            owned.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut is
        ))?;
        let mut raw: p::Mat = null_mut();
        let r = call!(MatCreateSubMatrix(
            self.raw,
            is,
            is,
            p::MAT_INITIAL_MATRIX,
            &mut raw
        ));
        // SAFETY: the index set was created above; the submatrix keeps what it needs.
        unsafe {
            p::ISDestroy(&mut is);
        }
        r?;
        Ok(Matrix { raw })
    }

    /// The symmetric part (A + Aᵀ)/2 of this matrix, a new matrix (collective).
    pub fn symmetric_part(&self) -> Result<Matrix, PetscError> {
        let mut t: p::Mat = null_mut();
        call!(MatTranspose(self.raw, p::MAT_INITIAL_MATRIX, &mut t))?;
        let sym = Matrix { raw: t };
        call!(MatAXPY(sym.raw, 1.0, self.raw, p::DIFFERENT_NONZERO_PATTERN))?;
        call!(MatScale(sym.raw, 0.5))?;
        Ok(sym)
    }

    /// A copy of this matrix, pattern and values.
    pub fn duplicate(&self) -> Result<Matrix, PetscError> {
        let mut raw: p::Mat = null_mut();
        call!(MatDuplicate(self.raw, p::MAT_COPY_VALUES, &mut raw))?;
        Ok(Matrix { raw })
    }

    /// `self ← self + a X` for a matrix `x` of the same nonzero pattern.
    pub fn axpy(&mut self, a: f64, x: &Matrix) -> Result<(), PetscError> {
        call!(MatAXPY(self.raw, a, x.raw, p::SAME_NONZERO_PATTERN))
    }
}

impl Drop for Matrix {
    fn drop(&mut self) {
        // SAFETY: created by MatCreate, destroyed once.
        unsafe {
            p::MatDestroy(&mut self.raw);
        }
    }
}

/// One owned row of an assembled matrix lent by PETSc (`MatGetRow`).
pub(super) struct MatRow {
    m: p::Mat,
    row: p::PetscInt,
    ncols: p::PetscInt,
    cols: *const p::PetscInt,
    vals: *const f64,
    /// The entries of the row (0 when PETSc gave none).
    len: usize,
}

impl MatRow {
    /// The global row `row` of `m` (owned by this rank).
    pub(super) fn get(m: p::Mat, row: p::PetscInt) -> Result<Lent<MatRow>, PetscError> {
        let (mut ncols, mut cols, mut vals): (p::PetscInt, *const p::PetscInt, *const f64) =
            (0, null(), null());
        call!(MatGetRow(m, row, &mut ncols, &mut cols, &mut vals))?;
        let mut lent = Lent::new(MatRow {
            m,
            row,
            ncols,
            cols,
            vals,
            len: 0,
        });
        if ncols > 0 {
            lent.len = to_usize(ncols, "entries of a row")?;
        }
        Ok(lent)
    }

    /// The global columns of the row's entries.
    pub(super) fn cols(&self) -> &[p::PetscInt] {
        // SAFETY: MatGetRow returned `len` column indices, valid until MatRestoreRow.
        unsafe { lent_slice(self.cols, self.len) }
    }

    /// The values of the row's entries.
    pub(super) fn values(&self) -> &[f64] {
        // SAFETY: MatGetRow returned `len` values, valid until MatRestoreRow.
        unsafe { lent_slice(self.vals, self.len) }
    }
}

impl Loan for MatRow {
    fn give_back(&mut self) -> Result<(), PetscError> {
        call!(MatRestoreRow(
            self.m,
            self.row,
            &mut self.ncols,
            &mut self.cols,
            &mut self.vals
        ))
    }
}
