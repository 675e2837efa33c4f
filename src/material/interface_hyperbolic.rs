//! Clough–Duncan hyperbolic interface (spec §3, eqs. (H1)–(H8)), integrated by substepped forward
//! Euler (spec §8.4).
//!
//! The law is nonlinear-elastic (hypo-elastic) in shear with a stress-level memory for
//! unloading/reloading, and a stiff penalty spring with opening memory in the normal direction
//! (the same normal law as the Mohr–Coulomb interface, [`super::interface_mc::ContactStep`]).
//!
//! # References
//! Clough G.W., Duncan J.M. (1971). Finite element analysis of retaining wall behavior.

use super::interface_mc::{
    goodman_outputs, janbu_stiffness, open_tangent, ContactStep, GAMMA_W_DEFAULT, PA_DEFAULT,
    SIGMA_MIN_DEFAULT,
};
use super::{InterfaceModel, InterfaceOutputs, InterfaceUpdate, TangentKind};
use crate::error::{require_non_negative, require_positive, require_range, MaterialError, ParamError};
use crate::tensor::{Local3, Tangent3};
use nalgebra::Vector2;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Tolerance on SL in the primary-loading test of (H5): SL ≥ SL_max − tol.
const SL_TOL: f64 = 1e-9;
/// Largest number of substeps of one update before it fails (the solver then cuts the step).
const MAX_SUBSTEPS: u32 = 200_000;

/// How the stress level of the two shear directions is formed (spec (H6), gap G3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum StressLevelMode {
    /// SL = ‖τ‖/τ_f with one stiffness for both directions (default, isotropic).
    #[default]
    Resultant,
    /// SL_i = |τ_i|/τ_f per direction, each with its own memory (not isotropic).
    PerDirection,
}

/// Parameters of the hyperbolic interface (seed Table 3 in SI by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HyperbolicParams {
    /// Shear stiffness number k1 (−). Seed Table 3: 600.
    pub k1: f64,
    /// Normal (penalty) stiffness k2 (Pa/m). Seed Table 3: 1×10⁷ kPa/m = 1×10¹⁰ Pa/m.
    pub k2: f64,
    /// Stiffness exponent n (−). Seed Table 3: 0.85.
    pub n: f64,
    /// Friction angle φ (degrees). Seed Table 3: 41.5.
    pub phi: f64,
    /// Failure ratio R_f (−). Seed Table 3: 0.9.
    pub rf: f64,
    /// Cohesion c (Pa). Seed Table 3: 0.
    pub c: f64,
    /// Unloading/reloading stiffness number k_ur (−); absent = k1 (spec (H5), gap G3).
    pub kur: Option<f64>,
    /// Unit weight of water γ_w (N/m³), default 9810 (spec §0.2).
    pub gamma_w: f64,
    /// Atmospheric pressure p_a (Pa), default 101300.
    pub pa: f64,
    /// Normal-stress floor σ_min in the stiffness formula (Pa), default 1000 (spec §8.6).
    pub sigma_min: f64,
    /// Stress-level cap SL_cap in the tangent stiffness (spec (H8)), default 0.99.
    pub sl_cap: f64,
    /// Resultant (default) or per-direction stress level (spec (H6)).
    pub stress_level: StressLevelMode,
    /// Largest change of SL per substep, relative to (1 − R_f·SL); default 0.02 (spec §8.4).
    pub max_sl_change: f64,
}

impl Default for HyperbolicParams {
    fn default() -> Self {
        HyperbolicParams {
            k1: 600.0,
            k2: 1.0e10,
            n: 0.85,
            phi: 41.5,
            rf: 0.9,
            c: 0.0,
            kur: None,
            gamma_w: GAMMA_W_DEFAULT,
            pa: PA_DEFAULT,
            sigma_min: SIGMA_MIN_DEFAULT,
            sl_cap: 0.99,
            stress_level: StressLevelMode::Resultant,
            max_sl_change: 0.02,
        }
    }
}

