//! Spectrum-compatible artificial accelerograms by the trigonometric-series method (spec
//! seismic §2.2; the algorithm and its measured performance are written up in
//! [`crate::seismic::algorithm`]).
//!
//! One component: target PSD from the design spectrum (Kaul/Vanmarcke, step 2), a sum of
//! cosines with random phases (step 3) under the Jennings–Housner–Tsai envelope (step 4), then
//! iterations that alternate the FFT spectral-ratio correction (step 6) with the zero-phase
//! high-pass and end-condition baseline correction (step 8) and the local peak adjustment
//! that sets the PGA (step 7), checking the 5 %-damped spectrum (step 5) every time and keeping
//! the best iterate. Three components (step 9) use independent ChaCha20 streams of one seed.

use super::correction::{
    apply_zero_phase_gain, end_taper, enforce_pga, highpass, ratio_gain, zero_end_motion,
};
use super::measures::{correlation, integrate, MotionMeasures, SpectralMatch};
use super::record::{Accelerogram, Axis};
use super::response::{log_spaced, response_spectrum};
use super::spectrum::DesignSpectrum;
use super::wavelet::wavelet_correction;
use crate::error::{require_positive, require_range, ParamError};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha20Rng;
use std::f64::consts::PI;
use thiserror::Error;

/// Number of log-spaced periods of the compatibility check (spec seismic §2.3 asks ≥ 50).
pub const ACCEPTANCE_COUNT: usize = 60;
/// Shortest period of the compatibility check (s), spec seismic §2.3.
pub const ACCEPTANCE_MIN_PERIOD: f64 = 0.04;
/// Shortest control period of the correction (s), spec seismic §2.2 step 5.
pub const CONTROL_MIN_PERIOD: f64 = 0.025;
/// Accepted spectral error at every check period, spec seismic §2.3.
pub const ACCEPTANCE_MAX_ERROR: f64 = 0.10;
/// Accepted mean spectral error, spec seismic §2.3.
pub const ACCEPTANCE_MEAN_ERROR: f64 = 0.05;
/// Length of the half-cosine taper at both ends of the record (s).
pub const END_TAPER: f64 = 0.5;
/// Rounds of end-condition correction and peak adjustment that finish an iterate.
const FINISH_ROUNDS: usize = 10;

/// A generation that could not be done.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeneratorError {
    /// A setting is out of range.
    #[error("{0}")]
    Invalid(#[from] ParamError),
    /// The peak adjustment did not reach the PGA (e.g. a record of zeros).
    #[error("component {axis}: the peak adjustment could not reach PGA = {pga} m/s²")]
    Pga {
        /// Component (`x`, `y`, `z`).
        axis: &'static str,
        /// Target PGA (m/s²).
        pga: f64,
    },
}

/// Jennings–Housner–Tsai (1969) intensity envelope (spec seismic §2.2 step 4):
/// f(t) = (t/t1)² for t < t1, 1 on [t1, t2], exp(−c·(t − t2)) after t2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Envelope {
    /// End of the rise (s).
    pub t1: f64,
    /// End of the stationary part (s); t2 − t1 is the strong-motion duration T_d.
    pub t2: f64,
    /// Decay rate of the tail (1/s).
    pub c: f64,
}

impl Envelope {
    /// The envelope value at time t (s).
    pub fn at(&self, t: f64) -> f64 {
        if t < self.t1 {
            (t / self.t1).powi(2)
        } else if t <= self.t2 {
            1.0
        } else {
            (-self.c * (t - self.t2)).exp()
        }
    }

    /// Strong-motion (stationary) duration T_d = t2 − t1 (s), spec seismic §2.2 step 2.
    pub fn strong_duration(&self) -> f64 {
        self.t2 - self.t1
    }
}

/// The target of one component: the normalized design spectrum and the PGA it scales.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComponentTarget {
    /// Normalized spectrum β(T).
    pub spectrum: DesignSpectrum,
    /// Design PGA a (m/s²); the target is Sa(T) = a·β(T).
    pub pga: f64,
}

impl ComponentTarget {
    /// Target pseudo-acceleration Sa(T) (m/s²).
    pub fn sa(&self, period: f64) -> f64 {
        self.spectrum.sa(period, self.pga)
    }
}

