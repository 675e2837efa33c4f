//! Static equilibrium with Newton's method (PETSc SNES with a line search) on the distributed system.
//!
//! ```text
//! r(u) = f_ext − f_int(u) = 0,   f_int = Σ_e ∫ Bᵀ σ(Δε) dV,   K δu = r,   u ← u + δu
//! ```
//! Every iterate integrates the material from the committed state with the total step
//! increment (spec §8.1); the states are committed only at convergence. Dirichlet DOFs are kept
//! in the system (block size 3 for algebraic multigrid) with unit rows and columns.
//!
//! Rank-count independence: the residual, the tangent and the external forces are assembled
//! row by row on the owning rank over the same elements in the same order at any rank count
//! (`discretization`); the convergence test, the line search (through the SNES objective) and
//! the Dirichlet scaling use exact sums (`exact_sum`); with
//! [`LinearSolver::CanonicalLu`] the corrections are too, so a run is the same bit for bit on
//! any number of ranks, whatever its load path.

use super::checkpoint::ProblemState;
use super::discretization::Discretization;
use super::interface::{InterfaceElementOutput, InterfaceElements};
use super::solid::{SolidBlock, Vector24};
use super::state_codec;
use crate::element::hex8::{face_pressure_load, gravity_load, Hex8Geometry};
use crate::element::interface8::Interface8Geometry;
use crate::element::interface_frame::FrameAxes;
use crate::linalg::petsc::{
    CanonicalSettings, Gather, Matrix, Petsc, PetscError, Snes, SnesOutcome, SnesProblem, Vector,
};
use crate::material::BlockMaterial;
use crate::mesh::Mesh;
use crate::parallel::{any_error, exact_norm2, exact_sum, sum_u64};
use crate::parallel::{any_true, broadcast_vec, max_f64};
use crate::scene::schema::{LinearSolver, PlacedNodes};
use crate::scene::{Scene, Term};
use crate::tensor::{Strain6, Stress6};
use mpi::collective::{CommunicatorCollectives, SystemOperation};
use mpi::topology::SimpleCommunicator;
use mpi::traits::Communicator;
use partition::Cells;
use std::time::Instant;

/// Failures of a static solve.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// PETSc failed.
    #[error(transparent)]
    Petsc(#[from] crate::linalg::petsc::PetscError),
    /// A material update failed (element id and reason).
    #[error("element {element}: {reason}")]
    Material {
        /// Input id of the element.
        element: u64,
        /// Why.
        reason: String,
    },
    /// An element has a non-positive Jacobian.
    #[error("element {element}: non-positive Jacobian")]
    Geometry {
        /// Input id of the element.
        element: u64,
    },
    /// The linear solver diverged.
    #[error("linear solver diverged (PETSc reason {reason}) after {iterations} iterations")]
    Linear {
        /// PETSc's converged reason.
        reason: i32,
        /// Iterations done.
        iterations: u32,
    },
    /// Newton did not converge.
    #[error(
        "Newton did not converge in {iterations} iterations (relative residual {residual:.3e}); \
         {worst}{hint}"
    )]
    Newton {
        /// Iterations done.
        iterations: u32,
        /// Last relative residual.
        residual: f64,
        /// Where the out-of-balance force of the last iterate is largest.
        worst: String,
        /// Empty, or why the residual may not fall further (the GP integration noise, spec §8.2).
        hint: String,
    },
    /// The line search found no step that reduces the residual.
    #[error(
        "line search failed after {iterations} Newton iterations (relative residual \
         {residual:.3e}); {worst}"
    )]
    LineSearch {
        /// Iterations done.
        iterations: u32,
        /// Last relative residual.
        residual: f64,
        /// Where the out-of-balance force of the last iterate is largest.
        worst: String,
    },
    /// A material update failed on some rank (message of the lowest failing rank).
    #[error("{0}")]
    Collective(String),
    /// A load step could not be completed even after cutting it back.
    #[error(
        "load step from λ = {from:.6} to λ = {to:.6} failed after {cutbacks} cut-back(s); \
         the last converged state is λ = {from:.6}: {source}"
    )]
    Step {
        /// Last converged load factor.
        from: f64,
        /// Load factor of the failed attempt.
        to: f64,
        /// Cut-backs tried.
        cutbacks: u32,
        /// Why the last attempt failed.
        source: Box<SolveError>,
    },
}

impl SolveError {
    /// Whether a smaller step may succeed (material failure, Newton or linear divergence).
    pub fn recoverable(&self) -> bool {
        matches!(
            self,
            SolveError::Material { .. }
                | SolveError::Collective(_)
                | SolveError::Newton { .. }
                | SolveError::LineSearch { .. }
                | SolveError::Linear { .. }
        )
    }
}

/// Where the load stepping of a stage stands: the load factor reached, the next increment and
/// the count of successes since the last change of the increment. Step checkpoints store it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadPath {
    /// Load factor λ reached in the stage (0 at its start, 1 at its end).
    pub lambda: f64,
    /// The next increment of λ (1/n_steps, or less after cut-backs).
    pub d_lambda: f64,
    /// Converged steps since the increment last changed (it doubles after two).
    pub streak: u32,
}

impl LoadPath {
    /// The start of a stage of `n_steps` equal increments.
    pub fn new(n_steps: u32) -> Self {
        LoadPath {
            lambda: 0.0,
            d_lambda: 1.0 / n_steps.max(1) as f64,
            streak: 0,
        }
    }

    /// Whether the stage's loads are fully applied.
    pub fn done(&self) -> bool {
        self.lambda >= 1.0 - 1e-12
    }
}

/// A stage in progress in a step checkpoint: the load path and what
/// [`StaticProblem::begin_stage`] computed at the stage's start (rank-local, owned order).
#[derive(Debug, Clone, PartialEq)]
pub struct StageProgress {
    /// The load stepping reached.
    pub path: LoadPath,
    /// Displacement of the owned DOFs at the start of the stage.
    pub u_stage_start: Vec<f64>,
    /// Per owned node: whether it was placed before the stage.
    pub node_was_active: Vec<bool>,
}

/// Counters and timings of a solve.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct SolveReport {
    /// Newton iterations.
    pub newton_iterations: u32,
    /// KSP iterations of each linear solve.
    pub ksp_iterations: Vec<u32>,
    /// Relative residual after each Newton iteration.
    pub residuals: Vec<f64>,
    /// Wall time in assembly (s).
    pub assembly_seconds: f64,
    /// Wall time in linear solves (s).
    pub solve_seconds: f64,
    /// Converged load steps.
    pub steps: u32,
    /// Step cut-backs (a failed step retried with half the increment).
    pub cutbacks: u32,
    /// Newton iterations of each converged step.
    pub newton_per_step: Vec<u32>,
    /// Numeric factorizations of the canonical direct solver.
    #[serde(default)]
    pub factorizations: u64,
    /// Wall-clock seconds of each completed stage, for the run summary.
    #[serde(default)]
    pub stage_seconds: Vec<crate::io::summary::StageSeconds>,
}