impl HyperbolicParams {
    /// Checks the ranges: k1, k2, kur, γ_w, p_a, σ_min > 0; 0 ≤ n ≤ 2; 0 ≤ φ < 90°; 0 < R_f ≤ 1;
    /// c ≥ 0; 0 < SL_cap < 1; 0 < max_sl_change ≤ 0.5.
    pub fn validate(&self) -> Result<(), ParamError> {
        require_positive("k1", self.k1)?;
        require_positive("k2", self.k2)?;
        require_range("n", self.n, 0.0, 2.0)?;
        require_range("phi", self.phi, 0.0, 89.0)?;
        require_range("rf", self.rf, 1e-6, 1.0)?;
        require_non_negative("c", self.c)?;
        if let Some(kur) = self.kur {
            require_positive("kur", kur)?;
        }
        require_positive("gamma_w", self.gamma_w)?;
        require_positive("pa", self.pa)?;
        require_positive("sigma_min", self.sigma_min)?;
        require_range("sl_cap", self.sl_cap, 1e-3, 0.999_999)?;
        require_range("max_sl_change", self.max_sl_change, 1e-8, 0.5)
    }
}

/// State of a hyperbolic interface point (spec §3.2, "State variables").
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct HyperbolicState {
    /// Shear traction τ = (τ_s, τ_a) (Pa).
    pub tau: [f64; 2],
    /// Normal stress σ_n (Pa, **compression positive**); the traction's t_n is −σ_n.
    pub sigma_n: f64,
    /// Total closure w = −δ_n since activation (m).
    pub closure: f64,
    /// Reference closure w0 at which σ_n = 0 (m); w < w0 is open with gap w0 − w.
    pub closure_ref: f64,
    /// Accumulated shear displacement while closed (m), output only.
    pub shear: [f64; 2],
    /// Largest resultant stress level reached, SL_max (used in `resultant` mode).
    pub sl_max: f64,
    /// Largest stress level per direction (s, a) (used in `per_direction` mode).
    pub sl_max_dir: [f64; 2],
    /// Whether the last substep was on primary loading (H3) rather than unload/reload (H5).
    pub primary: bool,
}

/// The Clough–Duncan hyperbolic interface law (spec §3).
#[derive(Debug, Clone, PartialEq)]
pub struct HyperbolicInterface {
    p: HyperbolicParams,
    tan_phi: f64,
    kur: f64,
}

impl HyperbolicInterface {
    /// Builds the law (parameters must have passed [`HyperbolicParams::validate`]).
    pub fn new(p: &HyperbolicParams) -> Self {
        HyperbolicInterface {
            p: p.clone(),
            tan_phi: p.phi.to_radians().tan(),
            kur: p.kur.unwrap_or(p.k1),
        }
    }

    /// The parameters.
    pub fn params(&self) -> &HyperbolicParams {
        &self.p
    }

    /// Shear strength τ_f = c + σ_n·tan φ (spec (H1)), Pa.
    pub fn strength(&self, sigma_n: f64) -> f64 {
        self.p.c + sigma_n.max(0.0) * self.tan_phi
    }

    /// Initial shear stiffness k_si = k1·γ_w·(σ̂_n/p_a)^n (spec (H2)), Pa/m.
    pub fn initial_stiffness(&self, sigma_n: f64) -> f64 {
        let p = &self.p;
        janbu_stiffness(p.k1, p.gamma_w, p.pa, p.n, p.sigma_min, sigma_n).0
    }

    /// Unloading/reloading stiffness k_sur = k_ur·γ_w·(σ̂_n/p_a)^n (spec (H5)), Pa/m.
    pub fn unload_stiffness(&self, sigma_n: f64) -> f64 {
        let p = &self.p;
        janbu_stiffness(self.kur, p.gamma_w, p.pa, p.n, p.sigma_min, sigma_n).0
    }

