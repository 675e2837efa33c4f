//! Bilinear elastic law of the slab joints (vertical and perimeter joints; spec §6.1 (J1)–(J3),
//! §6.2).
//!
//! The law is path-independent: the traction is a function of the total jump only. The local
//! frame of the [`super::InterfaceModel`] contract is used as is: components 0 and 1 are the two
//! in-plane shear directions of the joint (spec §6.1: e_1 up-slope, e_2 slab normal), component 2
//! the joint normal with δ_n > 0 opening.

use super::interface_mc::check_initial_normal_stress;
use super::{InterfaceModel, InterfaceOutputs, InterfaceUpdate, TangentKind};
use crate::error::{require_positive, MaterialError, ParamError};
use crate::tensor::{Local3, Tangent3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Parameters of the joint law (seed §2.2(2) values in SI by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct JointParams {
    /// Normal stiffness in compression k_c (Pa/m). Seed: 25 GPa/m = 2.5×10¹⁰ Pa/m.
    pub kn_comp: f64,
    /// Normal stiffness in opening (tension) k_t (Pa/m). Seed: 5 MPa/m = 5×10⁶ Pa/m.
    pub kn_tens: f64,
    /// Shear stiffness k_s in both in-plane directions (Pa/m). Seed: 1 MPa/m = 1×10⁶ Pa/m.
    pub ks: f64,
}

impl Default for JointParams {
    fn default() -> Self {
        JointParams {
            kn_comp: 2.5e10,
            kn_tens: 5.0e6,
            ks: 1.0e6,
        }
    }
}

impl JointParams {
    /// Checks that the three stiffnesses are positive.
    pub fn validate(&self) -> Result<(), ParamError> {
        require_positive("kn_comp", self.kn_comp)?;
        require_positive("kn_tens", self.kn_tens)?;
        require_positive("ks", self.ks)
    }
}

/// State of a joint point: the total jump and the traction it produces.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct JointState {
    /// Total jump δ = (δ_1, δ_2, δ_n) from the stress-free position (m), δ_n > 0 opening.
    pub jump: [f64; 3],
    /// Traction T = (τ_1, τ_2, t_n) (Pa), t_n tension positive.
    pub traction: [f64; 3],
}

/// The bilinear joint law (spec §6.1).
#[derive(Debug, Clone, PartialEq)]
pub struct JointLaw {
    p: JointParams,
}

impl JointLaw {
    /// Builds the law (parameters must have passed [`JointParams::validate`]).
    pub fn new(p: &JointParams) -> Self {
        JointLaw { p: p.clone() }
    }

    /// Normal stiffness k_n(δ_n) of (J1): k_c for closure (δ_n ≤ 0), k_t for opening.
    pub fn normal_stiffness(&self, jump_n: f64) -> f64 {
        if jump_n > 0.0 {
            self.p.kn_tens
        } else {
            self.p.kn_comp
        }
    }

    /// Traction of a total jump (spec (J1), (J2)):
    ///
    /// ```text
    /// t_n = −σ_n = k_n(δ_n)·δ_n,   τ_i = k_s·δ_i   (no friction limit)
    /// ```
    pub fn traction_of(&self, jump: &Local3) -> Local3 {
        Local3::new(
            self.p.ks * jump[0],
            self.p.ks * jump[1],
            self.normal_stiffness(jump[2]) * jump[2],
        )
    }
}

impl InterfaceModel for JointLaw {
    type State = JointState;

    fn symmetric_tangent(&self) -> bool {
        true
    }

    /// A joint under compressive σ_n0 sits at δ_n = −σ_n0/k_c.
    fn init_state(&self, sigma_n0: f64) -> Result<JointState, MaterialError> {
        check_initial_normal_stress(sigma_n0)?;
        let jump = Local3::new(0.0, 0.0, -sigma_n0 / self.p.kn_comp);
        let t = self.traction_of(&jump);
        Ok(JointState {
            jump: [jump[0], jump[1], jump[2]],
            traction: [t[0], t[1], t[2]],
        })
    }

    /// Path-independent update; the tangent (J3) is diag(k_s, k_s, k_n(δ_n,end)). Because the law
    /// is piecewise linear through the origin, this operator is also the exact secant T = D·δ.
    fn update(
        &self,
        prev: &JointState,
        d_jump: &Local3,
    ) -> Result<InterfaceUpdate<JointState>, MaterialError> {
        let jump = Local3::from(prev.jump) + d_jump;
        if !jump.iter().all(|v| v.is_finite()) {
            return Err(MaterialError::new("non-finite joint jump"));
        }
        let t = self.traction_of(&jump);
        let tangent =
            Tangent3::from_diagonal(&Local3::new(self.p.ks, self.p.ks, self.normal_stiffness(jump[2])));
        Ok(InterfaceUpdate {
            state: JointState {
                jump: [jump[0], jump[1], jump[2]],
                traction: [t[0], t[1], t[2]],
            },
            tangent,
            kind: TangentKind::Secant,
            substeps: 1,
        })
    }

    fn traction(state: &JointState) -> Local3 {
        Local3::from(state.traction)
    }

    /// Shear = (δ_1, δ_2); normal = closure ⟨−δ_n⟩; opening = ⟨δ_n⟩ (spec §6.2 outputs).
    fn outputs(state: &JointState) -> InterfaceOutputs {
        let jn = state.jump[2];
        InterfaceOutputs {
            shear: [state.jump[0], state.jump[1]],
            normal: (-jn).max(0.0),
            opening: jn.max(0.0),
            open: jn > 0.0,
            plastic: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::driver_interface::checks::*;
    use proptest::prelude::*;

    fn seed() -> JointLaw {
        JointLaw::new(&JointParams::default())
    }

    /// Newton on δ_n for a target t_n from `from`, with the secant/tangent of (J3); iterations.
    fn newton_normal(j: &JointLaw, from: &JointState, target_tn: f64) -> (JointState, usize) {
        let mut d_n = 0.0;
        for it in 0..50 {
            let up = j.update(from, &Local3::new(0.0, 0.0, d_n)).unwrap();
            let r = up.state.traction[2] - target_tn;
            if r.abs() <= 1e-8 * target_tn.abs().max(1.0) {
                return (up.state, it);
            }
            d_n -= r / up.tangent[(2, 2)];
        }
        panic!("no convergence to {target_tn}");
    }

    /// JT-1: k_c in compression, k_t in opening, tractions continuous at δ_n = 0, and a Newton
    /// iteration across δ_n = 0 converges without chattering (≤ 3 iterations each way).
    #[test]
    fn jt1_compression_opening_continuity() {
        let j = seed();
        let s0 = j.init_state(1e6).unwrap();
        assert!((s0.jump[2] + 1e6 / 2.5e10).abs() < 1e-20 && (s0.traction[2] + 1e6).abs() < 1e-6);
        let zero = JointState::default();
        for h in [1e-9, 1e-12, 1e-15] {
            let tp = j.update(&zero, &Local3::new(0.0, 0.0, h)).unwrap();
            let tm = j.update(&zero, &Local3::new(0.0, 0.0, -h)).unwrap();
            assert_eq!(tp.tangent[(2, 2)], 5e6);
            assert_eq!(tm.tangent[(2, 2)], 2.5e10);
            assert!(tp.state.traction[2] > 0.0 && tm.state.traction[2] < 0.0);
            assert!(
                (tp.state.traction[2] - tm.state.traction[2]).abs() <= (2.5e10 + 5e6) * h * (1.0 + 1e-12)
            );
        }
        let mut state = s0;
        for target in [2e3, -5e5, 1e3, -1.0, 0.5, -1e6] {
            let (next, iters) = newton_normal(&j, &state, target);
            assert!(iters <= 3, "target {target}: {iters} iterations");
            assert!((next.traction[2] - target).abs() <= 1e-8 * target.abs().max(1.0));
            state = next;
        }
    }

    /// JT-2: combined opening and shear: τ = k_s·δ_s with k_s = 10³ kPa/m whatever the opening.
    #[test]
    fn jt2_shear_independent_of_opening() {
        let j = seed();
        let s0 = j.init_state(0.0).unwrap();
        for open in [-1e-4, 0.0, 1e-3, 0.05] {
            let up = j.update(&s0, &Local3::new(2e-3, -1e-3, open)).unwrap();
            assert_eq!(up.state.traction[0], 1e6 * 2e-3);
            assert_eq!(up.state.traction[1], -1e6 * 1e-3);
            assert_eq!((up.tangent[(0, 0)], up.tangent[(1, 1)]), (1e6, 1e6));
            let out = JointLaw::outputs(&up.state);
            assert_eq!(out.opening, open.max(0.0));
            assert_eq!(up.kind, TangentKind::Secant);
        }
        let bad = JointParams {
            ks: 0.0,
            ..JointParams::default()
        };
        assert_eq!(bad.validate().unwrap_err().field, "ks");
    }

    proptest! {
        #![proptest_config(ProptestConfig {
            cases: 64,
            failure_persistence: crate::test_support::proptest_persistence(),
            ..ProptestConfig::default()
        })]

        /// Secant = tangent away from δ_n = 0 (FD), T = D·δ exactly, purity, serde, rotation;
        /// huge increments and 10,000 cycles are exact because the law is path-independent.
        #[test]
        fn properties(s in -0.1..0.1f64, a in -0.1..0.1f64, n in -1e-3..1e-3f64, angle in 0.0..6.3f64) {
            prop_assume!(n.abs() > 1e-8);
            let j = seed();
            let prev = j.init_state(1e5).unwrap();
            let d = Local3::new(s, a, n);
            let up = j.update(&prev, &d).unwrap();
            let fd = fd_tangent(&j, &prev, &d, [1e-9, 1e-9, 1e-10]);
            prop_assert!(rel_diff(&up.tangent, &fd, 1.0) < 1e-6);
            let jump = Local3::from(up.state.jump);
            prop_assert!((up.tangent * jump - JointLaw::traction(&up.state)).norm() < 1e-9);
            assert_pure_and_serde(&j, &prev, &d);
            let mut rprev = prev;
            let r = rotate3(angle, &Local3::from(prev.jump));
            rprev.jump = [r[0], r[1], r[2]];
            let rup = j.update(&rprev, &rotate3(angle, &d)).unwrap();
            prop_assert!((JointLaw::traction(&rup.state) - rotate3(angle, &JointLaw::traction(&up.state))).norm() < 1e-6);
        }
    }

    #[test]
    fn ten_thousand_cycles_return_exactly() {
        let j = seed();
        let mut state = j.init_state(2e5).unwrap();
        let start = state;
        for _ in 0..10_000 {
            state = j.update(&state, &Local3::new(0.01, -0.02, 1e-3)).unwrap().state;
            state = j.update(&state, &Local3::new(-0.01, 0.02, -1e-3)).unwrap().state;
        }
        for i in 0..3 {
            assert!(
                (state.traction[i] - start.traction[i]).abs() < 1e-6,
                "{:?} vs {:?}",
                state,
                start
            );
        }
    }
}
