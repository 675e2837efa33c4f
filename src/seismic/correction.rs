//! Corrections of a synthetic record (spec seismic §2.2 steps 6–8): the FFT spectral-ratio
//! correction, the zero-phase Butterworth-magnitude high-pass, the end-condition baseline
//! correction and the local peak adjustment that sets the PGA.
//!
//! FFTs use `rustfft`'s scalar planner (no CPU-dependent SIMD paths), so a record is the same
//! bytes on every machine with the same floating-point library.

use super::measures::integrate;
use rustfft::num_complex::Complex;
use rustfft::FftPlannerScalar;

/// Zero padding (s) after the record for the FFT-domain operations (spec seismic §2.2 step 8
/// asks for ≥ 10–20 s): the acausal spread of a zero-phase gain falls into the padding and is
/// cut off with it.
pub const FFT_PADDING: f64 = 20.0;
/// Order of the Butterworth magnitude of the high-pass, |H| = 1/√(1 + (f_c/f)^(2·order)).
pub const HIGHPASS_ORDER: i32 = 4;
/// Most peak adjustments tried by [`enforce_pga`] before it gives up.
const MAX_PEAK_ADJUSTMENTS: usize = 10_000;

/// Multiplies the spectrum of `signal` (zero-padded by [`FFT_PADDING`], sampled at `dt`) by the
/// real, even gain `gain(f)` (f ≥ 0 in Hz) and returns the first `signal.len()` samples of the
/// result: a zero-phase filter.
pub fn apply_zero_phase_gain(signal: &[f64], dt: f64, gain: impl Fn(f64) -> f64) -> Vec<f64> {
    let n = signal.len();
    let n_fft = (n + (FFT_PADDING / dt).ceil() as usize).next_power_of_two();
    let mut planner = FftPlannerScalar::<f64>::new();
    let mut buf: Vec<Complex<f64>> = signal.iter().map(|&x| Complex::new(x, 0.0)).collect();
    buf.resize(n_fft, Complex::new(0.0, 0.0));
    planner.plan_fft_forward(n_fft).process(&mut buf);
    let df = 1.0 / (n_fft as f64 * dt);
    for (k, z) in buf.iter_mut().enumerate() {
        let bin = k.min(n_fft - k);
        *z *= gain(bin as f64 * df);
    }
    planner.plan_fft_inverse(n_fft).process(&mut buf);
    buf.iter().take(n).map(|z| z.re / n_fft as f64).collect()
}

/// Spectral-ratio gain R(f) from the ratios `ratio[j]` = Sa_target/Sa at `periods[j]`
/// (increasing): linear in log T between control periods, constant beyond both ends (spec
/// seismic §2.2 step 6: R at the shortest/longest period, not 1).
pub fn ratio_gain(periods: &[f64], ratio: &[f64], f: f64) -> f64 {
    let (first, last) = (ratio[0], ratio[ratio.len() - 1]);
    if f <= 0.0 {
        return last;
    }
    let t = 1.0 / f;
    if t <= periods[0] {
        return first;
    }
    if t >= periods[periods.len() - 1] {
        return last;
    }
    let j = periods.partition_point(|&p| p <= t).clamp(1, periods.len() - 1);
    let s = (t / periods[j - 1]).ln() / (periods[j] / periods[j - 1]).ln();
    ratio[j - 1] + (ratio[j] - ratio[j - 1]) * s
}

/// Zero-phase high-pass with the Butterworth magnitude of [`HIGHPASS_ORDER`] and corner
/// `fc` (Hz), spec seismic §2.2 step 8. `fc` = 0 leaves the record unchanged.
pub fn highpass(signal: &[f64], dt: f64, fc: f64) -> Vec<f64> {
    if fc <= 0.0 {
        return signal.to_vec();
    }
    apply_zero_phase_gain(signal, dt, |f| {
        if f <= 0.0 {
            0.0
        } else {
            1.0 / (1.0 + (fc / f).powi(2 * HIGHPASS_ORDER)).sqrt()
        }
    })
}

/// Makes the end velocity and displacement zero (spec seismic §2.2 step 8, the low-order
/// baseline variant): subtracts w(t)·(α + β·t/T) with w the intensity envelope `weight`
/// sampled at the record's instants, α and β solving the two linear end conditions of the
/// integration of [`integrate`].
pub fn zero_end_motion(signal: &mut [f64], dt: f64, weight: &[f64]) {
    let n = signal.len();
    let duration = (n - 1) as f64 * dt;
    let ramp: Vec<f64> = weight
        .iter()
        .enumerate()
        .map(|(i, w)| w * i as f64 * dt / duration)
        .collect();
    let ends = |a: &[f64]| {
        let (v, d) = integrate(a, dt);
        (v[n - 1], d[n - 1])
    };
    let (v0, d0) = ends(signal);
    let (v1, d1) = ends(weight);
    let (v2, d2) = ends(&ramp);
    let det = v1 * d2 - v2 * d1;
    if det.abs() < f64::MIN_POSITIVE {
        return;
    }
    let alpha = (v0 * d2 - v2 * d0) / det;
    let beta = (v1 * d0 - v0 * d1) / det;
    for ((a, w), r) in signal.iter_mut().zip(weight).zip(&ramp) {
        *a -= alpha * w + beta * r;
    }
}

