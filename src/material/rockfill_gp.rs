//! Rockfill generalized-plasticity model: the DUT modification of Pastor–Zienkiewicz–Chan
//! (spec §1, equations (R1)–(R17); seed Table 1).
//!
//! This file holds the parameters ([`RockfillGpParams`]), the state ([`RockfillGpState`]) and
//! the *model functions* (elasticity, loading and flow directions, plastic moduli, memory
//! rules). The stress integration is the reusable explicit substepping of
//! [`crate::material::gp_integrator`] (spec §8.2); the tangent is the continuum operator
//! D^ep of the last substep (spec (R16), §8.5).
//!
//! # Units and signs
//! The boundary is SI and tension positive (Pa, [`Stress6`], [`Strain6`]). Inside, the model
//! works in **kPa, tension positive**: σ_kPa = 10⁻³·σ_Pa, and the tangent is multiplied by 10³
//! on the way out. The spec's compression-positive quantities (p, q, η, sin 3θ, ε_v^p) are
//! produced by the single function [`invariants_compression_positive`]; loading and flow
//! directions are formed in compression-positive form as in the spec and negated once
//! (`n_tension = −n_compression`), which leaves nᵀdσ, dλ and D^ep unchanged.
//!
//! # Decisions on the spec gaps (spec §10)
//! * **G1.1** H_den = exp(r_d·ε_v^p) with ε_v^p compression positive (spec (R13)).
//! * **G1.2** H_den also multiplies H_U by default (`hden_on_hu = true`); the RF-3 test of
//!   this file shows the decaying cyclic accumulation this gives and the near-constant rate
//!   without it (both readings are tested).
//! * **G1.3** `lode = pz1990` by default, without n_θ components (spec (R4)).
//! * **G1.6** softening guard on H_DM (`softening_guard = true`, spec (R12)).
//! * **G7 ξ at zero deviatoric stress**: option [`XiRule`], default
//!   [`XiRule::DeviatoricPlasticStrain`] (R11).
//!
//! # Safeguards (spec §8.6)
//! * p̂ = max(p, p_min) in every p-powered quantity and in η = q/p̂ (item 1);
//! * tension cut-off after each accepted substep: p < p_cutoff resets σ to p_min·I, keeps κ
//!   and flags the state `cut` (item 1);
//! * η ≤ η_cap = min(0.999·η_f, 3) by scaling the deviator after each accepted substep (item 1);
//! * q < 10⁻⁸·p̂: m_s from the deviator of the substep strain increment, or 0 (item 2, §1.2);
//! * H_DM, H_U,η and H_den computed in logarithms, each capped at 10¹² (item 5);
//! * H + nᵀD^e n_g ≥ 0.05·|nᵀD^e n_g| in rate and tangent (item 4, in the integrator);
//! * softening guard on H_DM (item 4, (R12)).

use super::gp_integrator::{
    integrate, Branch, GpModelFunctions, GpPoint, PlasticData, StageIncrement, SubstepOptions,
};
use super::{SolidModel, SolidUpdate};
use crate::error::{require_non_negative, require_positive, require_range, MaterialError, ParamError};
use crate::material::elastic::bulk_shear_stiffness;
use crate::tensor::{Matrix6, Strain6, Stress6, Tangent6, Vector6};
use nalgebra::{Matrix3, SVector};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Lode-angle dependence of M_g and M_f (spec §1.4, (R4)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "lowercase")]
pub enum Lode {
    /// M_g, M_f constant (the Table 1 values in every direction).
    Off,
    /// M(θ) = 18·M_c/(18 + 3(1 − sin 3θ)): M_c in compression, 0.75·M_c in extension.
    #[default]
    Pz1990,
}

/// How ξ, the accumulated plastic deviatoric strain of H_s (R11), grows (spec §10 G7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "snake_case")]
pub enum XiRule {
    /// (R11) dξ = |dε_q^p|, the deviatoric invariant of the plastic strain increment: ξ does not
    /// grow when there is no deviatoric stress nor deviatoric strain increment (isotropic
    /// compression).
    #[default]
    DeviatoricPlasticStrain,
    /// (R17) dξ = |dλ·n_gs|: ξ grows with the deviatoric *component* of the flow direction,
    /// also under isotropic compression where m_s = 0 (the triaxial p–q reading).
    FlowComponent,
}

