//! Which rows of a Jacobian are coupled to others ([`mark_coupled_rows`]), the split both the
//! canonical LU and the reduced multigrid rest on.
#![allow(unsafe_code)]

use super::error::{call, to_petsc_int, to_usize, PetscError};
use super::matrix::MatRow;
use crate::linalg::ffi as p;

/// Marks in `flags` (laid out like the rows of `pmat`) the coupled rows: an entry > 0 where a
/// row has a nonzero entry off the diagonal in its row or its column, 0 where it is decoupled
/// (the constrained DOFs and the nodes of fill not yet placed). Each rank marks its own rows
/// and the columns of their nonzero entries (a count, so the sum is exact in any order).
/// Collective.
pub(crate) fn mark_coupled_rows(pmat: p::Mat, flags: p::Vec) -> Result<(), PetscError> {
    let (mut lo, mut hi) = (0, 0);
    call!(VecGetOwnershipRange(flags, &mut lo, &mut hi))?;
    let mut marks = vec![false; to_usize(hi - lo, "owned rows")?];
    // the place of the owned row `r` among the owned rows
    let local = |r: p::PetscInt| to_usize(r - lo, "owned row");
    let mut remote: Vec<p::PetscInt> = Vec::new();
    for r in lo..hi {
        let row = MatRow::get(pmat, r)?;
        for (&c, &v) in row.cols().iter().zip(row.values()) {
            if c != r && v != 0.0 {
                marks[local(r)?] = true;
                if (lo..hi).contains(&c) {
                    marks[local(c)?] = true;
                } else {
                    remote.push(c);
                }
            }
        }
        row.restore()?;
    }
    remote.sort_unstable();
    remote.dedup();
    remote.extend((lo..hi).zip(&marks).filter(|&(_, &m)| m).map(|(r, _)| r));
    call!(VecSet(flags, 0.0))?;
    let ones = vec![1.0; remote.len()];
    let n = to_petsc_int(remote.len(), "marked rows")?;
    call!(VecSetValues(
        flags,
        n,
        remote.as_ptr(),
        ones.as_ptr(),
        p::ADD_VALUES
    ))?;
    call!(VecAssemblyBegin(flags))?;
    call!(VecAssemblyEnd(flags))?;
    Ok(())
}
