//! The model on this rank: the discretization, the material states of every evaluated
//! element, the tangent matrix and the displacement vectors; assembly of f_int and K_t.
//!
//! ```text
//! f_int = Σ_e ∫ Bᵀ σ(Δε) dV,    K_t = Σ_e ∫ Bᵀ D_t B dV
//! ```
//! Every evaluation integrates the material from the committed state with the total step
//! increment u − u_committed (spec models §8.1); `Model::commit` accepts the trial states.
//! Dirichlet DOFs are kept in the system (block size 3 for algebraic multigrid).
//!
//! Rank-count independence: the residual, the tangent and the external forces are assembled
//! row by row on the owning rank over the same elements in the same order at any rank count
//! (`discretization`), and the Dirichlet scaling is an exact sum (`exact_sum`).

use super::discretization::Discretization;
use super::error::SolveError;
use super::interface::InterfaceElements;
use super::report::InterfaceCounts;
use super::solid::{SolidBlock, Vector24};
use super::state_codec;
use super::tangent_slots::TangentSlots;
use crate::element::hex8::Hex8Geometry;
use crate::element::hex8_modes::{IncompatibleModes, SolidElement};
use crate::element::interface8::Interface8Geometry;
use crate::element::interface_frame::FrameAxes;
use crate::linalg::petsc::{Gather, Matrix, Petsc, Vector};
use crate::material::BlockMaterial;
use crate::mesh::Mesh;
use crate::parallel::sum_u64;
use crate::scene::Scene;
use mpi::topology::SimpleCommunicator;
use partition::Cells;

/// The elements of one block on this rank with their model and states.
#[derive(Debug, Clone)]
pub enum BlockStates {
    /// Hexahedra with a solid model.
    Solid(SolidBlock),
    /// Zero-thickness interface or joint elements with an interface law.
    Interface(InterfaceElements),
}

impl BlockStates {
    fn new(material: &BlockMaterial, initial_normal_stress: f64, n: usize) -> Result<Self, SolveError> {
        let made = match material {
            BlockMaterial::Solid(p) => SolidBlock::new(p, n).map(BlockStates::Solid),
            BlockMaterial::Interface(p) => {
                InterfaceElements::new(p, n, initial_normal_stress).map(BlockStates::Interface)
            }
        };
        made.map_err(|e| SolveError::Material {
            element: 0,
            reason: e.reason,
        })
    }
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

/// Cells (8 nodes each) of a mesh, for partitioning and indexing.
pub fn mesh_cells(mesh: &Mesh) -> Cells {
    let mut cells = Cells::default();
    for e in &mesh.elements {
        cells.push(&e.nodes);
    }
    cells
}

/// The rank-local model: what is assembled and what is committed.
pub struct Model<'a> {
    pub(super) scene: &'a Scene,
    pub(super) comm: &'a SimpleCommunicator,
    pub(super) disc: Discretization,
    pub(super) blocks: Vec<BlockStates>,
    /// Geometry of every evaluated interface element (`None` for solid elements).
    pub(super) iface_geo: Vec<Option<Interface8Geometry>>,
    /// Gauss-point geometry of every evaluated solid element (`None` for interfaces), built
    /// once: the mesh does not move (small strain), so every assembly reuses it.
    pub(super) solid_geo: Vec<Option<Hex8Geometry>>,
    /// For every evaluated element: (block, index within the block's elements on this rank).
    pub(super) elem_block: Vec<(usize, usize)>,
    /// The tangent (the Jacobian once the integrator's shifts and the constraints are in).
    pub(super) k: Matrix,
    /// Where each evaluated element's entries of K are stored.
    pub(super) slots: TangentSlots,
    /// Displacement of the current iterate.
    pub(super) u: Vector,
    /// Displacement of the committed state.
    pub(super) u_committed: Vector,
    pub(super) gather: Gather,
    pub(super) gather_committed: Gather,
    /// Diagonal value put on Dirichlet rows: the mean diagonal of the stiffness (same on every
    /// rank), so the constrained rows do not spoil the multigrid smoothers' scaling.
    pub(super) dirichlet_diag: f64,
    /// Whether each block is placed (same on every rank).
    pub(super) active_block: Vec<bool>,
    /// Whether each node belongs to a placed element (same on every rank).
    pub(super) node_active: Vec<bool>,
    /// Displacement of each evaluated element's nodes when it was placed: strains count from
    /// there.
    pub(super) elem_ref: Vec<Vector24>,
    /// Seconds this rank spent in its element loops (material updates, element matrices and
    /// their insertion), without the waits of the collective assembly: the ranks' figures
    /// side by side show the load balance of the assembly.
    pub(super) element_seconds: f64,
    /// In a linear scene: f_int at the committed displacement while the trial states are the
    /// committed ones ([`super::committed_forces`]); `None` otherwise.
    pub(super) f_int_committed: Option<Vector>,
}

