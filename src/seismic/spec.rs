//! The YAML format of `cfrd accel SPEC.yaml` (artificial accelerograms, spec seismic §2.2).
//!
//! SI units: s, Hz, m/s². Unknown keys are rejected; validation errors name the YAML path and
//! the unit.
//!
//! ```yaml
//! records:                       # one or more records, each one CSV/PNG set
//!   - { name: seed_quake, seed: 20150416 }
//! spectrum:
//!   edition: DL5073-2000         # or NB35047-2015 (sets the default gamma 0.9 / 0.6)
//!   beta_max: 1.6
//!   tg: 0.20                     # s
//!   gamma: 0.9                   # optional
//!   damping: 0.05                # optional, default 0.05
//! pga: { x: 3.0, y: 3.0, z: 2.0 }  # m/s²; or pga_h: 3.0 with vertical_ratio (default 2/3)
//! duration: 20.0                 # s
//! dt: 0.01                       # s
//! envelope: { t1: 2.0, t2: 12.0, c: 0.35 }   # s, s, 1/s
//! exceedance: 0.15               # optional, r of spec seismic §2.2 step 2
//! band: { f_lo: 0.2, f_hi: 40.0, count: 2400 }   # optional, Hz
//! iterations: 20                 # optional, FFT spectral-ratio iterations
//! wavelet_iterations: 20         # optional, wavelet iterations after them
//! highpass_hz: 0.05              # optional, baseline high-pass corner (0 = off)
//! ```

use super::generator::{ComponentTarget, Envelope, GeneratorSettings};
use super::spectrum::{CodeEdition, DesignSpectrum};
use crate::error::ParamError;
use serde::{Deserialize, Serialize};

/// Default vertical/horizontal PGA ratio (spec seismic §1.1).
pub const DEFAULT_VERTICAL_RATIO: f64 = 2.0 / 3.0;

/// A `cfrd accel` specification file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AccelSpecFile {
    /// Title of the figures (default: the record name).
    #[serde(default)]
    pub title: Option<String>,
    /// The records to generate (name and seed each).
    pub records: Vec<RecordSpec>,
    /// The design spectrum.
    pub spectrum: SpectrumSpec,
    /// Horizontal design PGA a_h (m/s²) of x and y; z gets `vertical_ratio`·a_h. Exclusive with
    /// `pga`.
    #[serde(default)]
    pub pga_h: Option<f64>,
    /// Vertical/horizontal PGA ratio with `pga_h` (default 2/3).
    #[serde(default)]
    pub vertical_ratio: Option<f64>,
    /// Explicit PGA per component (m/s²). Exclusive with `pga_h`.
    #[serde(default)]
    pub pga: Option<PgaSpec>,
    /// Record duration (s).
    pub duration: f64,
    /// Time step (s).
    pub dt: f64,
    /// Jennings–Housner–Tsai envelope.
    pub envelope: EnvelopeSpec,
    /// Probability r that the response exceeds the target (default 0.15).
    #[serde(default)]
    pub exceedance: Option<f64>,
    /// Frequency band of the trigonometric series (default 0.2 Hz to min(40 Hz, 0.4/dt)).
    #[serde(default)]
    pub band: Option<BandSpec>,
    /// FFT spectral-ratio iterations (default 20).
    #[serde(default)]
    pub iterations: Option<usize>,
    /// Wavelet iterations after the FFT ones (default 20).
    #[serde(default)]
    pub wavelet_iterations: Option<usize>,
    /// Corner of the baseline high-pass (Hz, default 0.05; 0 = off).
    #[serde(default)]
    pub highpass_hz: Option<f64>,
}

/// One record to generate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordSpec {
    /// File stem of the outputs: letters, digits, `_` and `-`.
    pub name: String,
    /// Seed of the random phases (the three components use streams 0, 1, 2 of it).
    pub seed: u64,
}

/// The design spectrum (spec seismic §1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpectrumSpec {
    /// `DL5073-2000` or `NB35047-2015`.
    pub edition: CodeEdition,
    /// Plateau βmax.
    pub beta_max: f64,
    /// Characteristic period Tg (s).
    pub tg: f64,
    /// Decay exponent γ (default: the edition's).
    #[serde(default)]
    pub gamma: Option<f64>,
    /// Damping ratio of the target spectrum (default 0.05).
    #[serde(default)]
    pub damping: Option<f64>,
}

/// PGA per component (m/s²).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PgaSpec {
    /// Stream direction.
    pub x: f64,
    /// Dam axis.
    pub y: f64,
    /// Vertical.
    pub z: f64,
}

/// Envelope times (s) and decay rate (1/s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvelopeSpec {
    /// End of the rise (s).
    pub t1: f64,
    /// End of the stationary part (s).
    pub t2: f64,
    /// Decay rate (1/s).
    pub c: f64,
}

