//! Solid element blocks: a material model and the integration-point states of the elements
//! of one block that this rank owns. The match on the model happens once per block; the
//! element loop is monomorphized for each model ([`SolidModel`]).

use super::qp_store::QpStore;
use crate::element::hex8::Hex8Geometry;
use crate::element::hex8_modes::{IncompatibleModes, Modes9};
use crate::element::quadrature::HEX_GAUSS_POINTS;
use crate::error::MaterialError;
use crate::material::elastic::LinearElastic;
use crate::material::rockfill_gp::RockfillGp;
use crate::material::{SolidModel, SolidParams};
use crate::tensor::{Strain6, Stress6, Tangent6};
use nalgebra::{SMatrix, SVector};

/// Element vector (24 DOFs).
pub type Vector24 = SVector<f64, 24>;
/// Element matrix (24 × 24).
pub type Matrix24 = SMatrix<f64, 24, 24>;

/// A model together with the states of its points.
#[derive(Debug, Clone)]
pub struct ModelStates<M: SolidModel> {
    /// The model.
    pub model: M,
    /// 8 Gauss points per element, element-major.
    pub store: QpStore<M::State>,
    /// The tangent of every trial state (same layout as the store), so that a Jacobian at the
    /// point of the last residual evaluation needs no second integration; empty for a model
    /// of constant tangent ([`SolidModel::CONSTANT_TANGENT`]).
    pub trial_tangents: Vec<Tangent6>,
    /// The incompatible modes of every element (`crate::element::hex8_modes`), or empty for
    /// the trilinear hexahedron.
    pub modes: Vec<IncompatibleModes>,
}

/// The solid models a block can use, each with its states.
#[derive(Debug, Clone)]
pub enum SolidBlock {
    /// Linear elastic.
    Elastic(ModelStates<LinearElastic>),
    /// Generalized-plasticity rockfill.
    RockfillGp(ModelStates<RockfillGp>),
}

/// Runs `$body` with `$ms` bound to the block's `ModelStates`, whatever the model (the match
/// happens once per call, the body is monomorphized per model).
macro_rules! with_states {
    ($block:expr, $ms:ident => $body:expr) => {
        match $block {
            SolidBlock::Elastic($ms) => $body,
            SolidBlock::RockfillGp($ms) => $body,
        }
    };
}

/// What an element evaluation returns.
pub struct ElementResponse {
    /// Internal force f_int (N).
    pub f_int: Vector24,
    /// Tangent stiffness (N/m), if asked for (boxed: an element's response is moved several
    /// times on its way into the assembly, and an unboxed 4.6 KB matrix was copied each time,
    /// a fifth of a linear quake's step).
    pub k: Option<Box<Matrix24>>,
    /// Average stress over the Gauss points (Pa).
    pub mean_stress: Stress6,
}

impl SolidBlock {
    /// Builds the block's model with `n_elements` elements starting at zero stress.
    pub fn new(params: &SolidParams, n_elements: usize) -> Result<SolidBlock, MaterialError> {
        let n = n_elements * HEX_GAUSS_POINTS;
        Ok(match params {
            SolidParams::Elastic(p) => {
                let model = LinearElastic::new(p);
                let init = model.init_state(&Stress6::default())?;
                SolidBlock::Elastic(ModelStates {
                    model,
                    store: QpStore::new(n, init),
                    trial_tangents: Vec::new(),
                    modes: Vec::new(),
                })
            }
            SolidParams::RockfillGp(p) => {
                let model = RockfillGp::new(p.clone()).map_err(|e| MaterialError::new(e.to_string()))?;
                // a point placed without stress starts at the pressure floor p_min (spec §8.6 item 1)
                let init = model.init_state(&Stress6::isotropic(-placement_pressure(p)))?;
                SolidBlock::RockfillGp(ModelStates {
                    model,
                    store: QpStore::new(n, init),
                    trial_tangents: vec![Tangent6::default(); n],
                    modes: Vec::new(),
                })
            }
        })
    }

    /// Evaluates element `e` (block-local index) for the step displacement increment `d_u`:
    /// updates its trial states from the committed ones (spec §8.1) and returns f_int and K.
    pub fn evaluate(
        &mut self,
        e: usize,
        geo: &Hex8Geometry,
        d_u: &Vector24,
        want_k: bool,
    ) -> Result<ElementResponse, MaterialError> {
        with_states!(self, ms => evaluate_element(ms, e, geo, d_u, want_k))
    }

