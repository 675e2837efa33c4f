//! The `cfrd run` pipeline: scene → mesh → partition → PETSc → solve → results.
//!
//! Every input error is decided collectively ([`crate::parallel::any_error`]), so all ranks
//! stop together with exit code 2 and rank 0 prints the message.

use crate::io::checkpoint::{self, CHECKPOINT_FILE};
use crate::io::hdf5_out::{strain_output_components, OwnedMesh, ResultsFile, StepInfo};
use crate::io::pacing::StageEndWrites;
use crate::io::summary::{ModalSummary, Phase, PhaseTimer, RunSummary, StageSeconds};
use crate::linalg::petsc::Petsc;
use crate::parallel::{any_error, broadcast_vec, EXIT_INPUT, EXIT_IO, EXIT_SOLVER};
use crate::scene::schema::CheckpointMode;
use crate::scene::Scene;
use crate::solver::discretization::Discretization;
use crate::solver::{mesh_cells, LocalResults, Problem, SolveError, SolveReport, StepControl};
use mpi::topology::{Communicator, SimpleCommunicator};
use partition::{partition_for_assembly, Partition, PartitionFile};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The embedded default scene.
pub const DEFAULT_SCENE: &str = include_str!("../inputs/scenes/default_dam.yaml");

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
    /// Checkpoint to restart from (`--restart`): the run continues after its last stage.
    pub restart: Option<PathBuf>,
    /// End the run cleanly after a stage, once its results and checkpoint are written
    /// (`--stop-after-stage`): a run in parts under a job time limit.
    pub stop_after_stage: Option<StopAfter>,
    /// When to write checkpoints, overriding the scene's `output.checkpoint` (`--checkpoint`;
    /// not part of the scene's hash, so a run continued with step checkpoints still restarts
    /// from its stage checkpoints).
    pub checkpoint: Option<CheckpointMode>,
    /// With step checkpoints: write them after every N-th converged load step of the run only
    /// (`--checkpoint-every`; counted by the run's converged steps, which a checkpoint keeps,
    /// so a restarted run writes them where the uninterrupted one does). `None`: every step.
    pub checkpoint_every: Option<u32>,
    /// Print every Newton iteration's residual and the reason and place of every cut-back
    /// (`--monitor`), as the scene's `solver.monitor` does, without changing the scene (its
    /// hash), so a run restarted from a checkpoint can be watched.
    pub monitor: bool,
    /// Cap the substepping tolerance of every GP material at this multiple of the Newton
    /// tolerance (`--integration-tol-ratio`, see
    /// [`crate::scene::schema::SolverSpec::integration_tol_ratio`]), without changing the scene
    /// (its hash), so a run stalled at the integration noise continues from its checkpoint.
    pub integration_tol_ratio: Option<f64>,
    /// The linear solver instead of the scene's `solver.linear_solver` (`--linear-solver`),
    /// without changing the scene (its hash), so a run continues from its checkpoint on
    /// another solver.
    pub linear_solver: Option<crate::scene::schema::LinearSolver>,
}

/// Where a run in parts ends (`--stop-after-stage K` or `+N`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopAfter {
    /// After stage K of the schedule (1-based).
    Stage(usize),
    /// After the N-th stage this run runs (counted from the restart's stage, if any), or at the
    /// end of the schedule if that comes first.
    Stages(usize),
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

