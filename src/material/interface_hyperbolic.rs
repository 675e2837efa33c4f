//! Clough–Duncan hyperbolic interface (spec §3, eqs. (H1)–(H8)), integrated by substeps (spec §8.4)
//! with the modified-Euler (Heun) stage pair the spec allows there: the branch (H5) is frozen over
//! a substep, the stiffness is averaged between the start and the Euler-predicted end. The
//! integration error is second order in the substep size.
//!
//! The law is nonlinear-elastic (hypo-elastic) in shear with a stress-level memory for
//! unloading/reloading, and a stiff penalty spring with opening memory in the normal direction
//! (the same normal law as the Mohr–Coulomb interface, [`super::interface_mc::ContactStep`]).
//!
//! # Behaviour worth knowing (documented by tests)
//! * A change of σ_n at fixed shear displacement leaves τ unchanged and changes the stiffness
//!   (hypo-elastic, HY-3). A rise of σ_n lowers SL below SL_max, so further shearing first reloads
//!   on k_ur; a fall of σ_n below τ/tan φ caps τ at τ_f (H8).
//! * Under displacement-controlled cycles of fixed amplitude the single stress-level memory of
//!   (H5) ratchets: reloading on k_ur reaches SL_max before the displacement amplitude, the
//!   primary curve then raises SL_max, and the loops grow cycle by cycle until τ reaches τ_f,
//!   where they become stationary (test `hard_cases`). A Masing-type rule would give stable loops
//!   below τ_f; the spec's rule is kept.
//!
//! # References
//! Clough G.W., Duncan J.M. (1971). Finite element analysis of retaining wall behavior.

