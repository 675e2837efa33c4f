//! PETSc vectors: the owned [`Vector`], vectors PETSc lends to a callback, and the guards of a
//! vector's borrowed local array and of a borrowed subvector.
#![allow(unsafe_code)]

use super::error::{call, to_petsc_int, to_usize, PetscError};
use super::init::Petsc;
use super::loan::{lent_slice, lent_slice_mut, Lent, Loan};
use crate::linalg::ffi as p;
use std::ffi::c_char;
use std::mem::ManuallyDrop;
use std::ptr::{null, null_mut};

/// A PETSc vector (MPI or sequential).
pub struct Vector {
    pub(super) raw: p::Vec,
}

impl Vector {
    /// A distributed vector with `n_local` entries on this rank.
    pub fn mpi(petsc: &Petsc, n_local: usize, block_size: usize) -> Result<Vector, PetscError> {
        let n_local = to_petsc_int(n_local, "local vector size")?;
        let block_size = to_petsc_int(block_size, "vector block size")?;
        let mut raw: p::Vec = null_mut();
        call!(VecCreate(petsc.comm(), &mut raw))?;
        let v = Vector { raw };
        call!(VecSetSizes(v.raw, n_local, p::PETSC_DETERMINE))?;
        call!(VecSetBlockSize(v.raw, block_size))?;
        call!(VecSetType(v.raw, p::VECMPI.as_ptr() as *const c_char))?;
        Ok(v)
    }

    /// A sequential (rank-local) vector of length `n`.
    pub fn seq(n: usize) -> Result<Vector, PetscError> {
        let n = to_petsc_int(n, "sequential vector size")?;
        let mut raw: p::Vec = null_mut();
        call!(VecCreateSeq(mpi::ffi::RSMPI_COMM_SELF, n, &mut raw))?;
        Ok(Vector { raw })
    }

    /// A vector PETSc owns, seen as a [`Vector`] for the duration of a callback (never
    /// destroyed).
    pub(super) fn borrowed(raw: p::Vec) -> ManuallyDrop<Vector> {
        ManuallyDrop::new(Vector { raw })
    }

    /// The raw handle, for the other safe layers of [`crate::linalg`] (SLEPc).
    pub(in crate::linalg) fn raw(&self) -> p::Vec {
        self.raw
    }

    /// A new vector with the same layout (values not copied).
    pub fn duplicate(&self) -> Result<Vector, PetscError> {
        let mut raw: p::Vec = null_mut();
        call!(VecDuplicate(self.raw, &mut raw))?;
        Ok(Vector { raw })
    }

    /// Global index range `[lo, hi)` owned by this rank.
    pub fn ownership_range(&self) -> Result<(usize, usize), PetscError> {
        let (lo, hi) = self.ownership_range_raw()?;
        Ok((to_usize(lo, "ownership start")?, to_usize(hi, "ownership end")?))
    }

    /// [`Vector::ownership_range`] as PETSc indices.
    pub(super) fn ownership_range_raw(&self) -> Result<(p::PetscInt, p::PetscInt), PetscError> {
        let (mut lo, mut hi) = (0, 0);
        call!(VecGetOwnershipRange(self.raw, &mut lo, &mut hi))?;
        Ok((lo, hi))
    }

    /// Sets every entry to `value`.
    pub fn set_all(&mut self, value: f64) -> Result<(), PetscError> {
        call!(VecSet(self.raw, value))
    }

    /// Adds (or inserts) values at global indices; negative indices are ignored. Call
    /// [`Vector::assemble`] afterwards.
    pub fn set_values(&mut self, idx: &[i32], values: &[f64], add: bool) -> Result<(), PetscError> {
        assert_eq!(idx.len(), values.len());
        let n = to_petsc_int(idx.len(), "entries to set")?;
        let mode = if add { p::ADD_VALUES } else { p::INSERT_VALUES };
        call!(VecSetValues(self.raw, n, idx.as_ptr(), values.as_ptr(), mode))
    }

    /// Communicates off-process contributions.
    pub fn assemble(&mut self) -> Result<(), PetscError> {
        call!(VecAssemblyBegin(self.raw))?;
        call!(VecAssemblyEnd(self.raw))
    }

    /// The number of entries this rank holds.
    fn local_size(&self) -> Result<usize, PetscError> {
        let mut n = 0;
        call!(VecGetLocalSize(self.raw, &mut n))?;
        to_usize(n, "local vector size")
    }

