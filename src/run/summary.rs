//! The summary observer: `summary.json` of a run that completed (wall times by phase and
//! stage, solver counters, interface counts, memory per rank) and its closing lines.

use super::observer::{Observer, Run, RunEnd};
use super::options::{io_failure, RunFailure};
use crate::io::summary::RunSummary;
use crate::parallel::{any_error, max_f64};
use mpi::topology::Communicator;
use std::time::Instant;

/// Writes the run summary when the run has completed.
pub struct SummaryWriter {
    /// Prints the closing lines (rank 0, `-v`).
    pub verbose: bool,
    /// When the run began.
    pub started: Instant,
    /// Whether the run was restarted from a checkpoint.
    pub restarted: bool,
    /// The summary written, for the caller.
    pub summary: Option<RunSummary>,
}

impl SummaryWriter {
    fn say(&self, s: String) {
        if self.verbose {
            eprintln!("{s}");
        }
    }

    fn closing_lines(&self, run: &Run<'_, '_>) {
        let report = &run.report;
        let factorizations = match report.factorizations {
            0 => String::new(),
            n => format!(", {n} factorization(s)"),
        };
        self.say(format!(
            "converged: {} step(s), {} Newton iteration(s), {} cut-back(s), {} KSP iterations{factorizations}",
            report.steps,
            report.newton_iterations,
            report.cutbacks,
            report.ksp_iterations.iter().sum::<u32>(),
        ));
        let counts = run.problem.interface_counts();
        if counts.points > 0 {
            self.say(format!(
                "interfaces: {} point(s), {} open, {} slipping",
                counts.points, counts.open, counts.slipping
            ));
        }
    }

    fn build(&self, run: &mut Run<'_, '_>) -> RunSummary {
        let (world, scene, report) = (run.world, run.scene, &run.report);
        let counts = run.problem.interface_counts();
        let mut summary = RunSummary::new(world, &scene.file.name);
        summary.nodes = scene.mesh.num_nodes() as u64;
        summary.elements = scene.mesh.elements.len() as u64;
        summary.dofs = 3 * summary.nodes;
        summary.phase_seconds = run.timer.seconds().max_over_ranks(world);
        summary.total_seconds = max_f64(world, self.started.elapsed().as_secs_f64());
        summary.ksp_iterations = report.ksp_iterations.iter().map(|&k| k as u64).sum();
        summary.newton_iterations = report.newton_iterations as u64;
        summary.residual_evaluations = report.residual_evaluations;
        summary.element_loops = report.element_loops;
        summary.steps = report.steps as u64;
        summary.cutbacks = report.cutbacks as u64;
        summary.predictions_dropped = report.predictions_dropped as u64;
        summary.newton_per_step = report.newton_per_step.clone();
        summary.factorizations = report.factorizations;
        summary.multigrid_builds = report.multigrid_builds;
        summary.interface_points = counts.points;
        summary.interface_open = counts.open;
        summary.interface_slipping = counts.slipping;
        summary.restarted_after_stage = self.restarted.then_some(run.record.first_stage as u64);
        summary.stopped_after_stage = run.record.stopped_after;
        summary.accepted_changed_inputs = run.record.accepted_changed.clone();
        summary.checkpoint_seconds = max_f64(world, run.record.checkpoint_seconds);
        summary.stage_seconds = report.stage_seconds.clone();
        summary.modal = run.record.modal.clone();
        summary.gather_element_seconds(world, run.problem.element_seconds());
        summary.gather_solver_rows(world, report.solver_rows_held);
        summary.gather_peak_memory(world);
        summary
    }
}

impl Observer for SummaryWriter {
    fn on_finish(&mut self, run: &mut Run<'_, '_>, end: &RunEnd<'_>) -> Result<(), RunFailure> {
        if end.failure.is_some() {
            return Ok(());
        }
        self.closing_lines(run);
        run.timer.stop();
        let summary = self.build(run);
        let path = run.out_dir.join("summary.json");
        let written = match run.world.rank() {
            0 => summary.write_json(&path),
            _ => Ok(()),
        };
        any_error(run.world, written).map_err(|m| io_failure("writing the run summary", m))?;
        self.say(format!(
            "results: {} (ParaView: {}), summary: {}",
            run.results_path.display(),
            run.out_dir.join("results.xdmf").display(),
            path.display()
        ));
        self.summary = Some(summary);
        Ok(())
    }
}
