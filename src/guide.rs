//! # User guide: scenes, the command line, restarts, outputs
//!
//! How to describe a dam in a scene file, run it on one machine or a cluster, continue a long
//! run from its checkpoints, and read what a run writes. The model checks and the comparison
//! with the seed paper are in [`crate::verification`]; run times, memory and solver
//! measurements in [`crate::performance`].
//!
//! Contents: [the main job](#the-main-job) · [scene files](#scene-files) ·
//! [materials](#materials) · [interfaces and joints](#interfaces-and-joints) ·
//! [the CFRD generator and the seed scenes](#the-cfrd-generator-and-the-seed-scenes) ·
//! [nonlinear runs](#nonlinear-runs) · [linear solvers and PETSc options](#linear-solvers-and-petsc-options) ·
//! [parallel runs](#parallel-runs-and-rank-count-independence) ·
//! [command line](#command-line) · [restart and checkpoints](#restart-and-checkpoints) ·
//! [runs in parts](#runs-in-parts) · [outputs](#outputs) · [exit codes](#exit-codes) ·
//! [fuzzing the input readers](#fuzzing-the-input-readers)
//!
//! ## The main job
//!
//! ```sh
//! bash ci/run-default.sh            # install, build, run the coarse seed dam on 2 ranks
//! bash ci/run-default.sh out/mine   # the same into another directory
//! SCENE=inputs/scenes/seed_coarse_hyperbolic.yaml RANKS=1 bash ci/run-default.sh
//! ```
//!
//! It installs the Debian packages that are missing (`ci/install-deps.sh`: PETSc, Open MPI,
//! parallel HDF5, METIS, an optimized serial BLAS), builds `cfrd` in release mode and runs
//! `inputs/scenes/seed_coarse_gp_interface.yaml` (listed in full [below](#a-seed-scene)) with
//! `mpirun -n 2` into `out/seed_coarse/`, then lists the files it wrote. Run again, it replaces
//! that directory (the new run goes into `out/seed_coarse.partial` and is moved into place when
//! it has finished; a directory it did not write is refused). `cfrd run` without a scene runs
//! the same study at a small size, the embedded default scene (`inputs/scenes/default_dam.yaml`:
//! the generated CFRD in 4 layers of GP rockfill, the slab in three stages on a GP interface,
//! joints, impoundment in 2 stages, Figs. 7–11; 9 s on 2 ranks at commit de30807, `mpirun -n 2 cfrd run -o out`).
//!
//! ## Scene files
//!
//! A scene is one YAML file: mesh, materials per block, boundary conditions, loads, stages,
//! solver and output settings. Units are SI throughout (N, m, kg, s, Pa); axes, signs and the
//! Voigt order are those of [`crate::conventions`] (x stream upstream → downstream, y dam axis,
//! z up; tension positive; `[xx, yy, zz, xy, yz, zx]`). Unknown keys are errors, and every error
//! names its YAML path. `cfrd schema` prints the JSON Schema of the format (for editors); the
//! types behind it, with every key documented, are [`crate::scene::schema::SceneFile`] and the
//! types it links to. Only the loads a scene names are built ([`crate::scene`]).
//!
//! A small scene:
//!
//! ```yaml
//! name: column
//! units: SI                        # only SI: N, m, kg, s, Pa
//! mesh:
//!   box: { size: [1.0, 1.0, 10.0], divisions: [1, 1, 8] }   # or { file: dam.msh }, { dam: {...} }, { cfrd: {...} }
//! materials:
//!   soil: { model: elastic, young: 5.0e7, poisson: 0.3, density: 2000.0 }
//! blocks:                          # every mesh block (Gmsh physical volume) gets a material
//!   layer_1: { material: soil }
//! boundary:
//!   - { set: zmin, fix: [x, y, z] }
//!   - { set: xmin, fix: [x] }
//! loads:                           # each load present is one physics term; nothing else is built
//!   gravity: { g: [0.0, 0.0, -9.81] }
//!   hydrostatic: [ { faces: upstream, level: 159.0 } ]
//! solver: { rtol: 1.0e-10, petsc_options: "-ksp_monitor" }
//! ```
//!
//! | key | what it holds |
//! |---|---|
//! | `name` | the scene's name, written into the results |
//! | `units` | `SI`, the only unit system accepted |
//! | `mesh` | one of `file` (Gmsh MSH 4.1 or 2.2; physical volumes are blocks, physical surfaces face sets, [`crate::mesh::gmsh`]), `box`, `dam` (a prismatic dam section) or `cfrd` (the [CFRD generator](#the-cfrd-generator-and-the-seed-scenes)) |
//! | `partition` | a partition file from `cfrd partition`; METIS runs at start-up otherwise |
//! | `materials` | materials by name, each with `model:` and its parameters ([materials](#materials)) |
//! | `blocks` | every mesh block with its `material`; interface blocks also take `orientation`, `rule` and `initial_normal_stress`; elastic blocks of hexahedra take `element: incompatible_modes` (the face slab with one element through its thickness, which the trilinear default locks in bending; [`crate::element::hex8_modes`]). A key with `*` is a pattern (`fill_*_cushion`) for the blocks without an exact key |
//! | `boundary` | `{ set, fix: [x, y, z], value }` on node sets (prescribed displacement, zero by default) |
//! | `loads` | `gravity: { g }`, `pressure: [ { faces, value } ]`, `hydrostatic: [ { faces, level, unit_weight } ]` (γ_w 9810 N/m³ by default) |
//! | `stages` | construction and loading stages in order: `{ name, activate: [blocks], loads, load_steps }`, plus `dynamic` ([dynamic stages](#dynamic-stages-and-earthquakes)) and `modal` ([modal analysis](#modal-analysis)); placed blocks start strain-free at zero stress. Without stages the scene is one stage (a `mesh.cfrd` scene runs the generator's schedule) |
//! | `solver` | [`SolverSpec`](crate::scene::schema::SolverSpec): `rtol` (1e-10), `max_iterations` (2000), `newton_tol` (1e-8), `newton_max_iterations` (25), `load_steps` (1), `step_growth` (1: equal steps), `max_cutbacks` (8), `petsc_options`, `monitor`, `linear_solver` (`iterative`, `reduced_amg`, `canonical_lu` or `distributed_lu`), `reuse_factorization` (true), `integration_tol_ratio` (0, off), `predictor` (`none`, or `extrapolate`: a static load step starts from the last step's rate du/dλ, [`crate::solver::integrator::QuasiStatic`]), `line_search` (`residual_secant`, `secant` or `full_step_first`, [`LineSearch`](crate::scene::schema::LineSearch)) |
//! | `output` | [`OutputSpec`](crate::scene::schema::OutputSpec): `dir` (`out`; `-o` overrides it), `placed_nodes` (`end_of_stage` or `start_of_stage`: where the displacement of a placed node counts from; in a dynamic stage `end_of_stage` counts from the stage's start, so the quake's motion of the blocks it places is reported, `dynamics::a_dynamic_stage_that_places_a_block_reports_its_motion_at_its_end`), `profiles` (the seed's Figs. 7–11, [`crate::post::profiles`], and after an earthquake Figs. 12–20, [`crate::post::quake_figures`]; `probes` name the elements followed), `checkpoint` (`stage`, `step` or `none`) |
//!
//! ### A seed scene
//!
//! The scene the main job runs, as generated by `scripts/make_seed_scenes.sh` (edit the script,
//! not the nine generated files, then rerun it):
//!
#![doc = concat!("```yaml\n", include_str!("../inputs/scenes/seed_coarse_gp_interface.yaml"), "```")]
//!
//! ## Materials
//!
//! Parameters left out take the seed's tables (Liu, Kong & Zou 2015, Tables 1–4); the spec's
//! inferred choices are named options with the recommended defaults, documented with each
//! model's parameters.
//!
//! | model | `model:` tag | spec | integration | tangent |
//! |---|---|---|---|---|
//! | rockfill generalized plasticity (seed Table 1), [`rockfill_gp`](crate::material::rockfill_gp) | `rockfill_gp` | models §1 | explicit modified Euler with error control, STOL 1e-4 (§8.2) | continuum D^ep; `tangent: numerical` (consistent, central differences) optional |
//! | 3D state-dependent GP interface (seed Table 2, e0 = 0.25), [`interface_gp`](crate::material::interface_gp) | `gp_interface` | models §2 | the same integrator, with reversal mapping, breakage, opening memory | continuum (numerical optional) |
//! | Clough–Duncan hyperbolic interface (Table 3), [`interface_hyperbolic`](crate::material::interface_hyperbolic) | `hyperbolic` | models §3 | substepped Heun, unload/reload with k_ur (§8.4) | continuum |
//! | ideal elasto-plastic Mohr–Coulomb interface (Table 4), [`interface_mc`](crate::material::interface_mc) | `mohr_coulomb` | models §4 | closed-form radial return (§8.3) | consistent (incl. ∂k_s/∂σ_n) |
//! | slab joint (25 GPa/m, 5 MPa/m, 1 MPa/m), [`joint`](crate::material::joint) | `joint` | models §6 | closed form | secant |
//! | linear elasticity (slab), [`elastic`](crate::material::elastic) | `elastic` | – | closed form | elastic |
//!
//! Named options of the inferred choices: `lode`, `hden_on_hu`, `softening_guard`, `xi_rule`
//! (rockfill); `peak_form`, `fh_mode`, `stiffness_basis`, `elastic_void_ratio`,
//! `normal_basis`, `void_ratio_bound` with `e_min`, `reversal_branch`, `stress_ratio_cap` (GP interface; their defaults
//! and the measurements behind them: [`interface_gp`](crate::material::interface_gp)). With the rockfill GP model in a staged dam, give
//! `tangent: numerical`: the continuum tangent of a large strain step is far from the
//! consistent one, and Newton then creeps ([`crate::performance`]). `cfrd point` drives one
//! material point along a laboratory path ([command line](#command-line)).
//!
//! ## Interfaces and joints
//!
//! A block of zero-thickness elements (models §5: in a Gmsh file, hexahedra whose nodes 5–8 sit
//! on nodes 1–4, nodes 1–4 on the slab side; the CFRD generator makes them itself) takes an
//! interface law as its material (`hyperbolic`, `mohr_coulomb`, `gp_interface`, `joint`) and an
//! orientation from the slab into the dam, e.g.
//! `contact: { material: mc, orientation: [1.0, 0.0, -1.4] }`. `rule` picks the nodal
//! Newton–Cotes points (`newton_cotes`, default, spec models §5.4) or `gauss2x2`
//! ([`crate::element::interface8`]). Results then hold
//! `interface_traction`, `interface_jump`, `interface_slip` and `interface_opening`, and the
//! run summary counts the open and slipping points.
//!
//! ## The CFRD generator and the seed scenes
//!
//! `mesh: { cfrd: {...} }` ([`CfrdSpec`](crate::mesh::dam_spec::CfrdSpec); geometry from spec seismic
//! §5) builds the seed dam: a trapezoidal canyon, the cushion, transition and rockfill zones in
//! fill layers, the face slab in three stages (stage I cast at fill el. 2780 m, II and III after
//! the fill) on a slab–cushion interface, vertical and perimetric joints (models §6) against a
//! rigid plinth, and the stage schedule: fill layers `fill_KKK`, slab stages `slab_S`,
//! impoundment stages `impound_N` to el. 2840 m. Omitted keys take the seed dam's values.
//!
//! `inputs/scenes/seed_{coarse,medium,fine}_{hyperbolic,mohr_coulomb,gp_interface}.yaml` are
//! the seed dam at three resolutions with each of the three interface models:
//!
//! | resolution | `mesh.cfrd` | solver |
//! |---|---|---|
//! | coarse | 8 fill layers, 30 m panels, 3 impoundment stages | canonical LU (PETSc's LU) |
//! | medium | 30 fill layers, 15 m panels, 4 impoundment stages | reduced multigrid (`reduced_amg`), load steps started from the last step's rate (`predictor: extrapolate`); its quake scenes canonical LU with MUMPS and the plain start |
//! | fine | 86 fill layers (as the seed), 2 elements per panel, 6 impoundment stages | reduced multigrid (`reduced_amg`), `predictor: extrapolate`; 29–36 min on 2 ranks depending on the interface (ideal elasto-plastic 28.9, hyperbolic 29.6, GP 35.5 min) ([`crate::performance`], "The fine run"), run it [in parts](#runs-in-parts) where a job or a session is shorter |
//!
//! All of them use 8 load steps per stage and at most 15 Newton iterations per step; the
//! coarse scenes and the quake scenes stop Newton at `newton_tol: 1.0e-5` (above the noise of
//! the GP substepping, see [nonlinear runs](#nonlinear-runs)), the medium and fine ones at
//! `1.0e-4`, which on the medium mesh leaves the results as close to a 32-load-step reference
//! as 1e-5 does in 0.61 of the time ([`crate::performance`], "The medium mesh's Newton
//! tolerance"). `seed_xfine_hyperbolic.yaml` (110 fill layers, 1,018,689 DOFs, Newton to 1e-4)
//! is the weak-scaling study's dam. All write the seed's Figs. 7–11 (`output.profiles`, probe
//! I-A at el. 2711 m). Their sizes and run times are in [`crate::performance`].
//!
//! ## Nonlinear runs
//!
//! Newton's method runs on PETSc SNES with cfrd's residual and Jacobian and the `l2` line
//! search; every material point is integrated from its last committed state over the total
//! step increment (spec models §8.1).
//!
//! * **Load steps.** `solver.load_steps` splits each stage's load into equal steps (a stage may
//!   set its own `load_steps`; generated fill layers take `mesh.cfrd.fill_load_steps`). A step
//!   whose Newton iteration or material update fails is halved, at most `solver.max_cutbacks`
//!   times in a row, and grown back after two successes; the run summary counts cut-backs and
//!   Newton iterations per step (`newton_per_step`). With GP rockfill, steps too large cost
//!   more than they save (measurements in [`crate::performance`]). `solver.step_growth: G`
//!   lets a static step that converged in one Newton iteration double the next one, up to G
//!   times the nominal step; a step of more than three iterations halves it back to the
//!   nominal one (the fine seed scenes take G = 2, [`crate::solver::step_control`]). With `solver.predictor:
//!   extrapolate` a step whose extrapolated start fails in a material update (a GP interface
//!   closed beyond its bound) first starts again from the last converged state
//!   (`predictions_dropped` in the summary), and is halved only if that fails too.
//! * **Watching a run.** `solver: { monitor: true }`, or `cfrd run --monitor` (which leaves the
//!   scene and its hash alone, so a restarted run can be watched), prints every Newton
//!   residual and the reason and place (the node of the largest out-of-balance force) of every
//!   cut-back.
//! * **The integration noise.** A Newton solve cannot go below the noise of the GP stress
//!   integration, about the substepping tolerance STOL (`integration.stol`, spec models §8.2,
//!   default 1e-4) relative to the reference force: when a point's number of substeps changes
//!   between two Newton iterates its stress jumps by up to that much. Give `newton_tol` above it
//!   (the seed scenes use 1e-5 or 1e-4). When a residual stays put a little above STOL while
//!   `newton_tol` is smaller, `solver: { integration_tol_ratio: 0.1 }` (or
//!   `cfrd run --integration-tol-ratio 0.1`, which leaves the hash alone, so a stalled run
//!   continues from its checkpoint) integrates every GP material at STOL ≤ 0.1·newton_tol. It
//!   costs substeps, so it is off by default and meant for small load steps on fine meshes; a
//!   step that fails within a decade of such a STOL says so in its report and names the remedy.
//!
//! ## Dynamic stages and earthquakes
//!
//! A stage with a `dynamic:` key is integrated in time under a ground-acceleration record on a
//! rigid base (spec seismic §3): Newmark's method (average acceleration, β = 1/4, γ = 1/2, by
//! default), Newton at every step with the same cut-backs, from the state the stages before
//! left (u₀ = the static displacement, v₀ = a₀ = 0); gravity and water stay applied. Mass
//! (consistent, or `mass: lumped`) and the stiffness K₀ of Rayleigh damping are built only for
//! such a stage. A generated dam takes its quake as a top-level `earthquake:` appended after the
//! schedule with the last stage's loads:
//!
//! ```yaml
//! earthquake:
//!   record: ../accel/seed_quake.csv   # t,a_x,a_y,a_z in m/s², our axes (cfrd accel writes it)
//!   duration: 20.0                    # s (default: the record's length)
//!   dt: 0.01                          # s (default: the record's sample interval), divides duration
//!   damping: { ratio: 0.05, frequencies: [1.0, 5.0] }   # C = a_M·M + a_K·K₀ (optional)
//!   output_every: 10                  # fields every 10 steps (default: the stage's end only)
//!   hht_alpha: -0.1                   # HHT-α instead of average acceleration (α ∈ [−1/3, 0])
//!   newton_tol: 1.0e-5                # the quake's Newton tolerance (default solver.newton_tol)
//!   # linear_solver: canonical_lu     # default distributed_lu (below)
//!   # predictor: extrapolate          # Newton from u₀ + Δt·v₀ (default none: from u₀)
//!   # line_search: secant             # default full_step_first
//! ```
//!
//! The record is a CSV file of the three components (above), or one PEER NGA AT2 file per
//! component, `record: { x: RSN6_X.AT2, y: RSN6_Y.AT2, z: RSN6_UP.AT2 }`, paths relative to the
//! scene's folder: each file's header gives its units (it must say `UNITS OF G`; the values
//! are converted with g = 9.80665 m/s²) and its `DT`. A component left out is zero, at least one
//! is given; the given ones must share their DT (to 1e-9 relative), or the scene is refused
//! naming the file and the key (`…record.y`); shorter components are padded with zeros to the
//! longest. The run's log states both at the stage's start.
//!
//! A dynamic stage runs what it asks, or it is refused (exit 2, naming the stage and the key),
//! or rank 0's log states the rule at the stage's start:
//!
//! * `dt` must divide `duration` (to 1e-9 relative): `dt: 0.21` over `duration: 0.3` is refused
//!   with the nearest `dt` that does, 0.15 s;
//! * a dynamic stage takes no `load_steps`: its steps are `duration`/`dt`;
//! * a `duration` past the record's end is a rule, not an error: from the record's last sample
//!   on the ground is at rest (zero ground acceleration), a quiet tail in which the dam vibrates
//!   freely, and the log says so ("record ends at 20 s; from 20 to 25 s the ground is at rest");
//! * `damping` gives its ratio with one of `frequencies: [f1, f2]` or `modes: [i, j]`;
//! * a dynamic stage starts at rest relative to the base, so one directly after another would
//!   cut the motion off: it is refused; join them in one stage (a `duration` past the record
//!   gives the quiet tail), or put a static stage between them (an aftershock after a
//!   settlement stage);
//! * a modal or dynamic stage before any block is placed is refused.
//!
//! The quake's outputs (`quake_crest.csv`, `quake_summary.json`, the probe histories and the
//! dynamic figures) cover every dynamic stage on one clock: the first starts at t = 0, each
//! later one where the dynamic stage before it ended; displacements count from the state
//! before the first one, and `quake_summary.json` names the stages (`stages`) and the crest's
//! node and coordinates (`dynamics::crest_history_runs_over_every_dynamic_stage_on_one_clock`).
//!
//! A dynamic stage has its own `linear_solver` and, if given, its own `newton_tol`; the static
//! stages' `solver.linear_solver` and `solver.newton_tol` do not reach it. The seed quake
//! scenes keep their static study's solver for the construction and impoundment and solve the
//! quake on the default. In a scene whose blocks are all linear elastic the Jacobian of a time
//! step does not change: the dynamic stage builds it and factors it completely once (again
//! only when a cut-back changes Δt), and each step costs one Newton iteration
//! (`dynamics::a_linear_scenes_quake_builds_and_factors_its_jacobian_once`).
//!
//! Each time step's Newton iterations start from the last converged displacement (`predictor:
//! none`, the default). `predictor: extrapolate` starts them from the committed velocity
//! carried over the step: on the coarse seed quake 12 % fewer Newton iterations and fewer
//! cut-backs, but 11 % more time: an iteration that does not start at u₀ costs more to
//! assemble ([`crate::performance`], "The seed quake (coarse mesh)").
//!
//! A time step takes the full Newton correction whenever it lowers the residual norm
//! (`line_search: full_step_first`, the default), one residual evaluation per iteration;
//! PETSc's secant line search (`secant`) evaluates three. On the coarse
//! seed quake that made the quake 1.54 times faster and a window of the medium quake 1.68
//! times (side by side); the whole medium GP quake took 52.7 min on 2 ranks alone on the
//! machine. Residual slab
//! stresses stay within 1 % of the secant run's ([`crate::performance`]). The static stages'
//! default, `solver.line_search: residual_secant`, takes the full step where it lowers the
//! residual and the secant of the residual vectors puts the minimum near it (one evaluation),
//! extends a correction that falls short along that secant (two), and takes the `secant`
//! step otherwise (three).
//!
//! `hht_alpha` integrates with HHT-α (β = (1 − α)²/4, γ = 1/2 − α): second-order accurate like
//! average acceleration, but modes the time step does not resolve are damped, down to a
//! spectral radius (1 + α)/(1 − α) at ω·Δt → ∞ (0.5 at α = −1/3), while a resolved mode loses
//! little (α = −0.3 at ω·Δt = 0.63: ζ = 0.38 %). Average acceleration keeps the response at
//! the step's Nyquist frequency (a period of 2Δt) undamped: where a contact closes or the
//! rockfill switches between loading and unloading, the crest acceleration then alternates in
//! sign from one step to the next, and its peak is a single-step spike. The seed quake scenes
//! therefore use `hht_alpha: -0.1` (`cfrd::verification`, "The seed quake (coarse mesh)", has
//! the measurement; Dynamics, the checks). `quake_summary.json` reports each component's raw
//! peak against its peak low-passed at 20 Hz (`spike_ratio`, near 1 for a resolved response).
//!
//! Rayleigh damping (spec seismic §3.3, a_M = 2ζω₁ω₂/(ω₁+ω₂), a_K = 2ζ/(ω₁+ω₂)) takes its two
//! anchors either as `frequencies: [f1, f2]` (Hz) or as `modes: [i, j]` (1-based): then a
//! modal analysis of the stage's start state runs first and the anchors are its i-th and j-th
//! frequencies (`damping: { ratio: 0.05, modes: [1, 3] }`).
//!
//! ### Modal analysis
//!
//! A stage with `modal: { modes: N }` (optionally `mass: lumped`) computes, when it starts
//! (after placing its blocks, before its first step), the N lowest natural frequencies and mode
//! shapes of K₀·φ = ω²·M·φ: K₀ the small-strain stiffness of that state (the solids' elastic
//! moduli there, e.g. the GP rockfill's G = G₀·p_a·(p'/p_a)^m_s at its current p'; interfaces at
//! their current tangent, symmetrized), M the consistent mass of the placed solids
//! ([`crate::scene::modal`], [`crate::solver::modal`]). A
//! stage with nothing else to do takes the modes of the state the stages before left, e.g.
//! after impoundment:
//!
//! ```yaml
//! stages:
//!   # ... construction and impoundment stages ...
//!   - { name: modes, modal: { modes: 6 } }
//! ```
//!
//! Only the free DOFs enter the eigenproblem: the rows and columns of the supports and of the
//! nodes no placed element touches yet are removed (no spurious mode, M positive definite on the
//! rest). SLEPc solves it by shift-and-invert about 0 with a MUMPS factorization of K₀
//! ([`crate::linalg::slepc`]); options with the prefix `modal_` (`-modal_eps_tol 1e-12`,
//! `-modal_eps_view`) reach it. `summary.json` gets
//! `"modal": {"stage", "frequencies_hz", "periods_s", "seconds"}`, and `modes.h5` /
//! `modes.xdmf` hold one step per mode (step time = mode number, label with its frequency) with
//! the node field `mode_shape`, scaled to a largest component of +1. At most one stage of a
//! scene runs a modal analysis (its own `modal` key or damping on modes); a bad count or pair of
//! modes exits with code 2 naming the key. Asking for as many modes as the stage has free DOFs
//! or more fails the stage (exit 3, naming the largest count possible). A restart inside a
//! dynamic stage with damping on modes recomputes the modes at the restored state: the same for
//! an elastic model, not for a softened one.
//! The probes of the seed's dynamic figures are named in `output.profiles.probes`, each the
//! element nearest to an elevation, in the central section (default) or at a bank
//! (`at: left_bank` / `right_bank`: the element of that row nearest the abutment, the left bank
//! at −y), an interface element (default) or a slab element (`element: slab`); the generated
//! quake scenes name the seed's F-A, I-A…I-D:
//!
//! ```yaml
//! output: { profiles: { probes: [ { name: I-B, elevation: 2809.0, at: left_bank },
//!                                 { name: F-A, elevation: 2813.0, element: slab } ] } }
//! ```
//!
//! `cfrd run` records their histories (Figs. 14, 18–20) at every time step, as it does the
//! crest's, so `output_every` only sets how often the full fields go to `results.h5` (the
//! coarse seed dam: about 0.24 MB per results step, 47 MB for the 20 s quake at
//! `output_every: 10`); `cfrd profiles` draws them again from results files, sampled at
//! their results steps ([`crate::post::quake_probes`]).
//!
//! Displacements of a dynamic stage are relative to the base; its results also hold the
//! `velocity` (relative) and the absolute `acceleration` (relative plus ground) of every node.
//! A results step inside stage k (1-based) at time t of its duration D has the step time
//! k − 1 + t/D and a label with t in seconds. `cfrd accel SPEC.yaml -o DIR` generates
//! spectrum-compatible records from the hydraulic code's design spectrum
//! ([`crate::seismic`], `inputs/accel/seed_quake.yaml`): at most
//! [`crate::seismic::spec::MAX_RECORD_SAMPLES`] samples per component (600 s at 0.01 s), a
//! longer spec refused at once naming `dt`; exit code 1 when a record misses the spectrum's
//! acceptance, 2 for bad input, 4 when an output cannot be written
//! (`bad_input::cfrd_accel_exits_4_when_it_cannot_write_and_2_for_a_record_too_long`).
//!
//! ## Linear solvers and PETSc options
//!
//! * `linear_solver: iterative` (default): CG with GAMG and the rigid-body near-null space for
//!   symmetric tangents, GMRES (right preconditioning) with GAMG levels smoothed by
//!   Richardson/SOR for non-symmetric ones. Results at different rank counts agree to the
//!   linear tolerance. It scales further (the solver benchmark goes to a million DOFs), but the
//!   stiff interfaces and joints of a dam with its slab defeat GAMG ([`crate::performance`]).
//! * `linear_solver: canonical_lu`: a sequential LU of the coupled part of the system on every
//!   rank, in the mesh's own DOF order (rows decoupled from the rest, the constrained DOFs and
//!   the nodes of fill not yet placed, are split off first). Results are then the same bit for
//!   bit on any number of ranks. It costs a serial factorization on every rank, so it suits
//!   meshes up to some 10⁵ DOFs (the fine seed mesh, 256,461 DOFs, still runs on it with
//!   MUMPS, at 10.2 GiB per rank). Within a stage the factors of an earlier Jacobian precondition
//!   GMRES on the current one and are renewed only when GMRES needs more than a few iterations
//!   (`reuse_factorization`, default true; `false` factors every Jacobian); the run summary
//!   counts the factorizations. `-canonical_pc_factor_mat_solver_type mumps` factors with MUMPS
//!   (faster from the medium mesh up, with the serial OpenBLAS that `ci/install-deps.sh`
//!   installs).
//! * `linear_solver: reduced_amg`: GMRES (CG for symmetric tangents) preconditioned on the
//!   coupled rows only, the rows of unplaced nodes and constrained DOFs solved by their
//!   diagonal. The interface, joint and slab nodes are factored (SuperLU_DIST over the ranks), the
//!   fill gets algebraic multigrid (GAMG), one after the other ([`crate::linalg::petsc::reduced_amg`]).
//!   Every rank holds only its share, so memory grows with the mesh and falls with the ranks:
//!   on the medium seed mesh, whose scenes use it, under half the canonical LU's memory per
//!   rank and time (medium hyperbolic scene: 291.0 s and 269 MiB against 614.3 s and 597 MiB,
//!   [`crate::performance`], "Linear solvers on the seed dam"). Its results agree with the canonical LU's to the Newton tolerance; two runs on the
//!   same rank count give the same bits, other rank counts other bits. Each rank runs one
//!   OpenMP thread inside SuperLU_DIST unless `OMP_NUM_THREADS` is set (one thread per core
//!   on every rank would compete for the cores of the other ranks). With more ranks than
//!   cores (or jobs side by side), set `OMPI_MCA_mpi_yield_when_idle=1`, as the tests do:
//!   a waiting rank then yields its core instead of spinning on it (the default dam to stage 5,
//!   two 2-rank jobs on 2 cores: 231 s each spinning, 15 s yielding). The corrections are
//!   solved only as tightly as Newton needs (Eisenstat–Walker; `rtol` is not used); the
//!   fill's multigrid is kept across the Jacobians of a stage while GMRES converges quickly,
//!   and the structure (slab, interfaces, joints) is factored afresh at every Jacobian; the
//!   run summary counts these factorizations. Options take the prefix `reduced_`
//!   (`-reduced_split false`, `-reduced_refresh_after N`, `-reduced_structure_refresh_after N`,
//!   `-reduced_fieldsplit_fill_pc_type hypre`, ...); `-snes_ksp_ew false` solves to `rtol`.
//! * `linear_solver: distributed_lu`: MUMPS's LU of the distributed matrix, factored by all
//!   ranks together. Each rank holds only its share of the matrix and the factors, so a mesh
//!   whose factors do not fit one rank's memory can use more ranks (or nodes). The factors are
//!   reused across Jacobians as with the canonical LU (`reuse_factorization`;
//!   [`crate::linalg::petsc::lagged_lu`]). Results agree with the canonical LU's, and between rank
//!   counts and runs, to the factorization's rounding, not bit for bit: MUMPS's parallel
//!   factorization sums in an order that depends on message timing. Its options take the
//!   prefix `distributed_` (`-distributed_mat_mumps_icntl_14 50` for more working memory,
//!   `-distributed_refactor_after 4`). `-distributed_pc_type asm -distributed_sub_pc_type lu`
//!   factors each rank's overlapping subdomain instead of the whole matrix (additive Schwarz
//!   under GMRES; the subdomain factors are reused the same way): no rank holds more than its
//!   subdomain's factors, at the price of more GMRES iterations; on the medium mesh's first
//!   17 stages it took 1.9 times the canonical LU's time on 2 ranks, and more memory
//!   ([`crate::performance`], "Tried and rejected").
//!
//! In a dynamic stage (its `linear_solver`, default `distributed_lu`) both direct solvers change
//! their inner solver: the Jacobian of a time step is dominated by the mass term, and an
//! incomplete LU of the current Jacobian (ILU(0), additive Schwarz with ILU(0) on subdomains
//! overlapping by two layers for the distributed solver, on the Jacobian in 3×3 node blocks)
//! preconditions GMRES for less than the substitutions of complete factors (twice as fast on
//! the coarse seed quake and over the first 0.88 s of the medium one, [`crate::performance`]).
//! GMRES solves a correction to 1e-6 of its residual, or only to a tenth of the Newton
//! tolerance where that is looser, so the later corrections of a step cost few iterations. With `distributed_lu` no rank
//! holds the whole Jacobian, its factors or a whole vector (`summary.json`,
//! `solver_rows_held_per_rank`; `dynamics::the_default_dynamic_solver_holds_no_global_matrix_on_any_rank`);
//! a solve that fails on ILU(0) is repeated with one more level of fill, up to ILU(2), kept for
//! the rest of the stage. Results agree between rank counts to the Newton tolerance (1, 2 and
//! 4 ranks: `dynamics::a_quake_on_the_distributed_solver_agrees_on_1_2_and_4_ranks`). The
//! canonical solver (`linear_solver: canonical_lu` in the dynamic stage) stays rank-count
//! independent, bit for bit. Their options there take the prefixes `canonical_dynamic_` and
//! `distributed_dynamic_`:
//! `-canonical_dynamic_pc_type lu -canonical_dynamic_pc_factor_mat_solver_type mumps` brings
//! back lagged complete factors ([`crate::linalg::petsc::lagged_lu`]).
//!
//! A scene whose blocks are all linear elastic is a linear problem, and its dynamic stages
//! take a shorter path: the Jacobian is built and completely factored once (again only when a
//! cut-back changes Δt) and its factors applied alone (options prefix `distributed_`, on one
//! rank PETSc's LU of the matrix in 3×3 node blocks, MUMPS on several); each step starts from
//! the internal forces kept at the committed state and integrates its elements once
//! (`summary.json`: `factorizations`, `element_loops`;
//! `dynamics::a_linear_scenes_quake_builds_and_factors_its_jacobian_once`). Such a quake
//! takes 12 times fewer seconds per step than OpenSees's on the same mesh
//! ([`crate::performance`], "A linear scene's quake against OpenSees").
//!
//! PETSc options go into `solver.petsc_options`, or follow the command: every single-dash word
//! with more than one letter is a PETSc option, taking the next word as its value unless that
//! is an option or a YAML file (a negative number is a value), and options on the command line
//! override the scene's. An option that no solver object read during the run (misspelled, or
//! for a solver the run does not use) is named in a warning at its end; `-log_view` (PETSc's
//! performance log, printed when the run ends) and the other options PETSc reads only when it
//! finalizes are not (`bad_input::negative_petsc_option_values_reach_petsc`):
//!
//! ```sh
//! mpirun -n 8 cfrd run dam.yaml -o out/dam -ksp_type gmres -pc_type hypre
//! mpirun -n 2 cfrd run dam.yaml -o out/dam -snes_linesearch_type basic -ksp_monitor
//! ```
//!
//! A bad PETSc option exits with code 2.
//!
//! ## Parallel runs and rank-count independence
//!
//! The mesh is partitioned with METIS across the MPI ranks, each construction band balanced on
//! its own so that every stage of a staged run keeps all ranks busy (`cfrd partition` does the
//! same ahead of time). Every rank evaluates its own elements and those along its partition
//! boundary and adds to its own rows only (the partition evens out these evaluated elements,
//! not only the owned ones; `cfrd partition` prints both), so each entry of the residual and
//! of the tangent is summed over the same elements in the same order at any rank count; every
//! norm behind a Newton decision (convergence, the line search's merit, the Dirichlet scaling)
//! is an exact, order-independent sum ([`crate::solver::exact_sum`]). With `canonical_lu` a static run, cut-backs,
//! line searches and plastic states included, is therefore the same bit for bit on any number of
//! ranks. A quake agrees to rounding, not bit for bit: between 1 and 2 ranks 2.0e-12 of the
//! largest values on a damped elastic column shaken in x and z, 1.4e-10 on an HHT-α quake of
//! a plastic column (its plastic path carries the rounding further), whose static stages stay
//! the same bit for bit (test
//! `quakes_on_the_canonical_solver_at_one_and_two_ranks`). With the iterative solver a run
//! agrees to the solver tolerance. Results go to one
//! parallel HDF5 file whose layout does not depend on the rank count. A panic on any rank
//! aborts the whole job (exit code 101), so a parallel job never hangs.
//!
//! ## Command line
//!
//! Run the parallel subcommands (`run`, `check`, `bench solver`) under `mpirun -n N`.
//!
//! | command | what it does |
//! |---|---|
//! | `cfrd run [SCENE] [-o DIR] [PETSc options]` | runs a scene (the embedded default scene without one) into `DIR` (the scene's `output.dir` otherwise) |
//! | `cfrd run ... --restart CHECKPOINT` | continues a run from a checkpoint of the same scene ([restart](#restart-and-checkpoints)) |
//! | `cfrd run ... --stop-after-stage K\|+N` | ends the run cleanly after stage K of the schedule, or after N stages of this run; results and checkpoint are written and `summary.json` records `stopped_after_stage` |
//! | `cfrd run ... --checkpoint stage\|step\|none` | overrides `output.checkpoint` without changing the scene (nor its hash) |
//! | `cfrd run ... --monitor` | prints every Newton residual and cut-back, as `solver.monitor` does, without changing the scene |
//! | `cfrd run ... --integration-tol-ratio R` | caps the GP substepping tolerance at R·newton_tol, as `solver.integration_tol_ratio` does, without changing the scene |
//! | `cfrd run ... --linear-solver iterative\|reduced_amg\|canonical_lu\|distributed_lu` | solves every stage with this linear solver instead of `solver.linear_solver` and the dynamic stages' `linear_solver`, without changing the scene: a long run continues from its checkpoint on another solver (its results then agree with the scene's to the solvers' tolerances, not bit for bit) |
//! | `cfrd run ... -q` | prints nothing but errors |
//! | `cfrd run ... --overwrite` | writes into a directory that holds another run's `results.h5`, `checkpoint.h5` or `summary.json` (its old checkpoint is removed first); without it such a directory is refused (exit code 2), and so is a restart from that directory's own checkpoint, which with `--overwrite` continues the results there (the steps before the checkpoint are kept). Temporary files of killed runs found there (`.results.h5.partial-<pid>` and the like) are named and removed. One run writes into a directory at a time: a run holds the lock of its `.cfrd.lock` (`flock`, released by the kernel when the run ends or is killed), and a second run into the same directory meanwhile exits 2 naming it, removing nothing (test `two_runs_into_one_output_directory_never_race`); a `.cfrd.lock` that is not a regular file (a directory, a symbolic link) is refused naming it |
//! | `cfrd run ... --restart CHECKPOINT --accept-changed FILE` | continues although FILE (a mesh, partition or record file of the scene) changed since the checkpoint was written, which is otherwise refused (exit code 2); repeatable; the log and `summary.json` name it |
//! | `cfrd check SCENE` | parses, validates and cross-checks the scene and its mesh without solving; prints the counts of nodes, elements, blocks, fixed DOFs and stages |
//! | `cfrd schema` | prints the JSON Schema of the scene format |
//! | `cfrd partition SCENE -n N -o FILE` | METIS partition for N ranks, written to `FILE`; the scene then names it in `partition:` |
//! | `cfrd compare A B [--tolerance T] [--common]` | largest absolute and relative difference of every field of every step of two results files or run directories (steps matched by stage and time, so a restarted run compares with the uninterrupted one) and the number of steps compared; exit code 1 when one run holds a step or field the other lacks (named on standard error) unless `--common` compares the steps both hold, and with `--tolerance` when a relative difference exceeds T |
//! | `cfrd export RESULTS --field F... [--stage S \| --step N] [--set NAME [--scene SCENE]] [--probe X,Y,Z...] [-o FILE.csv]` | fields of one step of a results file (or run directory) as CSV, without HDF5 tools: the last step by default, or the last step of stage S, or step N; node fields (`displacement`, `reaction`) or element fields (`stress`, `strain`, `interface_*`), one or more of the same kind; every node or element, those of a block (`--set 'slab_*'`, `*` matches any characters), of a node or face set of the scene (`--scene`), or the nearest node or element centre to each probe point (with its distance). Columns: ids, coordinates, then `<field>_<component>_<units>`; interface fields in their local frame [s, a, n]. Values exactly as stored. Standard output without `-o`; exit code 2 names an unknown field, stage, step or set and lists the ones there are (`cfrd::io::export`, feature `native`) |
//! | `cfrd overlay LABEL=DIR... -o FIG.png [--quake]` | the slab profiles (seed Figs. 8, 9) of several runs in one figure, e.g. one per interface model; with `--quake` their quake profiles before, after and residual (seed Fig. 13) |
//! | `cfrd profiles SCENE RUN... -o DIR` | the seed Figs. 7–11 (and 12–20 of a scene with an earthquake) of a run from its results, over several parts of a run made in parts, in order |
//! | `cfrd point TEST.yaml [-o DIR]` | material-point tests (drained triaxial, cyclic triaxial, oedometer, isotropic compression, interface direct shear under constant normal load or stiffness, model comparisons): CSV tables and a PNG figure; `inputs/point/` has an example of each and its `README.md` the format ([`crate::point`]) |
//! | `cfrd bench solver [--dofs N] [-o DIR]` | static linear-elastic solve of a seed-like dam section of about N DOFs: one table row (`scripts/bench_solver.sh` runs the set) |
//! | `cfrd bench materials [--quick]` | integration-point updates per second of every constitutive model, one core ([`crate::material::bench`]) |
//!
//! ```sh
//! mpirun -n 2 cfrd run inputs/scenes/seed_coarse_hyperbolic.yaml -o out/hyp
//! mpirun -n 2 cfrd check inputs/scenes/seed_fine_gp_interface.yaml
//! cfrd schema > cfrd-scene.schema.json
//! cfrd partition dam.yaml -n 8 -o dam.part
//! cfrd compare out/hyp_1rank out/hyp_2ranks --tolerance 1e-6
//! cfrd export out/hyp --stage impound_3 --field displacement --set 'slab_*' -o slab_u.csv
//! cfrd export out/hyp --field interface_traction --probe 42,0,2711 --set 'interface_*'
//! cfrd export out/hyp --field reaction --set foundation --scene inputs/scenes/seed_coarse_hyperbolic.yaml -o foundation.csv
//! cfrd overlay hyperbolic=out/hyp gp=out/gp -o slab.png
//! cfrd point inputs/point/interface_crosscheck.yaml -o out/point
//! mpirun -n 2 cfrd bench solver --dofs 1000000
//! ```
//!
//! ## Restart and checkpoints
//!
//! A staged scene writes `<out>/checkpoint.h5` at the end of a completed stage
//! (`output: { checkpoint: none }` turns it off): at every stage on small and medium meshes; on
//! large ones once the run has computed 39 times as long as the last checkpoint and results
//! copy took, so that writing costs at most 2.5 % of the run ([`crate::io::pacing`]; the fine
//! seed mesh every few stages), and always after the last stage and at
//! `--stop-after-stage`. With these default checkpoints a dynamic stage also writes one every
//! 100 of its time steps, counted from the stage's start (`cfrd::run::checkpoints`), so a quake
//! killed midway loses at most 100 steps. `output: { checkpoint: stage }` asks for the stage
//! ends only; `output: { checkpoint: step }` writes it after
//! every converged load step as well, for stages longer than a job may run: a restart then
//! continues inside the stage. `cfrd run --checkpoint stage|step|none` overrides the scene's
//! choice without changing the scene, whose hash a restart checks, so a run in parts may switch
//! to step checkpoints for its long stages. `--checkpoint-every N` writes the step checkpoints
//! after every N-th converged load step of the run only (counted over the run, so a restart
//! with the same N writes them at the same steps): a long quake writes a few checkpoints
//! instead of thousands (each holds the whole state, and in a static stage each starts a fresh
//! factorization), e.g. `--checkpoint-every 200` for the 2,000 steps of the seed quake.
//!
//! ```sh
//! mpirun -n 2 cfrd run dam.yaml -o out/a                                   # killed, or stopped
//! mpirun -n 2 cfrd run dam.yaml --restart out/a/checkpoint.h5 -o out/b     # continues
//! cfrd compare out/full out/b --common                                     # the steps both hold, matched by stage and time
//! ```
//!
//! * At the same rank count a restarted run gives the results of an uninterrupted run bit for
//!   bit; at another rank count it agrees to the solver tolerance (with `canonical_lu` static
//!   stages bit for bit too, quakes to rounding: see "Parallel runs"). A step checkpoint starts a fresh preconditioner after its step, in the
//!   uninterrupted run too, which is what makes the restart exact; so runs with step and with
//!   stage checkpoints differ by rounding, which the path-dependent plasticity carries further
//!   ([`crate::verification`]).
//! * A step checkpoint inside a quake also holds the point states of the quake's start, from
//!   which the restart rebuilds K₀ of Rayleigh damping and the modes, as the uninterrupted run
//!   built them at the quake's start (for a plastic dam they differ from the restored state's).
//! * The checkpoint is written to a temporary file and renamed when complete, so an interrupted
//!   write never damages the previous one. A checkpoint of another scene or mesh is refused
//!   (exit 2). It also names every file the scene reads (a Gmsh mesh, a partition, each
//!   component of a record) with the hash of its content: a restart with one that changed is
//!   refused (exit 2, naming the scene key and the file), so another record cannot be spliced
//!   into a quake halfway; `--accept-changed FILE` goes on with it, and the log and
//!   `summary.json` (`accepted_changed_inputs`) say so (test
//!   `a_changed_record_or_partition_is_refused_at_restart`).
//! * A run publishes its `results.h5` before every checkpoint (a complete copy, never a
//!   half-written file), so a run that is killed keeps the results of every step up to its
//!   checkpoint; a stage that fails leaves those of every stage it completed.
//! * The restarted run continues those results: its `results.h5` starts as a copy of the
//!   `results.h5` beside the checkpoint, keeps the steps up to the checkpoint and adds its
//!   own, numbered and timed as the uninterrupted run's (the fields every `output_every` time
//!   steps are counted from the stage's start), so its results, figures and tables are those of
//!   the whole run, and `cfrd compare` against the uninterrupted run needs no `--common`.
//!   Without such results beside the checkpoint (a checkpoint copied elsewhere, or written by
//!   an older build) the run says so and its results hold its own steps only. Give the restart
//!   its own `-o`; a restart into the checkpoint's own directory needs `--overwrite`. Its
//!   `summary.json` carries the solver counters and the per-stage wall times
//!   (`stage_seconds`) of the whole run, all parts.
//!
//! ## Runs in parts
//!
//! For runs longer than a job's time limit (the fine seed mesh runs for hours):
//!
//! ```sh
//! scripts/run_in_parts.sh SCENE OUT [RANKS] [-- cfrd run arguments]     # RANKS defaults to 2
//! PART_STAGES=10 scripts/run_in_parts.sh inputs/scenes/seed_fine_hyperbolic.yaml out/fine 2
//! cfrd profiles inputs/scenes/seed_fine_hyperbolic.yaml out/fine/part_1 out/fine/part_2 -o out/fine/profiles
//! ```
//!
//! Each call runs one part, `OUT/part_<k>`: the first starts the scene, every later call
//! restarts from the newest checkpoint into the next part, and a call after the last stage
//! says the run has finished. `PART_STAGES=N` ends each part cleanly after N stages
//! (`--stop-after-stage +N`); without it a part runs until it ends or is killed. Arguments after
//! `--` go to every part (e.g. `-- --checkpoint step`); the last part's results and figures
//! are those of the whole run. `OUT/parts.csv` lists each part's first
//! and last stage, wall time, peak memory of the largest rank and exit code; `OUT/part_<k>.log`
//! is its log. A part that was killed leaves its half-written results under a temporary name
//! (`.results.h5.partial-<pid>`); the next call removes it. `cfrd profiles` draws the seed
//! figures over the parts, so the probe histories cover all their stages. On a cluster,
//! submit the same call as a job until it reports that the run has finished, with `BIN`
//! pointing at an installed `cfrd`.
//!
//! ## Outputs
//!
//! A run writes into its output directory:
//!
//! | file | what |
//! |---|---|
//! | `results.h5` | one parallel HDF5 file: the mesh and, for every output step (the end of every stage), `displacement`, `reaction`, `strain`, `stress` and the interface fields, every dataset in input order whatever the rank count; layout, units and signs are documented in the crate docs of `cfrd::io` (feature `native`) |
//! | `results.xdmf` | the XDMF description of `results.h5`: open it in ParaView or VisIt (one time step per output step) |
//! | `summary.json` | run summary: scene, ranks, nodes, elements, DOFs, wall time per phase and per stage (`stage_seconds`), Newton iterations, steps, cut-backs, `newton_per_step`, factorizations, multigrid builds, KSP iterations, interface points open and slipping, peak memory per rank, checkpoint time, `restarted_after_stage` / `stopped_after_stage` |
//! | `checkpoint.h5` | the last checkpoint (staged scenes) |
//! | `fig07_dam_displacement`, `fig08_slab_stress`, `fig09_slab_deflection`, `fig10_probe_NAME`, `fig11_interface` (`.csv` and `.png`) | the seed's Figs. 7–11 with `output.profiles`: dam displacement on the crest vertical, slab stresses and deflection at the central section at the end of construction and after impoundment, the stress path of each probe interface element, interface jumps and opening ([`crate::post::profiles`]) |
//!
//! | `quake_crest.csv/.png`, `quake_summary.json` | a scene with an earthquake: the crest's (the centre of the dam body's crest, outside the face slab, [`crate::post::quake::crest_node`]) displacement since the quake began, absolute and ground acceleration at every time step (kept in step checkpoints, so a restarted run writes the whole quake); residual crest displacement, peak accelerations and amplification ([`crate::post::quake`]) |
//! | `fig12_outline`, `fig13_residual_slab` (`.csv` and `.png`) | a scene with an earthquake (with `output.profiles` or its defaults): the central cross-section before and after the quake, residual displacement magnified by the factor its CSV's first line and the plot state (seed Fig. 12); slab σ_s, σ_a and deflection at the central section before, after and residual = after − before (Fig. 13) ([`crate::post::quake_figures`]) |
//! | `fig15_interface_residual.csv`, `fig15_interface_slip.png`, `fig16_interface_normal`, `fig17_interface_opening` | residual interface shear displacement (cushion relative to slab) of every interface element as vectors on the unfolded face (Fig. 15), residual normal displacement excluding opening (Fig. 16) and opening after the quake (Figs. 16–17) along the axis, one line per elevation; the three CSVs hold one row per interface element |
//! | `fig14_slab_probe_NAME`, `fig18_interface_probe_NAME`, `fig20_opening` (`.csv` and `.png`), `quake_probes.csv` | histories of the probes of `output.profiles.probes`: σ_s, σ_a of a slab probe (`element: slab`, the seed's F-A, Fig. 14); σ_n, τ_s, τ_a, δ_s, δ_a, δ_n and opening of an interface probe (I-B, I-C: Figs. 18–19); the opening of every interface probe (I-D: Fig. 20); where each probe lies. Every time step of the quake plus t = 0, the state before it (kept in step checkpoints; `cfrd profiles` samples them at the results steps instead); each CSV says so in its first line ([`crate::post::quake_probes`]) |
//!
//! Fig. 8 of the main job (`fig08_slab_stress.png` of the coarse GP-interface scene, as kept
//! in `scripts/figures/seed_static_gp_interface_fig08_slab_stress.png`):
//!
//! ![slab stresses of the coarse seed dam, GP interface][fig08]
//!
//! ## Exit codes
//!
//! | code | meaning |
//! |---|---|
//! | 0 | success (also a run ended by `--stop-after-stage`) |
//! | 1 | `cfrd compare` found a larger difference than `--tolerance`, or steps or fields only one run holds (without `--common`); MPI could not be initialized |
//! | 2 | bad input: YAML, mesh, parameters, options, a checkpoint of another scene; the message names the YAML path, file line or element id |
//! | 3 | solver failure (a load step that still fails after its cut-backs); `cfrd bench materials` when a model failed |
//! | 4 | I/O or environment failure: a full disk, a failing file system, an output directory that cannot be created; the last checkpoint and the results published before it are intact |
//! | 101 | a bug: the panic hook aborts every rank, so a parallel job never hangs |
//!
//! A full disk is found before HDF5 writes: every collective write first checks that its size
//! plus a reserve of 512 KiB (room for the file's metadata) is free on the output file system,
//! and refuses it on every rank otherwise (exit code 4, naming the file and the bytes free and
//! needed). A write that fails anyway is never followed by a collective close (which could
//! hang); the ranks end with exit code 4 and remove their temporary files. A rank that stays
//! too long inside one collective file operation prints what it was writing and ends with exit
//! code 4, and `mpirun` ends the others: 45 s plus the operation's bytes at 4 MiB/s by default
//! (a few seconds more for a checkpoint of the fine seed mesh), `CFRD_IO_TIMEOUT` seconds if
//! set. Files it leaves (`.results.h5.partial-<pid>`) are named and removed by the next run
//! into that directory. Figures, tables and the summary are written under a temporary name
//! (`.fig08_slab_stress.partial-<pid>.png`) and renamed once complete, so a full disk while
//! they are written leaves no truncated file. `CFRD_IO_RESERVE` (bytes) changes the reserve; the fault tests set it to 0 to
//! meet a full disk inside HDF5.
//!
//! Every checkpoint is read back after it is written and before it replaces the previous one,
//! and ends with an integrity record (`cfrd::io::integrity`): checksums of each dataset's bytes
//! and of the HDF5 metadata in 4 KiB pieces. A restart checks it before HDF5 reads the file; a
//! changed byte is refused with exit code 2 naming the dataset (`dataset /checkpoint/u (bytes
//! 4096..4952) does not match its checksum`) or the metadata bytes. Every table of a results
//! file carries a `checksum` attribute, checked whenever cfrd reads it back (`cfrd compare`,
//! `cfrd profiles`).
//!
//! Hostile input is refused with exit code 2 before memory is reserved for it or a solve starts:
//! every count a mesh file announces is bounded by what a file of its size can hold; scene, mesh,
//! record and partition files, `cfrd accel` and `cfrd point` specifications and the files given to
//! `cfrd compare`, `cfrd export` and `--restart` must be regular files (scenes at most 16 MiB,
//! meshes 4 GiB, records 1 GiB), and their kind is checked before anything blocks on them, so a
//! FIFO is refused at once instead of hanging the reader (test
//! `a_fifo_in_place_of_any_input_file_exits_2_within_5_s`); an argument that is not UTF-8 is named
//! (`a_non_utf8_argument_exits_2_naming_it`); a generated mesh has at most 2^25 nodes, `mesh.cfrd.impoundment_stages` is at most
//! 10 000 and a stage at most 10^6 load steps; YAML may nest at most 64 brackets deep and 256
//! columns of indentation; a key given twice in a mapping (a block, a material) is an error
//! naming both lines; every body of the elements placed by a stage must be held against all six
//! rigid-body motions by its fixed displacements (the message names the free ones). The readers
//! are fuzzed ([below](#fuzzing-the-input-readers)).
//!
//! ## Fuzzing the input readers
//!
//! The readers that take a user's files are fuzzed, coverage-guided, so that hostile input
//! gives an error and never a panic, an abort or a hang. The fuzz targets live in `tests/fuzz`
//! (a `cargo fuzz` package of its own, building `cfrd` without the native stack); each runs one
//! entry function of [`crate::fuzzing`] on the bytes of one input:
//!
//! | target | reader | seeds |
//! |---|---|---|
//! | `scene` | [`crate::scene::Scene::from_str`] as `cfrd check` runs it: YAML, values, the mesh (generated, or a Gmsh file of `inputs/meshes`), records of `inputs/accel`, cross-references, restraint | `inputs/scenes`, `tests/fuzz/seeds/scene` |
//! | `gmsh` | [`crate::mesh::gmsh::parse_gmsh`], MSH 2.2 and 4.1 | `inputs/meshes` |
//! | `accel_csv` | [`crate::seismic::Accelerogram::from_csv_str`] (a dynamic stage's `record`) | `inputs/accel`, `tests/fuzz/seeds/accel_csv` |
//! | `accel_at2` | [`crate::seismic::at2::parse_at2`], then a three-component record | hand-written PEER AT2 samples |
//! | `state_codec` | the checkpoint's decoders of the integration-point states of every model ([`crate::solver::state_codec`]), with a re-encoding round trip | the encoded initial states of every model |
//! | `lock_file` | the output directory's lock ([`crate::dir_lock::RunLock::acquire`]) over whatever stands at `OUT/.cfrd.lock`: nothing, a file of any bytes, a directory, a link; the file's bytes and a link's target left as they were | `tests/fuzz/seeds/lock_file` |
//! | `checkpoint_inputs` | a checkpoint's `input_files` text against a scene's input files ([`crate::scene::inputs::changed`]), every change named a key of the text | `tests/fuzz/seeds/checkpoint_inputs` |
//!
//! An `Err` is the right answer to bad input; a panic, an abort (out of memory, a capacity
//! overflow, a sanitizer report) or an input that runs longer than 10 s is a bug. Scenes that
//! ask a generator for more than [`crate::fuzzing::SCENE_MAX_NODES`] nodes are valid input whose
//! cost grows with the size asked for; the `scene` target skips them (and keeps them out of the
//! corpus). The rest of the checkpoint reader (HDF5 attributes and datasets, `cfrd::io`) needs
//! the native stack and is not fuzzed; nor are partition files.
//!
//! ```sh
//! scripts/fuzz_campaign.sh 1000000    # RUNS inputs per target; installs cargo-fuzz if missing
//! cargo test --release --test fuzz_corpus   # stable: replays tests/fuzz/corpus/<target>/
//! ```
//!
//! The script builds the targets with the nightly toolchain (AddressSanitizer, debug
//! assertions), runs each under libFuzzer with `-timeout=10 -rss_limit_mb=2048
//! -malloc_limit_mb=2048 -max_len=8192` from the seeds, the kept corpus and a dictionary of
//! scene keys or Gmsh sections (`tests/fuzz/dict`), minimizes the corpus into
//! `tests/fuzz/corpus/<target>/` (at most 300 inputs per target: a greedy set cover of the
//! edges that libFuzzer's merge reports) and copies any crasher there. `tests/fuzz_corpus.rs` replays every corpus file on stable in CI, each in its own
//! thread: a panic or a run over 20 s fails the test naming the file.
//!
//! The campaign of commit 04cb365 (`scripts/fuzz_campaign.sh 1000000` from an empty corpus, on
//! 2 cores shared with other jobs):
//!
//! | target | inputs | accepted | rejected | skipped | panics | aborts | time-outs | time (s) | inputs/s | edges | corpus files | corpus KiB |
//! |---|---|---|---|---|---|---|---|---|---|---|---|---|
//! | `scene` | 1,000,000 | 3,841 | 996,132 | 27 | 0 | 0 | 0 | 1077 | 929 | 13,455 | 300 | 60 |
//! | `gmsh` | 1,000,000 | 1,399 | 998,601 | 0 | 0 | 0 | 0 | 98 | 10,163 | 2,212 | 300 | 142 |
//! | `accel_csv` | 1,000,000 | 4,725 | 995,275 | 0 | 0 | 0 | 0 | 13 | 76,923 | 303 | 45 | 3 |
//! | `accel_at2` | 1,000,000 | 9,395 | 990,605 | 0 | 0 | 0 | 0 | 16 | 62,112 | 476 | 87 | 3 |
//! | `state_codec` | 1,000,000 | 63,229 | 936,771 | 0 | 0 | 0 | 0 | 24 | 41,322 | 938 | 144 | 23 |
//!
//! The campaign of the lock and hashed-input targets, with the scene target again after AT2
//! records entered scenes (`TARGETS="lock_file checkpoint_inputs scene"
//! scripts/fuzz_campaign.sh 100000`, from the kept corpus and the seeds, on 2 cores):
//!
//! | target | inputs | accepted | rejected | skipped | panics | aborts | time-outs | time (s) | inputs/s | edges | corpus files | corpus KiB |
//! |---|---|---|---|---|---|---|---|---|---|---|---|---|
//! | `lock_file` | 100,000 | 46,660 | 53,340 | 0 | 0 | 0 | 0 | 44 | 2,278 | 94 | 7 | 0 |
//! | `checkpoint_inputs` | 100,000 | 427 | 99,573 | 0 | 0 | 0 | 0 | 12 | 8,264 | 232 | 21 | 1 |
//! | `scene` | 100,000 | 336 | 99,658 | 6 | 0 | 0 | 0 | 78 | 1,274 | 13,934 | 300 | 61 |
//!
//! Inputs are libFuzzer's executions (the seeds included); accepted and rejected count what the
//! reader returned; edges are the instrumented code edges reached (the readers and the libraries
//! they call). Every input finished in under a second (libFuzzer's slowest unit: 0 s); the peak
//! memory of a target was 390–620 MB, most of it the sanitizer's. The kept corpus (876 files, 230
//! KiB) reaches every edge of the campaign except 1,852 of the scene's and 39 of the Gmsh
//! reader's, cut by the cap of 300 inputs. No panic, abort or time-out was found: the counts and
//! sizes these readers take from a file were already bounded by what the file can hold. Writing
//! the targets found one hostile-input defect outside them: a dynamic stage's `record` (and
//! `cfrd::seismic::read_at2`) was read whole with no check of the file's kind, so a record path
//! naming a FIFO or a device hung or exhausted the memory; records are now read as regular files
//! of at most 1 GiB, like scenes and meshes. A state that decodes is not checked for physical
//! sense (its stress may be NaN): a checkpoint is trusted once its scene hash and layout match.
#![cfg_attr(doc, doc = embed_doc_image::embed_image!("fig08", "scripts/figures/seed_static_gp_interface_fig08_slab_stress.png"))]
