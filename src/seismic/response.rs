//! Elastic response spectra of a ground-acceleration record (spec seismic §2.2 step 5).
//!
//! The single-degree-of-freedom oscillator of period T = 2π/ω and damping ratio ζ < 1,
//!
//! ```text
//! ü + 2ζω·u̇ + ω²·u = −a_g(t)          u = displacement relative to the ground
//! ```
//!
//! is integrated exactly for a piecewise-linear a_g(t) (Nigam & Jennings 1969): on a step of
//! length h with a_g = p + q·τ, the solution is the particular part u_p = α + β·τ,
//! β = −q/ω², α = −p/ω² + 2ζq/ω³, plus the free damped vibration of (u − u_p, u̇ − β)
//! through the transition matrix
//!
//! ```text
//! E = exp(−ζωh), ω_d = ω·√(1 − ζ²), c = cos ω_d h, s = sin ω_d h, z = ζ/√(1 − ζ²)
//! Φ = E·[ c + z·s      s/ω_d  ]
//!       [ −ω_d(1 + z²)·s  c − z·s ]
//! ```
//!
//! The record is followed by [`TRAILING_ZEROS`] s (at least two periods) of zero input, so the
//! free vibration after the record counts; for T < [`SUBSTEP_RATIO`]·dt the input is
//! sub-stepped (linearly interpolated, which leaves the exact solution unchanged) to steps
//! of at most T/10; the peak between two samples where u̇ changes sign is located on the
//! cubic Hermite interpolant of (u, u̇). The spectral value is the pseudo-acceleration
//! Sa = ω²·max|u|.
//!
//! # References
//! Nigam, N. C. & Jennings, P. C. (1969). Calculation of response spectra from strong-motion
//! earthquake records. Bull. Seismol. Soc. Am. 59(2), 909–922.

use crate::error::{require_positive, require_range, ParamError};

/// Zero input appended after the record (s), spec seismic §2.2 step 5 (at least two periods
/// are appended for longer periods).
pub const TRAILING_ZEROS: f64 = 5.0;
/// The input is sub-stepped when T < SUBSTEP_RATIO·dt, to steps h ≤ T/SUBSTEP_RATIO.
pub const SUBSTEP_RATIO: f64 = 10.0;

/// A damped linear oscillator: period T (s) and damping ratio ζ ∈ [0, 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Oscillator {
    /// Natural period T (s).
    pub period: f64,
    /// Damping ratio ζ (0.05 for the design spectra, spec seismic §1.1).
    pub damping: f64,
}

impl Oscillator {
    /// An oscillator; rejects T ≤ 0 and ζ ∉ [0, 0.99].
    pub fn new(period: f64, damping: f64) -> Result<Self, ParamError> {
        require_positive("period", period)?;
        require_range("damping", damping, 0.0, 0.99)?;
        Ok(Oscillator { period, damping })
    }

    /// Circular frequency ω = 2π/T (rad/s).
    pub fn omega(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.period
    }
}

/// The exact step of length `h` for a linear input (see the module docs).
#[derive(Debug, Clone, Copy)]
struct ExactStep {
    h: f64,
    phi: [[f64; 2]; 2],
    inv_w2: f64,
    two_zeta_w3: f64,
}

impl ExactStep {
    fn new(osc: Oscillator, h: f64) -> Self {
        let (w, zeta) = (osc.omega(), osc.damping);
        let root = (1.0 - zeta * zeta).sqrt();
        let (wd, z) = (w * root, zeta / root);
        let e = (-zeta * w * h).exp();
        let (s, c) = (wd * h).sin_cos();
        ExactStep {
            h,
            phi: [
                [e * (c + z * s), e * s / wd],
                [-e * wd * (1.0 + z * z) * s, e * (c - z * s)],
            ],
            inv_w2: 1.0 / (w * w),
            two_zeta_w3: 2.0 * zeta / (w * w * w),
        }
    }