fn default_density() -> f64 {
    2150.0
}
fn default_pa() -> f64 {
    101_300.0
}
fn default_pmin() -> f64 {
    0.05 * 101_300.0
}
fn default_p_cutoff() -> f64 {
    0.01 * 101_300.0
}
fn default_true() -> bool {
    true
}

/// Parameters of the rockfill GP model (spec §1.1 and §7). Keys as in the spec's §7 table;
/// `pa`, `pmin`, `p_cutoff` are in **Pa** (SI input). [`Default`] is seed Table 1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RockfillGpParams {
    /// Shear-modulus number G0 (–), (R2). Table 1: 1475.
    #[serde(rename = "G0")]
    pub g0: f64,
    /// Bulk-modulus number K0 (–), (R2). Table 1: 1567.
    #[serde(rename = "K0")]
    pub k0: f64,
    /// Exponent m_s of G on p (–), (R2). Table 1: 0.43.
    pub ms: f64,
    /// Exponent m_v of K on p (–), (R2). Table 1: 0.43.
    pub mv: f64,
    /// Slope M_g of the characteristic line (–), (R5), (R10). Table 1: 1.75.
    #[serde(rename = "Mg")]
    pub mg: f64,
    /// Slope M_f of the loading direction (–), (R6), (R9), (R12). Table 1: 0.90.
    #[serde(rename = "Mf")]
    pub mf: f64,
    /// Loading-direction shape parameter α_f (–), (R6). Table 1: 0.21.
    pub alpha_f: f64,
    /// Dilatancy parameter α_g (–), (R5). Table 1: 0.43.
    pub alpha_g: f64,
    /// Loading plastic-modulus number H0 (–), (R8). Table 1: 570.
    #[serde(rename = "H0")]
    pub h0: f64,
    /// Exponent m_l of H_L on p (–), (R8). Table 1: 0.18.
    pub ml: f64,
    /// Shear-hardening decay rate β0 (–), (R11). Table 1: 42.
    pub beta0: f64,
    /// Shear-hardening amplitude β1 (–), (R11). Table 1: 0.039.
    pub beta1: f64,
    /// Unloading plastic-modulus number H_u0 (–), (R14). Table 1: 1500.
    #[serde(rename = "Hu0")]
    pub hu0: f64,
    /// Exponent m_u of H_U on p (–), (R14). Table 1: 0.18.
    pub mu: f64,
    /// Densification coefficient r_d (–), (R13). Table 1: 120.
    pub rd: f64,
    /// Discrete-memory exponent γ_DM (–), (R12). Table 1: 65.
    #[serde(rename = "gammaDM")]
    pub gamma_dm: f64,
    /// Unloading-modulus exponent γ_u (–), (R14). Table 1: 7.5.
    #[serde(rename = "gammaU")]
    pub gamma_u: f64,
    /// Mass density (kg/m³). Default 2150.
    #[serde(default = "default_density")]
    pub density: f64,
    /// Atmospheric pressure p_a (**Pa**). Default 101 300.
    #[serde(default = "default_pa")]
    pub pa: f64,
    /// Pressure floor p_min of every p-powered quantity (**Pa**), spec §8.6. Default 0.05·p_a.
    #[serde(default = "default_pmin")]
    pub pmin: f64,
    /// Tension cut-off pressure p_t (**Pa**), spec §8.6: below it σ is reset to p_min·I.
    /// Default 0.01·p_a; must not exceed `pmin`.
    #[serde(default = "default_p_cutoff")]
    pub p_cutoff: f64,
    /// Lode-angle dependence (spec (R4)). Default `pz1990`.
    #[serde(default)]
    pub lode: Lode,
    /// Whether H_den also multiplies H_U (spec (R14), gap G1.2). Default true.
    #[serde(default = "default_true")]
    pub hden_on_hu: bool,
    /// Use H_DM only while H_v + H_s > 0 (spec (R12), gap G1.6). Default true.
    #[serde(default = "default_true")]
    pub softening_guard: bool,
    /// Growth of ξ when there is no deviatoric stress (spec G7). Default (R11).
    #[serde(default)]
    pub xi_rule: XiRule,
    /// Substepping options (spec §8.2).
    #[serde(default)]
    pub integration: SubstepOptions,
}

