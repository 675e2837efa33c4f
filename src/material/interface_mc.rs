//! Ideal elasto-plastic Mohr–Coulomb interface (spec §4, eqs. (M1)–(M7)), integrated by the
//! closed-form radial return of spec §8.3 with its consistent tangent.
//!
//! Also holds the two ingredients shared with the hyperbolic law (spec §3, (H2), (H7)): the
//! stress-dependent (Janbu-type) shear stiffness [`janbu_stiffness`] and the penalty normal
//! contact with opening memory [`ContactStep`].
//!
//! Units are SI at the boundary and inside: k2 in Pa/m, c and σ_n in Pa, γ_w in N/m³ (so that
//! k1·γ_w is in Pa/m), p_a in Pa, φ in degrees.

use super::{InterfaceModel, InterfaceOutputs, InterfaceUpdate, TangentKind};
use crate::error::{require_non_negative, require_positive, require_range, MaterialError, ParamError};
use crate::tensor::{Local3, Tangent3};
use nalgebra::{Matrix2, Vector2};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Unit weight of water used in the stiffness formulas (H2), (M1): 9.81 kN/m³ = 9810 N/m³
/// (spec §0.2 allows 9.81 or 10; cfrd uses 9.81 everywhere).
pub const GAMMA_W_DEFAULT: f64 = 9810.0;
/// Atmospheric pressure p_a = 101.3 kPa (spec §0.2), Pa.
pub const PA_DEFAULT: f64 = 101_300.0;
/// Floor σ_min of the normal stress in the stiffness formulas, 1 kPa (spec §8.6 item 6), Pa.
pub const SIGMA_MIN_DEFAULT: f64 = 1000.0;
/// Factor of the regularizing stiffness of an open point (spec (H7)): 10⁻⁴ of k2 and of k_s(σ_min).
pub const OPEN_STIFFNESS_FACTOR: f64 = 1e-4;

/// Parameters of the ideal elasto-plastic interface (seed Table 4 in SI by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MohrCoulombParams {
    /// Shear stiffness number k1 (−). Seed Table 4: 300.
    pub k1: f64,
    /// Normal (penalty) stiffness k2 (Pa/m). Seed Table 4: 1×10⁷ kPa/m = 1×10¹⁰ Pa/m.
    pub k2: f64,
    /// Stiffness exponent n (−). Seed Table 4: 0.8.
    pub n: f64,
    /// Friction angle φ (degrees). Seed Table 4: 41.5.
    pub phi: f64,
    /// Cohesion c (Pa). Seed Table 4: 0.
    pub c: f64,
    /// Unit weight of water γ_w (N/m³), default 9810 (spec §0.2).
    pub gamma_w: f64,
    /// Atmospheric pressure p_a (Pa), default 101300.
    pub pa: f64,
    /// Normal-stress floor σ_min in the stiffness formula (Pa), default 1000 (spec §8.6).
    pub sigma_min: f64,
}

impl Default for MohrCoulombParams {
    fn default() -> Self {
        MohrCoulombParams {
            k1: 300.0,
            k2: 1.0e10,
            n: 0.8,
            phi: 41.5,
            c: 0.0,
            gamma_w: GAMMA_W_DEFAULT,
            pa: PA_DEFAULT,
            sigma_min: SIGMA_MIN_DEFAULT,
        }
    }
}

impl MohrCoulombParams {
    /// Checks k1, k2, γ_w, p_a, σ_min > 0, 0 ≤ n ≤ 2, 0 ≤ φ < 90°, c ≥ 0.
    pub fn validate(&self) -> Result<(), ParamError> {
        require_positive("k1", self.k1)?;
        require_positive("k2", self.k2)?;
        require_range("n", self.n, 0.0, 2.0)?;
        require_range("phi", self.phi, 0.0, 89.0)?;
        require_non_negative("c", self.c)?;
        require_positive("gamma_w", self.gamma_w)?;
        require_positive("pa", self.pa)?;
        require_positive("sigma_min", self.sigma_min)
    }
}