    /// Closed-form τ(u) of monotonic loading under constant σ_n (spec (H4)), Pa.
    ///
    /// ```text
    /// τ(u) = u / (1/k_si + R_f·u/τ_f)
    /// ```
    pub fn closed_form(&self, sigma_n: f64, u: f64) -> f64 {
        u / (1.0 / self.initial_stiffness(sigma_n) + self.p.rf * u / self.strength(sigma_n))
    }

    /// Shear strength used as a divisor (positive even at σ_n = 0 and c = 0).
    fn strength_floor(&self, sigma_n: f64) -> f64 {
        self.strength(sigma_n).max(1e-9 * self.p.pa)
    }

    /// Branch of one stress level at a substep start (spec (H5)): primary loading if
    /// SL ≥ SL_max − tol and τ·Δτ ≥ 0, otherwise unloading/reloading.
    fn is_primary(sl: f64, sl_max: f64, tau_dot_inc: f64) -> bool {
        sl >= sl_max - SL_TOL && tau_dot_inc >= 0.0
    }

    /// Shear stiffness of a branch (spec (H3), (H5), (H8)):
    ///
    /// ```text
    /// primary:        k_st = k_si·(1 − R_f·min(SL, SL_cap))²
    /// unload/reload:  k_sur = k_ur·γ_w·(σ̂_n/p_a)^n
    /// ```
    fn branch_stiffness(&self, primary: bool, sl: f64, sigma_n: f64) -> f64 {
        if primary {
            let reserve = 1.0 - self.p.rf * sl.min(self.p.sl_cap);
            self.initial_stiffness(sigma_n) * reserve * reserve
        } else {
            self.unload_stiffness(sigma_n)
        }
    }

    /// Largest substep fraction allowed by the stress-level and normal-stress controls (§8.4):
    /// ΔSL ≤ max_sl_change·(1 − R_f·SL) on primary loading (a stricter form of the spec's
    /// ΔSL ≤ 0.02, uniform in accuracy up to SL_cap), relative change of σ̂_n ≤ max_sl_change.
    fn substep_limit(
        &self,
        primary: bool,
        sl: f64,
        rate: f64,
        tau_f: f64,
        sigma_t: f64,
        d_sigma: f64,
    ) -> f64 {
        let dsl = self.p.max_sl_change;
        let mut h = f64::INFINITY;
        if primary && rate > 0.0 {
            h = h.min(dsl * (1.0 - self.p.rf * sl.min(self.p.sl_cap)) * tau_f / rate);
        }
        if d_sigma != 0.0 && rate > 0.0 {
            h = h.min(dsl * sigma_t.max(self.p.sigma_min) / d_sigma.abs());
        }
        h
    }

    /// Fails an update that needs too many substeps.
    fn check_substeps(substeps: u32, sigma_n: f64) -> Result<(), MaterialError> {
        if substeps > MAX_SUBSTEPS {
            Err(MaterialError::new(format!(
                "hyperbolic interface: more than {MAX_SUBSTEPS} substeps (sigma_n = {sigma_n:.4e} Pa)"
            )))
        } else {
            Ok(())
        }
    }

