//! Interface and joint element blocks: an interface law and the states of the 4 points of
//! each zero-thickness element of one block that this rank owns (spec §5, §6). The match on
//! the law happens once per call; the point loop is monomorphized for each law
//! ([`InterfaceModel`]).
//!
//! Every evaluation integrates the law from the committed state with the jump of the step
//! displacement increment (spec §8.1); the jump reported for output counts from the
//! displacement at the element's placement (spec (E9)).

use super::qp_store::QpStore;
use super::solid::{Matrix24, Vector24};
use crate::element::interface8::{Interface8Geometry, INTERFACE_POINTS};
use crate::error::MaterialError;
use crate::material::interface_gp::GpInterface;
use crate::material::interface_hyperbolic::HyperbolicInterface;
use crate::material::interface_mc::MohrCoulombInterface;
use crate::material::joint::JointLaw;
use crate::material::{InterfaceModel, InterfaceOutputs, InterfaceParams};
use crate::tensor::{Local3, Tangent3};

/// A law together with the states of its points.
#[derive(Debug, Clone)]
pub struct LawStates<M: InterfaceModel> {
    /// The law.
    pub model: M,
    /// 4 points per element, element-major, point `q` at node pair `q` (spec (E8)).
    pub store: QpStore<M::State>,
    /// The tangent of every trial state (same layout as the store), so that a Jacobian at the
    /// point of the last residual evaluation needs no second update.
    pub trial_tangents: Vec<Tangent3>,
}

/// The interface laws a block can use, each with its states.
#[derive(Debug, Clone)]
pub enum InterfaceElements {
    /// Clough–Duncan hyperbolic interface (spec §3).
    Hyperbolic(LawStates<HyperbolicInterface>),
    /// Ideal elasto-plastic Mohr–Coulomb interface (spec §4).
    MohrCoulomb(LawStates<MohrCoulombInterface>),
    /// Bilinear slab joint (spec §6).
    Joint(LawStates<JointLaw>),
    /// 3D generalized-plasticity interface (spec §2).
    GpInterface(LawStates<GpInterface>),
}

/// Runs `$body` with `$ls` bound to the block's `LawStates`, whatever the law.
macro_rules! with_law {
    ($block:expr, $ls:ident => $body:expr) => {
        match $block {
            InterfaceElements::Hyperbolic($ls) => $body,
            InterfaceElements::MohrCoulomb($ls) => $body,
            InterfaceElements::Joint($ls) => $body,
            InterfaceElements::GpInterface($ls) => $body,
        }
    };
}

/// What an interface element evaluation returns.
pub struct InterfaceElementResponse {
    /// Internal force f_int (N), spec (E7).
    pub f_int: Vector24,
    /// Tangent stiffness (N/m), spec (E7), if asked for (boxed, as for the solids).
    pub k: Option<Box<Matrix24>>,
}

/// Per-element output of the committed states: means over the 4 points, and counts.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct InterfaceElementOutput {
    /// Mean traction (τ_s, τ_a, t_n) (Pa; t_n tension positive, σ_n = −t_n).
    pub traction: [f64; 3],
    /// Mean accumulated shear displacement of the material (s, a) (m).
    pub shear: [f64; 2],
    /// Mean normal deformation of the material, closure positive (m).
    pub normal: f64,
    /// Mean opening (m).
    pub opening: f64,
    /// Points that are open.
    pub open_points: u32,
    /// Points on the plastic (slipping) branch in their last update.
    pub plastic_points: u32,
}

fn law_states<M: InterfaceModel>(model: M, n: usize, sigma_n0: f64) -> Result<LawStates<M>, MaterialError> {
    let init = model.init_state(sigma_n0)?;
    Ok(LawStates {
        model,
        store: QpStore::new(n * INTERFACE_POINTS, init),
        trial_tangents: vec![Tangent3::zeros(); n * INTERFACE_POINTS],
    })
}

impl InterfaceElements {
    /// Builds the block's law with `n_elements` elements whose points start under the normal
    /// stress `sigma_n0` (Pa, compression positive) and no shear (spec (E9)).
    pub fn new(params: &InterfaceParams, n_elements: usize, sigma_n0: f64) -> Result<Self, MaterialError> {
        let bad = |e: crate::error::ParamError| MaterialError::new(e.to_string());
        Ok(match params {
            InterfaceParams::Hyperbolic(p) => {
                InterfaceElements::Hyperbolic(law_states(HyperbolicInterface::new(p), n_elements, sigma_n0)?)
            }
            InterfaceParams::MohrCoulomb(p) => InterfaceElements::MohrCoulomb(law_states(
                MohrCoulombInterface::new(p),
                n_elements,
                sigma_n0,
            )?),
            InterfaceParams::Joint(p) => {
                InterfaceElements::Joint(law_states(JointLaw::new(p), n_elements, sigma_n0)?)
            }
            InterfaceParams::GpInterface(p) => InterfaceElements::GpInterface(law_states(
                GpInterface::new(p.clone()).map_err(bad)?,
                n_elements,
                sigma_n0,
            )?),
        })
    }