/// Rank-local results in input order of the owned nodes and elements.
#[derive(Debug, Clone, Default)]
pub struct LocalResults {
    /// Owned nodes (input indices).
    pub nodes: Vec<u32>,
    /// Displacement of each owned node (m).
    pub displacement: Vec<[f64; 3]>,
    /// Reaction force of each owned node (N), zero where no component is fixed.
    pub reaction: Vec<[f64; 3]>,
    /// Owned elements (input indices).
    pub elements: Vec<u32>,
    /// Mean stress of each owned element (Pa, tension positive).
    pub stress: Vec<Stress6>,
    /// Mean strain of each owned element (engineering shear, tension positive).
    pub strain: Vec<Strain6>,
    /// Interface output of each owned element (zero for solid elements).
    pub interface: Vec<InterfaceElementOutput>,
    /// Mean local jump (δ_s, δ_a, δ_n) of each owned interface element since its placement (m;
    /// zero for solid elements), spec (E4), (E9).
    pub jump: Vec<[f64; 3]>,
}

/// The elements of one block on this rank with their model and states.
#[derive(Debug, Clone)]
pub enum BlockStates {
    /// Hexahedra with a solid model.
    Solid(SolidBlock),
    /// Zero-thickness interface or joint elements with an interface law.
    Interface(InterfaceElements),
}

impl BlockStates {
    fn symmetric_tangent(&self) -> bool {
        match self {
            BlockStates::Solid(b) => b.symmetric_tangent(),
            BlockStates::Interface(b) => b.symmetric_tangent(),
        }
    }
    fn commit(&mut self) {
        match self {
            BlockStates::Solid(b) => b.commit(),
            BlockStates::Interface(b) => b.commit(),
        }
    }
    fn revert(&mut self) {
        match self {
            BlockStates::Solid(b) => b.revert(),
            BlockStates::Interface(b) => b.revert(),
        }
    }
}

/// Counts of interface points in the committed state (all ranks).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct InterfaceCounts {
    /// Interface and joint points of placed elements.
    pub points: u64,
    /// Points that are open.
    pub open: u64,
    /// Points on the plastic (slipping) branch.
    pub slipping: u64,
}

/// The static problem on this rank: discretization, PETSc objects and material states.
pub struct StaticProblem<'a> {
    scene: &'a Scene,
    disc: Discretization,
    blocks: Vec<BlockStates>,
    /// Geometry of every owned interface element (`None` for solid elements).
    iface_geo: Vec<Option<Interface8Geometry>>,
    /// For every owned element: (block, index within the block's owned elements).
    elem_block: Vec<(usize, usize)>,
    /// Fixed DOFs owned by this rank: (global dof, prescribed value).
    fixed: Vec<(i32, f64)>,
    k: Matrix,
    u: Vector,
    u_committed: Vector,
    gather: Gather,
    gather_committed: Gather,
    /// The nonlinear solver (taken out while it runs a step).
    snes: Option<Snes>,
    /// Diagonal value put on Dirichlet rows: the mean diagonal of the stiffness (same on every
    /// rank), so the constrained rows do not spoil the multigrid smoothers' scaling.
    dirichlet_diag: f64,
    /// The scene's displacement conditions on owned DOFs: (global dof, prescribed value).
    scene_fixed: Vec<(i32, f64)>,
    /// Values of the fixed DOFs at the start of the stage (same order as `fixed`).
    fixed_start: Vec<f64>,
    /// Whether each block is placed (same on every rank).
    active_block: Vec<bool>,
    /// Whether each node belongs to a placed element (same on every rank).
    node_active: Vec<bool>,
    /// Displacement of each owned element's nodes when it was placed: strains count from there.
    elem_ref: Vec<Vector24>,
    /// Per owned node: displacement at the end of the stage that placed it; reported
    /// displacements count from there (the surface of a new lift starts at zero).
    node_offset: Vec<[f64; 3]>,
    /// Per owned node: whether it is part of a placed element already at the start of the stage.
    node_was_active: Vec<bool>,
    /// Displacement of the owned DOFs at the start of the stage (for step checkpoints: the
    /// fixed DOFs' start values are recomputed from it on a restart within the stage).
    u_stage_start: Vec<f64>,
    /// Index of the current stage in `scene.stages`.
    stage: usize,
    /// External force at the end of the previous stage.
    f_prev: Vector,
}

/// Cells (8 nodes each) of a mesh, for partitioning and indexing.
pub fn mesh_cells(mesh: &Mesh) -> Cells {
    let mut cells = Cells::default();
    for e in &mesh.elements {
        cells.push(&e.nodes);
    }
    cells
}

