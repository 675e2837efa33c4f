//! The compressed rows of an assembled AIJ [`Matrix`]: where its owned rows keep their entries
//! ([`CsrLayout`]) and their values overwritten in place, through the guards of the arrays
//! PETSc lends for it (`MatGetRowIJ`, `MatSeqAIJGetArray`).
#![allow(unsafe_code)]

use super::error::{call, chk, count_from_double, to_usize, PetscError};
use super::loan::{lent_slice_mut, Lent, Loan};
use super::matrix::Matrix;
use crate::linalg::ffi as p;
use std::ffi::c_char;
use std::ptr::{null, null_mut};

/// Where the owned rows of an assembled AIJ matrix keep their entries ([`Matrix::csr_layout`]):
/// the diagonal block (the columns this rank owns) and the off-diagonal block, each in
/// compressed rows with increasing global columns.
#[derive(Debug, Clone, Default)]
pub struct CsrLayout {
    /// The diagonal block.
    pub diag: CsrPart,
    /// The off-diagonal block (no entries on one rank).
    pub off: CsrPart,
}

/// One block of a [`CsrLayout`]: entry `k` of local row `r` (`rows[r] <= k < rows[r + 1]`)
/// has global column `cols[k]`.
#[derive(Debug, Clone, Default)]
pub struct CsrPart {
    /// Row starts, one more than the owned rows.
    pub rows: Vec<i32>,
    /// Global column of every entry.
    pub cols: Vec<i32>,
}

impl CsrPart {
    /// The rows of the sequential AIJ matrix `m`, its local columns mapped by `global`.
    fn of(m: p::Mat, global: impl Fn(i32) -> i32) -> Result<CsrPart, PetscError> {
        let ij = RowIj::get(m)?;
        let n = to_usize(ij.n, "compressed rows")?;
        // SAFETY: PETSc returned n + 1 row starts, valid until MatRestoreRowIJ.
        let rows = unsafe { std::slice::from_raw_parts(ij.ia, n + 1) }.to_vec();
        let nnz = to_usize(rows[n], "entries of compressed rows")?;
        let cols = match nnz {
            0 => Vec::new(),
            // SAFETY: PETSc returned rows[n] column indices, valid until MatRestoreRowIJ.
            _ => unsafe { std::slice::from_raw_parts(ij.ja, nnz) }
                .iter()
                .map(|&j| global(j))
                .collect(),
        };
        ij.restore()?;
        Ok(CsrPart { rows, cols })
    }
}

/// The compressed rows of a sequential AIJ matrix lent by PETSc (`MatGetRowIJ`, unshifted and
/// as stored).
struct RowIj {
    m: p::Mat,
    /// Rows.
    n: p::PetscInt,
    /// Row starts, `n + 1`.
    ia: *const p::PetscInt,
    /// Column indices, `ia[n]`.
    ja: *const p::PetscInt,
    done: p::PetscBool,
}

impl RowIj {
    /// The compressed rows of `m`; an error where the matrix gives none.
    fn get(m: p::Mat) -> Result<Lent<RowIj>, PetscError> {
        let mut ij = RowIj {
            m,
            n: 0,
            ia: null(),
            ja: null(),
            done: p::PETSC_FALSE,
        };
        ij.call(p::MatGetRowIJ, "MatGetRowIJ")?;
        if ij.done != p::PETSC_TRUE {
            return Err(PetscError {
                code: 0,
                call: "MatGetRowIJ",
                message: "the matrix gives no compressed rows".into(),
            });
        }
        Ok(Lent::new(ij))
    }

    /// Calls `f` (`MatGetRowIJ` or `MatRestoreRowIJ`, which take the same arguments) on the
    /// matrix for its compressed rows, unshifted and as stored.
    fn call(&mut self, f: RowIjFn, name: &'static str) -> Result<(), PetscError> {
        let no = p::PETSC_FALSE;
        let (n, ia, ja, done) = (&mut self.n, &mut self.ia, &mut self.ja, &mut self.done);
        // SAFETY: `m` is a valid sequential AIJ matrix and PETSc writes only the four outputs.
        chk(unsafe { f(self.m, 0, no, no, n, ia, ja, done) }, name)
    }
}

impl Loan for RowIj {
    fn give_back(&mut self) -> Result<(), PetscError> {
        self.call(p::MatRestoreRowIJ, "MatRestoreRowIJ")
    }
}

/// `MatGetRowIJ` and `MatRestoreRowIJ`, which take the same arguments.
type RowIjFn = unsafe extern "C" fn(
    p::Mat,
    p::PetscInt,
    p::PetscBool,
    p::PetscBool,
    *mut p::PetscInt,
    *mut *const p::PetscInt,
    *mut *const p::PetscInt,
    *mut p::PetscBool,
) -> p::PetscErrorCode;

/// The values of a sequential AIJ matrix lent by PETSc (`MatSeqAIJGetArray`).
struct SeqValues {
    m: p::Mat,
    ptr: *mut f64,
    len: usize,
}