/// Stress-dependent shear stiffness of the Goodman-type laws (spec (H2), (M1)) and its
/// derivative with respect to σ_n:
///
/// ```text
/// k = k1·γ_w·(σ̂_n/p_a)^n,   σ̂_n = max(σ_n, σ_min)
/// dk/dσ_n = n·k/σ_n  if σ_n > σ_min,  else 0
/// ```
pub fn janbu_stiffness(k1: f64, gamma_w: f64, pa: f64, n: f64, sigma_min: f64, sigma_n: f64) -> (f64, f64) {
    let s = sigma_n.max(sigma_min);
    let k = k1 * gamma_w * (s / pa).powf(n);
    let dk = if sigma_n > sigma_min { n * k / sigma_n } else { 0.0 };
    (k, dk)
}

/// One step of the penalty normal contact with memory of opening (spec (M2), (M7), (H7)).
///
/// ```text
/// w = w_n − Δδ_n   (closure, m);   σ_n = k2·⟨w − w0⟩;   gap g = ⟨w0 − w⟩
/// ```
///
/// The shear increment of the step counts only for the part of the step during which the point
/// is closed (spec §8.3: "Δδs counts only from closure"); `shear_fraction` is that part and
/// `d_shear_fraction` its derivative with respect to δ_n (non-zero only when the point closes
/// inside the step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactStep {
    /// Closure at the end of the step, w_{n+1} (m).
    pub closure: f64,
    /// σ_n at the start of the closed part of the step (Pa, compression positive).
    pub sigma_start: f64,
    /// σ_n at the end of the step (Pa, compression positive).
    pub sigma_end: f64,
    /// Whether the point was open at the start of the step (τ restarts from 0).
    pub was_open: bool,
    /// Whether the point is open at the end of the step.
    pub open: bool,
    /// Fraction of the step during which the point is closed.
    pub shear_fraction: f64,
    /// d(shear_fraction)/dδ_n (1/m).
    pub d_shear_fraction: f64,
}

impl ContactStep {
    /// Evaluates the contact step from the committed closure `closure_n`, the reference closure
    /// `closure_ref` (w0) and the normal jump increment `d_jump_n` (δ_n > 0 opens).
    pub fn new(closure_n: f64, closure_ref: f64, k2: f64, d_jump_n: f64) -> Self {
        let dw = -d_jump_n;
        let w = closure_n + dw;
        let was_open = closure_n < closure_ref;
        let open = w < closure_ref;
        let (shear_fraction, d_shear_fraction) = match (was_open, open) {
            (false, false) => (1.0, 0.0),
            (true, true) => (0.0, 0.0),
            // Closes inside the step: the closed part is at its end.
            (true, false) => ((w - closure_ref) / dw, -(closure_ref - closure_n) / (dw * dw)),
            // Opens inside the step: the closed part is at its start (outputs only).
            (false, true) => ((closure_n - closure_ref) / (-dw), 0.0),
        };
        ContactStep {
            closure: w,
            sigma_start: if was_open {
                0.0
            } else {
                k2 * (closure_n - closure_ref)
            },
            sigma_end: k2 * (w - closure_ref).max(0.0),
            was_open,
            open,
            shear_fraction,
            d_shear_fraction,
        }
    }
}

/// Outputs shared by the Goodman-type states: opening g = ⟨w0 − w⟩, material closure ⟨w − w0⟩.
pub(crate) fn goodman_outputs(
    closure: f64,
    closure_ref: f64,
    shear: [f64; 2],
    plastic: bool,
) -> InterfaceOutputs {
    InterfaceOutputs {
        shear,
        normal: (closure - closure_ref).max(0.0),
        opening: (closure_ref - closure).max(0.0),
        open: closure < closure_ref,
        plastic,
    }
}

