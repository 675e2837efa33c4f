//! Checkpoints of staged static runs and the exact restart from them (issue 4).
//!
//! At the end of completed stages (scene option `output.checkpoint: stage`, the default for
//! scenes with `stages`; on large meshes not at every stage, [`crate::io::pacing`]), and with `output.checkpoint: step` also after every converged load
//! step, `cfrd run` writes `<out>/checkpoint.h5` with the whole state of the static problem;
//! `cfrd run SCENE --restart <out>/checkpoint.h5` loads it and continues with the next stage
//! (or inside the stage, from a step checkpoint). A restart at the same rank count gives results bitwise equal to the
//! uninterrupted run's: every value is stored exactly (IEEE bits) and the solve that follows
//! starts from the same state. The layout does not depend on the rank count (every table is in
//! global input order), so a checkpoint can also be restarted on another number of ranks; the
//! results then agree to the solver tolerances (the parallel sums are ordered differently).
//!
//! # Writing without a corrupt file
//!
//! The file is written under a temporary name in the output directory
//! (`.checkpoint.h5.partial-<pid>`) and renamed over `checkpoint.h5` only after HDF5 closed it
//! ([`ResultsFile::close`]). A run killed while writing leaves the previous checkpoint intact
//! (and a stale `.partial-<pid>` file that may be deleted).
//!
//! # Integrity
//!
//! Every table carries the `checksum` attribute of [`crate::io::hdf5_out::rows_checksum`], and
//! the attributes of `/checkpoint` the XXH3-64 of their text (`attrs_checksum`). After HDF5
//! closed the temporary file, every table is read back and checked before the file replaces
//! the previous checkpoint, and rank 0 appends the integrity record of
//! [`crate::io::integrity`] (checksums of every byte). A restart checks the record before HDF5
//! opens the file, then every table and the attributes as they are read: a changed byte gives
//! an input error (exit code 2) naming the dataset or the metadata bytes.
//!
//! # Layout (format `cfrd-results` version 1 with a `/checkpoint` group, no mesh or steps)
//!
//! ```text
//! /checkpoint            attributes: checkpoint_version = 2 (u64), scene_hash (FNV-1a of the
//!                        scene text), mesh_hash (FNV-1a of coordinates, connectivity, blocks),
//!                        n_nodes, n_elements, n_blocks, stages_done (completed stages, ≥ 1),
//!                        last_stage (its name), n_ranks (informational), state_encoding = "postcard",
//!                        input_files (a line `key<TAB>XXH3-64<TAB>path` per file the scene reads:
//!                        mesh, partition, record components; absent in older checkpoints),
//!                        attrs_checksum (XXH3-64 of the attributes above, hex)
//!   u                    f64 [n_nodes, 3]       displacement (m) at the end of the last stage
//!   f_prev               f64 [n_nodes, 3]       external force of the last stage (N), f_prev
//!   node_offset          f64 [n_nodes, 3]       zero of each node's reported displacement (m)
//!   node_active          i64 [n_nodes]          1 if a placed element touches the node
//!   active_block         i64 [n_blocks]         1 if the block is placed
//!   elem_ref             f64 [n_elements, 24]   displacement of each element's nodes at placement
//!   state_bytes          u64 [n_elements]       length of each element's encoded states
//!   states               u8  [n_elements, w]    committed point states of each element
//!                                               ([`crate::solver::state_codec`]), zero-padded to the
//!                                               longest (w bytes)
//!   report               u8  [len]              JSON of the load-step, Newton and KSP counters
//!                                               ([`SolveReport`] without timings and residuals)
//!   (step checkpoints only, `output.checkpoint: step`:)
//!   load_path            f64 [4]                time reached in the stage in progress (λ of a
//!                                               static stage, s of a dynamic one), the next
//!                                               increment, converged steps since it changed,
//!                                               converged steps since the stage's start
//!   u_stage_start        f64 [n_nodes, 3]       displacement at the start of that stage (m)
//!   node_was_active      i64 [n_nodes]          1 if the node was placed before that stage
//!   (step checkpoints of a dynamic stage only:)
//!   velocity             f64 [n_nodes, 3]       velocity relative to the base (m/s)
//!   acceleration         f64 [n_nodes, 3]       acceleration relative to the base (m/s²)
//!   start_state_bytes,   u64 [n_elements],      the point states at the start of the stage, as
//!   start_states         u8  [n_elements, w']   `state_bytes` and `states`: K₀ of Rayleigh
//!                                               damping and the stage's modes are rebuilt from
//!                                               them, as the uninterrupted run built them
//! ```
//!
//! A step checkpoint (written after every converged load step that does not end a stage) has
//! `stages_done` = the index of the stage in progress and `last_stage` the name of the stage
//! before it (empty in the first stage); the restart continues that stage from λ. Both the
//! uninterrupted run and the restarted one start a fresh preconditioner after the checkpoint's
//! step, so the restart is bitwise exact at the same rank count; with step checkpoints the
//! results differ in the last bits from a run with stage checkpoints only (the factors are
//! reused over fewer steps).
//!
//! Not stored, because [`Problem::begin_stage`] of the next stage recomputes them: the
//! fixed DOFs and their start values, and which nodes were placed before the stage.

