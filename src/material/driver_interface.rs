//! Interface material-point driver, generic over [`InterfaceModel`]: direct shear under constant
//! normal load (CNL) or constant normal stiffness (CNS), and arbitrary prescribed 3D jump paths.
//!
//! Every step integrates from the committed state with the total step increment and commits the
//! converged result (spec §8.1), as the global solver does. Under CNL/CNS the normal jump of each
//! step is the unknown of a scalar Newton iteration with backtracking line search (spec §9: the
//! mixed-control driver iterates with the model's tangent).
//!
//! Signs: jump δ = (δ_s, δ_a, δ_n) with δ_n > 0 opening; σ_n is compression positive.

use super::InterfaceModel;
use crate::error::MaterialError;
use crate::tensor::Local3;
use thiserror::Error;

/// Relative tolerance of the normal-stress equilibrium (spec §9: 10⁻⁸ relative).
pub const NORMAL_TOL: f64 = 1e-8;
/// Largest number of Newton iterations per step.
const MAX_ITER: usize = 60;

/// A driver run that could not be completed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DriverError {
    /// The material update failed.
    #[error("step {step}: material update failed: {source}")]
    Material {
        /// Step number (1-based; 0 is the initial state).
        step: usize,
        /// The material's error.
        source: MaterialError,
    },
    /// The normal-stress iteration did not converge (e.g. a tensile σ_n on a law without tension).
    #[error("step {step}: normal stress did not converge (residual {residual:.3e} Pa, target sigma_n {target:.4e} Pa)")]
    NoConvergence {
        /// Step number.
        step: usize,
        /// Last residual (Pa).
        residual: f64,
        /// Target normal stress (Pa, compression positive).
        target: f64,
    },
}

/// How the normal direction is controlled in a direct-shear test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalControl {
    /// Constant normal load: σ_n stays at `sigma_n` (Pa, compression positive).
    ConstantLoad {
        /// Normal stress (Pa, compression positive).
        sigma_n: f64,
    },
    /// Constant normal stiffness: σ_n = σ_n0 + K·δ_n, so dilation (δ_n > 0) raises σ_n as in a
    /// CNS apparatus (dσ_n = K·dv with v the dilation).
    ConstantStiffness {
        /// Initial normal stress (Pa, compression positive).
        sigma_n0: f64,
        /// Stiffness K of the normal restraint (Pa/m).
        stiffness: f64,
    },
}

impl NormalControl {
    /// Initial normal stress (Pa, compression positive).
    pub fn initial_sigma_n(&self) -> f64 {
        match *self {
            NormalControl::ConstantLoad { sigma_n } => sigma_n,
            NormalControl::ConstantStiffness { sigma_n0, .. } => sigma_n0,
        }
    }

    /// Target σ_n at a normal jump δ_n measured from the start of shearing, and dσ_n/dδ_n.
    fn target(&self, jump_n: f64) -> (f64, f64) {
        match *self {
            NormalControl::ConstantLoad { sigma_n } => (sigma_n, 0.0),
            NormalControl::ConstantStiffness { sigma_n0, stiffness } => {
                (sigma_n0 + stiffness * jump_n, stiffness)
            }
        }
    }
}

/// One output row of a driver run.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct InterfaceRow {
    /// Step number (0 = initial state).
    pub step: usize,
    /// Total jump since the start of the test, (δ_s, δ_a, δ_n) (m).
    pub jump: [f64; 3],
    /// Traction (τ_s, τ_a, t_n) (Pa), t_n tension positive.
    pub traction: [f64; 3],
    /// Normal stress σ_n = −t_n (Pa, compression positive).
    pub sigma_n: f64,
    /// Resultant shear stress ‖(τ_s, τ_a)‖ (Pa).
    pub tau: f64,
    /// Accumulated shear displacement of the material (s, a) (m), opening excluded.
    pub slip: [f64; 2],
    /// Normal deformation of the material, closure positive (m), opening excluded.
    pub normal: f64,
    /// Opening (gap) (m).
    pub opening: f64,
    /// Substeps used by the last accepted update.
    pub substeps: u32,
}

