//! # Performance: run times, memory, Newton and solver figures
//!
//! Measured figures only, each table with the build it was measured with and the command that
//! reproduces it, on the project's development machine (2 cores, 23 GiB;
//! `scripts/bench_solver.md`), each run alone on it unless a table says otherwise. Wall times
//! are from `/usr/bin/time -v` or `total_seconds` of the run's `summary.json`, the split into
//! assembly, linear solves and output is its `phase_seconds`, memory the peak resident set per
//! rank. Single runs of one build spread by up to ±10 %, more from day to day (the coarse
//! hyperbolic scene: 23 s below, medians of 46.3 and 45.6 s on 2026-11-26 with builds ecc4f9d
//! and 7e6f952); a ratio is a measurement only where both runs were made side by side. What the
//! runs compute is in [`crate::verification`], the options in [`crate::guide`].
//!
//! Contents: [the main job](#the-main-job) · [seed dam runs](#seed-dam-runs) ·
//! [the fine run](#the-fine-run) · [where a run's time goes](#where-a-runs-time-goes) ·
//! [Newton and load steps](#newton-iterations-load-steps-and-the-integration-noise) ·
//! [linear solvers](#linear-solvers-on-the-seed-dam) · [weak scaling](#weak-scaling) ·
//! [clusters](#scaling-on-clusters) · [checkpoints](#checkpoints) ·
//! [solver benchmark](#solver-benchmark) · [material updates](#material-updates) ·
//! [accuracy against cost](#accuracy-against-cost) · [coarse quake](#the-seed-quake-coarse-mesh) ·
//! [medium quake](#the-seed-quake-medium-mesh) · [tried and rejected](#tried-and-rejected)
//!
//! ## The main job
//!
//! `bash ci/run-default.sh` runs the coarse GP-interface seed scene on 2 ranks: 25 s of solving
//! (the [coarse table](#seed-dam-runs)). The README's two commands on a fresh clone (an empty
//! `target/`, the Debian packages installed), build of ecc4f9d, under `/usr/bin/time`:
//!
//! | command | wall time | of which |
//! |---|---|---|
//! | `bash ci/run-default.sh` | 156 s | 2 min 05 s building, 28.8 s solving (`total_seconds`): 532 Newton iterations, 5 cut-backs |
//! | `bash ci/test.sh` | 1125.5 s (18 min 46 s) | fmt, clippy (2 min 45 s with its build), `cargo doc`, the test build and 23 test targets: 643 passed, 0 failed, 15 ignored |
//!
//! ## Seed dam runs
//!
//! The seed scenes (`inputs/scenes/seed_*.yaml`, written by `scripts/make_seed_scenes.sh`;
//! [`crate::guide`]), 2 ranks. Details in the tables below and in [the fine
//! run](#the-fine-run), [the coarse quake](#the-seed-quake-coarse-mesh) and [the medium
//! quake](#the-seed-quake-medium-mesh):
//!
//! | scene | DOFs | stages | linear solver | wall time on 2 ranks | peak memory per rank |
//! |---|---|---|---|---|---|
//! | coarse static | 3,360 | 14 | canonical LU (PETSc's LU) | 22–25 s | 83–86 MiB |
//! | medium static | 35,151 | 37 | reduced multigrid | 151.0–175.9 s | 247–251 MiB |
//! | fine static | 256,461 | 95 | reduced multigrid | 28.9–35.5 min | 1.93–1.94 GiB |
//! | coarse quake (GP interface), the quake stage | 3,360 | 14 + the quake | canonical LU; Schwarz + ILU(0) in the quake | 114.6 s (141 s the whole run, build of 16092e5) | 125 MiB |
//! | medium quake (GP interface), the committed scene | 35,151 | 37 + the quake | reduced multigrid; Schwarz + ILU(0) on node blocks in the quake | 24.1 min in all, the quake stage 21.2 min | 511 / 295 MiB |
//!
//! **Coarse mesh** (PETSc's LU with reused factors, 8 load steps per stage). Build of 51547bd,
//! `scripts/make_seed_static_figures.sh`, table `scripts/figures/seed_static_runs.csv`:
//!
//! | interface | wall time, 2 / 1 ranks | peak memory per rank, 2 / 1 ranks | Newton iterations | steps | cut-backs | factorizations | open / slipping interface points (of 780) |
//! |---|---|---|---|---|---|---|---|
//! | hyperbolic | 23 / 34 s | 85 / 86 MiB | 491 | 119 | 6 | 113 | 124 / 28 |
//! | Mohr–Coulomb | 22 / 32 s | 83 / 89 MiB | 489 | 118 | 5 | 116 | 114 / 0 |
//! | GP interface | 25 / 37 s | 86 / 89 MiB | 532 | 118 | 5 | 127 | 118 / 295 |
//!
//! Newton iterations per converged step: median 4, mean 4.13 / 4.14 / 4.51, at most 14. With
//! `reuse_factorization: false` the 2-rank runs take 28, 28 and 31 s. The table predates the
//! scenes' residual-secant line search (its saving: [Newton](#newton-iterations-load-steps-and-the-integration-noise)).
//!
//! **Medium mesh** (9,414 elements; reduced multigrid, extrapolated start, `newton_tol` 1e-4, 8
//! load steps per stage). `/usr/bin/time -v mpirun -n 2 cfrd run
//! inputs/scenes/seed_medium_<model>.yaml -o OUT -q` with the build named in each row:
//!
//! | interface | build | wall time | assembly / linear solves | peak memory per rank | Newton iterations | residual evaluations | steps | cut-backs | GMRES iterations |
//! |---|---|---|---|---|---|---|---|---|---|
//! | hyperbolic | 814a095 | 151.0 s | 82.0 / 64.2 s | – | 513 | 1,043 | 296 | 0 | 3,127 |
//! | Mohr–Coulomb | e25ea71 | 153.9 s | – | 251 MiB | 515 | – | – | 0 | 3,128 |
//! | GP interface | 217ffc8 | 175.9 s (output 3.8 s) | – | 248 / 247 MiB | 530 | 1,111 | 296 | 0 | 4,293 |
//!
//! The GP-interface scene solves corrections to forcing terms of 0.01, the others to 0.03
//! ([why](#linear-solvers-on-the-seed-dam)). All meet the project's 3 min, the GP scene by 2 %.
//!
//! ## The fine run
//!
//! The fine scenes (76,502 elements, 95 stages): `newton_tol` 1e-4, 8 load steps per stage
//! growing to twice the nominal one on easy steps, `reduced_amg`, `predictor: extrapolate`,
//! forcing terms 0.01 (GP interface) and 0.03. Build of 217ffc8, one part each, one after the
//! other on 2026-11-29: `BIN=… /usr/bin/time -v scripts/run_in_parts.sh
//! inputs/scenes/seed_fine_<model>.yaml DIR/<model> 2`; `scripts/figures/seed_fine_runs.csv`
//! (`scripts/make_seed_fine_figures.sh DIR`), slab tables in [`crate::verification`]:
//!
//! | interface | wall time | peak memory per rank | Newton iterations | residual evaluations | steps | cut-backs | GMRES iterations | Newton per step (median / mean / max) | assembly / linear solves / output | open / slipping interface points (of 25,304) |
//! |---|---|---|---|---|---|---|---|---|---|---|
//! | hyperbolic | 1,774.3 s (29.6 min) | 1.93 / 1.35 GiB | 910 | 1,882 | 528 | 0 | 5,178 | 2 / 1.72 / 5 | 759.1 / 912.0 / 76.4 s | 948 / 1,692 |
//! | Mohr–Coulomb | **1,735.5 s (28.9 min)** | 1.94 / 1.36 GiB | 908 | 1,870 | 527 | 0 | 5,191 | 2 / 1.72 / 5 | 724.4 / 904.3 / 70.7 s | 910 / 2 |
//! | GP interface | **2,130.2 s (35.5 min)** | 1.93 / 1.36 GiB | 951 | 2,025 | 535 | 0 | 7,238 | 2 / 1.78 / 8 | 889.7 / 1,129.3 / 80.2 s | 910 / 16,512 |
//!
//! By stage band (`stage_seconds` of `summary.json`), hyperbolic / Mohr–Coulomb / GP interface:
//!
//! | stages | wall time | steps | Newton per step | GMRES per Newton iteration |
//! |---|---|---|---|---|
//! | fill_001–fill_020 | 137.6 / 140.1 / 153.9 s | 137 / 137 / 137 | 2.06 / 2.06 / 2.04 | 2.9 / 2.9 / 3.9 |
//! | fill_021–fill_050 | 385.6 / 390.1 / 405.9 s | 157 / 157 / 158 | 1.80 / 1.80 / 1.78 | 5.1 / 5.1 / 6.9 |
//! | slab_1 | 21.0 / 17.6 / 55.4 s | 5 / 5 / 6 | 1.60 / 1.60 / 2.33 | 8.4 / 8.9 / 12.1 |
//! | fill_051–fill_086 | 761.5 / 737.4 / 805.8 s (17–27 s per stage) | 180 / 180 / 180 | 1.37 / 1.36 / 1.35 | 8.4 / 8.4 / 11.4 |
//! | slab_2 (the hard case) | 39.0 / 39.5 / 91.9 s | 6 / 6 / 6 | 1.33 / 1.50 / 3.17 | 12.0 / 11.4 / 9.6 |
//! | slab_3 | 29.2 / 26.9 / 58.1 s | 5 / 5 / 5 | 1.00 / 1.00 / 2.00 | 13.4 / 12.8 / 14.1 |
//! | impound_1–impound_6 | 341.3 / 329.0 / 494.5 s | 38 / 37 / 43 | 2.05 / 2.05 / 2.44 | 8.1 / 8.5 / 9.1 |
//!
//! The fill costs the same with the hyperbolic and the ideal elasto-plastic interface (which
//! are not in place below slab stage I); the GP scene's forcing terms of 0.01 cost GMRES
//! iterations throughout, its slipping points Newton iterations in the slab stages and the
//! impoundment. Slab stage II passes without a cut-back in all three. Of the project's targets
//! (30 min and 3 GiB per rank on 2 ranks) all three meet the memory, the hyperbolic (by 1.4 %)
//! and ideal elasto-plastic scenes the time; the GP-interface scene is 18 % over. A second
//! hyperbolic run (same build and command, three hours later): 1,767.2 s (29.5 min), assembly
//! 752.2 s, linear solves 909.3 s, output 76.2 s, the same counts and slab table byte for byte.
//! Single runs on different days moved the assembly by 8 % and the solves by 9 %.
//!
//! **Output and the paced stage-end writes.** A stage's end publishes `results.h5` (a copy of
//! the file, which grows by 17 MB a stage to 1.6 GB) and writes the checkpoint, so writing at
//! every stage costs work quadratic in the stages: the copies took 0.17 s at stage 8 and
//! 3.4–3.8 s from stage 52 on, 79 s to stage 55 (build of 50e4ecd with timing lines).
//! [`crate::io::pacing`] writes once the run has computed 39 times as long as the last writes
//! took (at most 2.5 % of the run). The first 55 stages, every-stage writes against a ratio of
//! 19 (builds 50e4ecd and dc7a8a1, one pair, `/usr/bin/time -v mpirun -n 2 cfrd run
//! inputs/scenes/seed_fine_hyperbolic.yaml -o OUT --checkpoint stage --stop-after-stage 55`
//! with `-log_view`): 796.8 s against 742.8 s (0.932), output 106.8 s against 39.9 s,
//! checkpoints 21.5 s against 9.8 s, the same 664 Newton iterations and bits. On the whole fine
//! hyperbolic run a ratio of 19 left 102.0 and 104.6 s of output (builds 9345339 and 25c0469,
//! the counts above), 39 leaves 76.4 s. A killed run recomputes at most 39 times its last
//! writes' time (about 3 min on the fine mesh).
//!
//! **The growing load steps' cost in accuracy** (`cfrd accuracy --reference`, the growing-step
//! run of build 9345339 against the equal-step run of 42e465a): the slab table within 2.6e-4
//! (σ_s), 6.3e-4 (σ_a) and 1.3e-4 (deflection) of its largest values, 0.0022 MPa, 0.0041 MPa and
//! 0.0018 cm after impoundment, the crest settlement within 5.5e-4.
//!
//! ## Where a run's time goes
//!
//! The assembly, linear solves and output of each run are in its table: 759.1 / 912.0 / 76.4 s
//! of the fine hyperbolic run's 1,774.3 s, 82.0 / 64.2 s of the medium one's 151.0 s, and in
//! the medium quakes 1,758–1,846 s of assembly and 1,274–1,510 s of linear solves. Assembly is
//! mostly the GP rockfill's integration: 7.1 accepted and 1.2 rejected substeps per integration
//! of a nonzero increment, set by the error tolerance STOL (1e-4), not by the substep growth
//! limit (a counter in [`crate::material::gp_integrator::integrate`], not committed, in a build
//! of f99ca09's code; `cfrd run inputs/scenes/seed_medium_hyperbolic.yaml -o OUT -q
//! --stop-after-stage 6`, 1 rank).
//!
//! **A fine fill stage in detail** (build of 814a095): `fill_051`–`fill_054` restarted from the
//! checkpoint after slab stage I (`mpirun -n 2 cfrd run inputs/scenes/seed_fine_hyperbolic.yaml
//! -o OUT -q --restart CK --stop-after-stage 55`): 20 steps, 34 Newton iterations, 74 residual
//! evaluations, 212 GMRES iterations, 72.2, 79.1 and 78.1 s in three runs. `-log_view` (80.2 s):
//! the residual evaluations of the line searches 23.4 s and of the steps' starts 7.9 s, the
//! tangents 7.8 s; the structure's 34 factorizations 8.0 s and 246 triangular solves 10.6 s,
//! the fill's V-cycles 16.9 s (SOR 12.4 s), the extraction of the blocks 4.6 s and the fill's 4
//! multigrid set-ups 2.6 s. `perf` shows no function above 6 % (the GP integration's `pow`
//! 5.5 %, its functions together some 15 %).
//!
//! ## Newton iterations, load steps and the integration noise
//!
//! * **Newton tolerance.** Every Newton iteration integrates the GP points over the whole step
//!   increment from the committed state, and the substepping (STOL 1e-4) leaves an
//!   out-of-balance force of about 2e-6 of the layer weight (3e3 N at a cushion corner node of
//!   the coarse mesh's first fill layer), below which Newton cannot go. The coarse and quake
//!   scenes stop at `newton_tol: 1.0e-5`; the medium and fine ones at 1e-4, as accurate on the
//!   medium mesh in 0.61 of the time ([the medium mesh's Newton tolerance](#the-medium-meshs-newton-tolerance)).
//! * **The integration noise.** On the canonical LU's fine run (build of 6549cb1, slab stage II,
//!   `newton_tol` 1e-5, `--monitor`) the first load step starts at a relative residual of
//!   1.16e-4 and stays at 1.125e-4, to four digits, for 14 iterations (largest out-of-balance
//!   force 25 kN, at a node of the new slab at 2739 m); with the GP rockfill at STOL 1e-6
//!   (`--integration-tol-ratio 0.1`) it converges in 3. `integration_tol_ratio` is off by default: with it two
//!   GP dam tests of `tests/cfrd_dam.rs` exhaust the substep limit, and applied only to a
//!   stalled step it made them take 504 s instead of 117 s. At `newton_tol` 1e-4 the fine
//!   scenes pass slab stage II without it.
//! * **Load steps.** 8 per stage: a step too large to converge spends its 15 iterations before
//!   it is cut back, so on the coarse mesh fewer steps are slower and less accurate (1 step per
//!   stage 93.0 s with 30 cut-backs, 8 steps 25.3 s, 16 steps 21.7 s;
//!   [accuracy table](#accuracy-against-cost)). New fill layers start unconfined, where the GP
//!   model is softest: two load steps per fill layer instead of eight made the fine mesh's
//!   first 9 fill stages take 211 s instead of 110 s (build of b907149).
//! * **Load steps that grow on easy steps** (`solver.step_growth: G`,
//!   [`crate::solver::step_control`]): a step converged in one Newton iteration doubles the
//!   next, up to G times the nominal step; a step of more than three halves it back. Restarted
//!   after `slab_1`, `fill_051`–`fill_054` on 2 ranks (a prototype build reading G from the
//!   environment): G = 1 76.1 and 81.7 s, 32 steps, 40 Newton, 272 GMRES iterations; G = 2
//!   70.8 s, 20, 32, 205; G = 4 76.2 s, G = 2's counts. Every stage goes 3, 1, 2, 1, 1 Newton
//!   iterations over steps of 1/8, 1/8, 1/4, 1/4, 1/4, so G = 4 never grows past 2: the fine
//!   scenes take G = 2. The medium scenes and the extra-fine dam keep equal steps.
//! * **Predictor** (`solver.predictor: extrapolate`, [`crate::solver::integrator::QuasiStatic`]):
//!   a static step starts from the last step's rate. Medium scenes, build of 8e28a14
//!   (`/usr/bin/time mpirun -n 2 cfrd run SCENE -o OUT -q`, without and with the key):
//!   hyperbolic 356.1 → 291.0 s (1,155 → 910 Newton iterations), GP interface 414.2 → 341.0 s
//!   (1,222 → 984); slab tables within 0.0083 MPa and 0.0014 cm, 0.038 MPa in the GP
//!   interface's lower slab. On the coarse mesh (build of 8cb1fcb) it saves 16–18 % of the
//!   Newton iterations and no time, so the coarse scenes keep the plain start; under
//!   `--checkpoint step` it is idle. A predicted start that fails in a material update, or whose
//!   relative residual reaches 0.5, is dropped for the converged state
//!   ([`crate::solver::Problem::solve_step`]): the GP interface's closure stiffens towards its
//!   void-ratio bound, which a straight-line start overshoots. On the medium GP-interface scene
//!   (`--monitor --checkpoint none`, builds dc7a8a1 and 42e465a, one pair) that takes 11
//!   cut-backs to 1 and 214.2 s to 199.7 s.
//! * **Line search of the static stages** (`solver.line_search: residual_secant`, the default;
//!   [`crate::scene::schema::LineSearch`]). The GP rockfill's continuum tangent is stiffer than
//!   the consistent one, so corrections fall short (PETSc's `l2`, `secant`, takes λ > 1.05 in 349
//!   of the coarse hyperbolic scene's 565 Newton iterations). The residual secant evaluates F at
//!   the full step and takes the secant through F(x) and F(x − δ): the full step when that λ is
//!   within 0.1 of 1 (one evaluation), the longer step when it lowers ‖F‖ further (two), `l2`'s
//!   step otherwise (three). Build of 0842bb7, 2 ranks, one pair each (scene variants with
//!   `line_search` set; errors by `cfrd accuracy` against `secant`; medium `--stop-after-stage
//!   18`, fields by `cfrd compare`):
//!
//!   | scene | `secant`: wall time, Newton iterations, residual evaluations | `residual_secant`: the same | cut-backs | largest error σ_s / σ_a / deflection / crest |
//!   |---|---|---|---|---|
//!   | coarse hyperbolic | 43.1 s, 490, 1,818 | 35.4 s, 484, 1,153 | 5 / 5 | 1.0e-4 / 4.0e-4 / 4.4e-5 / 1.1e-4 |
//!   | coarse Mohr–Coulomb | 43.8 s, 489, 1,815 | 33.5 s, 475, 1,132 | 5 / 5 | 1.1e-4 / 4.4e-4 / 4.5e-5 / 1.6e-6 |
//!   | coarse GP interface | 61.4 s, 559, 2,047 | 48.6 s, 555, 1,356 | 5 / 5 | 1.4e-3 / 2.9e-3 / 5.8e-5 / 1.8e-4 |
//!   | medium hyperbolic, stages 1–18 | 258.7 s, 670, 2,154 | 188.7 s, 655, 1,283 | 0 / 0 | fields at slab_1: displacement 1.7e-2, stress 1.1e-2, strain 2.4e-2 |
//!
//!   The same Newton iterations and cut-backs for 34–40 % fewer residual evaluations. With the
//!   halving fallback where F cannot be evaluated (build of 6acaa62, the goldens' path) the
//!   coarse GP-interface scene takes 547 Newton iterations, its slab table within 1.9e-3 of the
//!   run above.
//! * **Rockfill tangent.** `tangent: numerical` converges in 4–5 Newton iterations where the
//!   continuum tangent creeps, but costs 13 integrations per update instead of one; the seed
//!   scenes keep the continuum tangent.
//!
//! ## Linear solvers on the seed dam
//!
//! | where | solver | why |
//! |---|---|---|
//! | coarse static scenes | `canonical_lu`, PETSc's LU | the same bits on any rank count (the goldens); on 3,360 DOFs the fastest factorization (first stage: PETSc's LU 1.1 s for 73 factorizations, MUMPS on the reference BLAS 12.1 s; build of a04d54c) |
//! | medium and fine static scenes | `reduced_amg`: GAMG on the fill, the slab, interfaces and joints factored by SuperLU_DIST, inexact Newton | under half the canonical LU's time and memory per rank on the medium mesh, 4.5 and 10.8 times faster with a quarter of its memory on fine stages; the same bits at every run on one rank count |
//! | static stages of the quake scenes | `canonical_lu` with MUMPS | the dynamic stages were verified on it |
//! | dynamic stages | GMRES to 1e-6, or to a tenth of the Newton tolerance where looser, with ILU(0) of the current Jacobian (canonical), additive Schwarz with ILU(0) subdomains on the Jacobian in node blocks (`distributed_lu`) | a time step's Jacobian is dominated by the mass term: 2.03 times faster than lagged complete factors on the coarse quake, 2.0 times on the medium one ([coarse quake](#the-seed-quake-coarse-mesh), [medium quake](#the-seed-quake-medium-mesh)) |
//! | a mesh whose factors do not fit one rank | `distributed_lu` (MUMPS over the ranks) | a third less memory per rank than the canonical LU, 1.24 times slower on 2 ranks |
//!
//! GAMG on the whole matrix (the default iterative solver) fails on the seed dam: the stiff
//! interfaces and joints (k2 1e10 and 2.5e10 Pa/m) defeat it. Factoring the interface, joint
//! and slab nodes apart, with GAMG on the rest of the coupled rows, takes the medium impoundment
//! from about 490 GMRES iterations per solve to 40 at rtol 1e-7 (build of d2432ba).
//!
//! **Reduced multigrid against the canonical LU** (`--linear-solver canonical_lu
//! -canonical_pc_factor_mat_solver_type mumps` against the scene's solver, 2 ranks, one after
//! the other; medium `/usr/bin/time -v mpirun -n 2 cfrd run inputs/scenes/seed_medium_<model>.yaml
//! -o OUT -q`; fine `mpirun -n 2 cfrd run inputs/scenes/seed_fine_hyperbolic.yaml -o OUT -q
//! --restart CK --stop-after-stage +1` from the checkpoint before the stage):
//!
//! | run | build | canonical LU | reduced multigrid | results agree to |
//! |---|---|---|---|---|
//! | medium hyperbolic | 8e28a14 | 614.3 s, 903 Newton, 597 MiB | 291.0 s, 910 Newton, 269 MiB | slab 0.0006 / 0.0065 MPa (σ_s / σ_a), 0.0002 cm |
//! | medium GP interface (forcing 0.03) | 8e28a14 | 832.5 s, 984 Newton, 7 cut-backs, 817 MiB | 341.0 s, 984 Newton, 9 cut-backs, 262 MiB | slab 0.0047 / 0.0091 MPa, 0.0008 cm |
//! | medium GP interface (forcing 0.03) | e25ea71 | 795.1 s, 532 Newton, 611 MiB | 179.6, 178.0 s, 531 Newton, 246–248 MiB | slab after impoundment 0.079 / 0.043 MPa, 0.0048 cm |
//! | fine `fill_051` | 3c9d446 | 376.7 s, 31 Newton, 3.6 GiB | 83.4 s, 30 Newton, 0.95 / 0.99 GiB | fields 3.2e-4 of their largest value, slab 5 Pa |
//! | fine `impound_1` | 3c9d446 | 1,249.8 s, 19 Newton, 6.0 GiB | 115.9 s, 19 Newton, 1.32 / 1.36 GiB | fields 4.6e-5, slab 42 Pa |
//!
//! The whole fine hyperbolic run on the canonical LU (build of 6549cb1, trilinear slab,
//! `scripts/run_in_parts.sh inputs/scenes/seed_fine_hyperbolic.yaml DIR 2`, seven parts, net of
//! stops) took 341 min (5.7 h) with 10.2 GiB per rank, 2,930 Newton iterations, 3 cut-backs;
//! from slab stage I on about 80 % of a stage went into the MUMPS factorization (`perf`).
//!
//! **Forcing terms of the GP-interface scenes.** The inexact Newton solves corrections to
//! Eisenstat–Walker forcing terms of at most 0.03 ([`crate::linalg::petsc::reduced_amg`]). The medium
//! GP-interface scene against its canonical-LU run (build of e25ea71, above), largest
//! differences of the slab table:
//!
//! | run | end of construction σ_s / σ_a / deflection | after impoundment σ_s / σ_a / deflection |
//! |---|---|---|
//! | forcing terms 0.03 (e25ea71) | 0.0006 / 0.0005 MPa / 0.0003 cm | **0.079 / 0.043 MPa** / 0.0048 cm |
//! | forcing terms 0.01 (the scene, build of 9345339) | 0.0002 / 0.0002 MPa / 0.0002 cm | 0.018 / 0.016 MPa / 0.0035 cm |
//!
//! In the impoundment the slipping GP interface follows the path of the converged states, and
//! looser iterates carry it 0.079 MPa away, beyond the 0.02 MPa the project allows between
//! solvers; so the GP-interface scenes give `-snes_ksp_ew_rtol0 0.01 -snes_ksp_ew_rtolmax 0.01`.
//!
//! **The structure factored at every Jacobian** (`-reduced_structure_refresh_after 0`, the
//! default; the fill's multigrid is kept while GMRES converges quickly): the interfaces' tangent
//! follows their stress and the slab hangs on it. Fine `fill_051` and `impound_1`, restarted as
//! above, builds of 42e465a (all lagged) and c991192 alternated, two pairs each: 0.936 and 0.801
//! of the lagged stage time, GMRES iterations 134 → 88 and 144 → 71.
//!
//! **The same bits at every run.** MUMPS's parallel factorization sums in an order that follows
//! message timing: three runs of the medium Mohr–Coulomb scene with MUMPS on the structure took
//! 1,150, 1,163 and 1,148 Newton iterations. With SuperLU_DIST (one OpenMP thread per rank) two
//! runs of the medium hyperbolic scene (same build, runs A and C: 396.9 and 423.5 s) give the
//! same bits; MUMPS (run B) took 447.4 s with 12 % less memory per rank. Test:
//! `multigrid_on_the_coupled_rows_gives_the_same_bits_at_every_run`. Other rank counts give
//! other bits; only the canonical LU is rank-count independent.
//!
//! **Distributed LU** (`linear_solver: distributed_lu`), the medium hyperbolic scene, build of
//! e4f3019, `CFRD_BIN=… scripts/solver_choice.sh RUNS 2 inputs/scenes/seed_medium_hyperbolic.yaml`:
//! canonical LU 570.0 s, 1,184 Newton iterations, 595 / 809 MiB per rank; distributed LU
//! 708.6 s, 1,186, 395 / 535 MiB; slab tables within 0.0023 MPa and 0.0024 cm. On the coarse
//! scenes (`scripts/solver_choice.sh RUNS 2`, build of 14ba286) 1.26–1.37 times slower, within
//! 0.005 MPa and 0.001 cm. Two runs differ in the last bits.
//!
//! **Hard cases: one load step per stage** (build of f99ca09; `/usr/bin/time mpirun -n 2 cfrd
//! run SCENE -o OUT -q --linear-solver S`, coarse scenes with `load_steps: 1`): hyperbolic
//! 85.4 s (canonical LU: 370 Newton iterations, 29 cut-backs) and 90.8 s (reduced multigrid:
//! 396, 30), GP interface 115.2 s (413, 32) and 124.3 s (439, 33); slab tables within 0.0014 MPa.
//!
//! ## Weak scaling
//!
//! One stage rerun from the checkpoint written at the end of the stage before it, on 2 ranks
//! and then on 1: `bash scripts/weak_scaling.sh RUN_DIR LABEL SCENE CHECKPOINT --linear-solver
//! reduced_amg` (`--restart CHECKPOINT --stop-after-stage +1`; `stage_seconds` and
//! `peak_memory_bytes_per_rank` of `summary.json`), build of dc7a8a1, the hyperbolic scenes
//! with equal load steps (`newton_tol` 1e-4, 8 load steps per stage). The stages: the first
//! fill stage after slab stage I (medium `fill_018`, fine `fill_051`, extra fine `fill_065`)
//! and the first impoundment stage.
//!
//! | mesh | DOFs | stage | ranks | wall time | Newton iterations | GMRES iterations | time per Newton iteration | GMRES per Newton iteration | peak memory per rank |
//! |---|---|---|---|---|---|---|---|---|---|
//! | medium | 35,151 | fill_018 | 2 | 4.2 s | 12 | 158 | 0.35 s | 13.2 | 175 / 180 MiB |
//! | medium | 35,151 | fill_018 | 1 | 8.0 s | 12 | 157 | 0.67 s | 13.1 | 279 MiB |
//! | fine | 256,461 | fill_051 | 2 | 27.7 s | 10 | 134 | 2.77 s | 13.4 | 1,054 / 1,053 MiB |
//! | fine | 256,461 | fill_051 | 1 | 48.8 s | 10 | 132 | 4.88 s | 13.2 | 1,874 MiB |
//! | extra fine | 1,018,689 | fill_065 | 2 | 102.4 s | 11 | 131 | 9.31 s | 11.9 | 4,082 / 4,003 MiB |
//! | extra fine | 1,018,689 | fill_065 | 1 | 217.5 s | 11 | 133 | 19.77 s | 12.1 | 7,534 MiB |
//! | medium | 35,151 | impound_1 | 2 | 8.0 s | 14 | 199 | 0.57 s | 14.2 | 259 / 257 MiB |
//! | medium | 35,151 | impound_1 | 1 | 13.9 s | 13 | 183 | 1.07 s | 14.1 | 394 MiB |
//! | fine | 256,461 | impound_1 | 2 | 52.0 s | 10 | 144 | 5.20 s | 14.4 | 1,404 / 1,436 MiB |
//! | fine | 256,461 | impound_1 | 1 | 93.8 s | 10 | 144 | 9.38 s | 14.4 | 2,546 MiB |
//! | extra fine | 1,018,689 | impound_1 | 2 | 242.8 s | 11 | 175 | 22.08 s | 15.9 | 5,338 / 5,060 MiB |
//! | extra fine | 1,018,689 | impound_1 | 1 | 442.4 s | 11 | 175 | 40.22 s | 15.9 | 9,422 MiB |
//!
//! * **GMRES iterations do not grow with the mesh**: 13.2, 13.4 and 11.9 per Newton iteration
//!   in the fill stage over 29 times the DOFs; 14.2, 14.4 and 15.9 in the impoundment.
//! * **Time per Newton iteration** on 2 ranks grows 7.8 (fill) and 9.1 times (impoundment) for
//!   7.3 times the DOFs, 26 and 39 times for 29 times: about linear in the fill, more in the
//!   impoundment. **2 ranks** are 1.74–2.12 times faster than 1, at 0.53–0.66 of its memory.
//! * **The extra-fine dam** (`inputs/scenes/seed_xfine_hyperbolic.yaml`, 319,646 elements, 119
//!   stages), build of dc7a8a1, `BIN=… scripts/run_in_parts.sh
//!   inputs/scenes/seed_xfine_hyperbolic.yaml DIR 2 -- --stop-after-stage 65`: to the end of
//!   slab stage I in 3,911 s net of stops, 848 Newton iterations, 0 cut-backs, 5.81 / 4.12 GiB
//!   per rank; to stage 113 (parts sharing the machine) 1,287 Newton iterations, 0 cut-backs.
//!
//! ## Scaling on clusters
//!
//! Nothing here ran on more than 2 ranks: measured inputs, then a projection that is only as
//! good as its stated assumptions.
//!
//! **Partitions** (`cfrd partition -n P -o FILE SCENE`, build of b16fc90, which prints these
//! figures; METIS with every construction band balanced over the parts):
//!
//! | mesh | P | elements per part, max / mean | ghost nodes of a part, max | ghost nodes, total | largest ghost / owned nodes of a part | METIS |
//! |---|---|---|---|---|---|---|
//! | medium (9,414 elements, 11,717 nodes) | 2 | 4,819 / 4,707 | 437 | 437 | 0.080 | 0.06 s |
//! | medium | 8 | 1,200 / 1,177 | 882 | 3,064 | 0.83 | 0.19 s |
//! | medium | 32 | 301 / 294 | 522 | 8,709 | 4.1 | 0.72 s |
//! | medium | 128 | 79 / 73.5 | 252 | 19,062 | 19.4 | 1.70 s |
//! | fine (76,502 elements, 85,487 nodes) | 2 | 39,330 / 38,251 | 1,893 | 1,893 | 0.044 | 0.13 s |
//! | fine | 8 | 9,872 / 9,563 | 2,391 | 11,680 | 0.19 | 0.32 s |
//! | fine | 32 | 2,470 / 2,391 | 1,726 | 32,090 | 0.46 | 0.75 s |
//! | fine | 128 | 615 / 598 | 862 | 65,192 | 0.74 | 3.13 s |
//!
//! The balance holds (at most 7.5 % over the mean); `cfrd partition` on the fine mesh peaks at
//! 74 MiB, and the ghost exchange moves at most 862 × 3 values (21 kB) per rank on 128 parts;
//! the medium mesh has more ghost than owned nodes per part from 32 ranks on. `cfrd run`
//! balances the elements a rank evaluates for its owned rows
//! ([`partition::partition_for_assembly`]; fine, 8 parts: busiest 11,490 instead of 12,315).
//!
//! **Parallel efficiency**, the medium hyperbolic scene (`/usr/bin/time -v mpirun -n P cfrd run
//! inputs/scenes/seed_medium_hyperbolic.yaml -o OUT -q`, 1 rank right after the 2-rank runs):
//!
//! | solver | build | 1 rank: wall / assembly / solves | 2 ranks: wall / assembly / solves | speed-up | memory per rank, 1 → 2 ranks |
//! |---|---|---|---|---|---|
//! | canonical LU | e4f3019 | 768.0 / 440.9 / 319.0 s | 570.0 / 243.1 / 321.4 s | 1.35 | 650 → 595 / 809 MiB |
//! | reduced multigrid | as runs A and C above | 873.0 / 435.4 / 421.7 s | 396.9 / 208.8 / 177.3 s (A) | 2.20 (A), 2.06 (C) | 390 → 257 / 252 MiB |
//!
//! The canonical LU factors the whole coupled block on every rank, so its solves do not speed
//! up; projected on P ranks (assembly 440.9 s / P times the partition's max / mean elements
//! times the 1.077 overhead of the 2-rank run, linear solves 321 s, the rest 8 s) the medium
//! scene takes 390, 344 and 333 s on 8, 32 and 128 ranks, a speed-up of 1.97, 2.23 and 2.31
//! against Amdahl's 768 / 329 = 2.33. The reduced multigrid's assembly splits evenly and its
//! solves more than evenly.
//!
//! **Projection for the fine dam on the reduced multigrid**, from a whole fine hyperbolic run
//! with equal load steps (build of 42e465a, 2,426.4 s in three parts: assembly 786.9 s, linear
//! solves 1,496.4 s, output 90.9 s) and the fine partitions above. The assembly falls with the
//! largest part's elements. Of the linear solves, the fill's multigrid (216 s of the 376 s of
//! `KSPSolve` and `PCSetUp` in a `-log_view` of the first 55 stages) falls the same way, its
//! GMRES iterations flat as measured; the rest (the structure's factorization and solves, the
//! Krylov vectors) as well (optimistic) or not at all (pessimistic, 43 % of the solves:
//! 636.8 s). Output is held at 90.9 s:
//!
//! | P | largest part / 2-rank part | assembly | linear solves, optimistic / pessimistic | whole run, optimistic / pessimistic |
//! |---|---|---|---|---|
//! | 2 (measured) | 1 | 786.9 s | 1,496.4 s | 40.4 min |
//! | 8 | 0.251 | 197.5 s | 375.6 / 852.3 s | 11.1 / 19.0 min |
//! | 32 | 0.0628 | 49.4 s | 94.0 / 690.7 s | 3.9 / 13.9 min |
//! | 128 | 0.0156 | 12.3 s | 23.4 / 650.2 s | 2.1 / 12.6 min |
//!
//! Where a cluster lands between the columns depends on how SuperLU_DIST factors the structure
//! over many ranks: `scripts/solver_choice.sh RUNS P SCENE` measures it there. The coarse-grid
//! solve of the fill's multigrid and the ghost exchanges are not in the model.
//!
//! ## Checkpoints
//!
//! * A checkpoint of the fine run is 102–105 MB; the whole fine hyperbolic run's paced
//!   checkpoints took 6.3 s ([the fine run](#the-fine-run)).
//! * Step checkpoints start a fresh preconditioner: the coarse hyperbolic scene on 2 ranks made
//!   192 factorizations instead of 113, 24.6 s instead of 22.6 s (build of 809a854,
//!   `--checkpoint step`).
//! * The integrity checks ([`crate::io::integrity`]: checksums, read-back, appended record) cost
//!   about 3 ms per 1 MB checkpoint: the coarse GP-interface scene with 122 step checkpoints
//!   (`mpirun -n 2 cfrd run ... --checkpoint step`, builds cc028bd and ef383e6 alternated, two
//!   pairs), `checkpoint_seconds` 0.56 / 0.54 s without and 0.86 / 0.98 s with them.
//!
//! ## Solver benchmark
//!
//! `bash scripts/bench_solver.sh` (build of 0f413f9, table `scripts/bench_solver.md`): the
//! seed-like dam section (H 171 m, 1:1.4 slopes) at three sizes, elastic self-weight, the default
//! iterative solver (CG, GAMG with the rigid-body near-null space, rtol 1e-10), slowest rank:
//!
//! | ranks | DOFs | elements | assembly (s) | solve (s) | KSP iterations | peak memory, max over ranks (MiB) | DOFs/s (assembly + solve) |
//! |---|---|---|---|---|---|---|---|
//! | 1 | 101568 | 30690 | 1.47 | 10.35 | 160 | 253 | 8595 |
//! | 2 | 101568 | 30690 | 0.70 | 4.76 | 162 | 240 | 18591 |
//! | 1 | 297792 | 92690 | 4.00 | 32.90 | 183 | 670 | 8070 |
//! | 2 | 297792 | 92690 | 2.45 | 19.09 | 186 | 622 | 13826 |
//! | 1 | 997920 | 317814 | 14.04 | 140.76 | 203 | 2160 | 6446 |
//! | 2 | 997920 | 317814 | 8.61 | 78.00 | 208 | 2020 | 11522 |
//!
//! KSP iterations grow by 27 % over a tenfold growth of the mesh (unpreconditioned CG: about
//! 2.2×); `-pc_type hypre` takes 16 iterations at 100k DOFs.
//!
//! ## Material updates
//!
//! `cfrd bench materials` (build of 0f413f9; one core; [`crate::material::bench`]). The
//! generalized-plasticity models (Pastor, Zienkiewicz & Chan 1990) pay for substepping:
//!
//! | model | path | updates/s (1 core) | µs/update | substeps/update | updates × passes × reps | path and increments |
//! |---|---|---:|---:|---:|---:|---|
//! | rockfill_gp | monotonic | 3.227e5 | 3.099 | 2.52 | 200 × 85 × 7 | drained triaxial, σ3 = 1000 kPa, dε_a = 5e-4 per step to 10 % |
//! | rockfill_gp | cyclic | 2.554e5 | 3.915 | 3.08 | 250 × 53 × 7 | drained cyclic triaxial, σ3 = 1000 kPa, q 0–2500 kPa, dq = 100 kPa per step, 5 cycles |
//! | gp_interface | monotonic | 8.659e5 | 1.155 | 1.03 | 300 × 154 × 7 | CNL direct shear, σn = 400 kPa, du = 0.2 mm per step to 60 mm |
//! | gp_interface | cyclic | 8.060e5 | 1.241 | 1.09 | 600 × 73 × 7 | CNL direct shear, σn = 400 kPa, ±10 mm, du = 0.2 mm per step, 3 cycles |
//! | hyperbolic | monotonic | 5.063e6 | 0.198 | 1.00 | 300 × 858 × 7 | as gp_interface |
//! | hyperbolic | cyclic | 5.378e6 | 0.186 | 1.01 | 600 × 470 × 7 | as gp_interface |
//! | mohr_coulomb | monotonic | 1.339e7 | 0.075 | 1.00 | 300 × 2289 × 7 | as gp_interface |
//! | mohr_coulomb | cyclic | 1.446e7 | 0.069 | 1.00 | 600 × 1219 × 7 | as gp_interface |
//! | joint | monotonic | 4.967e7 | 0.020 | 1.00 | 300 × 8472 × 7 | as gp_interface |
//! | joint | cyclic | 4.845e7 | 0.021 | 1.00 | 600 × 4263 × 7 | as gp_interface |
//! | elastic | monotonic | 2.682e7 | 0.037 | 1.00 | 200 × 6838 × 7 | as rockfill_gp |
//! | elastic | cyclic | 2.808e7 | 0.036 | 1.00 | 250 × 3606 × 7 | as rockfill_gp |
//!
//! ## Accuracy against cost
//!
//! `bash scripts/accuracy_cost.sh RUNS` (build of 39e961d): the coarse hyperbolic seed scene on
//! 2 ranks with one setting changed at a time, against a reference with the load path at its
//! most accurate (16 load steps per stage, STOL 1e-6, Newton tolerance 1e-6; 124 s). Errors
//! ([`crate::post::accuracy`]): the largest difference over the slab points of the central section
//! after impoundment, relative to the reference's largest magnitude; the crest settlement's
//! relative difference. Table `scripts/figures/accuracy_cost.csv`.
//!
//! ![accuracy against cost][accuracy]
//!
//! | run | wall time | Newton iterations / cut-backs | σ_s | σ_a | deflection | crest settlement |
//! |---|---|---|---|---|---|---|
//! | the scene: 8 load steps, STOL 1e-4, Newton 1e-5, nodal rule | 25.3 s | 491 / 6 | 5.9e-4 | 9.1e-4 | 7.8e-5 | 1.4e-4 |
//! | 1 load step | 93.0 s | 385 / 30 | 2.0e-2 | 1.9e-2 | 1.4e-3 | 6.3e-3 |
//! | 2 load steps | 55.7 s | 396 / 21 | 8.4e-3 | 8.3e-3 | 4.6e-4 | 2.5e-3 |
//! | 4 load steps | 37.7 s | 439 / 14 | 2.2e-3 | 3.1e-3 | 2.3e-4 | 6.1e-4 |
//! | 16 load steps | 21.7 s | 669 / 2 | 3.7e-4 | 3.8e-4 | 8.1e-5 | 1.1e-4 |
//! | STOL 1e-3 | 15.5 s | 514 / 5 | 1.3e-3 | 1.0e-3 | 7.6e-5 | 5.3e-4 |
//! | STOL 1e-5 | 50.3 s | 501 / 6 | 5.8e-4 | 9.9e-4 | 1.4e-4 | 1.8e-4 |
//! | STOL 1e-6 | 129.5 s | 490 / 5 | 7.5e-4 | 1.2e-3 | 1.8e-4 | 2.0e-4 |
//! | Newton 1e-4 | 17.2 s | 319 / 3 | 4.9e-4 | 7.9e-4 | 4.6e-5 | 4.7e-4 |
//! | Newton 1e-6 | 43.7 s | 858 / 31 | 1.0e-3 | 1.1e-3 | 2.2e-4 | 4.2e-4 |
//! | Gauss 2×2 interface rule | 25.8 s | 503 / 5 | 2.7e-2 | 4.1e-2 | 1.1e-2 | 3.6e-3 |
//!
//! * **The load path.** Fewer load steps are both less accurate and slower (30 cut-backs with
//!   one step per stage); sixteen steps per stage were the fastest and most accurate run here.
//! * **STOL and the Newton tolerance** move the slab by about 1e-3 at most; tighter than the
//!   defaults they cost time (STOL 1e-6: 5 times) for nothing measurable, and Newton 1e-6 stalls
//!   on the integration noise (31 cut-backs).
//! * **The interface integration rule** moves the slab stresses by 3–4 %, ten times any
//!   solution-control setting: a modelling choice, not a tolerance.
//!
//! ### The mesh
//!
//! `MEDIUM=1 bash scripts/accuracy_cost.sh RUNS` (build of cc66417; the coarse runs above
//! reused): the medium hyperbolic scene (with the settings of that build: canonical LU, Newton
//! 1e-5) is the reference of the coarse runs. Table `scripts/figures/mesh/accuracy_cost.csv`;
//! the fine mesh against the medium one is in [`crate::verification`] (the same error measure).
//!
//! ![coarse against medium mesh][mesh]
//!
//! | run | wall time | Newton iterations / cut-backs | σ_s | σ_a | deflection | crest settlement |
//! |---|---|---|---|---|---|---|
//! | medium mesh, the scene's settings (reference) | 696.6 s | 1236 / 8 | | | | |
//! | coarse mesh, the scene's settings | 25.3 s | 491 / 6 | 2.6e-1 | 2.7e-1 | 3.1e-1 | 1.5e-1 |
//! | coarse mesh, 16 load steps | 21.7 s | 669 / 2 | 2.6e-1 | 2.7e-1 | 3.1e-1 | 1.5e-1 |
//! | coarse mesh, Gauss 2×2 interface rule | 25.8 s | 503 / 5 | 2.5e-1 | 2.5e-1 | 3.2e-1 | 1.6e-1 |
//! | fine against medium ([`crate::verification`]) | hours | | 8e-2 | 2.5e-2 | 7.6e-2 | |
//!
//! The coarse mesh is 26–31 % off in the slab after impoundment and 15 % in the crest
//! settlement, a hundred times the error of any load-path or tolerance setting; the medium mesh
//! is within 2.5–8 % of the fine one. So: **a quick look**, the coarse scenes (half a minute),
//! for trends and for checking a scene, not for stresses; **a design check**, the medium mesh,
//! with 16 load steps per stage at Newton 1e-5 for the most accurate load path; **a paper**, the
//! fine mesh (or a mesh study ending in it), with the interface rule stated and both rules
//! compared.
//!
//! ### The medium mesh's Newton tolerance
//!
//! The medium hyperbolic scene against a reference of **32 load steps per stage** (Newton 1e-5,
//! 366.7 s), 2 ranks, errors by `cfrd accuracy --reference REF -o OUT LABEL=DIR …` (as above),
//! scene variants with `load_steps` and `newton_tol` changed; builds of ad29fd6 and cfad9f2 (a
//! line search that no longer extends a converged full step). Table
//! `scripts/figures/newton_tol/accuracy_cost.csv`.
//!
//! ![medium mesh: load steps and Newton tolerance][newton_tol]
//!
//! | run | build | wall time | Newton iterations | residual evaluations | σ_s | σ_a | deflection | crest settlement |
//! |---|---|---|---|---|---|---|---|---|
//! | 8 load steps, Newton 1e-5 | ad29fd6 | 290.5 s | 912 | 1,945 | 9.5e-4 | 3.4e-3 | 5.6e-4 | 3.4e-3 |
//! | 8 load steps, Newton 1e-5 | cfad9f2 | 261.0 s | 897 | 1,733 | 9.2e-4 | 2.8e-3 | 5.7e-4 | 3.5e-3 |
//! | 16 load steps, Newton 1e-5 | ad29fd6 | 276.6 s | 1,107 | 2,337 | 3.3e-4 | 1.7e-3 | 5.7e-5 | 2.0e-4 |
//! | 8 load steps, Newton 1e-4 | ad29fd6 | 179.9 s | 511 | 1,199 | 6.9e-4 | 3.1e-3 | 5.7e-4 | 2.8e-3 |
//! | **8 load steps, Newton 1e-4 (the scenes' settings)** | cfad9f2 | **160.2 s** | 514 | 1,041 | 7.6e-4 | 3.1e-3 | 5.4e-4 | 2.5e-3 |
//! | 16 load steps, Newton 1e-4 | ad29fd6 | 207.4 s | 708 | 1,633 | 2.1e-4 | 1.8e-3 | 3.9e-4 | 3.0e-3 |
//! | 16 load steps, Newton 1e-4 | cfad9f2 | 200.9 s | 709 | 1,473 | 3.5e-4 | 1.6e-3 | 6.2e-4 | 4.3e-3 |
//!
//! * **Newton 1e-4 costs no accuracy here**: with 8 load steps the errors are the load path's,
//!   as close to the reference as at 1e-5, with 0.56 of the Newton iterations and, on one build,
//!   0.61 of the time (160.2 s against 261.0 s). The scene is within 0.0067 MPa (σ_s), 0.020
//!   MPa (σ_a) and 0.0075 cm of the reference; 1e-4 and 1e-5 differ by up to 0.0045 MPa,
//!   0.029 MPa and 0.0042 cm.
//! * **More load steps are the accurate choice**, not the fast one: 16 steps cut the
//!   deflection's and the crest's errors by 10 and 17 times at Newton 1e-5 for 1.06 times the
//!   time; the scenes keep 8 to stay the study's yardstick.
//!
//! ## The seed quake (coarse mesh)
//!
//! `mpirun -n 2 cfrd run inputs/scenes/seed_coarse_gp_interface_quake.yaml -o OUT` (and
//! `seed_coarse_mohr_coulomb_quake.yaml`): construction and impoundment, then the 20 s record
//! `inputs/accel/seed_quake.csv` at Δt = 0.01 s (consistent mass, Rayleigh 2 % at 1 and 5 Hz;
//! the scenes now integrate with HHT-α, α = −0.1, on the distributed solver, see
//! [`crate::verification`], "The seed quake (coarse mesh)"). In the quake GMRES (to 1e-6) is
//! preconditioned by ILU(0) of each Jacobian ([`crate::linalg::petsc::lagged_lu`]), Newton
//! starts from the converged displacement and takes the full step first. The tables below were
//! measured with Newmark and the canonical solver, restarting the GP quake from its
//! post-impoundment checkpoint (`/usr/bin/time -v mpirun -n 2 cfrd run
//! inputs/scenes/seed_coarse_gp_interface_quake.yaml -o OUT --restart CKPT`), one run after the
//! other.
//!
//! **Line search** (`earthquake.line_search`, [`crate::scene::schema::LineSearch`]): build of
//! 65f5648 with `-snes_linesearch_type l2 | bt | basic`, and d9662ef with its default; errors by
//! `cfrd accuracy --quake` against the secant run (residual slab stresses and deflection of
//! seed Fig. 13, relative to the largest magnitude; residual crest settlement):
//!
//! | line search | quake | element loops rank 0 / 1 | linear solves | Newton iterations | cut-backs | σ_s | σ_a | deflection | crest settlement |
//! |---|---|---|---|---|---|---|---|---|---|
//! | secant (`l2`) | 344.8 s | 229.7 s / 178.5 s | 106.9 s | 5,663 | 15 | | | | |
//! | backtracking (`bt`) | 233.3 s | 127.2 s / 99.5 s | 99.8 s | 5,998 | 14 | 6.8e-3 | 1.1e-2 | 7.0e-4 | 2.1e-3 |
//! | full step (`basic`) | 245.5 s | 130.7 s / 105.3 s | 107.7 s | 5,811 | 68 | 1.2e-2 | 1.3e-2 | 2.3e-4 | 2.9e-4 |
//! | **full step first** (the default) | **223.2 s** | 119.1 s / 97.2 s | 96.9 s | 5,860 | 9 | 4.0e-3 | 9.7e-3 | 9.3e-4 | 2.0e-3 |
//!
//! `full_step_first` takes the full correction whenever it lowers ‖F‖² (one residual
//! evaluation; the secant search integrates every material point 3.5 times an iteration), else
//! the minimum of the parabola through the zero, half and full step. Its decisions rest on exact
//! norms, so runs stay the same bit for bit on 1 and 2 ranks, which PETSc's `bt` (its slope from
//! a `VecDot`) would not guarantee. The residual state moves by 0.4–1 % of the slab stresses, a
//! third to a tenth of what halving Δt moves it.
//!
//! **Incomplete factors in the quake stage.** The same restart, build of 3db3ef1, the second
//! run with `-canonical_dynamic_pc_type lu -canonical_dynamic_ksp_max_it 30
//! -canonical_dynamic_ksp_gmres_restart 30` (lagged complete factors, refactored after 30
//! GMRES iterations):
//!
//! | dynamic-stage solver | quake stage | linear solves / assembly | KSP iterations | factorizations | Newton iterations | cut-backs | memory per rank |
//! |---|---|---|---|---|---|---|---|
//! | ILU(0) (the default) | 334.5 s | 105.6 s / 224.7 s | 83,546 | 5,293 | 5,617 | 11 | 122 / 104 MiB |
//! | lagged LU | 679.3 s | 430.7 s / 244.1 s | 101,632 | 154 | 5,638 | 14 | 132 / 114 MiB |
//!
//! 2.03 times faster in the quake stage, 4.1 times in the linear solves (these two ran on a
//! machine where OpenBLAS used its generic kernels; see `ci/env.sh`). The residual slab tables differ
//! by at most 0.025 MPa (σ_s), 0.020 MPa (σ_a) and 0.02 cm.
//!
//! **Predictor** (`earthquake.predictor`, [`crate::solver::integrator::Newmark`]). The same
//! restart with `OPENBLAS_CORETYPE=SkylakeX`, build of 476de7c (from u₀, the default `none`):
//! 311.9 s, 5,663 Newton iterations, 15 cut-backs, 37 ms of assembly per iteration; a build
//! with u₀ + Δt·v₀ (`extrapolate`) as its default 345.6 s, 4,988, 11, 48 ms; one with
//! u₀ + Δt·v₀ + Δt²/2·a₀ 446.3 s, 6,425, 15, 48 ms. An iteration that starts at u₀ first
//! evaluates the materials at a zero increment, which is cheap, while one that starts at a
//! guess pays for plastic updates at once; average acceleration keeps the unresolved modes'
//! noise in a₀. The residual crest displacements differ by at most 0.44 mm.
//!
//! ### Time step, mass and integrator against cost
//!
//! `QUAKE=1 bash scripts/accuracy_cost.sh RUNS` (build of 6d2478f: lagged complete factors and
//! the secant line search in the quake): the coarse ideal elasto-plastic quake scene with one
//! setting changed, against a reference at Δt = 0.005 s. Errors (`cfrd accuracy --quake`): the
//! residual slab stresses and deflection at the central section (seed Fig. 13), relative to the
//! reference's largest magnitude (13.2 MPa residual axial compression), and the residual crest
//! settlement (0.177 m in the reference). Table `scripts/figures/quake/accuracy_cost.csv`.
//!
//! ![quake accuracy against cost][quake]
//!
//! | run | wall time (quake stage) | s per step | Newton per step (mean / largest) | residual σ_s | σ_a | deflection | crest settlement |
//! |---|---|---|---|---|---|---|---|
//! | Δt = 0.005 s (reference) | 417.4 s (392.2 s) | 0.098 | 2.05 / 4 | | | | |
//! | Δt = 0.01 s (the scene) | 324.8 s (300.7 s) | 0.150 | 2.40 / 6 | 3.1e-2 | 1.6e-2 | 7.5e-3 | 1.1e-2 |
//! | Δt = 0.02 s | 259.0 s (234.2 s) | 0.234 | 3.05 / 11 | 8.4e-2 | 3.3e-2 | 2.6e-2 | 5.9e-4 |
//! | Δt = 0.01 s, lumped mass | 282.6 s (257.9 s) | 0.129 | 2.20 / 4 | 1.9e-1 | 9.3e-2 | 8.4e-2 | 5.7e-2 |
//! | Δt = 0.01 s, HHT-α (α = −0.1) | 325.5 s (301.4 s) | 0.151 | 2.41 / 6 | 3.0e-2 | 1.8e-2 | 1.1e-2 | 1.6e-2 |
//!
//! * **Halving Δt costs 1.3 times the time, not 2**: the smaller step needs fewer Newton
//!   iterations and each is cheaper. Δt = 0.01 s, the record's own interval, is within 3 % of
//!   Δt = 0.005 s in the residual slab stresses and 1 % in the crest settlement; Δt = 0.02 s is
//!   8 % off in σ_s (its crest settlement agrees by chance).
//! * **Lumped mass is the worst trade**: 13 % faster but 6–19 % off. Keep the consistent mass.
//! * **HHT-α** (Hilber, Hughes & Taylor 1977; α = −0.1) costs the same as Newmark and changes
//!   the residual state by about as much as halving Δt: its damping acts on the modes the step
//!   does not resolve. The Δt = 0.01 s run held 132 MiB per rank.
//!
//! ## The seed quake (medium mesh)
//!
//! The medium quake scenes (9,414 elements, 35,151 DOFs; the 20 s record at Δt = 0.01 s), the
//! quake in one part from the post-impoundment checkpoint on the distributed solver (additive
//! Schwarz with ILU(0) subdomains in the quake) with the full-step-first line search: `/usr/bin/time
//! -v mpirun -n 2 cfrd run inputs/scenes/seed_medium_<model>_quake.yaml -o OUT --restart CKPT
//! --checkpoint-every 100 --linear-solver distributed_lu`:
//!
//! | interface | build | quake stage | s per step | Newton iterations | cut-backs | assembly / linear solves | element loops rank 0 / 1 | peak memory per rank |
//! |---|---|---|---|---|---|---|---|---|
//! | ideal elasto-plastic | d9662ef | **3,121 s (52.0 min)** net of stops (3,318 s wall) | 1.56 | 5,587 (2.79 per step), 7,615 residual evaluations | 0 | 1,758 / 1,510 s | 1,704 / 1,511 s | 498 / 271 MiB |
//! | GP interface | 56a695f | **3,164 s (52.7 min)**, never stopped | 1.58 | 3.14 per step | 4 | 1,846 / 1,274 s | 1,673 / 1,753 s | 487 / 286 MiB |
//!
//! Both meet the project's target of one hour. The cost per step follows the Newton
//! iterations, which follow the shaking (progress lines, per second of quake): the GP run takes
//! 0.73 s per step (1.59 Newton iterations) in the first second, 2.03–2.30 s (4.12–4.38) at
//! 9–13 s where the shaking is strongest, and 1.01 s (2.01) in the last; the ideal
//! elasto-plastic run 0.96 s (1.59), at most 2.04 s (3.26) at 9–10 s, and 1.08 s (2.00). Rank 0
//! owns the nodes shared by the two parts and so also evaluates the elements of rank 1 around
//! them.
//!
//! **The committed scene** (build of 18ba5c8: the static study's reduced multigrid for the
//! construction and impoundment, HHT-α −0.1 and the dynamic stages' distributed solver in the
//! quake): `/usr/bin/time -v mpirun -n 2 cfrd run
//! inputs/scenes/seed_medium_gp_interface_quake.yaml -o OUT --checkpoint-every 100`, alone on
//! the machine but for a compiler at `nice 19` that got 2 % of a core: **37.0 min** in all, the
//! static stages 167 s, the quake stage 2,047.6 s (1.02 s per step, 3.11 Newton iterations per
//! step, no cut-back), 519 / 306 MiB per rank; the ranks' Schwarz subdomains hold 20,271 and
//! 20,706 of the 35,151 rows (`solver_rows_held_per_rank`). Its residual slab table lies within
//! 0.07 MPa and 0.1 cm of the table in [`crate::verification`] ("The seed quake (medium
//! mesh)"). The two runs are many builds apart and not side by side, so no speed ratio is
//! claimed from them. The same command without step checkpoints on the build of this
//! section's commit (the stiffness boxed, no tangent per point in the slab, the loads kept;
//! nothing else in a GP scene changes): 37 min 27 s in all, the quake stage 2,067.1 s (6,239
//! Newton iterations, 2 cut-backs), 515 MiB peak per rank: no quicker. With a time step's
//! corrections solved to a tenth of the Newton tolerance on the Jacobian in node blocks (the
//! window below), the same command: **24 min 7 s** in all, the quake stage **1,270.1 s** (0.63 s
//! per step; 6,160 Newton iterations, 58,392 GMRES iterations against 147,531, 3 cut-backs),
//! assembly 968 s and linear solves 460 s of the whole run against 1,050 and 1,190 s, 511 MiB
//! peak per rank. One run after the other, not side by side: the ratio of the two quake
//! stages, 1.63, is the window's below. The residual slab table lies within 0.46 % (σ_s),
//! 0.25 % (σ_a), 0.024 % (deflection) and 0.009 % (crest settlement) of the largest values of
//! the run before (`cfrd accuracy --quake --reference OLD -o ACC new=NEW`).
//!
//! **Where a step of the medium GP quake goes** (`perf record` of one rank for 60 s in the
//! quake, that run): the linear solves half (GMRES's products with the Jacobian 18.5 %, the
//! ILU(0) substitutions 12 %, the preconditioner's set-ups 15.5 %, of which extracting the
//! overlapping subdomain matrices 7.9 % and factoring them 7.6 %), the GP rockfill's updates a
//! quarter (4.4 residual evaluations per step), the element stiffness 5 % and the slab's
//! incompatible modes 2.8 %. 23.7 GMRES iterations per solve.
//!
//! **A time step's linear solves, this build against the last** (`bash
//! scripts/bench_quake_window.sh BASE_CFRD THIS_CFRD
//! inputs/scenes/seed_medium_gp_interface_quake.yaml CK 50 3`: the committed scene restarted
//! from its step checkpoint at t = 8.04 s, 50 steps, 2 ranks, the builds alternated; base
//! 39bf82a, this build the same but for two changes in the quake: GMRES stops at a tenth of the
//! Newton tolerance (a step's later corrections need 1e-3–1e-1 of their residual, not 1e-6),
//! and the distributed solver's Schwarz subdomains, ILU(0) factors and products work on a
//! copy of the Jacobian in 3×3 node blocks):
//!
//! | pair | base, s | this build, s | Newton iterations (each) | base / this |
//! |---|---|---|---|---|
//! | 1 | 53.30 | 31.76 | 177 | 1.68 |
//! | 2 | 54.83 | 33.70 | 177 | 1.63 |
//! | 3 | 53.76 | 34.15 | 177 | 1.57 |
//!
//! **1.63 times (1.57–1.68)** fewer seconds per step, 0.66 s per step against 1.08 s, with the
//! same Newton iterations. The small GP dam's 30-step quake now agrees between 1, 2 and 4
//! ranks to 5.4e-6 and 3.6e-6 of the largest displacement, against 6.9e-8 and 1.1e-7 with
//! every correction solved to 1e-6: still below the Newton tolerance
//! (`dynamics::a_quake_on_the_distributed_solver_agrees_on_1_2_and_4_ranks`). A `perf record`
//! of one rank on this window with both changes (a relative tolerance of 1e-3 then) puts the GP
//! rockfill's updates at about 40 % of a step, the element stiffness with its assembly into
//! K and the slab's incompatible modes at about 12 %; the linear solves no longer lead.
//!
//! **The GP update's powers, this build against the last** (the same script, `CK` the
//! committed scene's step checkpoint at t = 8.07 s, 50 steps, 2 pairs; base 87f15fe): in a
//! `perf record` of one rank on that window (base) the GP updates took 53 % of the time and
//! `pow` alone 13.9 %, called by the invariants' J2^{3/2}, the elastic moduli and the plastic
//! moduli's (p̂/pa)^m. This build writes J2^{3/2} as J2·√J2 and folds (p̂/pa)^m into the
//! exponential that H_DM and H_den already take, with ln p̂ shared with ln ζ:
//!
//! | pair | base, s | this build, s | Newton iterations (each) | base / this |
//! |---|---|---|---|---|
//! | 1 | 38.58 | 36.26 | 180 | 1.064 |
//! | 2 | 38.39 | 36.37 | 180 | 1.055 |
//!
//! **1.06 times (1.055–1.064)**. The last bits of every GP update move; the coarse seed
//! scenes' static results move by at most 5.5e-4 of the largest slab stress (within the
//! Newton tolerance; `tests/goldens.rs`, regenerated), their Newton iterations 542 → 531.
//!
//! **The quake's solver choices, side by side** (windows of the medium GP quake from a step
//! checkpoint, 2 ranks, one run after the other):
//!
//! | window | build | compared | result |
//! |---|---|---|---|
//! | t = 0 → 0.88 s | 4924734 | ILU(0), GMRES to 1e-6, against lagged MUMPS factors refactored after 30 GMRES iterations (`-canonical_dynamic_pc_type lu -canonical_dynamic_pc_factor_mat_solver_type mumps -canonical_dynamic_ksp_max_it 30 -canonical_dynamic_ksp_gmres_restart 30`) | 97 s against 197 s, 132 Newton iterations each; t = 0.5 s after 40 s against 70 s |
//! | 40 steps from t = 4.02 s | 8e8aa44 | the canonical solver (Jacobian gathered, ILU(0) and GMRES on both ranks) against `--linear-solver distributed_lu` (Schwarz, overlap 2, ILU(0) subdomains) | 149 s against 119 s (1.25), 145 Newton iterations each; 445 / 268 MiB per rank against about 650 MiB each with lagged factors |
//! | 60 steps, t = 4.03 → 4.62 s | d9662ef | `full_step_first` against `l2`, distributed solver | 99 s against 166 s (1.68), 206 and 203 Newton iterations |
//! | 60 steps from t = 4.02 s | 7e6f952, 56a695f | partition balanced by owned against by evaluated elements, alternated | 121, 127 s against 122, 122 s |
//!
//! With ILU(0) a time step's solve takes 17.7 GMRES iterations (at most 24) over the quake's
//! first 396 solves, each a product and two sparse triangular solves.
//!
//! ## A linear scene's quake against OpenSees
//!
//! `bash scripts/bench_linear_quake.sh OUT 3` (needs `pip install openseespy h5py`):
//! `inputs/scenes/elastic_embankment_quake.yaml` (a 40 m elastic embankment of 2,000
//! hexahedra, 7,623 DOFs, base and banks fixed, 1,000 Newmark steps of the seed record,
//! consistent mass, Rayleigh 5 % at 1 and 5 Hz) on one rank, then the same mesh, record and
//! damping in OpenSees 3.7.1 (openseespy: `stdBrick`, `ElasticIsotropic`, `rayleigh` on the
//! initial stiffness, `UniformExcitation`, `Newmark 0.5 0.25`, `Linear -factorOnce`, `Mumps`),
//! alternating, three pairs (the build of this section's commit):
//!
//! | pair | cfrd, ms per step (quake stage) | OpenSees, ms per step (analyze loop) | OpenSees / cfrd |
//! |---|---|---|---|
//! | 1 | 8.70 | 105.45 | 12.12 |
//! | 2 | 9.64 | 119.73 | 12.42 |
//! | 3 | 9.06 | 108.06 | 11.93 |
//!
//! **cfrd takes 12.1 (11.9–12.4) times fewer seconds per step than OpenSees** here.
//!
//! The two crest histories agree to 6.6e-12 of the largest displacement: the same element, mass,
//! damping and scheme. What a step of a linear scene's dynamic stage does:
//!
//! - **One factorization.** The Jacobian K + shift_v·C + shift_a·M of a scene whose blocks are
//!   all linear elastic is built and completely factored once (again only if a cut-back
//!   changes Δt): two factorizations and one Newton iteration per step in the run
//!   (`dynamics::a_linear_scenes_quake_builds_and_factors_its_jacobian_once`). The factors
//!   are applied alone, with no Krylov iteration around them; on one rank they are PETSc's
//!   own LU of the matrix in 3×3 node blocks (MUMPS on several ranks).
//! - **One element loop.** A step starts at the committed displacement, where the internal
//!   forces are those of the evaluation the last step converged at; a linear scene takes them
//!   from there, so each step integrates its elements once, at its converged point, for its
//!   two residuals (the same test; `element_loops` in `summary.json`).
//! - **The loads once per stage.** The external and placement forces of a stage at one load
//!   factor are assembled once and kept (every step of a dynamic stage has factor 1).
//!
//! What a step costs now (one rank, `-log_view` and `perf record` of one run): the
//! substitution 2.8–2.9 ms (4.6–5.7 ms with PETSc's LU of the scalar matrix, 7.1 ms with
//! MUMPS's, each measured with `-log_view` on this scene), the products with M and K₀ of the two residuals (summed in the
//! mesh's DOF order, `CanonicalProduct`) about 2 ms, the element loop about 1.7–2 ms.
//!
//! ## Tried and rejected
//!
//! Measured and not adopted (the runs are in the git history); "medium" is the medium
//! hyperbolic scene on 2 ranks unless named.
//!
//! | what | measured | why not |
//! |---|---|---|
//! | Cholesky for a linear scene's kept factors (the linear embankment, one rank, `-log_view`) | substitution 9.3 ms (MUMPS) and 5.2 ms (PETSc) against 4.6–5.7 ms with PETSc's LU | no quicker than LU, and slower than LU of the 3×3-block matrix (2.8 ms) |
//! | four rows of `CanonicalProduct` summed side by side (each row's order kept) | 0.37 against 0.41 ms per product in a stand-alone loop; the linear embankment's quake stage not quicker | not worth the code |
//! | static load steps that double after two converged steps, up to 4 × (build ad29fd6) | medium 358.7 s against 290.5 s, 8 cut-backs | longer increments cost GP substeps and line-search evaluations |
//! | step growth also after a two-iteration step (G = 2) | fine fill_001–fill_020: 159.8 s against 140.9 s | longer increments cost GP substeps |
//! | quadratic extrapolation of a step's start | medium stages 1–24: 686 Newton iterations against 659 | the start residual is not the path's curvature |
//! | a layer's first step from the last layer's rate (against build 814a095) | medium 363.5 s against 151.0 s (2.41), 721 against 513 Newton iterations | the last layer's settlement peaks one layer below where the next acts |
//! | a stage's first step from the previous stage's increment | medium to stage 20: 119.7 s against 55.3 s | further from the answer than the converged state |
//! | numerical tangent at points below 15 kPa (young fill) | medium to stage 20: 402.9 s, 18 cut-backs, against 59.4 s, 0 | far more iterations outside a layer's first step |
//! | `full_step_first` in the static stages (coarse GP, build 692b961, three alternated pairs) | medians 55.9 s (`secant`) against 50.0 s; 9–10 cut-backs instead of 5 (build 7e6f952) | cut-backs double, hard cases not run |
//! | the full Newton step in the static stages (`basic`) | coarse 15.7 s against 23 s, 12 cut-backs against 6 | fine slab stage II left 4e8 N out of balance |
//! | STOL 1e-3 (build of f99ca09) | medium 421.1 s against 484.8 s (0.87) | twice as far from the reference on the coarse mesh |
//! | GAMG on the whole matrix or on the coupled rows | PC failed in the first fill stages; with the translations as near-null space about 490 GMRES per solve | the stiff interfaces and joints |
//! | BoomerAMG (`-pc_type hypre`) on the whole matrix / on the fill | fine first 8 fill stages 13.0 min against 1.6 min (canonical LU); medium `impound_1` solves 30.7 s against 9.7 s | too slow |
//! | MUMPS for the reduced multigrid's structure | 447.4 s against 396.9 / 423.5 s | not reproducible run to run |
//! | the structure by block Jacobi and ILU(0) / ILU(2) | medium stages 25–37: 211.5 / 218.3 s against 127.1 s | 2.5–3 times the GMRES iterations |
//! | the structure by a sequential LU on each rank (`redundant`) | medium stages 25–37: 141.6 s against 135.7 s (both `-log_view`); PETSc's LU 18.7 s of solves in `impound_1` against 9.7 s | slower than the distributed factorization |
//! | fill levels smoothed by Chebyshev and Jacobi; one sweep per level | medium stages 25–37: 142.9 s against 127.1 s; fine fill_051–fill_054: 312 GMRES against 272 | more GMRES iterations |
//! | block Jacobi with a complete or incomplete LU per rank; GAMG without squaring the graph | 865 / 1,017 and 406 GMRES iterations against 417 | no faster |
//! | rotations in the near-null space (`-reduced_near_null_modes 6`) | fine `fill_051`: 164 GMRES against 134; with SOR smoothing PC failed | zero pivots on the second level |
//! | the structure's factors lagged (`-reduced_structure_refresh_after 10`) | fine fill_051–fill_054 66.4 s against 72.2–79.1 s; `impound_1` 36.9 s, 75 GMRES, against 31.7–32.7 s, 36 | costs a Newton iteration and twice the GMRES in the impoundment |
//! | forcing terms 0.05 | fine fill_051–fill_054 76.3 s; `impound_1` 36.6 s, 9 Newton against 8 | costs a Newton iteration in the impoundment |
//! | MUMPS block low-rank factors | medium: solves ±3 %, 11 % less memory after slab stage I | fronts too small to pay |
//! | additive Schwarz with complete subdomain factors (static) | medium GP stages 1–17: 458.2 s against 239.9 s (canonical LU) | 1.91 times slower, more memory |
//! | canonical LU refactored after 30 or 4 GMRES iterations instead of 8 | fine first 11 fill stages 201 s and 186 s against 170 s | slower |
//! | `integration_tol_ratio` on by default | GP dam tests exhaust the substep limit; on stalls only 504 s against 117 s | costly where not needed |
//! | quake: lagged complete factors with the static settings (refactor after 8, rtol 1e-9) | coarse GP quake 384.7 s against 318.4 s at 30 and 1e-6 (builds b16fc90, b351936) | factors renewed every other step |
//! | quake: METIS ordering, block low-rank factors or PETSc's LU for the lagged factors | 0.69, 0.68 and 0.60 s of quake in 85 s against 0.68 s | no gain |
//! | quake: the velocity or acceleration predictor | coarse GP quake 345.6 / 446.3 s against 311.9 s | cost more per iteration than they save |
//! | quake: lumped mass | 13 % faster, 6–19 % off | worst accuracy per cost |
//! | quake: ILU(1) Schwarz subdomains throughout (`-distributed_dynamic_sub_pc_factor_levels 1`) | coarse GP quake stage 162.5 s against 123.8 s with ILU(0), 15 % fewer GMRES iterations (build of 18ba5c8, one run after the other) | fill is added only to a stage whose ILU(0) solve fails |
//! | quake: every correction to a fixed 1e-2 (node blocks) or 1e-3 (scalar matrix) of its residual (medium GP window above, one run each) | 37.7 and 43.9 s against 54.1 s, the same Newton iterations | the small GP dam's 1, 2 and 4 ranks then differ by 1.6e-5 and 4.2e-5, more than the Newton tolerance |
//! | quake: the incomplete factors kept across Jacobians while GMRES needs at most 30 iterations (prototype option, window above) | 54.3 s against 54.1 s | renewed nearly as often; no gain |
//! | quake: the block by `MatConvert` at every Jacobian | 45.7 s against 43.9 s without blocks | the conversion inserts one scalar at a time: a sixth of the step |
//! | quake: the Jacobian of every other Newton iteration kept (`-snes_lag_jacobian 2`, GP window at t = 8.07 s, base 87f15fe) | 95.8 s against 38.2 s, 346 Newton iterations against 180 | the tangent is what converges a step |
//! | quake: the predictor x⁰ = u₀ + Δt·v₀ + c·Δt²·a₀ with c = 0.25 (a₁ = 0) or 0.5 (a₁ = a₀) (same window, prototype) | 38.7 and 38.4 s against 38.2 s, 180 Newton iterations each | the iterations are set by the end of a step, not its start |
//! | GP elastic moduli as exp(m·ln(p̂/pa)) instead of a power (same window, against the powers above) | 0.978 and 1.012 | no gain |
//! | quake: the reduced split (structure LU, fill by block Jacobi ILU(0)) as the dynamic solver (`--linear-solver reduced_amg -reduced_fieldsplit_fill_pc_type bjacobi`, window above) | 73.6 s against 54.1 s, 201 Newton iterations against 177 | the structure factored at every Jacobian |
#![cfg_attr(doc, doc = embed_doc_image::embed_image!("accuracy", "scripts/figures/accuracy_cost.png"))]
#![cfg_attr(doc, doc = embed_doc_image::embed_image!("mesh", "scripts/figures/mesh/accuracy_cost.png"))]
#![cfg_attr(doc, doc = embed_doc_image::embed_image!("newton_tol", "scripts/figures/newton_tol/accuracy_cost.png"))]
#![cfg_attr(doc, doc = embed_doc_image::embed_image!("quake", "scripts/figures/quake/accuracy_cost.png"))]
