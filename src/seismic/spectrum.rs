//! The standard design response spectrum β(T) of the Chinese hydraulic seismic codes
//! DL 5073-2000 and NB 35047-2015 (spec seismic §1.1).
//!
//! ```text
//! β(T) = 1 + (βmax − 1)·T / 0.1       0   ≤ T ≤ 0.1 s   (rising branch, β(0) = 1)
//! β(T) = βmax                          0.1 < T ≤ Tg      (plateau)
//! β(T) = βmax·(Tg / T)^γ               Tg  < T ≤ 3.0 s   (decay)
//! β(T) ≥ 0.2·βmax                      (floor, all T)
//! ```
//!
//! The target pseudo-acceleration spectrum is Sa(T) = a·β(T) with a the design peak ground
//! acceleration of the component (spec seismic §1.1; the vertical uses the same normalized
//! shape with a_v = 2/3·a_h).

use crate::error::{require_positive, require_range, ParamError};
use serde::{Deserialize, Serialize};

/// End of the rising branch (s): β rises linearly from 1 at T = 0 to βmax at T = 0.1 s.
pub const RISE_END: f64 = 0.1;
/// End of the decay branch of the codes (s). The codes stop at 3 s; [`DesignSpectrum::beta`]
/// continues the decay law (bounded by the floor) beyond it, which only the generator's
/// frequencies below 1/3 Hz use.
pub const DECAY_END: f64 = 3.0;
/// The floor β ≥ FLOOR_RATIO·βmax (spec seismic §1.1).
pub const FLOOR_RATIO: f64 = 0.2;

/// The code edition, which fixes the default decay exponent γ (spec seismic §1.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum CodeEdition {
    /// DL 5073-2000 (水工建筑物抗震设计规范), γ = 0.9: the seed paper's code.
    #[serde(rename = "DL5073-2000")]
    Dl5073_2000,
    /// NB 35047-2015 (水电工程水工建筑物抗震设计规范, §5.3.2), γ = 0.6: the current code.
    #[serde(rename = "NB35047-2015")]
    Nb35047_2015,
}

impl CodeEdition {
    /// The decay exponent γ of the edition: 0.9 (DL 5073-2000) or 0.6 (NB 35047-2015).
    pub fn default_gamma(self) -> f64 {
        match self {
            CodeEdition::Dl5073_2000 => 0.9,
            CodeEdition::Nb35047_2015 => 0.6,
        }
    }

    /// The name as written in the codes and in YAML, e.g. `DL5073-2000`.
    pub fn name(self) -> &'static str {
        match self {
            CodeEdition::Dl5073_2000 => "DL5073-2000",
            CodeEdition::Nb35047_2015 => "NB35047-2015",
        }
    }
}

/// A normalized design spectrum β(T) (spec seismic §1.1–§1.3). Build it with
/// [`DesignSpectrum::new`], which checks the parameters; γ defaults to the edition's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignSpectrum {
    /// The code edition (sets the default γ).
    pub edition: CodeEdition,
    /// Plateau value βmax (1.60 for earth-rock dams, spec seismic §1.2).
    pub beta_max: f64,
    /// Characteristic period Tg (s), spec seismic §1.3.
    pub tg: f64,
    /// Decay exponent γ.
    pub gamma: f64,
}

impl DesignSpectrum {
    /// A spectrum of `edition` with γ = `gamma` or, when `None`, the edition's default.
    /// Rejects βmax ∉ [1, 10], Tg ∉ [0.1, 3] s and γ ∉ (0, 3].
    pub fn new(edition: CodeEdition, beta_max: f64, tg: f64, gamma: Option<f64>) -> Result<Self, ParamError> {
        let gamma = gamma.unwrap_or(edition.default_gamma());
        require_range("beta_max", beta_max, 1.0, 10.0)?;
        require_range("tg", tg, RISE_END, DECAY_END).map_err(|e| ParamError::new("tg", e.reason + " s"))?;
        require_positive("gamma", gamma)?;
        require_range("gamma", gamma, 0.0, 3.0)?;
        Ok(DesignSpectrum {
            edition,
            beta_max,
            tg,
            gamma,
        })
    }

    /// The floor 0.2·βmax.
    pub fn beta_min(&self) -> f64 {
        FLOOR_RATIO * self.beta_max
    }

    /// β(T) for a period T ≥ 0 (s); see the module docs. Negative or non-finite periods give
    /// NaN.
    pub fn beta(&self, period: f64) -> f64 {
        if !(period.is_finite() && period >= 0.0) {
            return f64::NAN;
        }
        let shape = if period <= RISE_END {
            1.0 + (self.beta_max - 1.0) * period / RISE_END
        } else if period <= self.tg {
            self.beta_max
        } else {
            self.beta_max * (self.tg / period).powf(self.gamma)
        };
        shape.max(self.beta_min())
    }

