//! Value checks of a parsed scene that need no mesh: units, ranges, plausibility of SI
//! magnitudes.

use super::error::SceneError;
use super::schema::{SceneFile, SolverSpec};
use crate::material::{BlockMaterial, MaterialParams};

/// Value checks that need no mesh: units, ranges, plausibility of SI magnitudes.
pub(super) fn check_values(
    f: &SceneFile,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<(), SceneError> {
    for (name, m) in &f.materials {
        m.validate()
            .map_err(|e| inv(&format!("materials.{name}.{}", e.field), e.reason))?;
        if let MaterialParams::Elastic(p) = m {
            if !(1.0e5..=1.0e13).contains(&p.young) {
                return Err(inv(
                    &format!("materials.{name}.young"),
                    format!(
                        "{} Pa is not a plausible Young's modulus; values are in Pa (SI), e.g. 25.5e9",
                        p.young
                    ),
                ));
            }
        }
        let BlockMaterial::Solid(solid) = m.split() else {
            continue;
        };
        let rho = solid.density();
        if !(100.0..=30_000.0).contains(&rho) {
            return Err(inv(
                &format!("materials.{name}.density"),
                format!("{rho} kg/m³ is not a plausible density; values are in kg/m³ (SI), e.g. 2150"),
            ));
        }
    }
    super::ranges::check_loads(&f.loads, "loads", inv)?;
    super::ranges::check_stages_and_counts(f, inv)?;
    let s = &f.solver;
    if !(s.rtol > 0.0 && s.rtol < 1.0) {
        return Err(inv("solver.rtol", format!("must lie in (0, 1), got {}", s.rtol)));
    }
    if !(s.newton_tol > 0.0 && s.newton_tol < 1.0) {
        return Err(inv(
            "solver.newton_tol",
            format!("must lie in (0, 1), got {}", s.newton_tol),
        ));
    }
    check_integration_tol_ratio(s, "solver.integration_tol_ratio", inv)
}

/// `solver.integration_tol_ratio` (or the command line's value, named `path`) is 0 or in
/// (0, 1] with ratio·newton_tol ≥ 1e-12, the smallest substepping tolerance.
pub(super) fn check_integration_tol_ratio(
    s: &SolverSpec,
    path: &str,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<(), SceneError> {
    let r = s.integration_tol_ratio;
    if !(r.is_finite() && (r == 0.0 || (r * s.newton_tol >= 1.0e-12 && r <= 1.0))) {
        return Err(inv(
            path,
            format!(
                "must be 0 (off) or lie in (0, 1] with ratio·newton_tol ≥ 1e-12 (the smallest \
                 substepping tolerance), got {r} (newton_tol {})",
                s.newton_tol
            ),
        ));
    }
    Ok(())
}
