//! Zero-phase low-pass filtering of a sampled history: a Butterworth filter of order 4 (two
//! second-order sections from the bilinear transform with the cut-off pre-warped), run forward
//! and then backward, so the result has no phase shift and the squared magnitude response
//! |H(f)|² = 1 / (1 + (tan(πf/f_s) / tan(πf_c/f_s))⁸) (what `scipy.signal.sosfiltfilt` does with
//! `butter(4, f_c, fs=f_s, output='sos')`). cfrd uses it to tell a resolved peak of a response
//! history from a single-step spike: the raw peak against the peak of the history low-passed at
//! 20 Hz (`spike_ratio` in a quake's `quake_summary.json`).

use std::f64::consts::PI;

/// One second-order section y = (b₀ + b₁z⁻¹ + b₂z⁻²) / (1 + a₁z⁻¹ + a₂z⁻²) x.
#[derive(Debug, Clone, Copy)]
struct Biquad {
    b: [f64; 3],
    a: [f64; 2],
}

impl Biquad {
    /// The low-pass section of quality factor `q` at the pre-warped cut-off `k` = tan(πf_c/f_s).
    fn low_pass(k: f64, q: f64) -> Biquad {
        let norm = 1.0 / (1.0 + k / q + k * k);
        let b0 = k * k * norm;
        Biquad {
            b: [b0, 2.0 * b0, b0],
            a: [2.0 * (k * k - 1.0) * norm, (1.0 - k / q + k * k) * norm],
        }
    }

    /// Filters `x` in place (transposed direct form II), the states set to the steady state of
    /// a constant input equal to `x[0]` (unit gain at zero frequency), so a history that starts
    /// away from zero starts without a transient.
    fn run(&self, x: &mut [f64]) {
        let Some(&x0) = x.first() else { return };
        let [b0, b1, b2] = self.b;
        let [a1, a2] = self.a;
        let (mut z1, mut z2) = ((1.0 - b0) * x0, (b2 - a2) * x0);
        for v in x.iter_mut() {
            let y = b0 * *v + z1;
            z1 = b1 * *v - a1 * y + z2;
            z2 = b2 * *v - a2 * y;
            *v = y;
        }
    }
}

/// `x` sampled every `dt` seconds, low-passed at `cutoff` Hz by the zero-phase Butterworth
/// filter of order 4 (the module docs); the ends are extended by odd reflection over three
/// periods of the cut-off (at most the history's length) before filtering. `None` when the
/// cut-off is not below the Nyquist frequency 1/(2·dt) or the arguments are not positive.
pub fn low_pass_zero_phase(x: &[f64], dt: f64, cutoff: f64) -> Option<Vec<f64>> {
    let nyquist_ratio = 2.0 * cutoff * dt;
    if !(dt > 0.0 && cutoff > 0.0 && nyquist_ratio < 1.0) {
        return None;
    }
    if x.len() < 2 {
        return Some(x.to_vec());
    }
    let k = (PI * cutoff * dt).tan();
    // the poles of order 4 at 22.5° and 67.5° from the imaginary axis
    let sections = [
        Biquad::low_pass(k, 1.0 / (2.0 * (PI / 8.0).cos())),
        Biquad::low_pass(k, 1.0 / (2.0 * (3.0 * PI / 8.0).cos())),
    ];
    let pad = ((3.0 / (cutoff * dt)).ceil() as usize).min(x.len() - 1);
    let (first, last) = (x[0], x[x.len() - 1]);
    let mut y: Vec<f64> = (1..=pad).rev().map(|i| 2.0 * first - x[i]).collect();
    y.extend_from_slice(x);
    y.extend((1..=pad).map(|i| 2.0 * last - x[x.len() - 1 - i]));
    // forward, then backward: the phase shifts cancel
    for _ in 0..2 {
        for s in &sections {
            s.run(&mut y);
        }
        y.reverse();
    }
    Some(y[pad..pad + x.len()].to_vec())
}

