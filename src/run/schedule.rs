//! The schedule: the stages of a scene in order and the steps of each, from where the run
//! starts (a restart's stage, or inside one from a step checkpoint) to the last stage, the
//! stage `--stop-after-stage` names, or the first stage that fails. It calls the observers at
//! every event ([`super::observer`]) and decides nothing about output itself.

use super::observer::{Halt, Observer, Run, RunEnd, StageAt, StepAt};
use super::options::RunFailure;
use crate::io::summary::Phase;
use crate::parallel::any_error;
use crate::solver::{SolveReport, StageSeconds, StepControl};
use std::time::{Duration, Instant};

/// Where a schedule starts and ends.
pub struct Plan {
    /// The first stage (index) this run runs.
    pub first_stage: usize,
    /// The stage of a step checkpoint, resumed where it stood.
    pub resume: Option<StepControl>,
    /// The stage (1-based) after which the run stops (`--stop-after-stage`).
    pub stop_after: Option<usize>,
    /// Prints the stop (rank 0, `-v`), naming the checkpoint to continue from.
    pub verbose: bool,
    /// The checkpoint a stopped run continues from.
    pub checkpoint: std::path::PathBuf,
}

/// Runs the stages of `plan` with `observers`, closes the results file and lets every
/// observer finish (the summary observer stops the output phase's clock). Returns the
/// failure of a stage (its message), if one failed; `Err` when an observer ended the run.
pub fn run_schedule(
    run: &mut Run<'_, '_>,
    observers: &mut [&mut dyn Observer],
    mut plan: Plan,
) -> Result<Option<String>, RunFailure> {
    let failure = run_stages(run, observers, &mut plan)?;
    let report = &run.report;
    run.timer
        .add(Phase::Assembly, Duration::from_secs_f64(report.assembly_seconds));
    run.timer
        .add(Phase::Solve, Duration::from_secs_f64(report.solve_seconds));
    run.timer.start(Phase::Output);
    run.close_results()?;
    let end = RunEnd {
        failure: failure.as_deref(),
    };
    for o in observers.iter_mut() {
        o.on_finish(run, &end)?;
    }
    Ok(failure)
}

/// The stage loop; the failure of a stage ends it.
fn run_stages(
    run: &mut Run<'_, '_>,
    observers: &mut [&mut dyn Observer],
    plan: &mut Plan,
) -> Result<Option<String>, RunFailure> {
    let n_stages = run.scene.stages.len();
    let scene = run.scene;
    for (k, stage) in scene.stages.iter().enumerate().skip(plan.first_stage) {
        let started = Instant::now();
        let counts_at_start = stage_counts(run.report);
        let at = StageAt {
            k,
            stage,
            fresh: plan.resume.is_none(),
            last: k + 1 == n_stages || plan.stop_after == Some(k + 1),
        };
        // the stage of a step checkpoint continues where it stood (restore resumed it)
        let path = match plan.resume.take() {
            Some(p) => p,
            None => {
                if let Err(m) = any_error(run.world, run.problem.begin_stage(k)) {
                    return Ok(Some(m));
                }
                StepControl::growing(stage.t_end(), stage.load_steps, stage.step_growth)
            }
        };
        let (path, steps_in_stage, solved) = run_steps(run, observers, &at, path, started)?;
        if let Err(m) = any_error(run.world, solved.and_then(|_| run.problem.end_stage())) {
            return Ok(Some(format!("stage '{}': {m}", stage.name)));
        }
        run.report
            .stage_seconds
            .push(stage_seconds(run.report, &stage.name, started, counts_at_start));
        let end = StepAt {
            stage: &at,
            path: &path,
            steps_in_stage,
            stage_seconds: started.elapsed().as_secs_f64(),
        };
        for o in observers.iter_mut() {
            halted(o.on_stage_end(run, &end))?;
        }
        if plan.stop_after == Some(k + 1) && k + 1 < n_stages {
            if plan.verbose {
                eprintln!(
                    "stopped after stage {} of {n_stages} (--stop-after-stage); continue with --restart {}",
                    k + 1,
                    plan.checkpoint.display()
                );
            }
            run.record.stopped_after = Some((k + 1) as u64);
            break;
        }
    }
    Ok(None)
}

/// The steps of one stage, after telling the observers it starts. Returns where the stage
/// stands, its converged steps since its start (also those before the step checkpoint a
/// restart continues from), and whether its steps (and the observers) went well; `Err` ends
/// the run.
fn run_steps(
    run: &mut Run<'_, '_>,
    observers: &mut [&mut dyn Observer],
    at: &StageAt<'_>,
    mut path: StepControl,
    started: Instant,
) -> Result<(StepControl, u32, Result<(), crate::solver::SolveError>), RunFailure> {
    let mut solved = notify(observers, |o| o.on_stage_start(run, at))?;
    let max_cutbacks = run.scene.file.solver.max_cutbacks;
    while solved.is_ok() && !path.done() {
        solved = run.problem.advance(&mut path, max_cutbacks, run.report);
        if solved.is_err() {
            break;
        }
        let step = StepAt {
            stage: at,
            path: &path,
            steps_in_stage: path.steps,
            stage_seconds: started.elapsed().as_secs_f64(),
        };
        solved = notify(observers, |o| o.on_step(run, &step))?;
    }
    Ok((path, path.steps, solved))
}

/// Calls `event` on every observer in order until one halts: a solver halt is the stage's
/// outcome, any other ends the run.
fn notify(
    observers: &mut [&mut dyn Observer],
    mut event: impl FnMut(&mut dyn Observer) -> Result<(), Halt>,
) -> Result<Result<(), crate::solver::SolveError>, RunFailure> {
    for o in observers.iter_mut() {
        match event(&mut **o) {
            Ok(()) => {}
            Err(Halt::Solver(e)) => return Ok(Err(e)),
            Err(Halt::Failure(f)) => return Err(f),
        }
    }
    Ok(Ok(()))
}

/// A stage-end event's outcome: after the stage's end nothing is a solver failure any more.
fn halted(r: Result<(), Halt>) -> Result<(), RunFailure> {
    match r {
        Ok(()) => Ok(()),
        Err(Halt::Failure(f)) => Err(f),
        Err(Halt::Solver(e)) => Err(RunFailure {
            code: crate::parallel::EXIT_SOLVER,
            message: e.to_string(),
        }),
    }
}

/// The wall time and counts of a completed stage.
fn stage_seconds(
    report: &SolveReport,
    name: &str,
    started: Instant,
    at_start: (u32, u32, u64),
) -> StageSeconds {
    let counts = stage_counts(report);
    StageSeconds {
        stage: name.to_string(),
        seconds: started.elapsed().as_secs_f64(),
        steps: counts.0 - at_start.0,
        newton_iterations: counts.1 - at_start.1,
        ksp_iterations: counts.2 - at_start.2,
    }
}

/// The report's converged steps, Newton iterations and Krylov iterations so far (a stage's
/// counts in the run summary are differences of these).
fn stage_counts(report: &SolveReport) -> (u32, u32, u64) {
    let ksp = report.ksp_iterations.iter().map(|&k| u64::from(k)).sum();
    (report.steps, report.newton_iterations, ksp)
}