use super::error::agree;
use super::{IoError, Redistribution, ResultsFile, ResultsReader};
use crate::mesh::Mesh;
use crate::parallel::broadcast_vec;
use crate::scene::resolved::fnv1a;
use crate::scene::Scene;
use crate::solver::discretization::Discretization;
use crate::solver::integrator::Rates;
use crate::solver::{Problem, ProblemState, Resumed, SolveReport, StageProgress, StepControl};
use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, CommunicatorCollectives};
use std::path::Path;

/// Version of the `/checkpoint` layout; a checkpoint of another version is refused.
pub const CHECKPOINT_VERSION: u64 = 2;

/// File name of the checkpoint in the output directory.
pub const CHECKPOINT_FILE: &str = "checkpoint.h5";

/// FNV-1a hash (hex) of the mesh: coordinates (bits), connectivity and block of every element.
/// A checkpoint is refused for a mesh with another hash.
pub fn mesh_hash(mesh: &Mesh) -> String {
    let mut bytes = Vec::with_capacity(24 * mesh.num_nodes() + 40 * mesh.elements.len());
    for c in &mesh.coords {
        for x in c {
            bytes.extend_from_slice(&x.to_bits().to_le_bytes());
        }
    }
    for e in &mesh.elements {
        for n in &e.nodes {
            bytes.extend_from_slice(&n.to_le_bytes());
        }
        bytes.extend_from_slice(&e.block.to_le_bytes());
    }
    fnv1a(&bytes)
}

fn flags(v: impl Iterator<Item = bool>) -> Vec<i64> {
    v.map(i64::from).collect()
}

/// Writes a table that every rank holds whole (`values` the same everywhere): each rank passes
/// its block of rows. Collective.
fn write_replicated<T: crate::io::hdf5_out::TableValue>(
    file: &mut ResultsFile,
    dataset: &str,
    values: &[T],
) -> Result<(), IoError> {
    let n = values.len().max(1) as u64;
    let padded: Vec<T> = if values.is_empty() {
        vec![T::default()]
    } else {
        values.to_vec()
    };
    let rows =
        crate::io::BlockDistribution::new(n, file.comm().size() as usize).range(file.comm().rank() as usize);
    let block = &padded[rows.start as usize..rows.end as usize];
    file.write_table_block(dataset, n, 1, block)
}

/// Writes the checkpoint of `problem` to `path`, atomically (temporary file renamed on
/// success): at the end of a stage (`within: None`), or after a converged load step inside
/// it (`within`: the stage's load path; a step checkpoint). Collective.
pub fn write(
    world: &SimpleCommunicator,
    path: &Path,
    scene: &Scene,
    problem: &Problem,
    report: &SolveReport,
    within: Option<StepControl>,
) -> Result<(), IoError> {
    let saved = problem
        .save_state(within)
        .map_err(|e| IoError::Usage(format!("saving the state: {e}")));
    let state = agree(world, saved)?;
    let disc = problem.discretization();
    let mesh = &scene.mesh;
    let (n_nodes, n_elements) = (mesh.num_nodes() as u64, mesh.elements.len() as u64);
    let mut file = ResultsFile::create(world, path, &scene.file.name)?;
    file.seal_on_close();
    let comm = file.comm().duplicate();
    let plans = Plans {
        node: Redistribution::new(&comm, "nodes", n_nodes, &disc.owned_nodes)?,
        element: Redistribution::new(&comm, "elements", n_elements, &disc.owned_elements)?,
    };
    write_state_tables(&mut file, &comm, &plans, disc, &state)?;
    if let Some(p) = &state.in_stage {
        write_progress(&mut file, &comm, &plans, p)?;
    }
    write_report(&mut file, &comm, report)?;
    write_attrs(&mut file, scene, &state, comm.size() as u64)?;
    // read back before it replaces the last checkpoint: a write that failed without an error
    // (a full device behind MPI-IO) must not replace a good checkpoint by a bad one
    file.close_checked(|temp| {
        ResultsReader::open(&comm, temp)?
            .requiring_checksums()
            .verify_tables()
            .map(|_| ())
    })
}

