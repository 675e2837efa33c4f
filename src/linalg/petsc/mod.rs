//! A small safe layer over PETSc: owned handles destroyed on drop, `Result` errors carrying
//! PETSc's message, and only the Vec/Mat/KSP/PC/SNES operations cfrd needs (SNES drives the
//! Newton iterations through the [`SnesProblem`] callbacks).
//!
//! Start-up and shutdown order: MPI first (rsmpi), then [`Petsc::initialize`]
//! on the same communicator (through `SlepcInitialize`, which initializes PETSc and SLEPc at
//! once, so the eigensolvers of [`super::slepc`] need no second start-up); every PETSc object
//! must be dropped before the [`Petsc`] guard, which finalizes SLEPc and PETSc but leaves MPI to
//! rsmpi. nalgebra is column-major while `MatSetValues` expects
//! row-major blocks: [`Matrix::add_values`] takes row-major data and says so.
//!
//! **Files and layers.** Each file uses only files of the layers above it (`a ← b`: `b` uses
//! `a`), so no two files import each other:
//!
//! 1. `error.rs`: [`PetscError`], `chk`, the one `call!` macro of the crate (also used by
//!    [`super::slepc`]), the callbacks' error code, checked conversions between
//!    [`PetscInt`](crate::linalg::ffi::PetscInt) and `usize`.
//! 2. `init.rs` ([`Petsc`]) and `options.rs` (single options) ← error.
//! 3. `vector.rs` ([`Vector`], guards of borrowed arrays and subvectors) ← init.
//! 4. `matrix.rs` ([`Matrix`], the guard of a borrowed row) and `gather.rs` ([`Gather`]) ←
//!    vector.
//! 5. `csr.rs` ([`CsrLayout`], [`CsrPart`], guards of the borrowed compressed rows and values)
//!    and `coupling.rs` (the coupled rows of a Jacobian) ← matrix; `blocked.rs` (a matrix's
//!    copy in node blocks) ← error; `canonical_product.rs`
//!    ([`CanonicalProduct`]) ← matrix, gather; `pc_shell.rs` (the `PcShell` trait and the one
//!    pair of set-up/apply trampolines of every shell) ← error.
//! 6. [`lagged_lu`] (`LaggedLu`, [`DistributedLu`]) ← pc_shell, blocked; [`reduced_amg`]
//!    ([`ReducedAmg`]) ← pc_shell, coupling, options, vector.
//! 7. `canonical_lu.rs` ([`CanonicalLu`]) ← lagged_lu, coupling, gather, pc_shell.
//! 8. `method.rs` ([`LinearMethod`], [`CanonicalSettings`], the solver built from them, the
//!    Krylov defaults) ← canonical_lu, lagged_lu, reduced_amg: the only file that knows every
//!    linear solver. `problem.rs` ([`SnesProblem`]) ← matrix, vector; `line_search.rs`
//!    ([`LineSearch`] and its step rules) ← problem.
//! 9. `snes.rs` ([`Snes`], [`SnesOutcome`], the SNES callbacks) ← method, line_search, problem.

mod blocked;
mod canonical_lu;
mod canonical_product;
mod coupling;
mod csr;
pub(crate) mod error;
mod gather;
mod init;
pub mod lagged_lu;
mod line_search;
mod loan;
mod matrix;
mod method;
mod options;
mod pc_shell;
mod problem;
pub mod reduced_amg;
mod snes;
mod vector;

pub use canonical_lu::CanonicalLu;
pub use canonical_product::CanonicalProduct;
pub use csr::{CsrLayout, CsrPart};
pub(crate) use error::call;
pub use error::PetscError;
pub use gather::Gather;
pub use init::Petsc;
pub use lagged_lu::DistributedLu;
pub use line_search::LineSearch;
pub use matrix::Matrix;
pub use method::{CanonicalSettings, LinearMethod};
pub use problem::SnesProblem;
pub use reduced_amg::ReducedAmg;
pub use snes::{Snes, SnesOutcome};
pub use vector::Vector;
