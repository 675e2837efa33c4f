//! The profiles observer: a run's static tables and figures (the seed's Figs. 7–11), written
//! from the closed results file when the run ends, if the scene asks for them
//! (`output.profiles`).

use super::observer::{Observer, Run, RunEnd};
use super::options::RunFailure;
use crate::parallel::{any_error, EXIT_IO, EXIT_SOLVER};
use crate::post::profiles_from_results::write_profiles_from_results;
use mpi::topology::Communicator;

/// Writes the profiles at the end of a run.
pub struct ProfilesWriter {
    /// Prints the outcome (rank 0, `-v`).
    pub verbose: bool,
}

impl Observer for ProfilesWriter {
    /// Needs at least one completed stage; a failure to write them never hides the failure of
    /// a stage.
    fn on_finish(&mut self, run: &mut Run<'_, '_>, end: &RunEnd<'_>) -> Result<(), RunFailure> {
        let say = |s: String| {
            if run.world.rank() == 0 && self.verbose {
                eprintln!("{s}");
            }
        };
        let Some(spec) = &run.scene.file.output.profiles else {
            return Ok(());
        };
        if run.record.stages_written == 0 {
            say("profiles: not written, no stage completed".into());
            return Ok(());
        }
        // rank 0 reads the closed results file back (serial HDF5) and writes the tables and plots
        let written = if run.world.rank() == 0 {
            let parts = std::slice::from_ref(&run.results_path);
            write_profiles_from_results(run.scene, spec, parts, &run.out_dir)
        } else {
            Ok(Vec::new())
        };
        match any_error(run.world, written) {
            Ok(files) => {
                say(format!(
                    "profiles: {} file(s) in {}",
                    files.len(),
                    run.out_dir.display()
                ));
                Ok(())
            }
            Err(m) => {
                let stage = end.failure.map(|f| format!("{f}; ")).unwrap_or_default();
                Err(RunFailure {
                    code: if end.failure.is_some() {
                        EXIT_SOLVER
                    } else {
                        EXIT_IO
                    },
                    message: format!("{stage}writing the profiles: {m}"),
                })
            }
        }
    }
}
