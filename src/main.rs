//! The `cfrd` command line: a thin layer that parses arguments and calls the library.

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

/// cfrd: parallel finite-element analysis of concrete-faced rockfill dams.
#[derive(Parser, Debug)]
#[command(version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Bench {
    /// Static solve of a seed-like dam mesh of about `--dofs` DOFs: prints one table row
    /// (ranks, DOFs, assembly and solve time, KSP iterations, peak memory, DOFs per second).
    Solver {
        /// Target number of DOFs.
        #[arg(long, default_value_t = 100_000)]
        dofs: usize,
        /// Output directory of the run.
        #[arg(short = 'o', long = "out", default_value = "out/bench")]
        out: PathBuf,
    },
    /// Integration-point updates per second of every constitutive model on monotonic and
    /// cyclic paths (one core; prints a markdown table).
    Materials {
        /// Short run (fewer repetitions).
        #[arg(long)]
        quick: bool,
    },
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a scene (the embedded default scene when none is given). Run it under `mpirun -n N`.
    /// Single-dash words such as `-ksp_type gmres` are PETSc options; they override the scene's.
    Run {
        /// Scene file (YAML).
        scene: Option<PathBuf>,
        /// Output directory (overrides the scene's `output.dir`).
        #[arg(short = 'o', long = "out")]
        out: Option<PathBuf>,
        /// Print nothing but errors.
        #[arg(short, long)]
        quiet: bool,
        /// Restart from a checkpoint (`<out>/checkpoint.h5`, written at the end of stages)
        /// of the same scene: the run continues with the stage after the checkpoint's, and
        /// `results.h5` holds the stages run from there.
        #[arg(long, value_name = "CHECKPOINT")]
        restart: Option<PathBuf>,
        /// End the run cleanly after stage K of the schedule (1-based), or with `+N` after the
        /// N-th stage this run runs (or at the end of the schedule): the results of the stages run and the checkpoint are
        /// written, and `summary.json` records `stopped_after_stage`; continue with `--restart
        /// <out>/checkpoint.h5` (a run in parts under a job time limit,
        /// `scripts/run_in_parts.sh`).
        #[arg(long, value_name = "K|+N", value_parser = parse_stop_after)]
        stop_after_stage: Option<cfrd::run::StopAfter>,
        /// When to write `<out>/checkpoint.h5`: `stage` (end of stages, paced so that writing
        /// costs at most 2.5 % of the run; always after the last and at a stop), `step` (also after
        /// every converged load step; a restart continues inside the stage) or `none`.
        /// Overrides the scene's `output.checkpoint` without changing the scene, so a run in
        /// parts may switch to step checkpoints for its long stages.
        #[arg(long, value_name = "stage|step|none", value_parser = parse_checkpoint)]
        checkpoint: Option<cfrd::scene::schema::CheckpointMode>,
        /// Step checkpoints after every N-th converged load step of the run only (and at the
        /// end of every stage), counted over the whole run, so a restarted run writes them
        /// at the same steps as an uninterrupted one with the same N; implies `--checkpoint
        /// step`. Each step checkpoint costs a write of the whole state and, where factors are
        /// reused across steps (static stages), a fresh factorization, which a long run of
        /// thousands of steps need not pay at every step.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
        checkpoint_every: Option<u32>,
        /// Print every Newton iteration's relative residual and the reason of every cut-back,
        /// with the node of the largest out-of-balance force (rank 0, standard error), as the
        /// scene's `solver.monitor: true` does; the scene (and its hash, which a restart checks)
        /// stays unchanged.
        #[arg(long)]
        monitor: bool,
        /// Integrate every generalized-plasticity material at a substepping tolerance of at most
        /// R·newton_tol (the scene's `solver.integration_tol_ratio`, which this caps further);
        /// the scene (and its hash) stays unchanged, so a run whose Newton iterations stall at
        /// the integration noise can be continued from its checkpoint with, e.g., R = 0.1.
        #[arg(long, value_name = "R")]
        integration_tol_ratio: Option<f64>,
        /// Solve the Newton corrections with this linear solver instead of the scene's
        /// `solver.linear_solver`; the scene (and its hash) stays unchanged, so a long run can
        /// continue from its checkpoint on another solver (the results then agree with the
        /// scene's to the solvers' tolerances, not bit for bit).
        #[arg(long, value_name = "iterative|reduced_amg|canonical_lu|distributed_lu", value_parser = parse_linear_solver)]
        linear_solver: Option<cfrd::scene::schema::LinearSolver>,
        /// Write into an output directory that holds another run's `results.h5`,
        /// `checkpoint.h5` or `summary.json` (its old checkpoint is removed first); without it
        /// such a directory is refused unless the run restarts from its checkpoint.
        #[arg(long)]
        overwrite: bool,
    },
    /// Validate a scene (YAML, mesh, cross-references) without solving.
    Check {
        /// Scene file (YAML).
        scene: PathBuf,
    },
    /// Print the JSON Schema of the scene format.
    Schema,
    /// Benchmarks (run `cfrd bench solver` under `mpirun -n N`).
    #[command(subcommand)]
    Bench(Bench),
    /// Partition a scene's mesh ahead of time with METIS for a given rank count; the scene then
    /// names the file in `partition:`.
    Partition {
        /// Scene file (YAML).
        scene: PathBuf,
        /// Number of parts (the rank count of the run).
        #[arg(short = 'n', long = "parts")]
        parts: usize,
        /// Partition file to write.
        #[arg(short = 'o', long = "out")]
        out: PathBuf,
    },
    /// Compare two results files field by field (e.g. 1 and 2 ranks): prints the maximum
    /// absolute and relative difference of every field of every common step. With
    /// `--tolerance`, exits with code 1 when a relative difference exceeds it.
    Compare {
        /// First results file or run directory (the reference).
        a: PathBuf,
        /// Second results file or run directory; steps are matched by stage and time, so a run
        /// restarted from a checkpoint compares with the uninterrupted one.
        b: PathBuf,
        /// Largest accepted relative difference (max |a − b| / max |a|): a finite number ≥ 0.
        #[arg(long, value_parser = parse_tolerance)]
        tolerance: Option<f64>,
    },
    /// Write fields of one step of a results file as CSV: every node or element, a set, or the
    /// nodes or elements nearest to probe points, e.g. `cfrd export out/dam --stage
    /// impound_3 --field displacement --probe 244.4,0,2852 -o crest.csv` (standard output without
    /// `-o`).
    Export {
        /// Results file or run directory.
        results: PathBuf,
        /// Field to write (repeatable; node fields or element fields, not both), e.g.
        /// `displacement`, `reaction`, `stress`, `strain`, `interface_traction`.
        #[arg(short = 'f', long = "field", required = true)]
        fields: Vec<String>,
        /// The last step of this stage (default: the last step of the file).
        #[arg(long, conflicts_with = "step")]
        stage: Option<String>,
        /// The step with this number (1-based, as in `/steps/000003`).
        #[arg(long)]
        step: Option<u64>,
        /// Only the nodes or elements of this set: an element block of the results (`*` matches
        /// any characters), or with `--scene` a node set or face set of the scene's mesh.
        #[arg(long)]
        set: Option<String>,
        /// The scene of the run, for its node and face sets.
        #[arg(long)]
        scene: Option<PathBuf>,
        /// A point X,Y,Z (m): the nearest node, or the element with the nearest centre
        /// (repeatable; among the rows of `--set` when given).
        #[arg(long = "probe", value_name = "X,Y,Z", value_parser = cfrd::io::export::parse_probe)]
        probes: Vec<[f64; 3]>,
        /// Output CSV file (standard output without it).
        #[arg(short = 'o', long = "out")]
        out: Option<PathBuf>,
    },
    /// Overlay the slab profiles (seed Figs. 8, 9) of several runs with `output.profiles`, e.g.
    /// one per interface model: `cfrd overlay hyperbolic=out/a mohr_coulomb=out/b -o fig.png`;
    /// with `--quake` the quake's before, after and residual profiles (seed Fig. 13).
    Overlay {
        /// `LABEL=DIR` pairs, DIR holding the run's `fig08_slab_stress.csv` (or
        /// `fig13_residual_slab.csv`).
        #[arg(required = true)]
        runs: Vec<String>,
        /// Output PNG.
        #[arg(short = 'o', long = "out")]
        out: PathBuf,
        /// Overlay the quake's slab table instead (`fig13_residual_slab.csv`: before, after
        /// and residual, seed Fig. 13).
        #[arg(long)]
        quake: bool,
    },
    /// Compare runs of one dam with a reference run: the error of the slab stresses and
    /// deflection (seed Figs. 8, 9) and of the crest settlement after impoundment, against each
    /// run's wall time (`accuracy_cost.csv` and `accuracy_cost.png` in the output directory;
    /// `scripts/accuracy_cost.sh` makes the runs).
    Accuracy {
        /// The most accurate run, holding `fig08_slab_stress.csv`, `fig07_dam_displacement.csv`
        /// and `summary.json` (with `--quake`: `fig13_residual_slab.csv`, `quake_summary.json`).
        #[arg(long)]
        reference: PathBuf,
        /// Compare what the earthquake leaves instead: the residual slab stresses and
        /// deflection (seed Fig. 13) and the residual crest settlement.
        #[arg(long)]
        quake: bool,
        /// `LABEL=DIR` pairs of the runs to compare (`steps_4=runs/steps_4`).
        #[arg(required = true)]
        runs: Vec<String>,
        /// Output directory.
        #[arg(short = 'o', long = "out")]
        out: PathBuf,
    },
    /// Write the seed-figure tables and plots (`output.profiles`, seed Figs. 7–11, and Figs.
    /// 12–20 of a scene with an earthquake) of a run from its results: of a run made in parts
    /// (restarted from checkpoints, each part's `results.h5` holding its own stages), list the
    /// parts in order, and the probe histories cover every stage:
    /// `cfrd profiles dam.yaml out/part_1 out/part_2 -o out/figures`.
    Profiles {
        /// Scene file (YAML) of the run, with `output.profiles`.
        scene: PathBuf,
        /// Results files or run directories, in the order they ran.
        #[arg(required = true)]
        runs: Vec<PathBuf>,
        /// Output directory of the tables and plots.
        #[arg(short = 'o', long = "out")]
        out: PathBuf,
    },
    /// Generate spectrum-compatible artificial accelerograms from a YAML file (design spectrum
    /// of DL 5073-2000 / NB 35047-2015, three components): writes `<name>.csv` (t,a_x,a_y,a_z in
    /// m/s²), `<name>_compatibility.csv` and `<name>.png` per record (`inputs/accel/README.md`).
    /// Exit code 1 when a record misses the acceptance (spec seismic §2.3), 2 on bad input.
    Accel {
        /// Specification file (YAML), e.g. `inputs/accel/seed_quake.yaml`.
        spec: PathBuf,
        /// Output directory.
        #[arg(short = 'o', long = "out", default_value = "out/accel")]
        out: PathBuf,
    },
    /// Run material-point tests from a YAML file: drained triaxial (monotonic, cyclic),
    /// oedometer, isotropic compression, interface direct shear (CNL, CNS, monotonic, cyclic,
    /// model comparison); writes CSV tables and a PNG figure (`inputs/point/README.md`).
    Point {
        /// Test file (YAML), e.g. `inputs/point/hyperbolic_cnl_monotonic.yaml`.
        test: PathBuf,
        /// Output directory.
        #[arg(short = 'o', long = "out", default_value = "out/point")]
        out: PathBuf,
    },
}