/// The redistributions of the node and element tables of a checkpoint.
struct Plans {
    /// Rows of the node tables.
    node: Redistribution,
    /// Rows of the element tables.
    element: Redistribution,
}

/// Writes the tables of the state at the end of the last completed step: displacements,
/// forces, offsets, placement flags, element references and point states. Collective.
fn write_state_tables(
    file: &mut ResultsFile,
    comm: &SimpleCommunicator,
    plans: &Plans,
    disc: &Discretization,
    state: &ProblemState,
) -> Result<(), IoError> {
    let (node_plan, element_plan) = (&plans.node, &plans.element);
    file.write_table("/checkpoint/u", node_plan, 3, &state.u)?;
    file.write_table("/checkpoint/f_prev", node_plan, 3, &state.f_prev)?;
    let offsets: Vec<f64> = state.node_offset.iter().flatten().copied().collect();
    file.write_table("/checkpoint/node_offset", node_plan, 3, &offsets)?;
    let active = flags(disc.owned_nodes.iter().map(|&n| state.node_active[n as usize]));
    file.write_table("/checkpoint/node_active", node_plan, 1, &active)?;
    write_replicated(
        file,
        "/checkpoint/active_block",
        &flags(state.active_block.iter().copied()),
    )?;
    let refs: Vec<f64> = state.elem_ref.iter().flatten().copied().collect();
    file.write_table("/checkpoint/elem_ref", element_plan, 24, &refs)?;
    write_states(file, comm, element_plan, "", &state.element_states)
}

/// Writes the tables of a step checkpoint: the stage's start states and displacements, the
/// load path, and the rates of a dynamic stage. Collective.
fn write_progress(
    file: &mut ResultsFile,
    comm: &SimpleCommunicator,
    plans: &Plans,
    p: &StageProgress,
) -> Result<(), IoError> {
    let node_plan = &plans.node;
    if let Some(start) = &p.start_states {
        write_states(file, comm, &plans.element, "start_", start)?;
    }
    file.write_table("/checkpoint/u_stage_start", node_plan, 3, &p.u_stage_start)?;
    let was = flags(p.node_was_active.iter().copied());
    file.write_table("/checkpoint/node_was_active", node_plan, 1, &was)?;
    let path = [
        p.path.t,
        p.path.dt,
        f64::from(p.path.streak),
        f64::from(p.path.steps),
    ];
    write_replicated(file, "/checkpoint/load_path", &path)?;
    if let Some(r) = &p.rates {
        file.write_table("/checkpoint/velocity", node_plan, 3, &r.velocity)?;
        file.write_table("/checkpoint/acceleration", node_plan, 3, &r.acceleration)?;
        if !r.history.is_empty() {
            file.write_table("/checkpoint/hht_history", node_plan, 3, &r.history)?;
        }
    }
    Ok(())
}

/// Writes the solver counters of `report` as JSON. Collective.
fn write_report(
    file: &mut ResultsFile,
    comm: &SimpleCommunicator,
    report: &SolveReport,
) -> Result<(), IoError> {
    // the counters are the same on every rank; rank 0's are stored (timings are per run; the
    // residual history is not needed and may hold a non-finite value, which JSON cannot)
    let counters = SolveReport {
        assembly_seconds: 0.0,
        solve_seconds: 0.0,
        residuals: Vec::new(),
        ..report.clone()
    };
    let mut json = serde_json::to_vec(&counters).unwrap_or_default();
    broadcast_vec(comm, 0, &mut json);
    write_replicated(file, "/checkpoint/report", &json)
}