    /// (u, u̇) at the end of the step from (u, u̇) at its start, for a_g going from `a0` to `a1`.
    fn advance(&self, [u, v]: [f64; 2], a0: f64, a1: f64) -> [f64; 2] {
        let q = (a1 - a0) / self.h;
        let beta = -q * self.inv_w2;
        let alpha = -a0 * self.inv_w2 + q * self.two_zeta_w3;
        let (du, dv) = (u - alpha, v - beta);
        let p = &self.phi;
        [
            alpha + beta * self.h + p[0][0] * du + p[0][1] * dv,
            beta + p[1][0] * du + p[1][1] * dv,
        ]
    }
}

/// The exact step of `osc` over a length `h` as a function (u, u̇), a0, a1 → (u, u̇).
pub(crate) fn exact_step(osc: Oscillator, h: f64) -> impl Fn([f64; 2], f64, f64) -> [f64; 2] {
    let step = ExactStep::new(osc, h);
    move |state, a0, a1| step.advance(state, a0, a1)
}

/// Largest |u| on [0, h] of the cubic Hermite interpolant of (u0, v0) and (u1, v1), used when
/// the velocity changes sign inside the step.
fn hermite_peak([u0, v0]: [f64; 2], [u1, v1]: [f64; 2], h: f64) -> f64 {
    let (m0, m1) = (h * v0, h * v1);
    let a = 6.0 * u0 + 3.0 * m0 - 6.0 * u1 + 3.0 * m1;
    let b = -6.0 * u0 - 4.0 * m0 + 6.0 * u1 - 2.0 * m1;
    let c = m0;
    let root = if a.abs() < 1e-14 * (b.abs() + c.abs()) {
        -c / b
    } else {
        let d = (b * b - 4.0 * a * c).max(0.0).sqrt();
        let (r1, r2) = ((-b + d) / (2.0 * a), (-b - d) / (2.0 * a));
        if (0.0..=1.0).contains(&r1) {
            r1
        } else {
            r2
        }
    };
    let s = root.clamp(0.0, 1.0);
    let (s2, s3) = (s * s, s * s * s);
    let p = (2.0 * s3 - 3.0 * s2 + 1.0) * u0
        + (s3 - 2.0 * s2 + s) * m0
        + (-2.0 * s3 + 3.0 * s2) * u1
        + (s3 - s2) * m1;
    p.abs().max(u0.abs()).max(u1.abs())
}

/// Relative displacement u and velocity u̇ of the oscillator at the record's instants
/// t_i = i·dt, starting at rest (no trailing zeros, no sub-stepping: the recurrence is exact).
pub fn response_history(accel: &[f64], dt: f64, osc: Oscillator) -> Vec<[f64; 2]> {
    let step = ExactStep::new(osc, dt);
    let mut state = [0.0, 0.0];
    let mut out = Vec::with_capacity(accel.len());
    out.push(state);
    for w in accel.windows(2) {
        state = step.advance(state, w[0], w[1]);
        out.push(state);
    }
    out
}

/// Peak |u| of the oscillator under the record followed by the trailing zeros, sub-stepped
/// when T < 10·dt (see the module docs).
pub fn peak_displacement(accel: &[f64], dt: f64, osc: Oscillator) -> f64 {
    let substeps = (SUBSTEP_RATIO * dt / osc.period).ceil().max(1.0) as usize;
    let h = dt / substeps as f64;
    let step = ExactStep::new(osc, h);
    let tail = (TRAILING_ZEROS.max(2.0 * osc.period) / dt).ceil() as usize;
    let input = |i: usize| accel.get(i).copied().unwrap_or(0.0);
    let mut state = [0.0, 0.0];
    let mut peak: f64 = 0.0;
    for i in 0..(accel.len() + tail) {
        let (a0, a1) = (input(i), input(i + 1));
        for k in 0..substeps {
            let s0 = k as f64 / substeps as f64;
            let s1 = (k + 1) as f64 / substeps as f64;
            let next = step.advance(state, a0 + (a1 - a0) * s0, a0 + (a1 - a0) * s1);
            peak = if state[1] * next[1] < 0.0 {
                peak.max(hermite_peak(state, next, h))
            } else {
                peak.max(next[0].abs())
            };
            state = next;
        }
    }
    peak
}