/// The values of a history sampled at times `t` (increasing) at the uniform grid 0, `dt`, 2`dt`,
/// … up to the last time, by linear interpolation (a run's time steps are uniform but for the
/// steps cut back, which add samples between).
pub fn on_uniform_grid(t: &[f64], x: &[f64], dt: f64) -> Vec<f64> {
    let Some(&end) = t.last() else {
        return Vec::new();
    };
    let n = ((end - t[0]) / dt + 1e-9).floor() as usize;
    let mut j = 0;
    (0..=n)
        .map(|i| {
            let ti = t[0] + i as f64 * dt;
            while j + 2 < t.len() && t[j + 1] < ti {
                j += 1;
            }
            match t.get(j + 1) {
                Some(&t1) if t1 > t[j] => {
                    let w = ((ti - t[j]) / (t1 - t[j])).clamp(0.0, 1.0);
                    x[j] + w * (x[j + 1] - x[j])
                }
                _ => x[j],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The squared magnitude of the zero-phase filter at `f` (the module docs).
    fn gain(f: f64, fc: f64, dt: f64) -> f64 {
        let r = (PI * f * dt).tan() / (PI * fc * dt).tan();
        1.0 / (1.0 + r.powi(8))
    }

    /// The amplitude of `y` at frequency `f` over whole periods (least squares on sin and cos).
    fn amplitude_and_phase(y: &[f64], f: f64, dt: f64) -> (f64, f64) {
        let (mut s, mut c) = (0.0, 0.0);
        for (i, v) in y.iter().enumerate() {
            let w = 2.0 * PI * f * i as f64 * dt;
            s += v * w.sin();
            c += v * w.cos();
        }
        let n = y.len() as f64 / 2.0;
        ((s * s + c * c).sqrt() / n, c.atan2(s))
    }

    #[test]
    fn sines_pass_with_the_butterworth_gain_and_no_phase_shift() {
        let dt = 0.01;
        for (f, periods) in [
            (2.0_f64, 40.0_f64),
            (10.0, 100.0),
            (20.0, 200.0),
            (30.0, 300.0),
            (40.0, 400.0),
        ] {
            let n = (periods / (f * dt)).round() as usize;
            let x: Vec<f64> = (0..n).map(|i| (2.0 * PI * f * i as f64 * dt).sin()).collect();
            let y = low_pass_zero_phase(&x, dt, 20.0).unwrap();
            // away from the ends, where the reflection is not the signal's continuation
            let (a, b) = (n / 4, n / 4 + n / 2);
            let (amp, phase) = amplitude_and_phase(&y[a..b], f, dt);
            let (amp_x, phase_x) = amplitude_and_phase(&x[a..b], f, dt);
            let want = gain(f, 20.0, dt);
            assert!(
                (amp / amp_x - want).abs() < 1e-3 * want.max(1e-3),
                "{f} Hz: gain {} against {want}",
                amp / amp_x
            );
            if want > 1e-3 {
                assert!(
                    (phase - phase_x).abs() < 1e-6,
                    "{f} Hz: phase {phase} against {phase_x}"
                );
            }
        }
    }

    #[test]
    fn a_single_sample_spike_is_cut_and_a_constant_kept() {
        let dt = 0.01;
        let mut x = vec![1.0; 400];
        x[200] = 51.0;
        let y = low_pass_zero_phase(&x, dt, 20.0).unwrap();
        let peak = y.iter().copied().fold(f64::MIN, f64::max);
        assert!(peak < 1.0 + 0.45 * 50.0, "the spike kept to {peak}");
        assert!(
            (y[0] - 1.0).abs() < 1e-12 && (y[399] - 1.0).abs() < 1e-12,
            "{} {}",
            y[0],
            y[399]
        );
        assert!((y.iter().sum::<f64>() - x.iter().sum::<f64>()).abs() < 1e-6 * 450.0);
        assert!(
            low_pass_zero_phase(&x, 0.03, 20.0).is_none(),
            "above the Nyquist frequency"
        );
    }

    #[test]
    fn a_history_with_cut_back_steps_is_resampled_on_the_uniform_grid() {
        let t = [0.0, 0.01, 0.015, 0.02, 0.03];
        let x = [0.0, 1.0, 5.0, 2.0, 3.0];
        let y = on_uniform_grid(&t, &x, 0.01);
        assert_eq!(y, vec![0.0, 1.0, 2.0, 3.0]);
    }
}