impl Default for RockfillGpParams {
    /// Seed Table 1 (main rockfill; transition and cushion use the same values).
    fn default() -> Self {
        RockfillGpParams {
            g0: 1475.0,
            k0: 1567.0,
            ms: 0.43,
            mv: 0.43,
            mg: 1.75,
            mf: 0.90,
            alpha_f: 0.21,
            alpha_g: 0.43,
            h0: 570.0,
            ml: 0.18,
            beta0: 42.0,
            beta1: 0.039,
            hu0: 1500.0,
            mu: 0.18,
            rd: 120.0,
            gamma_dm: 65.0,
            gamma_u: 7.5,
            density: default_density(),
            pa: default_pa(),
            pmin: default_pmin(),
            p_cutoff: default_p_cutoff(),
            lode: Lode::default(),
            hden_on_hu: true,
            softening_guard: true,
            xi_rule: XiRule::default(),
            integration: SubstepOptions::default(),
        }
    }
}

impl RockfillGpParams {
    /// Checks every field; the error names the input key.
    pub fn validate(&self) -> Result<(), ParamError> {
        require_positive("G0", self.g0)?;
        require_positive("K0", self.k0)?;
        require_range("ms", self.ms, 0.0, 1.0)?;
        require_range("mv", self.mv, 0.0, 1.0)?;
        require_positive("Mg", self.mg)?;
        require_positive("Mf", self.mf)?;
        require_positive("alpha_f", self.alpha_f)?;
        require_positive("alpha_g", self.alpha_g)?;
        require_positive("H0", self.h0)?;
        require_range("ml", self.ml, 0.0, 1.0)?;
        require_non_negative("beta0", self.beta0)?;
        require_non_negative("beta1", self.beta1)?;
        require_positive("Hu0", self.hu0)?;
        require_range("mu", self.mu, 0.0, 1.0)?;
        require_range("rd", self.rd, -1.0e4, 1.0e4)?;
        require_non_negative("gammaDM", self.gamma_dm)?;
        require_non_negative("gammaU", self.gamma_u)?;
        require_non_negative("density", self.density)?;
        require_positive("pa", self.pa)?;
        require_positive("pmin", self.pmin)?;
        require_range("p_cutoff", self.p_cutoff, 0.0, self.pmin)?;
        self.integration.validate("integration.")
    }
}

/// State of a rockfill GP point (spec §1.9). SI, tension positive unless named otherwise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RockfillGpState {
    /// Stress σ (Pa, tension positive).
    pub stress: Stress6,
    /// Accumulated plastic volumetric strain ε_v^p (compression positive), (R13), (R17).
    pub eps_p_vol: f64,
    /// Accumulated plastic deviatoric strain ξ, (R11), (R17).
    pub xi: f64,
    /// Largest size ζ of the loading surface reached in loading (Pa), (R12).
    pub zeta_max: f64,
    /// Stress ratio η at the last loading → unloading switch, (R14).
    pub eta_u: f64,
    /// Branch of the last accepted substep (spec §1.9 "last branch flag").
    pub branch: Branch,
    /// Plastic strain ε^p (tension positive, engineering shear), for output.
    pub eps_p: Strain6,
    /// Whether the tension cut-off (spec §8.6) acted during the update that produced this state.
    pub cut: bool,
}

/// Compression-positive invariants of a stress (spec (R1)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InvariantsCompressionPositive {
    /// Mean pressure p = −tr σ/3 (compression positive; the unit of the input).
    pub p: f64,
    /// Deviatoric stress q = √(3 J2) ≥ 0.
    pub q: f64,
    /// Lode function sin 3θ = (3√3/2)·J3/J2^{3/2} ∈ [−1, 1] of the compression-positive
    /// deviator: +1 in triaxial compression, −1 in extension, 0 when q = 0.
    pub sin3theta: f64,
    /// Compression-positive deviator s = −σ − p·I, stress-like Voigt (tensorial shear).
    pub dev: Vector6,
}

impl InvariantsCompressionPositive {
    /// η = q/p, +∞ when p ≤ 0 < q, 0 when q = 0.
    pub fn eta(&self) -> f64 {
        if self.q == 0.0 {
            0.0
        } else if self.p > 0.0 {
            self.q / self.p
        } else {
            f64::INFINITY
        }
    }
}

