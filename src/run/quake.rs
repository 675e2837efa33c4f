//! The quake recorder: the crest's motion and the probes' state at every time step of the
//! run's dynamic stages, on the quake's clock ([`crate::post::quake_clock`]), into the run's
//! report (kept in step checkpoints, so a restarted run has the whole history), and the
//! earthquake's tables and figures when the run ends.

use super::observer::{Halt, Observer, Run, RunEnd, StageAt, StepAt};
use super::options::RunFailure;
use crate::parallel::{any_error, EXIT_IO, EXIT_SOLVER};
use crate::post::quake_clock::QuakeClock;
use crate::post::quake_probes::QuakeProbe;
use crate::scene::Scene;
use crate::solver::{Problem, SolveError, SolveReport};
use mpi::topology::Communicator;
use std::path::Path;

/// Records the dynamic stages of a run and writes their outputs.
pub struct QuakeRecorder {
    clock: QuakeClock,
    crest: usize,
    probes: Vec<QuakeProbe>,
    /// The time step of each stage (0 for a static one): the probes' times are put on its
    /// grid, as those of the results steps are ([`crate::post::quake_fields::on_time_grid`]).
    dt: Vec<f64>,
    /// The crest's displacement at the current stage's start less the one at the first
    /// dynamic stage's start (m): added to the rows of later dynamic stages.
    shift: [f64; 3],
}

impl QuakeRecorder {
    /// The recorder of `scene`'s crest node and probes.
    pub fn new(scene: &Scene) -> Self {
        let spec = scene.file.output.profiles.clone().unwrap_or_default();
        let dt = scene
            .stages
            .iter()
            .map(|s| s.dynamic.as_ref().map_or(0.0, |d| d.dt()))
            .collect();
        QuakeRecorder {
            clock: QuakeClock::new(scene),
            crest: crate::post::quake::crest_node(scene),
            probes: crate::post::quake_probes::probe_elements(&scene.mesh, &spec),
            dt,
            shift: [0.0; 3],
        }
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
            .push(crate::post::quake_probes::probe_row(t, &self.probes, &states));
        Ok(())
    }
}

impl Observer for QuakeRecorder {
    /// The probes at t = 0, the state before the quake; at every dynamic stage's start (fresh
    /// or resumed) the crest's shift from the first one's start.
    fn on_stage_start(&mut self, run: &mut Run<'_, '_>, at: &StageAt<'_>) -> Result<(), Halt> {
        if self.clock.start(at.k).is_none() {
            return Ok(());
        }
        let here = run.problem.node_stage_start(self.crest);
        let first = self.clock.first() == Some(at.k);
        if first && at.fresh {
            run.report.crest.clear();
            run.report.probes.clear();
            self.record_probes(run.problem, 0.0, run.report)?;
        }
        if first || run.report.crest_quake_start.is_none() {
            // a checkpoint written before the start was kept counts from its own stage
            run.report.crest_quake_start = Some(here);
        }
        let start = run.report.crest_quake_start.unwrap_or(here);
        self.shift = std::array::from_fn(|c| here[c] - start[c]);
        Ok(())
    }

    /// The crest and the probes after a converged time step of a dynamic stage.
    fn on_step(&mut self, run: &mut Run<'_, '_>, step: &StepAt<'_>) -> Result<(), Halt> {
        let k = step.stage.k;
        if let Some(t0) = self.clock.start(k) {
            let t = t0 + step.path.t;
            let mut row = run.problem.node_motion(self.crest, t)?;
            for c in 0..3 {
                row[1 + c] += self.shift[c];
            }
            run.report.crest.push(row);
            let on_grid = t0 + crate::post::quake_fields::on_time_grid(step.path.t, self.dt[k]);
            self.record_probes(run.problem, on_grid, run.report)?;
        }
        Ok(())
    }

    /// The crest history and summary ([`crate::post::quake`]) and the seed's dynamic figures
    /// ([`crate::post::quake_figures`]) from the closed results file (rank 0; collective
    /// decision). A failure to write them never hides the failure of a stage.
    fn on_finish(&mut self, run: &mut Run<'_, '_>, end: &RunEnd<'_>) -> Result<(), RunFailure> {
        if self.clock.is_empty() {
            return Ok(());
        }
        let (scene, h5) = (run.scene, run.results_path.as_path());
        // a run whose first stage failed wrote no step to draw from
        let written = if run.world.rank() != 0 || lacks_steps(h5) {
            Ok(Vec::new())
        } else {
            write_outputs(scene, h5, run.report, &run.out_dir)
        };
        any_error(run.world, written).map(|_| ()).map_err(|m| RunFailure {
            code: if end.failure.is_some() {
                EXIT_SOLVER
            } else {
                EXIT_IO
            },
            message: match end.failure {
                Some(f) => format!("{f}; writing the earthquake outputs: {m}"),
                None => format!("writing the earthquake outputs: {m}"),
            },
        })
    }
}

/// The earthquake's tables and figures of a run (rank 0).
fn write_outputs(
    scene: &Scene,
    h5: &Path,
    report: &SolveReport,
    out_dir: &Path,
) -> Result<Vec<std::path::PathBuf>, String> {
    let spec = scene.file.output.profiles.clone().unwrap_or_default();
    let mut files = crate::post::quake::write_quake_outputs(scene, h5, &report.crest, out_dir)?;
    let parts = [h5.to_path_buf()];
    files.extend(crate::post::quake_figures::write_quake_figures(
        scene,
        &spec,
        &parts,
        &report.probes,
        out_dir,
    )?);
    Ok(files)
}

/// Whether the results file `h5` opens and holds no step (a run whose first stage failed); a
/// file that does not open is left to the writers, which name the error.
fn lacks_steps(h5: &Path) -> bool {
    use crate::io::results_reader::{open, step_names};
    open(h5).is_ok_and(|f| !f.link_exists("steps") || step_names(&f, h5).is_ok_and(|n| n.is_empty()))
}
