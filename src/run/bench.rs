//! `cfrd bench solver`: a generated linear-elastic dam section of a chosen size, run through
//! the same pipeline as any scene.

use super::options::{input, RunFailure, RunOptions};
use super::run_scene;
use crate::io::summary::{Phase, PhaseTimer, RunSummary};
use crate::parallel::any_error;
use crate::scene::Scene;
use mpi::topology::SimpleCommunicator;
use std::path::Path;
use std::time::Instant;

/// The solver benchmark scene: the seed-like dam section (H = 171 m, slopes 1:1.4, crest 10 m)
/// extruded over 355 m, sized for about `target_dofs` DOFs, linear elastic under gravity and a
/// reservoir at 159 m. Used by `cfrd bench solver`.
pub fn bench_scene(target_dofs: usize) -> Result<Scene, RunFailure> {
    let spec = crate::mesh::generate::DamSpec::seed_like(355.0, [1, 1, 1], 1)
        .with_target_dofs(target_dofs)
        .map_err(|e| input(e.to_string()))?;
    let [nx, ny, nz] = spec.divisions;
    let text = format!(
        "name: bench-dam-{target_dofs}\nunits: SI\n\
         mesh: {{ dam: {{ height: 171.0, crest_width: 10.0, upstream_slope: 1.4, downstream_slope: 1.4, \
         length: 355.0, divisions: [{nx}, {ny}, {nz}], layers: 1 }} }}\n\
         materials: {{ rockfill: {{ model: elastic, young: 8.0e8, poisson: 0.3, density: 2150.0 }} }}\n\
         blocks: {{ layer_1: {{ material: rockfill }} }}\n\
         boundary: [ {{ set: base, fix: [x, y, z] }}, {{ set: ymin, fix: [y] }}, {{ set: ymax, fix: [y] }} ]\n\
         loads: {{ gravity: {{ g: [0.0, 0.0, -9.81] }}, hydrostatic: [ {{ faces: upstream, level: 159.0 }} ] }}\n"
    );
    Scene::from_str(&text, "<benchmark scene>", Path::new(".")).map_err(|e| input(e.to_string()))
}

/// `cfrd bench solver`: runs [`bench_scene`] and returns its summary.
pub fn bench_solver(
    world: &SimpleCommunicator,
    target_dofs: usize,
    opts: &RunOptions,
) -> Result<RunSummary, RunFailure> {
    let t_all = Instant::now();
    let mut timer = PhaseTimer::new();
    timer.start(Phase::Read);
    let scene = any_error(world, bench_scene(target_dofs).map_err(|e| e.message)).map_err(input)?;
    run_scene(world, &scene, opts, timer, t_all)
}
