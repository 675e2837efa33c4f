//! Range checks of the loads, stages, boundary values and solver counts of a scene, like those
//! of the material parameters: every value finite and plausible in SI units, every count within
//! a documented limit; each error names the YAML path and the unit.

use super::error::SceneError;
use super::schema::{LoadsSpec, SceneFile, SolverSpec};

/// Most load steps of a stage (`solver.load_steps`, `stages[k].load_steps`).
pub const MAX_LOAD_STEPS: u32 = 1_000_000;
/// Largest growth of a static load step over its nominal size (`solver.step_growth`).
pub const MAX_STEP_GROWTH: u32 = 64;
/// Most consecutive cut-backs (`solver.max_cutbacks`): beyond some 50 halvings a load step is
/// below the resolution of a double.
pub const MAX_CUTBACKS: u32 = 60;
/// Largest magnitude of a pressure load (Pa).
pub const MAX_PRESSURE: f64 = 1.0e10;
/// Largest magnitude of a free-surface elevation of a hydrostatic load (m).
pub const MAX_LEVEL: f64 = 1.0e5;
/// Largest magnitude of a gravity vector (m/s²).
pub const MAX_GRAVITY: f64 = 100.0;
/// Largest magnitude of a prescribed displacement (m).
pub const MAX_DISPLACEMENT: f64 = 1.0e3;

type Inv<'a> = &'a dyn Fn(&str, String) -> SceneError;

/// Checks the loads `loads` found at the YAML path `path` (`loads` or `stages[k].loads`).
pub fn check_loads(loads: &LoadsSpec, path: &str, inv: Inv) -> Result<(), SceneError> {
    if let Some(g) = &loads.gravity {
        let small = g.g.iter().all(|c| c.is_finite() && c.abs() <= MAX_GRAVITY);
        let norm = g.g.iter().map(|c| c * c).sum::<f64>().sqrt();
        if !(small && norm <= MAX_GRAVITY) {
            return Err(inv(
                &format!("{path}.gravity.g"),
                format!(
                    "{:?} m/s² is not plausible: |g| must be at most {MAX_GRAVITY} m/s² (SI: [0, 0, -9.81])",
                    g.g
                ),
            ));
        }
    }
    for (i, p) in loads.pressure.iter().enumerate() {
        if !(p.value.is_finite() && p.value.abs() <= MAX_PRESSURE) {
            return Err(inv(
                &format!("{path}.pressure[{i}].value"),
                format!(
                    "{} Pa is not plausible: a pressure must be finite and at most {MAX_PRESSURE:e} Pa \
                     in magnitude (values are in Pa, SI)",
                    p.value
                ),
            ));
        }
    }
    for (i, h) in loads.hydrostatic.iter().enumerate() {
        if !(h.level.is_finite() && h.level.abs() <= MAX_LEVEL) {
            return Err(inv(
                &format!("{path}.hydrostatic[{i}].level"),
                format!(
                    "{} m is not plausible: the free-surface elevation must be finite and at most \
                     {MAX_LEVEL:e} m in magnitude (m, SI)",
                    h.level
                ),
            ));
        }
        if !(h.unit_weight.is_finite() && h.unit_weight > 100.0 && h.unit_weight < 1.0e5) {
            return Err(inv(
                &format!("{path}.hydrostatic[{i}].unit_weight"),
                format!("{} N/m³ is not plausible (SI: 9810)", h.unit_weight),
            ));
        }
    }
    Ok(())
}

/// Checks a count at `path` (load steps, step growth) against [1, `max`].
fn check_count(n: u32, max: u32, path: &str, inv: Inv) -> Result<(), SceneError> {
    if (1..=max).contains(&n) {
        Ok(())
    } else {
        Err(inv(path, format!("{n} must lie in [1, {max}]")))
    }
}

/// Checks the stages' loads and load steps, the boundary values and the solver's counts.
pub fn check_stages_and_counts(f: &SceneFile, inv: Inv) -> Result<(), SceneError> {
    for (k, st) in f.stages.iter().enumerate() {
        check_loads(&st.loads, &format!("stages[{k}].loads"), inv)?;
        if let Some(n) = st.load_steps {
            check_count(n, MAX_LOAD_STEPS, &format!("stages[{k}].load_steps"), inv)?;
        }
    }
    for (i, b) in f.boundary.iter().enumerate() {
        for (k, v) in b.value.iter().enumerate() {
            if !(v.is_finite() && v.abs() <= MAX_DISPLACEMENT) {
                return Err(inv(
                    &format!("boundary[{i}].value[{k}]"),
                    format!(
                        "{v} m is not plausible: a prescribed displacement must be finite and at \
                         most {MAX_DISPLACEMENT} m in magnitude (m, SI)"
                    ),
                ));
            }
        }
    }
    check_solver_counts(&f.solver, inv)
}

/// Checks the solver's iteration, step and cut-back counts.
fn check_solver_counts(s: &SolverSpec, inv: Inv) -> Result<(), SceneError> {
    check_count(s.load_steps, MAX_LOAD_STEPS, "solver.load_steps", inv)?;
    check_count(s.step_growth, MAX_STEP_GROWTH, "solver.step_growth", inv)?;
    if s.max_cutbacks > MAX_CUTBACKS {
        return Err(inv(
            "solver.max_cutbacks",
            format!("{} must be at most {MAX_CUTBACKS}", s.max_cutbacks),
        ));
    }
    for (n, path) in [
        (s.max_iterations, "solver.max_iterations"),
        (s.newton_max_iterations, "solver.newton_max_iterations"),
    ] {
        if n == 0 {
            return Err(inv(path, "must be at least 1".into()));
        }
    }
    Ok(())
}
