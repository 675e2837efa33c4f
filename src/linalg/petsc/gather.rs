//! [`Gather`]: selected global entries of a distributed vector into a local sequential vector.
#![allow(unsafe_code)]

use super::error::{call, to_petsc_int, PetscError};
use super::vector::Vector;
use crate::linalg::ffi as p;
use std::ptr::null_mut;

/// Gathers selected global entries of a distributed vector into a local sequential vector.
pub struct Gather {
    ctx: p::VecScatter,
    local: Vector,
}

impl Gather {
    /// A gather of the global indices `from` of vectors laid out like `like`.
    pub fn new(like: &Vector, from: &[i32]) -> Result<Gather, PetscError> {
        let local = Vector::seq(from.len())?;
        let n = to_petsc_int(from.len(), "gathered entries")?;
        let mut is: p::IS = null_mut();
        call!(ISCreateGeneral(
            mpi::ffi::RSMPI_COMM_SELF,
            n,
            from.as_ptr(),
            p::PETSC_COPY_VALUES,
            &mut is
        ))?;
        let mut ctx: p::VecScatter = null_mut();
        let r = call!(VecScatterCreate(like.raw, is, local.raw, null_mut(), &mut ctx));
        // SAFETY: the index set was created above and is no longer needed.
        unsafe {
            p::ISDestroy(&mut is);
        }
        r?;
        Ok(Gather { ctx, local })
    }

    /// Gathers the entries of `x` and returns them in the order of `from`.
    pub fn gather<'a>(&'a mut self, x: &Vector) -> Result<&'a Vector, PetscError> {
        let (ctx, x, y) = (self.ctx, x.raw, self.local.raw);
        call!(VecScatterBegin(ctx, x, y, p::INSERT_VALUES, p::SCATTER_FORWARD))?;
        call!(VecScatterEnd(ctx, x, y, p::INSERT_VALUES, p::SCATTER_FORWARD))?;
        Ok(&self.local)
    }

    /// The entries of the last gather, in the order of `from`.
    pub fn last(&self) -> &Vector {
        &self.local
    }
}

impl Drop for Gather {
    fn drop(&mut self) {
        // SAFETY: created by VecScatterCreate, destroyed once.
        unsafe {
            p::VecScatterDestroy(&mut self.ctx);
        }
    }
}