/// Frequency band of the series.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BandSpec {
    /// Lowest frequency (Hz).
    pub f_lo: f64,
    /// Highest frequency (Hz), at most 0.5/dt.
    pub f_hi: f64,
    /// Number of cosines (default ⌈60·f_hi⌉).
    #[serde(default)]
    pub count: Option<usize>,
}

/// A validated specification: what the generator needs.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedSpec {
    /// Targets of x, y, z.
    pub targets: [ComponentTarget; 3],
    /// Generator settings.
    pub settings: GeneratorSettings,
    /// Records (name, seed).
    pub records: Vec<RecordSpec>,
}

/// The most samples (duration/dt + 1) of one record component `cfrd accel` makes: 600 s at
/// 0.01 s, or 60 s at 0.001 s. The work grows with the samples (measured on this project's
/// machine: 4.3 s for the seed's 2,001, 18 s for 10,001).
pub const MAX_RECORD_SAMPLES: usize = 60_001;

/// A [`ParamError`] whose reason ends with a unit.
fn unit_error(field: &str, value: f64, rule: &str, unit: &str) -> ParamError {
    ParamError::new(field, format!("{rule}, got {value} {unit}"))
}

/// Checks a finite value in [lo, hi] with its unit.
fn in_range(field: &str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<f64, ParamError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(unit_error(
            field,
            value,
            &format!("must lie in [{lo}, {hi}] {unit}"),
            unit,
        ))
    }
}

impl AccelSpecFile {
    /// Parses YAML text; the error gives the YAML path, line and column.
    pub fn parse(text: &str) -> Result<Self, String> {
        let de = serde_yaml::Deserializer::from_str(text);
        serde_path_to_error::deserialize(de).map_err(|e| {
            let path = e.path().to_string();
            let inner = e.into_inner();
            if path == "." {
                inner.to_string()
            } else {
                format!("{path}: {inner}")
            }
        })
    }

    /// Validates and resolves the file; errors name the YAML path and the unit.
    pub fn resolve(&self) -> Result<ResolvedSpec, ParamError> {
        self.check_records()?;
        let s = &self.spectrum;
        let spectrum = DesignSpectrum::new(s.edition, s.beta_max, s.tg, s.gamma)
            .map_err(|e| ParamError::new(format!("spectrum.{}", e.field), e.reason))?;
        let pga = self.component_pga()?;
        let dt = in_range("dt", self.dt, 1e-4, 0.1, "s")?;
        let duration = in_range("duration", self.duration, 1.0, 600.0, "s")?;
        let samples = (duration / dt).round() + 1.0;
        if samples > MAX_RECORD_SAMPLES as f64 {
            return Err(ParamError::new(
                "dt",
                format!(
                    "{duration} s at dt = {dt} s is {samples} samples per component; at most \
                     {MAX_RECORD_SAMPLES} (the generator's work grows with the samples): a \
                     larger dt or a shorter duration"
                ),
            ));
        }
        let e = self.envelope;
        let envelope = Envelope {
            t1: in_range("envelope.t1", e.t1, dt, duration, "s")?,
            t2: in_range("envelope.t2", e.t2, e.t1 + dt, duration, "s")?,
            c: in_range("envelope.c", e.c, 1e-3, 100.0, "1/s")?,
        };
        let mut settings = GeneratorSettings::new(duration, dt, envelope);
        settings.damping = in_range(
            "spectrum.damping",
            s.damping.unwrap_or(0.05),
            0.001,
            0.5,
            "(ratio)",
        )?;
        if let Some(r) = self.exceedance {
            settings.exceedance = in_range("exceedance", r, 1e-6, 0.99, "(probability)")?;
        }
        if let Some(b) = self.band {
            settings.f_lo = in_range("band.f_lo", b.f_lo, 0.01, 10.0, "Hz")?;
            settings.f_hi = in_range("band.f_hi", b.f_hi, b.f_lo, 0.5 / dt, "Hz")?;
            settings.n_frequencies = (60.0 * settings.f_hi).ceil() as usize;
            if let Some(n) = b.count {
                settings.n_frequencies =
                    in_range("band.count", n as f64, 2.0, 100_000.0, "cosines")? as usize;
            }
        }
        if let Some(n) = self.iterations {
            settings.iterations = in_range("iterations", n as f64, 0.0, 1000.0, "iterations")? as usize;
        }
        if let Some(n) = self.wavelet_iterations {
            settings.wavelet_iterations =
                in_range("wavelet_iterations", n as f64, 0.0, 1000.0, "iterations")? as usize;
        }
        if let Some(fc) = self.highpass_hz {
            settings.highpass_hz = in_range("highpass_hz", fc, 0.0, settings.f_lo, "Hz (below band.f_lo)")?;
        }
        settings.validate()?;
        Ok(ResolvedSpec {
            targets: pga.map(|pga| ComponentTarget { spectrum, pga }),
            settings,
            records: self.records.clone(),
        })
    }

