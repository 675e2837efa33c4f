//! The scene file format (serde + JSON Schema). Every field is documented here; `cfrd schema`
//! prints the JSON Schema generated from these types, so editors can validate and complete
//! scene files and this documentation cannot fall out of date.

use crate::element::interface8::InterfaceRule;
use crate::material::MaterialParams;
pub use crate::mesh::cfrd::CfrdSpec;
pub use crate::mesh::generate::{BoxSpec, DamSpec};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// A scene: mesh, materials, boundary conditions, loads, solver and output settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Name of the scene (written into the results).
    pub name: String,
    /// Unit system. Only `SI` is accepted (N, m, kg, s, Pa).
    pub units: Units,
    /// Where the mesh comes from.
    pub mesh: MeshSource,
    /// Optional precomputed partition (`cfrd partition`); METIS runs at start-up otherwise.
    #[serde(default)]
    pub partition: Option<PathBuf>,
    /// Materials by name.
    pub materials: BTreeMap<String, MaterialParams>,
    /// Element blocks (mesh physical volumes) by name, each with its material. Every block of
    /// the mesh must be listed. A key with `*` is a pattern (`*` matches any run of characters,
    /// e.g. `fill_*_cushion`): it applies to every block it matches that has no exact key; a
    /// pattern that matches no block, or a block matched by two patterns, is an error.
    pub blocks: BTreeMap<String, BlockSpec>,
    /// Displacement boundary conditions on node sets.
    #[serde(default)]
    pub boundary: Vec<FixSpec>,
    /// Loads. Each load present adds one physics term; absent loads are not built.
    #[serde(default)]
    pub loads: LoadsSpec,
    /// Construction and loading stages, in order. Without stages the scene is one stage that
    /// places every block and applies `loads` (a `mesh.cfrd` scene runs the generator's
    /// schedule instead). With stages, each stage places its blocks
    /// (strain-free) and applies `loads` plus its own loads.
    #[serde(default)]
    pub stages: Vec<StageSpec>,
    /// Linear and nonlinear solver settings.
    #[serde(default)]
    pub solver: SolverSpec,
    /// Output settings.
    #[serde(default)]
    pub output: OutputSpec,
}

/// Unit system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum Units {
    /// N, m, kg, s, Pa.
    SI,
}

/// Mesh source: exactly one of `file`, `box`, `dam` or `cfrd`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshSource {
    /// A Gmsh MSH 4.1 or 2.2 ASCII file, relative to the scene file.
    #[serde(default)]
    pub file: Option<PathBuf>,
    /// A structured box of hexahedra: blocks `layer_1..layer_k` from the bottom up, node and
    /// face sets `xmin, xmax, ymin, ymax, zmin, zmax`.
    #[serde(default, rename = "box")]
    pub box_: Option<BoxSpec>,
    /// A dam-like trapezoidal section extruded along the dam axis: blocks `layer_1..layer_k`;
    /// node and face sets `upstream`, `downstream`, `base` (z = 0), `crest`, `ymin`, `ymax`.
    #[serde(default)]
    pub dam: Option<DamSpec>,
    /// A complete CFRD in a trapezoidal canyon (`crate::mesh::cfrd`; omitted keys take the seed
    /// dam's values): blocks `fill_KKK_{cushion,transition,rockfill}`, `slab_S`, `interface_S`,
    /// `joint_vertical_S`, `joint_perimetric_{bottom,left,right}_S` (orientations set); node
    /// sets `foundation`, `plinth`; face set `slab_upstream`; z is the elevation. Without
    /// `stages` the scene runs the generator's schedule: fill layers, slab stages, then
    /// impoundment (hydrostatic load on `slab_upstream` at rising levels).
    #[serde(default)]
    pub cfrd: Option<CfrdSpec>,
}

/// Material assignment of a block.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    /// Name of a material in `materials`: a solid model for a block of hexahedra, an interface
    /// or joint law for a block of zero-thickness elements.
    pub material: String,
    /// Interface blocks: the orientation vector n_ref, from the slab side (nodes 1–4) into the
    /// cushion/dam side (nodes 5–8) (spec (E3)), e.g. `[1, 0, -1.4]` under an upstream slab.
    /// Required unless the mesh generator sets it.
    #[serde(default)]
    pub orientation: Option<[f64; 3]>,
    /// Interface blocks: integration rule, `newton_cotes` (nodal, default, spec (E8)) or
    /// `gauss2x2`.
    #[serde(default)]
    pub rule: Option<InterfaceRule>,
    /// Interface blocks: normal stress σ_n0 ≥ 0 (Pa, compression positive) of the points when
    /// the block is placed (spec (E9), gap G5; default 0: placed without stress, like the fill).
    #[serde(default)]
    pub initial_normal_stress: Option<f64>,
}

/// Displacement component.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// x (stream).
    X,
    /// y (dam axis).
    Y,
    /// z (up).
    Z,
}

