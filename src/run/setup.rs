//! A run's set-up: the scene loaded, the mesh partitioned, PETSc and the problem started and a
//! checkpoint restored, collectively, every rank agreeing on each input error.

use super::options::{input, RunFailure};
use crate::io::checkpoint;
use crate::io::summary::{Phase, PhaseTimer};
use crate::linalg::petsc::Petsc;
use crate::parallel::{any_error, broadcast_vec, EXIT_SOLVER};
use crate::scene::Scene;
use crate::solver::discretization::Discretization;
use crate::solver::{mesh_cells, Problem, SolveReport, StepControl};
use mpi::topology::{Communicator, SimpleCommunicator};
use partition::{partition_for_assembly, Partition, PartitionFile};
use std::path::Path;

/// Loads a scene (or the embedded default) collectively.
pub fn load_scene(world: &SimpleCommunicator, scene: Option<&Path>) -> Result<Scene, RunFailure> {
    let local = match scene {
        Some(p) => Scene::load(p),
        None => Scene::from_str(
            crate::scene::DEFAULT_SCENE,
            "<embedded default scene>",
            Path::new("."),
        ),
    };
    any_error(world, local).map_err(input)
}

/// Computes (or reads) the element partition on rank 0 and broadcasts it.
pub fn partition_scene(world: &SimpleCommunicator, scene: &Scene) -> Result<Partition, RunFailure> {
    let cells = mesh_cells(&scene.mesh);
    let n_nodes = scene.mesh.num_nodes();
    let nparts = world.size() as usize;
    let local = if world.rank() == 0 {
        match &scene.file.partition {
            Some(p) => {
                PartitionFile::read(&scene.resolve(p), &cells, n_nodes, nparts).map_err(|e| e.to_string())
            }
            None => {
                let (band, n_bands) = construction_bands(scene);
                partition_for_assembly(&cells, n_nodes, nparts, &band, n_bands)
                    .map_err(|e| format!("{}: {e}", scene.source))
            }
        }
    } else {
        Ok(Vec::new())
    };
    let mut part = any_error(world, local).map_err(input)?;
    broadcast_vec(world, 0, &mut part);
    Ok(Partition::new(&cells, n_nodes, nparts, part))
}

/// Most construction bands of [`construction_bands`] (constraints of the METIS partition).
const MAX_BANDS: usize = 8;

/// The construction band of every element and the number of bands: the stages that place
/// elements, in order, grouped into at most 8 consecutive bands of about equal
/// numbers of stages. Elements never placed by a stage go with the first band. The partition
/// balances each band over the ranks and evens out the elements each rank evaluates
/// (`partition::partition_for_assembly`).
pub fn construction_bands(scene: &Scene) -> (Vec<u32>, usize) {
    let placing: Vec<&crate::scene::Stage> = scene.stages.iter().filter(|s| !s.activate.is_empty()).collect();
    let n_bands = placing.len().min(MAX_BANDS);
    let mut block_band = vec![0u32; scene.mesh.blocks.len()];
    for (k, stage) in placing.iter().enumerate() {
        for &b in &stage.activate {
            block_band[b as usize] = (k * n_bands / placing.len()) as u32;
        }
    }
    let band = scene
        .mesh
        .elements
        .iter()
        .map(|e| block_band[e.block as usize])
        .collect();
    (band, n_bands)
}

/// PETSc started with the scene's and the command line's options, and the rank-local problem
/// of `scene` on the METIS partition. Collective.
pub fn start_solver<'a>(
    world: &'a SimpleCommunicator,
    scene: &'a Scene,
    petsc_options: &[String],
    timer: &mut PhaseTimer,
) -> Result<(Petsc, Problem<'a>), RunFailure> {
    timer.start(Phase::Partition);
    let partition = partition_scene(world, scene)?;
    let cells = mesh_cells(&scene.mesh);
    let disc = Discretization::new(&cells, scene.mesh.num_nodes(), partition, world.rank() as usize);
    timer.start(Phase::Setup);
    let petsc = Petsc::initialize(world).map_err(|e| RunFailure {
        code: EXIT_SOLVER,
        message: e.to_string(),
    })?;
    let opt_result = petsc
        .insert_run_options(&scene.file.solver.petsc_options)
        .and_then(|_| petsc.insert_run_options(&petsc_options.join(" ")));
    any_error(world, opt_result).map_err(|m| input(format!("PETSc options: {m}")))?;
    let setup = Problem::new(&petsc, world, scene, cells, disc);
    let problem = any_error(world, setup).map_err(|m| input(format!("setting up the solver: {m}")))?;
    timer.stop();
    Ok((petsc, problem))
}

