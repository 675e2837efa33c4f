//! Progress on rank 0 (`-v`): a line at every stage's start (with a dynamic stage's notes on its
//! record, [`crate::scene::dynamic::DynamicStage::notes`]), and at every converged step a bar
//! on a terminal or a line in a log (nohup, a cluster job's output).

use super::observer::{Halt, Observer, Run, RunEnd, StageAt, StepAt};
use super::options::RunFailure;
use super::results::stage_time;

/// Prints what the run is doing.
pub struct Progress {
    show: bool,
    /// Without a terminal the bar is not drawn: a line per step instead.
    step_lines: bool,
    n_stages: usize,
    bar: indicatif::ProgressBar,
}

impl Progress {
    /// Progress of a run of `n_stages` stages, shown when `show` (rank 0 and `-v`).
    pub fn new(show: bool, n_stages: usize) -> Self {
        Progress {
            show,
            step_lines: show && !std::io::IsTerminal::is_terminal(&std::io::stderr()),
            n_stages,
            bar: indicatif::ProgressBar::hidden(),
        }
    }
}

impl Observer for Progress {
    fn on_stage_start(&mut self, _run: &mut Run<'_, '_>, at: &StageAt<'_>) -> Result<(), Halt> {
        let stage = at.stage;
        if self.show {
            let steps = match (&stage.dynamic, stage.step_growth) {
                (Some(d), _) => format!("{} time step(s) of {} s", stage.load_steps, d.dt()),
                (None, 1) => format!("{} load step(s)", stage.load_steps),
                (None, g) => format!(
                    "{} load step(s), easy ones growing up to {g} times",
                    stage.load_steps
                ),
            };
            eprintln!("stage {}/{} '{}': {steps}", at.k + 1, self.n_stages, stage.name);
            for note in stage.dynamic.iter().flat_map(|d| &d.notes) {
                eprintln!("  {note}");
            }
        }
        self.bar = progress_bar(self.show, stage.load_steps as u64);
        Ok(())
    }

    fn on_step(&mut self, run: &mut Run<'_, '_>, step: &StepAt<'_>) -> Result<(), Halt> {
        let stage = step.stage.stage;
        let at = stage_time(stage, step.path.t);
        let report = &run.report;
        if self.step_lines {
            eprintln!(
                "  {at} after {:.0} s ({} Newton iterations, {} cut-backs in the run so far)",
                step.stage_seconds, report.newton_iterations, report.cutbacks
            );
        }
        let done = step.path.t / step.path.t_end * stage.load_steps as f64;
        self.bar.set_position(done.round() as u64);
        self.bar.set_message(format!(
            "{at}, Newton {}, cut-backs {}",
            report.newton_iterations, report.cutbacks
        ));
        Ok(())
    }

    fn on_stage_end(&mut self, _run: &mut Run<'_, '_>, _end: &StepAt<'_>) -> Result<(), Halt> {
        self.bar.finish_and_clear();
        Ok(())
    }

    fn on_finish(&mut self, _run: &mut Run<'_, '_>, _end: &RunEnd<'_>) -> Result<(), RunFailure> {
        self.bar.finish_and_clear();
        Ok(())
    }
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