/// The compression-positive invariants p, q, sin 3θ and deviator of a **tension-positive**
/// Voigt stress in any unit (spec (R1)). This is the single place where the sign convention
/// of the geotechnical invariants is switched.
///
/// ```text
/// σc = −σ;  p = tr σc/3;  s = σc − p I;  J2 = ½ s:s;  q = √(3 J2);  J3 = det s
/// sin 3θ = (3√3/2)·J3/J2^{3/2}  clipped to [−1, 1]
/// ```
pub fn invariants_compression_positive(sigma: &Vector6) -> InvariantsCompressionPositive {
    let p = -(sigma[0] + sigma[1] + sigma[2]) / 3.0;
    let dev = Vector6::new(
        -sigma[0] - p,
        -sigma[1] - p,
        -sigma[2] - p,
        -sigma[3],
        -sigma[4],
        -sigma[5],
    );
    let j2 = 0.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2])
        + dev[3] * dev[3]
        + dev[4] * dev[4]
        + dev[5] * dev[5];
    let q = (3.0 * j2).sqrt();
    let sin3theta = lode_function(&dev, j2);
    InvariantsCompressionPositive { p, q, sin3theta, dev }
}

/// sin 3θ of a deviator (stress-like Voigt) with J2 given; 0 when J2 vanishes.
fn lode_function(dev: &Vector6, j2: f64) -> f64 {
    if !(j2 > 0.0) {
        return 0.0;
    }
    let m = Matrix3::new(
        dev[0], dev[3], dev[5], dev[3], dev[1], dev[4], dev[5], dev[4], dev[2],
    );
    let j3 = m.determinant();
    (1.5 * 3.0_f64.sqrt() * j3 / j2.powf(1.5)).clamp(-1.0, 1.0)
}

/// Strain-like gradient of q for a deviator `dev` with deviatoric stress `q` (spec §1.2):
/// m_s = (3/(2q))·(s11, s22, s33, 2s12, 2s23, 2s13).
fn q_gradient(dev: &Vector6, q: f64) -> Vector6 {
    let c = 1.5 / q;
    Vector6::new(
        c * dev[0],
        c * dev[1],
        c * dev[2],
        2.0 * c * dev[3],
        2.0 * c * dev[4],
        2.0 * c * dev[5],
    )
}

/// m_v = ∂p/∂σc = (1/3)(1, 1, 1, 0, 0, 0) (spec §1.2).
fn m_v() -> Vector6 {
    let t = 1.0 / 3.0;
    Vector6::new(t, t, t, 0.0, 0.0, 0.0)
}

/// Largest factor allowed for H_DM, H_U,η and H_den, as a logarithm (spec §8.6 item 5).
const LN_FACTOR_CAP: f64 = 27.631_021_115_928_547; // ln(1e12)
/// q below this fraction of p̂ counts as "no deviatoric stress" (spec §1.2).
const Q_TOL: f64 = 1.0e-8;
/// η_u below this makes unloading elastic (H_U = ∞), spec (R14).
const ETA_U_MIN: f64 = 1.0e-4;
/// Upper bound of η (spec §8.6 item 1): η ≤ min(0.999·η_f, ETA_CAP_ABS).
const ETA_CAP_ABS: f64 = 3.0;
/// Number of rate-integrated internal variables: ε_v^p, ξ, ε^p (6).
const NK: usize = 8;

/// Memory variables of a point in model units (kPa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RockfillMemory {
    /// ζ_max (kPa), (R12).
    pub zeta_max: f64,
    /// η_u, (R14).
    pub eta_u: f64,
    /// Tension cut-off acted in this update.
    pub cut: bool,
}

type Point = GpPoint<6, NK, RockfillMemory>;

/// The rockfill GP model built from validated parameters. Immutable.
#[derive(Debug, Clone, PartialEq)]
pub struct RockfillGp {
    params: RockfillGpParams,
    /// p_a in kPa.
    pa: f64,
    /// p_min in kPa.
    pmin: f64,
    /// p_cutoff in kPa.
    p_cutoff: f64,
}

/// Local kinematic quantities at a state (compression positive, kPa).
struct Local {
    /// p̂ = max(p, p_min).
    p_hat: f64,
    /// η = q/p̂.
    eta: f64,
    /// m_s (strain-like), or 0 when there is no deviatoric direction.
    m_s: Vector6,
    /// M_g(θ).
    mg: f64,
    /// M_f(θ).
    mf: f64,
}

