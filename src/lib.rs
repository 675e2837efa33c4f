//! # cfrd: parallel finite-element analysis of concrete-faced rockfill dams
//!
//! Architecture (one concept per file; `mod.rs` only lists and re-exports):
//!
//! | module | what it holds |
//! |---|---|
//! | [`conventions`] | units, axes, signs, Voigt order, frames (read first) |
//! | [`tensor`] | Voigt stress/strain/tangent newtypes |
//! | [`material`] | constitutive library: elastic, rockfill GP, interface laws, joints |
//! | [`mesh`] | global mesh, Gmsh reader, validation, generators |
//! | [`element`] | element kernels (hex8) |
//!
//! The native parallel stack (MPI, PETSc, parallel HDF5, METIS) is behind the default
//! `native` feature; the constitutive library, the mesh code and the element kernels build
//! and test without it (`cargo test --no-default-features --lib`).

pub mod conventions;
pub mod element;
pub mod error;
pub mod material;
pub mod mesh;
pub mod plot;
pub mod point;
pub mod tensor;
