//! The command line's words: the subcommands and their options (clap), and the parsers of
//! option values.

use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// cfrd: parallel finite-element analysis of concrete-faced rockfill dams.
#[derive(Parser, Debug)]
#[command(version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Bench {
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
pub enum Command {
    /// Run a scene (the embedded default scene when none is given). Run it under `mpirun -n N`.
    /// Single-dash words such as `-ksp_type gmres` are PETSc options; they override the scene's.
    Run(RunArgs),
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
        /// Compare the steps both runs hold and accept steps or fields only one of them holds
        /// (named on standard error), e.g. a run restarted from a stage checkpoint against the
        /// whole run; without it such a difference fails the comparison (exit code 1).
        #[arg(long)]
        common: bool,
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
    /// Exit code 1 when a record misses the spectrum acceptance (`cfrd::guide`), 2 on bad input.
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

/// The options of `cfrd run`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Scene file (YAML).
    pub scene: Option<PathBuf>,
    /// Output directory (overrides the scene's `output.dir`).
    #[arg(short = 'o', long = "out")]
    pub out: Option<PathBuf>,
    /// Print nothing but errors.
    #[arg(short, long)]
    pub quiet: bool,
    /// Restart from a checkpoint (`<out>/checkpoint.h5`, written at the end of stages)
    /// of the same scene: the run continues with the stage after the checkpoint's, and
    /// `results.h5` holds the stages run from there.
    #[arg(long, value_name = "CHECKPOINT")]
    pub restart: Option<PathBuf>,
    /// End the run cleanly after stage K of the schedule (1-based), or with `+N` after the
    /// N-th stage this run runs (or at the end of the schedule): the results of the stages run and the checkpoint are
    /// written, and `summary.json` records `stopped_after_stage`; continue with `--restart
    /// <out>/checkpoint.h5` (a run in parts under a job time limit,
    /// `scripts/run_in_parts.sh`).
    #[arg(long, value_name = "K|+N", value_parser = parse_stop_after)]
    pub stop_after_stage: Option<cfrd::run::StopAfter>,
    /// When to write `<out>/checkpoint.h5`: `stage` (end of stages, paced so that writing
    /// costs at most 2.5 % of the run; always after the last and at a stop), `step` (also after
    /// every converged load step; a restart continues inside the stage) or `none`.
    /// Overrides the scene's `output.checkpoint` without changing the scene, so a run in
    /// parts may switch to step checkpoints for its long stages.
    #[arg(long, value_name = "stage|step|none", value_parser = parse_checkpoint)]
    pub checkpoint: Option<cfrd::scene::schema::CheckpointMode>,
    /// Step checkpoints after every N-th converged load step of the run only (and at the
    /// end of every stage), counted over the whole run, so a restarted run writes them
    /// at the same steps as an uninterrupted one with the same N; implies `--checkpoint
    /// step`. Each step checkpoint costs a write of the whole state and, where factors are
    /// reused across steps (static stages), a fresh factorization, which a long run of
    /// thousands of steps need not pay at every step.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub checkpoint_every: Option<u32>,
    /// Print every Newton iteration's relative residual and the reason of every cut-back,
    /// with the node of the largest out-of-balance force (rank 0, standard error), as the
    /// scene's `solver.monitor: true` does; the scene (and its hash, which a restart checks)
    /// stays unchanged.
    #[arg(long)]
    pub monitor: bool,
    /// Integrate every generalized-plasticity material at a substepping tolerance of at most
    /// R·newton_tol (the scene's `solver.integration_tol_ratio`, which this caps further);
    /// the scene (and its hash) stays unchanged, so a run whose Newton iterations stall at
    /// the integration noise can be continued from its checkpoint with, e.g., R = 0.1.
    #[arg(long, value_name = "R")]
    pub integration_tol_ratio: Option<f64>,
    /// Solve the Newton corrections of every stage with this linear solver instead of the
    /// scene's `solver.linear_solver` (static stages) and the dynamic stages' own
    /// `linear_solver`; the scene (and its hash) stays unchanged, so a long run can
    /// continue from its checkpoint on another solver (the results then agree with the
    /// scene's to the solvers' tolerances, not bit for bit).
    #[arg(long, value_name = "iterative|reduced_amg|canonical_lu|distributed_lu", value_parser = parse_linear_solver)]
    pub linear_solver: Option<cfrd::scene::schema::LinearSolver>,
    /// Write into an output directory that holds another run's `results.h5`,
    /// `checkpoint.h5` or `summary.json` (its old checkpoint is removed first); without it
    /// such a directory is refused, and so is a restart into its own checkpoint's directory.
    #[arg(long)]
    pub overwrite: bool,
    /// With `--restart`: go on although this input file of the scene (mesh, partition or
    /// record) changed since the checkpoint was written; said in the log and in
    /// `summary.json` (repeatable).
    #[arg(long = "accept-changed", value_name = "FILE")]
    pub accept_changed: Vec<PathBuf>,
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

/// The command line as text: every argument must be UTF-8 (paths are written into results,
/// summaries and logs as text). The first that is not is named by its position and its
/// lossy form, for an exit with code 2 instead of a panic.
pub fn utf8_args(args: impl IntoIterator<Item = std::ffi::OsString>) -> Result<Vec<String>, String> {
    args.into_iter()
        .enumerate()
        .map(|(i, a)| {
            a.into_string().map_err(|a| {
                format!(
                    "argument {i} ('{}') is not valid UTF-8: cfrd reads paths and options as UTF-8 \
                     text; rename the file or give another path to it",
                    a.to_string_lossy()
                )
            })
        })
        .collect()
}

/// Splits PETSc options (`-word` with more than one letter after a single dash, plus its value
/// when the next argument is a number, negative ones included, or is not an option and not a
/// YAML file) from cfrd's own arguments.
pub fn split_petsc_options(args: Vec<String>) -> (Vec<String>, Vec<String>) {
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