impl<'a> Model<'a> {
    /// Sets up the rank-local model for a given element partition: material states, interface
    /// geometry, the full sparsity pattern (every element, placed or not yet) with the
    /// rigid-body near-null space, and zero displacements.
    pub fn new(
        petsc: &Petsc,
        comm: &'a SimpleCommunicator,
        scene: &'a Scene,
        cells: &Cells,
        disc: Discretization,
    ) -> Result<Self, SolveError> {
        let mesh = &scene.mesh;
        let (elem_block, mut blocks) = Self::blocks_of(scene, &disc)?;
        Self::attach_modes(scene, &disc, &elem_block, &mut blocks)?;
        let iface_geo = Self::interface_geometry(scene, &disc)?;
        let solid_geo = Self::solid_geometry(scene, &disc, &iface_geo)?;
        let (d_nnz, o_nnz) = disc.preallocation(cells, mesh.num_nodes());
        let mut k = Matrix::aij(petsc, disc.n_owned_dofs, 3, &d_nnz, &o_nnz)?;
        let mut u = Vector::mpi(petsc, disc.n_owned_dofs, 3)?;
        let mut coords = u.duplicate()?;
        coords.write(|c| {
            for (i, &n) in disc.owned_nodes.iter().enumerate() {
                c[3 * i..3 * i + 3].copy_from_slice(&mesh.coords[n as usize]);
            }
        })?;
        k.set_rigid_body_near_null_space(&coords)?;
        Self::preallocate_pattern(&mut k, mesh, &disc)?;
        let slots = TangentSlots::new(k.csr_layout()?, &disc).map_err(SolveError::Collective)?;
        u.set_all(0.0)?;
        let mut u_committed = u.duplicate()?;
        u_committed.set_all(0.0)?;
        let gather = Gather::new(&u, &disc.local_dofs)?;
        let gather_committed = Gather::new(&u, &disc.local_dofs)?;
        let n_elements = disc.elements.len();
        Ok(Model {
            scene,
            comm,
            disc,
            blocks,
            iface_geo,
            solid_geo,
            elem_block,
            k,
            slots,
            u,
            u_committed,
            gather,
            gather_committed,
            dirichlet_diag: 1.0,
            f_int_committed: None,
            element_seconds: 0.0,
            active_block: vec![false; mesh.blocks.len()],
            node_active: vec![false; mesh.num_nodes()],
            elem_ref: vec![Vector24::zeros(); n_elements],
        })
    }