impl RockfillGp {
    /// Builds the model after validating the parameters.
    pub fn new(params: RockfillGpParams) -> Result<Self, ParamError> {
        params.validate()?;
        Ok(RockfillGp {
            pa: params.pa * 1.0e-3,
            pmin: params.pmin * 1.0e-3,
            p_cutoff: params.p_cutoff * 1.0e-3,
            params,
        })
    }

    /// The parameters the model was built from.
    pub fn params(&self) -> &RockfillGpParams {
        &self.params
    }

    /// Bulk and shear moduli K, G (kPa) at p̂ (spec (R2)):
    ///
    /// ```text
    /// K = K0·pa·(p̂/pa)^mv,   G = G0·pa·(p̂/pa)^ms
    /// ```
    fn moduli(&self, p_hat: f64) -> (f64, f64) {
        let r = p_hat / self.pa;
        (
            self.params.k0 * self.pa * r.powf(self.params.mv),
            self.params.g0 * self.pa * r.powf(self.params.ms),
        )
    }

    /// Elastic matrix D^e (kPa) at a tension-positive stress in kPa (spec (R2), (R3)).
    fn elastic_kpa(&self, sigma: &Vector6) -> Matrix6 {
        let p = -(sigma[0] + sigma[1] + sigma[2]) / 3.0;
        let (k, g) = self.moduli(p.max(self.pmin));
        bulk_shear_stiffness(k, g)
    }

    /// The elastic tangent D^e (Pa) at a state (spec (R3)); used as a fallback tangent.
    pub fn elastic_tangent(&self, state: &RockfillGpState) -> Tangent6 {
        Tangent6(self.elastic_kpa(&(state.stress.0 * 1.0e-3)) * 1.0e3)
    }

    /// Lode-dependent slope (spec (R4)): M(θ) = 18·M_c/(18 + 3(1 − sin 3θ)).
    fn lode_slope(&self, m_c: f64, sin3theta: f64) -> f64 {
        match self.params.lode {
            Lode::Off => m_c,
            Lode::Pz1990 => 18.0 * m_c / (18.0 + 3.0 * (1.0 - sin3theta)),
        }
    }