/// Half-cosine taper weight of sample i of n over `length` samples at both ends: 0 at the
/// first and last samples, 1 in between.
pub fn end_taper(i: usize, n: usize, length: usize) -> f64 {
    let from_end = i.min(n - 1 - i);
    if length == 0 || from_end >= length {
        1.0
    } else {
        0.5 * (1.0 - (std::f64::consts::PI * from_end as f64 / length as f64).cos())
    }
}

/// Index and value of the largest |a|.
fn peak(signal: &[f64]) -> (usize, f64) {
    signal.iter().enumerate().fold(
        (0, 0.0),
        |(ip, vp), (i, &v)| if v.abs() > vp { (i, v.abs()) } else { (ip, vp) },
    )
}

/// Sets max|a| to `pga` by local peak adjustment, not scaling (spec seismic §2.2 step 7): the
/// largest peak t_p is multiplied by k = pga/|a(t_p)| through the smooth window
/// 1 + (k − 1)·exp(−(t − t_p)²/(2σ²)), repeated (for k < 1, peak after peak) until
/// max|a| = pga. Returns the number of adjustments, or `None` if it did not converge.
pub fn enforce_pga(signal: &mut [f64], dt: f64, pga: f64, sigma: f64) -> Option<usize> {
    let half_width = (6.0 * sigma / dt).ceil() as usize;
    for count in 0..MAX_PEAK_ADJUSTMENTS {
        let (p, value) = peak(signal);
        if value == 0.0 {
            return None;
        }
        let k = pga / value;
        if (k - 1.0).abs() <= 1e-12 {
            return Some(count);
        }
        let range = p.saturating_sub(half_width)..(p + half_width + 1).min(signal.len());
        for i in range {
            let x = (i as f64 - p as f64) * dt / sigma;
            signal[i] *= 1.0 + (k - 1.0) * (-0.5 * x * x).exp();
        }
        signal[p] = signal[p].signum() * pga;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A unit gain returns the signal; the gain acts on the frequency of a sine.
    #[test]
    fn zero_phase_gain_scales_a_sine() {
        let dt = 0.01;
        let n = 2000;
        let s: Vec<f64> = (0..n).map(|i| (2.0 * PI * 2.0 * i as f64 * dt).sin()).collect();
        let same = apply_zero_phase_gain(&s, dt, |_| 1.0);
        assert!(s.iter().zip(&same).all(|(a, b)| (a - b).abs() < 1e-12));
        let half = apply_zero_phase_gain(&s, dt, |f| if f > 1.0 { 0.5 } else { 1.0 });
        let mid = n / 2;
        assert!(
            (half[mid] - 0.5 * s[mid]).abs() < 0.02,
            "{} {}",
            half[mid],
            s[mid]
        );
    }

    #[test]
    fn ratio_gain_interpolates_in_log_period_and_extrapolates_constant() {
        let periods = [0.1, 1.0];
        let ratio = [2.0, 4.0];
        assert_eq!(ratio_gain(&periods, &ratio, 100.0), 2.0);
        assert_eq!(ratio_gain(&periods, &ratio, 0.1), 4.0);
        assert_eq!(ratio_gain(&periods, &ratio, 0.0), 4.0);
        let mid = ratio_gain(&periods, &ratio, 1.0 / 0.1f64.sqrt());
        assert!((mid - 3.0).abs() < 1e-12, "{mid}");
    }

    /// A constant offset is removed by the high-pass; the end motion is zeroed exactly.
    #[test]
    fn baseline_corrections_remove_drift() {
        let dt = 0.01;
        let n = 2001;
        let s: Vec<f64> = (0..n)
            .map(|i| 0.05 + (2.0 * PI * 3.0 * i as f64 * dt).sin())
            .collect();
        let hp = highpass(&s, dt, 0.1);
        let mid_mean: f64 = hp[500..1500].iter().sum::<f64>() / 1000.0;
        assert!(mid_mean.abs() < 5e-3, "{mid_mean}");
        let weight: Vec<f64> = (0..n).map(|i| (PI * i as f64 / (n - 1) as f64).sin()).collect();
        let mut z = s.clone();
        zero_end_motion(&mut z, dt, &weight);
        let (v, d) = integrate(&z, dt);
        assert!(
            v[n - 1].abs() < 1e-12 && d[n - 1].abs() < 1e-10,
            "{} {}",
            v[n - 1],
            d[n - 1]
        );
    }

    #[test]
    fn end_taper_goes_from_zero_to_one() {
        assert_eq!(end_taper(0, 100, 10), 0.0);
        assert_eq!(end_taper(99, 100, 10), 0.0);
        assert!((end_taper(5, 100, 10) - 0.5).abs() < 1e-15);
        assert_eq!(end_taper(50, 100, 10), 1.0);
    }

    /// The peak adjustment reaches the target exactly, up and down, leaving far samples alone.
    #[test]
    fn peak_adjustment_sets_the_pga() {
        let dt = 0.01;
        let s: Vec<f64> = (0..1000)
            .map(|i| (0.37 * i as f64).sin() * (1.0 + 0.2 * (0.011 * i as f64).cos()))
            .collect();
        for target in [1.5, 0.9] {
            let mut a = s.clone();
            let count = enforce_pga(&mut a, dt, target, 0.02).unwrap();
            let max = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(count >= 1 && (max - target).abs() < 1e-12, "{target}: {max}");
        }
        let mut flat = vec![0.0; 10];
        assert_eq!(enforce_pga(&mut flat, dt, 1.0, 0.02), None);
    }
}