    /// Target pseudo-acceleration Sa(T) = pga·β(T) (same unit as `pga`).
    pub fn sa(&self, period: f64, pga: f64) -> f64 {
        pga * self.beta(period)
    }

    /// The period at which the decay branch reaches the floor, Tg·5^(1/γ) (spec seismic §1.4).
    pub fn floor_period(&self) -> f64 {
        self.tg * (1.0 / FLOOR_RATIO).powf(1.0 / self.gamma)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PERIODS: [f64; 12] = [0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.8, 1.0, 1.5, 2.0, 3.0];

    /// The table of spec seismic §1.4 (βmax = 1.6): (Tg, γ, β at PERIODS).
    const TABLE: [(f64, f64, [f64; 12]); 6] = [
        (
            0.20,
            0.9,
            [
                1.000, 1.300, 1.600, 1.600, 1.111, 0.857, 0.701, 0.459, 0.376, 0.320, 0.320, 0.320,
            ],
        ),
        (
            0.30,
            0.9,
            [
                1.000, 1.300, 1.600, 1.600, 1.600, 1.235, 1.010, 0.662, 0.541, 0.376, 0.320, 0.320,
            ],
        ),
        (
            0.40,
            0.9,
            [
                1.000, 1.300, 1.600, 1.600, 1.600, 1.600, 1.309, 0.857, 0.701, 0.487, 0.376, 0.320,
            ],
        ),
        (
            0.20,
            0.6,
            [
                1.000, 1.300, 1.600, 1.600, 1.254, 1.056, 0.923, 0.696, 0.609, 0.478, 0.402, 0.320,
            ],
        ),
        (
            0.30,
            0.6,
            [
                1.000, 1.300, 1.600, 1.600, 1.600, 1.346, 1.178, 0.888, 0.777, 0.609, 0.513, 0.402,
            ],
        ),
        (
            0.40,
            0.6,
            [
                1.000, 1.300, 1.600, 1.600, 1.600, 1.600, 1.400, 1.056, 0.923, 0.724, 0.609, 0.478,
            ],
        ),
    ];

    fn edition_of(gamma: f64) -> CodeEdition {
        if gamma == 0.9 {
            CodeEdition::Dl5073_2000
        } else {
            CodeEdition::Nb35047_2015
        }
    }

    /// Every entry of the table of spec seismic §1.4 to 1e-3, with γ from the edition.
    #[test]
    fn reproduces_the_reference_table() {
        for (tg, gamma, row) in TABLE {
            let s = DesignSpectrum::new(edition_of(gamma), 1.6, tg, None).unwrap();
            assert_eq!(s.gamma, gamma);
            for (t, expected) in PERIODS.iter().zip(row) {
                let b = s.beta(*t);
                assert!(
                    (b - expected).abs() <= 1e-3,
                    "Tg {tg} γ {gamma} T {t}: {b} vs {expected}"
                );
            }
        }
    }

    /// The two worked exam problems of spec seismic §1.1 / §1.4.
    #[test]
    fn reproduces_the_exam_checks() {
        let nb = DesignSpectrum::new(CodeEdition::Nb35047_2015, 1.6, 0.30, None).unwrap();
        assert!((nb.beta(1.8) - 0.546).abs() < 1e-3, "{}", nb.beta(1.8));
        let dl = DesignSpectrum::new(CodeEdition::Dl5073_2000, 2.5, 0.35, None).unwrap();
        assert!((dl.beta(1.5) - 0.675).abs() < 1e-3, "{}", dl.beta(1.5));
    }

    /// The floor periods of spec seismic §1.4 and an explicit γ overriding the edition's.
    #[test]
    fn floor_period_and_gamma_override() {
        let s = DesignSpectrum::new(CodeEdition::Dl5073_2000, 1.6, 0.2, None).unwrap();
        assert!((s.floor_period() - 1.20).abs() < 5e-3, "{}", s.floor_period());
        assert!((s.beta(2.9) - 0.32).abs() < 1e-15);
        let o = DesignSpectrum::new(CodeEdition::Dl5073_2000, 1.6, 0.4, Some(0.6)).unwrap();
        assert!((o.beta(1.0) - 0.923).abs() < 1e-3);
        assert!(o.beta(-1.0).is_nan());
    }

    #[test]
    fn rejects_out_of_range_parameters() {
        let e = DesignSpectrum::new(CodeEdition::Dl5073_2000, 0.5, 0.2, None).unwrap_err();
        assert_eq!(e.field, "beta_max");
        let e = DesignSpectrum::new(CodeEdition::Dl5073_2000, 1.6, 5.0, None).unwrap_err();
        assert!(e.field == "tg" && e.reason.ends_with(" s"), "{e}");
        let e = DesignSpectrum::new(CodeEdition::Dl5073_2000, 1.6, 0.2, Some(f64::NAN)).unwrap_err();
        assert_eq!(e.field, "gamma");
    }
}