    /// Local quantities at a tension-positive kPa stress (spec (R1), (R4), §1.2).
    ///
    /// When q < 10⁻⁸·p̂ the deviatoric direction and the Lode angle come from the deviator of
    /// the (sub)step strain increment `d_eps` (compression positive); if that is also below
    /// 10⁻¹⁰·‖dε‖, m_s = 0 and sin 3θ = 1 (the compression values of M_g, M_f apply).
    fn local(&self, sigma: &Vector6, d_eps: &Vector6) -> Local {
        let inv = invariants_compression_positive(sigma);
        let p_hat = inv.p.max(self.pmin);
        let (m_s, sin3theta, q) = if inv.q >= Q_TOL * p_hat {
            (q_gradient(&inv.dev, inv.q), inv.sin3theta, inv.q)
        } else {
            // Trial direction: deviator of −dε with tensorial shear (compression positive).
            let tr = -(d_eps[0] + d_eps[1] + d_eps[2]) / 3.0;
            let e = Vector6::new(
                -d_eps[0] - tr,
                -d_eps[1] - tr,
                -d_eps[2] - tr,
                -0.5 * d_eps[3],
                -0.5 * d_eps[4],
                -0.5 * d_eps[5],
            );
            let j2 = 0.5 * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) + e[3] * e[3] + e[4] * e[4] + e[5] * e[5];
            let q_d = (3.0 * j2).sqrt();
            if q_d > 1.0e-10 * d_eps.norm() && q_d > 0.0 {
                (q_gradient(&e, q_d), lode_function(&e, j2), inv.q)
            } else {
                (Vector6::zeros(), 1.0, inv.q)
            }
        };
        Local {
            p_hat,
            eta: q / p_hat,
            m_s,
            mg: self.lode_slope(self.params.mg, sin3theta),
            mf: self.lode_slope(self.params.mf, sin3theta),
        }
    }

    /// η_f = (1 + 1/α_f)·M_f (spec (R9)).
    fn eta_f(&self, mf: f64) -> f64 {
        (1.0 + 1.0 / self.params.alpha_f) * mf
    }

    /// ln ζ of the PZ loading surface through the state (spec (R12)):
    ///
    /// ```text
    /// ζ = p̂·[1 − (α_f/(1+α_f))·(η/M_f)]^{−1/α_f},   η ≤ 0.999·η_f
    /// ```
    fn ln_zeta(&self, p_hat: f64, eta: f64, mf: f64) -> f64 {
        let af = self.params.alpha_f;
        let eta_c = eta.min(0.999 * self.eta_f(mf));
        let bracket = 1.0 - af / (1.0 + af) * eta_c / mf;
        p_hat.ln() - bracket.ln() / af
    }

    /// ln H_den = r_d·ε_v^p, capped at ln 10¹² (spec (R13), §8.6 item 5).
    fn ln_hden(&self, eps_p_vol: f64) -> f64 {
        (self.params.rd * eps_p_vol).min(LN_FACTOR_CAP)
    }

    /// Loading plastic modulus H_L (kPa), spec (R8)–(R13):
    ///
    /// ```text
    /// H_L = H0·pa·(p̂/pa)^ml · H_f·(H_v + H_s) · H_DM · H_den
    /// H_f = ⟨1 − η/η_f⟩⁴;  H_v = 1 − η/M_g;  H_s = β0·β1·exp(−β0·ξ)
    /// H_DM = (max(ζ_max, ζ)/ζ)^γDM   (1 if softening_guard and H_v + H_s ≤ 0)
    /// H_den = exp(r_d·ε_v^p)
    /// ```
    /// ζ_max is taken as max(ζ_max, ζ) so that H_DM ≥ 1 also inside a substep, before the
    /// memory update of the accepted substep.
    fn h_loading(&self, loc: &Local, kappa: &SVector<f64, NK>, mem: &RockfillMemory) -> f64 {
        let p = &self.params;
        let hf = (1.0 - loc.eta / self.eta_f(loc.mf)).max(0.0).powi(4);
        let hv = 1.0 - loc.eta / loc.mg;
        let hs = p.beta0 * p.beta1 * (-p.beta0 * kappa[1]).exp();
        let ln_dm = if p.softening_guard && hv + hs <= 0.0 {
            0.0
        } else {
            let ln_z = self.ln_zeta(loc.p_hat, loc.eta, loc.mf);
            let ln_zmax = mem.zeta_max.max(f64::MIN_POSITIVE).ln().max(ln_z);
            (p.gamma_dm * (ln_zmax - ln_z)).min(LN_FACTOR_CAP)
        };
        let base = p.h0 * self.pa * (loc.p_hat / self.pa).powf(p.ml) * hf * (hv + hs);
        base * (ln_dm + self.ln_hden(kappa[0])).exp()
    }

    /// Unloading plastic modulus H_U (kPa), spec (R14):
    ///
    /// ```text
    /// H_U = Hu0·pa·(p̂/pa)^mu · H_U,η · H_den^(U)
    /// H_U,η = (M_g/η_u)^γu if M_g/η_u > 1, else 1;   H_U = ∞ if η_u < 1e-4
    /// H_den^(U) = H_den if hden_on_hu, else 1
    /// ```
    fn h_unloading(&self, loc: &Local, kappa: &SVector<f64, NK>, mem: &RockfillMemory) -> f64 {
        let p = &self.params;
        if mem.eta_u < ETA_U_MIN {
            return f64::INFINITY;
        }
        let ratio = loc.mg / mem.eta_u;
        let ln_u = if ratio > 1.0 {
            (p.gamma_u * ratio.ln()).min(LN_FACTOR_CAP)
        } else {
            0.0
        };
        let ln_den = if p.hden_on_hu { self.ln_hden(kappa[0]) } else { 0.0 };
        p.hu0 * self.pa * (loc.p_hat / self.pa).powf(p.mu) * (ln_u + ln_den).exp()
    }

    /// Converts a state to the integrator's point (kPa).
    fn to_point(&self, s: &RockfillGpState) -> Point {
        let mut kappa = SVector::<f64, NK>::zeros();
        kappa[0] = s.eps_p_vol;
        kappa[1] = s.xi;
        for i in 0..6 {
            kappa[2 + i] = s.eps_p.0[i];
        }
        GpPoint {
            sigma: s.stress.0 * 1.0e-3,
            kappa,
            memory: RockfillMemory {
                zeta_max: s.zeta_max * 1.0e-3,
                eta_u: s.eta_u,
                cut: false,
            },
        }
    }

    /// Converts an integrator point back to a state (SI).
    fn from_point(pt: &Point, branch: Branch) -> RockfillGpState {
        RockfillGpState {
            stress: Stress6(pt.sigma * 1.0e3),
            eps_p_vol: pt.kappa[0],
            xi: pt.kappa[1],
            zeta_max: pt.memory.zeta_max * 1.0e3,
            eta_u: pt.memory.eta_u,
            branch,
            eps_p: Strain6(Vector6::from_fn(|i, _| pt.kappa[2 + i])),
            cut: pt.memory.cut,
        }
    }

    /// Tension cut-off and η cap on a kPa tension-positive stress (spec §8.6 item 1).
    /// Returns true when the cut-off reset the stress.
    fn apply_stress_limits(&self, sigma: &mut Vector6) -> bool {
        let inv = invariants_compression_positive(sigma);
        if !(inv.p >= self.p_cutoff) {
            *sigma = Vector6::new(-self.pmin, -self.pmin, -self.pmin, 0.0, 0.0, 0.0);
            return true;
        }
        let mf = self.lode_slope(self.params.mf, inv.sin3theta);
        let eta_cap = (0.999 * self.eta_f(mf)).min(ETA_CAP_ABS);
        if inv.q > eta_cap * inv.p {
            let scale = eta_cap * inv.p / inv.q;
            let s = inv.dev * scale;
            *sigma = -Vector6::new(
                s[0] + inv.p,
                s[1] + inv.p,
                s[2] + inv.p,
                s[3],
                s[4],
                s[5],
            );
        }
        false
    }
}