/// Writes the attributes of `/checkpoint` with their checksum; `n_ranks` is the rank count.
/// Collective.
fn write_attrs(
    file: &mut ResultsFile,
    scene: &Scene,
    state: &ProblemState,
    n_ranks: u64,
) -> Result<(), IoError> {
    let mesh = &scene.mesh;
    let stage_name = match state.stages_done {
        0 => "",
        k => scene.stages[k - 1].name.as_str(),
    };
    let numbers = [
        ("checkpoint_version", CHECKPOINT_VERSION),
        ("n_nodes", mesh.num_nodes() as u64),
        ("n_elements", mesh.elements.len() as u64),
        ("n_blocks", state.active_block.len() as u64),
        ("stages_done", state.stages_done as u64),
        ("n_ranks", n_ranks),
    ];
    let m_hash = mesh_hash(mesh);
    let inputs = crate::scene::inputs::to_text(&scene.inputs);
    let strings = [
        ("scene_hash", scene.hash.as_str()),
        ("mesh_hash", m_hash.as_str()),
        ("last_stage", stage_name),
        ("state_encoding", "postcard"),
        (INPUT_FILES, inputs.as_str()),
    ];
    let sum = attrs_checksum(&numbers, &strings);
    let mut all_strings = strings.to_vec();
    all_strings.push(("attrs_checksum", sum.as_str()));
    file.write_group_attrs("/checkpoint", &numbers, &all_strings)
}

/// Writes encoded element states as `/checkpoint/<prefix>state_bytes` (each element's length)
/// and `/checkpoint/<prefix>states` (zero-padded to the longest). Collective.
fn write_states(
    file: &mut ResultsFile,
    comm: &SimpleCommunicator,
    plan: &Redistribution,
    prefix: &str,
    states: &[Vec<u8>],
) -> Result<(), IoError> {
    let lens: Vec<u64> = states.iter().map(|s| s.len() as u64).collect();
    file.write_table(&format!("/checkpoint/{prefix}state_bytes"), plan, 1, &lens)?;
    let local_w = lens.iter().copied().max().unwrap_or(0);
    let mut width = 0u64;
    comm.all_reduce_into(&local_w, &mut width, mpi::collective::SystemOperation::max());
    let width = width.max(1) as usize;
    let mut packed = vec![0u8; width * states.len()];
    for (row, s) in packed.chunks_mut(width).zip(states) {
        row[..s.len()].copy_from_slice(s);
    }
    file.write_table(&format!("/checkpoint/{prefix}states"), plan, width, &packed)
}

/// Unpacks the encoded states written by [`write_states`], checking them against the number
/// of elements `ne`; `what` names them in the error.
fn unpack_states(lens: &[u64], packed: &[u8], ne: usize, what: &str) -> Result<Vec<Vec<u8>>, String> {
    let width = packed.len().checked_div(ne).unwrap_or(0);
    if lens.len() != ne || packed.len() != width * ne || lens.iter().any(|&l| l as usize > width) {
        return Err(format!("the stored {what} do not fit their lengths"));
    }
    Ok(lens
        .iter()
        .enumerate()
        .map(|(i, &l)| packed[i * width..i * width + l as usize].to_vec())
        .collect())
}

/// XXH3-64 (hex) of the `/checkpoint` attributes `name=value`, one per line in the order
/// given: stored as `attrs_checksum` and checked before the attributes are used.
fn attrs_checksum(numbers: &[(&str, u64)], strings: &[(&str, &str)]) -> String {
    let text: Vec<String> = numbers
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .chain(strings.iter().map(|(k, v)| format!("{k}={v}")))
        .collect();
    format!("{:016x}", xxhash_rust::xxh3::xxh3_64(text.join("\n").as_bytes()))
}

/// The `/checkpoint` attribute naming the scene's input files with their content hashes
/// ([`crate::scene::inputs::to_text`]).
pub const INPUT_FILES: &str = "input_files";