    /// f_int and K of element `e` from its current trial states and their tangents, without
    /// integrating the material: the response [`SolidBlock::evaluate`] gave for the last
    /// increment, now with K.
    pub fn evaluate_trial(&self, e: usize, geo: &Hex8Geometry) -> ElementResponse {
        with_states!(self, ms => trial_response(ms, e, geo))
    }

    /// Stress σ₀ (Pa) of a point when its element is placed: zero for the elastic model, the
    /// pressure floor p_min·I (compression) for the rockfill (spec §8.6 item 1).
    pub fn placement_stress(&self) -> Stress6 {
        match self {
            SolidBlock::Elastic(_) => Stress6::default(),
            SolidBlock::RockfillGp(ms) => Stress6::isotropic(-placement_pressure(ms.model.params())),
        }
    }

    /// Nodal forces f₀ = ∫ Bᵀσ₀ dV (N) of the placement stress σ₀ of an element. The static
    /// solver adds them to the external force of every placed element, so that a lift is placed
    /// in equilibrium at σ₀ (see `crate::solver::loads`).
    pub fn placement_force(&self, geo: &Hex8Geometry) -> Vector24 {
        geo.internal_force(&[self.placement_stress(); HEX_GAUSS_POINTS])
    }

    /// The elastic stiffness ∫ Bᵀ D^e B dV of element `e` (block-local index) at its committed
    /// states (the modal analysis, spec seismic §4 item 9).
    pub fn elastic_stiffness(&self, e: usize, geo: &Hex8Geometry) -> Matrix24 {
        with_states!(self, ms => {
            let tan: [Tangent6; HEX_GAUSS_POINTS] = std::array::from_fn(|q| {
                ms.model.elastic_tangent(&ms.store.committed[e * HEX_GAUSS_POINTS + q])
            });
            stiffness(ms, e, geo, &tan)
        })
    }

    /// Whether the model's tangent is symmetric (CG needs it; otherwise GMRES is used).
    pub fn symmetric_tangent(&self) -> bool {
        with_states!(self, ms => ms.model.symmetric_tangent())
    }

    /// Mean committed stress over the Gauss points of element `e` (block-local index).
    pub fn mean_stress(&self, e: usize) -> Stress6 {
        with_states!(self, ms => mean_committed_stress(ms, e))
    }

    /// Gives the block's elements (block-local order) incompatible modes
    /// (`crate::element::hex8_modes`); the block must be elastic (the scene checks it).
    pub fn attach_modes(&mut self, modes: Vec<IncompatibleModes>) {
        with_states!(self, ms => ms.modes = modes)
    }

    /// Mean strain over the Gauss points of element `e` (block-local index) for the
    /// displacement `ue` since its placement, with its modes' part when it has them (their
    /// stress-free placement makes α = −K_αα⁻¹ K_αu u_e).
    pub fn mean_strain(&self, e: usize, geo: &Hex8Geometry, ue: &Vector24) -> Strain6 {
        let eps = with_states!(self, ms => match ms.modes.get(e) {
            None => geo.strain_increments(ue),
            Some(modes) => {
                let tan: [Tangent6; HEX_GAUSS_POINTS] = std::array::from_fn(|q| {
                    ms.model.elastic_tangent(&ms.store.committed[e * HEX_GAUSS_POINTS + q])
                });
                let alpha = modes.condense(geo, &tan).map_or(Modes9::zeros(), |c| c.modes(ue, &Modes9::zeros()));
                modes.strain_increments(geo, ue, &alpha)
            }
        });
        eps.iter().fold(Strain6::default(), |a, s| {
            Strain6(a.0 + s.0 / HEX_GAUSS_POINTS as f64)
        })
    }

    /// Accepts the trial states.
    pub fn commit(&mut self) {
        with_states!(self, ms => ms.store.commit())
    }

    /// Discards the trial states.
    pub fn revert(&mut self) {
        with_states!(self, ms => ms.store.revert())
    }
}

/// Isotropic compression (Pa) of a freshly placed rockfill point: p_min (spec §8.6 item 1).
fn placement_pressure(p: &crate::material::rockfill_gp::RockfillGpParams) -> f64 {
    p.pmin
}