/// Parses `--stop-after-stage`: `K` (a stage of the schedule) or `+N` (stages of this run).
fn parse_stop_after(s: &str) -> Result<cfrd::run::StopAfter, String> {
    let (relative, digits) = match s.strip_prefix('+') {
        Some(d) => (true, d),
        None => (false, s),
    };
    let n: usize = digits
        .parse()
        .map_err(|_| format!("'{s}': expected a stage number K or +N"))?;
    Ok(if relative {
        cfrd::run::StopAfter::Stages(n)
    } else {
        cfrd::run::StopAfter::Stage(n)
    })
}

/// Parses `--linear-solver`: iterative, reduced_amg, canonical_lu or distributed_lu.
fn parse_linear_solver(s: &str) -> Result<cfrd::scene::schema::LinearSolver, String> {
    use cfrd::scene::schema::LinearSolver;
    match s {
        "iterative" => Ok(LinearSolver::Iterative),
        "canonical_lu" => Ok(LinearSolver::CanonicalLu),
        "distributed_lu" => Ok(LinearSolver::DistributedLu),
        "reduced_amg" => Ok(LinearSolver::ReducedAmg),
        _ => Err(format!(
            "'{s}': expected iterative, reduced_amg, canonical_lu or distributed_lu"
        )),
    }
}

