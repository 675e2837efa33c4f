//! The YAML format of a material-point test file (`cfrd point TEST.yaml`).
//!
//! SI units (Pa, m). Geotechnical quantities are compression positive and say so in their
//! names: `normal_stresses` (σ_n), `confining_pressures`, `initial_pressure`, and the axial
//! *compression* strain of the solid paths. Unknown keys are rejected.
//!
//! ```yaml
//! title: Hyperbolic interface, CNL monotonic    # optional
//! interface:                                    # or `solid:`; omitted keys = seed tables
//!   model: hyperbolic
//! test:
//!   kind: direct_shear
//!   control: cnl                                # or cns (with normal_stiffness, Pa/m)
//!   normal_stresses: [100.0e3, 200.0e3, 400.0e3]
//!   path: { kind: monotonic, target: 0.06, steps: 300 }   # shear displacement, m
//! ```
//!
//! **Comparison mode**: `interfaces:` (a list of interface laws) instead of `interface:` runs the
//! same `direct_shear` test with every law, plots one panel per normal stress with one curve per
//! law, and writes a table of the peak shear stress and of the shear displacements at 50 % and
//! 95 % of the peak (see [`crate::point::runner::CrossCheckRow`]).
//!
//! **Initial state of the solid tests** (spec G7: the densification factor of the rockfill GP
//! model remembers isotropic consolidation). Every solid test starts from the *virgin* isotropic
//! state at `initial_pressure` p0 (`init_state(−p0·I)`: no plastic strain, loading surface
//! through the stress point). The triaxial tests default to p0 = σ3 (virgin isotropic state at
//! the confining pressure); a p0 different from σ3 is first brought to σ3 by
//! `consolidation_steps` stress-controlled isotropic steps, which are not part of the output.

use crate::material::{InterfaceParams, SolidParams};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A material-point test file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointTestFile {
    /// Title of the plots and the summary (default: the file name).
    #[serde(default)]
    pub title: Option<String>,
    /// Interface or joint law (exactly one of `interface`, `interfaces` and `solid`).
    #[serde(default)]
    pub interface: Option<InterfaceParams>,
    /// Comparison mode: several interface laws run through the same `direct_shear` test.
    #[serde(default)]
    pub interfaces: Option<Vec<InterfaceParams>>,
    /// Solid model (exactly one of `interface`, `interfaces` and `solid`).
    #[serde(default)]
    pub solid: Option<SolidParams>,
    /// The test to run.
    pub test: TestSpec,
}

/// The test kinds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum TestSpec {
    /// Interface direct shear (CNL or CNS) at one or more normal stresses.
    DirectShear(DirectShearTest),
    /// Interface under a prescribed 3D jump path.
    JumpPath(JumpPathTest),
    /// Solid drained triaxial compression (constant lateral stress) at several confining pressures.
    Triaxial(TriaxialTest),
    /// Solid drained cyclic triaxial test (q cycled between two limits at constant σ3).
    CyclicTriaxial(CyclicTriaxialTest),
    /// Solid oedometric compression (no lateral strain).
    Oedometer(OedometerTest),
    /// Solid isotropic compression / unloading through a list of pressures.
    IsotropicCompression(IsotropicTest),
}

impl TestSpec {
    /// The `kind:` tag.
    pub fn name(&self) -> &'static str {
        match self {
            TestSpec::DirectShear(_) => "direct_shear",
            TestSpec::JumpPath(_) => "jump_path",
            TestSpec::Triaxial(_) => "triaxial",
            TestSpec::CyclicTriaxial(_) => "cyclic_triaxial",
            TestSpec::Oedometer(_) => "oedometer",
            TestSpec::IsotropicCompression(_) => "isotropic_compression",
        }
    }

    /// Whether the test needs an interface law (else a solid model).
    pub fn is_interface(&self) -> bool {
        matches!(self, TestSpec::DirectShear(_) | TestSpec::JumpPath(_))
    }
}

/// Normal control of a direct-shear test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum NormalControlKind {
    /// Constant normal load.
    #[default]
    Cnl,
    /// Constant normal stiffness (needs `normal_stiffness`).
    Cns,
}