/// Regularized tangent of an open point (spec (H7)): diag(10⁻⁴·k_s(σ_min), 10⁻⁴·k_s(σ_min), 10⁻⁴·k2).
pub fn open_tangent(k_s_min: f64, k2: f64) -> Tangent3 {
    Tangent3::from_diagonal(&Local3::new(
        OPEN_STIFFNESS_FACTOR * k_s_min,
        OPEN_STIFFNESS_FACTOR * k_s_min,
        OPEN_STIFFNESS_FACTOR * k2,
    ))
}

/// Rejects a negative or non-finite activation normal stress (`init_state` of the interface laws).
pub(crate) fn check_initial_normal_stress(sigma_n0: f64) -> Result<(), MaterialError> {
    if sigma_n0.is_finite() && sigma_n0 >= 0.0 {
        Ok(())
    } else {
        Err(MaterialError::new(format!(
            "initial normal stress must be finite and >= 0, got {sigma_n0} Pa"
        )))
    }
}

/// Rejects a non-finite jump increment (`update` of the interface laws).
pub(crate) fn check_jump(d_jump: &Local3) -> Result<(), MaterialError> {
    if d_jump.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(MaterialError::new(format!(
            "non-finite jump increment {d_jump:?}"
        )))
    }
}

/// State of an ideal elasto-plastic interface point (spec §4.2, "State variables").
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct MohrCoulombState {
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
    /// Accumulated plastic slip (m), output only.
    pub slip: [f64; 2],
    /// Whether the last update slipped.
    pub slipping: bool,
}

/// The ideal elasto-plastic Mohr–Coulomb interface law (spec §4).
#[derive(Debug, Clone, PartialEq)]
pub struct MohrCoulombInterface {
    p: MohrCoulombParams,
    tan_phi: f64,
}

impl MohrCoulombInterface {
    /// Builds the law (parameters must have passed [`MohrCoulombParams::validate`]).
    pub fn new(p: &MohrCoulombParams) -> Self {
        MohrCoulombInterface {
            p: p.clone(),
            tan_phi: p.phi.to_radians().tan(),
        }
    }

    /// The parameters.
    pub fn params(&self) -> &MohrCoulombParams {
        &self.p
    }

    /// Shear strength τ_f = c + σ_n·tan φ (spec (M3)), Pa.
    pub fn strength(&self, sigma_n: f64) -> f64 {
        self.p.c + sigma_n.max(0.0) * self.tan_phi
    }

    /// Elastic shear stiffness k_s(σ_n) and dk_s/dσ_n (spec (M1)).
    pub fn shear_stiffness(&self, sigma_n: f64) -> (f64, f64) {
        let p = &self.p;
        janbu_stiffness(p.k1, p.gamma_w, p.pa, p.n, p.sigma_min, sigma_n)
    }

    /// The update of a point that is open at the end of the step: no traction, the committed
    /// slip, `closure` and the counted shear displacement `shear`; the open tangent.
    fn open_update(
        &self,
        prev: &MohrCoulombState,
        closure: f64,
        shear: [f64; 2],
    ) -> InterfaceUpdate<MohrCoulombState> {
        let (k_min, _) = self.shear_stiffness(0.0);
        let state = MohrCoulombState {
            tau: [0.0; 2],
            sigma_n: 0.0,
            closure,
            closure_ref: prev.closure_ref,
            shear,
            slip: prev.slip,
            slipping: false,
        };
        InterfaceUpdate {
            state,
            tangent: open_tangent(k_min, self.p.k2),
            kind: TangentKind::Elastic,
            substeps: 1,
        }
    }
}

impl InterfaceModel for MohrCoulombInterface {
    type State = MohrCoulombState;

    fn symmetric_tangent(&self) -> bool {
        false
    }

    fn init_state(&self, sigma_n0: f64) -> Result<MohrCoulombState, MaterialError> {
        check_initial_normal_stress(sigma_n0)?;
        Ok(MohrCoulombState {
            sigma_n: sigma_n0,
            closure_ref: -sigma_n0 / self.p.k2,
            ..MohrCoulombState::default()
        })
    }