    /// The block of every evaluated element (and its index within the block) and the blocks'
    /// material states.
    #[allow(clippy::type_complexity)]
    fn blocks_of(
        scene: &Scene,
        disc: &Discretization,
    ) -> Result<(Vec<(usize, usize)>, Vec<BlockStates>), SolveError> {
        let mesh = &scene.mesh;
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
            .map(|((m, ib), &n)| {
                BlockStates::new(m, ib.as_ref().map_or(0.0, |ib| ib.initial_normal_stress), n)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok((elem_block, blocks))
    }

    /// The owned DOFs (global indices, increasing) of the stiff structure that the reduced
    /// multigrid factors apart from the fill ([`crate::linalg::petsc::reduced_amg`]): the nodes of
    /// zero-thickness elements (interfaces and joints, both faces) and of the blocks with
    /// incompatible modes (the face slab).
    pub(super) fn structure_dofs(&self) -> Vec<i32> {
        let mesh = &self.scene.mesh;
        let mut stiff = vec![false; mesh.num_nodes()];
        for (&e, &(b, _)) in self.disc.elements.iter().zip(&self.elem_block) {
            let e = e as usize;
            if mesh.is_interface(e) || self.scene.block_element[b] == SolidElement::IncompatibleModes {
                for &n in &mesh.elements[e].nodes {
                    stiff[n as usize] = true;
                }
            }
        }
        let lo = self.disc.dof_lo as i32;
        self.disc
            .owned_nodes
            .iter()
            .enumerate()
            .filter(|(_, &n)| stiff[n as usize])
            .flat_map(|(i, _)| (0..3).map(move |c| lo + 3 * i as i32 + c))
            .collect()
    }

    /// Gives the elements of the blocks that ask for them their incompatible modes
    /// (`crate::element::hex8_modes`), in block-local order.
    fn attach_modes(
        scene: &Scene,
        disc: &Discretization,
        elem_block: &[(usize, usize)],
        blocks: &mut [BlockStates],
    ) -> Result<(), SolveError> {
        let mesh = &scene.mesh;
        let mut modes: Vec<Vec<IncompatibleModes>> = vec![Vec::new(); blocks.len()];
        for (&e, &(b, _)) in disc.elements.iter().zip(elem_block) {
            if scene.block_element[b] == SolidElement::IncompatibleModes {
                let m = IncompatibleModes::new(&mesh.element_coords(e as usize)).map_err(|_| {
                    SolveError::Geometry {
                        element: mesh.elements[e as usize].id,
                    }
                })?;
                modes[b].push(m);
            }
        }
        for (block, m) in blocks.iter_mut().zip(modes) {
            if let (BlockStates::Solid(solid), false) = (block, m.is_empty()) {
                solid.attach_modes(m);
            }
        }
        Ok(())
    }

    /// The geometry of every evaluated interface element (`None` for solids).
    fn interface_geometry(
        scene: &Scene,
        disc: &Discretization,
    ) -> Result<Vec<Option<Interface8Geometry>>, SolveError> {
        let mesh = &scene.mesh;
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
        Ok(iface_geo)
    }

    /// The Gauss-point geometry of every evaluated solid element (`None` for interfaces).
    fn solid_geometry(
        scene: &Scene,
        disc: &Discretization,
        iface_geo: &[Option<Interface8Geometry>],
    ) -> Result<Vec<Option<Hex8Geometry>>, SolveError> {
        let mesh = &scene.mesh;
        let solid = |(&e, iface): (&u32, &Option<Interface8Geometry>)| match iface {
            Some(_) => Ok(None),
            None => Hex8Geometry::new(&mesh.element_coords(e as usize))
                .map(Some)
                .map_err(|_| SolveError::Geometry {
                    element: mesh.elements[e as usize].id,
                }),
        };
        disc.elements.iter().zip(iface_geo).map(solid).collect()
    }

    /// The full pattern once: every element, placed or not yet, and every diagonal block, so
    /// that placing blocks later never needs a new nonzero (zero entries stay in the pattern);
    /// only owned rows, as in every assembly (module docs of `discretization`).
    fn preallocate_pattern(k: &mut Matrix, mesh: &Mesh, disc: &Discretization) -> Result<(), SolveError> {
        let zeros = vec![0.0f64; 576];
        for &e in &disc.elements {
            let cols: Vec<i32> = mesh.elements[e as usize]
                .nodes
                .iter()
                .flat_map(|&n| (0..3).map(move |c| disc.dof(n, c)))
                .collect();
            let rows: Vec<i32> = cols.iter().copied().filter(|&d| disc.owns_dof(d)).collect();
            k.add_values(&rows, &cols, &zeros[..24 * rows.len()])?;
        }
        for &n in &disc.owned_nodes {
            let d = [disc.dof(n, 0), disc.dof(n, 1), disc.dof(n, 2)];
            k.add_values(&d, &d, &zeros[..9])?;
        }
        k.assemble()?;
        Ok(())
    }

    /// Whether every block's tangent is symmetric (CG is then allowed).
    pub fn symmetric_tangent(&self) -> bool {
        self.blocks.iter().all(BlockStates::symmetric_tangent)
    }

    /// Whether every block of the scene is linear elastic (no rockfill, interface or joint),
    /// so that K_t is the same at every displacement. The same on every rank.
    pub(super) fn is_linear(&self) -> bool {
        self.scene.block_materials.iter().all(|m| {
            matches!(
                m,
                crate::material::BlockMaterial::Solid(crate::material::SolidParams::Elastic(_))
            )
        })
    }

    /// The rank-local indexing.
    pub fn discretization(&self) -> &Discretization {
        &self.disc
    }

    /// The current displacement at this rank's local DOFs (owned and ghost), in
    /// [`Discretization::local_dofs`] order. Collective.
    pub(super) fn local_u(&mut self) -> Result<Vec<f64>, SolveError> {
        Ok(self.gather.gather(&self.u)?.read(|s| s.to_vec())?)
    }

    /// Places the blocks `activate` (strain-free: their states start from the initial state
    /// and their strains count from the current displacement) and marks their nodes.
    /// Collective.
    pub(super) fn place(&mut self, activate: &[u32]) -> Result<(), SolveError> {
        self.f_int_committed = None;
        let mesh = &self.scene.mesh;
        let mut newly = vec![false; mesh.blocks.len()];
        for &b in activate {
            newly[b as usize] = !self.active_block[b as usize];
            self.active_block[b as usize] = true;
        }
        for e in &mesh.elements {
            if self.active_block[e.block as usize] {
                for &n in &e.nodes {
                    self.node_active[n as usize] = true;
                }
            }
        }
        let u_loc = self.local_u()?;
        for (i, &e) in self.disc.elements.iter().enumerate() {
            if newly[mesh.elements[e as usize].block as usize] {
                let loc = &self.disc.element_local[i];
                self.elem_ref[i] = Vector24::from_fn(|r, _| u_loc[3 * loc[r / 3] as usize + r % 3]);
            }
        }
        Ok(())
    }

    /// Global DOFs of the 8 nodes of element `e` (input index), node-major.
    pub(super) fn element_dofs(&self, e: usize) -> Vec<i32> {
        self.scene.mesh.elements[e]
            .nodes
            .iter()
            .flat_map(|&n| (0..3).map(move |c| (n, c)))
            .map(|(n, c)| self.disc.dof(n, c))
            .collect()
    }

    /// Accepts the trial states and the current displacement.
    pub(super) fn commit(&mut self) -> Result<(), SolveError> {
        for b in &mut self.blocks {
            b.commit();
        }
        self.u_committed.copy_from(&self.u)?;
        Ok(())
    }

    /// Returns to the committed state (after a failed step).
    pub(super) fn revert(&mut self) -> Result<(), SolveError> {
        for b in &mut self.blocks {
            b.revert();
        }
        self.u.copy_from(&self.u_committed)?;
        Ok(())
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
        InterfaceCounts {
            points: sum_u64(self.comm, points),
            open: sum_u64(self.comm, open),
            slipping: sum_u64(self.comm, slipping),
        }
    }

    /// The committed states of the owned elements, encoded ([`state_codec`]).
    pub(super) fn encode_states(&self) -> Result<Vec<Vec<u8>>, SolveError> {
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
        Ok(element_states)
    }

    /// Restores the states of every evaluated element from `states` (one encoding each, in
    /// [`Discretization::elements`] order). Fails naming the element whose bytes do not decode.
    pub(super) fn decode_states(&mut self, states: &[Vec<u8>]) -> Result<(), String> {
        self.f_int_committed = None;
        for (i, &(b, be)) in self.elem_block.iter().enumerate() {
            let bytes = &states[i];
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
        Ok(())
    }
}

/// Adds the entries of an element vector (global DOFs `rows`) that fall in this rank's rows to
/// `v`; the other entries are added by their owner, which evaluates the element too
/// (rank-count-independent assembly, see `discretization`).
pub(super) fn add_owned_rows(
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
