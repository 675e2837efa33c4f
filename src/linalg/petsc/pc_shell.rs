//! cfrd's preconditioner shells: a [`PcShell`] (the canonical LU, the distributed LU, the
//! reduced multigrid) is installed on a PETSc `PC` of type `shell` with itself as the shell's
//! context, and PETSc calls it back through one pair of generic trampolines.
#![allow(unsafe_code)]

use super::error::{call, callback_code, PetscError};
use crate::linalg::ffi as p;
use std::ffi::{c_char, c_void, CStr};
use std::ptr::{null, null_mut};

/// A preconditioner PETSc applies as a shell: set up at every new operator, applied as y =
/// P⁻¹x. Its state must stay at one address while a `PC` refers to it (the owner keeps it
/// boxed and drops it only after the solver).
pub(crate) trait PcShell {
    /// The name the shell reports (`-ksp_view`), and by which it is recognised.
    const NAME: &'static CStr;

    /// Sets up on the operators of `pc` (a failure of the preconditioner is `pc`'s failed
    /// reason; an `Err` stops the solve).
    fn setup(&mut self, pc: p::PC) -> Result<(), PetscError>;

    /// y = P⁻¹ x.
    fn apply(&mut self, pc: p::PC, x: p::Vec, y: p::Vec) -> Result<(), PetscError>;
}

/// Makes `pc` apply `shell`: type `shell`, `shell` as its context, the trampolines of `S`, its
/// name.
pub(crate) fn install<S: PcShell>(pc: p::PC, shell: &S) -> Result<(), PetscError> {
    call!(PCSetType(pc, p::PCSHELL.as_ptr() as *const c_char))?;
    let ctx = shell as *const S as *mut c_void;
    call!(PCShellSetContext(pc, ctx))?;
    call!(PCShellSetSetUp(pc, Some(shell_setup::<S>)))?;
    call!(PCShellSetApply(pc, Some(shell_apply::<S>)))?;
    call!(PCShellSetName(pc, S::NAME.as_ptr()))
}

/// Makes `ksp` apply `shell` alone (`preonly` with the shell preconditioner): the direct
/// solvers.
pub(crate) fn install_preonly<S: PcShell>(ksp: p::KSP, shell: &S) -> Result<(), PetscError> {
    call!(KSPSetType(ksp, p::KSPPREONLY.as_ptr() as *const c_char))?;
    let mut pc: p::PC = null_mut();
    call!(KSPGetPC(ksp, &mut pc))?;
    install(pc, shell)
}

/// The name of the shell `pc` (`None` when it has none).
///
/// # Safety
/// `pc` must be a live `PC` of type `shell`.
pub(crate) unsafe fn name<'a>(pc: p::PC) -> Option<&'a CStr> {
    let mut name: *const c_char = null();
    // SAFETY: the caller's contract; PETSc only writes the name's pointer
    unsafe { p::PCShellGetName(pc, &mut name) };
    if name.is_null() {
        return None;
    }
    // SAFETY: the name set by `install`, NUL-terminated while the PC lives.
    Some(unsafe { CStr::from_ptr(name) })
}

/// The shell context of `pc` as an `S`.
///
/// # Safety
/// `pc` must be a shell installed by [`install`] with an `S`, whose state is alive and not
/// otherwise borrowed.
pub(crate) unsafe fn context<'a, S: PcShell>(pc: p::PC) -> Result<&'a mut S, PetscError> {
    let mut ctx: *mut c_void = null_mut();
    call!(PCShellGetContext(pc, &mut ctx as *mut *mut c_void as *mut c_void))?;
    // SAFETY: the context is the `S` given to `install` (caller's contract).
    Ok(unsafe { &mut *(ctx as *mut S) })
}

/// PETSc's set-up callback of every shell of type `S`.
unsafe extern "C" fn shell_setup<S: PcShell>(pc: p::PC) -> p::PetscErrorCode {
    // SAFETY: installed by `install::<S>` with its context.
    callback_code(unsafe { context::<S>(pc) }.and_then(|shell| shell.setup(pc)))
}

/// PETSc's apply callback of every shell of type `S`.
unsafe extern "C" fn shell_apply<S: PcShell>(pc: p::PC, x: p::Vec, y: p::Vec) -> p::PetscErrorCode {
    // SAFETY: installed by `install::<S>` with its context.
    callback_code(unsafe { context::<S>(pc) }.and_then(|shell| shell.apply(pc, x, y)))
}