    /// Evaluates element `e` (block-local index) for the step displacement increment `d_u`:
    /// updates its trial states from the committed ones and returns f_int and K (spec (E4)–(E7)).
    pub fn evaluate(
        &mut self,
        e: usize,
        geo: &Interface8Geometry,
        d_u: &Vector24,
        want_k: bool,
    ) -> Result<InterfaceElementResponse, MaterialError> {
        with_law!(self, ls => evaluate_element(ls, e, geo, d_u, want_k))
    }

    /// f_int and K of element `e` from its current trial states and their tangents, without
    /// updating the law: the response [`InterfaceElements::evaluate`] gave for the last
    /// increment, now with K (an update is a pure function of the committed state and the
    /// jump, so the values are the same).
    pub fn evaluate_trial(&self, e: usize, geo: &Interface8Geometry) -> InterfaceElementResponse {
        with_law!(self, ls => trial_response(ls, e, geo))
    }

    /// Whether the law's tangent is symmetric.
    pub fn symmetric_tangent(&self) -> bool {
        with_law!(self, ls => ls.model.symmetric_tangent())
    }

    /// Output of the committed states of element `e` (block-local index).
    pub fn output(&self, e: usize) -> InterfaceElementOutput {
        with_law!(self, ls => element_output(ls, e))
    }

    /// Accepts the trial states.
    pub fn commit(&mut self) {
        with_law!(self, ls => ls.store.commit())
    }

    /// Discards the trial states.
    pub fn revert(&mut self) {
        with_law!(self, ls => ls.store.revert())
    }
}

fn evaluate_element<M: InterfaceModel>(
    ls: &mut LawStates<M>,
    e: usize,
    geo: &Interface8Geometry,
    d_u: &Vector24,
    want_k: bool,
) -> Result<InterfaceElementResponse, MaterialError> {
    let base = e * INTERFACE_POINTS;
    let jumps = geo.jumps(d_u);
    let mut tractions = [Local3::zeros(); INTERFACE_POINTS];
    for (q, jump) in jumps.iter().enumerate() {
        let up = ls.model.update(&ls.store.committed[base + q], jump)?;
        tractions[q] = M::traction(&up.state);
        ls.store.trial[base + q] = up.state;
        ls.trial_tangents[base + q] = up.tangent;
    }
    Ok(InterfaceElementResponse {
        f_int: geo.internal_force(&tractions),
        k: want_k.then(|| Box::new(geo.stiffness(&trial_tangents(ls, e)))),
    })
}

/// The tangents of element `e`'s trial states.
fn trial_tangents<M: InterfaceModel>(ls: &LawStates<M>, e: usize) -> [Tangent3; INTERFACE_POINTS] {
    std::array::from_fn(|q| ls.trial_tangents[e * INTERFACE_POINTS + q])
}

fn trial_response<M: InterfaceModel>(
    ls: &LawStates<M>,
    e: usize,
    geo: &Interface8Geometry,
) -> InterfaceElementResponse {
    let tractions = std::array::from_fn(|q| M::traction(&ls.store.trial[e * INTERFACE_POINTS + q]));
    InterfaceElementResponse {
        f_int: geo.internal_force(&tractions),
        k: Some(Box::new(geo.stiffness(&trial_tangents(ls, e)))),
    }
}

fn element_output<M: InterfaceModel>(ls: &LawStates<M>, e: usize) -> InterfaceElementOutput {
    let mut out = InterfaceElementOutput::default();
    let w = 1.0 / INTERFACE_POINTS as f64;
    for s in &ls.store.committed[e * INTERFACE_POINTS..(e + 1) * INTERFACE_POINTS] {
        let t = M::traction(s);
        let o: InterfaceOutputs = M::outputs(s);
        for c in 0..3 {
            out.traction[c] += w * t[c];
        }
        out.shear[0] += w * o.shear[0];
        out.shear[1] += w * o.shear[1];
        out.normal += w * o.normal;
        out.opening += w * o.opening;
        out.open_points += u32::from(o.open);
        out.plastic_points += u32::from(o.plastic);
    }
    out
}