    /// Closed-form return of spec §8.3 with the consistent tangent (M6), including the
    /// ∂k_s/∂σ_n term that §8.3 omits (spec §10 G7):
    ///
    /// ```text
    /// σ = k2·⟨w − w0⟩,  k_s = k_s(σ),  Δs = f·Δδ_s  (f: closed part of the step)
    /// τ_tr = τ_n + k_s·Δs  (τ_n := 0 if the point was open),   τ_f = c + σ·tan φ
    /// stick (‖τ_tr‖ ≤ τ_f):  τ = τ_tr
    ///     ∂τ/∂δ_s = k_s·f·I,   ∂τ/∂δ_n = −k2·k_s'·Δs + k_s·Δδ_s·∂f/∂δ_n
    /// slip:  r = τ_tr/‖τ_tr‖,  τ = τ_f·r,  Δλ = (‖τ_tr‖ − τ_f)/k_s
    ///     ∂τ/∂δ_s = (τ_f/‖τ_tr‖)(I − r⊗r)·k_s·f
    ///     ∂τ/∂δ_n = −k2·tan φ·r + (τ_f/‖τ_tr‖)(I − r⊗r)·∂τ_tr/∂δ_n
    /// ∂t_n/∂δ_n = k2   (t_n = −σ)
    /// ```
    fn update(
        &self,
        prev: &MohrCoulombState,
        d_jump: &Local3,
    ) -> Result<InterfaceUpdate<MohrCoulombState>, MaterialError> {
        check_jump(d_jump)?;
        let p = &self.p;
        let contact = ContactStep::new(prev.closure, prev.closure_ref, p.k2, d_jump[2]);
        let d_shear = Vector2::new(d_jump[0], d_jump[1]);
        let counted = d_shear * contact.shear_fraction;
        let shear = [prev.shear[0] + counted[0], prev.shear[1] + counted[1]];
        if contact.open {
            return Ok(self.open_update(prev, contact.closure, shear));
        }
        let sigma = contact.sigma_end;
        let (k_s, dk_s) = self.shear_stiffness(sigma);
        let tau_start = if contact.was_open {
            Vector2::zeros()
        } else {
            Vector2::new(prev.tau[0], prev.tau[1])
        };
        let tau_tr = tau_start + counted * k_s;
        let dtr_ds = Matrix2::identity() * (k_s * contact.shear_fraction);
        let dtr_dn = counted * (-p.k2 * dk_s) + d_shear * (k_s * contact.d_shear_fraction);
        let tau_f = self.strength(sigma);
        let norm_tr = tau_tr.norm();
        let mut tangent = Tangent3::zeros();
        tangent[(2, 2)] = p.k2;
        let mut slip = prev.slip;
        let (tau, slipping) = if norm_tr <= tau_f * (1.0 + 1e-14) {
            tangent.fixed_view_mut::<2, 2>(0, 0).copy_from(&dtr_ds);
            tangent.fixed_view_mut::<2, 1>(0, 2).copy_from(&dtr_dn);
            (tau_tr, false)
        } else {
            let r = tau_tr / norm_tr;
            let ratio = tau_f / norm_tr;
            let proj = (Matrix2::identity() - r * r.transpose()) * ratio;
            tangent.fixed_view_mut::<2, 2>(0, 0).copy_from(&(proj * dtr_ds));
            let col = r * (-p.k2 * self.tan_phi) + proj * dtr_dn;
            tangent.fixed_view_mut::<2, 1>(0, 2).copy_from(&col);
            let d_lambda = (norm_tr - tau_f) / k_s;
            slip[0] += d_lambda * r[0];
            slip[1] += d_lambda * r[1];
            (r * tau_f, true)
        };
        let state = MohrCoulombState {
            tau: [tau[0], tau[1]],
            sigma_n: sigma,
            closure: contact.closure,
            closure_ref: prev.closure_ref,
            shear,
            slip,
            slipping,
        };
        Ok(InterfaceUpdate {
            state,
            tangent,
            kind: TangentKind::Consistent,
            substeps: 1,
        })
    }

    fn traction(state: &MohrCoulombState) -> Local3 {
        Local3::new(state.tau[0], state.tau[1], -state.sigma_n)
    }