/// Settings of the generator (spec seismic §2.2 inputs). [`GeneratorSettings::new`] fills the
/// spec's recommended values; every field may be changed before [`GeneratorSettings::validate`].
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratorSettings {
    /// Record duration (s); the record has duration/dt + 1 samples from t = 0.
    pub duration: f64,
    /// Time step (s).
    pub dt: f64,
    /// Intensity envelope.
    pub envelope: Envelope,
    /// Damping ratio ζ of the target spectrum (0.05).
    pub damping: f64,
    /// Probability r that the response exceeds the target (0.15), step 2.
    pub exceedance: f64,
    /// Lowest frequency of the series (Hz), step 1 (0.2).
    pub f_lo: f64,
    /// Highest frequency of the series (Hz), step 1 (min(40, 0.4/dt)).
    pub f_hi: f64,
    /// Number of cosines N, step 1 (⌈60·f_hi⌉).
    pub n_frequencies: usize,
    /// FFT spectral-ratio iterations (each followed by the baseline correction and the peak
    /// adjustment), step 6 (20).
    pub iterations: usize,
    /// Wavelet iterations after the FFT ones ([`super::wavelet`]), each followed by the baseline
    /// correction and the peak adjustment (20).
    pub wavelet_iterations: usize,
    /// Iterations stop early once every control period ≥ 0.04 s is within this error (0.03).
    pub stop_tolerance: f64,
    /// Corner frequency of the baseline high-pass (Hz), step 8 (0.05; 0 = off).
    pub highpass_hz: f64,
    /// Longest control and check period (s), step 5 (3.0).
    pub period_max: f64,
    /// Number of control periods of the correction, step 5 (300, 1.6 % apart from 0.025 to 3 s).
    pub control_count: usize,
}

impl GeneratorSettings {
    /// Settings for a record of `duration` at `dt` under `envelope`, other values as
    /// recommended by spec seismic §2.2.
    pub fn new(duration: f64, dt: f64, envelope: Envelope) -> Self {
        let f_hi = (0.4 / dt).min(40.0);
        GeneratorSettings {
            duration,
            dt,
            envelope,
            damping: 0.05,
            exceedance: 0.15,
            f_lo: 0.2,
            f_hi,
            n_frequencies: (60.0 * f_hi).ceil().max(2.0) as usize,
            iterations: 20,
            wavelet_iterations: 20,
            stop_tolerance: 0.03,
            highpass_hz: 0.05,
            period_max: 3.0,
            control_count: 300,
        }
    }

    /// Number of samples, duration/dt + 1.
    pub fn n_samples(&self) -> usize {
        (self.duration / self.dt).round() as usize + 1
    }

    /// Control periods of the correction: `control_count` log-spaced in
    /// [max(0.025 s, 2.5·dt), period_max].
    pub fn control_periods(&self) -> Vec<f64> {
        log_spaced(
            CONTROL_MIN_PERIOD.max(2.5 * self.dt),
            self.period_max,
            self.control_count,
        )
    }

    /// Periods of the compatibility check (spec seismic §2.3): [`ACCEPTANCE_COUNT`]
    /// log-spaced in [max(0.04 s, 2.5·dt), period_max]; they differ from the control periods.
    pub fn acceptance_periods(&self) -> Vec<f64> {
        log_spaced(
            ACCEPTANCE_MIN_PERIOD.max(2.5 * self.dt),
            self.period_max,
            ACCEPTANCE_COUNT,
        )
    }

    /// Checks ranges and consistency; names the setting and the unit.
    pub fn validate(&self) -> Result<(), ParamError> {
        require_positive("dt", self.dt).map_err(with_unit("s"))?;
        require_range("duration", self.duration, 10.0 * self.dt, 600.0).map_err(with_unit("s"))?;
        let e = &self.envelope;
        require_range("envelope.t1", e.t1, self.dt, self.duration).map_err(with_unit("s"))?;
        require_range("envelope.t2", e.t2, e.t1 + self.dt, self.duration).map_err(with_unit("s"))?;
        require_positive("envelope.c", e.c).map_err(with_unit("1/s"))?;
        require_range("damping", self.damping, 0.001, 0.5)?;
        require_range("exceedance", self.exceedance, 1e-6, 0.99)?;
        require_positive("f_lo", self.f_lo).map_err(with_unit("Hz"))?;
        require_range("f_hi", self.f_hi, self.f_lo, 0.5 / self.dt)
            .map_err(with_unit("Hz (at most the Nyquist 0.5/dt)"))?;
        require_range("n_frequencies", self.n_frequencies as f64, 2.0, 100_000.0)?;
        require_range("iterations", self.iterations as f64, 0.0, 1000.0)?;
        require_range("wavelet_iterations", self.wavelet_iterations as f64, 0.0, 1000.0)?;
        require_range("stop_tolerance", self.stop_tolerance, 0.0, 1.0)?;
        require_range("highpass_hz", self.highpass_hz, 0.0, self.f_lo)
            .map_err(with_unit("Hz (below f_lo)"))?;
        require_range("period_max", self.period_max, 0.5, 0.5 * self.duration).map_err(with_unit("s"))?;
        require_range("control_count", self.control_count as f64, 10.0, 1000.0)?;
        let w_min = -PI * (1.0 - self.exceedance).ln() / e.strong_duration();
        if 2.0 * PI * self.f_lo <= w_min {
            return Err(ParamError::new(
                "f_lo",
                format!(
                    "the peak-factor relation (spec seismic §2.2 step 2) needs f_lo > {:.4} Hz for r = {} and \
                     T_d = {} s, got {} Hz",
                    w_min / (2.0 * PI),
                    self.exceedance,
                    e.strong_duration(),
                    self.f_lo
                ),
            ));
        }
        Ok(())
    }