/// The input files stored in the checkpoint at `path` (`None` for a checkpoint written before
/// they were stored). One rank, after [`read`] has checked the file.
pub fn stored_inputs(path: &Path) -> Result<Option<String>, IoError> {
    let file = crate::io::results_reader::open(path).map_err(IoError::Layout)?;
    let attr = file.group("checkpoint").and_then(|g| g.attr(INPUT_FILES));
    match attr {
        Ok(a) => {
            let v: hdf5::types::VarLenUnicode = a
                .read_scalar()
                .map_err(|e| IoError::hdf5(format!("{}: {INPUT_FILES}", path.display()), e))?;
            Ok(Some(v.as_str().to_string()))
        }
        Err(_) => Ok(None),
    }
}

/// Reads the `/checkpoint` attributes and checks them against `attrs_checksum`; returns
/// `n_nodes`, `n_elements`, `stages_done`, `scene_hash` and `mesh_hash`.
fn checked_attrs(reader: &ResultsReader, path: &Path) -> Result<(u64, u64, u64, String, String), IoError> {
    let corrupt = |m: &str| IoError::Layout(format!("{}: {m}: the file is corrupted", path.display()));
    let num = |k: &str| reader.attr::<u64>("/checkpoint", k);
    let text = |k: &str| reader.attr_string("/checkpoint", k);
    let numbers = [
        ("checkpoint_version", CHECKPOINT_VERSION),
        ("n_nodes", num("n_nodes")?),
        ("n_elements", num("n_elements")?),
        ("n_blocks", num("n_blocks")?),
        ("stages_done", num("stages_done")?),
        ("n_ranks", num("n_ranks")?),
    ];
    let (scene_hash, m_hash) = (text("scene_hash")?, text("mesh_hash")?);
    let (last, encoding) = (text("last_stage")?, text("state_encoding")?);
    // checkpoints written before the input files were identified lack them
    let inputs = text(INPUT_FILES).ok();
    let mut strings = vec![
        ("scene_hash", scene_hash.as_str()),
        ("mesh_hash", m_hash.as_str()),
        ("last_stage", last.as_str()),
        ("state_encoding", encoding.as_str()),
    ];
    if let Some(inputs) = &inputs {
        strings.push((INPUT_FILES, inputs.as_str()));
    }
    if text("attrs_checksum")? != attrs_checksum(&numbers, &strings) {
        return Err(corrupt(
            "the attributes of /checkpoint do not match their checksum",
        ));
    }
    Ok((numbers[1].1, numbers[2].1, numbers[4].1, scene_hash, m_hash))
}

/// Reads a checkpoint for `scene` and this rank's part `disc`. Refuses a checkpoint of another
/// layout version, scene or mesh. Collective.
pub fn read(
    world: &SimpleCommunicator,
    path: &Path,
    scene: &Scene,
    disc: &Discretization,
) -> Result<(ProblemState, SolveReport), IoError> {
    let intact = match world.rank() {
        0 => super::integrity::verify(path),
        _ => Ok(()),
    };
    agree(world, intact)?;
    let reader = ResultsReader::open(world, path)?.requiring_checksums();
    let comm = reader.comm().duplicate();
    let (n_nodes, n_elements) = (scene.mesh.num_nodes() as u64, scene.mesh.elements.len() as u64);
    let (stages_done, within) = agree(&comm, check_header(&reader, path, scene))?;
    let plans = Plans {
        node: Redistribution::new(&comm, "nodes", n_nodes, &disc.owned_nodes)?,
        // the states of every element this rank evaluates (owned and along the partition boundary)
        element: Redistribution::for_reading(&comm, "elements", n_elements, &disc.elements)?,
    };
    let stored = read_stored(&reader, &plans, within)?;
    let sizes = Sizes {
        nn: disc.owned_nodes.len(),
        ne: disc.elements.len(),
        n_nodes,
    };
    agree(&comm, assemble(stored, scene, path, stages_done, &sizes))
}