    fn outputs(state: &MohrCoulombState) -> InterfaceOutputs {
        goodman_outputs(state.closure, state.closure_ref, state.shear, state.slipping)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::driver_interface::checks::*;
    use crate::material::driver_interface::{cyclic_waypoints, direct_shear, shear_path, NormalControl};
    use proptest::prelude::*;

    fn seed() -> MohrCoulombInterface {
        MohrCoulombInterface::new(&MohrCoulombParams::default())
    }

    /// A closed state at σ_n with a shear stress of `tau` (Pa) reached elastically.
    fn loaded(m: &MohrCoulombInterface, sigma_n: f64, tau: [f64; 2]) -> MohrCoulombState {
        let s0 = m.init_state(sigma_n).unwrap();
        let (k, _) = m.shear_stiffness(sigma_n);
        m.update(&s0, &Local3::new(tau[0] / k, tau[1] / k, 0.0))
            .unwrap()
            .state
    }

    #[test]
    fn defaults_are_seed_table_4_in_si() {
        let p = MohrCoulombParams::default();
        assert_eq!((p.k1, p.k2, p.n, p.phi, p.c), (300.0, 1.0e10, 0.8, 41.5, 0.0));
        p.validate().unwrap();
        let mut bad = p.clone();
        bad.phi = 95.0;
        assert_eq!(bad.validate().unwrap_err().field, "phi");
    }

    /// MC-1: linear up to τ_f = σ_n tan 41.5° at u = τ_f/k_s (≈ 30 mm at 100 kPa, ≈ 40 mm at
    /// 400 kPa), then perfectly plastic; the normal displacement stays 0.
    #[test]
    fn mc1_cnl_monotonic() {
        let m = seed();
        for (sigma_n, u_yield_mm) in [(100e3, 30.4), (400e3, 40.0)] {
            let (k, _) = m.shear_stiffness(sigma_n);
            let tau_f = m.strength(sigma_n);
            let u_y = tau_f / k;
            assert!((u_y * 1e3 - u_yield_mm).abs() < 0.5, "u_y = {} mm", u_y * 1e3);
            let rows = direct_shear(
                &m,
                NormalControl::ConstantLoad { sigma_n },
                &shear_path(&[[0.08, 0.0]], 400),
            )
            .unwrap();
            for r in &rows {
                let u = r.jump[0];
                let expect = if u < u_y { k * u } else { tau_f };
                assert!(
                    (r.tau - expect).abs() <= 1e-9 * tau_f,
                    "u = {u}: {} vs {expect}",
                    r.tau
                );
                assert!(r.jump[2].abs() < 1e-15 && (r.sigma_n - sigma_n).abs() < 1e-6);
            }
        }
    }

    /// MC-2: slip at 45°, then the displacement direction rotates by 90°: τ stays on ‖τ‖ = τ_f
    /// and its direction turns gradually towards the new direction (radial return). The angle ψ
    /// between τ and the new direction follows the continuous solution of perfect plasticity
    /// on the circle, dψ/du = −(k_s/τ_f)·sin ψ, i.e. tan(ψ/2) = tan(ψ0/2)·exp(−k_s·u/τ_f).
    #[test]
    fn mc2_direction_change_on_the_yield_circle() {
        let m = seed();
        let d = 0.05 / 2f64.sqrt();
        let rows = direct_shear(
            &m,
            NormalControl::ConstantLoad { sigma_n: 100e3 },
            &shear_path(&[[d, d], [0.0, 2.0 * d]], 200),
        )
        .unwrap();
        let tau_f = m.strength(100e3);
        let (k, _) = m.shear_stiffness(100e3);
        let mut last_angle = 45f64;
        for (i, r) in rows[201..].iter().enumerate() {
            assert!((r.tau - tau_f).abs() < 1e-9 * tau_f, "off the circle: {}", r.tau);
            let angle = r.traction[1].atan2(r.traction[0]).to_degrees();
            assert!(
                angle >= last_angle - 1e-9 && angle - last_angle < 10.0,
                "{last_angle} -> {angle}"
            );
            let u = 0.05 * (i + 1) as f64 / 200.0;
            let psi = 2.0 * (-k * u / tau_f).exp().atan();
            assert!(
                (135.0 - psi.to_degrees() - angle).abs() < 0.5,
                "u = {u}: {angle} vs {psi}"
            );
            last_angle = angle;
        }
        assert!(
            last_angle > 110.0 && last_angle < 135.0,
            "final angle {last_angle}"
        );
    }

    /// MC-3: cyclic shear gives a rectangular loop: slip only at |τ| = τ_f, unloading with k_s,
    /// no residual normal displacement.
    #[test]
    fn mc3_cyclic_rectangular_loop() {
        let m = seed();
        let path = shear_path(&cyclic_waypoints(0.05, [1.0, 0.0], 3), 100);
        let rows = direct_shear(&m, NormalControl::ConstantLoad { sigma_n: 100e3 }, &path).unwrap();
        let tau_f = m.strength(100e3);
        let (k, _) = m.shear_stiffness(100e3);
        for w in rows.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            let du = b.jump[0] - a.jump[0];
            let elastic = a.traction[0] + k * du;
            if elastic.abs() <= tau_f {
                assert!((b.traction[0] - elastic).abs() < 1e-9 * tau_f, "step {}", b.step);
            } else {
                assert!(
                    (b.traction[0].abs() - tau_f).abs() < 1e-9 * tau_f,
                    "step {}",
                    b.step
                );
            }
            assert!(b.jump[2].abs() < 1e-15 && b.normal >= 0.0);
        }
        let peak = rows.iter().map(|r| r.traction[0]).fold(f64::MIN, f64::max);
        let low = rows.iter().map(|r| r.traction[0]).fold(f64::MAX, f64::min);
        assert!((peak - tau_f).abs() < 1e-9 * tau_f && (low + tau_f).abs() < 1e-9 * tau_f);
    }