/// Builds a row from a state.
pub fn row_of<M: InterfaceModel>(step: usize, jump: Local3, state: &M::State, substeps: u32) -> InterfaceRow {
    let t = M::traction(state);
    let out = M::outputs(state);
    InterfaceRow {
        step,
        jump: [jump[0], jump[1], jump[2]],
        traction: [t[0], t[1], t[2]],
        sigma_n: -t[2],
        tau: t[0].hypot(t[1]),
        slip: out.shear,
        normal: out.normal,
        opening: out.opening,
        substeps,
    }
}

/// Shear increments of a path through `waypoints` (each a point of (δ_s, δ_a) in m, starting
/// from the origin), `steps_per_segment` equal steps per segment.
pub fn shear_path(waypoints: &[[f64; 2]], steps_per_segment: usize) -> Vec<[f64; 2]> {
    let mut out = Vec::with_capacity(waypoints.len() * steps_per_segment);
    let mut from = [0.0, 0.0];
    for to in waypoints {
        let n = steps_per_segment.max(1);
        for _ in 0..n {
            out.push([(to[0] - from[0]) / n as f64, (to[1] - from[1]) / n as f64]);
        }
        from = *to;
    }
    out
}

/// Waypoints of a cyclic shear path along `direction` (unit (s, a) vector): 0 → +A → −A → … for
/// `cycles` full cycles, ending at 0.
pub fn cyclic_waypoints(amplitude: f64, direction: [f64; 2], cycles: usize) -> Vec<[f64; 2]> {
    let p = [amplitude * direction[0], amplitude * direction[1]];
    let mut w = Vec::with_capacity(2 * cycles + 1);
    for _ in 0..cycles {
        w.push(p);
        w.push([-p[0], -p[1]]);
    }
    w.push([0.0, 0.0]);
    w
}

/// Direct shear of one interface point: prescribed shear increments, normal direction under
/// `control`. Starts from `model.init_state(σ_n0)`; returns the initial row and one row per step.
pub fn direct_shear<M: InterfaceModel>(
    model: &M,
    control: NormalControl,
    shear_increments: &[[f64; 2]],
) -> Result<Vec<InterfaceRow>, DriverError> {
    let mut state = model
        .init_state(control.initial_sigma_n())
        .map_err(|source| DriverError::Material { step: 0, source })?;
    let mut jump = Local3::zeros();
    let mut rows = Vec::with_capacity(shear_increments.len() + 1);
    rows.push(row_of::<M>(0, jump, &state, 0));
    for (i, inc) in shear_increments.iter().enumerate() {
        let step = i + 1;
        let (next, d_n, substeps) = normal_equilibrium(model, &state, &control, jump[2], *inc, step)?;
        jump += Local3::new(inc[0], inc[1], d_n);
        state = next;
        rows.push(row_of::<M>(step, jump, &state, substeps));
    }
    Ok(rows)
}

/// Smallest bracket of the normal increment (m) below which a step without an exact normal
/// equilibrium takes the closed side (see [`normal_equilibrium`]).
const BRACKET_MIN: f64 = 1e-13;

/// One evaluation of the normal equilibrium: the trial state, the residual t_n + σ_n,target,
/// its slope with respect to δ_n and the substep count.
type NormalEval<S> = (S, f64, f64, u32);

