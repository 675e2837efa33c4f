//! The `cfrd run` pipeline: scene → mesh → partition → PETSc → solve → results.
//!
//! Every input error is decided collectively ([`crate::parallel::any_error`]), so all ranks
//! stop together with exit code 2 and rank 0 prints the message.

use crate::linalg::petsc::Petsc;
use crate::parallel::{any_error, broadcast_u32, EXIT_INPUT, EXIT_SOLVER};
use crate::scene::Scene;
use crate::solver::discretization::Discretization;
use crate::solver::statics::{mesh_cells, SolveReport, StaticProblem};
use mpi::topology::{Communicator, SimpleCommunicator};
use partition::{partition_elements, Partition, PartitionFile};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The embedded default scene.
pub const DEFAULT_SCENE: &str = include_str!("scene/default.yaml");

/// A failed run: message and process exit code.
#[derive(Debug)]
pub struct RunFailure {
    /// Exit code (2 input, 3 solver).
    pub code: i32,
    /// Message (printed by rank 0).
    pub message: String,
}

fn input(message: String) -> RunFailure {
    RunFailure {
        code: EXIT_INPUT,
        message,
    }
}

/// Options of `cfrd run`.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Scene file; `None` runs the embedded default scene.
    pub scene: Option<PathBuf>,
    /// Output directory overriding the scene's.
    pub out_dir: Option<PathBuf>,
    /// PETSc options from the command line (override the scene's).
    pub petsc_options: Vec<String>,
    /// Print progress (rank 0).
    pub verbose: bool,
}

/// Loads a scene (or the embedded default) collectively.
pub fn load_scene(world: &SimpleCommunicator, scene: Option<&Path>) -> Result<Scene, RunFailure> {
    let local = match scene {
        Some(p) => Scene::load(p),
        None => Scene::from_str(DEFAULT_SCENE, "<embedded default scene>", Path::new(".")),
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
            Some(p) => PartitionFile::read(p, &cells, n_nodes, nparts).map_err(|e| e.to_string()),
            None => partition_elements(&cells, n_nodes, nparts).map_err(|e| e.to_string()),
        }
    } else {
        Ok(Vec::new())
    };
    let mut part = any_error(world, local).map_err(input)?;
    broadcast_u32(world, 0, &mut part);
    Ok(Partition::new(&cells, n_nodes, nparts, part))
}

/// Runs a static analysis. Returns the run summary on success.
pub fn run(world: &SimpleCommunicator, opts: &RunOptions) -> Result<serde_json::Value, RunFailure> {
    let rank = world.rank();
    let say = |s: &str| {
        if rank == 0 && opts.verbose {
            eprintln!("{s}");
        }
    };
    let t_all = Instant::now();
    let t = Instant::now();
    let scene = load_scene(world, opts.scene.as_deref())?;
    let t_read = t.elapsed().as_secs_f64();
    say(&format!(
        "scene '{}': {} nodes, {} elements, {} ranks",
        scene.file.name,
        scene.mesh.num_nodes(),
        scene.mesh.elements.len(),
        world.size()
    ));

    let t = Instant::now();
    let partition = partition_scene(world, &scene)?;
    let cells = mesh_cells(&scene.mesh);
    let disc = Discretization::new(&cells, scene.mesh.num_nodes(), partition, rank as usize);
    let t_partition = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let petsc = Petsc::initialize(world).map_err(|e| RunFailure {
        code: EXIT_SOLVER,
        message: e.to_string(),
    })?;
    let opt_result = petsc
        .insert_options(&scene.file.solver.petsc_options)
        .and_then(|_| petsc.insert_options(&opts.petsc_options.join(" ")));
    any_error(world, opt_result).map_err(|m| input(format!("PETSc options: {m}")))?;
    let setup = StaticProblem::new(&petsc, &scene, cells, disc);
    let mut problem = any_error(world, setup).map_err(|m| input(format!("setting up the solver: {m}")))?;
    let t_setup = t.elapsed().as_secs_f64();

    say("solving static equilibrium ...");
    let mut report = SolveReport::default();
    let solved = problem.solve_step(1.0, &mut report);
    any_error(world, solved).map_err(|m| RunFailure {
        code: EXIT_SOLVER,
        message: m,
    })?;
    say(&format!(
        "converged: {} Newton iterations, KSP iterations {:?}",
        report.newton_iterations, report.ksp_iterations
    ));
    let results = any_error(world, problem.results()).map_err(|m| RunFailure {
        code: EXIT_SOLVER,
        message: m,
    })?;
    let _ = results;
    drop(problem);
    drop(petsc);
    Ok(serde_json::json!({
        "scene": scene.file.name,
        "ranks": world.size(),
        "nodes": scene.mesh.num_nodes(),
        "elements": scene.mesh.elements.len(),
        "dofs": 3 * scene.mesh.num_nodes(),
        "newton_iterations": report.newton_iterations,
        "ksp_iterations": report.ksp_iterations,
        "residuals": report.residuals,
        "seconds": {
            "read": t_read, "partition": t_partition, "setup": t_setup,
            "assembly": report.assembly_seconds, "solve": report.solve_seconds,
            "total": t_all.elapsed().as_secs_f64(),
        },
    }))
}
