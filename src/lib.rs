//! # cfrd: parallel finite-element analysis of concrete-faced rockfill dams
//!
//! The rooms and the arrows between them: [`architecture`]. One concept per file; `mod.rs`
//! only lists and re-exports.
//!
//! | module | what it holds |
//! |---|---|
//! | [`architecture`] | the map of the rooms and their one-way arrows (documentation only) |
//! | [`guide`] | user guide (documentation only): scene format, command line, restart, runs in parts, outputs, exit codes, PETSc options |
//! | [`verification`] | what has been checked (documentation only): solver checks, material points, the seed dam's Figs. 7–11 on three meshes |
//! | [`performance`] | measured run times, memory, Newton and solver figures, each with its commit and command (documentation only) |
//! | [`conventions`] | units, axes, signs, Voigt order, frames (read first) |
//! | [`tensor`] | Voigt stress/strain/tangent newtypes |
//! | [`material`] | constitutive library: elastic, rockfill GP, interface laws, joints |
//! | [`input`] | bounded reading of input files (regular files only, size caps) |
//! | [`mesh`] | global mesh, Gmsh reader, validation, generators |
//! | [`element`] | element kernels (hex8) |
//! | [`scene`] | the YAML scene: schema, validation, physics terms |
//! | [`solver`] | integration-point storage, element blocks, rank-local discretization, Newton, stage checkpoints and restart |
//! | `partition` (crate) | METIS partition, ownership, ghosts, partition files |
//! | `linalg` | PETSc safe layer (feature `native`) |
//! | `io` | parallel HDF5 results, XDMF, run summary (feature `native`) |
//! | `parallel` | MPI start-up, abort-on-panic hook, collective decisions (feature `native`) |
//! | `run` | the `cfrd run` pipeline: the schedule and its observers (feature `native`) |
//! | [`point`] | `cfrd point`: material-point tests from YAML, CSV and PNG output |
//! | [`plot`] | PNG line plots (figures of point tests and dam outputs) |
//! | [`post`] | post-processing: the seed's static and dynamic figures and tables, accuracy against a reference |
//! | [`seismic`] | design spectrum, response spectra, artificial accelerograms, record readers, `cfrd accel` |
//! | [`fuzzing`] | one input through one reader: the entry points of the fuzz targets and of their corpus replay |
//!
//! The native parallel stack (MPI, PETSc, parallel HDF5, METIS) is behind the default
//! `native` feature; the constitutive library, the mesh code and the element kernels build
//! and test without it (`cargo test --no-default-features --lib`).

pub mod architecture;
pub mod conventions;
pub mod dir_lock;
pub mod element;
pub mod error;
pub mod fuzzing;
pub mod guide;
pub mod input;
#[cfg(feature = "native")]
pub mod io;
#[cfg(feature = "native")]
pub mod linalg;
pub mod material;
pub mod mesh;
#[cfg(feature = "native")]
pub mod parallel;
pub mod performance;
pub mod plot;
pub mod point;
pub mod post;
#[cfg(feature = "native")]
pub mod run;
pub mod scene;
pub mod seismic;
pub mod solver;
pub mod tensor;
#[cfg(test)]
mod test_support;
pub mod verification;