/// Solves t_n(Δδ) + σ_n,target(δ_n) = 0 for the normal increment of one step by Newton with
/// backtracking; returns the converged trial state, Δδ_n and the substep count. When Newton
/// stalls, the root is bracketed by the iterates and bisected; where σ_n(δ_n) jumps across the
/// target (a branch change of a GP law inside the step, spec G7: under stress control an exact
/// solution may not exist), the closed side of a [`BRACKET_MIN`] bracket is taken.
fn normal_equilibrium<M: InterfaceModel>(
    model: &M,
    prev: &M::State,
    control: &NormalControl,
    jump_n: f64,
    inc: [f64; 2],
    step: usize,
) -> Result<(M::State, f64, u32), DriverError> {
    let eval = |d_n: f64| -> Result<NormalEval<M::State>, DriverError> {
        let up = model
            .update(prev, &Local3::new(inc[0], inc[1], d_n))
            .map_err(|source| DriverError::Material { step, source })?;
        let (target, d_target) = control.target(jump_n + d_n);
        let residual = M::traction(&up.state)[2] + target;
        Ok((up.state, residual, up.tangent[(2, 2)] + d_target, up.substeps))
    };
    let scale = control.initial_sigma_n().abs().max(1.0);
    // residual < 0: σ_n above its target (too closed), the root lies at a larger δ_n
    let mut bracket = (f64::NEG_INFINITY, f64::INFINITY);
    let mut record = |d_n: f64, residual: f64| {
        if residual < 0.0 {
            bracket.0 = bracket.0.max(d_n);
        } else {
            bracket.1 = bracket.1.min(d_n);
        }
    };
    let mut d_n = 0.0;
    let (mut state, mut residual, mut slope, mut substeps) = eval(d_n)?;
    record(d_n, residual);
    for _ in 0..MAX_ITER {
        if residual.abs() <= NORMAL_TOL * scale {
            return Ok((state, d_n, substeps));
        }
        if !(slope.is_finite() && slope > 0.0) {
            break;
        }
        let mut alpha = 1.0;
        let correction = -residual / slope;
        loop {
            // a failed update (e.g. a closure beyond the GP interface's void-ratio bound) is a
            // correction that went too far: backtrack
            let trial = match eval(d_n + alpha * correction) {
                Err(_) if alpha >= 1e-6 => {
                    alpha *= 0.5;
                    continue;
                }
                other => other?,
            };
            record(d_n + alpha * correction, trial.1);
            if trial.1.abs() < residual.abs() || alpha < 1e-6 {
                d_n += alpha * correction;
                (state, residual, slope, substeps) = trial;
                break;
            }
            alpha *= 0.5;
        }
    }
    if residual.abs() <= NORMAL_TOL * scale {
        return Ok((state, d_n, substeps));
    }
    if bracket.0.is_finite() && bracket.1.is_finite() {
        return bisect_normal(&eval, bracket, NORMAL_TOL * scale);
    }
    Err(DriverError::NoConvergence {
        step,
        residual,
        target: control.target(jump_n + d_n).0,
    })
}

/// Bisection of the normal equilibrium on a bracket (δ_n with σ_n above, δ_n with σ_n below the
/// target) down to `tol` in the residual, or to [`BRACKET_MIN`], where the closed side is taken.
fn bisect_normal<S, F>(eval: &F, bracket: (f64, f64), tol: f64) -> Result<(S, f64, u32), DriverError>
where
    F: Fn(f64) -> Result<NormalEval<S>, DriverError>,
{
    let (mut closed, mut open) = bracket;
    while open - closed > BRACKET_MIN {
        let mid = 0.5 * (closed + open);
        let (state, residual, _, substeps) = eval(mid)?;
        if residual.abs() <= tol {
            return Ok((state, mid, substeps));
        }
        if residual < 0.0 {
            closed = mid;
        } else {
            open = mid;
        }
    }
    let (state, _, _, substeps) = eval(closed)?;
    Ok((state, closed, substeps))
}

/// Prescribed 3D jump path: every component of every step is given. Starts from
/// `model.init_state(sigma_n0)`.
pub fn jump_path<M: InterfaceModel>(
    model: &M,
    sigma_n0: f64,
    increments: &[Local3],
) -> Result<Vec<InterfaceRow>, DriverError> {
    let mut state = model
        .init_state(sigma_n0)
        .map_err(|source| DriverError::Material { step: 0, source })?;
    let mut jump = Local3::zeros();
    let mut rows = Vec::with_capacity(increments.len() + 1);
    rows.push(row_of::<M>(0, jump, &state, 0));
    for (i, inc) in increments.iter().enumerate() {
        let up = model
            .update(&state, inc)
            .map_err(|source| DriverError::Material { step: i + 1, source })?;
        jump += inc;
        state = up.state;
        rows.push(row_of::<M>(i + 1, jump, &state, up.substeps));
    }
    Ok(rows)
}

/// Increments of a 3D jump path through `waypoints` (from the origin), `steps_per_segment` each.
pub fn jump_path_increments(waypoints: &[[f64; 3]], steps_per_segment: usize) -> Vec<Local3> {
    let mut out = Vec::with_capacity(waypoints.len() * steps_per_segment);
    let mut from = Local3::zeros();
    for to in waypoints {
        let to = Local3::from(*to);
        let n = steps_per_segment.max(1);
        for _ in 0..n {
            out.push((to - from) / n as f64);
        }
        from = to;
    }
    out
}

/// Checks shared by the interface-law tests (finite-difference tangent, purity, serde round
/// trip, rotation of the shear axes).
#[cfg(test)]
pub(crate) mod checks {
    use super::*;
    use crate::tensor::Tangent3;
    use nalgebra::Matrix2;