    /// Shear integration of the closed part of a step (spec §8.4), resultant SL (H6).
    /// A reloading substep stops where ‖τ‖ meets SL_max·τ_f, so primary loading resumes there.
    fn integrate_resultant(
        &self,
        state: &mut HyperbolicState,
        inc: Vector2<f64>,
        sigma0: f64,
        sigma1: f64,
    ) -> Result<u32, MaterialError> {
        let mut tau = Vector2::new(state.tau[0], state.tau[1]);
        let mut t = 0.0;
        let mut substeps = 0;
        while t < 1.0 {
            let sigma_t = sigma0 + t * (sigma1 - sigma0);
            let tau_f = self.strength_floor(sigma_t);
            let sl = tau.norm() / tau_f;
            let primary = Self::is_primary(sl, state.sl_max, tau.dot(&inc));
            let v_t = inc * self.branch_stiffness(primary, sl, sigma_t);
            let mut h =
                (1.0 - t).min(self.substep_limit(primary, sl, v_t.norm(), tau_f, sigma_t, sigma1 - sigma0));
            let radius = state.sl_max * tau_f;
            if !primary && v_t.norm() > 0.0 && tau.norm() < radius {
                let (a, b, c) = (
                    v_t.norm_squared(),
                    2.0 * tau.dot(&v_t),
                    tau.norm_squared() - radius * radius,
                );
                h = h.min((-b + (b * b - 4.0 * a * c).max(0.0).sqrt()) / (2.0 * a));
            }
            // σ_n first (spec §8.4), then the shear at the updated σ_n.
            let sigma_h = sigma0 + (t + h) * (sigma1 - sigma0);
            let tau_f_h = self.strength_floor(sigma_h);
            tau += inc * (self.branch_stiffness(primary, tau.norm() / tau_f_h, sigma_h) * h);
            let strength = self.strength(sigma_h);
            if tau.norm() > strength {
                tau *= strength / tau.norm();
            }
            state.sl_max = state.sl_max.max(tau.norm() / tau_f_h);
            state.primary = primary;
            t += h;
            substeps += 1;
            Self::check_substeps(substeps, sigma_h)?;
        }
        state.tau = [tau[0], tau[1]];
        Ok(substeps)
    }

    /// Shear integration of the closed part of a step, per-direction SL (option of (H6)).
    fn integrate_per_direction(
        &self,
        state: &mut HyperbolicState,
        inc: Vector2<f64>,
        sigma0: f64,
        sigma1: f64,
    ) -> Result<u32, MaterialError> {
        let mut t = 0.0;
        let mut substeps = 0;
        while t < 1.0 {
            let sigma_t = sigma0 + t * (sigma1 - sigma0);
            let tau_f = self.strength_floor(sigma_t);
            let mut h = 1.0 - t;
            let mut primary = [true; 2];
            for i in 0..2 {
                let tau = state.tau[i];
                let sl = tau.abs() / tau_f;
                primary[i] = Self::is_primary(sl, state.sl_max_dir[i], tau * inc[i]);
                let v = inc[i] * self.branch_stiffness(primary[i], sl, sigma_t);
                h = h.min(self.substep_limit(primary[i], sl, v.abs(), tau_f, sigma_t, sigma1 - sigma0));
                let radius = state.sl_max_dir[i] * tau_f;
                if !primary[i] && v != 0.0 && tau.abs() < radius {
                    h = h.min((radius * v.signum() - tau) / v);
                }
            }
            let sigma_h = sigma0 + (t + h) * (sigma1 - sigma0);
            let tau_f_h = self.strength_floor(sigma_h);
            let strength = self.strength(sigma_h);
            for i in 0..2 {
                let tau = state.tau[i];
                let k = self.branch_stiffness(primary[i], tau.abs() / tau_f_h, sigma_h);
                let next = (tau + k * inc[i] * h).clamp(-strength, strength);
                state.tau[i] = next;
                state.sl_max_dir[i] = state.sl_max_dir[i].max(next.abs() / tau_f_h);
            }
            state.primary = primary[0] || primary[1];
            t += h;
            substeps += 1;
            Self::check_substeps(substeps, sigma_h)?;
        }
        Ok(substeps)
    }

    /// Continuum tangent at the end state: D = diag(k_1, k_2, k2) (spec §8.4).
    fn end_tangent(&self, state: &HyperbolicState, inc: Vector2<f64>) -> Tangent3 {
        let sigma = state.sigma_n;
        let tau_f = self.strength_floor(sigma);
        let tau = Vector2::new(state.tau[0], state.tau[1]);
        let diag = match self.p.stress_level {
            StressLevelMode::Resultant => {
                let sl = tau.norm() / tau_f;
                let k = self.branch_stiffness(Self::is_primary(sl, state.sl_max, tau.dot(&inc)), sl, sigma);
                Local3::new(k, k, self.p.k2)
            }
            StressLevelMode::PerDirection => {
                let k = |i: usize| {
                    let sl = tau[i].abs() / tau_f;
                    self.branch_stiffness(
                        Self::is_primary(sl, state.sl_max_dir[i], tau[i] * inc[i]),
                        sl,
                        sigma,
                    )
                };
                Local3::new(k(0), k(1), self.p.k2)
            }
        };
        Tangent3::from_diagonal(&diag)
    }
}

