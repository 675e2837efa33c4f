//! The `cfrd run` pipeline: scene → mesh → partition → PETSc → the schedule of stages →
//! results.
//!
//! | file | what it holds |
//! |---|---|
//! | [`options`] | what `cfrd run` is asked ([`RunOptions`]) and how a run fails ([`RunFailure`]) |
//! | [`setup`] | the scene loaded, the mesh partitioned, PETSc and the problem started, a checkpoint restored |
//! | [`schedule`] | the stage and step loop |
//! | [`observer`] | the [`Observer`] trait and what the schedule tells at each event |
//! | [`results`] | observer: the results file's steps |
//! | [`checkpoints`] | observer: checkpoint pacing |
//! | [`quake`] | observer: the crest and probe histories of an earthquake and its outputs |
//! | [`modes`] | observer: the mode shapes of a modal analysis |
//! | [`profiles`] | observer: the static figures at the run's end |
//! | [`progress`] | observer: progress lines and bar |
//! | [`summary`] | observer: `summary.json` and the closing lines |
//! | [`mod@bench`] | `cfrd bench solver` |
//!
//! Every input error is decided collectively ([`crate::parallel::any_error`]), so all ranks
//! stop together with exit code 2 and rank 0 prints the message.

pub mod bench;
pub mod checkpoints;
pub mod modes;
pub mod observer;
pub mod options;
pub mod profiles;
pub mod progress;
pub mod quake;
pub mod results;
pub mod schedule;
pub mod setup;
pub mod summary;

pub use bench::{bench_scene, bench_solver};
pub use observer::Observer;
pub use options::{RunFailure, RunOptions, StopAfter};
pub use setup::{construction_bands, load_scene, partition_scene};

use crate::io::summary::{Phase, PhaseTimer, RunSummary};
use crate::parallel::{any_error, EXIT_SOLVER};
use crate::scene::Scene;
use crate::solver::SolveReport;
use mpi::topology::{Communicator, SimpleCommunicator};
use observer::{Run, RunRecord};
use options::{input, io_failure};
use std::time::Instant;

/// Runs a scene file (or the embedded default scene) and writes `results.h5`, `results.xdmf`
/// and `summary.json` into the output directory. Returns the run summary on success.
pub fn run(world: &SimpleCommunicator, opts: &RunOptions) -> Result<RunSummary, RunFailure> {
    let t_all = Instant::now();
    let mut timer = PhaseTimer::new();
    timer.start(Phase::Read);
    let mut scene = load_scene(world, opts.scene.as_deref())?;
    scene.file.solver.monitor |= opts.monitor;
    if let Some(solver) = opts.linear_solver {
        scene.file.solver.linear_solver = solver;
        for dynamic in scene.stages.iter_mut().filter_map(|s| s.dynamic.as_mut()) {
            dynamic.linear_solver = solver;
        }
    }
    if let Some(ratio) = opts.integration_tol_ratio {
        // the same check on every rank: an invalid ratio fails on all alike
        scene
            .cap_integration_tol(ratio)
            .map_err(|e| input(e.to_string()))?;
    }
    run_scene(world, &scene, opts, timer, t_all)
}

/// Runs an already loaded scene (used by `cfrd run` and the benchmarks); `timer` has the read
/// phase running, `t_all` is the start of the run.
pub fn run_scene(
    world: &SimpleCommunicator,
    scene: &Scene,
    opts: &RunOptions,
    mut timer: PhaseTimer,
    t_all: Instant,
) -> Result<RunSummary, RunFailure> {
    let rank = world.rank();
    let verbose = rank == 0 && opts.verbose;
    if verbose {
        announce(world, scene);
    }
    let out_dir = opts
        .out_dir
        .clone()
        .unwrap_or_else(|| scene.file.output.dir.clone());
    any_error(world, std::fs::create_dir_all(&out_dir))
        .map_err(|m| io_failure(&format!("output directory {}", out_dir.display()), m))?;
    let (petsc, mut problem) = setup::start_solver(world, scene, &opts.petsc_options, &mut timer)?;
    let mut report = SolveReport::default();
    // a restart continues after the checkpoint's last stage, or inside the stage of a step
    // checkpoint (input error if it does not fit)
    let (first_stage, resume) = match &opts.restart {
        Some(path) => setup::restart(world, scene, path, &mut problem, &mut report, verbose)?,
        None => (0, None),
    };
    // the files the scene reads are those the checkpoint was written with, or accepted
    let accepted_changed = match &opts.restart {
        Some(path) => setup::check_inputs(world, scene, path, &opts.accept_changed, !verbose)?,
        None => Vec::new(),
    };
    let mut pacer = checkpoints::CheckpointPacer::new(scene, opts, first_stage, &out_dir)?;
    timer.start(Phase::Output);
    let results_path = out_dir.join("results.h5");
    let results = match &opts.restart {
        Some(checkpoint) => {
            let at = results::RestartPoint {
                checkpoint,
                stages_done: first_stage,
                within: resume.as_ref(),
            };
            results::continue_results(world, scene, &problem, &results_path, &at, !verbose)?
        }
        None => results::create_results(world, scene, &problem, &results_path)?,
    };
    timer.stop();
    let plan = pacer.plan(first_stage, resume, verbose);
    let mut summary = summary::SummaryWriter {
        verbose,
        started: t_all,
        restarted: opts.restart.is_some(),
        summary: None,
    };
    let mut run = Run {
        world,
        scene,
        problem: &mut problem,
        report: &mut report,
        timer: &mut timer,
        results: Some(results),
        results_path,
        out_dir,
        record: RunRecord {
            first_stage,
            accepted_changed,
            ..RunRecord::default()
        },
    };
    let failure = schedule::run_schedule(
        &mut run,
        &mut [
            &mut progress::Progress::new(verbose, scene.stages.len()),
            &mut modes::ModesWriter { verbose },
            &mut quake::QuakeRecorder::new(scene),
            &mut results::ResultsWriter::new(scene),
            &mut pacer,
            &mut profiles::ProfilesWriter { verbose },
            &mut summary,
        ],
        plan,
    )?;
    if let Some(m) = failure {
        return Err(RunFailure {
            code: EXIT_SOLVER,
            message: format!(
                "{m} (results of the completed stages are in {})",
                run.results_path.display()
            ),
        });
    }
    drop(problem);
    setup::warn_unused_options(rank, &petsc);
    drop(petsc);
    summary
        .summary
        .ok_or_else(|| io_failure("writing the run summary", "no summary"))
}

/// The run's first progress line: the scene and its size.
fn announce(world: &SimpleCommunicator, scene: &Scene) {
    eprintln!(
        "scene '{}': {} nodes, {} elements, {} DOFs, {} ranks",
        scene.file.name,
        scene.mesh.num_nodes(),
        scene.mesh.elements.len(),
        3 * scene.mesh.num_nodes(),
        world.size()
    );
}
