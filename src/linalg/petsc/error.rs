//! PETSc's errors as [`PetscError`], the one [`call!`](crate::linalg::petsc::call) macro through
//! which every PETSc function is called, the error code a failed callback returns, and the
//! checked conversions between PETSc's sizes and indices ([`p::PetscInt`]) and Rust's.
#![allow(unsafe_code)]

use crate::linalg::ffi as p;
use std::ffi::{c_char, CStr};
use std::fmt::Display;
use std::ptr::{null, null_mut};
use thiserror::Error;

/// A failed PETSc call.
#[derive(Debug, Clone, Error)]
#[error("PETSc error {code} in {call}: {message}")]
pub struct PetscError {
    /// PETSc's error code.
    pub code: i32,
    /// The PETSc function that failed.
    pub call: &'static str,
    /// PETSc's text for the code.
    pub message: String,
}

/// `Ok` for a zero PETSc error code, else the error with PETSc's text for the code.
pub(crate) fn chk(code: p::PetscErrorCode, call: &'static str) -> Result<(), PetscError> {
    if code == 0 {
        return Ok(());
    }
    let mut text: *const c_char = null();
    // SAFETY: PetscErrorMessage only writes a pointer to a static string.
    let message = unsafe {
        if p::PetscErrorMessage(code, &mut text, null_mut()) == 0 && !text.is_null() {
            CStr::from_ptr(text).to_string_lossy().into_owned()
        } else {
            "unknown error".to_string()
        }
    };
    Err(PetscError { code, call, message })
}

/// Calls the PETSc (or SLEPc) function `f` of the FFI with the arguments given, evaluated
/// inside the same `unsafe` block, and turns its error code into a `Result` through [`chk`]:
/// `call!(VecSet(v, 0.0))?`. The caller's file allows `unsafe_code` and answers for the
/// arguments.
macro_rules! call {
    ($f:ident ( $($arg:expr),* $(,)? )) => {
        $crate::linalg::petsc::error::chk(
            unsafe { $crate::linalg::ffi::$f($($arg),*) },
            stringify!($f),
        )
    };
}
pub(crate) use call;

/// PETSc error code of a failed callback.
pub(crate) const CALLBACK_FAILED: p::PetscErrorCode = 1;

/// The code a callback returns to PETSc for `result`: 0, or the error's code (at least
/// [`CALLBACK_FAILED`]).
pub(crate) fn callback_code(result: Result<(), PetscError>) -> p::PetscErrorCode {
    match result {
        Ok(()) => 0,
        Err(e) => e.code.max(CALLBACK_FAILED),
    }
}

/// PETSc's code for an argument out of range (`PETSC_ERR_ARG_OUTOFRANGE`), the code of a
/// failed conversion.
const OUT_OF_RANGE: p::PetscErrorCode = 63;
const _: () = assert!(p::PETSC_ERR_ARG_OUTOFRANGE == 63);

/// `n` converted to `U`, or an error naming `what` (the size or index) and its value.
pub(crate) fn convert<T, U>(n: T, what: &str) -> Result<U, PetscError>
where
    T: Copy + Display,
    U: TryFrom<T>,
{
    U::try_from(n).map_err(|_| PetscError {
        code: OUT_OF_RANGE,
        call: "size conversion",
        message: format!("{what} = {n} is out of range for {}", std::any::type_name::<U>()),
    })
}

/// A size or index as a `usize` (checked: an error naming `what` if it does not fit).
pub(crate) fn to_usize<T>(n: T, what: &str) -> Result<usize, PetscError>
where
    T: Copy + Display,
    usize: TryFrom<T>,
{
    convert(n, what)
}

/// A size or index as a [`p::PetscInt`] (checked: an error naming `what` if it does not fit).
pub(crate) fn to_petsc_int<T>(n: T, what: &str) -> Result<p::PetscInt, PetscError>
where
    T: Copy + Display,
    p::PetscInt: TryFrom<T>,
{
    convert(n, what)
}

/// A count PETSc reports as a double (`MatInfo`), as a `usize`: an error naming `what` unless
/// it is a whole number from 0 to 2⁵³ (exact in a double and in a `usize` of 64 bits).
pub(crate) fn count_from_double(x: f64, what: &str) -> Result<usize, PetscError> {
    const EXACT: f64 = 9_007_199_254_740_992.0;
    if !(x.fract() == 0.0 && (0.0..=EXACT).contains(&x)) {
        return Err(PetscError {
            code: OUT_OF_RANGE,
            call: "size conversion",
            message: format!("{what} = {x} is not a count"),
        });
    }
    // a whole number in [0, 2⁵³], checked above: the conversion is exact
    to_usize(x as u64, what)
}
