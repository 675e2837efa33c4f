//! Linear algebra backends. PETSc (MPI-parallel, [`petsc`]) is the production backend; SLEPc
//! ([`slepc`]) solves the eigenproblems of the modal analysis. The preconditioner shells
//! [`lagged_lu`] and [`reduced_amg`] are modules of [`petsc`], named here too.

pub mod ffi;
pub mod petsc;
pub mod slepc;

pub use petsc::{lagged_lu, reduced_amg};