impl<'a> StaticProblem<'a> {
    /// Sets up the rank-local problem for a given element partition.
    pub fn new(
        petsc: &Petsc,
        scene: &'a Scene,
        cells: Cells,
        disc: Discretization,
    ) -> Result<Self, SolveError> {
        let mesh = &scene.mesh;
        let n_nodes = mesh.num_nodes();
        // blocks and the block-local numbering of owned elements
        let mut per_block = vec![0usize; mesh.blocks.len()];
        let elem_block: Vec<(usize, usize)> = disc
            .elements
            .iter()
            .map(|&e| {
                let b = mesh.elements[e as usize].block as usize;
                per_block[b] += 1;
                (b, per_block[b] - 1)
            })
            .collect();
        let blocks = scene
            .block_materials
            .iter()
            .zip(&scene.block_interface)
            .zip(&per_block)
            .map(|((m, ib), &n)| match (m, ib) {
                (BlockMaterial::Solid(p), _) => SolidBlock::new(p, n).map(BlockStates::Solid),
                (BlockMaterial::Interface(p), Some(ib)) => {
                    InterfaceElements::new(p, n, ib.initial_normal_stress).map(BlockStates::Interface)
                }
                (BlockMaterial::Interface(p), None) => {
                    InterfaceElements::new(p, n, 0.0).map(BlockStates::Interface)
                }
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| SolveError::Material {
                element: 0,
                reason: e.reason,
            })?;
        let mut iface_geo = Vec::with_capacity(disc.elements.len());
        for &e in &disc.elements {
            let el = &mesh.elements[e as usize];
            iface_geo.push(match &scene.block_interface[el.block as usize] {
                None => None,
                Some(ib) => Some(
                    Interface8Geometry::new(
                        &mesh.element_coords(e as usize),
                        &ib.orientation,
                        &FrameAxes::default(),
                        ib.rule,
                    )
                    .map_err(|_| SolveError::Geometry { element: el.id })?,
                ),
            });
        }

        // the scene's displacement conditions on owned DOFs; nodes outside the placed elements
        // are added per stage (begin_stage)
        let me = disc.rank as u32;
        let scene_fixed: Vec<(i32, f64)> = scene
            .fixed
            .iter()
            .filter(|(n, _, _)| disc.partition.node_owner[*n as usize] == me)
            .map(|&(n, c, v)| (disc.dof(n, c as usize), v))
            .collect();

        let (d_nnz, o_nnz) = disc.preallocation(&cells, n_nodes);
        let mut k = Matrix::aij(petsc, disc.n_owned_dofs, 3, &d_nnz, &o_nnz)?;
        let u = Vector::mpi(petsc, disc.n_owned_dofs, 3)?;
        let mut coords = u.duplicate()?;
        coords.write(|c| {
            for (i, &n) in disc.owned_nodes.iter().enumerate() {
                c[3 * i..3 * i + 3].copy_from_slice(&mesh.coords[n as usize]);
            }
        })?;
        k.set_rigid_body_near_null_space(&coords)?;
        // the full pattern once: every element, placed or not yet, and every diagonal block, so
        // that placing blocks later never needs a new nonzero (zero entries stay in the pattern);
        // only owned rows, as in every assembly (module docs of `discretization`)
        let zeros = vec![0.0f64; 576];
        let disc_ref = &disc;
        for &e in &disc.elements {
            let cols: Vec<i32> = mesh.elements[e as usize]
                .nodes
                .iter()
                .flat_map(|&n| (0..3).map(move |c| disc_ref.dof(n, c)))
                .collect();
            let rows: Vec<i32> = cols.iter().copied().filter(|&d| disc.owns_dof(d)).collect();
            k.add_values(&rows, &cols, &zeros[..24 * rows.len()])?;
        }
        for &n in &disc.owned_nodes {
            let d = [disc.dof(n, 0), disc.dof(n, 1), disc.dof(n, 2)];
            k.add_values(&d, &d, &zeros[..9])?;
        }
        k.assemble()?;
        let mut u = u;
        u.set_all(0.0)?;
        let mut u_committed = u.duplicate()?;
        u_committed.set_all(0.0)?;
        let gather = Gather::new(&u, &disc.local_dofs)?;
        let gather_committed = Gather::new(&u, &disc.local_dofs)?;
        // the non-associated GP models have non-symmetric tangents: CG only when all are symmetric
        let symmetric = blocks.iter().all(BlockStates::symmetric_tangent);
        // options (scene and command line) are applied here, so a bad one is an input error
        let canonical = match scene.file.solver.linear_solver {
            LinearSolver::Iterative => None,
            LinearSolver::CanonicalLu => Some(CanonicalSettings {
                dofs: disc.canonical_dofs(),
                reuse_factorization: scene.file.solver.reuse_factorization,
            }),
        };
        let snes = Snes::new(
            petsc,
            scene.file.solver.newton_max_iterations,
            scene.file.solver.rtol,
            scene.file.solver.max_iterations,
            symmetric,
            canonical,
        )?;
        let mut f_prev = u.duplicate()?;
        f_prev.set_all(0.0)?;
        let n_elements = disc.elements.len();
        let n_owned_nodes = disc.owned_nodes.len();
        Ok(StaticProblem {
            scene,
            disc,
            blocks,
            iface_geo,
            elem_block,
            fixed: Vec::new(),
            scene_fixed,
            fixed_start: Vec::new(),
            active_block: vec![false; mesh.blocks.len()],
            node_active: vec![false; n_nodes],
            elem_ref: vec![Vector24::zeros(); n_elements],
            node_offset: vec![[0.0; 3]; n_owned_nodes],
            node_was_active: vec![false; n_owned_nodes],
            u_stage_start: Vec::new(),
            stage: 0,
            f_prev,
            k,
            u,
            u_committed,
            gather,
            gather_committed,
            snes: Some(snes),
            dirichlet_diag: 1.0,
        })
    }

    /// The rank-local indexing.
    pub fn discretization(&self) -> &Discretization {
        &self.disc
    }

    /// The state a checkpoint stores, in this rank's owned order ([`super::checkpoint`]): with
    /// `within: None` at the end of the current stage (after [`StaticProblem::end_stage`]),
    /// everything [`StaticProblem::begin_stage`] of the next stage and the solve need; with
    /// `Some(path)` after a converged load step inside the stage, also what
    /// [`StaticProblem::resume_stage`] needs to continue the stage from `path`.
    pub(crate) fn save_state(&self, within: Option<LoadPath>) -> Result<ProblemState, SolveError> {
        let mut element_states = Vec::with_capacity(self.disc.owned_elements.len());
        for (i, &(b, be)) in self.elem_block.iter().enumerate() {
            if !self.disc.element_owned[i] {
                continue;
            }
            let encoded = match &self.blocks[b] {
                BlockStates::Solid(block) => state_codec::encode_solid(block, be),
                BlockStates::Interface(block) => state_codec::encode_interface(block, be),
            };
            element_states.push(encoded.map_err(|reason| SolveError::Material {
                element: self.scene.mesh.elements[self.disc.elements[i] as usize].id,
                reason,
            })?);
        }
        let in_stage = within.map(|path| StageProgress {
            path,
            u_stage_start: self.u_stage_start.clone(),
            node_was_active: self.node_was_active.clone(),
        });
        Ok(ProblemState {
            stages_done: if within.is_some() {
                self.stage
            } else {
                self.stage + 1
            },
            in_stage,
            active_block: self.active_block.clone(),
            node_active: self.node_active.clone(),
            u: self.u_committed.read(|s| s.to_vec())?,
            f_prev: self.f_prev.read(|s| s.to_vec())?,
            node_offset: self.node_offset.clone(),
            elem_ref: self
                .elem_ref
                .iter()
                .zip(&self.disc.element_owned)
                .filter(|(_, &owned)| owned)
                .map(|(v, _)| std::array::from_fn(|k| v[k]))
                .collect(),
            element_states,
        })
    }

    /// Restores a state saved by [`StaticProblem::save_state`] (possibly under another
    /// partition: the caller maps it to this rank's owned nodes and evaluated elements,
    /// [`Discretization::elements`]). The next call is
    /// [`StaticProblem::begin_stage`] of stage `state.stages_done`, or
    /// [`StaticProblem::resume_stage`] for a state saved within that stage. Local; fails on wrong lengths
    /// or states that do not decode for the block's model (naming the element).
    pub(crate) fn restore_state(&mut self, state: &ProblemState) -> Result<(), String> {
        let (nn, ne) = (self.disc.owned_nodes.len(), self.disc.elements.len());
        let lens = [
            ("active blocks", state.active_block.len(), self.active_block.len()),
            ("node flags", state.node_active.len(), self.node_active.len()),
            ("displacements", state.u.len(), 3 * nn),
            ("previous loads", state.f_prev.len(), 3 * nn),
            ("node offsets", state.node_offset.len(), nn),
            ("element references", state.elem_ref.len(), ne),
            ("element states", state.element_states.len(), ne),
        ];
        if let Some((what, got, want)) = lens.iter().find(|(_, got, want)| got != want) {
            return Err(format!("{what}: {got} values, this problem has {want}"));
        }
        if let Some(p) = &state.in_stage {
            if p.u_stage_start.len() != 3 * nn || p.node_was_active.len() != nn {
                return Err("the stage's start values do not fit this problem".into());
            }
        }
        let first = usize::from(state.in_stage.is_none());
        if state.stages_done < first || state.stages_done > self.scene.stages.len() {
            return Err(format!(
                "{} completed stage(s), the scene has {}",
                state.stages_done,
                self.scene.stages.len()
            ));
        }
        for (i, &(b, be)) in self.elem_block.iter().enumerate() {
            let bytes = &state.element_states[i];
            let decoded = match &mut self.blocks[b] {
                BlockStates::Solid(block) => state_codec::decode_solid(block, be, bytes),
                BlockStates::Interface(block) => state_codec::decode_interface(block, be, bytes),
            };
            decoded.map_err(|m| {
                format!(
                    "element {}: {m}",
                    self.scene.mesh.elements[self.disc.elements[i] as usize].id
                )
            })?;
        }
        self.stage = state.stages_done.saturating_sub(first);
        self.active_block.clone_from(&state.active_block);
        self.node_active.clone_from(&state.node_active);
        self.node_offset.clone_from(&state.node_offset);
        self.elem_ref = state
            .elem_ref
            .iter()
            .map(|r| Vector24::from_column_slice(r))
            .collect();
        let petsc = |e: crate::linalg::petsc::PetscError| e.to_string();
        self.u.write(|s| s.copy_from_slice(&state.u)).map_err(petsc)?;
        self.u_committed.copy_from(&self.u).map_err(petsc)?;
        self.f_prev
            .write(|s| s.copy_from_slice(&state.f_prev))
            .map_err(petsc)?;
        Ok(())
    }

    /// Starts stage `k` of the scene: places its blocks (strain-free: their states start from
    /// the initial state and their strains count from the current displacement) and fixes, at
    /// their current displacement, the nodes that no placed element touches yet.
    pub fn begin_stage(&mut self, k: usize) -> Result<(), SolveError> {
        let mesh = &self.scene.mesh;
        self.stage = k;
        for (i, &n) in self.disc.owned_nodes.iter().enumerate() {
            self.node_was_active[i] = self.node_active[n as usize];
        }
        let newly: Vec<bool> = {
            let mut v = vec![false; mesh.blocks.len()];
            for &b in &self.scene.stages[k].activate {
                v[b as usize] = !self.active_block[b as usize];
                self.active_block[b as usize] = true;
            }
            v
        };
        for e in &mesh.elements {
            if self.active_block[e.block as usize] {
                for &n in &e.nodes {
                    self.node_active[n as usize] = true;
                }
            }
        }
        let u_loc: Vec<f64> = self.gather.gather(&self.u)?.read(|s| s.to_vec())?;
        for (i, &e) in self.disc.elements.iter().enumerate() {
            if newly[mesh.elements[e as usize].block as usize] {
                let loc = &self.disc.element_local[i];
                self.elem_ref[i] = Vector24::from_fn(|r, _| u_loc[3 * loc[r / 3] as usize + r % 3]);
            }
        }
        self.u_stage_start = self.u.read(|s| s.to_vec())?;
        self.fix_for_stage()
    }

    /// Continues the stage in progress of a step checkpoint, once the problem's state is
    /// restored from it ([`super::checkpoint::restore`] calls this): the fixed DOFs and their
    /// start values from the stored start of the stage, and a fresh preconditioner, as the
    /// uninterrupted run has after writing that checkpoint. Collective.
    pub fn resume_stage(&mut self, progress: &StageProgress) -> Result<(), SolveError> {
        self.node_was_active.clone_from(&progress.node_was_active);
        self.u_stage_start.clone_from(&progress.u_stage_start);
        self.fix_for_stage()
    }

    /// A fresh preconditioner (after a step checkpoint: the steps that follow do not depend on
    /// the factors of the steps before it, so a restart from it repeats them exactly).
    /// Collective.
    pub fn fresh_preconditioner(&mut self) -> Result<(), SolveError> {
        self.snes
            .as_mut()
            .expect("the nonlinear solver is in place between steps")
            .reset()?;
        Ok(())
    }

    /// The fixed DOFs of the current stage: the scene's conditions and the nodes not yet placed
    /// (held at their displacement at the stage's start), with their start values from
    /// `u_stage_start`; then a fresh preconditioner. Collective.
    fn fix_for_stage(&mut self) -> Result<(), SolveError> {
        let lo = self.disc.dof_lo;
        let u_own = &self.u_stage_start;
        // the nodes not yet placed are held where they are; that replaces any scene constraint
        let mut held: Vec<(i32, f64)> = Vec::new();
        for &n in &self.disc.owned_nodes {
            if !self.node_active[n as usize] {
                for c in 0..3 {
                    let d = self.disc.dof(n, c);
                    held.push((d, u_own[d as usize - lo]));
                }
            }
        }
        held.sort_by_key(|f| f.0);
        let mut fixed: Vec<(i32, f64)> = self
            .scene_fixed
            .iter()
            .copied()
            .filter(|f| held.binary_search_by_key(&f.0, |h| h.0).is_err())
            .collect();
        fixed.extend(held);
        fixed.sort_by_key(|f| f.0);
        fixed.dedup_by_key(|f| f.0);
        self.fixed_start = fixed.iter().map(|&(d, _)| u_own[d as usize - lo]).collect();
        self.fixed = fixed;
        // a fresh preconditioner per stage: the stage's solves do not depend on earlier
        // stages, so a restart from the checkpoint of previous stage repeats them exactly
        self.fresh_preconditioner()
    }

    /// Ends the current stage: its loads become the starting loads of the next one, and the
    /// nodes it placed get their current displacement as the zero of their reported
    /// displacement (a new lift's surface starts level; settlement counts from its placement).
    pub fn end_stage(&mut self) -> Result<(), SolveError> {
        let mut f = self.u.duplicate()?;
        self.external_force(1.0, &mut f)?;
        self.f_prev.copy_from(&f)?;
        let u_own: Vec<f64> = self.u.read(|s| s.to_vec())?;
        let staged = !self.scene.file.stages.is_empty();
        let reset = staged && self.scene.file.output.placed_nodes == PlacedNodes::EndOfStage;
        for (i, &n) in self.disc.owned_nodes.iter().enumerate() {
            if reset && self.node_active[n as usize] && !self.node_was_active[i] {
                self.node_offset[i] = [u_own[3 * i], u_own[3 * i + 1], u_own[3 * i + 2]];
            }
        }
        Ok(())
    }

    /// External force at load factor `lambda` of the current stage:
    /// f = f_prev + λ (f_stage − f_prev), with f_stage the stage's terms on the placed elements.
    fn external_force(&self, lambda: f64, f: &mut Vector) -> Result<(), SolveError> {
        let mesh = &self.scene.mesh;
        f.set_all(0.0)?;
        // placed elements this rank evaluates; terms add to owned rows only, in the scene's
        // fixed order (rank-count independent, see `discretization`)
        let mut placed = vec![false; mesh.elements.len()];
        for &e in &self.disc.elements {
            placed[e as usize] = self.active_block[mesh.elements[e as usize].block as usize];
        }
        let add = |e: usize, fe: &Vector24, f: &mut Vector| -> Result<(), SolveError> {
            add_owned_rows(&self.disc, f, &self.element_dofs(e), fe.as_slice())
        };
        for term in &self.scene.stages[self.stage].terms {
            match term {
                Term::Gravity { g } => {
                    for &e in &self.disc.elements {
                        let e = e as usize;
                        if !placed[e] || mesh.is_interface(e) {
                            continue;
                        }
                        let rho = self.scene.block_materials[mesh.elements[e].block as usize].density();
                        add(e, &gravity_load(&mesh.element_coords(e), rho, g), f)?;
                    }
                }
                Term::Pressure { faces, value } => {
                    for face in &mesh.face_sets[faces] {
                        if placed[face.element as usize] {
                            let e = face.element as usize;
                            let fe = face_pressure_load(
                                &mesh.element_coords(e),
                                face.local_face as usize,
                                &[*value; 4],
                            );
                            add(e, &fe, f)?;
                        }
                    }
                }
                Term::Hydrostatic {
                    faces,
                    level,
                    unit_weight,
                } => {
                    for face in &mesh.face_sets[faces] {
                        if placed[face.element as usize] {
                            let e = face.element as usize;
                            let p = face
                                .nodes
                                .map(|n| unit_weight * (level - mesh.coords[n as usize][2]).max(0.0));
                            let fe =
                                face_pressure_load(&mesh.element_coords(e), face.local_face as usize, &p);
                            add(e, &fe, f)?;
                        }
                    }
                }
            }
        }
        f.assemble()?;
        // f ← λ f_stage + (1 − λ) f_prev
        f.write(|s| s.iter_mut().for_each(|v| *v *= lambda))?;
        f.axpy(1.0 - lambda, &self.f_prev)?;
        Ok(())
    }

    /// Global DOFs of the 8 nodes of element `e` (input index), node-major.
    fn element_dofs(&self, e: usize) -> Vec<i32> {
        self.scene.mesh.elements[e]
            .nodes
            .iter()
            .flat_map(|&n| (0..3).map(move |c| (n, c)))
            .map(|(n, c)| self.disc.dof(n, c))
            .collect()
    }

    /// Adds to `f` the forces f₀ = ∫ Bᵀσ₀ dV of the placement stress σ₀ of every placed solid
    /// element (spec §8.6 item 1: a rockfill point is placed at p_min·I, not at zero stress).
    ///
    /// σ₀ is uniform, so f₀ vanishes inside a lift and is a pressure p_min on its free faces.
    /// Without f₀ that pressure is unbalanced: the faces of every new lift expand to shed it,
    /// the points at the crest edges drop to p ≈ p_min/3, next to the tension cut-off
    /// p_t = 0.2·p_min, and Newton chatters as they cross it and are reset to p_min·I.
    /// With f₀ a lift is in equilibrium at σ₀ before its own weight acts, and the stress change
    /// Δσ = σ − σ₀ balances the real loads alone.
    fn add_placement_force(&self, f: &mut Vector) -> Result<(), SolveError> {
        let mesh = &self.scene.mesh;
        let mut f0 = f.duplicate()?;
        f0.set_all(0.0)?;
        for (i, &e) in self.disc.elements.iter().enumerate() {
            let (b, _) = self.elem_block[i];
            let BlockStates::Solid(block) = &self.blocks[b] else {
                continue;
            };
            if !self.active_block[b] {
                continue;
            }
            let e = e as usize;
            let geo = Hex8Geometry::new(&mesh.element_coords(e)).map_err(|_| SolveError::Geometry {
                element: mesh.elements[e].id,
            })?;
            add_owned_rows(
                &self.disc,
                &mut f0,
                &self.element_dofs(e),
                block.placement_force(&geo).as_slice(),
            )?;
        }
        f0.assemble()?;
        f.axpy(1.0, &f0)?;
        Ok(())
    }

    /// Updates the trial states for the current `u` and assembles f_int and (optionally) K.
    fn assemble(&mut self, f_int: &mut Vector, want_k: bool) -> Result<(), SolveError> {
        self.assemble_with(f_int, want_k, false)
    }

    /// [`StaticProblem::assemble`]; with `trial_is_current` the solid trial states are known to
    /// be those of the current `u` (the last evaluation was there), so f_int and K of the solid
    /// elements come from them and their stored tangents without a second integration (the
    /// same values, since an update is a pure function of the committed state and the
    /// increment).
    fn assemble_with(
        &mut self,
        f_int: &mut Vector,
        want_k: bool,
        trial_is_current: bool,
    ) -> Result<(), SolveError> {
        let mesh = &self.scene.mesh;
        let u_loc: Vec<f64> = self.gather.gather(&self.u)?.read(|s| s.to_vec())?;
        let u0_loc: Vec<f64> = self
            .gather_committed
            .gather(&self.u_committed)?
            .read(|s| s.to_vec())?;
        f_int.set_all(0.0)?;
        if want_k {
            self.k.zero()?;
        }
        let mut rows = [0i32; 24];
        let mut kt = [0.0f64; 576];
        // stiffness diagonals of the owned elements, for the Dirichlet scaling (an exact sum:
        // the same at any rank count)
        let mut diagonals: Vec<f64> = Vec::new();
        // the element loop stops at the first local failure, but the collective assembly calls
        // below run on every rank whatever happened here (no rank may skip a collective)
        let mut local = Ok(());
        for (i, &e) in self.disc.elements.iter().enumerate() {
            let e = e as usize;
            let (b, be) = self.elem_block[i];
            if !self.active_block[b] {
                continue;
            }
            let loc = &self.disc.element_local[i];
            let mut d_u = Vector24::zeros();
            for a in 0..8 {
                for c in 0..3 {
                    let l = 3 * loc[a] as usize + c;
                    d_u[3 * a + c] = u_loc[l] - u0_loc[l];
                    rows[3 * a + c] = self.disc.local_dofs[l];
                }
            }
            let evaluated = match &mut self.blocks[b] {
                BlockStates::Solid(block) => {
                    let Ok(geo) = Hex8Geometry::new(&mesh.element_coords(e)) else {
                        local = Err(SolveError::Geometry {
                            element: mesh.elements[e].id,
                        });
                        break;
                    };
                    if trial_is_current {
                        let r = block.evaluate_trial(be, &geo);
                        Ok((r.f_int, r.k.filter(|_| want_k)))
                    } else {
                        block.evaluate(be, &geo, &d_u, want_k).map(|r| (r.f_int, r.k))
                    }
                }
                BlockStates::Interface(block) => {
                    let geo = self.iface_geo[i]
                        .as_ref()
                        .expect("interface geometry built at set-up");
                    block.evaluate(be, geo, &d_u, want_k).map(|r| (r.f_int, r.k))
                }
            };
            let (fe, ke) = match evaluated {
                Ok(r) => r,
                Err(m) => {
                    local = Err(SolveError::Material {
                        element: mesh.elements[e].id,
                        reason: m.reason,
                    });
                    break;
                }
            };
            add_owned_rows(&self.disc, f_int, &rows, fe.as_slice())?;
            if let Some(ke) = ke {
                if self.disc.element_owned[i] {
                    diagonals.extend(ke.diagonal().iter().map(|v| v.abs()));
                }
                // the owned rows, row-major (nalgebra is column-major)
                let mut owned_rows = [0i32; 24];
                let mut m = 0;
                for (r, &d) in rows.iter().enumerate() {
                    if self.disc.owns_dof(d) {
                        owned_rows[m] = d;
                        for c in 0..24 {
                            kt[24 * m + c] = ke[(r, c)];
                        }
                        m += 1;
                    }
                }
                if m > 0 {
                    self.k.add_values(&owned_rows[..m], &rows, &kt[..24 * m])?;
                }
            }
        }
        f_int.assemble()?;
        if want_k {
            self.k.assemble()?;
            let world = SimpleCommunicator::world();
            let n = sum_u64(&world, diagonals.len() as u64);
            let s = exact_sum(&world, diagonals.iter().copied());
            self.dirichlet_diag = if n > 0 && s > 0.0 { s / n as f64 } else { 1.0 };
        }
        local
    }

    /// One converged load step along `path` (a stage applies its loads in `n_steps` equal
    /// increments of λ from the committed state to 1; the caller advances until
    /// [`LoadPath::done`]): a failed increment is cut in half (at most `max_cutbacks` times in a row) and grown
    /// back after two successes. Every decision is collective, so all ranks take the same path.
    pub fn advance(
        &mut self,
        path: &mut LoadPath,
        n_steps: u32,
        max_cutbacks: u32,
        report: &mut SolveReport,
    ) -> Result<(), SolveError> {
        let base = 1.0 / n_steps.max(1) as f64;
        let mut cuts = 0u32;
        loop {
            let next = if path.lambda + path.d_lambda > 1.0 - 1e-12 {
                1.0
            } else {
                path.lambda + path.d_lambda
            };
            let before = report.newton_iterations;
            match self.solve_step(next, report) {
                Ok(()) => {
                    path.lambda = next;
                    report.steps += 1;
                    report.newton_per_step.push(report.newton_iterations - before);
                    path.streak += 1;
                    if path.streak >= 2 && path.d_lambda < base {
                        path.d_lambda = (2.0 * path.d_lambda).min(base);
                        path.streak = 0;
                    }
                    return Ok(());
                }
                Err(e) if e.recoverable() && cuts < max_cutbacks => {
                    if self.scene.file.solver.monitor && SimpleCommunicator::world().rank() == 0 {
                        eprintln!("step to λ = {next:.6} cut back: {e}");
                    }
                    cuts += 1;
                    report.cutbacks += 1;
                    path.d_lambda *= 0.5;
                    path.streak = 0;
                }
                Err(e) => {
                    return Err(SolveError::Step {
                        from: path.lambda,
                        to: next,
                        cutbacks: cuts,
                        source: Box::new(e),
                    });
                }
            }
        }
    }

    /// Returns to the committed state (after a failed step).
    fn revert(&mut self) -> Result<(), SolveError> {
        for b in &mut self.blocks {
            b.revert();
        }
        self.u.copy_from(&self.u_committed)?;
        Ok(())
    }

    /// Solves one load step to equilibrium at load factor `lambda` (loads and prescribed
    /// displacements scaled by it) and commits the states. On failure the problem is back at
    /// its committed state.
    pub fn solve_step(&mut self, lambda: f64, report: &mut SolveReport) -> Result<(), SolveError> {
        let r = self.newton(lambda, report);
        if r.is_err() {
            self.revert()?;
        }
        r
    }

    /// Newton's method with a line search on PETSc's SNES for the load factor `lambda`
    /// (residual and Jacobian from [`StaticProblem::assemble`], convergence test on the relative
    /// residual ‖f_ext − f_int‖ / max(‖f_ext‖, ‖f_int‖) over the free DOFs; see [`NewtonStep`]).
    /// Commits the states on convergence.
    fn newton(&mut self, lambda: f64, report: &mut SolveReport) -> Result<(), SolveError> {
        let mut f_ext = self.u.duplicate()?;
        self.external_force(lambda, &mut f_ext)?;
        self.add_placement_force(&mut f_ext)?;
        let lo = self.disc.dof_lo;
        let targets: Vec<(usize, f64)> = self
            .fixed
            .iter()
            .zip(&self.fixed_start)
            .map(|(&(d, v), &v0)| (d as usize - lo, v0 + lambda * (v - v0)))
            .collect();
        let rows: Vec<i32> = self.fixed.iter().map(|f| f.0).collect();
        // initial guess: the committed state with the prescribed values of this step
        let mut x = self.u.duplicate()?;
        x.copy_from(&self.u_committed)?;
        x.write(|s| {
            for &(l, v) in &targets {
                s[l] = v;
            }
        })?;
        let mut r = self.u.duplicate()?;
        let f_int = self.u.duplicate()?;
        let f_last = Some(self.u.duplicate()?);
        let t0 = Instant::now();
        let mut snes = self
            .snes
            .take()
            .expect("the nonlinear solver is in place between steps");
        let mut step = NewtonStep {
            problem: self,
            f_ext,
            f_int,
            targets,
            rows,
            lambda,
            ref_norm: 1e-300,
            residual_norm: f64::NAN,
            residual_at: None,
            f_last,
            failure: None,
            report,
            assembly_seconds: 0.0,
            last_linear_iterations: 0,
        };
        let solved = snes.solve(&mut step, &mut r, &mut x);
        let NewtonStep {
            problem,
            failure,
            report,
            assembly_seconds,
            last_linear_iterations,
            f_ext,
            f_int,
            targets,
            ..
        } = step;
        report.factorizations += snes.take_factorizations();
        problem.snes = Some(snes);
        report.solve_seconds += (t0.elapsed().as_secs_f64() - assembly_seconds).max(0.0);
        let (outcome, iterations) = solved?;
        let residual = report.residuals.last().copied().unwrap_or(f64::NAN);
        match outcome {
            SnesOutcome::Converged => {
                // the states must be those of the solution: re-evaluate if the last residual
                // was not at x (collective)
                let same = problem.u.read(|u| x.read(|s| u == s))??;
                if any_true(&SimpleCommunicator::world(), !same) {
                    problem.u.copy_from(&x)?;
                    let mut f = problem.u.duplicate()?;
                    let assembled = problem.assemble(&mut f, false);
                    any_error(&SimpleCommunicator::world(), assembled).map_err(SolveError::Collective)?;
                }
                report.newton_iterations += iterations;
                for b in &mut problem.blocks {
                    b.commit();
                }
                problem.u_committed.copy_from(&problem.u)?;
                Ok(())
            }
            SnesOutcome::DomainError => Err(SolveError::Collective(
                failure.unwrap_or_else(|| "the residual could not be evaluated".into()),
            )),
            SnesOutcome::LinearSolve(reason) => Err(SolveError::Linear {
                reason,
                iterations: last_linear_iterations,
            }),
            SnesOutcome::LineSearch => Err(SolveError::LineSearch {
                iterations,
                residual,
                worst: problem.worst_node(&f_int, &f_ext, &targets)?,
            }),
            SnesOutcome::Diverged(_) => Err(SolveError::Newton {
                iterations,
                residual,
                worst: problem.worst_node(&f_int, &f_ext, &targets)?,
                hint: problem.stall_hint(residual),
            }),
        }
    }

    /// A hint for a Newton solve that ended at `residual` (relative) without converging: when
    /// the largest substepping tolerance STOL of the scene's GP materials lies above
    /// `newton_tol` and the residual within a decade of it, the residual may be the noise of
    /// the stress integration (spec §8.2; `solver.integration_tol_ratio`). Empty otherwise.
    fn stall_hint(&self, residual: f64) -> String {
        let tol = self.scene.file.solver.newton_tol;
        let stol = self
            .scene
            .block_materials
            .iter()
            .filter_map(|m| m.gp_integration().map(|o| o.stol))
            .reduce(f64::max);
        match stol {
            Some(stol) if stol > tol && residual < 10.0 * stol => format!(
                "; the residual is within a decade of the GP substepping tolerance STOL = {stol:.1e}, \
                 which lies above newton_tol = {tol:.1e}: Newton may be stalled at the integration \
                 noise (cap STOL with `solver.integration_tol_ratio: 0.1` or `cfrd run \
                 --integration-tol-ratio 0.1`)"
            ),
            _ => String::new(),
        }
    }

    /// Names the node where the out-of-balance force f_int − f_ext of the last evaluated
    /// iterate is largest (free components only), with its coordinates and the placed blocks
    /// around it, for the report of a failed step (collective). Non-finite forces are skipped.
    fn worst_node(
        &self,
        f_int: &Vector,
        f_ext: &Vector,
        targets: &[(usize, f64)],
    ) -> Result<String, SolveError> {
        let mut r: Vec<f64> =
            f_int.read(|a| f_ext.read(|b| a.iter().zip(b).map(|(p, q)| p - q).collect()))??;
        for &(l, _) in targets {
            r[l] = 0.0;
        }
        let (mut best, mut node) = (-1.0f64, 0usize);
        for (i, &n) in self.disc.owned_nodes.iter().enumerate() {
            let v = (r[3 * i].powi(2) + r[3 * i + 1].powi(2) + r[3 * i + 2].powi(2)).sqrt();
            if v > best {
                (best, node) = (v, n as usize);
            }
        }
        let world = SimpleCommunicator::world();
        let top = max_f64(&world, best);
        let holder = if best == top { world.rank() } else { i32::MAX };
        let mut root = i32::MAX;
        world.all_reduce_into(&holder, &mut root, SystemOperation::min());
        let mesh = &self.scene.mesh;
        if top < 0.0 {
            return Ok("no node has a finite out-of-balance force".into());
        }
        let mut msg: Vec<u8> = if world.rank() == root {
            let mut blocks: Vec<&str> = mesh
                .elements
                .iter()
                .filter(|el| self.active_block[el.block as usize] && el.nodes.contains(&(node as u32)))
                .map(|el| mesh.blocks[el.block as usize].name.as_str())
                .collect();
            blocks.sort_unstable();
            blocks.dedup();
            let [x, y, z] = mesh.coords[node];
            format!(
                "largest out-of-balance force {top:.3e} N at node {} ({x:.2}, {y:.2}, {z:.2}) in {}",
                mesh.node_ids[node],
                blocks.join(", ")
            )
            .into_bytes()
        } else {
            Vec::new()
        };
        broadcast_vec(&world, root, &mut msg);
        Ok(String::from_utf8_lossy(&msg).into_owned())
    }

    /// Counts the interface points of placed elements that are open or slipping in the
    /// committed state, over all ranks (collective).
    pub fn interface_counts(&self) -> InterfaceCounts {
        let (mut points, mut open, mut slipping) = (0u64, 0u64, 0u64);
        for (i, &(b, be)) in self.elem_block.iter().enumerate() {
            if let (true, BlockStates::Interface(block), Some(geo)) = (
                self.active_block[b] && self.disc.element_owned[i],
                &self.blocks[b],
                &self.iface_geo[i],
            ) {
                let o = block.output(be);
                points += geo.area_w.len() as u64;
                open += o.open_points as u64;
                slipping += o.plastic_points as u64;
            }
        }
        let world = SimpleCommunicator::world();
        InterfaceCounts {
            points: sum_u64(&world, points),
            open: sum_u64(&world, open),
            slipping: sum_u64(&world, slipping),
        }
    }

    /// Collects the rank-local results (owned nodes and elements) at the committed state.
    pub fn results(&mut self) -> Result<LocalResults, SolveError> {
        let mesh = &self.scene.mesh;
        let mut f_int = self.u.duplicate()?;
        self.assemble(&mut f_int, false)?;
        let mut f_ext = self.u.duplicate()?;
        self.external_force(1.0, &mut f_ext)?;
        self.add_placement_force(&mut f_ext)?;
        let mut reac = f_int;
        reac.axpy(-1.0, &f_ext)?;
        let reac_all: Vec<f64> = reac.read(|s| s.to_vec())?;
        let u_own: Vec<f64> = self.u.read(|s| s.to_vec())?;
        let lo = self.disc.dof_lo;
        let mut is_fixed = vec![false; self.disc.n_owned_dofs];
        for &(d, _) in &self.fixed {
            is_fixed[d as usize - lo] = true;
        }
        let mut out = LocalResults {
            nodes: self.disc.owned_nodes.clone(),
            ..Default::default()
        };
        for i in 0..self.disc.owned_nodes.len() {
            let o = self.node_offset[i];
            out.displacement.push([
                u_own[3 * i] - o[0],
                u_own[3 * i + 1] - o[1],
                u_own[3 * i + 2] - o[2],
            ]);
            out.reaction.push(std::array::from_fn(|c| {
                if is_fixed[3 * i + c] {
                    reac_all[3 * i + c]
                } else {
                    0.0
                }
            }));
        }
        let u_loc: Vec<f64> = self.gather.gather(&self.u)?.read(|s| s.to_vec())?;
        out.elements = self.disc.owned_elements.clone();
        for (i, &e) in self.disc.elements.iter().enumerate() {
            if !self.disc.element_owned[i] {
                continue;
            }
            let (b, be) = self.elem_block[i];
            let loc = &self.disc.element_local[i];
            let ue = Vector24::from_fn(|k, _| u_loc[3 * loc[k / 3] as usize + k % 3]) - self.elem_ref[i];
            let (mut strain, mut stress) = (Strain6::default(), Stress6::default());
            let (mut iface, mut jump) = (InterfaceElementOutput::default(), [0.0; 3]);
            match &self.blocks[b] {
                _ if !self.active_block[b] => {}
                BlockStates::Solid(block) => {
                    let geo = Hex8Geometry::new(&mesh.element_coords(e as usize)).map_err(|_| {
                        SolveError::Geometry {
                            element: mesh.elements[e as usize].id,
                        }
                    })?;
                    let eps = geo.strain_increments(&ue);
                    strain = eps
                        .iter()
                        .fold(Strain6::default(), |a, s| Strain6(a.0 + s.0 / 8.0));
                    stress = block.mean_stress(be);
                }
                BlockStates::Interface(block) => {
                    let geo = self.iface_geo[i]
                        .as_ref()
                        .expect("interface geometry built at set-up");
                    let w = 1.0 / geo.area_w.len() as f64;
                    for j in geo.jumps(&ue) {
                        for c in 0..3 {
                            jump[c] += w * j[c];
                        }
                    }
                    iface = block.output(be);
                }
            }
            out.strain.push(strain);
            out.stress.push(stress);
            out.interface.push(iface);
            out.jump.push(jump);
        }
        Ok(out)
    }
}

/// One load step's nonlinear problem as SNES sees it:
///
/// ```text
/// F(x) = f_int(x) − f_ext(λ)   on free DOFs,     F_i = d·(x_i − ū_i)   on fixed DOFs,
/// J(x) = K_t(x) with the fixed rows and columns replaced by d·I
/// ```
/// (d the mean stiffness diagonal, set by the last assembly of K). The initial guess already
/// holds the prescribed values ū, so the fixed entries of F stay zero and zeroing the fixed
/// columns of J is exact. Every evaluation integrates the materials from the committed states
/// with the step increment x − u_committed (spec §8.1); only the Jacobian assembles K (the line
/// search's residual evaluations do not pay for tangents).
struct NewtonStep<'s, 'a> {
    problem: &'s mut StaticProblem<'a>,
    f_ext: Vector,
    f_int: Vector,
    /// Fixed DOFs: (local index, prescribed value at this λ).
    targets: Vec<(usize, f64)>,
    /// Fixed DOFs (global rows).
    rows: Vec<i32>,
    lambda: f64,
    /// max(‖f_ext‖, ‖f_int‖) of the last residual evaluation.
    ref_norm: f64,
    /// ‖F‖ of the last residual evaluation (exact sum: the same at any rank count).
    residual_norm: f64,
    /// This rank's entries of the x of the last residual evaluation (`None`: it failed).
    residual_at: Option<Vec<f64>>,
    /// F of the last residual evaluation (at `residual_at`); `None` only while it is filled.
    f_last: Option<Vector>,
    /// Message of the last failed material update.
    failure: Option<String>,
    report: &'s mut SolveReport,
    assembly_seconds: f64,
    last_linear_iterations: u32,
}

impl NewtonStep<'_, '_> {
    /// Sets u = x and assembles f_int (and K if `want_k`) there; a material failure on any rank
    /// is reported on all (collective). With `trial_is_current` the solid trial states are
    /// already those of x ([`StaticProblem::assemble_with`]).
    fn evaluate_at(&mut self, x: &Vector, want_k: bool, trial_is_current: bool) -> Result<bool, PetscError> {
        if !trial_is_current {
            // the trial states move to x: they are no longer those of the last residual
            self.residual_at = None;
        }
        self.problem.u.copy_from(x)?;
        let t0 = Instant::now();
        let assembled = self
            .problem
            .assemble_with(&mut self.f_int, want_k, trial_is_current);
        let dt = t0.elapsed().as_secs_f64();
        self.report.assembly_seconds += dt;
        self.assembly_seconds += dt;
        match any_error(&SimpleCommunicator::world(), assembled) {
            Ok(()) => Ok(true),
            Err(m) => {
                self.failure = Some(m);
                Ok(false)
            }
        }
    }
}

impl NewtonStep<'_, '_> {
    /// Whether `x` is (on every rank) the iterate of the last successful residual evaluation,
    /// whose trial states and norm are still current. Collective.
    fn at_last_residual(&self, x: &Vector) -> Result<bool, PetscError> {
        let here = match &self.residual_at {
            Some(at) => x.read(|s| s == at.as_slice())?,
            None => false,
        };
        Ok(!any_true(&SimpleCommunicator::world(), !here))
    }