impl SeqValues {
    /// The values of `m`, its used nonzeros.
    fn get(m: p::Mat) -> Result<Lent<SeqValues>, PetscError> {
        // SAFETY: MatInfo holds only doubles, for which zero bits are a valid value.
        let mut info: p::MatInfo = unsafe { std::mem::zeroed() };
        call!(MatGetInfo(m, p::MAT_LOCAL, &mut info))?;
        let mut ptr: *mut f64 = null_mut();
        call!(MatSeqAIJGetArray(m, &mut ptr))?;
        let mut values = Lent::new(SeqValues { m, ptr, len: 0 });
        values.len = count_from_double(info.nz_used, "used nonzeros")?;
        Ok(values)
    }

    fn slice(&mut self) -> &mut [f64] {
        // SAFETY: PETSc lent `len` values (the used nonzeros) until MatSeqAIJRestoreArray.
        unsafe { lent_slice_mut(self.ptr, self.len) }
    }
}

impl Loan for SeqValues {
    fn give_back(&mut self) -> Result<(), PetscError> {
        call!(MatSeqAIJRestoreArray(self.m, &mut self.ptr))
    }
}

/// The off-diagonal block of an MPIAIJ matrix's owned rows and the global column of each of
/// its local columns.
type OffDiagonal = (p::Mat, *const p::PetscInt);

impl Matrix {
    /// The diagonal and off-diagonal blocks of the owned rows (PETSc's MPIAIJ split; on one
    /// rank the whole matrix is the diagonal block) and the global column of every local
    /// column of the off-diagonal block.
    fn owned_blocks(&self) -> Result<(p::Mat, Option<OffDiagonal>), PetscError> {
        let mut seq = p::PETSC_FALSE;
        call!(PetscObjectTypeCompare(
            self.raw as p::PetscObject,
            p::MATSEQAIJ.as_ptr() as *const c_char,
            &mut seq
        ))?;
        if seq == p::PETSC_TRUE {
            return Ok((self.raw, None));
        }
        let (mut ad, mut ao, mut colmap): (p::Mat, p::Mat, *const p::PetscInt) =
            (null_mut(), null_mut(), null());
        call!(MatMPIAIJGetSeqAIJ(self.raw, &mut ad, &mut ao, &mut colmap))?;
        Ok((ad, Some((ao, colmap))))
    }

    /// Where the entries of the owned rows are stored ([`CsrLayout`]). The pattern must be
    /// final (assembled, no new nonzeros allowed), as [`Matrix::aij`] makes it.
    pub fn csr_layout(&self) -> Result<CsrLayout, PetscError> {
        let (mut c_lo, mut c_hi) = (0, 0);
        call!(MatGetOwnershipRangeColumn(self.raw, &mut c_lo, &mut c_hi))?;
        let (ad, off) = self.owned_blocks()?;
        let diag = CsrPart::of(ad, |j| j + c_lo)?;
        let off = match off {
            None => CsrPart {
                rows: vec![0; diag.rows.len()],
                cols: Vec::new(),
            },
            Some((ao, colmap)) => {
                let n = CsrPart::of(ao, |j| j)?;
                let n_cols = match n.cols.iter().max() {
                    Some(&m) => to_usize(m, "off-diagonal column")? + 1,
                    None => 0,
                };
                // SAFETY: `colmap` maps each of the off-diagonal block's columns (all below
                // n_cols) to its global column while the matrix lives.
                let colmap = unsafe { std::slice::from_raw_parts(colmap, n_cols) };
                let cols = n
                    .cols
                    .iter()
                    .map(|&j| Ok(colmap[to_usize(j, "off-diagonal column")?]))
                    .collect::<Result<Vec<_>, PetscError>>()?;
                CsrPart { cols, rows: n.rows }
            }
        };
        Ok(CsrLayout { diag, off })
    }

    /// Overwrites the values of the owned rows: `f` gets the values of the diagonal and of the
    /// off-diagonal block in the order of [`Matrix::csr_layout`] (it sees the old values), then
    /// the matrix is assembled. For a pattern that is final and values set on owned rows only,
    /// as the element assembly does; no communication but the assembly's own. Collective.
    pub fn overwrite_values<R>(
        &mut self,
        f: impl FnOnce(&mut [f64], &mut [f64]) -> R,
    ) -> Result<R, PetscError> {
        let (ad, off) = self.owned_blocks()?;
        let mut diag = SeqValues::get(ad)?;
        let mut off = match off {
            Some((ao, _)) => Some(SeqValues::get(ao)?),
            None => None,
        };
        let r = f(diag.slice(), off.as_mut().map_or(&mut [][..], |o| o.slice()));
        diag.restore()?;
        if let Some(o) = off {
            o.restore()?;
        }
        call!(MatSetOption(self.raw, p::MAT_NO_OFF_PROC_ENTRIES, p::PETSC_TRUE))?;
        self.assemble()?;
        Ok(r)
    }
}