    /// Time of sample i (s).
    fn time(&self, i: usize) -> f64 {
        i as f64 * self.dt
    }
}

/// Appends a unit to the reason of a [`ParamError`].
fn with_unit(unit: &'static str) -> impl Fn(ParamError) -> ParamError {
    move |e| ParamError::new(e.field, format!("{} {unit}", e.reason))
}

/// Two-sided target PSD S(ω) (m²/s³) by the Kaul/Vanmarcke first-passage relation (spec
/// seismic §2.2 step 2):
///
/// ```text
/// S(ω) = (ζ/(π·ω)) · Sa(ω)² / (−ln[−(π/(ω·T_d))·ln(1 − r)])
/// ```
pub fn target_psd(target: &ComponentTarget, settings: &GeneratorSettings, omega: f64) -> f64 {
    let zeta = settings.damping;
    let td = settings.envelope.strong_duration();
    let sa = target.sa(2.0 * PI / omega);
    let peak = -(-(PI / (omega * td)) * (1.0 - settings.exceedance).ln()).ln();
    zeta / (PI * omega) * sa * sa / peak
}

/// The initial non-stationary record of one component (spec seismic §2.2 steps 1–4):
/// a(t) = f(t)·Σ_k A_k·cos(ω_k·t + φ_k), A_k = √(4·S(ω_k)·Δω), ω_k uniformly spaced over
/// [f_lo, f_hi], φ_k drawn uniformly in [0, 2π) from `rng` in the order k = 1..N.
pub fn synthesize(target: &ComponentTarget, settings: &GeneratorSettings, rng: &mut ChaCha20Rng) -> Vec<f64> {
    let n = settings.n_frequencies;
    let d_omega = 2.0 * PI * (settings.f_hi - settings.f_lo) / (n - 1) as f64;
    let waves: Vec<(f64, f64, f64)> = (0..n)
        .map(|k| {
            let omega = 2.0 * PI * settings.f_lo + k as f64 * d_omega;
            let amplitude = (4.0 * target_psd(target, settings, omega) * d_omega).sqrt();
            (amplitude, omega, 2.0 * PI * rng.random::<f64>())
        })
        .collect();
    (0..settings.n_samples())
        .map(|i| {
            let t = settings.time(i);
            let sum: f64 = waves.iter().map(|(a, w, phi)| a * (w * t + phi).cos()).sum();
            settings.envelope.at(t) * sum
        })
        .collect()
}

/// What the iterations of one component produced.
#[derive(Debug, Clone, PartialEq)]
pub struct ComponentResult {
    /// The record (m/s²).
    pub accel: Vec<f64>,
    /// Iteration of the kept record (0 = before any spectral correction).
    pub iteration: usize,
    /// Its largest spectral error at the control periods ≥ 0.04 s.
    pub control_max_error: f64,
}