impl InterfaceModel for HyperbolicInterface {
    type State = HyperbolicState;

    fn symmetric_tangent(&self) -> bool {
        true
    }

    fn init_state(&self, sigma_n0: f64) -> Result<HyperbolicState, MaterialError> {
        if !(sigma_n0.is_finite() && sigma_n0 >= 0.0) {
            return Err(MaterialError::new(format!(
                "initial normal stress must be finite and >= 0, got {sigma_n0} Pa"
            )));
        }
        Ok(HyperbolicState {
            sigma_n: sigma_n0,
            closure_ref: -sigma_n0 / self.p.k2,
            primary: true,
            ..HyperbolicState::default()
        })
    }

    /// Normal law first (H7: σ_n = k2·⟨w − w0⟩ with the gap memory of (M2)/(M7)), then the shear
    /// by forward Euler substeps (spec §8.4) with branch (H5) frozen per substep, σ_n interpolated
    /// linearly over the step, SL capped in the stiffness and τ capped at τ_f (H8). While open:
    /// τ = 0, σ_n = 0 and the regularized tangent of (H7); on re-closure τ restarts from 0 and the
    /// stress-level memory is kept. The tangent is the continuum one at the end state.
    fn update(
        &self,
        prev: &HyperbolicState,
        d_jump: &Local3,
    ) -> Result<InterfaceUpdate<HyperbolicState>, MaterialError> {
        if !d_jump.iter().all(|v| v.is_finite()) {
            return Err(MaterialError::new("non-finite jump increment"));
        }
        let p = &self.p;
        let contact = ContactStep::new(prev.closure, prev.closure_ref, p.k2, d_jump[2]);
        let inc = Vector2::new(d_jump[0], d_jump[1]) * contact.shear_fraction;
        let mut state = *prev;
        state.closure = contact.closure;
        state.shear = [prev.shear[0] + inc[0], prev.shear[1] + inc[1]];
        if contact.open {
            state.tau = [0.0; 2];
            state.sigma_n = 0.0;
            state.primary = false;
            return Ok(InterfaceUpdate {
                state,
                tangent: open_tangent(self.initial_stiffness(0.0), p.k2),
                kind: TangentKind::Elastic,
                substeps: 1,
            });
        }
        if contact.was_open {
            state.tau = [0.0; 2];
        }
        let (sigma0, sigma1) = (contact.sigma_start, contact.sigma_end);
        let substeps = match p.stress_level {
            StressLevelMode::Resultant => self.integrate_resultant(&mut state, inc, sigma0, sigma1)?,
            StressLevelMode::PerDirection => self.integrate_per_direction(&mut state, inc, sigma0, sigma1)?,
        };
        state.sigma_n = sigma1;
        if !state.tau.iter().all(|v| v.is_finite()) {
            return Err(MaterialError::new(
                "hyperbolic interface: non-finite shear stress",
            ));
        }
        let dir = if inc.norm() > 0.0 {
            inc
        } else {
            Vector2::new(d_jump[0], d_jump[1])
        };
        Ok(InterfaceUpdate {
            tangent: self.end_tangent(&state, dir),
            state,
            kind: TangentKind::Continuum,
            substeps: substeps.max(1),
        })
    }

    fn traction(state: &HyperbolicState) -> Local3 {
        Local3::new(state.tau[0], state.tau[1], -state.sigma_n)
    }

    fn outputs(state: &HyperbolicState) -> InterfaceOutputs {
        goodman_outputs(state.closure, state.closure_ref, state.shear, state.primary)
    }
}