    /// F(x) into the kept vector of the last residual (see [`NewtonStep::evaluate_residual`]).
    fn evaluate_last(&mut self, x: &Vector) -> Result<bool, PetscError> {
        let mut f = self.f_last.take().expect("F of the last residual is kept");
        let ok = self.evaluate_residual(x, &mut f);
        self.f_last = Some(f);
        ok
    }

    /// F(x) into `f` and its norm, with the norms of f_ext and f_int (exact sums, so every
    /// Newton decision is the same at any rank count). `Ok(false)`: a material update failed.
    fn evaluate_residual(&mut self, x: &Vector, f: &mut Vector) -> Result<bool, PetscError> {
        self.residual_at = None;
        if !self.evaluate_at(x, false, false)? {
            return Ok(false);
        }
        f.copy_from(&self.f_int)?;
        f.axpy(-1.0, &self.f_ext)?;
        let d = self.problem.dirichlet_diag;
        let xs: Vec<f64> = x.read(|s| s.to_vec())?;
        f.write(|s| {
            for &(l, v) in &self.targets {
                s[l] = d * (xs[l] - v);
            }
        })?;
        let world = SimpleCommunicator::world();
        let norm = |v: &Vector| v.read(|s| exact_norm2(&world, s));
        self.ref_norm = norm(&self.f_ext)?.max(norm(&self.f_int)?).max(1e-300);
        self.residual_norm = norm(f)?;
        self.residual_at = Some(xs);
        Ok(true)
    }
}

impl SnesProblem for NewtonStep<'_, '_> {
    fn residual(&mut self, x: &Vector, f: &mut Vector) -> Result<bool, PetscError> {
        // a line search that accepts the point of its last merit evaluation asks for F there
        // again: it is known
        if !self.at_last_residual(x)? && !self.evaluate_last(x)? {
            return Ok(false);
        }
        f.copy_from(self.f_last.as_ref().expect("F of the last residual is kept"))?;
        Ok(true)
    }