/// Finishes an iterate (spec seismic §2.2 steps 7–8): zero-phase high-pass, half-cosine taper
/// of [`END_TAPER`] at both ends (the acausal corrections spread into t = 0), then alternately
/// the end-condition baseline correction and the peak adjustment, ending on the latter so
/// that the PGA is exact. `weight` is the envelope times the taper.
fn finish(
    accel: &mut Vec<f64>,
    target: &ComponentTarget,
    settings: &GeneratorSettings,
    weight: &[f64],
) -> bool {
    *accel = highpass(accel, settings.dt, settings.highpass_hz);
    let taper = (END_TAPER / settings.dt).round() as usize;
    let n = accel.len();
    for (i, a) in accel.iter_mut().enumerate() {
        *a *= end_taper(i, n, taper);
    }
    let sigma = 2.0 * settings.dt;
    for _ in 0..FINISH_ROUNDS {
        zero_end_motion(accel, settings.dt, weight);
        if enforce_pga(accel, settings.dt, target.pga, sigma).is_none() {
            return false;
        }
        let (v, d) = integrate(accel, settings.dt);
        if v[v.len() - 1].abs() < 1e-7 && d[d.len() - 1].abs() < 1e-6 {
            break;
        }
    }
    true
}

/// The control periods and their target Sa.
struct Control {
    periods: Vec<f64>,
    wanted: Vec<f64>,
}

impl Control {
    /// Largest |Sa/target − 1| over the control periods inside the acceptance range (≥ 0.04 s):
    /// the score by which the best iterate is kept.
    fn max_error(&self, sa: &[f64]) -> f64 {
        sa.iter()
            .zip(&self.wanted)
            .zip(&self.periods)
            .filter(|(_, &t)| t >= ACCEPTANCE_MIN_PERIOD * (1.0 - 1e-9))
            .fold(0.0, |m: f64, ((s, w), _)| m.max((s / w - 1.0).abs()))
    }

    /// One spectral correction of `accel` with spectrum `sa`: the FFT ratio correction for
    /// the first `settings.iterations` iterations (spec seismic §2.2 step 6), then wavelets at
    /// the extrema of the error ([`super::wavelet`]).
    fn correct(&self, accel: &mut Vec<f64>, sa: &[f64], iteration: usize, settings: &GeneratorSettings) {
        if iteration < settings.iterations {
            let ratio: Vec<f64> = self.wanted.iter().zip(sa).map(|(w, s)| w / s).collect();
            *accel = apply_zero_phase_gain(accel, settings.dt, |f| ratio_gain(&self.periods, &ratio, f));
        } else {
            let chosen = error_extrema(sa, &self.wanted);
            let pick = |v: &[f64]| -> Vec<f64> { chosen.iter().map(|&j| v[j]).collect() };
            let (periods, wanted, achieved) = (pick(&self.periods), pick(&self.wanted), pick(sa));
            wavelet_correction(accel, settings.dt, &periods, settings.damping, &wanted, &achieved);
        }
    }
}

/// Generates one component (spec seismic §2.2 steps 1–8) with phases from `rng`: every
/// iterate is finished (baseline, PGA) and scored, the best one is returned.
pub fn generate_component(
    target: &ComponentTarget,
    settings: &GeneratorSettings,
    rng: &mut ChaCha20Rng,
    axis: Axis,
) -> Result<ComponentResult, GeneratorError> {
    settings.validate()?;
    let periods = settings.control_periods();
    let wanted = periods.iter().map(|&t| target.sa(t)).collect();
    let control = Control { periods, wanted };
    let (n, taper) = (settings.n_samples(), (END_TAPER / settings.dt).round() as usize);
    let weight: Vec<f64> = (0..n)
        .map(|i| settings.envelope.at(settings.time(i)) * end_taper(i, n, taper))
        .collect();
    let pga_error = || GeneratorError::Pga {
        axis: axis.name(),
        pga: target.pga,
    };
    let mut accel = synthesize(target, settings, rng);
    let mut best: Option<ComponentResult> = None;
    for iteration in 0..=(settings.iterations + settings.wavelet_iterations) {
        if !finish(&mut accel, target, settings, &weight) {
            return Err(pga_error());
        }
        let sa = response_spectrum(&accel, settings.dt, &control.periods, settings.damping)?;
        let error = control.max_error(&sa);
        if best.as_ref().is_none_or(|b| error < b.control_max_error) {
            best = Some(ComponentResult {
                accel: accel.clone(),
                iteration,
                control_max_error: error,
            });
        }
        if error <= settings.stop_tolerance {
            break;
        }
        control.correct(&mut accel, &sa, iteration, settings);
    }
    best.ok_or_else(pga_error)
}

