//! What a scene asks of the post-processing (`output.profiles`): the slab, interface and
//! impoundment prefixes, the central section and the probes that the figures of
//! post-processing and of the earthquake follow.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Scene settings of the profile outputs (`output.profiles`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct ProfilesSpec {
    /// Solid blocks whose names start with this are the face slab (default `slab`).
    pub slab_prefix: String,
    /// Interface blocks whose names start with this are the slab–cushion interface (default
    /// `interface`).
    pub interface_prefix: String,
    /// Stages whose names start with this belong to the impoundment (default `impound`).
    pub impoundment_prefix: String,
    /// y of the central section (m); default: the middle of the slab's y-range.
    pub section_y: Option<f64>,
    /// Named interface elements followed through the stages (seed Fig. 10, element I-A).
    pub probes: Vec<Probe>,
}

impl Default for ProfilesSpec {
    fn default() -> Self {
        ProfilesSpec {
            slab_prefix: "slab".into(),
            interface_prefix: "interface".into(),
            impoundment_prefix: "impound".into(),
            section_y: None,
            probes: Vec::new(),
        }
    }
}

/// An element followed through the stages (seed Fig. 10) and through an earthquake (seed
/// Figs. 14, 18–20): the element of kind `element` whose centre is
/// nearest to `elevation`, in the central section or at a bank ([`ProbeAt`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Probe {
    /// Name (used in file names), e.g. `I-A`.
    pub name: String,
    /// Elevation z of the element (m, mesh coordinates).
    pub elevation: f64,
    /// Where along the dam axis (default: the central section).
    #[serde(default)]
    pub at: ProbeAt,
    /// Interface element (default) or face-slab element (the seed's F-A).
    #[serde(default)]
    pub element: ProbeElement,
}

/// Where along the dam axis a probe lies (spec seismic §3.6: F-A, I-A…I-D).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ProbeAt {
    /// The central section ([`ProfilesSpec::section_y`]).
    #[default]
    Centre,
    /// The element nearest the left abutment (smallest y, the generated dam's left bank,
    /// [`crate::mesh::dam_generator`]) in the row of elements nearest to the elevation.
    LeftBank,
    /// The element nearest the right abutment (largest y) in that row.
    RightBank,
}

/// The kind of element a probe follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ProbeElement {
    /// A slab–cushion interface element ([`ProfilesSpec::interface_prefix`]).
    #[default]
    Interface,
    /// A face-slab element ([`ProfilesSpec::slab_prefix`]).
    Slab,
}