/// Interface direct shear.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DirectShearTest {
    /// Normal stresses σ_n of the runs (Pa, compression positive), one run each.
    pub normal_stresses: Vec<f64>,
    /// `cnl` (default) or `cns`.
    #[serde(default)]
    pub control: NormalControlKind,
    /// Stiffness K of the normal restraint for `cns` (Pa/m): dσ_n = K·d(dilation).
    #[serde(default)]
    pub normal_stiffness: Option<f64>,
    /// Shear displacement path (m) along `direction_deg`.
    pub path: ScalarPath,
    /// Shear direction in the (s, a) plane, degrees from s (default 0).
    #[serde(default)]
    pub direction_deg: f64,
}

/// Interface under a prescribed jump path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JumpPathTest {
    /// Normal stress at the start (Pa, compression positive).
    pub sigma_n0: f64,
    /// Waypoints (δ_s, δ_a, δ_n) of the total jump (m), from the origin; δ_n > 0 opens.
    pub waypoints: Vec<[f64; 3]>,
    /// Equal steps per segment.
    pub steps_per_segment: usize,
}

/// Default number of isotropic steps from p0 to σ3 when p0 ≠ σ3.
pub const DEFAULT_CONSOLIDATION_STEPS: usize = 20;

/// Solid drained triaxial test: lateral stresses held at σ3, axial strain prescribed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TriaxialTest {
    /// Confining pressures σ_3 (Pa, compression positive), one run each.
    pub confining_pressures: Vec<f64>,
    /// Pressure p0 of the virgin isotropic start (Pa, compression positive); default σ3 of
    /// each run. When p0 ≠ σ3 the point is first consolidated isotropically to σ3.
    #[serde(default)]
    pub initial_pressure: Option<f64>,
    /// Isotropic steps from p0 to σ3 (default 20; only used when p0 ≠ σ3).
    #[serde(default)]
    pub consolidation_steps: Option<usize>,
    /// Axial compression strain path ε_a (−, compression positive), from the start of shearing.
    pub path: ScalarPath,
}

/// Solid drained cyclic triaxial test: σ3 constant, q = σ_a − σ_r stress controlled from 0 to
/// `q_min`, then `cycles` times `q_min` → `q_max` → `q_min`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CyclicTriaxialTest {
    /// Confining pressures σ_3 (Pa, compression positive), one run each.
    pub confining_pressures: Vec<f64>,
    /// Pressure p0 of the virgin isotropic start (Pa, compression positive); default σ3.
    #[serde(default)]
    pub initial_pressure: Option<f64>,
    /// Isotropic steps from p0 to σ3 (default 20; only used when p0 ≠ σ3).
    #[serde(default)]
    pub consolidation_steps: Option<usize>,
    /// Lower deviator q_min (Pa, default 0).
    #[serde(default)]
    pub q_min: f64,
    /// Upper deviator q_max (Pa), > q_min.
    pub q_max: f64,
    /// Number of load cycles.
    pub cycles: usize,
    /// Stress-controlled steps per half cycle (also used for the first ramp 0 → q_min).
    pub steps_per_half: usize,
}

/// Solid oedometer test.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OedometerTest {
    /// Pressure p0 of the virgin isotropic start (Pa, compression positive).
    pub initial_pressure: f64,
    /// Axial compression strain path ε_a (−, compression positive).
    pub path: ScalarPath,
}

/// Solid isotropic compression: the pressure goes from p0 through `pressures`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct IsotropicTest {
    /// Pressure p0 of the virgin isotropic start (Pa, compression positive).
    pub initial_pressure: f64,
    /// Pressures to go through (Pa, compression positive), e.g. loading then unloading.
    pub pressures: Vec<f64>,
    /// Stress-controlled steps per segment.
    pub steps_per_segment: usize,
}

/// A path of one scalar (a shear displacement or an axial strain), from 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ScalarPath {
    /// 0 → `target` in `steps` equal steps.
    Monotonic(MonotonicPath),
    /// 0 → mean + A → mean − A → … (`cycles` times) → mean.
    Cyclic(CyclicPath),
    /// Through the listed points.
    Waypoints(WaypointPath),
}

/// Monotonic path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MonotonicPath {
    /// End value.
    pub target: f64,
    /// Number of equal steps.
    pub steps: usize,
}

/// Cyclic path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CyclicPath {
    /// Amplitude A.
    pub amplitude: f64,
    /// Mean value (default 0).
    #[serde(default)]
    pub mean: f64,
    /// Number of full cycles.
    pub cycles: usize,
    /// Equal steps per half cycle (segment).
    pub steps_per_segment: usize,
}