use super::interface_mc::{
    check_initial_normal_stress, check_jump, goodman_outputs, janbu_stiffness, open_tangent, ContactStep,
    GAMMA_W_DEFAULT, PA_DEFAULT, SIGMA_MIN_DEFAULT,
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

/// The closed part of a step, integrated by substeps: its shear increment, and σ_n
/// interpolated linearly from `sigma0` at its start to `sigma1` at its end (spec §8.4).
#[derive(Debug, Clone, Copy)]
struct ClosedStep {
    /// Shear jump increment over the closed part (m).
    inc: Vector2<f64>,
    /// σ_n at the start of the closed part (Pa, compression positive).
    sigma0: f64,
    /// σ_n at the end of the step (Pa, compression positive).
    sigma1: f64,
}

impl ClosedStep {
    /// σ_n at pseudo-time `t` ∈ [0, 1] of the closed part.
    fn sigma_at(&self, t: f64) -> f64 {
        self.sigma0 + t * self.d_sigma()
    }

    /// Change of σ_n over the closed part.
    fn d_sigma(&self) -> f64 {
        self.sigma1 - self.sigma0
    }
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

    /// Shear strength in the stress level SL = τ/τ_f(σ̂_n), with the floor σ̂_n = max(σ_n, σ_min)
    /// of the stiffness formula (spec §8.6 item 6), so that SL stays defined at σ_n = 0, c = 0.
    fn strength_floor(&self, sigma_n: f64) -> f64 {
        self.strength(sigma_n.max(self.p.sigma_min))
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

    /// Runs the substeps of the closed part of a step over its pseudo-time t ∈ [0, 1]:
    /// `substep(t)` advances the state from t and returns its size h and σ_n at t + h. Returns
    /// the number of substeps; fails past [`MAX_SUBSTEPS`].
    fn run_substeps(mut substep: impl FnMut(f64) -> (f64, f64)) -> Result<u32, MaterialError> {
        let mut t = 0.0;
        let mut substeps = 0;
        while t < 1.0 {
            let (h, sigma_h) = substep(t);
            t += h;
            substeps += 1;
            Self::check_substeps(substeps, sigma_h)?;
        }
        Ok(substeps)
    }

    /// Shear integration of the closed part of a step (spec §8.4), resultant SL (H6).
    /// A reloading substep stops where ‖τ‖ meets SL_max·τ_f, so primary loading resumes there.
    fn integrate_resultant(
        &self,
        state: &mut HyperbolicState,
        step: ClosedStep,
    ) -> Result<u32, MaterialError> {
        let inc = step.inc;
        let mut tau = Vector2::new(state.tau[0], state.tau[1]);
        let substeps = Self::run_substeps(|t| {
            let sigma_t = step.sigma_at(t);
            let tau_f = self.strength_floor(sigma_t);
            let sl = tau.norm() / tau_f;
            let primary = Self::is_primary(sl, state.sl_max, tau.dot(&inc));
            let v_t = inc * self.branch_stiffness(primary, sl, sigma_t);
            let mut h =
                (1.0 - t).min(self.substep_limit(primary, sl, v_t.norm(), tau_f, sigma_t, step.d_sigma()));
            let radius = state.sl_max * tau_f;
            if !primary && v_t.norm() > 0.0 && tau.norm() < radius {
                let (a, b, c) = (
                    v_t.norm_squared(),
                    2.0 * tau.dot(&v_t),
                    tau.norm_squared() - radius * radius,
                );
                h = h.min((-b + (b * b - 4.0 * a * c).max(0.0).sqrt()) / (2.0 * a));
            }
            // σ_n first (spec §8.4), then the shear at the updated σ_n by a Heun (modified
            // Euler) stage pair on the frozen branch.
            let sigma_h = step.sigma_at(t + h);
            let tau_f_h = self.strength_floor(sigma_h);
            let k_1 = self.branch_stiffness(primary, tau.norm() / tau_f_h, sigma_h);
            let k_2 = self.branch_stiffness(primary, (tau + inc * (k_1 * h)).norm() / tau_f_h, sigma_h);
            tau += inc * (0.5 * (k_1 + k_2) * h);
            let strength = self.strength(sigma_h);
            if tau.norm() > strength {
                tau *= strength / tau.norm();
            }
            state.sl_max = state.sl_max.max(tau.norm() / tau_f_h);
            state.primary = primary;
            (h, sigma_h)
        })?;
        state.tau = [tau[0], tau[1]];
        Ok(substeps)
    }

    /// Shear integration of the closed part of a step, per-direction SL (option of (H6)).
    fn integrate_per_direction(
        &self,
        state: &mut HyperbolicState,
        step: ClosedStep,
    ) -> Result<u32, MaterialError> {
        let inc = step.inc;
        Self::run_substeps(|t| {
            let sigma_t = step.sigma_at(t);
            let tau_f = self.strength_floor(sigma_t);
            let mut h = 1.0 - t;
            let mut primary = [true; 2];
            for i in 0..2 {
                let tau = state.tau[i];
                let sl = tau.abs() / tau_f;
                primary[i] = Self::is_primary(sl, state.sl_max_dir[i], tau * inc[i]);
                let v = inc[i] * self.branch_stiffness(primary[i], sl, sigma_t);
                h = h.min(self.substep_limit(primary[i], sl, v.abs(), tau_f, sigma_t, step.d_sigma()));
                let radius = state.sl_max_dir[i] * tau_f;
                if !primary[i] && v != 0.0 && tau.abs() < radius {
                    h = h.min((radius * v.signum() - tau) / v);
                }
            }
            let sigma_h = step.sigma_at(t + h);
            let tau_f_h = self.strength_floor(sigma_h);
            let strength = self.strength(sigma_h);
            for i in 0..2 {
                let tau = state.tau[i];
                let k_1 = self.branch_stiffness(primary[i], tau.abs() / tau_f_h, sigma_h);
                let k_2 =
                    self.branch_stiffness(primary[i], (tau + k_1 * inc[i] * h).abs() / tau_f_h, sigma_h);
                let next = (tau + 0.5 * (k_1 + k_2) * inc[i] * h).clamp(-strength, strength);
                state.tau[i] = next;
                state.sl_max_dir[i] = state.sl_max_dir[i].max(next.abs() / tau_f_h);
            }
            state.primary = primary[0] || primary[1];
            (h, sigma_h)
        })
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
        check_initial_normal_stress(sigma_n0)?;
        Ok(HyperbolicState {
            sigma_n: sigma_n0,
            closure_ref: -sigma_n0 / self.p.k2,
            primary: true,
            ..HyperbolicState::default()
        })
    }

    /// Normal law first (H7: σ_n = k2·⟨w − w0⟩ with the gap memory of (M2)/(M7)), then the shear
    /// by modified-Euler substeps (spec §8.4) with branch (H5) frozen per substep, σ_n interpolated
    /// linearly over the step, SL capped in the stiffness and τ capped at τ_f (H8). While open:
    /// τ = 0, σ_n = 0 and the regularized tangent of (H7); on re-closure τ restarts from 0 and the
    /// stress-level memory is kept. The tangent is the continuum one at the end state.
    fn update(
        &self,
        prev: &HyperbolicState,
        d_jump: &Local3,
    ) -> Result<InterfaceUpdate<HyperbolicState>, MaterialError> {
        check_jump(d_jump)?;
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
        let step = ClosedStep {
            inc,
            sigma0: contact.sigma_start,
            sigma1: contact.sigma_end,
        };
        let substeps = match p.stress_level {
            StressLevelMode::Resultant => self.integrate_resultant(&mut state, step)?,
            StressLevelMode::PerDirection => self.integrate_per_direction(&mut state, step)?,
        };
        state.sigma_n = step.sigma1;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::driver_interface::checks::*;
    use crate::material::driver_interface::{
        cyclic_waypoints, direct_shear, jump_path, shear_path, InterfaceRow, NormalControl,
    };
    use proptest::prelude::*;

    fn model(max_sl_change: f64) -> HyperbolicInterface {
        HyperbolicInterface::new(&HyperbolicParams {
            max_sl_change,
            ..HyperbolicParams::default()
        })
    }

    fn cnl(m: &HyperbolicInterface, sigma_n: f64, waypoints: &[[f64; 2]], steps: usize) -> Vec<InterfaceRow> {
        direct_shear(
            m,
            NormalControl::ConstantLoad { sigma_n },
            &shear_path(waypoints, steps),
        )
        .unwrap()
    }

    /// Largest relative error against the closed form (H4) over a monotonic CNL run.
    fn closed_form_error(m: &HyperbolicInterface, sigma_n: f64, steps: usize) -> f64 {
        let rows = cnl(m, sigma_n, &[[0.06, 0.0]], steps);
        rows[1..]
            .iter()
            .map(|r| (r.tau - m.closed_form(sigma_n, r.jump[0])).abs() / m.closed_form(sigma_n, r.jump[0]))
            .fold(0.0, f64::max)
    }

    #[test]
    fn defaults_are_seed_table_3_in_si() {
        let p = HyperbolicParams::default();
        assert_eq!(
            (p.k1, p.k2, p.n, p.phi, p.rf, p.c),
            (600.0, 1.0e10, 0.85, 41.5, 0.9, 0.0)
        );
        p.validate().unwrap();
        let bad = HyperbolicParams { rf: 1.5, ..p };
        assert_eq!(bad.validate().unwrap_err().field, "rf");
    }

    /// HY-1: CNL monotonic vs the closed form (H4) at 100, 200, 400 kPa; the error falls with the
    /// substep size (second order, modified Euler); the spec's numbers at 100 kPa.
    #[test]
    fn hy1_closed_form_and_substep_convergence() {
        let m = model(0.02);
        let (tau_f, k_si) = (m.strength(100e3), m.initial_stiffness(100e3));
        assert!((tau_f - 88.5e3).abs() < 0.1e3 && (tau_f / 0.9 - 98.3e3).abs() < 0.1e3);
        for (u, expect) in [(0.005, 22.5e3), (0.030, 63e3), (0.060, 77e3)] {
            assert!(
                (m.closed_form(100e3, u) - expect).abs() < 0.01 * expect,
                "tau({u})"
            );
        }
        let rows = cnl(&m, 100e3, &[[0.06, 0.0]], 600);
        for (i, expect) in [(50, 22.5e3), (300, 63e3), (600, 77e3)] {
            assert!(
                (rows[i].tau - expect).abs() < 0.01 * expect,
                "u = {}: {}",
                rows[i].jump[0],
                rows[i].tau
            );
        }
        assert!(k_si > 0.0);
        for sigma_n in [100e3, 200e3, 400e3] {
            // Large driver steps (5 mm): the substep control alone sets the accuracy.
            let errors: Vec<f64> = [0.04, 0.02, 0.01, 0.005]
                .iter()
                .map(|&d| closed_form_error(&model(d), sigma_n, 12))
                .collect();
            println!(
                "HY-1 sigma_n = {sigma_n} Pa: max rel. error vs (H4), max_sl_change 0.04/0.02/0.01/0.005: {:?}",
                errors.iter().map(|e| format!("{e:.3e}")).collect::<Vec<_>>()
            );
            for w in errors.windows(2) {
                assert!(w[1] < 0.35 * w[0], "sigma_n {sigma_n}: errors {errors:?}");
            }
            assert!(
                errors[1] < 1e-3,
                "sigma_n {sigma_n}: error at the default {:.3e}",
                errors[1]
            );
        }
    }

    /// HY-2: unload–reload with k_ur: a residual displacement at τ = 0, reloading on k_ur back to
    /// SL_max, then the hyperbola resumes; a full cycle dissipates energy.
    #[test]
    fn hy2_unload_reload_hysteresis() {
        let m = model(0.005);
        let sigma_n = 100e3;
        let rows = cnl(&m, sigma_n, &[[0.02, 0.0], [0.005, 0.0], [0.045, 0.0]], 200);
        let k_ur = m.unload_stiffness(sigma_n);
        let peak = rows[200];
        let after = rows[201];
        let slope = (after.tau - peak.tau) / (after.jump[0] - peak.jump[0]);
        assert!(
            (slope - k_ur).abs() < 1e-6 * k_ur,
            "unloading slope {slope} vs k_ur {k_ur}"
        );
        let k_st = m.initial_stiffness(sigma_n) * (1.0 - 0.9 * peak.tau / m.strength(sigma_n)).powi(2);
        assert!(k_ur > 2.0 * k_st);
        // Unloading reaches τ = 0 at u_res = u_max − τ_max/k_ur > 0.
        let u_res = peak.jump[0] - peak.tau / k_ur;
        let zero = rows[200..400].iter().find(|r| r.traction[0] <= 0.0).unwrap();
        assert!(
            u_res > 0.005 && (zero.jump[0] - u_res).abs() <= 0.015 / 200.0 + 1e-12,
            "{} vs {u_res}",
            zero.jump[0]
        );
        // Reloading retraces k_ur to (20 mm, τ_max) and resumes the primary curve.
        let back = rows.iter().skip(400).find(|r| r.jump[0] >= 0.02 - 1e-12).unwrap();
        assert!(
            (back.tau - peak.tau).abs() < 1e-6 * peak.tau,
            "{} vs {}",
            back.tau,
            peak.tau
        );
        let end = rows.last().unwrap();
        let closed = m.closed_form(sigma_n, 0.045);
        assert!(
            (end.tau - closed).abs() < 0.005 * closed,
            "{} vs {closed}",
            end.tau
        );
        // A full cycle ±20 mm is a loop of positive area (energy dissipated).
        let cyc = cnl(&m, sigma_n, &cyclic_waypoints(0.02, [1.0, 0.0], 2), 100);
        let area: f64 = cyc[201..]
            .windows(2)
            .map(|w| 0.5 * (w[0].tau_s() + w[1].tau_s()) * (w[1].jump[0] - w[0].jump[0]))
            .sum();
        assert!(area > 0.1 * peak.tau * 0.02, "loop area {area}");
    }

    trait TauS {
        fn tau_s(&self) -> f64;
    }
    impl TauS for InterfaceRow {
        fn tau_s(&self) -> f64 {
            self.traction[0]
        }
    }

    /// HY-3: σ_n changes at fixed shear displacement: τ stays (hypo-elastic) while the stiffness
    /// changes. Documented behaviour: a rise of σ_n lowers SL below SL_max, so further shearing
    /// first reloads on k_ur(σ_n); a fall of σ_n below τ/tan φ caps τ at τ_f (H8).
    #[test]
    fn hy3_normal_stress_change_at_fixed_shear() {
        let m = model(0.02);
        let s0 = m.init_state(100e3).unwrap();
        let loaded = m.update(&s0, &Local3::new(0.01, 0.0, 0.0)).unwrap();
        let tau0 = loaded.state.tau[0];
        let k_before = loaded.tangent[(0, 0)];
        let up = m
            .update(&loaded.state, &Local3::new(0.0, 0.0, -300e3 / 1e10))
            .unwrap();
        assert!((up.state.sigma_n - 400e3).abs() < 1e-6);
        assert_eq!(up.state.tau[0], tau0);
        assert!((up.tangent[(0, 0)] - m.unload_stiffness(400e3)).abs() < 1e-9 * up.tangent[(0, 0)]);
        assert!(up.tangent[(0, 0)] > 3.0 * k_before);
        let down = m
            .update(&loaded.state, &Local3::new(0.0, 0.0, 70e3 / 1e10))
            .unwrap();
        assert!((down.state.sigma_n - 30e3).abs() < 1e-6);
        assert!(
            (down.state.tau[0] - m.strength(30e3)).abs() < 1e-9 * tau0,
            "capped at tau_f"
        );
    }

    /// HY-4: opening gives zero stresses and the regularized tangent; the gap is remembered and
    /// τ restarts from 0 on re-closure.
    #[test]
    fn hy4_opening() {
        let m = model(0.02);
        let s0 = m.init_state(100e3).unwrap();
        let loaded = m.update(&s0, &Local3::new(0.01, 0.0, 0.0)).unwrap().state;
        let open = m.update(&loaded, &Local3::new(0.002, 0.0, 1e-3)).unwrap();
        assert_eq!(HyperbolicInterface::traction(&open.state), Local3::zeros());
        let out = HyperbolicInterface::outputs(&open.state);
        assert!(out.open && (out.opening - (1e-3 - 1e-5)).abs() < 1e-15);
        let k_min = m.initial_stiffness(0.0);
        assert_eq!(
            open.tangent,
            Tangent3::from_diagonal(&Local3::new(1e-4 * k_min, 1e-4 * k_min, 1e6))
        );
        let shut = m
            .update(&open.state, &Local3::new(0.0, 0.0, -(1e-3 - 1e-5) - 1e-5))
            .unwrap();
        assert!((shut.state.sigma_n - 100e3).abs() < 1e-3 && shut.state.tau == [0.0, 0.0]);
        assert_eq!(shut.state.sl_max, loaded.sl_max);
    }

    /// HY-5: shearing at 45° gives the same ‖τ‖ response as at 0° (resultant SL is isotropic).
    #[test]
    fn hy5_isotropy_of_the_resultant() {
        let m = model(0.02);
        let d = 0.04 / 2f64.sqrt();
        let a = cnl(&m, 200e3, &[[0.04, 0.0], [0.01, 0.0], [0.05, 0.0]], 50);
        let b = cnl(
            &m,
            200e3,
            &[[d, d], [0.25 * d, 0.25 * d], [1.25 * d, 1.25 * d]],
            50,
        );
        for (ra, rb) in a.iter().zip(&b) {
            assert!(
                (ra.tau - rb.tau).abs() < 1e-9 * ra.tau.max(1.0),
                "step {}: {} vs {}",
                ra.step,
                ra.tau,
                rb.tau
            );
        }
    }

    /// Per-direction option: each direction follows its own hyperbola (1D checks against (H4)).
    #[test]
    fn per_direction_option() {
        let m = HyperbolicInterface::new(&HyperbolicParams {
            stress_level: StressLevelMode::PerDirection,
            max_sl_change: 0.005,
            ..HyperbolicParams::default()
        });
        let rows = cnl(&m, 100e3, &[[0.03, 0.01]], 300);
        let r = rows.last().unwrap();
        for (i, u) in [(0, 0.03), (1, 0.01)] {
            let c = m.closed_form(100e3, u);
            assert!(
                (r.traction[i] - c).abs() < 0.005 * c,
                "dir {i}: {} vs {c}",
                r.traction[i]
            );
        }
    }

    /// Zero and tensile normal stress, 100× increments, 10,000 cycles without drift.
    #[test]
    fn hard_cases() {
        let m = model(0.02);
        let rows = cnl(&m, 0.0, &[[0.01, 0.0]], 10);
        assert!(rows.iter().all(|r| r.tau == 0.0 && r.tau.is_finite()));
        let s0 = m.init_state(100e3).unwrap();
        let open = m.update(&s0, &Local3::new(0.0, 0.0, 1.0)).unwrap();
        assert!(open.tangent.iter().all(|v| v.is_finite() && *v > -1e-300));
        // One step of 10 mm (100× a usual 0.1 mm step) and of 1 m.
        for u in [0.01, 1.0] {
            let up = m.update(&s0, &Local3::new(u, 0.0, 0.0)).unwrap();
            let c = m.closed_form(100e3, u).min(m.strength(100e3));
            assert!(
                (up.state.tau[0] - c).abs() < 0.02 * c,
                "u = {u}: {} vs {c} ({} substeps)",
                up.state.tau[0],
                up.substeps
            );
        }
        // 10,000 cycles of ±20 mm. With (H5), reloading reaches SL_max before the displacement
        // amplitude, so SL_max grows from cycle to cycle (the law has no displacement memory):
        // τ at +A rises monotonically, stays ≤ τ_f, and the loop becomes stationary.
        let path = shear_path(&cyclic_waypoints(0.02, [0.8, -0.6], 10_000), 2);
        let rows = direct_shear(&m, NormalControl::ConstantLoad { sigma_n: 150e3 }, &path).unwrap();
        let peaks: Vec<&InterfaceRow> = rows.iter().skip(2).step_by(4).take(10_000).collect();
        assert_eq!(peaks.len(), 10_000);
        let tau_f = m.strength(150e3);
        for w in peaks.windows(2) {
            assert!((w[0].jump[0] - w[1].jump[0]).abs() < 1e-9);
            assert!(
                w[1].tau >= w[0].tau - 1e-9 * tau_f && w[1].tau <= tau_f,
                "{} -> {}",
                w[0].tau,
                w[1].tau
            );
        }
        let (a, b) = (peaks[peaks.len() - 2], peaks[peaks.len() - 1]);
        assert!((a.tau - b.tau).abs() < 1e-9 * tau_f && (a.traction[1] - b.traction[1]).abs() < 1e-9 * tau_f);
        assert!(rows
            .iter()
            .all(|r| r.tau.is_finite() && r.tau <= tau_f * (1.0 + 1e-12)));
    }

    #[test]
    fn jump_path_runs_open_close_cycles() {
        let m = model(0.02);
        let inc = crate::material::driver_interface::jump_path_increments(
            &[[0.01, 0.0, -1e-5], [0.01, 0.005, 1e-4], [0.02, 0.005, -2e-5]],
            20,
        );
        let rows = jump_path(&m, 0.0, &inc).unwrap();
        assert!(rows[40].opening > 0.0 && rows[40].tau == 0.0);
        assert!((rows[60].sigma_n - 2e5).abs() < 1e-3 && rows[60].tau > 0.0);
    }

    /// The branch (H5) the shear increment of `d` starts on from `prev`.
    fn starts_primary(m: &HyperbolicInterface, prev: &HyperbolicState, d: &Local3) -> bool {
        let tau = Vector2::from(prev.tau);
        let sl = tau.norm() / m.strength_floor(prev.sigma_n);
        HyperbolicInterface::is_primary(sl, prev.sl_max, tau.dot(&Vector2::new(d[0], d[1])))
    }

    /// A reload that meets SL_max 1.95e-8 m into an increment of 1e-7 m (the proptest's case
    /// sigma_n = 20 kPa, u0 = 4.5e-4 m, back = 2.17e-4): along τ the derivative is the end
    /// state's primary stiffness, across τ the step's secant one (τ_y accumulates k over the
    /// whole path, reload and primary), 1.35 % above. The continuum tangent is the limit as the
    /// increment → 0: an increment of 1e-9 m, which stays on the reload branch, has it in
    /// both directions.
    #[test]
    fn a_reload_meeting_sl_max_within_the_increment_has_the_end_tangent_in_the_limit() {
        let m = model(0.02);
        let u0 = 0.00044983891490434807;
        let a = m
            .update(&m.init_state(2e4).unwrap(), &Local3::new(u0, 0.0, 0.0))
            .unwrap()
            .state;
        let prev = m
            .update(&a, &Local3::new(-0.00021701029553606118 * u0 * 0.2, 0.0, 0.0))
            .unwrap()
            .state;
        let long = Local3::new(1e-7, 0.0, 0.0);
        let up = m.update(&prev, &long).unwrap();
        assert!(!starts_primary(&m, &prev, &long) && up.state.primary, "{up:?}");
        let fd = fd_tangent(&m, &prev, &long, [1e-10, 1e-10, 1e-12]);
        let secant = (up.state.tau[0] - prev.tau[0]) / long[0];
        assert!(
            (fd[(0, 0)] / up.tangent[(0, 0)] - 1.0).abs() < 1e-6,
            "{fd}{}",
            up.tangent
        );
        assert!((fd[(1, 1)] / secant - 1.0).abs() < 1e-6, "{fd} secant {secant}");
        assert!(fd[(1, 1)] > 1.01 * up.tangent[(1, 1)], "{fd}{}", up.tangent);
        let short = Local3::new(1e-9, 0.0, 0.0);
        let up = m.update(&prev, &short).unwrap();
        assert!(!up.state.primary, "{up:?}");
        let fd = fd_tangent(&m, &prev, &short, [1e-11, 1e-11, 1e-12]);
        for i in 0..2 {
            assert!(
                (fd[(i, i)] / up.tangent[(i, i)] - 1.0).abs() < 1e-3,
                "{fd}{}",
                up.tangent
            );
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Continuum tangent = the limit of the FD derivative as the increment → 0; purity; serde;
        /// rotation of the shear axes.
        #[test]
        fn properties(
            sigma_n in 2e4..5e5f64, u0 in 0.0..0.03f64, back in 0.0..1.0f64,
            dir in 0.0..6.3f64, angle in 0.0..6.3f64, dn in -1e-5..1e-6f64,
        ) {
            let m = model(0.02);
            let s0 = m.init_state(sigma_n).unwrap();
            let a = m.update(&s0, &Local3::new(u0, 0.0, 0.0)).unwrap().state;
            let prev = m.update(&a, &Local3::new(-back * u0 * 0.2, 0.0, 0.0)).unwrap().state;
            let eps = 1e-7;
            let d = Local3::new(eps * dir.cos(), eps * dir.sin(), 0.0);
            let tau = Vector2::from(prev.tau);
            prop_assume!(tau.norm() < 1e-9 || tau.dot(&Vector2::new(d[0], d[1])).abs() > 1e-3 * tau.norm() * eps);
            let up = m.update(&prev, &d).unwrap();
            // an increment that meets SL_max part-way is not yet in the limit (see
            // `a_reload_meeting_sl_max_within_the_increment_has_the_end_tangent_in_the_limit`)
            prop_assume!(starts_primary(&m, &prev, &d) == up.state.primary);
            let fd = fd_tangent(&m, &prev, &d, [1e-10, 1e-10, 1e-12]);
            let scale = up.tangent[(0, 0)];
            for i in 0..2 {
                prop_assert!((fd[(i, i)] - scale).abs() < 1e-3 * scale, "{}\n{}", up.tangent, fd);
            }
            prop_assert!((fd[(2, 2)] - 1e10).abs() < 1e-6 * 1e10);
            prop_assert_eq!(up.kind, TangentKind::Continuum);
            let dd = Local3::new(0.01 * dir.cos(), 0.01 * dir.sin(), dn);
            assert_pure_and_serde(&m, &prev, &dd);
            let full = m.update(&prev, &dd).unwrap();
            let mut rprev = prev;
            rprev.tau = rotate2(angle, prev.tau);
            rprev.shear = rotate2(angle, prev.shear);
            let rup = m.update(&rprev, &rotate3(angle, &dd)).unwrap();
            let t = HyperbolicInterface::traction(&full.state);
            let rt = HyperbolicInterface::traction(&rup.state);
            prop_assert!((rt - rotate3(angle, &t)).norm() < 1e-7 * t.norm().max(1.0), "{} vs {}", rt, rotate3(angle, &t));
            prop_assert!(rel_diff(&rup.tangent, &rotate_tangent(angle, &full.tangent), 1.0) < 1e-7);
        }
    }
}
