//! Modal analysis of a stage's start state (spec seismic §4 items 4 and 9): the lowest
//! natural frequencies and mode shapes of K₀·φ = ω²·M·φ on the placed, unconstrained DOFs,
//! with K₀ the small-strain (elastic) stiffness of that state (the solver's modal analysis).
//!
//! ```yaml
//! stages:
//!   - name: modes            # after impoundment: a stage with nothing else to do
//!     modal: { modes: 6 }    # mass: consistent (default) or lumped
//! ```
//!
//! The analysis runs when the stage starts, after its blocks are placed and before its first
//! step. A dynamic stage whose Rayleigh damping names modes (`damping: { ratio: 0.05,
//! modes: [1, 3] }`) runs one there too, with at least as many modes as the higher anchor. At
//! most one stage of a scene runs a modal analysis: its frequencies go to `summary.json`
//! (`"modal": {"stage", "frequencies_hz", "periods_s"}`) and its mode shapes to `modes.h5` /
//! `modes.xdmf` (one step per mode, the node field `mode_shape` scaled to a largest component
//! of 1).

use super::dynamic::{Anchors, DynamicStage, MassKind};
use super::error::SceneError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Largest number of modes a scene may ask for.
pub const MAX_MODES: u32 = 1000;

/// A modal analysis at the start of a stage (scene key `stages[k].modal`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ModalSpec {
    /// Number of modes, the lowest frequencies first (1 to 1000).
    pub modes: u32,
    /// Mass matrix: `consistent` (default) or `lumped` (row sums).
    #[serde(default)]
    pub mass: MassKind,
}

/// A validated modal analysis: how many modes, with which mass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModalRequest {
    /// Number of modes computed.
    pub modes: u32,
    /// Lumped mass instead of consistent.
    pub lumped: bool,
}

/// The modal analysis of stage `k`: its own `modal` key and the modes its Rayleigh damping
/// names, merged (the larger count; a dynamic stage's mass kind wins over the default).
/// `path` is the stage's YAML path for errors.
pub fn resolve(
    spec: Option<&ModalSpec>,
    dynamic: Option<&DynamicStage>,
    path: &str,
    invalid: &dyn Fn(&str, String) -> SceneError,
) -> Result<Option<ModalRequest>, SceneError> {
    let own = match spec {
        Some(m) if !(1..=MAX_MODES).contains(&m.modes) => {
            return Err(invalid(
                &format!("{path}.modal.modes"),
                format!("{} must be from 1 to {MAX_MODES}", m.modes),
            ))
        }
        Some(m) => Some(ModalRequest {
            modes: m.modes,
            lumped: m.mass == MassKind::Lumped,
        }),
        None => None,
    };
    let anchor = dynamic.and_then(|d| match d.damping.map(|r| r.anchors) {
        Some(Anchors::Modes([_, j])) => Some(ModalRequest {
            modes: j,
            lumped: d.lumped,
        }),
        _ => None,
    });
    Ok(match (own, anchor) {
        (Some(a), Some(b)) => Some(ModalRequest {
            modes: a.modes.max(b.modes),
            lumped: a.lumped,
        }),
        (a, b) => a.or(b),
    })
}
