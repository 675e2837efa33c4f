//! Constitutive library: solid models at a Gauss point and interface laws at an interface point.
//!
//! Design (`spec/style.md` G.3): parameters, model and state are three separate things.
//! Parameters are serde data validated at load ([`crate::error::ParamError`]); a model is built
//! from them and is immutable; the state is plain, serializable data. `update` is **pure**: it
//! reads the last *committed* state and the *total step* increment and returns a new trial state,
//! the tangent and the kind of tangent (spec §8.1). The framework owns commit/revert.
//!
//! Units at the model boundary are SI (Pa, m). Models written in kPa in the spec convert once,
//! at this boundary.

use crate::error::MaterialError;
use crate::tensor::{Local3, Strain6, Stress6, Tangent3, Tangent6};
use serde::{de::DeserializeOwned, Serialize};

pub mod bench;
pub mod driver_interface;
pub mod driver_solid;
pub mod elastic;
pub mod gp_integrator;
pub mod interface_gp;
pub mod interface_gp_functions;
pub mod interface_hyperbolic;
pub mod interface_mc;
pub mod joint;
pub mod rockfill_gp;

/// Which tangent an update returns (cf. MOOSE `TangentCalculationMethod`, spec §8.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum TangentKind {
    /// The elastic operator D^e (elastic step, or a fallback).
    Elastic,
    /// The continuum elasto-plastic operator D^ep at the end state (spec eqs. (R16), (I19)).
    Continuum,
    /// The algorithmic (consistent) tangent of the discrete update (spec §8.3, §8.5).
    Consistent,
    /// A secant operator (piecewise-linear laws, spec §6.1 (J3)).
    Secant,
}

/// Result of a solid update.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidUpdate<S> {
    /// The new trial state (holds the stress).
    pub state: S,
    /// Tangent dσ/dε.
    pub tangent: Tangent6,
    /// Which tangent `tangent` is.
    pub kind: TangentKind,
    /// Number of accepted substeps used (1 for closed-form updates).
    pub substeps: u32,
}

/// Result of an interface update.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceUpdate<S> {
    /// The new trial state (holds the traction).
    pub state: S,
    /// Tangent dT/dδ in the local frame `[s, a, n]`, Pa/m.
    pub tangent: Tangent3,
    /// Which tangent `tangent` is.
    pub kind: TangentKind,
    /// Number of accepted substeps used (1 for closed-form updates).
    pub substeps: u32,
}

/// Small-strain solid model at one Gauss point. Immutable after construction.
pub trait SolidModel: Send + Sync {
    /// Integration-point state (stress and internal variables).
    type State: Clone + PartialEq + core::fmt::Debug + Serialize + DeserializeOwned + Send + Sync;

    /// Whether the tangent is the same at every state and increment, [`SolidModel::elastic_tangent`]
    /// (linear elasticity): the assembly then keeps no tangent per point.
    const CONSTANT_TANGENT: bool = false;

    /// Whether the tangent is symmetric (false for the non-associated GP model).
    fn symmetric_tangent(&self) -> bool;

    /// State of a point that starts at stress `sigma0` (Pa, tension positive), e.g. at activation.
    fn init_state(&self, sigma0: &Stress6) -> Result<Self::State, MaterialError>;

    /// σ_{n+1}, D_{n+1}, κ_{n+1} = f(κ_n, Δε): integrates from the committed state `prev`
    /// with the total step strain increment `d_eps` (spec §8.1).
    fn update(&self, prev: &Self::State, d_eps: &Strain6) -> Result<SolidUpdate<Self::State>, MaterialError>;

    /// The stress held by a state (Pa, tension positive).
    fn stress(state: &Self::State) -> Stress6;

    /// The elastic stiffness D^e (Pa) at a state: the small-strain stiffness of the modal
    /// analysis (spec seismic §4 item 9, the rockfill's G = G₀·p_a·(p'/p_a)^m_s at its p').
    fn elastic_tangent(&self, state: &Self::State) -> Tangent6;
}

/// Displacement-jump (traction–separation) law of an interface or joint point, in the local
/// frame `[s, a, n]` (spec §5.2).
///
/// * jump δ = (δ_s, δ_a, δ_n) in m: cushion (face A) relative to slab (face B); δ_n > 0 opens;
/// * traction T = (τ_s, τ_a, t_n) in Pa, work-conjugate to δ: t_n = −σ_n is **tension positive**
///   (σ_n, the compression-positive normal stress of the spec, is `-T[2]`).
pub trait InterfaceModel: Send + Sync {
    /// Interface-point state (traction, internal variables, opening memory).
    type State: Clone + PartialEq + core::fmt::Debug + Serialize + DeserializeOwned + Send + Sync;

    /// Whether the tangent is symmetric.
    fn symmetric_tangent(&self) -> bool;

    /// State at activation under a compressive normal stress `sigma_n0` ≥ 0 (Pa) and no shear.
    fn init_state(&self, sigma_n0: f64) -> Result<Self::State, MaterialError>;

