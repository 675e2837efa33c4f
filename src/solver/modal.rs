//! Modal analysis of the committed state (spec seismic §4 items 4 and 9): the lowest pairs of
//!
//! ```text
//! K₀·φ = ω²·M·φ,    f = ω/(2π),    T = 1/f
//! ```
//!
//! on the free DOFs only: the rows and columns of every prescribed DOF (the scene's supports
//! and the nodes no placed element touches yet, [`super::constraints`]) are removed from K₀
//! and M before SLEPc sees them (`MatCreateSubMatrix`). Removing them, rather than keeping
//! them with a zero mass row and a large stiffness diagonal, gives no spurious eigenvalue to
//! push away and leaves M positive definite on what remains, so the generalized symmetric
//! (GHEP) solver of [`crate::linalg::slepc`] applies as is. M is the consistent (or lumped)
//! mass of the placed solids ([`crate::element::hex8::consistent_mass`]). K₀ is the
//! small-strain stiffness of the committed state: the solids with their elastic D^e there (for
//! the GP rockfill G = G₀·p_a·(p'/p_a)^m_s at its current p', spec seismic §4 item 9; its
//! elasto-plastic tangent is neither symmetric nor what "natural period" means), the
//! interfaces and joints at their tangent of a zero increment, then symmetrized. For elastic
//! solids this is the K₀ of Rayleigh damping (spec seismic §3.3); with the GP rockfill the
//! damping's K₀ is its tangent at the stage's start, which the modes do not use.

use super::error::SolveError;
use super::model::{BlockStates, Model};
use super::problem::Problem;
use super::solid::{Matrix24, Vector24};
use crate::linalg::petsc::Matrix;
use crate::linalg::slepc::Eps;
use crate::parallel::{any_error, max_f64, sum_f64, sum_u64};
use crate::scene::modal::ModalRequest;

/// The modes of one state, lowest frequency first.
#[derive(Debug, Clone, PartialEq)]
pub struct Modes {
    /// Name of the stage at whose start they were computed.
    pub stage: String,
    /// Natural frequencies f = ω/(2π) (Hz), ascending.
    pub frequencies_hz: Vec<f64>,
    /// Mode shapes on this rank's owned DOFs (3 per owned node, zero on prescribed DOFs),
    /// scaled to a largest component of 1 over all ranks, that component positive.
    pub shapes: Vec<Vec<f64>>,
    /// Wall-clock seconds of the analysis (max over ranks).
    pub seconds: f64,
}

impl Problem<'_> {
    /// The modal analysis `request` of the current stage's committed state with its fixed
    /// DOFs removed (collective).
    pub(super) fn modal_analysis(&mut self, request: ModalRequest) -> Result<Modes, SolveError> {
        let start = std::time::Instant::now();
        let mask = self.constraints.mask(&self.model.disc);
        let free = self.model.free_dofs(&mask);
        let n_free = sum_u64(self.comm, free.len() as u64);
        if n_free < u64::from(request.modes) + 1 {
            return Err(SolveError::Collective(format!(
                "the modal analysis asks for {} modes, but the stage has {n_free} free DOFs: at most {}",
                request.modes,
                n_free.saturating_sub(1)
            )));
        }
        let mass = self.model.assemble_mass(request.lumped)?.submatrix(&free)?;
        let k0 = self.model.modal_stiffness()?.submatrix(&free)?;
        let pairs = Eps::lowest_generalized(&k0, &mass, request.modes as usize, "modal_")?;
        let lo = self.model.disc.dof_lo;
        let n_owned = self.model.disc.n_owned_dofs;
        let mut modes = Modes {
            stage: self.scene.stages[self.stage].name.clone(),
            frequencies_hz: Vec::with_capacity(pairs.len()),
            shapes: Vec::with_capacity(pairs.len()),
            seconds: 0.0,
        };
        for pair in pairs {
            modes
                .frequencies_hz
                .push(pair.value.max(0.0).sqrt() / (2.0 * std::f64::consts::PI));
            let mut shape = vec![0.0; n_owned];
            for (&d, &v) in free.iter().zip(&pair.vector) {
                shape[d as usize - lo] = v;
            }
            modes.shapes.push(self.unit_peak(shape));
        }
        modes.seconds = max_f64(self.comm, start.elapsed().as_secs_f64());
        Ok(modes)
    }

    /// `shape` scaled so that its component of largest magnitude over all ranks is +1 (the
    /// lowest global DOF among equal magnitudes, so the sign is the same at any rank count).
    fn unit_peak(&self, mut shape: Vec<f64>) -> Vec<f64> {
        let lo = self.model.disc.dof_lo;
        let magnitude = max_f64(self.comm, shape.iter().fold(0.0f64, |m, v| m.max(v.abs())));
        let first = shape.iter().position(|v| v.abs() == magnitude);
        // the lowest global index holding the peak (as −index under a max), then its value
        let index = -max_f64(self.comm, first.map_or(f64::MIN, |i| -((lo + i) as f64)));
        let mine = first.filter(|&i| (lo + i) as f64 == index);
        let peak = sum_f64(self.comm, mine.map_or(0.0, |i| shape[i]));
        if peak != 0.0 {
            shape.iter_mut().for_each(|v| *v /= peak);
        }
        shape
    }
}