    /// MC-4: the consistent tangent of §8.3 with the ∂k_s/∂σ_n term (spec G7) against central
    /// finite differences, sticking and slipping, with a shear increment not parallel to τ_n.
    #[test]
    fn mc4_consistent_tangent_by_finite_differences() {
        let m = seed();
        let prev = loaded(&m, 200e3, [60e3, -20e3]);
        let h = [1e-9, 1e-9, 1e-10];
        let mut kinds = Vec::new();
        for d in [
            Local3::new(1e-3, 2e-3, -3e-6),
            Local3::new(40e-3, 30e-3, -3e-6),
            Local3::new(-2e-3, 60e-3, 2e-6),
        ] {
            let up = m.update(&prev, &d).unwrap();
            kinds.push(up.state.slipping);
            let fd = fd_tangent(&m, &prev, &d, h);
            let err = rel_diff(&up.tangent, &fd, 1.0);
            assert!(
                err < 1e-6,
                "slipping {} tangent error {err:.2e}\n{}\n{}",
                up.state.slipping,
                up.tangent,
                fd
            );
            // The ∂k_s/∂σ_n term matters: FD differs from the tangent without it.
            let col_err = (fd[(0, 2)] - up.tangent[(0, 2)])
                .abs()
                .max((fd[(1, 2)] - up.tangent[(1, 2)]).abs());
            let (k, dk) = m.shear_stiffness(up.state.sigma_n);
            assert!(dk > 0.0 && k > 0.0);
            let without = without_dks(&m, &prev, &d);
            let omitted = (fd[(0, 2)] - without[0])
                .abs()
                .max((fd[(1, 2)] - without[1]).abs());
            assert!(
                omitted > 1e3 * col_err.max(1e-3),
                "term not significant: {omitted:.3e} vs {col_err:.3e}"
            );
            println!(
                "MC-4 slipping {}: tangent vs FD {err:.2e}; dtau/d(delta_n) error {col_err:.3e} Pa/m with the dks term, {omitted:.3e} Pa/m without",
                up.state.slipping
            );
        }
        assert_eq!(kinds, vec![false, true, true]);
    }