    /// Integrates from the committed state `prev` with the total step jump increment `d_jump`.
    fn update(
        &self,
        prev: &Self::State,
        d_jump: &Local3,
    ) -> Result<InterfaceUpdate<Self::State>, MaterialError>;

    /// The traction held by a state, T = (τ_s, τ_a, t_n), Pa.
    fn traction(state: &Self::State) -> Local3;

    /// Output quantities of a state (slip, normal deformation without opening, opening).
    fn outputs(state: &Self::State) -> InterfaceOutputs;
}

/// What an interface point reports (the seed's Figs. 10, 11, 15, 16).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct InterfaceOutputs {
    /// Accumulated shear displacement (s, a) of the material (m), opening excluded.
    pub shear: [f64; 2],
    /// Normal deformation of the material, closure positive (m), opening excluded (spec §2.12).
    pub normal: f64,
    /// Current opening (gap) ≥ 0 (m).
    pub opening: f64,
    /// Whether the point is open.
    pub open: bool,
    /// Whether the point is slipping / on the plastic branch in its last update.
    pub plastic: bool,
}

/// Parameters of any solid model, as written in a scene or a point-test file (`model:` tag).
///
/// Adding a model: one variant here, one arm in [`SolidParams::validate`], [`SolidParams::name`]
/// and [`SolidParams::visit`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum SolidParams {
    /// Isotropic linear elasticity (spec §6.3).
    Elastic(elastic::ElasticParams),
    /// Generalized-plasticity rockfill (spec §1); omitted keys take seed Table 1 values.
    RockfillGp(rockfill_gp::RockfillGpParams),
}

/// An operation generic over the solid model type, run by [`SolidParams::visit`] with the model
/// built from the parameters (enum dispatch once, monomorphized code inside).
pub trait SolidVisitor {
    /// What the operation returns.
    type Output;
    /// Runs the operation on a model.
    fn visit<M: SolidModel>(self, model: &M) -> Self::Output;
}

impl SolidParams {
    /// Checks the parameters of the selected model.
    pub fn validate(&self) -> Result<(), crate::error::ParamError> {
        match self {
            SolidParams::Elastic(p) => p.validate(),
            SolidParams::RockfillGp(p) => p.validate(),
        }
    }

    /// Mass density (kg/m³).
    pub fn density(&self) -> f64 {
        match self {
            SolidParams::Elastic(p) => p.density,
            SolidParams::RockfillGp(p) => p.density,
        }
    }

    /// The `model:` tag of the variant.
    pub fn name(&self) -> &'static str {
        match self {
            SolidParams::Elastic(_) => "elastic",
            SolidParams::RockfillGp(_) => "rockfill_gp",
        }
    }

    /// Builds the model and runs `visitor` on it (fails only for invalid parameters).
    pub fn visit<V: SolidVisitor>(&self, visitor: V) -> Result<V::Output, crate::error::ParamError> {
        Ok(match self {
            SolidParams::Elastic(p) => visitor.visit(&elastic::LinearElastic::new(p)),
            SolidParams::RockfillGp(p) => visitor.visit(&rockfill_gp::RockfillGp::new(p.clone())?),
        })
    }
}

/// Parameters of any interface or joint law, as written in a scene or a point-test file
/// (`model:` tag). Omitted fields take the seed's values (Tables 3, 4 and the joint values).
///
/// Adding a law: one variant here, one arm in [`InterfaceParams::validate`],
/// [`InterfaceParams::name`] and [`InterfaceParams::visit`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum InterfaceParams {
    /// Clough–Duncan hyperbolic interface (spec §3).
    Hyperbolic(interface_hyperbolic::HyperbolicParams),
    /// Ideal elasto-plastic Mohr–Coulomb interface (spec §4).
    MohrCoulomb(interface_mc::MohrCoulombParams),
    /// Bilinear slab joint (spec §6.1).
    Joint(joint::JointParams),
    /// 3D state-dependent generalized-plasticity interface (spec §2, seed Table 2).
    GpInterface(interface_gp::GpInterfaceParams),
}

/// An operation generic over the interface model type, run by [`InterfaceParams::visit`].
pub trait InterfaceVisitor {
    /// What the operation returns.
    type Output;
    /// Runs the operation on a model.
    fn visit<M: InterfaceModel>(self, model: &M) -> Self::Output;
}

impl InterfaceParams {
    /// Checks the parameters of the selected law.
    pub fn validate(&self) -> Result<(), crate::error::ParamError> {
        match self {
            InterfaceParams::Hyperbolic(p) => p.validate(),
            InterfaceParams::MohrCoulomb(p) => p.validate(),
            InterfaceParams::Joint(p) => p.validate(),
            InterfaceParams::GpInterface(p) => p.validate(),
        }
    }