impl Model<'_> {
    /// The stiffness of the modal analysis at the committed state: ∫ Bᵀ D^e B dV of the solids
    /// with the elastic D^e of their committed states (the rockfill's G = G₀·p_a·(p'/p_a)^m_s at
    /// its p', spec seismic §4 item 9), the interfaces and joints at their tangent of a zero
    /// increment, symmetrized as (K + Kᵀ)/2 for the symmetric eigensolver (the GP interface's
    /// tangent is not symmetric). Collective; leaves the trial states at the committed ones.
    fn modal_stiffness(&mut self) -> Result<Matrix, SolveError> {
        let mut k = self.k.duplicate()?;
        k.zero()?;
        let mut values = [0.0f64; 576];
        let mut local = Ok(());
        for i in 0..self.disc.elements.len() {
            let (b, _) = self.elem_block[i];
            if !self.active_block[b] || local.is_err() {
                continue;
            }
            let e = self.disc.elements[i] as usize;
            let ke = match self.modal_element_stiffness(i) {
                Ok(ke) => ke,
                Err(err) => {
                    local = Err(err);
                    continue;
                }
            };
            let rows = self.element_dofs(e);
            let mut owned = Vec::with_capacity(24);
            for (r, &d) in rows.iter().enumerate() {
                if self.disc.owns_dof(d) {
                    for c in 0..24 {
                        values[24 * owned.len() + c] = ke[(r, c)];
                    }
                    owned.push(d);
                }
            }
            if !owned.is_empty() {
                k.add_values(&owned, &rows, &values[..24 * owned.len()])?;
            }
        }
        k.assemble()?;
        self.revert()?;
        any_error(self.comm, local).map_err(SolveError::Collective)?;
        Ok(k.symmetric_part()?)
    }

    /// The modal stiffness of the `i`-th evaluated element: elastic for a solid, the tangent of
    /// a zero increment for an interface or joint ([`Model::modal_stiffness`]).
    fn modal_element_stiffness(&mut self, i: usize) -> Result<Matrix24, SolveError> {
        let mesh = &self.scene.mesh;
        let e = self.disc.elements[i] as usize;
        let (b, be) = self.elem_block[i];
        let element = mesh.elements[e].id;
        match &mut self.blocks[b] {
            BlockStates::Solid(block) => {
                let geo = self.solid_geo[i]
                    .as_ref()
                    .expect("solid geometry built at set-up");
                Ok(block.elastic_stiffness(be, geo))
            }
            BlockStates::Interface(block) => {
                let geo = self.iface_geo[i]
                    .as_ref()
                    .expect("interface geometry built at set-up");
                block
                    .evaluate(be, geo, &Vector24::zeros(), true)
                    .map(|r| *r.k.expect("a tangent was asked for"))
                    .map_err(|m| SolveError::Material {
                        element,
                        reason: m.reason,
                    })
            }
        }
    }

    /// The global indices of the owned DOFs that are free: on a placed node and not fixed by
    /// `fixed_mask` (per owned DOF), ascending.
    fn free_dofs(&self, fixed_mask: &[bool]) -> Vec<i32> {
        let disc = &self.disc;
        (0..disc.n_owned_dofs)
            .filter(|&i| !fixed_mask[i] && self.node_active[disc.owned_nodes[i / 3] as usize])
            .map(|i| (disc.dof_lo + i) as i32)
            .collect()
    }
}
