//! Material-point tests from YAML files (`cfrd point TEST.yaml`): interface direct shear (CNL,
//! CNS; monotonic, cyclic, waypoints) and prescribed jump paths; solid drained triaxial
//! (monotonic or cyclic), oedometer and isotropic compression through
//! [`crate::material::driver_solid`]. Each file gives a material (any
//! [`crate::material::InterfaceParams`] or [`crate::material::SolidParams`]; omitted parameters
//! take the seed tables) and a test; the runner writes one CSV per run and one PNG figure (see
//! [`spec`] for the format and `inputs/point/` for examples). A file with a list `interfaces:`
//! compares several interface laws on the same direct-shear test (cross-check table and figure).
//! Solid tests start from the virgin isotropic state at a stated p0 (default σ3, spec G7).

pub mod csv;
pub mod runner;
pub mod spec;

pub use runner::{run_file, CaseSummary, CrossCheckRow, PointError, Summary};
pub use spec::PointTestFile;

/// JSON schema of the point-test file format (for `--print-schema`).
pub fn schema_json() -> String {
    let schema = schemars::schema_for!(PointTestFile);
    serde_json::to_string_pretty(&schema).unwrap_or_default()
}
