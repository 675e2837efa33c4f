//! The commands that run under MPI (`cfrd run`, `cfrd check`, `cfrd bench solver`): MPI
//! started with the abort-on-panic hook, every failure mapped to its exit code on every rank.

use super::args::RunArgs;
use std::path::PathBuf;
use std::process::ExitCode;

/// `cfrd run`.
pub fn run(a: RunArgs, petsc: Vec<String>) -> ExitCode {
    with_mpi(|world| {
        if a.checkpoint_every.is_some()
            && a.checkpoint
                .is_some_and(|c| c != cfrd::scene::schema::CheckpointMode::Step)
        {
            return Err(cfrd::run::RunFailure {
                code: 2,
                message: "--checkpoint-every needs step checkpoints: leave out --checkpoint or give --checkpoint step".into(),
            });
        }
        let dir = cfrd::io::outdir::run_output_dir(a.out.as_deref(), a.scene.as_deref());
        let _lock = preflight_run(world, dir.as_deref(), a.restart.as_deref(), a.overwrite, a.quiet)?;
        let opts = cfrd::run::RunOptions {
            scene: a.scene,
            out_dir: a.out,
            petsc_options: petsc,
            verbose: !a.quiet,
            restart: a.restart,
            stop_after_stage: a.stop_after_stage,
            checkpoint: a
                .checkpoint_every
                .map_or(a.checkpoint, |_| Some(cfrd::scene::schema::CheckpointMode::Step)),
            checkpoint_every: a.checkpoint_every,
            monitor: a.monitor,
            integration_tol_ratio: a.integration_tol_ratio,
            linear_solver: a.linear_solver,
            accept_changed: a.accept_changed,
        };
        cfrd::run::run(world, &opts)?;
        Ok(())
    })
}

/// `cfrd check`: the scene and its mesh validated, nothing solved.
pub fn check(scene: PathBuf) -> ExitCode {
    with_mpi(|world| {
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
    })
}

/// `cfrd bench solver`: one table row of a generated dam of about `dofs` DOFs.
pub fn bench_solver(dofs: usize, out: PathBuf, petsc: Vec<String>) -> ExitCode {
    with_mpi(|world| {
        let opts = cfrd::run::RunOptions {
            out_dir: Some(out),
            petsc_options: petsc,
            ..Default::default()
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
    })
}

/// Checks before `cfrd run` starts, on every rank alike: the `--restart` file is a readable
/// regular file, no other run holds the output directory `dir` (when known; its lock is
/// returned, to be held for the run: [`cfrd::io::run_lock`]) and it holds no other run's files
/// ([`cfrd::io::outdir::prepare_output_dir`]). Collective.
fn preflight_run(
    world: &mpi::topology::SimpleCommunicator,
    dir: Option<&std::path::Path>,
    restart: Option<&std::path::Path>,
    overwrite: bool,
    quiet: bool,
) -> Result<Option<cfrd::io::run_lock::RunLock>, cfrd::run::RunFailure> {
    let input = |message: String| cfrd::run::RunFailure {
        code: cfrd::parallel::EXIT_INPUT,
        message,
    };
    let checked = restart.map_or(Ok(()), cfrd::io::preflight::check_restart_file);
    cfrd::parallel::any_error(world, checked).map_err(input)?;
    let Some(dir) = dir else { return Ok(None) };
    let lock = cfrd::io::run_lock::acquire_collective(world, dir).map_err(input)?;
    cfrd::io::outdir::prepare_output_dir_collective(world, dir, restart, overwrite, quiet).map_err(input)?;
    Ok(lock)
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
