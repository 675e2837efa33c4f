//! A copy of a matrix in 3×3 node blocks (PETSc's `BAIJ` formats), for the solvers whose
//! products, factorizations and substitutions are quicker on blocks: the kept factors of a
//! linear scene on one rank, and the incomplete factors of a dynamic stage
//! (`lagged_lu.rs`).
//!
//! The first copy is made by `MatConvert`. Later copies of a matrix of the same pattern (a
//! stage's Jacobians) write the values block row by block row (`MatSetValuesBlocked`):
//! `MatConvert` with `MAT_REUSE_MATRIX` inserts them one scalar at a time, which took a
//! sixth of a time step of the medium seed quake on 2 ranks.
#![allow(unsafe_code)]

use super::error::{call, convert, PetscError};
use crate::linalg::ffi as p;
use std::ffi::c_char;
use std::ptr::null_mut;

/// The block size: the three displacement DOFs of a node.
const BLOCK: usize = 3;

/// A matrix's copy in node blocks (null until the first [`BlockedCopy::update`]).
pub(crate) struct BlockedCopy {
    /// The copy (`MATSEQBAIJ` on one rank, `MATMPIBAIJ` on several).
    pub(crate) mat: p::Mat,
    /// The copy is distributed over several ranks.
    distributed: bool,
    /// Values of one block row, row by row (reused between rows).
    values: Vec<f64>,
    /// Block columns of one block row.
    columns: Vec<i32>,
}

impl BlockedCopy {
    /// An empty copy for a matrix on `ranks` ranks.
    pub(crate) fn new(ranks: i32) -> BlockedCopy {
        BlockedCopy {
            mat: null_mut(),
            distributed: ranks > 1,
            values: Vec::new(),
            columns: Vec::new(),
        }
    }

    /// Makes the copy that of `from` (the same pattern as at the first call, whose rows hold
    /// whole node blocks).
    pub(crate) fn update(&mut self, from: p::Mat) -> Result<(), PetscError> {
        if self.mat.is_null() {
            return call!(MatConvert(
                from,
                self.kind(),
                p::MAT_INITIAL_MATRIX,
                &mut self.mat
            ));
        }
        let (mut lo, mut hi) = (0, 0);
        call!(MatGetOwnershipRange(from, &mut lo, &mut hi))?;
        for first in (lo..hi).step_by(BLOCK) {
            if !self.copy_block_row(from, first)? {
                // a row that is not made of whole blocks: PETSc's own conversion
                return call!(MatConvert(from, self.kind(), p::MAT_REUSE_MATRIX, &mut self.mat));
            }
        }
        call!(MatAssemblyBegin(self.mat, p::MAT_FINAL_ASSEMBLY))?;
        call!(MatAssemblyEnd(self.mat, p::MAT_FINAL_ASSEMBLY))
    }

    /// PETSc's name of the copy's type.
    fn kind(&self) -> *const c_char {
        let kind = match self.distributed {
            true => p::MATMPIBAIJ.as_slice(),
            false => p::MATSEQBAIJ.as_slice(),
        };
        kind.as_ptr() as *const c_char
    }

    /// Copies the block row of `from` whose first scalar row is `first`: its three rows,
    /// one after the other, are the row-oriented values of the block row. `Ok(false)`, with
    /// nothing written, when a row's columns are not whole blocks.
    fn copy_block_row(&mut self, from: p::Mat, first: i32) -> Result<bool, PetscError> {
        self.values.clear();
        self.columns.clear();
        for row in first..first + BLOCK as i32 {
            let (mut n, mut cols, mut vals) = (0, std::ptr::null(), std::ptr::null());
            call!(MatGetRow(from, row, &mut n, &mut cols, &mut vals))?;
            let len: usize = convert(n, "row length")?;
            // SAFETY: MatGetRow hands out `n` columns and values until MatRestoreRow.
            let (c, v) = unsafe {
                (
                    std::slice::from_raw_parts(cols, len),
                    std::slice::from_raw_parts(vals, len),
                )
            };
            if row == first {
                self.columns
                    .extend(c.iter().step_by(BLOCK).map(|&j| j / BLOCK as i32));
            }
            let whole = len == BLOCK * self.columns.len()
                && c.chunks(BLOCK)
                    .zip(&self.columns)
                    .all(|(js, &b)| js.iter().zip(0..).all(|(&j, k)| j == BLOCK as i32 * b + k));
            self.values.extend_from_slice(v);
            call!(MatRestoreRow(from, row, &mut n, &mut cols, &mut vals))?;
            if !whole {
                return Ok(false);
            }
        }
        let (block_row, n_blocks) = (first / BLOCK as i32, convert(self.columns.len(), "blocks")?);
        call!(MatSetValuesBlocked(
            self.mat,
            1,
            &block_row,
            n_blocks,
            self.columns.as_ptr(),
            self.values.as_ptr(),
            p::INSERT_VALUES
        ))?;
        Ok(true)
    }
}

impl Drop for BlockedCopy {
    fn drop(&mut self) {
        // SAFETY: made by MatConvert (or null, which MatDestroy accepts), destroyed once; a
        // solver that refers to it keeps its own reference.
        unsafe {
            p::MatDestroy(&mut self.mat);
        }
    }
}