fn evaluate_element<M: SolidModel>(
    ms: &mut ModelStates<M>,
    e: usize,
    geo: &Hex8Geometry,
    d_u: &Vector24,
    want_k: bool,
) -> Result<ElementResponse, MaterialError> {
    let d_eps = match ms.modes.get(e) {
        None => geo.strain_increments(d_u),
        Some(modes) => {
            let range = e * HEX_GAUSS_POINTS..(e + 1) * HEX_GAUSS_POINTS;
            let committed = &ms.store.committed[range];
            let tan: [Tangent6; HEX_GAUSS_POINTS] =
                std::array::from_fn(|q| ms.model.elastic_tangent(&committed[q]));
            let sig: [Stress6; HEX_GAUSS_POINTS] = std::array::from_fn(|q| M::stress(&committed[q]));
            let d_alpha = modes
                .condense(geo, &tan)
                .map_or(Modes9::zeros(), |c| c.modes(d_u, &modes.residual(geo, &sig)));
            modes.strain_increments(geo, d_u, &d_alpha)
        }
    };
    let mut sig = [Stress6::default(); HEX_GAUSS_POINTS];
    for q in 0..HEX_GAUSS_POINTS {
        let i = e * HEX_GAUSS_POINTS + q;
        let up = ms.model.update(&ms.store.committed[i], &d_eps[q])?;
        sig[q] = M::stress(&up.state);
        if !M::CONSTANT_TANGENT {
            ms.trial_tangents[i] = up.tangent;
        }
        ms.store.trial[i] = up.state;
    }
    let mean = mean_of(&sig);
    Ok(ElementResponse {
        f_int: geo.internal_force(&sig),
        k: want_k.then(|| Box::new(stiffness(ms, e, geo, &trial_tangents(ms, e)))),
        mean_stress: mean,
    })
}

/// The tangents of element `e`'s trial states: kept from their update, or the model's own
/// for a model of constant tangent.
fn trial_tangents<M: SolidModel>(ms: &ModelStates<M>, e: usize) -> [Tangent6; HEX_GAUSS_POINTS] {
    let first = e * HEX_GAUSS_POINTS;
    std::array::from_fn(|q| match M::CONSTANT_TANGENT {
        true => ms.model.elastic_tangent(&ms.store.trial[first + q]),
        false => ms.trial_tangents[first + q],
    })
}

/// The element stiffness at tangents `tan`: Σ Bᵀ D B dV, condensed when the element has
/// incompatible modes. K_αα is positive definite for an elastic D (the only model the scene
/// allows with the modes); were it singular, the modes would be left at rest (α = 0) and the
/// element be the trilinear one, here and in [`evaluate_element`].
fn stiffness<M: SolidModel>(
    ms: &ModelStates<M>,
    e: usize,
    geo: &Hex8Geometry,
    tan: &[Tangent6; HEX_GAUSS_POINTS],
) -> Matrix24 {
    let k = geo.stiffness(tan);
    match ms.modes.get(e).and_then(|m| m.condense(geo, tan)) {
        Some(c) => c.stiffness(&k),
        None => k,
    }
}

/// Average of the Gauss-point stresses of an element.
fn mean_of(sig: &[Stress6; HEX_GAUSS_POINTS]) -> Stress6 {
    sig.iter().fold(Stress6::default(), |a, s| {
        Stress6(a.0 + s.0 / HEX_GAUSS_POINTS as f64)
    })
}

fn trial_response<M: SolidModel>(ms: &ModelStates<M>, e: usize, geo: &Hex8Geometry) -> ElementResponse {
    let range = e * HEX_GAUSS_POINTS..(e + 1) * HEX_GAUSS_POINTS;
    let sig: [Stress6; HEX_GAUSS_POINTS] =
        std::array::from_fn(|q| M::stress(&ms.store.trial[range.start + q]));
    let tan = trial_tangents(ms, e);
    let mean = mean_of(&sig);
    ElementResponse {
        f_int: geo.internal_force(&sig),
        k: Some(Box::new(stiffness(ms, e, geo, &tan))),
        mean_stress: mean,
    }
}

fn mean_committed_stress<M: SolidModel>(ms: &ModelStates<M>, e: usize) -> Stress6 {
    let range = e * HEX_GAUSS_POINTS..(e + 1) * HEX_GAUSS_POINTS;
    let sum = ms.store.committed[range]
        .iter()
        .fold(Stress6::default(), |a, s| Stress6(a.0 + M::stress(s).0));
    Stress6(sum.0 / HEX_GAUSS_POINTS as f64)
}