/// Checks the version, the attributes, the scene and the mesh of a checkpoint and that it
/// leaves something to restart; returns the completed stages and whether it is a step
/// checkpoint.
fn check_header(reader: &ResultsReader, path: &Path, scene: &Scene) -> Result<(usize, bool), IoError> {
    let mesh = &scene.mesh;
    let (n_nodes, n_elements) = (mesh.num_nodes() as u64, mesh.elements.len() as u64);
    let layout = |m: String| IoError::Layout(format!("{}: {m}", path.display()));
    let version: u64 = reader
        .attr("/checkpoint", "checkpoint_version")
        .map_err(|_| layout("not a cfrd checkpoint (no /checkpoint group)".into()))?;
    if version != CHECKPOINT_VERSION {
        return Err(layout(format!(
            "checkpoint version {version}, this cfrd reads version {CHECKPOINT_VERSION}"
        )));
    }
    let (nn, ne, done, hash, m_hash) = checked_attrs(reader, path)?;
    if hash != scene.hash {
        return Err(layout(format!(
            "written for another scene (scene hash {hash}, this scene's is {}); a \
             checkpoint restarts only the scene file it was written by, unchanged",
            scene.hash
        )));
    }
    if m_hash != mesh_hash(mesh) || nn != n_nodes || ne != n_elements {
        return Err(layout(format!(
            "written for another mesh ({nn} nodes, {ne} elements, mesh hash {m_hash}; \
             this mesh: {n_nodes} nodes, {n_elements} elements, mesh hash {})",
            mesh_hash(mesh)
        )));
    }
    let within = reader.shape("/checkpoint/load_path").is_ok();
    if (done == 0 && !within) || done >= scene.stages.len() as u64 {
        return Err(layout(format!(
            "{done} of the scene's {} stage(s) completed: nothing to restart",
            scene.stages.len()
        )));
    }
    Ok((done as usize, within))
}

/// The tables of a checkpoint as read, before they are checked.
struct Stored {
    /// `u`.
    u: Vec<f64>,
    /// `f_prev`.
    f_prev: Vec<f64>,
    /// `node_offset`.
    offsets: Vec<f64>,
    /// `elem_ref`.
    refs: Vec<f64>,
    /// `state_bytes`.
    lens: Vec<u64>,
    /// `states`.
    packed: Vec<u8>,
    /// `node_active` (every node).
    node_active: Vec<i64>,
    /// `active_block`.
    active_block: Vec<i64>,
    /// `report`.
    json: Vec<u8>,
    /// The tables of a step checkpoint.
    progress: Option<StoredProgress>,
}

/// The tables of a step checkpoint as read, before they are checked.
struct StoredProgress {
    /// `u_stage_start`.
    start: Vec<f64>,
    /// `node_was_active`.
    was: Vec<i64>,
    /// `load_path`.
    path: Vec<f64>,
    /// `velocity`, `acceleration` and `hht_history` (empty without it) of a dynamic stage.
    rates: Option<(Vec<f64>, Vec<f64>, Vec<f64>)>,
    /// `start_state_bytes` and `start_states`.
    start_states: Option<(Vec<u64>, Vec<u8>)>,
}

/// This rank's row counts and the mesh's node count, which the stored tables must fit.
struct Sizes {
    /// Nodes this rank owns.
    nn: usize,
    /// Elements this rank evaluates.
    ne: usize,
    /// Nodes of the mesh.
    n_nodes: u64,
}

/// Reads this rank's rows of the checkpoint's tables, those of a step checkpoint if `within`.
/// Collective.
fn read_stored(reader: &ResultsReader, plans: &Plans, within: bool) -> Result<Stored, IoError> {
    let (node_plan, element_plan) = (&plans.node, &plans.element);
    Ok(Stored {
        u: reader.read_owned::<f64>("/checkpoint/u", node_plan)?,
        f_prev: reader.read_owned::<f64>("/checkpoint/f_prev", node_plan)?,
        offsets: reader.read_owned::<f64>("/checkpoint/node_offset", node_plan)?,
        refs: reader.read_owned::<f64>("/checkpoint/elem_ref", element_plan)?,
        lens: reader.read_owned::<u64>("/checkpoint/state_bytes", element_plan)?,
        packed: reader.read_owned::<u8>("/checkpoint/states", element_plan)?,
        node_active: reader.read_all::<i64>("/checkpoint/node_active")?.0,
        active_block: reader.read_all::<i64>("/checkpoint/active_block")?.0,
        json: reader.read_all::<u8>("/checkpoint/report")?.0,
        progress: match within {
            true => Some(read_progress(reader, plans)?),
            false => None,
        },
    })
}

