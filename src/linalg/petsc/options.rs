//! Single entries of PETSc's options database: defaults that the user's options override, and
//! integer and boolean options read with a default.
#![allow(unsafe_code)]

use super::error::{call, PetscError};
use crate::linalg::ffi as p;
use std::ffi::CString;
use std::ptr::{null, null_mut};

/// Sets `-name value` in PETSc's options database unless the user has set `-name`.
pub(crate) fn default_option(name: &str, value: &str) -> Result<(), PetscError> {
    let (n, v) = (
        CString::new(name).expect("option name without NUL"),
        CString::new(value).expect("option value without NUL"),
    );
    let mut set = p::PETSC_FALSE;
    call!(PetscOptionsHasName(null_mut(), null(), n.as_ptr(), &mut set))?;
    if set == p::PETSC_FALSE {
        call!(PetscOptionsSetValue(null_mut(), n.as_ptr(), v.as_ptr()))?;
    }
    Ok(())
}

/// The integer option `name`, or `default` when it is not set.
pub(crate) fn int_option(name: &str, default: p::PetscInt) -> Result<p::PetscInt, PetscError> {
    let (name, mut set, mut n) = (CString::new(name).expect("no NUL"), p::PETSC_FALSE, default);
    call!(PetscOptionsGetInt(
        null_mut(),
        null(),
        name.as_ptr(),
        &mut n,
        &mut set
    ))?;
    Ok(n)
}

/// The boolean option `name`, or `default` when it is not set.
pub(crate) fn bool_option(name: &str, default: bool) -> Result<bool, PetscError> {
    let (name, mut set) = (CString::new(name).expect("no NUL"), p::PETSC_FALSE);
    let mut on = if default { p::PETSC_TRUE } else { p::PETSC_FALSE };
    call!(PetscOptionsGetBool(
        null_mut(),
        null(),
        name.as_ptr(),
        &mut on,
        &mut set
    ))?;
    Ok(on == p::PETSC_TRUE)
}
