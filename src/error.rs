//! Error types of each layer. Every error names its place: a YAML path, an element id, a field.

use thiserror::Error;

/// A material update that could not be completed. Recoverable: the solver cuts the step.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{reason}")]
pub struct MaterialError {
    /// What went wrong, in words (e.g. "substep size fell below DT_MIN at p = 3.2 kPa").
    pub reason: String,
}

impl MaterialError {
    /// Convenience constructor.
    pub fn new(reason: impl Into<String>) -> Self {
        MaterialError {
            reason: reason.into(),
        }
    }
}

/// An invalid material parameter (checked when a scene or test file is loaded).
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{field}: {reason}")]
pub struct ParamError {
    /// Parameter name as written in the input (e.g. `G0`, `poisson`).
    pub field: String,
    /// Why the value is rejected.
    pub reason: String,
}

impl ParamError {
    /// Convenience constructor.
    pub fn new(field: impl Into<String>, reason: impl Into<String>) -> Self {
        ParamError {
            field: field.into(),
            reason: reason.into(),
        }
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn require_positive(field: &str, value: f64) -> Result<(), ParamError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(ParamError::new(
            field,
            format!("must be a positive number, got {value}"),
        ))
    }
}

/// Checks that `value` is finite and not negative.
pub fn require_non_negative(field: &str, value: f64) -> Result<(), ParamError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(ParamError::new(
            field,
            format!("must be a non-negative number, got {value}"),
        ))
    }
}

/// Checks that `value` lies in the closed range `[lo, hi]`.
pub fn require_range(field: &str, value: f64, lo: f64, hi: f64) -> Result<(), ParamError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(ParamError::new(
            field,
            format!("must lie in [{lo}, {hi}], got {value}"),
        ))
    }
}
