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
//! (GHEP) solver of [`crate::linalg::slepc`] applies as is. K₀ is the stiffness at the
//! committed state, as for Rayleigh damping (spec seismic §3.3); M is the consistent (or
//! lumped) mass of the placed solids.

use super::error::SolveError;
use super::model::Model;
use super::problem::Problem;
use crate::linalg::slepc::Eps;
use crate::parallel::{max_f64, sum_f64, sum_u64};
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
                "the modal analysis asks for {} modes, the model has {n_free} free DOFs",
                request.modes
            )));
        }
        let mass = self.model.assemble_mass(request.lumped)?.submatrix(&free)?;
        let k0 = self.model.initial_stiffness()?.submatrix(&free)?;
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