/// Reads this rank's rows of the tables of a step checkpoint. Collective.
fn read_progress(reader: &ResultsReader, plans: &Plans) -> Result<StoredProgress, IoError> {
    let (node_plan, element_plan) = (&plans.node, &plans.element);
    let start = reader.read_owned::<f64>("/checkpoint/u_stage_start", node_plan)?;
    let was = reader.read_owned::<i64>("/checkpoint/node_was_active", node_plan)?;
    let (path, _) = reader.read_all::<f64>("/checkpoint/load_path")?;
    let rates = if reader.shape("/checkpoint/velocity").is_ok() {
        let v = reader.read_owned::<f64>("/checkpoint/velocity", node_plan)?;
        let a = reader.read_owned::<f64>("/checkpoint/acceleration", node_plan)?;
        let h = match reader.shape("/checkpoint/hht_history") {
            Ok(_) => reader.read_owned::<f64>("/checkpoint/hht_history", node_plan)?,
            Err(_) => Vec::new(),
        };
        Some((v, a, h))
    } else {
        None
    };
    let start_states = match reader.shape("/checkpoint/start_states") {
        Ok(_) => Some((
            reader.read_owned::<u64>("/checkpoint/start_state_bytes", element_plan)?,
            reader.read_owned::<u8>("/checkpoint/start_states", element_plan)?,
        )),
        Err(_) => None,
    };
    Ok(StoredProgress {
        start,
        was,
        path,
        rates,
        start_states,
    })
}

/// `v` if it has `want` values, else an error naming the table `/checkpoint/<name>` of the
/// checkpoint at `path`.
fn sized(path: &Path, name: &str, v: Vec<f64>, want: usize) -> Result<Vec<f64>, IoError> {
    if v.len() == want {
        Ok(v)
    } else {
        Err(IoError::Layout(format!(
            "{}: /checkpoint/{name} has the wrong number of components",
            path.display()
        )))
    }
}

/// Checks the stored tables against this rank's part and the scene and builds the state and
/// the counters from them. Local.
fn assemble(
    stored: Stored,
    scene: &Scene,
    path: &Path,
    stages_done: usize,
    sizes: &Sizes,
) -> Result<(ProblemState, SolveReport), IoError> {
    let (nn, ne) = (sizes.nn, sizes.ne);
    let u = sized(path, "u", stored.u, 3 * nn)?;
    let f_prev = sized(path, "f_prev", stored.f_prev, 3 * nn)?;
    let offsets = sized(path, "node_offset", stored.offsets, 3 * nn)?;
    let refs = sized(path, "elem_ref", stored.refs, 24 * ne)?;
    let bad = |m: &str| IoError::Layout(format!("{}: {m}", path.display()));
    let (node_active, active_block) = (stored.node_active, stored.active_block);
    if node_active.len() as u64 != sizes.n_nodes {
        return Err(bad("the node flags do not fit the mesh"));
    }
    let element_states = unpack_states(&stored.lens, &stored.packed, ne, "states").map_err(|m| bad(&m))?;
    if active_block.len() < scene.mesh.blocks.len() {
        return Err(bad("fewer block flags than blocks"));
    }
    let report: SolveReport = serde_json::from_slice(&stored.json)
        .map_err(|e| bad(&format!("the stored solver counters do not parse ({e})")))?;
    let in_stage = match stored.progress {
        None => None,
        Some(p) => Some(stage_progress(p, &scene.stages[stages_done], path, sizes)?),
    };
    let state = ProblemState {
        stages_done,
        in_stage,
        active_block: active_block[..scene.mesh.blocks.len()]
            .iter()
            .map(|&f| f != 0)
            .collect(),
        node_active: node_active.iter().map(|&f| f != 0).collect(),
        u,
        f_prev,
        node_offset: offsets.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
        elem_ref: refs.chunks(24).map(|c| std::array::from_fn(|k| c[k])).collect(),
        element_states,
    };
    Ok((state, report))
}

