//! The results writer: `results.h5` (and its XDMF) of a run, a step at every stage's end and,
//! inside a dynamic stage, every `output_every` time steps.

use super::observer::{Halt, Observer, Run, StepAt};
use super::options::{io_failure, RunFailure};
use crate::io::hdf5_out::{strain_output_components, OwnedMesh, ResultsFile, StepInfo};
use crate::io::summary::Phase;
use crate::parallel::any_error;
use crate::scene::{Scene, Stage};
use crate::solver::{LocalResults, Problem};
use mpi::topology::Communicator;
use mpi::topology::SimpleCommunicator;
use std::path::Path;

/// Opens `results.h5` in `out_dir` with the mesh of `scene`. Collective.
pub fn create_results(
    world: &SimpleCommunicator,
    scene: &Scene,
    problem: &Problem,
    path: &Path,
) -> Result<ResultsFile, RunFailure> {
    let created = ResultsFile::create(world, path, &scene.file.name).and_then(|mut f| {
        f.write_mesh(&owned_mesh(scene, problem))?;
        Ok(f)
    });
    any_error(world, created).map_err(|m| io_failure("writing results", m))
}

/// Where a restart continues the schedule: after `stages_done` stages, inside the next one at
/// `within` (a step checkpoint).
pub struct RestartPoint<'a> {
    /// The checkpoint the run restarts from.
    pub checkpoint: &'a Path,
    /// Completed stages.
    pub stages_done: usize,
    /// Where the stage in progress stands (step checkpoints).
    pub within: Option<&'a crate::solver::StepControl>,
}

/// Opens `results.h5` at `path` for a run restarted at `at`: it continues the results
/// published beside the checkpoint (`results.h5` in the checkpoint's directory, which holds
/// every step written before the checkpoint) with their steps up to the checkpoint's point, so
/// the restarted run's results hold every step of the uninterrupted run. When there are none,
/// or they do not reach the checkpoint (written by another run or an older build), the run's
/// results hold its own steps only, and rank 0 says so unless `quiet`. Collective.
pub fn continue_results(
    world: &SimpleCommunicator,
    scene: &Scene,
    problem: &Problem,
    path: &Path,
    at: &RestartPoint<'_>,
    quiet: bool,
) -> Result<ResultsFile, RunFailure> {
    let prior = at.checkpoint.with_file_name("results.h5");
    let limit = at.stages_done as f64 + at.within.map_or(0.0, |p| p.t / p.t_end);
    let keep = |info: &StepInfo| info.time <= limit * (1.0 + 1e-12);
    let reaches = match world.rank() {
        0 => reaches(&prior, at.stages_done),
        _ => Ok(()),
    };
    if let Err(why) = any_error(world, reaches) {
        if !quiet {
            eprintln!("note: {why}: this run's results.h5 holds the steps it computes only");
        }
        return create_results(world, scene, problem, path);
    }
    let mesh = owned_mesh(scene, problem);
    let continued = ResultsFile::continuing(world, path, &scene.file.name, &prior, &mesh, &keep);
    any_error(world, continued).map_err(|m| io_failure("continuing the results", m))
}

/// Whether the results file `prior` holds the end of stage `stages_done` (the last step a
/// checkpoint after it follows), or says why not. One rank.
fn reaches(prior: &Path, stages_done: usize) -> Result<(), String> {
    let shown = prior.display();
    if !prior.exists() {
        return Err(format!("no results beside the checkpoint ({shown})"));
    }
    let file = crate::io::results_reader::open(prior)?;
    let names = crate::io::results_reader::step_names(&file, prior)?;
    let end = stages_done as f64;
    let found = names.iter().any(|n| {
        file.group(&format!("/steps/{n}"))
            .and_then(|g| g.attr("time"))
            .and_then(|a| a.read_scalar::<f64>())
            .is_ok_and(|t| t == end)
    });
    match found || stages_done == 0 {
        true => Ok(()),
        false => Err(format!("{shown} does not reach the end of stage {stages_done}")),
    }
}

/// Decides which states go into the run's results file: every stage's end and, inside a
/// dynamic stage, every `output_every` time steps.
pub struct ResultsWriter {
    has_interfaces: bool,
}

impl ResultsWriter {
    /// The writer of `scene`'s fields (interface fields only where it has interface blocks).
    pub fn new(scene: &Scene) -> Self {
        ResultsWriter {
            has_interfaces: scene.block_interface.iter().any(Option::is_some),
        }
    }

    /// Collects the committed state and writes it as the step `info` (collective).
    fn write(&self, run: &mut Run<'_, '_>, info: StepInfo) -> Result<(), RunFailure> {
        let file = run
            .results
            .as_mut()
            .expect("the results file is open until the run ends");
        let has_interfaces = self.has_interfaces;
        let written = run
            .problem
            .results()
            .map_err(|e| e.to_string())
            .and_then(|res| write_step(file, info, &res, has_interfaces).map_err(|e| e.to_string()));
        any_error(run.world, written).map_err(|m| io_failure("writing results", m))
    }
}

impl Observer for ResultsWriter {
    fn on_step(&mut self, run: &mut Run<'_, '_>, step: &StepAt<'_>) -> Result<(), Halt> {
        let stage = step.stage.stage;
        let every = stage.dynamic.as_ref().map_or(0, |d| d.output_every);
        if every > 0 && step.steps_in_stage.is_multiple_of(every) && !step.path.done() {
            run.timer.start(Phase::Output);
            self.write(run, step_info(step.stage.k, stage, step.path.t, step.path.t_end))?;
            run.timer.stop();
        }
        Ok(())
    }

    fn on_stage_end(&mut self, run: &mut Run<'_, '_>, end: &StepAt<'_>) -> Result<(), Halt> {
        run.timer.start(Phase::Output);
        let t_end = end.path.t_end;
        self.write(run, step_info(end.stage.k, end.stage.stage, t_end, t_end))?;
        run.record.stages_written += 1;
        run.timer.stop();
        Ok(())
    }
}

/// The owned part of the scene's mesh, as the results files store it.
pub fn owned_mesh(scene: &Scene, problem: &Problem) -> OwnedMesh {
    let d = problem.discretization();
    OwnedMesh::from_mesh(&scene.mesh, d.owned_nodes.clone(), d.owned_elements.clone())
}

/// Where a stage stands, for progress lines: "λ = 0.375" or "t = 3.20 s".
pub fn stage_time(stage: &Stage, t: f64) -> String {
    match stage.dynamic {
        Some(_) => format!("t = {t:.2} s"),
        None => format!("λ = {t:.3}"),
    }
}

/// The results step of stage `k` (index) at its time `t` of `t_end`: the step time is
/// k + t/t_end, so the stages follow each other in order in ParaView and a stage's end is at
/// its number.
fn step_info(k: usize, stage: &Stage, t: f64, t_end: f64) -> StepInfo {
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