/// Runs a static analysis and writes `results.h5`, `results.xdmf` and `summary.json` into the
/// output directory. Returns the run summary on success.
pub fn run(world: &SimpleCommunicator, opts: &RunOptions) -> Result<RunSummary, RunFailure> {
    let t_all = Instant::now();
    let mut timer = PhaseTimer::new();
    timer.start(Phase::Read);
    let mut scene = load_scene(world, opts.scene.as_deref())?;
    scene.file.solver.monitor |= opts.monitor;
    if let Some(solver) = opts.linear_solver {
        scene.file.solver.linear_solver = solver;
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
    let say = |s: &str| {
        if rank == 0 && opts.verbose {
            eprintln!("{s}");
        }
    };
    say(&format!(
        "scene '{}': {} nodes, {} elements, {} DOFs, {} ranks",
        scene.file.name,
        scene.mesh.num_nodes(),
        scene.mesh.elements.len(),
        3 * scene.mesh.num_nodes(),
        world.size()
    ));
    let out_dir = opts
        .out_dir
        .clone()
        .unwrap_or_else(|| scene.file.output.dir.clone());
    any_error(world, std::fs::create_dir_all(&out_dir)).map_err(|m| RunFailure {
        code: EXIT_IO,
        message: format!("output directory {}: {m}", out_dir.display()),
    })?;

    timer.start(Phase::Partition);
    let partition = partition_scene(world, scene)?;
    let cells = mesh_cells(&scene.mesh);
    let disc = Discretization::new(&cells, scene.mesh.num_nodes(), partition, rank as usize);

    timer.start(Phase::Setup);
    let petsc = Petsc::initialize(world).map_err(|e| RunFailure {
        code: EXIT_SOLVER,
        message: e.to_string(),
    })?;
    let opt_result = petsc
        .insert_options(&scene.file.solver.petsc_options)
        .and_then(|_| petsc.insert_options(&opts.petsc_options.join(" ")));
    any_error(world, opt_result).map_err(|m| input(format!("PETSc options: {m}")))?;
    let setup = Problem::new(&petsc, world, scene, cells, disc);
    let mut problem = any_error(world, setup).map_err(|m| input(format!("setting up the solver: {m}")))?;
    timer.stop();

    let sopts = &scene.file.solver;
    let mut report = SolveReport::default();
    // a restart continues after the checkpoint's last stage, or inside the stage of a step
    // checkpoint (input error if it does not fit)
    let mut first_stage = 0;
    let mut resume = None;
    if let Some(path) = &opts.restart {
        let restored = checkpoint::restore(world, path, scene, &mut problem, &mut report);
        (first_stage, resume) =
            any_error(world, restored).map_err(|m| input(format!("restart from {}: {m}", path.display())))?;
        say(&match resume {
            Some(p) => format!(
                "restarted from {} in stage {} '{}' at λ = {:.3}",
                path.display(),
                first_stage + 1,
                scene.stages[first_stage].name,
                p.t
            ),
            None => format!(
                "restarted from {} after stage {first_stage} '{}'",
                path.display(),
                scene.stages[first_stage - 1].name
            ),
        });
    }
    let mode = opts.checkpoint.or(scene.file.output.checkpoint);
    let checkpoints = match mode {
        Some(mode) => mode != CheckpointMode::None,
        None => !scene.file.stages.is_empty(),
    };
    let step_checkpoints = mode == Some(CheckpointMode::Step);
    let checkpoint_every = opts.checkpoint_every.unwrap_or(1).max(1);
    let stop_after_stage = opts.stop_after_stage.map(|s| match s {
        StopAfter::Stage(k) => k,
        StopAfter::Stages(n) => (first_stage + n).min(scene.stages.len()),
    });
    if let Some(stop) = stop_after_stage {
        let n = scene.stages.len();
        if !checkpoints {
            return Err(input(format!(
                "--stop-after-stage {stop}: the run writes no checkpoints (output.checkpoint or \
                 --checkpoint), so it could not be continued"
            )));
        }
        if stop <= first_stage || stop > n {
            return Err(input(format!(
                "--stop-after-stage {stop}: not one of the stages this run runs ({} to {n})",
                first_stage + 1
            )));
        }
    }
    let ckpt = out_dir.join(CHECKPOINT_FILE);
    let mut ckpt_seconds = 0.0;
    timer.start(Phase::Output);
    let h5 = out_dir.join("results.h5");
    let created = ResultsFile::create(world, &h5, &scene.file.name).and_then(|mut f| {
        let d = problem.discretization();
        f.write_mesh(&OwnedMesh::from_mesh(
            &scene.mesh,
            d.owned_nodes.clone(),
            d.owned_elements.clone(),
        ))?;
        Ok(f)
    });
    let mut file = any_error(world, created).map_err(|m| RunFailure {
        code: EXIT_IO,
        message: format!("writing results: {m}"),
    })?;
    timer.stop();
    let n_stages = scene.stages.len();
    let has_interfaces = scene.block_interface.iter().any(Option::is_some);
    let mut failure = None;
    let mut stages_written = 0usize;
    let mut stopped_after = None;
    let mut modal = None;
    // without a terminal (nohup, a cluster job's log) the bar is not drawn: a line per load step
    let step_lines = rank == 0 && opts.verbose && !std::io::IsTerminal::is_terminal(&std::io::stderr());
    // the crest's motion and the probes are recorded at every step of the first dynamic stage
    // (crate::quake, crate::quake_probes)
    let first_dynamic = scene.stages.iter().position(|s| s.dynamic.is_some());
    let recorder = QuakeRecorder::new(scene);
    let mut writes = StageEndWrites::new();
    for (k, stage) in scene.stages.iter().enumerate().skip(first_stage) {
        let stage_start = Instant::now();
        let counts_at_start = stage_counts(&report);
        let growth = match stage.step_growth {
            1 => String::new(),
            g => format!(", easy ones growing up to {g} times"),
        };
        say(&format!(
            "stage {}/{n_stages} '{}': {} load step(s){growth}",
            k + 1,
            stage.name,
            stage.load_steps
        ));
        // the stage of a step checkpoint continues where it stood (restore resumed it)
        let fresh = resume.is_none();
        let mut path = match resume.take() {
            Some(p) => p,
            None => {
                let begun = problem.begin_stage(k);
                if let Err(m) = any_error(world, begun) {
                    failure = Some(m);
                    break;
                }
                if let Some(modes) = problem.modes() {
                    timer.start(Phase::Output);
                    modal = Some(write_modes(world, scene, &problem, modes, &out_dir)?);
                    timer.stop();
                    let hz: Vec<String> = modes.frequencies_hz.iter().map(|f| format!("{f:.4}")).collect();
                    say(&format!(
                        "modal analysis: {} Hz in {:.1} s",
                        hz.join(", "),
                        modes.seconds
                    ));
                }
                StepControl::growing(stage.t_end(), stage.load_steps, stage.step_growth)
            }
        };
        let mut steps_in_stage = 0u32;
        let bar = progress_bar(rank == 0 && opts.verbose, stage.load_steps as u64);
        let quake = Some(k) == first_dynamic;
        let mut solved = if quake && fresh {
            recorder.record_start(&mut problem, &mut report)
        } else {
            Ok(())
        };
        while solved.is_ok() && !path.done() {
            solved = problem.advance(&mut path, sopts.max_cutbacks, &mut report);
            if solved.is_err() {
                break;
            }
            steps_in_stage += 1;
            if quake {
                solved = recorder.record_step(&mut problem, path.t, &mut report);
                if solved.is_err() {
                    break;
                }
            }
            let at = stage_time(stage, path.t);
            if step_lines {
                eprintln!(
                    "  {at} after {:.0} s ({} Newton iterations, {} cut-backs in the run so far)",
                    stage_start.elapsed().as_secs_f64(),
                    report.newton_iterations,
                    report.cutbacks
                );
            }
            bar.set_position((path.t / path.t_end * stage.load_steps as f64).round() as u64);
            bar.set_message(format!(
                "{at}, Newton {}, cut-backs {}",
                report.newton_iterations, report.cutbacks
            ));
            let every = stage.dynamic.as_ref().map_or(0, |d| d.output_every);
            if every > 0 && steps_in_stage.is_multiple_of(every) && !path.done() {
                timer.start(Phase::Output);
                let info = step_info(k, stage, path.t, path.t_end);
                write_results(world, &mut problem, &mut file, info, has_interfaces)?;
                timer.stop();
            }
            if step_checkpoints && !path.done() && report.steps.is_multiple_of(checkpoint_every) {
                timer.start(Phase::Output);
                ckpt_seconds += write_checkpoint(world, &ckpt, scene, &problem, &report, Some(path))?;
                timer.stop();
                // the restart starts with a fresh preconditioner here; so does this run
                solved = problem.fresh_preconditioner();
            }
        }
        bar.finish_and_clear();
        if let Err(m) = any_error(world, solved.and_then(|_| problem.end_stage())) {
            failure = Some(format!("stage '{}': {m}", stage.name));
            break;
        }
        timer.start(Phase::Output);
        let info = step_info(k, stage, path.t_end, path.t_end);
        write_results(world, &mut problem, &mut file, info, has_interfaces)?;
        stages_written += 1;
        let counts = stage_counts(&report);
        report.stage_seconds.push(StageSeconds {
            stage: stage.name.clone(),
            seconds: stage_start.elapsed().as_secs_f64(),
            steps: counts.0 - counts_at_start.0,
            newton_iterations: counts.1 - counts_at_start.1,
            ksp_iterations: counts.2 - counts_at_start.2,
        });
        // stage checkpoints are paced (crate::io::pacing); step checkpoints are not
        let must = step_checkpoints || k + 1 == n_stages || stop_after_stage == Some(k + 1);
        if checkpoints && writes.due(world, must) {
            let began = Instant::now();
            // the results of the completed stages are published before the checkpoint that
            // follows them: a run killed later leaves both (a stage in both a killed part's and
            // the next part's results is one run again after a kill between the two writes)
            any_error(world, file.publish()).map_err(|m| RunFailure {
                code: EXIT_IO,
                message: format!("writing results: {m}"),
            })?;
            ckpt_seconds += write_checkpoint(world, &ckpt, scene, &problem, &report, None)?;
            writes.wrote(world, began);
        }
        timer.stop();
        if stop_after_stage == Some(k + 1) && k + 1 < n_stages {
            say(&format!(
                "stopped after stage {} of {n_stages} (--stop-after-stage); continue with --restart {}",
                k + 1,
                ckpt.display()
            ));
            stopped_after = Some((k + 1) as u64);
            break;
        }
    }
    timer.add(
        Phase::Assembly,
        std::time::Duration::from_secs_f64(report.assembly_seconds),
    );
    timer.add(
        Phase::Solve,
        std::time::Duration::from_secs_f64(report.solve_seconds),
    );
    // the stages completed so far are kept, also when a later stage failed
    timer.start(Phase::Output);
    any_error(world, file.close()).map_err(|m| RunFailure {
        code: EXIT_IO,
        message: format!("writing results: {m}"),
    })?;
    write_quake(world, scene, &h5, &report, &out_dir, failure.as_deref())?;
    // the profiles need at least one completed stage; a failure to write them never hides the
    // failure of a stage
    match &scene.file.output.profiles {
        Some(_) if stages_written == 0 => say("profiles: not written, no stage completed"),
        Some(spec) => {
            // rank 0 reads the closed results file back (serial HDF5) and writes the tables and
            // plots
            let written = if rank == 0 {
                write_profiles_from_results(scene, spec, std::slice::from_ref(&h5), &out_dir)
            } else {
                Ok(Vec::new())
            };
            match any_error(world, written) {
                Ok(files) => say(&format!(
                    "profiles: {} file(s) in {}",
                    files.len(),
                    out_dir.display()
                )),
                Err(m) => {
                    let stage = failure.as_ref().map(|f| format!("{f}; ")).unwrap_or_default();
                    return Err(RunFailure {
                        code: if failure.is_some() { EXIT_SOLVER } else { EXIT_IO },
                        message: format!("{stage}writing the profiles: {m}"),
                    });
                }
            }
        }
        None => {}
    }
    if let Some(m) = failure {
        return Err(RunFailure {
            code: EXIT_SOLVER,
            message: format!("{m} (results of the completed stages are in {})", h5.display()),
        });
    }
    say(&format!(
        "converged: {} step(s), {} Newton iteration(s), {} cut-back(s), {} KSP iterations{}",
        report.steps,
        report.newton_iterations,
        report.cutbacks,
        report.ksp_iterations.iter().sum::<u32>(),
        if report.factorizations > 0 {
            format!(", {} factorization(s)", report.factorizations)
        } else {
            String::new()
        }
    ));
    let counts = problem.interface_counts();
    let element_seconds = problem.element_seconds();
    if counts.points > 0 {
        say(&format!(
            "interfaces: {} point(s), {} open, {} slipping",
            counts.points, counts.open, counts.slipping
        ));
    }
    timer.stop();
    drop(problem);
    warn_unused_options(rank, &petsc);
    drop(petsc);

    let mut summary = RunSummary::new(world, &scene.file.name);
    summary.nodes = scene.mesh.num_nodes() as u64;
    summary.elements = scene.mesh.elements.len() as u64;
    summary.dofs = 3 * summary.nodes;
    summary.phase_seconds = timer.seconds().max_over_ranks(world);
    summary.total_seconds = crate::parallel::max_f64(world, t_all.elapsed().as_secs_f64());
    summary.ksp_iterations = report.ksp_iterations.iter().map(|&k| k as u64).sum();
    summary.newton_iterations = report.newton_iterations as u64;
    summary.residual_evaluations = report.residual_evaluations;
    summary.steps = report.steps as u64;
    summary.cutbacks = report.cutbacks as u64;
    summary.predictions_dropped = report.predictions_dropped as u64;
    summary.newton_per_step = report.newton_per_step.clone();
    summary.factorizations = report.factorizations;
    summary.multigrid_builds = report.multigrid_builds;
    summary.interface_points = counts.points;
    summary.interface_open = counts.open;
    summary.interface_slipping = counts.slipping;
    summary.restarted_after_stage = opts.restart.as_ref().map(|_| first_stage as u64);
    summary.stopped_after_stage = stopped_after;
    summary.checkpoint_seconds = crate::parallel::max_f64(world, ckpt_seconds);
    summary.stage_seconds = report.stage_seconds.clone();
    summary.modal = modal;
    summary.gather_element_seconds(world, element_seconds);
    summary.gather_peak_memory(world);
    let written = match rank {
        0 => summary.write_json(&out_dir.join("summary.json")),
        _ => Ok(()),
    };
    any_error(world, written).map_err(|m| RunFailure {
        code: EXIT_IO,
        message: format!("writing the run summary: {m}"),
    })?;
    say(&format!(
        "results: {} (ParaView: {}), summary: {}",
        h5.display(),
        out_dir.join("results.xdmf").display(),
        out_dir.join("summary.json").display()
    ));
    Ok(summary)
}

/// Prints (rank 0, also with `-q`) the PETSc options that no solver object read during the
/// run: a misspelled option (`-ksp_rtoll`) would otherwise be ignored without a word.
fn warn_unused_options(rank: i32, petsc: &Petsc) {
    match petsc.unused_options() {
        Ok(left) if rank == 0 && !left.is_empty() => eprintln!(
            "warning: PETSc option(s) set but not used by any solver object: {} (misspelled, \
             or for a solver this run does not use)",
            left.join(", ")
        ),
        _ => {}
    }
}

/// Writes the checkpoint ([`checkpoint::write`]) and returns the seconds it took. Collective.
fn write_checkpoint(
    world: &SimpleCommunicator,
    ckpt: &Path,
    scene: &Scene,
    problem: &Problem,
    report: &SolveReport,
    within: Option<StepControl>,
) -> Result<f64, RunFailure> {
    let t0 = Instant::now();
    let written = checkpoint::write(world, ckpt, scene, problem, report, within);
    any_error(world, written).map_err(|m| RunFailure {
        code: EXIT_IO,
        message: format!("writing the checkpoint {}: {m}", ckpt.display()),
    })?;
    Ok(t0.elapsed().as_secs_f64())
}

/// Writes the crest history and summary of a dynamic stage ([`crate::quake`]) and the seed's
/// dynamic figures ([`crate::quake_figures`], with the scene's `output.profiles` settings or
/// their defaults) from the closed results file (rank 0; collective decision). A failure to write them never hides the failure
/// of a stage (`failure`).
fn write_quake(
    world: &SimpleCommunicator,
    scene: &Scene,
    h5: &Path,
    report: &SolveReport,
    out_dir: &Path,
    failure: Option<&str>,
) -> Result<(), RunFailure> {
    if scene.stages.iter().all(|s| s.dynamic.is_none()) {
        return Ok(());
    }
    // a run whose first stage failed wrote no step to draw from
    let written = if world.rank() != 0 || lacks_steps(h5) {
        Ok(Vec::new())
    } else {
        let spec = scene.file.output.profiles.clone().unwrap_or_default();
        crate::quake::write_quake_outputs(scene, h5, &report.crest, out_dir).and_then(|mut files| {
            let parts = [h5.to_path_buf()];
            files.extend(crate::quake_figures::write_quake_figures(
                scene,
                &spec,
                &parts,
                &report.probes,
                out_dir,
            )?);
            Ok(files)
        })
    };
    any_error(world, written).map(|_| ()).map_err(|m| RunFailure {
        code: if failure.is_some() { EXIT_SOLVER } else { EXIT_IO },
        message: match failure {
            Some(f) => format!("{f}; writing the earthquake outputs: {m}"),
            None => format!("writing the earthquake outputs: {m}"),
        },
    })
}

/// Whether the results file `h5` opens and holds no step (a run whose first stage failed); a
/// file that does not open is left to the writers, which name the error.
fn lacks_steps(h5: &Path) -> bool {
    crate::io::compare::open(h5).is_ok_and(|f| {
        !f.link_exists("steps") || crate::io::compare::step_names(&f, h5).is_ok_and(|n| n.is_empty())
    })
}

/// What a run records at every time step of its first dynamic stage: the crest's motion
/// ([`crate::quake`]) and the probes' state ([`crate::quake_probes`]), into the run's report.
struct QuakeRecorder {
    crest: usize,
    probes: Vec<crate::quake_probes::QuakeProbe>,
    /// The time step of the first dynamic stage: the probes' times are put on its grid, as
    /// those of the results steps are ([`crate::quake_figures::on_time_grid`]).
    dt: f64,
}

impl QuakeRecorder {
    fn new(scene: &Scene) -> Self {
        let spec = scene.file.output.profiles.clone().unwrap_or_default();
        let dt = scene
            .stages
            .iter()
            .find_map(|s| s.dynamic.as_ref())
            .map_or(0.0, |d| d.dt());
        QuakeRecorder {
            crest: crate::quake::crest_node(scene),
            probes: crate::quake_probes::probe_elements(&scene.mesh, &spec),
            dt,
        }
    }

    /// The probes at t = 0, the state before the quake. Collective.
    fn record_start(&self, problem: &mut Problem, report: &mut SolveReport) -> Result<(), SolveError> {
        report.probes.clear();
        self.record_probes(problem, 0.0, report)
    }

    /// The crest and the probes after a converged step at time `t`. Collective.
    fn record_step(&self, problem: &mut Problem, t: f64, report: &mut SolveReport) -> Result<(), SolveError> {
        report.crest.push(problem.node_motion(self.crest, t)?);
        let on_grid = crate::quake_figures::on_time_grid(t, self.dt);
        self.record_probes(problem, on_grid, report)
    }

    fn record_probes(
        &self,
        problem: &mut Problem,
        t: f64,
        report: &mut SolveReport,
    ) -> Result<(), SolveError> {
        if self.probes.is_empty() {
            return Ok(());
        }
        let elements: Vec<usize> = self.probes.iter().map(|p| p.element).collect();
        let states = problem.element_states(&elements)?;
        report
            .probes
            .push(crate::quake_probes::probe_row(t, &self.probes, &states));
        Ok(())
    }
}

/// Writes the mode shapes of `modes` into `modes.h5` / `modes.xdmf` of `out_dir`, one step
/// per mode (time = mode number, so ParaView steps through them), and returns their summary
/// ([`crate::scene::modal`]). Collective.
fn write_modes(
    world: &SimpleCommunicator,
    scene: &Scene,
    problem: &Problem,
    modes: &crate::solver::Modes,
    out_dir: &Path,
) -> Result<ModalSummary, RunFailure> {
    let written = ResultsFile::create(world, out_dir.join("modes.h5"), &scene.file.name).and_then(|mut f| {
        let d = problem.discretization();
        f.write_mesh(&OwnedMesh::from_mesh(
            &scene.mesh,
            d.owned_nodes.clone(),
            d.owned_elements.clone(),
        ))?;
        for (i, (freq, shape)) in modes.frequencies_hz.iter().zip(&modes.shapes).enumerate() {
            f.begin_step(StepInfo {
                time: (i + 1) as f64,
                stage: modes.stage.clone(),
                label: format!("mode {} at {freq:.6} Hz", i + 1),
            })?;
            f.write_node_field("mode_shape", "-", 3, shape)?;
        }
        f.close()
    });
    any_error(world, written).map_err(|m| RunFailure {
        code: EXIT_IO,
        message: format!("writing the mode shapes: {m}"),
    })?;
    Ok(ModalSummary {
        stage: modes.stage.clone(),
        frequencies_hz: modes.frequencies_hz.clone(),
        periods_s: modes.frequencies_hz.iter().map(|f| 1.0 / f).collect(),
        seconds: modes.seconds,
    })
}

/// Where a stage stands, for progress lines: "λ = 0.375" or "t = 3.20 s".
fn stage_time(stage: &crate::scene::Stage, t: f64) -> String {
    match stage.dynamic {
        Some(_) => format!("t = {t:.2} s"),
        None => format!("λ = {t:.3}"),
    }
}

/// The results step of stage `k` (index) at its time `t` of `t_end`: the step time is
/// k + t/t_end, so the stages follow each other in order in ParaView and a stage's end is at
/// its number.
fn step_info(k: usize, stage: &crate::scene::Stage, t: f64, t_end: f64) -> StepInfo {
    let label = if t >= t_end {
        format!("end of stage {}", k + 1)
    } else {
        format!("stage {} at {}", k + 1, stage_time(stage, t))
    };
    StepInfo {
        time: if t >= t_end {
            (k + 1) as f64
        } else {
            k as f64 + t / t_end
        },
        stage: stage.name.clone(),
        label,
    }
}

/// Collects the results of the committed state and writes them as the step `info`
/// (collective).
fn write_results(
    world: &SimpleCommunicator,
    problem: &mut Problem,
    file: &mut ResultsFile,
    info: StepInfo,
    has_interfaces: bool,
) -> Result<(), RunFailure> {
    let written = problem
        .results()
        .map_err(|e| e.to_string())
        .and_then(|res| write_step(file, info, &res, has_interfaces).map_err(|e| e.to_string()));
    any_error(world, written).map_err(|m| RunFailure {
        code: EXIT_IO,
        message: format!("writing results: {m}"),
    })
}

/// Writes the fields of a converged state as one step (collective; input order, any rank
/// count).
fn write_step(
    file: &mut ResultsFile,
    info: StepInfo,
    res: &LocalResults,
    has_interfaces: bool,
) -> Result<(), crate::io::IoError> {
    file.begin_step(info)?;
    let flat3 = |v: &[[f64; 3]]| v.iter().flatten().copied().collect::<Vec<f64>>();
    file.write_node_field("displacement", "m", 3, &flat3(&res.displacement))?;
    file.write_node_field("reaction", "N", 3, &flat3(&res.reaction))?;
    if let Some(m) = &res.motion {
        file.write_node_field("velocity", "m/s", 3, &flat3(&m.velocity))?;
        file.write_node_field("acceleration", "m/s^2", 3, &flat3(&m.acceleration))?;
    }
    let stress: Vec<f64> = res.stress.iter().flat_map(|s| s.0.iter().copied()).collect();
    file.write_element_field("stress", "Pa", 6, &stress)?;
    let strain: Vec<f64> = res.strain.iter().flat_map(strain_output_components).collect();
    file.write_element_field("strain", "-", 6, &strain)?;
    if has_interfaces {
        // only a scene with interface or joint blocks writes their fields (zero on solids)
        let traction: Vec<f64> = res.interface.iter().flat_map(|o| o.traction).collect();
        file.write_element_field("interface_traction", "Pa", 3, &traction)?;
        file.write_element_field("interface_jump", "m", 3, &flat3(&res.jump))?;
        let slip: Vec<f64> = res.interface.iter().flat_map(|o| o.shear).collect();
        file.write_element_field("interface_slip", "m", 2, &slip)?;
        let opening: Vec<f64> = res.interface.iter().map(|o| o.opening).collect();
        file.write_element_field("interface_opening", "m", 1, &opening)?;
    }
    Ok(())
}

/// Reads every stage of the closed results files `h5s` (serial HDF5), in order, and writes the
/// profile tables and plots of [`crate::profiles`] into `dir`. Several files are the parts of a
/// run restarted from checkpoints (`cfrd profiles`): their stages are joined in the order given,
/// and a stage found again in a later file replaces the earlier one (a part killed after it
/// published a stage's results but before that stage's checkpoint, so the next part ran the
/// stage again; or a second restart from the same checkpoint).
pub fn write_profiles_from_results(
    scene: &Scene,
    spec: &crate::profiles::ProfilesSpec,
    h5s: &[PathBuf],
    dir: &Path,
) -> Result<Vec<PathBuf>, String> {
    use crate::io::compare::{open, stage_name, step_names};
    let mut stages: Vec<crate::profiles::StageFields> = Vec::new();
    for h5 in h5s {
        let file = open(h5)?;
        let elements = file
            .dataset("/mesh/element_ids")
            .map(|d| d.size())
            .map_err(|e| format!("{}: /mesh/element_ids: {e}", h5.display()))?;
        if elements != scene.mesh.elements.len() {
            return Err(format!(
                "{}: {elements} elements, the scene's mesh has {}: results of another scene?",
                h5.display(),
                scene.mesh.elements.len()
            ));
        }
        for name in step_names(&file, h5)? {
            let g = file.group(&format!("/steps/{name}")).map_err(|e| e.to_string())?;
            let stage = stage_name(&g).unwrap_or_else(|| name.clone());
            // Figs. 7-11 are the static states: a dynamic stage's steps are not theirs
            let dynamic = scene
                .stages
                .iter()
                .any(|s| s.name == stage && s.dynamic.is_some());
            if dynamic {
                continue;
            }
            stages.retain(|s| s.name != stage);
            stages.push(crate::profiles::StageFields::read(&g, h5, stage)?);
        }
    }
    // a part that ran only dynamic stages (restarted into a quake) has no static figures
    if stages.is_empty() {
        return Ok(Vec::new());
    }
    crate::profiles::write_profiles(&scene.mesh, spec, &stages, dir).map_err(|e| e.to_string())
}

/// The solver benchmark scene: the seed-like dam section (H = 171 m, slopes 1:1.4, crest 10 m)
/// extruded over 355 m, sized for about `target_dofs` DOFs, linear elastic under gravity and a
/// reservoir at 159 m. Used by `cfrd bench solver`.
pub fn bench_scene(target_dofs: usize) -> Result<Scene, RunFailure> {
    let spec = crate::mesh::generate::DamSpec::seed_like(355.0, [1, 1, 1], 1)
        .with_target_dofs(target_dofs)
        .map_err(|e| input(e.to_string()))?;
    let [nx, ny, nz] = spec.divisions;
    let text = format!(
        "name: bench-dam-{target_dofs}\nunits: SI\n\
         mesh: {{ dam: {{ height: 171.0, crest_width: 10.0, upstream_slope: 1.4, downstream_slope: 1.4, \
         length: 355.0, divisions: [{nx}, {ny}, {nz}], layers: 1 }} }}\n\
         materials: {{ rockfill: {{ model: elastic, young: 8.0e8, poisson: 0.3, density: 2150.0 }} }}\n\
         blocks: {{ layer_1: {{ material: rockfill }} }}\n\
         boundary: [ {{ set: base, fix: [x, y, z] }}, {{ set: ymin, fix: [y] }}, {{ set: ymax, fix: [y] }} ]\n\
         loads: {{ gravity: {{ g: [0.0, 0.0, -9.81] }}, hydrostatic: [ {{ faces: upstream, level: 159.0 }} ] }}\n"
    );
    Scene::from_str(&text, "<benchmark scene>", Path::new(".")).map_err(|e| input(e.to_string()))
}

/// `cfrd bench solver`: runs [`bench_scene`] and returns its summary.
pub fn bench_solver(
    world: &SimpleCommunicator,
    target_dofs: usize,
    opts: &RunOptions,
) -> Result<RunSummary, RunFailure> {
    let t_all = Instant::now();
    let mut timer = PhaseTimer::new();
    timer.start(Phase::Read);
    let scene = any_error(world, bench_scene(target_dofs).map_err(|e| e.message)).map_err(input)?;
    run_scene(world, &scene, opts, timer, t_all)
}

/// A progress bar on rank 0's terminal (hidden elsewhere and when stderr is not a terminal).
fn progress_bar(show: bool, len: u64) -> indicatif::ProgressBar {
    if !show {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:30}] step {pos}/{len} {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar
}

/// The report's converged steps, Newton iterations and Krylov iterations so far (a stage's
/// counts in the run summary are differences of these).
fn stage_counts(report: &SolveReport) -> (u32, u32, u64) {
    let ksp = report.ksp_iterations.iter().map(|&k| u64::from(k)).sum();
    (report.steps, report.newton_iterations, ksp)
}
