//! Linear algebra backends. PETSc (MPI-parallel, [`petsc`]) is the production backend; SLEPc
//! ([`slepc`]) solves the eigenproblems of the modal analysis.

pub mod ffi;
pub mod petsc;
pub mod slepc;