impl Axis {
    /// Component index 0, 1, 2.
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }
}

/// Fixed displacement components on a node set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FixSpec {
    /// Node set name (a mesh physical group of points, curves or surfaces).
    pub set: String,
    /// Components to fix.
    pub fix: Vec<Axis>,
    /// Prescribed displacement (m) for the fixed components, in the order of `fix`;
    /// zero when omitted.
    #[serde(default)]
    pub value: Vec<f64>,
}

/// One construction or loading stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StageSpec {
    /// Stage name (unique; written into the results).
    pub name: String,
    /// Blocks placed at the start of the stage. A placed block starts without strain and at
    /// zero stress (the GP rockfill at its pressure floor); its nodes that were not yet part of
    /// the model start with zero displacement, so displacements count from placement.
    #[serde(default)]
    pub activate: Vec<String>,
    /// Loads of this stage, on top of the scene's `loads` (at the end of the stage; the force
    /// goes linearly from the previous stage's to this one's).
    #[serde(default)]
    pub loads: LoadsSpec,
    /// Load steps of this stage (default: `solver.load_steps`).
    #[serde(default)]
    pub load_steps: Option<u32>,
}

/// Loads of the scene.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadsSpec {
    /// Self-weight with the gravity vector `g` (m/s²), e.g. `[0, 0, -9.81]`.
    #[serde(default)]
    pub gravity: Option<GravitySpec>,
    /// Uniform pressures on face sets.
    #[serde(default)]
    pub pressure: Vec<PressureSpec>,
    /// Hydrostatic water pressure on face sets, from a free surface at `level`.
    #[serde(default)]
    pub hydrostatic: Vec<HydrostaticSpec>,
}

/// Gravity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GravitySpec {
    /// Gravity acceleration vector (m/s²).
    pub g: [f64; 3],
}

/// A uniform pressure on a face set; positive pushes against the face (compression).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PressureSpec {
    /// Face set name (a mesh physical surface).
    pub faces: String,
    /// Pressure (Pa).
    pub value: f64,
}

/// Hydrostatic pressure p = γ_w·⟨level − z⟩ on a face set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HydrostaticSpec {
    /// Face set name.
    pub faces: String,
    /// Elevation of the free surface (m).
    pub level: f64,
    /// Unit weight of water γ_w (N/m³); default 9810.
    #[serde(default = "gamma_w")]
    pub unit_weight: f64,
}

fn gamma_w() -> f64 {
    9810.0
}

/// Solver settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Relative tolerance of the linear solver (unpreconditioned residual).
    #[serde(default = "rtol")]
    pub rtol: f64,
    /// Maximum linear iterations.
    #[serde(default = "max_it")]
    pub max_iterations: u32,
    /// Newton tolerance on the residual relative to the external force.
    #[serde(default = "newton_tol")]
    pub newton_tol: f64,
    /// Maximum Newton iterations per step.
    #[serde(default = "newton_max")]
    pub newton_max_iterations: u32,
    /// Number of equal load steps from no load to the full loads (load factor λ = k/n).
    #[serde(default = "one")]
    pub load_steps: u32,
    /// Consecutive cut-backs (halving the load step) allowed before a step is declared failed.
    #[serde(default = "max_cutbacks")]
    pub max_cutbacks: u32,
    /// PETSc options, e.g. `-ksp_type gmres -pc_type hypre`; command-line options override them.
    #[serde(default)]
    pub petsc_options: String,
    /// Print every Newton iteration's relative residual and the reason of every cut-back
    /// (rank 0, to standard error). Default false.
    #[serde(default)]
    pub monitor: bool,
    /// Linear solver of the Newton corrections: `iterative` (default; CG or GMRES with GAMG,
    /// PETSc options override) or `canonical_lu`, a sequential LU of the whole system on every
    /// rank in the mesh's own DOF order, whose results are the same bit for bit at any rank
    /// count (`linalg::petsc::CanonicalLu`; up to some 10⁵ DOFs).
    #[serde(default)]
    pub linear_solver: LinearSolver,
    /// With `canonical_lu`: keep the factors of an earlier Jacobian of the same stage as the
    /// preconditioner of GMRES on the current one, and factor again only when GMRES needs more
    /// than a few iterations (`linalg::petsc::CanonicalLu`). Default true; `false` factors every
    /// Jacobian (an exact direct solve per Newton iteration).
    #[serde(default = "yes")]
    pub reuse_factorization: bool,
    /// Cap on the substepping tolerance STOL (spec §8.2) of every generalized-plasticity
    /// material (rockfill and interface), as a multiple of `newton_tol`: with a ratio R > 0 a
    /// GP material integrates at min(its `integration.stol`, R·newton_tol). The explicit
    /// integration's local error, some STOL of the stress, changes by jumps as the number of
    /// substeps of a point changes from one Newton iterate to the next; in the internal forces
    /// it is noise that no Newton correction removes, so Newton stalls at a relative residual
    /// of about STOL when that lies above `newton_tol`. Measured on the fine seed mesh (slab
    /// stage II, newton_tol 1e-5, the spec's STOL 1e-4): the first load step's residual stayed
    /// at 1.125e-4 for 14 iterations, and after two half steps the step to λ = 0.25 stalled at
    /// 1.128e-4; at STOL 1e-6 (R = 0.1) that step converged in 3 iterations. A tighter STOL
    /// costs substeps (about STOL^−1/2 each where an increment needs several): on the small GP dam of `tests/cfrd_dam.rs` with one
    /// load step per stage R = 0.1 exhausts the substep limit, so the cap is for small load
    /// steps on fine meshes. Default 0 (off: each material's own STOL). The command line's
    /// `--integration-tol-ratio` caps further without changing the scene (a restart accepts it).
    #[serde(default = "integration_tol_ratio")]
    pub integration_tol_ratio: f64,
}