impl GpModelFunctions<6, NK> for RockfillGp {
    type Memory = RockfillMemory;

    fn elastic_matrix(&self, point: &Point) -> Matrix6 {
        self.elastic_kpa(&point.sigma)
    }

    /// Directions (R5)–(R7) and moduli (R8)/(R14), returned tension positive (n = −n_c).
    fn plastic_data(&self, point: &Point, branch: Branch, d_eps: &Vector6) -> Result<PlasticData<6>, MaterialError> {
        let loc = self.local(&point.sigma, d_eps);
        let p = &self.params;
        let mv = m_v();
        let d_f = (1.0 + p.alpha_f) * (loc.mf - loc.eta);
        let nf = (1.0 + d_f * d_f).sqrt();
        let n_c = mv * (d_f / nf) + loc.m_s * (1.0 / nf);
        let d_g = (1.0 + p.alpha_g) * (loc.mg - loc.eta);
        let ng = (1.0 + d_g * d_g).sqrt();
        let (n_gv, n_gs) = (d_g / ng, 1.0 / ng);
        let (n_g_c, h) = match branch {
            Branch::Loading => (mv * n_gv + loc.m_s * n_gs, self.h_loading(&loc, &point.kappa, &point.memory)),
            Branch::Unloading => (
                mv * (-n_gv.abs()) + loc.m_s * n_gs,
                self.h_unloading(&loc, &point.kappa, &point.memory),
            ),
            Branch::Elastic => return Err(MaterialError::new("rockfill GP: plastic data of the elastic branch")),
        };
        if !h.is_nan() && n_c.iter().chain(n_g_c.iter()).all(|x| x.is_finite()) {
            Ok(PlasticData {
                n: -n_c,
                n_g: -n_g_c,
                h,
            })
        } else {
            Err(MaterialError::new(format!(
                "rockfill GP: non-finite plastic data at p = {:.4e} kPa, η = {:.4e}",
                loc.p_hat, loc.eta
            )))
        }
    }

    /// (R17): dε_v^p = dλ·tr(n_g_c), dξ per [`XiRule`], dε^p = dλ·n_g.
    fn kappa_increment(&self, _point: &Point, stage: &StageIncrement<'_, 6>) -> SVector<f64, NK> {
        let mut dk = SVector::<f64, NK>::zeros();
        let Some(data) = stage.plastic else {
            return dk;
        };
        let dl = stage.d_lambda;
        let g = &data.n_g;
        // Compression-positive volumetric component of the flow direction: n_gv = −tr(n_g).
        let n_gv = -(g[0] + g[1] + g[2]);
        dk[0] = dl * n_gv;
        dk[1] = match self.params.xi_rule {
            XiRule::DeviatoricPlasticStrain => dl.abs() * deviatoric_invariant(g),
            XiRule::FlowComponent => dl.abs() * (1.0 - n_gv * n_gv).max(0.0).sqrt(),
        };
        for i in 0..6 {
            dk[2 + i] = dl * g[i];
        }
        dk
    }