    /// The `model:` tag of the variant.
    pub fn name(&self) -> &'static str {
        match self {
            InterfaceParams::Hyperbolic(_) => "hyperbolic",
            InterfaceParams::MohrCoulomb(_) => "mohr_coulomb",
            InterfaceParams::Joint(_) => "joint",
            InterfaceParams::GpInterface(_) => "gp_interface",
        }
    }

    /// Builds the law and runs `visitor` on it (fails only for invalid parameters).
    pub fn visit<V: InterfaceVisitor>(&self, visitor: V) -> Result<V::Output, crate::error::ParamError> {
        Ok(match self {
            InterfaceParams::Hyperbolic(p) => {
                visitor.visit(&interface_hyperbolic::HyperbolicInterface::new(p))
            }
            InterfaceParams::MohrCoulomb(p) => visitor.visit(&interface_mc::MohrCoulombInterface::new(p)),
            InterfaceParams::Joint(p) => visitor.visit(&joint::JointLaw::new(p)),
            InterfaceParams::GpInterface(p) => visitor.visit(&interface_gp::GpInterface::new(p.clone())?),
        })
    }
}

/// Parameters of any model, as written in a scene's `materials` (`model:` tag): a solid model
/// for hexahedral blocks or an interface/joint law for zero-thickness blocks.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum MaterialParams {
    /// Isotropic linear elasticity (spec §6.3).
    Elastic(elastic::ElasticParams),
    /// Generalized-plasticity rockfill (spec §1).
    RockfillGp(rockfill_gp::RockfillGpParams),
    /// Clough–Duncan hyperbolic interface (spec §3).
    Hyperbolic(interface_hyperbolic::HyperbolicParams),
    /// Ideal elasto-plastic Mohr–Coulomb interface (spec §4).
    MohrCoulomb(interface_mc::MohrCoulombParams),
    /// Bilinear slab joint (spec §6.1).
    Joint(joint::JointParams),
    /// 3D generalized-plasticity interface (spec §2).
    GpInterface(interface_gp::GpInterfaceParams),
}

/// A scene material sorted by what it applies to.
#[derive(Debug, Clone, PartialEq)]
pub enum BlockMaterial {
    /// A solid model (hexahedral blocks).
    Solid(SolidParams),
    /// An interface or joint law (zero-thickness blocks).
    Interface(InterfaceParams),
}

impl MaterialParams {
    /// The solid or interface parameters.
    pub fn split(&self) -> BlockMaterial {
        match self {
            MaterialParams::Elastic(p) => BlockMaterial::Solid(SolidParams::Elastic(p.clone())),
            MaterialParams::RockfillGp(p) => BlockMaterial::Solid(SolidParams::RockfillGp(p.clone())),
            MaterialParams::Hyperbolic(p) => BlockMaterial::Interface(InterfaceParams::Hyperbolic(p.clone())),
            MaterialParams::MohrCoulomb(p) => {
                BlockMaterial::Interface(InterfaceParams::MohrCoulomb(p.clone()))
            }
            MaterialParams::Joint(p) => BlockMaterial::Interface(InterfaceParams::Joint(p.clone())),
            MaterialParams::GpInterface(p) => {
                BlockMaterial::Interface(InterfaceParams::GpInterface(p.clone()))
            }
        }
    }

    /// Checks the parameters of the selected model.
    pub fn validate(&self) -> Result<(), crate::error::ParamError> {
        match self.split() {
            BlockMaterial::Solid(p) => p.validate(),
            BlockMaterial::Interface(p) => p.validate(),
        }
    }
}

impl BlockMaterial {
    /// The substepping options (spec §8.2) of a generalized-plasticity model, rockfill or
    /// interface; `None` for the other models.
    pub fn gp_integration(&self) -> Option<&gp_integrator::SubstepOptions> {
        match self {
            BlockMaterial::Solid(SolidParams::RockfillGp(p)) => Some(&p.integration),
            BlockMaterial::Interface(InterfaceParams::GpInterface(p)) => Some(&p.integration),
            _ => None,
        }
    }

    /// The substepping options of a generalized-plasticity model, to change
    /// ([`BlockMaterial::gp_integration`]).
    pub fn gp_integration_mut(&mut self) -> Option<&mut gp_integrator::SubstepOptions> {
        match self {
            BlockMaterial::Solid(SolidParams::RockfillGp(p)) => Some(&mut p.integration),
            BlockMaterial::Interface(InterfaceParams::GpInterface(p)) => Some(&mut p.integration),
            _ => None,
        }
    }

    /// Mass density (kg/m³) of a solid; zero for a (zero-thickness) interface.
    pub fn density(&self) -> f64 {
        match self {
            BlockMaterial::Solid(p) => p.density(),
            BlockMaterial::Interface(_) => 0.0,
        }
    }

    /// The `model:` tag.
    pub fn name(&self) -> &'static str {
        match self {
            BlockMaterial::Solid(p) => p.name(),
            BlockMaterial::Interface(p) => p.name(),
        }
    }
}
