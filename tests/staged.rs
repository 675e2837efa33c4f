//! Staged construction (issue 4, acceptance 1, layered column): a laterally confined column
//! built in layers, each placed strain-free under its own weight, matches the closed-form
//! layered settlement s(z) = γ (H − z) z / M at the layer boundaries (largest at mid-height),
//! which differs from one-shot gravity s(z) = γ (H z − z²/2) / M. Run on 2 ranks; the results
//! file holds one step per stage.

mod common;
use common::*;

const LAYERS: usize = 8;
const H: f64 = 16.0;

fn scene(staged: bool) -> String {
    let mut s = format!(
        "name: layered-column
units: SI
mesh:
  box: {{ size: [1.0, 1.0, {H}], divisions: [1, 1, {LAYERS}], layers: {LAYERS} }}
materials:
  soil: {{ model: elastic, young: 5.0e7, poisson: 0.3, density: 2000.0 }}
blocks:
"
    );
    for k in 1..=LAYERS {
        s += &format!("  layer_{k}: {{ material: soil }}\n");
    }
    s += CONFINED_COLUMN_BOUNDARY;
    s += "loads:
  gravity: { g: [0.0, 0.0, -9.81] }
solver: { rtol: 1.0e-12, petsc_options: '-pc_type jacobi' }
";
    if staged {
        s += "stages:\n";
        for k in 1..=LAYERS {
            s += &format!("  - {{ name: fill_{k}, activate: [layer_{k}] }}\n");
        }
    }
    s
}

#[test]
fn layered_column_matches_the_closed_form() {
    let dir = tempdir();
    std::fs::write(dir.path().join("staged.yaml"), scene(true)).unwrap();
    std::fs::write(dir.path().join("oneshot.yaml"), scene(false)).unwrap();
    for (f, out) in [("staged.yaml", "s"), ("oneshot.yaml", "o")] {
        let o = cfrd_mpi(2, dir.path(), &["run", f, "-o", out, "-q"]);
        assert!(o.status.success(), "{f}: {}", text(&o));
    }
    let file = dir.path().join("s/results.h5");
    let steps: Vec<String> = layout(&file)
        .into_iter()
        .filter(|(n, _)| n.ends_with("/displacement"))
        .map(|(n, _)| n)
        .collect();
    assert_eq!(steps.len(), LAYERS, "one results step per stage: {steps:?}");
    let last = format!("/steps/{LAYERS:06}/displacement");
    let u = read_f64(&file, &last);
    let u1 = read_f64(&dir.path().join("o/results.h5"), "/steps/000001/displacement");
    let z: Vec<f64> = read_f64(&file, "/mesh/coordinates")
        .chunks(3)
        .map(|c| c[2])
        .collect();
    let (e, nu, gamma) = (5.0e7, 0.3, 2000.0 * 9.81);
    let m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mut worst = 0.0f64;
    let scale = gamma * H * H / (4.0 * m);
    for (i, &zi) in z.iter().enumerate() {
        let layered = -gamma * (H - zi) * zi / m;
        let oneshot = -gamma * (H * zi - 0.5 * zi * zi) / m;
        worst = worst.max((u[3 * i + 2] - layered).abs() / scale);
        assert!(
            (u1[3 * i + 2] - oneshot).abs() / scale < 1e-8,
            "one-shot gravity at z = {zi}"
        );
    }
    println!("layered settlement: max error {worst:.2e} of γH²/(4M) = {scale:.4e} m");
    assert!(worst < 1e-8, "layered settlement error {worst:.3e}");
    // the largest settlement is at mid-height, not at the top
    let (i_max, _) = u
        .chunks(3)
        .enumerate()
        .fold((0, 0.0), |b, (i, c)| if c[2] < b.1 { (i, c[2]) } else { b });
    assert!(
        (z[i_max] - H / 2.0).abs() < 1e-9,
        "largest settlement at z = {}",
        z[i_max]
    );
    let top = z.iter().position(|&zi| (zi - H).abs() < 1e-9).unwrap();
    assert!(
        u[3 * top + 2].abs() < 1e-12,
        "the top was placed last: no settlement"
    );
}