/// Parses `--checkpoint`.
fn parse_checkpoint(s: &str) -> Result<cfrd::scene::schema::CheckpointMode, String> {
    use cfrd::scene::schema::CheckpointMode;
    match s {
        "stage" => Ok(CheckpointMode::Stage),
        "step" => Ok(CheckpointMode::Step),
        "none" => Ok(CheckpointMode::None),
        _ => Err(format!("'{s}': expected stage, step or none")),
    }
}

/// Parses `--tolerance`: a finite number ≥ 0.
fn parse_tolerance(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(t) if t.is_finite() && t >= 0.0 => Ok(t),
        _ => Err(format!(
            "'{s}': expected a finite relative difference ≥ 0, e.g. 1e-8"
        )),
    }
}

/// Splits PETSc options (`-word` with more than one letter after a single dash, plus its value
/// when the next argument is a number, negative ones included, or is not an option and not a
/// YAML file) from cfrd's own arguments.
fn split_petsc_options(args: Vec<String>) -> (Vec<String>, Vec<String>) {
    let is_petsc = |a: &str| {
        a.len() > 2 && a.starts_with('-') && !a.starts_with("--") && a.as_bytes()[1].is_ascii_alphabetic()
    };
    let (mut own, mut petsc) = (Vec::new(), Vec::new());
    let mut it = args.into_iter().peekable();
    while let Some(a) = it.next() {
        if is_petsc(&a) {
            petsc.push(a);
            if let Some(next) = it.peek() {
                let yaml = next.ends_with(".yaml") || next.ends_with(".yml");
                let number = next.parse::<f64>().is_ok();
                if number || (!next.starts_with('-') && !yaml) {
                    petsc.push(it.next().expect("peeked"));
                }
            }
        } else {
            own.push(a);
        }
    }
    (own, petsc)
}

