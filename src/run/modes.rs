//! The modes writer: a stage that asks for a modal analysis has its mode shapes written into
//! `modes.h5` / `modes.xdmf` and its frequencies into the run summary.

use super::observer::{Halt, Observer, Run, StageAt};
use super::options::{io_failure, RunFailure};
use super::results::owned_mesh;
use crate::io::hdf5_out::{ResultsFile, StepInfo};
use crate::io::summary::{ModalSummary, Phase};
use crate::parallel::any_error;
use crate::scene::Scene;
use crate::solver::{Modes, Problem};
use mpi::topology::SimpleCommunicator;
use std::path::Path;

/// Writes the modes of every stage that computes them.
pub struct ModesWriter {
    /// Prints the frequencies (rank 0, `-v`).
    pub verbose: bool,
}

impl Observer for ModesWriter {
    fn on_stage_start(&mut self, run: &mut Run<'_, '_>, at: &StageAt<'_>) -> Result<(), Halt> {
        let Some(modes) = run.problem.modes().filter(|_| at.fresh) else {
            return Ok(());
        };
        run.timer.start(Phase::Output);
        let summary = write_modes(run.world, run.scene, run.problem, modes, &run.out_dir)?;
        run.timer.stop();
        if self.verbose {
            let hz: Vec<String> = modes.frequencies_hz.iter().map(|f| format!("{f:.4}")).collect();
            eprintln!("modal analysis: {} Hz in {:.1} s", hz.join(", "), modes.seconds);
        }
        run.record.modal = Some(summary);
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
    modes: &Modes,
    out_dir: &Path,
) -> Result<ModalSummary, RunFailure> {
    let written = ResultsFile::create(world, out_dir.join("modes.h5"), &scene.file.name).and_then(|mut f| {
        f.write_mesh(&owned_mesh(scene, problem))?;
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
    any_error(world, written).map_err(|m| io_failure("writing the mode shapes", m))?;
    Ok(ModalSummary {
        stage: modes.stage.clone(),
        frequencies_hz: modes.frequencies_hz.clone(),
        periods_s: modes.frequencies_hz.iter().map(|f| 1.0 / f).collect(),
        seconds: modes.seconds,
    })
}
