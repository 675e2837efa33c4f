//! A rockfill lift is placed in equilibrium at its placement stress σ₀ = −p_min·I (spec §8.6
//! item 1): the solver adds the nodal forces ∫ Bᵀσ₀ dV of every placed element to the external
//! force, so a lift with no load stays at σ₀ with zero displacement.
//!
//! Regression for issue 4 (staged GP dam stalls in the crest layer). Before the change the
//! uniform σ₀ was unbalanced on the free faces: the faces expanded to shed it, the points at the
//! lift edges dropped to the uniaxial state p ≈ p_min/3, η = 3 (the η cap) or crossed the tension
//! cut-off, and Newton chattered. Measured on this scene (2 ranks): before, the load step failed
//! after 8 cut-backs ("Newton did not converge in 25 iterations (relative residual 8.974e-1)",
//! exit code 3); after, it converges in 1 Newton iteration with σ = −p_min·I and u = 0 (~7 s).

mod common;
use common::*;

const SCENE: &str = "name: placed-lift
units: SI
mesh:
  box: { size: [10.0, 10.0, 10.0], divisions: [2, 2, 2] }
materials:
  fill: { model: rockfill_gp, density: 2150.0, tangent: numerical }
blocks:
  layer_1: { material: fill }
boundary:
  - { set: zmin, fix: [x, y, z] }
loads:
  gravity: { g: [0.0, 0.0, 0.0] }
solver: { load_steps: 1 }
";

/// p_min of the rockfill (Pa): the default 0.05·p_a with p_a = 101 300 Pa.
const P_MIN: f64 = 0.05 * 101_300.0;

#[test]
fn a_lift_placed_without_load_stays_at_the_pressure_floor() {
    let dir = tempdir();
    std::fs::write(dir.path().join("lift.yaml"), SCENE).unwrap();
    let o = cfrd_mpi(2, dir.path(), &["run", "lift.yaml", "-o", "out", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
    assert_eq!(summary["cutbacks"].as_u64(), Some(0), "{summary}");
    assert!(summary["newton_iterations"].as_u64().unwrap() <= 2, "{summary}");
    let h5 = dir.path().join("out/results.h5");
    let stress = read_f64(&h5, "/steps/000001/stress");
    let u = read_f64(&h5, "/steps/000001/displacement");
    assert_eq!(stress.len(), 8 * 6);
    for s in stress.chunks(6) {
        for c in 0..3 {
            assert!((s[c] + P_MIN).abs() < 1e-6 * P_MIN, "normal stress {s:?}");
        }
        for c in 3..6 {
            assert!(s[c].abs() < 1e-6 * P_MIN, "shear stress {s:?}");
        }
    }
    let u_max = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(u_max < 1e-12, "max |u| = {u_max:e}");
}