/// Indices of the local extrema of the signed spectral error Sa/target − 1 over the control
/// periods (both ends included): where the wavelets of [`wavelet_correction`] go.
fn error_extrema(sa: &[f64], wanted: &[f64]) -> Vec<usize> {
    let e: Vec<f64> = sa.iter().zip(wanted).map(|(s, w)| s / w - 1.0).collect();
    let m = e.len();
    (0..m)
        .filter(|&j| {
            let left = if j == 0 { None } else { Some(e[j - 1]) };
            let right = e.get(j + 1).copied();
            let above = left.is_none_or(|l| e[j] >= l) && right.is_none_or(|r| e[j] > r);
            let below = left.is_none_or(|l| e[j] <= l) && right.is_none_or(|r| e[j] < r);
            above || below
        })
        .collect()
}

/// The random stream of one component: ChaCha20 keyed by `seed`, stream number 0, 1, 2 for
/// x, y, z (independent, platform-independent streams of one seed, spec seismic §2.2 step 9).
pub fn component_rng(seed: u64, axis: Axis) -> ChaCha20Rng {
    let mut rng = ChaCha20Rng::seed_from_u64(seed);
    rng.set_stream(axis.index() as u64);
    rng
}

/// One generated component and how it matches its target.
#[derive(Debug, Clone, PartialEq)]
pub struct ComponentReport {
    /// The axis.
    pub axis: Axis,
    /// Its target.
    pub target: ComponentTarget,
    /// Peak and end values.
    pub measures: MotionMeasures,
    /// The 5 %-damped (settings' ζ) spectrum at the acceptance periods against the target.
    pub spectral: SpectralMatch,
    /// Iteration of the kept record.
    pub iteration: usize,
}

impl ComponentReport {
    /// Whether the component meets spec seismic §2.3: PGA to 0.1 %, every check period within
    /// ±10 %, mean error ≤ 5 %.
    pub fn accepted(&self) -> bool {
        (self.measures.pga / self.target.pga - 1.0).abs() <= 1e-3
            && self.spectral.max_abs_error() <= ACCEPTANCE_MAX_ERROR
            && self.spectral.mean_abs_error() <= ACCEPTANCE_MEAN_ERROR
    }
}

/// A generated three-component record with its compatibility report.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratedRecord {
    /// The record (m/s², axes x, y, z).
    pub record: Accelerogram,
    /// One report per axis, x, y, z.
    pub components: [ComponentReport; 3],
    /// Pearson correlation of the pairs (x, y), (y, z), (z, x).
    pub correlations: [f64; 3],
}

impl GeneratedRecord {
    /// Whether every component meets spec seismic §2.3.
    pub fn accepted(&self) -> bool {
        self.components.iter().all(ComponentReport::accepted)
    }
}

/// The spectrum of `accel` at the acceptance periods against `target`.
pub fn spectral_match(
    accel: &[f64],
    target: &ComponentTarget,
    settings: &GeneratorSettings,
) -> Result<SpectralMatch, ParamError> {
    let periods = settings.acceptance_periods();
    let achieved = response_spectrum(accel, settings.dt, &periods, settings.damping)?;
    let target = periods.iter().map(|&t| target.sa(t)).collect();
    Ok(SpectralMatch {
        periods,
        target,
        achieved,
    })
}

/// Generates the three components x, y, z (targets in that order) from one seed (spec seismic
/// §2.2 step 9) and checks them (§2.3).
pub fn generate_record(
    targets: &[ComponentTarget; 3],
    settings: &GeneratorSettings,
    seed: u64,
) -> Result<GeneratedRecord, GeneratorError> {
    settings.validate()?;
    let mut accels: Vec<Vec<f64>> = Vec::with_capacity(3);
    let mut reports = Vec::with_capacity(3);
    for (axis, target) in Axis::ALL.into_iter().zip(targets) {
        let result = generate_component(target, settings, &mut component_rng(seed, axis), axis)?;
        reports.push(ComponentReport {
            axis,
            target: *target,
            measures: MotionMeasures::of(&result.accel, settings.dt),
            spectral: spectral_match(&result.accel, target, settings)?,
            iteration: result.iteration,
        });
        accels.push(result.accel);
    }
    let correlations = [
        correlation(&accels[0], &accels[1]),
        correlation(&accels[1], &accels[2]),
        correlation(&accels[2], &accels[0]),
    ];
    let [x, y, z]: [Vec<f64>; 3] = accels
        .try_into()
        .map_err(|_| ParamError::new("components", "expected 3"))?;
    let record = Accelerogram::new(settings.dt, x, y, z).map_err(|m| ParamError::new("record", m))?;
    let components: [ComponentReport; 3] = reports
        .try_into()
        .map_err(|_| ParamError::new("components", "expected 3"))?;
    Ok(GeneratedRecord {
        record,
        components,
        correlations,
    })
}