fn main() -> ExitCode {
    let (args, petsc) = split_petsc_options(std::env::args().collect());
    let cli = Cli::parse_from(args);
    match cli.command {
        Command::Schema => {
            let schema = schemars::schema_for!(cfrd::scene::SceneFile);
            println!(
                "{}",
                serde_json::to_string_pretty(&schema).expect("schema serializes")
            );
            ExitCode::SUCCESS
        }
        Command::Point { test, out } => match cfrd::point::run_file(&test, &out) {
            Ok(summary) => {
                println!("{summary}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(e.exit_code())
            }
        },
        Command::Accel { spec, out } => match cfrd::seismic::run_file(&spec, &out) {
            Ok(summary) => {
                print!("{summary}");
                if summary.accepted() {
                    ExitCode::SUCCESS
                } else {
                    ExitCode::from(1)
                }
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(e.exit_code())
            }
        },
        Command::Compare { a, b, tolerance } => match cfrd::io::compare::compare_results(&a, &b) {
            Ok(diffs) => {
                use std::io::Write as _;
                let worst = diffs.iter().map(|d| d.relative()).fold(0.0, f64::max);
                // a closed pipe (`cfrd compare a b | head`) is not an error of the comparison
                let mut out = std::io::stdout().lock();
                let _ = write!(out, "{}", cfrd::io::compare::DiffTable(&diffs))
                    .and_then(|()| writeln!(out, "largest relative difference: {worst:.3e}"));
                match tolerance {
                    Some(t) if worst > t => ExitCode::from(1),
                    _ => ExitCode::SUCCESS,
                }
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Export {
            results,
            fields,
            stage,
            step,
            set,
            scene,
            probes,
            out,
        } => {
            let step = match (stage, step) {
                (Some(s), _) => cfrd::io::export::StepChoice::Stage(s),
                (None, Some(n)) => cfrd::io::export::StepChoice::Number(n),
                (None, None) => cfrd::io::export::StepChoice::Last,
            };
            let req = cfrd::io::export::ExportRequest {
                results,
                step,
                fields,
                rows: cfrd::io::export::RowChoice { set, scene, probes },
            };
            match export_fields(&req, out.as_deref()) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            }
        }
        Command::Accuracy {
            reference,
            quake,
            runs,
            out,
        } => {
            let study = match quake {
                true => cfrd::post::accuracy::Study::Quake,
                false => cfrd::post::accuracy::Study::Static,
            };
            match label_pairs(&runs)
                .and_then(|p| cfrd::post::accuracy::write_study(study, &reference, &p, &out))
            {
                Ok(files) => {
                    for f in files {
                        println!("{}", f.display());
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            }
        }
        Command::Overlay { runs, out, quake } => {
            let table = if quake {
                cfrd::post::profiles::SlabTable::Quake
            } else {
                cfrd::post::profiles::SlabTable::Static
            };
            match label_pairs(&runs).map(|p| {
                cfrd::post::profiles::overlay_slab_profiles(&p, table, &out).map_err(|e| e.to_string())
            }) {
                Ok(Ok(n)) => {
                    println!("{n} rows from {} run(s): {}", runs.len(), out.display());
                    ExitCode::SUCCESS
                }
                Ok(Err(e)) | Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            }
        }
        Command::Profiles { scene, runs, out } => match profiles_of_parts(&scene, &runs, &out) {
            Ok(n) => {
                println!("{n} file(s) from {} run(s) in {}", runs.len(), out.display());
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Partition { scene, parts, out } => match partition_ahead(&scene, parts, &out) {
            Ok(msg) => {
                println!("{msg}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Bench(Bench::Materials { quick }) => {
            let rows = cfrd::material::bench::run(quick);
            println!("{}", cfrd::material::bench::BenchTable(&rows));
            if rows.iter().any(|r| r.error.is_some()) {
                ExitCode::from(3)
            } else {
                ExitCode::SUCCESS
            }
        }
        Command::Bench(Bench::Solver { dofs, out }) => with_mpi(|world| {
            let opts = cfrd::run::RunOptions {
                scene: None,
                out_dir: Some(out),
                petsc_options: petsc,
                verbose: false,
                restart: None,
                stop_after_stage: None,
                checkpoint: None,
                checkpoint_every: None,
                monitor: false,
                integration_tol_ratio: None,
                linear_solver: None,
            };
            let s = cfrd::run::bench_solver(world, dofs, &opts)?;
            if mpi::topology::Communicator::rank(world) == 0 {
                let work = s.phase_seconds.assembly + s.phase_seconds.solve;
                println!(
                    "| {} | {} | {} | {:.2} | {:.2} | {} | {:.0} | {:.0} |",
                    s.ranks,
                    s.dofs,
                    s.elements,
                    s.phase_seconds.assembly,
                    s.phase_seconds.solve,
                    s.ksp_iterations,
                    s.peak_memory_bytes as f64 / 1048576.0,
                    s.dofs as f64 / work
                );
            }
            Ok(())
        }),
        Command::Check { scene } => with_mpi(|world| {
            let s = cfrd::run::load_scene(world, Some(&scene))?;
            if mpi::topology::Communicator::rank(world) == 0 {
                println!(
                    "{}: ok ({} nodes, {} elements, {} blocks, {} fixed DOFs, {} stage(s))",
                    scene.display(),
                    s.mesh.num_nodes(),
                    s.mesh.elements.len(),
                    s.mesh.blocks.len(),
                    s.fixed.len(),
                    s.stages.len()
                );
            }
            Ok(())
        }),
        Command::Run {
            scene,
            out,
            quiet,
            restart,
            stop_after_stage,
            checkpoint,
            checkpoint_every,
            monitor,
            integration_tol_ratio,
            linear_solver,
            overwrite,
        } => with_mpi(|world| {
            if checkpoint_every.is_some()
                && checkpoint.is_some_and(|c| c != cfrd::scene::schema::CheckpointMode::Step)
            {
                return Err(cfrd::run::RunFailure {
                    code: 2,
                    message: "--checkpoint-every needs step checkpoints: leave out --checkpoint or give --checkpoint step".into(),
                });
            }
            let dir = cfrd::io::outdir::run_output_dir(out.as_deref(), scene.as_deref());
            preflight_run(world, dir.as_deref(), restart.as_deref(), overwrite, quiet)?;
            let opts = cfrd::run::RunOptions {
                scene,
                out_dir: out,
                petsc_options: petsc,
                verbose: !quiet,
                restart,
                stop_after_stage,
                checkpoint: checkpoint_every
                    .map_or(checkpoint, |_| Some(cfrd::scene::schema::CheckpointMode::Step)),
                checkpoint_every,
                monitor,
                integration_tol_ratio,
                linear_solver,
            };
            cfrd::run::run(world, &opts)?;
            Ok(())
        }),
    }
}

/// Checks before `cfrd run` starts, on every rank alike: the `--restart` file is a readable
/// regular file, and the output directory `dir` (when known) holds no other run's files
/// ([`cfrd::io::outdir::prepare_output_dir`]). Collective.
fn preflight_run(
    world: &mpi::topology::SimpleCommunicator,
    dir: Option<&std::path::Path>,
    restart: Option<&std::path::Path>,
    overwrite: bool,
    quiet: bool,
) -> Result<(), cfrd::run::RunFailure> {
    let input = |message: String| cfrd::run::RunFailure {
        code: cfrd::parallel::EXIT_INPUT,
        message,
    };
    let checked = restart.map_or(Ok(()), cfrd::io::preflight::check_restart_file);
    cfrd::parallel::any_error(world, checked).map_err(input)?;
    if let Some(dir) = dir {
        cfrd::io::outdir::prepare_output_dir_collective(world, dir, restart, overwrite, quiet)
            .map_err(input)?;
    }
    Ok(())
}

/// `cfrd profiles`: the profile tables and plots of the runs `runs` (results files or run
/// directories, in order) of `scene`, written into `out`; returns the number of files.
fn profiles_of_parts(
    scene: &std::path::Path,
    runs: &[PathBuf],
    out: &std::path::Path,
) -> Result<usize, String> {
    let s = cfrd::scene::Scene::load(scene).map_err(|e| e.to_string())?;
    let spec = s.file.output.profiles.as_ref().ok_or_else(|| {
        format!(
            "{}: output.profiles: not set, so there is nothing to draw",
            scene.display()
        )
    })?;
    let files: Vec<PathBuf> = runs
        .iter()
        .map(|r| cfrd::io::results_reader::results_file(r))
        .collect();
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let statics = cfrd::post::profiles_from_results::write_profiles_from_results(&s, spec, &files, out)?;
    let quake = cfrd::post::quake_figures::write_quake_figures(&s, spec, &files, &[], out)?;
    Ok(statics.len() + quake.len())
}

/// `cfrd export`: the table of `req`, into `out` (with a line saying what was written) or to
/// standard output.
fn export_fields(req: &cfrd::io::export::ExportRequest, out: Option<&std::path::Path>) -> Result<(), String> {
    use std::io::Write as _;
    let table = cfrd::io::export::export(req)?;
    match out {
        Some(path) => {
            std::fs::write(path, &table.csv).map_err(|e| format!("{}: {e}", path.display()))?;
            println!(
                "{}: {} row(s) of step {} (stage {})",
                path.display(),
                table.rows,
                table.step,
                table.stage
            );
        }
        // a closed pipe (`cfrd export ... | head`) is not an error of the export
        None => {
            let _ = std::io::stdout().lock().write_all(table.csv.as_bytes());
        }
    }
    Ok(())
}

/// `cfrd partition`: METIS on the scene's mesh (each construction band balanced and the
/// evaluated elements evened out, as `cfrd run` does), written to a partition file.
fn partition_ahead(scene: &std::path::Path, parts: usize, out: &std::path::Path) -> Result<String, String> {
    if parts == 0 {
        return Err("--parts must be at least 1".into());
    }
    let s = cfrd::scene::Scene::load(scene).map_err(|e| e.to_string())?;
    let cells = cfrd::solver::mesh_cells(&s.mesh);
    let n = s.mesh.num_nodes();
    let (band, n_bands) = cfrd::run::construction_bands(&s);
    let started = std::time::Instant::now();
    let part = partition::partition_for_assembly(&cells, n, parts, &band, n_bands)
        .map_err(|e| format!("{}: {e}", scene.display()))?;
    let seconds = started.elapsed().as_secs_f64();
    let p = partition::Partition::new(&cells, n, parts, part.clone());
    let by_count =
        partition::partition_elements_by_band(&cells, n, parts, &band, n_bands).map_err(|e| e.to_string())?;
    let by_count = partition::Partition::new(&cells, n, parts, by_count);
    partition::PartitionFile::new(&cells, n, parts, part)
        .write(out)
        .map_err(|e| e.to_string())?;
    Ok(format!(
        "{}: {} elements, {} nodes in {parts} parts ({seconds:.2} s)\n{}\n  elements evaluated per \
         part with the partition balanced by owned elements alone: max {}",
        out.display(),
        cells.len(),
        n,
        partition_statistics(&p, &cells),
        by_count.evaluated_cells(&cells).into_iter().max().unwrap_or(0)
    ))
}

/// What a partition costs a run in balance and communication: elements, owned nodes and ghost
/// nodes per part (min / mean / max) and the elements on part boundaries. A ghost node is
/// received at every update of the ghosted displacement (3 values) and sends its element
/// forces back once per assembly.
fn partition_statistics(p: &partition::Partition, cells: &partition::Cells) -> String {
    let parts = p.nparts;
    let spread = |v: Vec<usize>| {
        let (min, max) = (
            v.iter().min().copied().unwrap_or(0),
            v.iter().max().copied().unwrap_or(0),
        );
        let total: usize = v.iter().sum();
        (min, total as f64 / parts as f64, max, total)
    };
    let line = |what: &str, (min, mean, max, total): (usize, f64, usize, usize)| {
        format!("  {what} per part: min {min}, mean {mean:.1}, max {max} (total {total})\n")
    };
    let owned: Vec<usize> = (0..parts)
        .map(|r| p.node_offsets[r + 1] - p.node_offsets[r])
        .collect();
    let ghosts: Vec<usize> = (0..parts).map(|r| p.ghost_nodes(cells, r).len()).collect();
    let ratio = owned
        .iter()
        .zip(&ghosts)
        .map(|(&o, &g)| g as f64 / o.max(1) as f64)
        .fold(0.0, f64::max);
    format!(
        "{}{}{}{}  elements on part boundaries: {}; largest ghost / owned nodes of a part: {ratio:.3}",
        line(
            "elements",
            spread((0..parts).map(|r| p.owned_cells(r).len()).collect())
        ),
        line(
            "elements evaluated (own and neighbours' around owned nodes)",
            spread(p.evaluated_cells(cells))
        ),
        line("owned nodes", spread(owned)),
        line("ghost nodes", spread(ghosts)),
        p.boundary_cells(cells),
    )
}

/// Initializes MPI, installs the abort-on-panic hook, runs `f`, and maps failures to exit codes
/// (rank 0 prints the message).
fn with_mpi(
    f: impl FnOnce(&mpi::topology::SimpleCommunicator) -> Result<(), cfrd::run::RunFailure>,
) -> ExitCode {
    let Some(universe) = mpi::initialize() else {
        eprintln!("error: MPI could not be initialized");
        return ExitCode::from(1);
    };
    cfrd::parallel::install_panic_hook();
    let world = universe.world();
    let rank = mpi::topology::Communicator::rank(&world);
    let code = match f(&world) {
        Ok(()) => 0,
        Err(e) => {
            if rank == 0 {
                eprintln!("error: {}", e.message);
            }
            e.code
        }
    };
    if cfrd::io::guard::abandoned() {
        // an HDF5 file whose write failed is still open: finalizing MPI would flush it
        // collectively and could hang (cfrd::io::guard)
        mpi::traits::CommunicatorCollectives::barrier(&world);
        std::mem::forget(universe);
        cfrd::io::guard::exit_now(code);
    }
    drop(universe);
    ExitCode::from(code as u8)
}

/// `LABEL=DIR` arguments as (label, directory) pairs.
fn label_pairs(runs: &[String]) -> Result<Vec<(String, PathBuf)>, String> {
    runs.iter()
        .map(|r| match r.split_once('=') {
            Some((l, d)) if !l.is_empty() && !d.is_empty() => Ok((l.to_string(), PathBuf::from(d))),
            _ => Err(format!("'{r}': expected LABEL=DIR")),
        })
        .collect()
}