    fn objective(&mut self, x: &Vector) -> Result<Option<f64>, PetscError> {
        // the line search first asks at the current iterate, where F is already known
        if !self.at_last_residual(x)? && !self.evaluate_last(x)? {
            return Ok(None);
        }
        Ok(Some(self.residual_norm * self.residual_norm))
    }

    fn jacobian(&mut self, x: &Vector) -> Result<bool, PetscError> {
        // SNES asks for J where the line search left its last residual: the trial states are
        // those of x already, and need no second integration
        let current = self.at_last_residual(x)?;
        if !self.evaluate_at(x, true, current)? {
            return Ok(false);
        }
        let d = self.problem.dirichlet_diag;
        self.problem.k.zero_rows_columns_only(&self.rows, d)?;
        Ok(true)
    }

    fn jacobian_matrix(&self) -> &Matrix {
        &self.problem.k
    }

    fn converged(&mut self, it: u32, _fnorm: f64, linear_iterations: u32) -> Option<bool> {
        // the exact norm of the last residual (at the iterate SNES accepted), not VecNorm's
        let rel = self.residual_norm / self.ref_norm;
        if it > 0 {
            self.report.ksp_iterations.push(linear_iterations);
            self.last_linear_iterations = linear_iterations;
        }
        self.report.residuals.push(rel);
        let opts = &self.problem.scene.file.solver;
        if opts.monitor && SimpleCommunicator::world().rank() == 0 {
            eprintln!(
                "newton λ = {:.6} iteration {it}: relative residual {rel:.3e}{}",
                self.lambda,
                if it > 0 {
                    format!(" ({linear_iterations} linear iterations)")
                } else {
                    String::new()
                }
            );
        }
        if !rel.is_finite() {
            return Some(false);
        }
        (it > 0 && rel <= opts.newton_tol).then_some(true)
    }
}

/// Adds the entries of an element vector (global DOFs `rows`) that fall in this rank's rows to
/// `v`; the other entries are added by their owner, which evaluates the element too
/// (rank-count-independent assembly, see `discretization`).
fn add_owned_rows(
    disc: &Discretization,
    v: &mut Vector,
    rows: &[i32],
    values: &[f64],
) -> Result<(), SolveError> {
    let (mut r, mut x, mut m) = ([0i32; 24], [0.0f64; 24], 0);
    for (&d, &value) in rows.iter().zip(values) {
        if disc.owns_dof(d) {
            r[m] = d;
            x[m] = value;
            m += 1;
        }
    }
    if m > 0 {
        v.set_values(&r[..m], &x[..m], true)?;
    }
    Ok(())
}