    /// Central finite-difference tangent dT/dδ of `update` from `prev` around `d_jump`.
    pub fn fd_tangent<M: InterfaceModel>(
        model: &M,
        prev: &M::State,
        d_jump: &Local3,
        h: [f64; 3],
    ) -> Tangent3 {
        let mut d = Tangent3::zeros();
        for j in 0..3 {
            let mut e = Local3::zeros();
            e[j] = h[j];
            let tp = M::traction(&model.update(prev, &(d_jump + e)).expect("update +h").state);
            let tm = M::traction(&model.update(prev, &(d_jump - e)).expect("update -h").state);
            d.set_column(j, &((tp - tm) / (2.0 * h[j])));
        }
        d
    }

    /// Two updates from the same committed state are bitwise equal, and the state survives a
    /// YAML round trip unchanged.
    pub fn assert_pure_and_serde<M: InterfaceModel>(model: &M, prev: &M::State, d_jump: &Local3) {
        let a = model.update(prev, d_jump).expect("update a");
        let b = model.update(prev, d_jump).expect("update b");
        assert_eq!(a, b, "update is not pure");
        let text = serde_yaml::to_string(&a.state).expect("serialize");
        let back: M::State = serde_yaml::from_str(&text).expect("deserialize");
        assert_eq!(back, a.state, "serde round trip changed the state");
    }

    /// Rotation by `angle` of the (s, a) axes applied to a 3-vector.
    pub fn rotate3(angle: f64, v: &Local3) -> Local3 {
        let (s, c) = angle.sin_cos();
        Local3::new(c * v[0] - s * v[1], s * v[0] + c * v[1], v[2])
    }

    /// Rotation of a 2-vector of the (s, a) plane.
    pub fn rotate2(angle: f64, v: [f64; 2]) -> [f64; 2] {
        let r = rotate3(angle, &Local3::new(v[0], v[1], 0.0));
        [r[0], r[1]]
    }

    /// Rotation Q of the tangent: D' = Q·D·Qᵀ.
    pub fn rotate_tangent(angle: f64, d: &Tangent3) -> Tangent3 {
        let (s, c) = angle.sin_cos();
        let mut q = Tangent3::identity();
        q.fixed_view_mut::<2, 2>(0, 0)
            .copy_from(&Matrix2::new(c, -s, s, c));
        q * d * q.transpose()
    }

