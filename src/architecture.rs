//! # Architecture: the rooms of the code and the one-way arrows between them
//!
//! ```text
//!   main.rs, cli/ ── the binary's command line: parses, dispatches, maps failures to exit codes
//!      │
//!      ▼
//!   run/     the `cfrd run` pipeline: set-up, the schedule of stages and steps, and the
//!      │     observers that decide what is written (results, checkpoints, quake, modes,
//!      │     profiles, progress, summary)
//!      ▼
//!   post/    results → tables and figures (Figs. 7–20, accuracy against a reference)
//!      │
//!      ▼
//!   io/      parallel HDF5 results and checkpoints, the serial results reader, XDMF,
//!      │     summary.json, output directories, I/O guards
//!      ▼
//!   solver/  the problem of a run: discretization, assembly, Newton, step control, time
//!      │     integrators, modal analysis; reports numbers, writes nothing
//!      ▼
//!   linalg/  PETSc and SLEPc behind safe types: vectors, matrices, SNES, line searches,
//!            preconditioner shells, the direct and reduced solvers
//!
//!   foundation, used by every room above and using none of them:
//!   scene/ (the YAML scene, resolved)   mesh/ (meshes, Gmsh, the dam generator)
//!   material/ (constitutive models)     element/ (element kernels)
//!   seismic/ (spectra, records)         point/ (material-point tests)
//!   tensor, input, plot (figures)       partition (crate: METIS, ownership, ghosts)
//! ```
//!
//! An arrow points down only: a room may use the rooms below it, never one above, and the
//! foundation uses none of the five rooms. Among the files of `linalg/` there is no circle.
//! `cargo test --test architecture` checks both on the source (every `crate::` path in the
//! code and in doc links) together with the house rules that keep rooms readable: no function
//! over 100 lines and no file over 1,200 lines outside tests, one definition of the FFI
//! `call!` macro, and no unchecked `as` cast to or from `usize` or `PetscInt` in `linalg/`.
//! CI runs it with the rest of the tests (`bash ci/test.sh`).
//!
//! ## How a run flows
//!
//! 1. `run::setup` loads the scene on every rank, partitions the mesh with METIS (rank 0, then
//!    broadcast), starts PETSc and builds the rank-local `solver::Problem`; a `--restart`
//!    restores its state from `io::checkpoint`.
//! 2. `run::schedule` walks the stages: begins each in the problem, advances its steps, ends
//!    it, and at every event calls the observers in order: progress, modes, quake recorder,
//!    results writer, checkpoint pacing, profiles, summary. An observer returns a solver halt
//!    (the stage fails, what was written is kept, exit 3) or a failure (the run ends, exit 4).
//! 3. At the end the results file is closed and the post-processing observers read it back
//!    through `io::results_reader` to draw the figures.
//!
//! ## Where a new capability goes
//!
//! - A new output: an observer in `run/` and, if it draws from results, a module in `post/`.
//! - A new physics term (a load, an added mass, a dashpot): the scene's terms in `scene/`,
//!   assembled by `solver/`.
//! - A new time integrator: one file in `solver/integrator/`, its scene key, its checkpoint
//!   fields.
//! - A new preconditioner: one `linalg/` file implementing the preconditioner-shell trait.