/// Pseudo-acceleration Sa = ω²·max|u| of one oscillator (unit of `accel`).
pub fn pseudo_acceleration(accel: &[f64], dt: f64, osc: Oscillator) -> f64 {
    let w = osc.omega();
    w * w * peak_displacement(accel, dt, osc)
}

/// Pseudo-acceleration response spectrum Sa(T_j) at `periods` for damping ratio `damping`.
/// Rejects dt ≤ 0, a period ≤ 0 and ζ ∉ [0, 0.99].
pub fn response_spectrum(
    accel: &[f64],
    dt: f64,
    periods: &[f64],
    damping: f64,
) -> Result<Vec<f64>, ParamError> {
    require_positive("dt", dt)?;
    periods
        .iter()
        .map(|&t| Oscillator::new(t, damping).map(|osc| pseudo_acceleration(accel, dt, osc)))
        .collect()
}

/// `n` ≥ 2 periods log-spaced from `lo` to `hi` inclusive.
pub fn log_spaced(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let n = n.max(2);
    let ratio = (hi / lo).ln() / (n - 1) as f64;
    (0..n).map(|j| lo * (ratio * j as f64).exp()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix4;
    use std::f64::consts::PI;

    /// A long sine at the oscillator's frequency: steady amplitude 1/(2ζ) × static, so
    /// Sa = A/(2ζ) (spec seismic §4 item 2a).
    #[test]
    fn harmonic_resonance_reaches_the_steady_amplitude() {
        for (period, zeta) in [(0.5, 0.05), (0.1, 0.05), (1.0, 0.02)] {
            let osc = Oscillator::new(period, zeta).unwrap();
            let dt = period / 200.0;
            let amplitude = 2.0;
            let n = (120.0 / zeta * period / dt) as usize;
            let accel: Vec<f64> = (0..n)
                .map(|i| amplitude * (osc.omega() * i as f64 * dt).sin())
                .collect();
            let sa = pseudo_acceleration(&accel, dt, osc);
            let expected = amplitude / (2.0 * zeta);
            assert!(
                (sa / expected - 1.0).abs() < 1e-3,
                "T {period} ζ {zeta}: {sa} vs {expected}"
            );
        }
    }

    /// The state-space solution of x' = M·x for x = (u, u̇, a_g, ȧ_g) over one step of a
    /// piecewise-linear input, by the matrix exponential (nalgebra's Padé approximant).
    fn exact_by_matrix_exponential(accel: &[f64], dt: f64, osc: Oscillator) -> Vec<[f64; 2]> {
        let (w, zeta) = (osc.omega(), osc.damping);
        #[rustfmt::skip]
        let m = Matrix4::new(
            0.0, 1.0, 0.0, 0.0,
            -w * w, -2.0 * zeta * w, -1.0, 0.0,
            0.0, 0.0, 0.0, 1.0,
            0.0, 0.0, 0.0, 0.0,
        );
        let phi = (m * dt).exp();
        let mut state = [0.0, 0.0];
        let mut out = vec![state];
        for pair in accel.windows(2) {
            let x = nalgebra::Vector4::new(state[0], state[1], pair[0], (pair[1] - pair[0]) / dt);
            let next = phi * x;
            state = [next[0], next[1]];
            out.push(state);
        }
        out
    }

    /// A deterministic, irregular piecewise-linear input (m/s²).
    fn irregular_input(n: usize, dt: f64) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let t = i as f64 * dt;
                3.0 * (7.3 * t).sin() * (1.1 * t).cos() + 1.5 * (23.0 * t + 0.4).sin() - 0.7 * (2.0 * t).cos()
            })
            .collect()
    }

    /// Nigam–Jennings against the matrix-exponential solution to 1e-6 relative
    /// (spec seismic §4 item 2).
    #[test]
    fn matches_the_state_space_solution() {
        let dt = 0.01;
        let accel = irregular_input(1500, dt);
        for (period, zeta) in [(0.05, 0.05), (0.3, 0.05), (1.2, 0.02), (3.0, 0.10)] {
            let osc = Oscillator::new(period, zeta).unwrap();
            let nj = response_history(&accel, dt, osc);
            let ss = exact_by_matrix_exponential(&accel, dt, osc);
            let scale_u = ss.iter().map(|s| s[0].abs()).fold(0.0, f64::max);
            let scale_v = ss.iter().map(|s| s[1].abs()).fold(0.0, f64::max);
            for (a, b) in nj.iter().zip(&ss) {
                assert!(
                    (a[0] - b[0]).abs() <= 1e-6 * scale_u,
                    "T {period}: u {} vs {}",
                    a[0],
                    b[0]
                );
                assert!(
                    (a[1] - b[1]).abs() <= 1e-6 * scale_v,
                    "T {period}: v {} vs {}",
                    a[1],
                    b[1]
                );
            }
        }
    }

    /// Peak |u| by Newmark average acceleration with `substeps` sub-steps per record step,
    /// the record followed by the same trailing zeros.
    fn newmark_peak(accel: &[f64], dt: f64, osc: Oscillator, substeps: usize) -> f64 {
        let (w, zeta) = (osc.omega(), osc.damping);
        let h = dt / substeps as f64;
        let tail = (TRAILING_ZEROS.max(2.0 * osc.period) / dt).ceil() as usize;
        let input = |i: usize| accel.get(i).copied().unwrap_or(0.0);
        let k_eff = w * w + 2.0 * zeta * w * 2.0 / h + 4.0 / (h * h);
        let (mut u, mut v) = (0.0, 0.0);
        let mut acc = -input(0);
        let mut peak: f64 = 0.0;
        for i in 0..(accel.len() + tail) {
            for k in 1..=substeps {
                let s = k as f64 / substeps as f64;
                let ag = input(i) + (input(i + 1) - input(i)) * s;
                let rhs = -ag + (4.0 / (h * h) * u + 4.0 / h * v + acc) + 2.0 * zeta * w * (2.0 / h * u + v);
                let u_new = rhs / k_eff;
                let v_new = 2.0 / h * (u_new - u) - v;
                acc = 4.0 / (h * h) * (u_new - u) - 4.0 / h * v - acc;
                (u, v) = (u_new, v_new);
                peak = peak.max(u.abs());
            }
        }
        peak
    }

    /// Sa against sub-stepped Newmark (20 sub-steps) within 2 % (spec seismic §4 item 2).
    #[test]
    fn agrees_with_substepped_newmark() {
        let dt = 0.01;
        let accel = irregular_input(1000, dt);
        for period in log_spaced(0.04, 3.0, 12) {
            let osc = Oscillator::new(period, 0.05).unwrap();
            let nj = peak_displacement(&accel, dt, osc);
            let nm = newmark_peak(&accel, dt, osc, 20);
            assert!((nj / nm - 1.0).abs() < 0.02, "T {period}: {nj} vs {nm}");
        }
    }

    /// The Hermite peak finds the crest of a sampled cosine between two samples.
    #[test]
    fn hermite_peak_locates_the_crest() {
        let (w, h) = (2.0 * PI, 0.1);
        let (t0, t1) = (-0.04, 0.06);
        let s0 = [(w * t0).cos(), -w * (w * t0).sin()];
        let s1 = [(w * t1).cos(), -w * (w * t1).sin()];
        let p = hermite_peak(s0, s1, h);
        assert!((p - 1.0).abs() < 1e-3 && p > s0[0].max(s1[0]) + 0.03, "{p}");
    }

    #[test]
    fn rejects_invalid_parameters() {
        assert_eq!(Oscillator::new(0.0, 0.05).unwrap_err().field, "period");
        assert_eq!(Oscillator::new(1.0, 1.0).unwrap_err().field, "damping");
        assert_eq!(
            response_spectrum(&[0.0], -1.0, &[1.0], 0.05).unwrap_err().field,
            "dt"
        );
        let p = log_spaced(0.04, 3.0, 50);
        assert!(p.len() == 50 && (p[0] - 0.04).abs() < 1e-15 && (p[49] - 3.0).abs() < 1e-12);
    }
}