    /// Tension cut-off, η cap, and in loading ζ_max ← max(ζ_max, ζ), η_u ← η (spec (R12),
    /// (R17), §8.6). Setting η_u in every loading substep stores the ratio at the last
    /// loading → unloading switch.
    fn after_accept(&self, point: &mut Point, branch: Branch) -> Result<Branch, MaterialError> {
        if self.apply_stress_limits(&mut point.sigma) {
            point.memory.cut = true;
            return Ok(Branch::Elastic);
        }
        if branch == Branch::Loading {
            let inv = invariants_compression_positive(&point.sigma);
            let p_hat = inv.p.max(self.pmin);
            let eta = inv.q / p_hat;
            let mf = self.lode_slope(self.params.mf, inv.sin3theta);
            let zeta = self.ln_zeta(p_hat, eta, mf).exp();
            point.memory.zeta_max = point.memory.zeta_max.max(zeta);
            point.memory.eta_u = eta;
        }
        Ok(branch)
    }

    /// p_a for the stress; 10⁻³ for every strain-like internal variable.
    fn error_scales(&self) -> (f64, SVector<f64, NK>) {
        (self.pa, SVector::<f64, NK>::repeat(1.0e-3))
    }
}

/// ε_q = √(2/3·e:e) of a strain-like Voigt vector (engineering shear).
pub fn deviatoric_invariant(eps: &Vector6) -> f64 {
    let tr = (eps[0] + eps[1] + eps[2]) / 3.0;
    let (a, b, c) = (eps[0] - tr, eps[1] - tr, eps[2] - tr);
    let ee = a * a + b * b + c * c + 0.5 * (eps[3] * eps[3] + eps[4] * eps[4] + eps[5] * eps[5]);
    (2.0 / 3.0 * ee).sqrt()
}

impl SolidModel for RockfillGp {
    type State = RockfillGpState;

    fn symmetric_tangent(&self) -> bool {
        false
    }

    /// Virgin state at σ0 (spec §1.9): ζ_max = ζ(σ0), η_u = η0, ξ = ε_v^p = 0. A σ0 below the
    /// tension cut-off is replaced by p_min·I (flagged `cut`); η is capped (spec §8.6).
    fn init_state(&self, sigma0: &Stress6) -> Result<RockfillGpState, MaterialError> {
        if !sigma0.0.iter().all(|x| x.is_finite()) {
            return Err(MaterialError::new("rockfill GP: non-finite initial stress"));
        }
        let mut sigma = sigma0.0 * 1.0e-3;
        let cut = self.apply_stress_limits(&mut sigma);
        let inv = invariants_compression_positive(&sigma);
        let p_hat = inv.p.max(self.pmin);
        let eta = inv.q / p_hat;
        let mf = self.lode_slope(self.params.mf, inv.sin3theta);
        Ok(RockfillGpState {
            stress: Stress6(sigma * 1.0e3),
            eps_p_vol: 0.0,
            xi: 0.0,
            zeta_max: self.ln_zeta(p_hat, eta, mf).exp() * 1.0e3,
            eta_u: eta,
            branch: Branch::Elastic,
            eps_p: Strain6::default(),
            cut,
        })
    }

    fn update(&self, prev: &RockfillGpState, d_eps: &Strain6) -> Result<SolidUpdate<RockfillGpState>, MaterialError> {
        let start = self.to_point(prev);
        let res = integrate(self, &start, &d_eps.0, prev.branch, &self.params.integration)?;
        let state = if res.substeps == 0 {
            prev.clone()
        } else {
            Self::from_point(&res.point, res.last_branch)
        };
        Ok(SolidUpdate {
            state,
            tangent: Tangent6(res.tangent * 1.0e3),
            kind: res.kind,
            substeps: res.substeps.max(1),
        })
    }

    fn stress(state: &RockfillGpState) -> Stress6 {
        state.stress
    }
}