    /// Names are non-empty, safe as file stems and unique.
    fn check_records(&self) -> Result<(), ParamError> {
        if self.records.is_empty() {
            return Err(ParamError::new("records", "at least one record is needed"));
        }
        for (i, r) in self.records.iter().enumerate() {
            let safe = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
            if r.name.is_empty() || !r.name.chars().all(safe) {
                return Err(ParamError::new(
                    format!("records[{i}].name"),
                    format!("'{}' must be letters, digits, '_' or '-'", r.name),
                ));
            }
            if self.records[..i].iter().any(|o| o.name == r.name) {
                return Err(ParamError::new(
                    format!("records[{i}].name"),
                    format!("'{}' is used twice", r.name),
                ));
            }
        }
        Ok(())
    }

    /// PGA of x, y, z (m/s²) from `pga` or `pga_h` and `vertical_ratio`.
    fn component_pga(&self) -> Result<[f64; 3], ParamError> {
        let check = |field: &str, v: f64| in_range(field, v, 1e-3, 100.0, "m/s²");
        match (self.pga, self.pga_h) {
            (Some(p), None) => {
                if self.vertical_ratio.is_some() {
                    return Err(ParamError::new("vertical_ratio", "only with pga_h, not with pga"));
                }
                Ok([check("pga.x", p.x)?, check("pga.y", p.y)?, check("pga.z", p.z)?])
            }
            (None, Some(h)) => {
                let h = check("pga_h", h)?;
                let ratio = self.vertical_ratio.unwrap_or(DEFAULT_VERTICAL_RATIO);
                let ratio = in_range("vertical_ratio", ratio, 0.01, 2.0, "(ratio)")?;
                Ok([h, h, h * ratio])
            }
            (Some(_), Some(_)) => Err(ParamError::new("pga", "give either pga or pga_h, not both")),
            (None, None) => Err(ParamError::new(
                "pga_h",
                "missing: give pga_h (m/s²) or pga: {x, y, z}",
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SEED: &str = include_str!("../../inputs/accel/seed_quake.yaml");

    #[test]
    fn the_seed_spec_resolves() {
        let r = AccelSpecFile::parse(SEED).unwrap().resolve().unwrap();
        assert_eq!(r.targets.map(|t| t.pga), [3.0, 3.0, 2.0]);
        assert_eq!(r.targets[0].spectrum.gamma, 0.9);
        assert_eq!(r.targets[0].spectrum.tg, 0.2);
        assert_eq!((r.settings.duration, r.settings.dt), (20.0, 0.01));
        assert_eq!((r.settings.envelope.t1, r.settings.envelope.t2), (2.0, 12.0));
        assert_eq!(r.records.len(), 1);
    }

    fn error_of(yaml: &str) -> String {
        match AccelSpecFile::parse(yaml) {
            Err(e) => e,
            Ok(f) => f.resolve().unwrap_err().to_string(),
        }
    }

    /// Each invalid input names the YAML path (and the unit where there is one).
    #[test]
    fn invalid_specs_name_the_path_and_unit() {
        let cases = [
            ("dt: 0.01", "dt: -0.01", "dt: must lie in"),
            ("dt: 0.01", "dt: .nan", "s"),
            ("tg: 0.20", "tg: 7.0", "spectrum.tg"),
            ("t2: 12.0", "t2: 1.0", "envelope.t2"),
            (
                "{ x: 3.0, y: 3.0, z: 2.0 }",
                "{ x: 3.0, y: -3.0, z: 2.0 }",
                "pga.y: must lie in [0.001, 100] m/s²",
            ),
            ("name: seed_quake", "name: ../evil", "records[0].name"),
            (
                "dt: 0.01",
                "dt: 0.01\nunknown_key: 1",
                "unknown field `unknown_key`",
            ),
            ("beta_max: 1.6", "beta_max: big", "spectrum.beta_max"),
            ("edition: DL5073-2000", "edition: GB2018", "spectrum.edition"),
            ("dt: 0.01", "dt: 0.01\npga_h: 3.0", "either pga or pga_h"),
            (
                "dt: 0.01",
                "dt: 0.0001",
                "dt: 20 s at dt = 0.0001 s is 200001 samples per component; at most 60001",
            ),
        ];
        for (from, to, expected) in cases {
            let yaml = SEED.replace(from, to);
            assert_ne!(yaml, SEED, "{from}");
            let e = error_of(&yaml);
            assert!(e.contains(expected), "{to}: {e}");
        }
        // the longest record at the usual step is within the bound
        let longest = AccelSpecFile::parse(&SEED.replace("duration: 20.0", "duration: 600.0")).unwrap();
        assert_eq!(
            longest.resolve().unwrap().settings.n_samples(),
            MAX_RECORD_SAMPLES
        );
    }
}