/// Checks the stored tables of a step checkpoint against the stage in progress `stage` and
/// this rank's part and builds the stage's progress from them. Local.
fn stage_progress(
    p: StoredProgress,
    stage: &crate::scene::Stage,
    path: &Path,
    sizes: &Sizes,
) -> Result<StageProgress, IoError> {
    let (nn, ne) = (sizes.nn, sizes.ne);
    let bad = |m: &str| IoError::Layout(format!("{}: {m}", path.display()));
    let StoredProgress {
        start,
        was,
        path: load_path,
        rates,
        start_states,
    } = p;
    let count = |v: f64| v >= 0.0 && v.fract() == 0.0 && v <= f64::from(u32::MAX);
    let fits = (load_path.len() == 3 || load_path.len() == 4 && count(load_path[3]))
        && (0.0..stage.t_end()).contains(&load_path[0])
        && load_path[1] > 0.0
        && count(load_path[2])
        && was.len() == nn;
    if !fits {
        return Err(bad("the stored load path of the stage in progress is not valid"));
    }
    if rates.is_some() != stage.dynamic.is_some() {
        return Err(bad("the stored velocities do not fit the stage in progress"));
    }
    let rates = match rates {
        Some((v, a, h)) => Some(Rates {
            velocity: sized(path, "velocity", v, 3 * nn)?,
            acceleration: sized(path, "acceleration", a, 3 * nn)?,
            ground: [0.0; 3],
            history: hht_history(h, stage, nn).map_err(|m| bad(&m))?,
        }),
        None => None,
    };
    Ok(StageProgress {
        rates,
        path: StepControl::resumed(
            resumed_at(&load_path, stage),
            stage.t_end(),
            stage.load_steps,
            stage.step_growth,
        ),
        u_stage_start: sized(path, "u_stage_start", start, 3 * nn)?,
        node_was_active: was.iter().map(|&f| f != 0).collect(),
        start_states: match start_states {
            Some((l, p)) => Some(unpack_states(&l, &p, ne, "start states").map_err(|m| bad(&m))?),
            None => None,
        },
    })
}

/// Where the stored load path `p` (checked) left the stage in progress `stage`. A checkpoint
/// written before the stage's step count was stored (3 entries) counts the nominal steps to
/// the time reached, which is the count unless the stage had cut-backs before it.
fn resumed_at(p: &[f64], stage: &crate::scene::Stage) -> Resumed {
    let nominal = stage.t_end() / f64::from(stage.load_steps.max(1));
    let steps = p.get(3).copied().unwrap_or_else(|| (p[0] / nominal).round());
    Resumed {
        t: p[0],
        dt: p[1],
        streak: p[2] as u32,
        steps: steps as u32,
    }
}

/// Reads a checkpoint and restores `problem` and the counters in `report` from it; returns the
/// number of completed stages (the index of the stage to run or continue next) and, for a step
/// checkpoint, the load path to continue that stage from (the problem is then inside the
/// stage, [`Problem::resume_stage`]). Collective.
pub fn restore(
    world: &SimpleCommunicator,
    path: &Path,
    scene: &Scene,
    problem: &mut Problem,
    report: &mut SolveReport,
) -> Result<(usize, Option<StepControl>), IoError> {
    let (state, counters) = read(world, path, scene, problem.discretization())?;
    let restored = problem
        .restore_state(&state)
        .map_err(|m| IoError::Layout(format!("{}: {m}", path.display())));
    agree(world, restored)?;
    if let Some(progress) = &state.in_stage {
        let resumed = problem
            .resume_stage(progress)
            .map_err(|e| IoError::Usage(format!("continuing the stage: {e}")));
        agree(world, resumed)?;
    }
    *report = counters;
    Ok((state.stages_done, state.in_stage.map(|p| p.path)))
}

/// HHT-α's stored force history `h` of the stage in progress: 3 values per owned node when the
/// stage integrates with α ≠ 0, none otherwise (a Newmark checkpoint cannot continue as HHT-α).
fn hht_history(h: Vec<f64>, stage: &crate::scene::Stage, nn: usize) -> Result<Vec<f64>, String> {
    let alpha = stage.dynamic.as_ref().map_or(0.0, |d| d.alpha);
    match (alpha != 0.0, h.len()) {
        (false, 0) => Ok(h),
        (true, n) if n == 3 * nn => Ok(h),
        (true, 0) => Err("the stage integrates with HHT-α but the checkpoint holds no HHT history".into()),
        _ => Err("/checkpoint/hht_history does not fit the stage in progress".into()),
    }
}