/// Checks the input files stored in the checkpoint at `path` against the scene's (on rank 0,
/// shared): a file whose content changed since the checkpoint was written is refused, naming
/// it, unless it is in `accepted`; returns the accepted changed ones as `key: path` (rank 0
/// prints them unless `quiet`). A checkpoint written before input files were stored is
/// accepted with a note. Collective.
pub fn check_inputs(
    world: &SimpleCommunicator,
    scene: &Scene,
    path: &Path,
    accepted: &[std::path::PathBuf],
    quiet: bool,
) -> Result<Vec<String>, RunFailure> {
    let local = match world.rank() {
        0 => compare_inputs(scene, path, accepted, quiet),
        _ => Ok(Vec::new()),
    };
    let mut bytes = any_error(world, local).map_err(input)?.join("\n").into_bytes();
    broadcast_vec(world, 0, &mut bytes);
    Ok(String::from_utf8_lossy(&bytes)
        .lines()
        .map(str::to_string)
        .collect())
}

/// [`check_inputs`] on one rank.
fn compare_inputs(
    scene: &Scene,
    path: &Path,
    accepted: &[std::path::PathBuf],
    quiet: bool,
) -> Result<Vec<String>, String> {
    let shown = path.display();
    let Some(stored) = checkpoint::stored_inputs(path).map_err(|e| format!("restart from {shown}: {e}"))?
    else {
        if !quiet && !scene.inputs.is_empty() {
            eprintln!("note: {shown} was written before checkpoints identified the scene's input files: they are not checked");
        }
        return Ok(Vec::new());
    };
    let all = crate::scene::inputs::changed(&stored, &scene.inputs, &[]);
    let refused = crate::scene::inputs::changed(&stored, &scene.inputs, accepted);
    if let Some((key, file, why)) = refused.first() {
        return Err(format!(
            "restart from {shown}: {key} ({file}): {why} since the checkpoint was written, so the \
             restart would continue the run on other input; restore the file, or pass \
             --accept-changed {file} to go on with it"
        ));
    }
    let accepted: Vec<String> = all
        .iter()
        .map(|(key, file, _)| format!("{key}: {file}"))
        .collect();
    for a in accepted.iter().filter(|_| !quiet) {
        eprintln!("warning: --accept-changed: going on with the changed input {a}");
    }
    Ok(accepted)
}

/// Restores `problem` and `report` from the checkpoint `path`: the stage index the run goes on
/// from, and the step control of the stage a step checkpoint resumes inside. Collective.
pub fn restart(
    world: &SimpleCommunicator,
    scene: &Scene,
    path: &Path,
    problem: &mut Problem,
    report: &mut SolveReport,
    verbose: bool,
) -> Result<(usize, Option<StepControl>), RunFailure> {
    let restored = checkpoint::restore(world, path, scene, problem, report);
    let (first_stage, resume) =
        any_error(world, restored).map_err(|m| input(format!("restart from {}: {m}", path.display())))?;
    if verbose {
        eprintln!(
            "{}",
            match resume {
                Some(p) => format!(
                    "restarted from {} in stage {} '{}' at {}",
                    path.display(),
                    first_stage + 1,
                    scene.stages[first_stage].name,
                    super::results::stage_time(&scene.stages[first_stage], p.t)
                ),
                None => format!(
                    "restarted from {} after stage {first_stage} '{}'",
                    path.display(),
                    scene.stages[first_stage - 1].name
                ),
            }
        );
    }
    Ok((first_stage, resume))
}

/// Prints (rank 0, also with `-q`) the PETSc options that no solver object read during the
/// run: a misspelled option (`-ksp_rtoll`) would otherwise be ignored without a word. The
/// options PETSc reads only when it finalizes, after this check ([`read_at_finalize`]), are
/// not named.
pub fn warn_unused_options(rank: i32, petsc: &Petsc) {
    let left = petsc
        .unused_options()
        .map(|l| l.into_iter().filter(|o| !read_at_finalize(o)).collect::<Vec<_>>());
    match left {
        Ok(left) if rank == 0 && !left.is_empty() => eprintln!(
            "warning: PETSc option(s) set but not used by any solver object: {} (misspelled, \
             or for a solver this run does not use)",
            left.join(", ")
        ),
        _ => {}
    }
}

/// Whether the option `-name [value]` is one PETSc reads when it finalizes (`PetscFinalize`:
/// the performance log `-log_view` and its kin, the option and memory reports), so that it
/// is still unread when the run checks for unused options.
pub fn read_at_finalize(option: &str) -> bool {
    let name = option
        .trim_start_matches('-')
        .split_whitespace()
        .next()
        .unwrap_or("");
    name.starts_with("log_")
        || matches!(
            name,
            "options_left" | "options_view" | "malloc_dump" | "malloc_view" | "memory_view" | "objects_dump"
        )
}

#[cfg(test)]
mod finalize_tests {
    use super::read_at_finalize;

    #[test]
    fn the_options_petsc_reads_at_finalize_are_told_apart_from_misspelled_ones() {
        for o in [
            "-log_view",
            "-log_view :perf.txt",
            "-log_view_memory",
            "-options_left",
            "-malloc_dump",
        ] {
            assert!(read_at_finalize(o), "{o}");
        }
        for o in ["-ksp_rtoll 1e-8", "-logview", "-pc_type lu", "-snes_monitor"] {
            assert!(!read_at_finalize(o), "{o}");
        }
    }
}