    /// Reads the local part.
    pub fn read<R>(&self, f: impl FnOnce(&[f64]) -> R) -> Result<R, PetscError> {
        let n = self.local_size()?;
        let array = ReadArray::get(self.raw, n)?;
        let r = f(array.slice());
        array.restore()?;
        Ok(r)
    }

    /// Writes the local part.
    pub fn write<R>(&mut self, f: impl FnOnce(&mut [f64]) -> R) -> Result<R, PetscError> {
        let n = self.local_size()?;
        let mut array = WriteArray::get(self.raw, n)?;
        let r = f(array.slice());
        array.restore()?;
        Ok(r)
    }

    /// `self ← self + alpha·x`.
    pub fn axpy(&mut self, alpha: f64, x: &Vector) -> Result<(), PetscError> {
        call!(VecAXPY(self.raw, alpha, x.raw))
    }

    /// Copies the values of `x` into `self`.
    pub fn copy_from(&mut self, x: &Vector) -> Result<(), PetscError> {
        call!(VecCopy(x.raw, self.raw))
    }

    /// Euclidean norm (collective).
    pub fn norm2(&self) -> Result<f64, PetscError> {
        let mut r = 0.0;
        call!(VecNorm(self.raw, p::NORM_2, &mut r))?;
        Ok(r)
    }

    /// Max norm (collective).
    pub fn norm_inf(&self) -> Result<f64, PetscError> {
        let mut r = 0.0;
        call!(VecNorm(self.raw, p::NORM_INFINITY, &mut r))?;
        Ok(r)
    }
}

impl Drop for Vector {
    fn drop(&mut self) {
        // SAFETY: raw was created by PETSc and is destroyed once.
        unsafe {
            p::VecDestroy(&mut self.raw);
        }
    }
}

/// A vector's local array lent for reading (`VecGetArrayRead`).
struct ReadArray {
    v: p::Vec,
    ptr: *const f64,
    len: usize,
}

impl ReadArray {
    /// The local array of `v`, which holds `len` entries on this rank.
    fn get(v: p::Vec, len: usize) -> Result<Lent<ReadArray>, PetscError> {
        let mut ptr: *const f64 = null();
        call!(VecGetArrayRead(v, &mut ptr))?;
        Ok(Lent::new(ReadArray { v, ptr, len }))
    }

    fn slice(&self) -> &[f64] {
        // SAFETY: PETSc guarantees `len` readable entries until VecRestoreArrayRead.
        unsafe { lent_slice(self.ptr, self.len) }
    }
}

impl Loan for ReadArray {
    fn give_back(&mut self) -> Result<(), PetscError> {
        call!(VecRestoreArrayRead(self.v, &mut self.ptr))
    }
}

/// A vector's local array lent for writing (`VecGetArray`).
struct WriteArray {
    v: p::Vec,
    ptr: *mut f64,
    len: usize,
}

impl WriteArray {
    /// The local array of `v`, which holds `len` entries on this rank.
    fn get(v: p::Vec, len: usize) -> Result<Lent<WriteArray>, PetscError> {
        let mut ptr: *mut f64 = null_mut();
        call!(VecGetArray(v, &mut ptr))?;
        Ok(Lent::new(WriteArray { v, ptr, len }))
    }

    fn slice(&mut self) -> &mut [f64] {
        // SAFETY: PETSc guarantees `len` writable entries until VecRestoreArray.
        unsafe { lent_slice_mut(self.ptr, self.len) }
    }
}

impl Loan for WriteArray {
    fn give_back(&mut self) -> Result<(), PetscError> {
        call!(VecRestoreArray(self.v, &mut self.ptr))
    }
}

/// The entries `is` of a vector as a vector of their own (`VecGetSubVector`; the values
/// written into it go back with it).
pub(super) struct SubVector {
    v: p::Vec,
    is: p::IS,
    /// The subvector (PETSc's, valid until given back).
    pub(super) sub: p::Vec,
}

impl SubVector {
    /// The entries `is` of `v`.
    pub(super) fn get(v: p::Vec, is: p::IS) -> Result<Lent<SubVector>, PetscError> {
        let mut sub: p::Vec = null_mut();
        call!(VecGetSubVector(v, is, &mut sub))?;
        Ok(Lent::new(SubVector { v, is, sub }))
    }
}

impl Loan for SubVector {
    fn give_back(&mut self) -> Result<(), PetscError> {
        call!(VecRestoreSubVector(self.v, self.is, &mut self.sub))
    }
}
