//! What PETSc lends until it is given back (an array, a row, a subvector): a [`Loan`] says how
//! to give it back, and [`Lent`] gives it back exactly once, by [`Lent::restore`] (whose error
//! is returned) or, on an early return, when dropped.
#![allow(unsafe_code)]

use super::error::PetscError;
use std::ops::{Deref, DerefMut};

/// Something PETSc lent.
pub(super) trait Loan {
    /// Gives it back to PETSc.
    fn give_back(&mut self) -> Result<(), PetscError>;
}

/// A loan given back exactly once.
pub(super) struct Lent<L: Loan> {
    loan: L,
    lent: bool,
}

impl<L: Loan> Lent<L> {
    /// Holds `loan`, which PETSc has just lent.
    pub(super) fn new(loan: L) -> Self {
        Lent { loan, lent: true }
    }

    /// Gives the loan back to PETSc.
    pub(super) fn restore(mut self) -> Result<(), PetscError> {
        self.lent = false;
        self.loan.give_back()
    }
}

impl<L: Loan> Deref for Lent<L> {
    type Target = L;

    fn deref(&self) -> &L {
        &self.loan
    }
}

impl<L: Loan> DerefMut for Lent<L> {
    fn deref_mut(&mut self) -> &mut L {
        &mut self.loan
    }
}

impl<L: Loan> Drop for Lent<L> {
    fn drop(&mut self) {
        if self.lent {
            // an error is already on its way out; this one would only hide it
            let _ = self.loan.give_back();
        }
    }
}

/// The `len` entries PETSc lent at `ptr` (none when `len` is 0 or `ptr` null, as PETSc gives a
/// rank that holds no entries).
///
/// # Safety
/// PETSc must have lent `len` readable entries at `ptr`, valid while the slice lives.
pub(super) unsafe fn lent_slice<'a, T>(ptr: *const T, len: usize) -> &'a [T] {
    if len == 0 || ptr.is_null() {
        return &[];
    }
    // SAFETY: the caller's guarantee
    unsafe { std::slice::from_raw_parts(ptr, len) }
}

/// The `len` writable entries PETSc lent at `ptr` (none when `len` is 0 or `ptr` null).
///
/// # Safety
/// PETSc must have lent `len` writable entries at `ptr`, valid and not aliased while the slice
/// lives.
pub(super) unsafe fn lent_slice_mut<'a, T>(ptr: *mut T, len: usize) -> &'a mut [T] {
    if len == 0 || ptr.is_null() {
        return &mut [];
    }
    // SAFETY: the caller's guarantee
    unsafe { std::slice::from_raw_parts_mut(ptr, len) }
}