/// Path through waypoints.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WaypointPath {
    /// The points, from 0.
    pub points: Vec<f64>,
    /// Equal steps per segment.
    pub steps_per_segment: usize,
}

impl ScalarPath {
    /// The waypoints and the steps per segment.
    pub fn segments(&self) -> (Vec<f64>, usize) {
        match self {
            ScalarPath::Monotonic(p) => (vec![p.target], p.steps),
            ScalarPath::Cyclic(p) => {
                let mut w = Vec::with_capacity(2 * p.cycles + 1);
                for _ in 0..p.cycles {
                    w.push(p.mean + p.amplitude);
                    w.push(p.mean - p.amplitude);
                }
                w.push(p.mean);
                (w, p.steps_per_segment)
            }
            ScalarPath::Waypoints(p) => (p.points.clone(), p.steps_per_segment),
        }
    }

    /// The increments of the path, step by step.
    pub fn increments(&self) -> Vec<f64> {
        let (points, steps) = self.segments();
        let mut out = Vec::with_capacity(points.len() * steps);
        let mut from = 0.0;
        for to in points {
            for _ in 0..steps {
                out.push((to - from) / steps as f64);
            }
            from = to;
        }
        out
    }

    /// Checks step counts and finiteness; `field` is the YAML path of the path.
    pub fn validate(&self, field: &str) -> Result<(), (String, String)> {
        let (points, steps) = self.segments();
        let steps_key = match self {
            ScalarPath::Monotonic(_) => "steps",
            _ => "steps_per_segment",
        };
        if steps == 0 || steps > 10_000_000 {
            return Err((
                format!("{field}.{steps_key}"),
                format!("must be in 1..=10000000, got {steps}"),
            ));
        }
        if let ScalarPath::Cyclic(c) = self {
            if c.cycles == 0 {
                return Err((format!("{field}.cycles"), "must be at least 1".into()));
            }
        }
        if points.is_empty() || points.iter().any(|v| !v.is_finite()) {
            return Err((field.to_string(), "needs finite values".into()));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::interface_hyperbolic::HyperbolicParams;
    use crate::material::interface_mc::MohrCoulombParams;
    use crate::material::joint::JointParams;

    /// Omitted parameters take the seed tables; every variant survives a YAML round trip.
    #[test]
    fn interface_params_defaults_and_round_trip() {
        let p: InterfaceParams = serde_yaml::from_str("model: hyperbolic").unwrap();
        assert_eq!(p, InterfaceParams::Hyperbolic(HyperbolicParams::default()));
        let p: InterfaceParams = serde_yaml::from_str("model: mohr_coulomb\nphi: 30.0").unwrap();
        assert_eq!(
            p,
            InterfaceParams::MohrCoulomb(MohrCoulombParams {
                phi: 30.0,
                ..MohrCoulombParams::default()
            })
        );
        for p in [
            InterfaceParams::Hyperbolic(HyperbolicParams {
                kur: Some(900.0),
                ..HyperbolicParams::default()
            }),
            InterfaceParams::MohrCoulomb(MohrCoulombParams::default()),
            InterfaceParams::Joint(JointParams::default()),
        ] {
            let text = serde_yaml::to_string(&p).unwrap();
            assert!(text.contains(&format!("model: {}", p.name())), "{text}");
            assert_eq!(serde_yaml::from_str::<InterfaceParams>(&text).unwrap(), p);
            p.validate().unwrap();
        }
        assert!(serde_yaml::from_str::<InterfaceParams>("model: joint\nkn: 1.0").is_err());
    }

    #[test]
    fn path_increments_sum_to_the_waypoints() {
        let p = ScalarPath::Cyclic(CyclicPath {
            amplitude: 0.01,
            mean: 0.002,
            cycles: 3,
            steps_per_segment: 7,
        });
        let inc = p.increments();
        assert_eq!(inc.len(), 7 * 7);
        assert!((inc.iter().sum::<f64>() - 0.002).abs() < 1e-15);
        assert!(p.validate("test.path").is_ok());
        let bad = ScalarPath::Monotonic(MonotonicPath {
            target: 1.0,
            steps: 0,
        });
        assert_eq!(bad.validate("test.path").unwrap_err().0, "test.path.steps");
    }
}