    /// Largest entry of |a − b| relative to the largest entry of |b| (floor `floor`).
    pub fn rel_diff(a: &Tangent3, b: &Tangent3, floor: f64) -> f64 {
        (a - b).abs().max() / b.abs().max().max(floor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::interface_hyperbolic::{HyperbolicInterface, HyperbolicParams};
    use crate::material::interface_mc::{MohrCoulombInterface, MohrCoulombParams};
    use crate::material::joint::{JointLaw, JointParams};
    use crate::material::{InterfaceOutputs, InterfaceUpdate, TangentKind};
    use crate::tensor::Tangent3;

    /// A dilatant elastic test law: τ = k_s·δ_s, t_n = k_n·(δ_n − tan ψ·‖δ_s‖) (total jump).
    struct Dilatant {
        k_s: f64,
        k_n: f64,
        tan_psi: f64,
    }

    impl InterfaceModel for Dilatant {
        type State = [f64; 6];
        fn symmetric_tangent(&self) -> bool {
            false
        }
        fn init_state(&self, sigma_n0: f64) -> Result<[f64; 6], MaterialError> {
            Ok([0.0, 0.0, -sigma_n0 / self.k_n, 0.0, 0.0, -sigma_n0])
        }
        fn update(&self, prev: &[f64; 6], d: &Local3) -> Result<InterfaceUpdate<[f64; 6]>, MaterialError> {
            let j = [prev[0] + d[0], prev[1] + d[1], prev[2] + d[2]];
            let s = j[0].hypot(j[1]);
            let t = [
                self.k_s * j[0],
                self.k_s * j[1],
                self.k_n * (j[2] - self.tan_psi * s),
            ];
            Ok(InterfaceUpdate {
                state: [j[0], j[1], j[2], t[0], t[1], t[2]],
                tangent: Tangent3::from_diagonal(&Local3::new(self.k_s, self.k_s, self.k_n)),
                kind: TangentKind::Elastic,
                substeps: 1,
            })
        }
        fn traction(s: &[f64; 6]) -> Local3 {
            Local3::new(s[3], s[4], s[5])
        }
        fn outputs(s: &[f64; 6]) -> InterfaceOutputs {
            InterfaceOutputs {
                shear: [s[0], s[1]],
                ..InterfaceOutputs::default()
            }
        }
    }

    /// CNL keeps σ_n and lets the law dilate by tan ψ·u; CNS raises σ_n by K·δ_n with
    /// δ_n = k_n·tan ψ·u/(k_n + K) (closed form of the test law), both to 10⁻⁸ relative.
    #[test]
    fn cnl_and_cns_against_closed_form() {
        let law = Dilatant {
            k_s: 1e6,
            k_n: 1e8,
            tan_psi: 0.2,
        };
        let inc = shear_path(&[[0.006, 0.008]], 20);
        let cnl = direct_shear(&law, NormalControl::ConstantLoad { sigma_n: 1e5 }, &inc).unwrap();
        let k = 5e7;
        let cns = direct_shear(
            &law,
            NormalControl::ConstantStiffness {
                sigma_n0: 1e5,
                stiffness: k,
            },
            &inc,
        )
        .unwrap();
        for (a, b) in cnl.iter().zip(&cns) {
            let u = a.jump[0].hypot(a.jump[1]);
            assert!((a.sigma_n - 1e5).abs() < 1e-8 * 1e5 && (a.jump[2] - 0.2 * u).abs() < 1e-12);
            let dn = 1e8 * 0.2 * u / (1e8 + k);
            assert!((b.jump[2] - dn).abs() < 1e-10, "{} vs {dn}", b.jump[2]);
            assert!((b.sigma_n - (1e5 + k * dn)).abs() < 1e-8 * b.sigma_n);
        }
    }

    #[test]
    fn path_builders() {
        let w = cyclic_waypoints(0.01, [0.0, 1.0], 2);
        assert_eq!(
            w,
            vec![[0.0, 0.01], [0.0, -0.01], [0.0, 0.01], [0.0, -0.01], [0.0, 0.0]]
        );
        let inc = shear_path(&w, 4);
        assert_eq!(inc.len(), 20);
        let end: f64 = inc.iter().map(|d| d[1]).sum();
        assert!(end.abs() < 1e-15);
        let j = jump_path_increments(&[[1.0, 2.0, 3.0]], 4);
        assert_eq!(j.len(), 4);
        assert!((j.iter().sum::<Local3>() - Local3::new(1.0, 2.0, 3.0)).norm() < 1e-15);
    }

    /// Updates per second of each law (release timing; run with
    /// `cargo test --release --no-default-features --lib updates_per_second -- --ignored --nocapture`).
    #[test]
    #[ignore]
    fn updates_per_second() {
        fn rate<M: InterfaceModel>(name: &str, model: &M, label: &str, inc: &[Local3]) {
            let start = std::time::Instant::now();
            let rows = jump_path(model, 1e5, inc).unwrap();
            let secs = start.elapsed().as_secs_f64();
            let substeps: u64 = rows.iter().map(|r| r.substeps as u64).sum();
            println!(
                "{name:<14} {label:<10} {:>10.3e} updates/s  ({} updates, {:.2} substeps/update)",
                inc.len() as f64 / secs,
                inc.len(),
                substeps as f64 / inc.len() as f64
            );
        }
        let n = 200_000;
        let mono = vec![Local3::new(0.1e-3, 0.05e-3, 0.0); n];
        let cyc = jump_path_increments(&[[0.01, 0.005, -1e-6], [-0.01, -0.005, 0.0]].repeat(n / 200), 100);
        let hy = HyperbolicInterface::new(&HyperbolicParams::default());
        let mc = MohrCoulombInterface::new(&MohrCoulombParams::default());
        let jt = JointLaw::new(&JointParams::default());
        rate("hyperbolic", &hy, "monotonic", &mono);
        rate("hyperbolic", &hy, "cyclic", &cyc);
        rate("mohr_coulomb", &mc, "monotonic", &mono);
        rate("mohr_coulomb", &mc, "cyclic", &cyc);
        rate("joint", &jt, "monotonic", &mono);
        rate("joint", &jt, "cyclic", &cyc);
    }
}