impl SolverSpec {
    /// The substepping tolerance of a GP material whose own tolerance is `stol`
    /// ([`SolverSpec::integration_tol_ratio`]).
    pub fn capped_stol(&self, stol: f64) -> f64 {
        if self.integration_tol_ratio > 0.0 {
            stol.min(self.integration_tol_ratio * self.newton_tol)
        } else {
            stol
        }
    }
}

/// The linear solver of the Newton corrections.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum LinearSolver {
    /// Krylov (CG for symmetric tangents, GMRES otherwise) with algebraic multigrid; results at
    /// different rank counts agree to the linear tolerance.
    #[default]
    Iterative,
    /// Sequential LU on every rank in the mesh's DOF order: results independent of the rank
    /// count, bit for bit.
    CanonicalLu,
}

fn rtol() -> f64 {
    1e-10
}
fn max_it() -> u32 {
    2000
}
fn newton_tol() -> f64 {
    1e-8
}
fn yes() -> bool {
    true
}
fn integration_tol_ratio() -> f64 {
    0.0
}
fn one() -> u32 {
    1
}
fn newton_max() -> u32 {
    25
}
fn max_cutbacks() -> u32 {
    8
}

impl Default for SolverSpec {
    fn default() -> Self {
        SolverSpec {
            rtol: rtol(),
            max_iterations: max_it(),
            newton_tol: newton_tol(),
            newton_max_iterations: newton_max(),
            load_steps: 1,
            max_cutbacks: max_cutbacks(),
            petsc_options: String::new(),
            monitor: false,
            linear_solver: LinearSolver::Iterative,
            reuse_factorization: true,
            integration_tol_ratio: integration_tol_ratio(),
        }
    }
}

/// Output settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output directory, relative to the working directory (the command line `-o` overrides it).
    #[serde(default = "out_dir")]
    pub dir: PathBuf,
    /// Where the reported displacement of a node placed by a construction stage counts from
    /// (scenes with `stages` only; the solution itself does not depend on it).
    #[serde(default)]
    pub placed_nodes: PlacedNodes,
    /// CSV tables and PNG plots of the seed's static outputs (Figs. 7–11: dam displacement,
    /// slab stresses and deflection, interface jumps, probe stress paths) written into the
    /// output directory at the end of the run; see [`crate::profiles`]. Absent: not written.
    #[serde(default)]
    pub profiles: Option<crate::profiles::ProfilesSpec>,
    /// When to write `checkpoint.h5` into the output directory for `cfrd run --restart`:
    /// `stage` (at the end of every completed stage) or `none`. Default: `stage` for scenes
    /// with `stages`, `none` otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub checkpoint: Option<CheckpointMode>,
}

/// When a run writes its checkpoint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CheckpointMode {
    /// At the end of every completed stage (replacing the previous checkpoint).
    Stage,
    /// After every converged load step, and at the end of every stage: a restart continues
    /// inside the stage (for stages that take longer than a job may run). Each such
    /// checkpoint also starts a fresh preconditioner, so the results differ in the last bits
    /// from a run with stage checkpoints (`io::checkpoint`).
    Step,
    /// Never.
    None,
}

/// Zero of the reported displacement of nodes placed by a construction stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum PlacedNodes {
    /// From the end of the stage that placed them: the surface of a new lift starts level and
    /// its settlement counts from then (the usual convention of layered-embankment analysis,
    /// which gives the classical layered settlement s(z) = γ(H − z)z/M of a confined column).
    #[default]
    EndOfStage,
    /// From the start of the stage that placed them (includes the settlement under the lift's
    /// own weight during its placement).
    StartOfStage,
}

fn out_dir() -> PathBuf {
    PathBuf::from("out")
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            dir: out_dir(),
            placed_nodes: PlacedNodes::default(),
            profiles: None,
            checkpoint: None,
        }
    }
}