    /// ∂τ/∂δ_n of spec §8.3 as printed (without ∂k_s/∂σ_n).
    fn without_dks(m: &MohrCoulombInterface, prev: &MohrCoulombState, d: &Local3) -> [f64; 2] {
        let up = m.update(prev, d).unwrap();
        if !up.state.slipping {
            return [0.0, 0.0];
        }
        let tau = Vector2::from(up.state.tau) / m.strength(up.state.sigma_n);
        let c = -m.params().k2 * m.tan_phi;
        [c * tau[0], c * tau[1]]
    }

    /// MC-5: open, shear while open, re-close: τ = 0 while open, the gap is remembered, τ
    /// restarts from 0 on re-closure and only the shear after closure counts.
    #[test]
    fn mc5_open_shear_reclose() {
        let m = seed();
        let prev = loaded(&m, 100e3, [50e3, 0.0]);
        let w_open = 1e-4;
        let open = m.update(&prev, &Local3::new(0.0, 0.0, w_open)).unwrap();
        assert_eq!(MohrCoulombInterface::traction(&open.state), Local3::zeros());
        let gap = MohrCoulombInterface::outputs(&open.state).opening;
        assert!((gap - (w_open - 100e3 / 1e10)).abs() < 1e-15, "gap {gap}");
        assert!(open.tangent[(2, 2)] > 0.0 && open.tangent[(0, 0)] > 0.0);
        let sheared = m.update(&open.state, &Local3::new(5e-3, 0.0, 0.0)).unwrap();
        assert_eq!(sheared.state.tau, [0.0, 0.0]);
        assert_eq!(MohrCoulombInterface::outputs(&sheared.state).opening, gap);
        // Re-close to σ_n = 100 kPa while shearing 2 mm; half of the normal travel is the gap.
        let dn = -(gap + 100e3 / 1e10);
        let closed = m.update(&sheared.state, &Local3::new(2e-3, 0.0, dn)).unwrap();
        let frac = (100e3 / 1e10) / (-dn);
        let (k, _) = m.shear_stiffness(100e3);
        assert!((closed.state.sigma_n - 100e3).abs() < 1e-3);
        assert!(
            (closed.state.tau[0] - k * 2e-3 * frac).abs() < 1e-6 * k * 2e-3,
            "{}",
            closed.state.tau[0]
        );
        let fd = fd_tangent(
            &m,
            &sheared.state,
            &Local3::new(2e-3, 0.0, dn),
            [1e-9, 1e-9, 1e-12],
        );
        assert!(
            rel_diff(&closed.tangent, &fd, 1.0) < 1e-5,
            "{}\n{}",
            closed.tangent,
            fd
        );
    }

    /// Zero and tensile normal stress: σ_n0 = 0 shears at zero strength; a tensile CNL target
    /// has no equilibrium and gives an error, not a NaN.
    #[test]
    fn zero_and_tensile_normal_stress() {
        let m = seed();
        let rows = direct_shear(
            &m,
            NormalControl::ConstantLoad { sigma_n: 0.0 },
            &shear_path(&[[0.01, 0.0]], 10),
        )
        .unwrap();
        assert!(rows.iter().all(|r| r.tau == 0.0 && r.sigma_n == 0.0));
        let s0 = m.init_state(0.0).unwrap();
        let up = m.update(&s0, &Local3::new(1e-3, 0.0, 1e-3)).unwrap();
        assert!(up.tangent.iter().all(|v| v.is_finite()) && MohrCoulombInterface::outputs(&up.state).open);
        let tensile = direct_shear(
            &m,
            NormalControl::ConstantLoad { sigma_n: -1e3 },
            &shear_path(&[[1e-3, 0.0]], 2),
        );
        assert!(matches!(
            tensile,
            Err(crate::material::driver_interface::DriverError::Material { step: 0, .. })
        ));
    }

