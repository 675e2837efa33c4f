//! Linear algebra backends. PETSc (MPI-parallel, [`petsc`]) is the production backend.

pub mod ffi;
pub mod petsc;
