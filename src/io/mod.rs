//! Results and checkpoint I/O: one HDF5 file written collectively by all ranks, its XDMF
//! description for ParaView, and the JSON run summary.
//!
//! | file | what it holds |
//! |---|---|
//! | [`redistribute`] | METIS ownership ↔ contiguous input-order blocks (MPI all-to-all) |
//! | [`hdf5_out`] | [`ResultsFile`] (collective MPI-IO writer), [`ResultsReader`] |
//! | [`xdmf`] | the XDMF 3 XML that ParaView opens |
//! | [`summary`] | [`RunSummary`] JSON, [`PhaseTimer`], peak memory |
//! | [`error`] | [`IoError`] and the rule that makes every error collective |
//! | [`guard`] | I/O failures that end every rank: free-space checks, watchdog, exit code 4 |
//! | [`integrity`] | the checksums appended to a checkpoint, checked before HDF5 reads it |
//! | [`results_reader`] | a closed results file read serially: its steps and their stages (every post-processing reader uses it) |
//! | [`compare`] | `cfrd compare`: field differences between two results files |
//! | [`export`] | `cfrd export`: one step's fields as CSV, by set or probe |
//! | [`outdir`] | `cfrd run`'s output directory: another run's files, stale temporaries |
//! | [`pacing`] | when a staged run publishes its results and writes its checkpoint |
//! | [`preflight`] | checks of `cfrd run`'s file arguments before HDF5 opens them |
//!
//! # The results file (format `cfrd-results`, version 1)
//!
//! One HDF5 file, e.g. `results.h5`, with `results.xdmf` next to it. **Every dataset is in global
//! input order** (row `i` is node `i` or element `i` of the mesh file, 0-based), so the file is
//! the same, value for value, whatever the number of ranks that wrote it. Units are SI
//! (m, Pa, N, s). Floats are IEEE 64-bit, integers signed 64-bit.
//!
//! ```text
//! /                                 attributes:
//!   format          = "cfrd-results"
//!   format_version  = 1              (u32)
//!   units           = "SI"
//!   n_ranks         = ranks that wrote the file (informational only; the layout does not depend on it)
//!   scene           = scene name
//!   cfrd_version    = e.g. "0.1.0"
//! /mesh                             attributes: n_nodes, n_elements (u64), cell_type = "hex8",
//!                                   node_order = "gmsh", block_names (names joined by '\n')
//!   coordinates     f64 [n_nodes, 3]     x, y, z in m (x stream, y dam axis, z up); attr units = "m"
//!   node_ids        i64 [n_nodes]        node ids of the mesh file
//!   topology        i64 [n_elements, 8]  hex8 connectivity: 0-based rows of `coordinates`,
//!                                        Gmsh node order (the same as VTK/XDMF Hexahedron)
//!   element_ids     i64 [n_elements]     element ids of the mesh file
//!   element_block   i64 [n_elements]     0-based index into `block_names`
//! /steps/000001                     attributes: step (u64, 1-based), time (f64), stage, label
//!   <field>         f64 [n_nodes, ncomp] or [n_elements, ncomp] ([n] when ncomp = 1)
//!                                   attributes: center = "node" | "element", units,
//!                                   components (labels, e.g. "xx,yy,zz,xy,yz,zx"),
//!                                   checksum (u64, [`hdf5_out::rows_checksum`], on every table)
//! /steps/000002 ...
//! ```
//!
//! `time` increases from step to step, as ParaView expects: the end of stage k (1-based) is at
//! time k, and a step written inside a dynamic stage k at its time t of duration D is at
//! k − 1 + t/D (its `label` gives t in seconds).
//!
//! ## Standard fields and sign conventions
//!
//! | name | center | ncomp | units | meaning |
//! |---|---|---|---|---|
//! | `displacement` | node | 3 | m | nodal displacement u = (u_x, u_y, u_z), positive along the axes |
//! | `reaction` | node | 3 | N | reaction forces at constrained DOFs (force exerted **on** the structure), 0 elsewhere |
//! | `velocity`, `acceleration` | node | 3 | m/s, m/s² | dynamic stages |
//! | `stress` | element | 6 | Pa | Cauchy stress at the element centre, Voigt `[xx, yy, zz, xy, yz, zx]`, **tension positive** |
//! | `interface_traction` | element | 3 | Pa | interface and joint elements (scenes with interface blocks only; 0 on solids): mean traction (τ_s, τ_a, t_n) over the 4 points in the local frame `[s, a, n]` (spec (E3)), t_n **tension positive** (σ_n = −t_n) |
//! | `interface_jump` | element | 3 | m | mean jump (δ_s, δ_a, δ_n) since placement, cushion relative to slab, δ_n > 0 opening (spec (E4), (E9)) |
//! | `interface_slip` | element | 2 | m | mean accumulated shear displacement of the material (s, a), opening excluded |
//! | `interface_opening` | element | 1 | m | mean opening (gap) ≥ 0 |
//! | `strain` | element | 6 | – | total strain at the element centre, Voigt order, **tensor** shear ε_xy = γ_xy/2 (see [`hdf5_out::strain_output_components`]), extension positive |
//!
//! Compression-positive geotechnical quantities (p, q, stress ratio) are written only under
//! names that say so (e.g. `mean_stress_compression_positive`), never under the names above.
//! In ParaView, 3-component fields are vectors and 6-component fields symmetric tensors whose
//! components XX, YY, ZZ, XY, YZ, XZ are exactly the Voigt order above.
//!
//! ## Checkpoint data
//!
//! Checkpoints use the same writer: [`ResultsFile::write_table`] stores any distributed table
//! (`n_rows × ncomp` of `f64`, `i64`, `u8`, ...) in global row order and
//! [`ResultsFile::write_group_attrs`] its metadata; [`ResultsReader::read_owned`] gives each
//! rank back the rows it owns under a possibly different rank count. The static solver's
//! checkpoint (`checkpoint.h5`, a `/checkpoint` group with one row per node or element) is
//! described in [`checkpoint`].
//!
//! # Use from the solver
//!
//! ```ignore
//! let owned = OwnedMesh::from_mesh(&mesh, my_nodes, my_elements);    // METIS ownership
//! let mut out = ResultsFile::create(&world, "out/results.h5", &scene.name)?;
//! out.write_mesh(&owned)?;                                            // sets the node/element plans
//! for step in output_steps {
//!     out.begin_step(StepInfo { time, stage: stage.name.clone(), label })?;
//!     out.write_node_field("displacement", "m", 3, &u_owned)?;        // 3 values per owned node
//!     out.write_element_field("stress", "Pa", 6, &sig_centre_owned)?; // 6 values per owned element
//! }
//! out.close()?;                       // rename into place, rank 0 writes out/results.xdmf
//! ```
//!
//! # Collective calls, locks and initialisation order
//!
//! * Every method of [`ResultsFile`] and [`ResultsReader`] (except `read_all` and the accessors)
//!   is collective: all ranks call it in the same order with the same names and metadata
//!   (checked by hashing). Errors are collective too ([`error::agree`]).
//! * MPI must be initialised before the first call; close (or drop) every writer and reader
//!   before the `Universe` is dropped (MPI_Finalize), and before `PetscFinalize` if PETSc's
//!   HDF5 is also used.
//! * The raw HDF5 calls run inside `hdf5::sync::sync`, the global lock of `hdf5-metno`
//!   (Debian's parallel libhdf5 is not thread-safe).
//! * The file is written under a temporary name (`.results.h5.partial-<pid>`) and renamed into
//!   place by [`ResultsFile::close`]; a writer dropped without closing removes it.

pub mod checkpoint;
pub mod compare;
pub mod error;
pub mod export;
pub mod guard;
pub mod hdf5_out;
pub mod integrity;
pub mod outdir;
pub mod pacing;
pub mod preflight;
pub mod redistribute;
pub mod results_reader;
pub mod run_lock;
pub mod summary;
pub mod xdmf;

#[cfg(test)]
mod mpi_tests;

pub use error::IoError;
pub use hdf5_out::{OwnedMesh, ResultsFile, ResultsReader, StepInfo, TableBlock};
pub use redistribute::{BlockDistribution, Redistribution};
pub use summary::{Phase, PhaseTimer, RunSummary};
pub use xdmf::Center;