    /// Increments 500× and 10⁴× the usual 0.1 mm in one step, with a 1 MPa jump of σ_n: the
    /// closed-form return puts τ on the yield circle.
    #[test]
    fn huge_increments() {
        let m = seed();
        let prev = loaded(&m, 100e3, [10e3, 10e3]);
        for u in [0.05, 1.0] {
            let up = m.update(&prev, &Local3::new(u, -u, -1e-4)).unwrap();
            assert!(up.state.slipping && (up.state.sigma_n - 1.1e6).abs() < 1e-3);
            let tau = Vector2::from(up.state.tau).norm();
            assert!((tau - m.strength(up.state.sigma_n)).abs() < 1e-6, "tau {tau}");
            assert!(up.tangent.iter().all(|v| v.is_finite()));
        }
    }

    /// 10,000 cycles of ±50 mm: the loop is stationary (no drift) and finite.
    #[test]
    fn ten_thousand_cycles_without_drift() {
        let m = seed();
        let path = shear_path(&cyclic_waypoints(0.05, [0.6, 0.8], 10_000), 4);
        let rows = direct_shear(&m, NormalControl::ConstantLoad { sigma_n: 150e3 }, &path).unwrap();
        let first = &rows[12];
        let last = &rows[rows.len() - 9];
        assert!((first.jump[0] - 0.6 * 0.05).abs() < 1e-15);
        assert!(
            (last.tau - first.tau).abs() < 1e-9 * first.tau && (last.jump[0] - first.jump[0]).abs() < 1e-9
        );
        assert!(rows
            .iter()
            .all(|r| r.tau.is_finite() && r.tau <= m.strength(150e3) * (1.0 + 1e-12)));
        assert!(rows.last().unwrap().jump[2].abs() < 1e-15);
    }

    proptest! {
        #![proptest_config(ProptestConfig {
            cases: 64,
            failure_persistence: crate::test_support::proptest_persistence(),
            ..ProptestConfig::default()
        })]

        /// Consistent tangent vs central FD, purity, serde, rotation of the shear axes.
        #[test]
        fn properties(
            sigma_n in 1e4..5e5f64, ts in -1.0..1.0f64, ta in -1.0..1.0f64,
            ds in -0.03..0.03f64, da in -0.03..0.03f64, dn in -2e-5..2e-6f64, angle in 0.0..6.3f64,
        ) {
            let m = seed();
            let tau_f = m.strength(sigma_n);
            let prev = loaded(&m, sigma_n, [0.7 * tau_f * ts, 0.7 * tau_f * ta]);
            let d = Local3::new(ds, da, dn);
            prop_assume!(prev.closure - dn > prev.closure_ref + 1e-9);
            let up = m.update(&prev, &d).unwrap();
            let tau_tr_margin = {
                let s = up.state.sigma_n;
                let (k, _) = m.shear_stiffness(s);
                let tr = Vector2::from(prev.tau) + Vector2::new(ds, da) * k;
                (tr.norm() - m.strength(s)).abs() / m.strength(s)
            };
            prop_assume!(tau_tr_margin > 1e-4 && up.state.sigma_n > 2.0 * m.params().sigma_min);
            let fd = fd_tangent(&m, &prev, &d, [1e-9, 1e-9, 1e-11]);
            prop_assert!(rel_diff(&up.tangent, &fd, 1.0) < 1e-5, "{}\n{}", up.tangent, fd);
            prop_assert_eq!(up.kind, TangentKind::Consistent);
            assert_pure_and_serde(&m, &prev, &d);
            let mut rprev = prev;
            rprev.tau = rotate2(angle, prev.tau);
            let rup = m.update(&rprev, &rotate3(angle, &d)).unwrap();
            let t = MohrCoulombInterface::traction(&up.state);
            let rt = MohrCoulombInterface::traction(&rup.state);
            prop_assert!((rt - rotate3(angle, &t)).norm() < 1e-9 * tau_f);
            prop_assert!(rel_diff(&rup.tangent, &rotate_tangent(angle, &up.tangent), 1.0) < 1e-9);
        }
    }
}
