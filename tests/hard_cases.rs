//! Hard cases (issue 21): small scenes that push the solver and the models where dams push them.
//! Every case runs through `cfrd run` on 2 ranks (or `cfrd point`) and asserts that it converges
//! with its cut-backs counted in `summary.json`, that no output (every field of every step of
//! `results.h5`, every CSV table, the summary) holds a NaN or an infinity, and that its results
//! stay within stated physical bounds. Each case names what it guards against.
//!
//! Cases covered elsewhere, not repeated here:
//! * one load step for a whole stage on the generated dam with GP rockfill (hyperbolic
//!   interface, cut-backs counted, 1 and 2 ranks bitwise):
//!   `cfrd_dam::gp_dam_forces_cutbacks_and_opens_the_interface`; a GP column in one step under a
//!   30 MPa surcharge: `step_control.rs`;
//! * a lift placed in equilibrium at its placement stress σ₀ = −p_min·I: `placement.rs`;
//! * interface slip at the friction angle and joint opening and closing: `interfaces.rs`;
//! * 10,000 cycles of the models' own updates (no driver): `cfrd::material` unit tests
//!   `rockfill_gp::…::ten_thousand_cycles_stay_finite`, `interface_gp_tests::if7_ten_thousand_cycles_without_nan`,
//!   `joint::…::ten_thousand_cycles_return_exactly`, and the hyperbolic law's 10,000 cycles;
//! * the GP interface's neutral-loading paths: the ignored
//!   `interface_gp_tests::neutral_loading_path_does_not_stall` (known defect, measured there and
//!   in `cfrd::verification`, "Known defects"), with the reading that follows them tested
//!   beside it.
//!
//! Failing cases stay here, ignored, with the measured failure in their reason and doc comment
//! (`cargo test --release --test hard_cases -- --ignored` runs them).

mod common;
use common::*;
use std::path::Path;
use std::sync::OnceLock;

/// Unit weight of the rockfill (N/m³): 2150 kg/m³ · 9.81 m/s².
const GAMMA_FILL: f64 = 2150.0 * 9.81;

// ---------------------------------------------------------------------------------------------
// What every case checks

/// A run's `summary.json`.
fn summary(out: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary.json");
    serde_json::from_str(&text).expect("summary is JSON")
}

/// Converged: the summary counts its steps, Newton iterations per step and cut-backs, and the
/// cut-backs are at most `max_cutbacks`. Returns the cut-back count.
fn assert_converged_with_counted_cutbacks(case: &str, out: &Path, max_cutbacks: u64) -> u64 {
    let s = summary(out);
    let n = |k: &str| s[k].as_u64().unwrap_or_else(|| panic!("{case}: summary has {k}"));
    let per_step: Vec<u64> = s["newton_per_step"]
        .as_array()
        .expect("newton_per_step")
        .iter()
        .map(|v| v.as_u64().expect("a count"))
        .collect();
    println!(
        "{case}: {} steps, {} Newton iterations {per_step:?}, {} cut-backs, {:.1} s",
        n("steps"),
        n("newton_iterations"),
        n("cutbacks"),
        s["total_seconds"].as_f64().unwrap_or(f64::NAN)
    );
    assert_eq!(per_step.len() as u64, n("steps"), "{case}");
    assert_eq!(per_step.iter().sum::<u64>(), n("newton_iterations"), "{case}");
    assert!(
        n("cutbacks") <= max_cutbacks,
        "{case}: {} cut-backs",
        n("cutbacks")
    );
    n("cutbacks")
}

/// Every value of every step field of `results.h5`, every number of every CSV table and of
/// `summary.json` in `out` is finite.
fn assert_no_nan_in_any_output(case: &str, out: &Path) {
    let file = out.join("results.h5");
    let mut values = 0;
    for (name, _) in layout(&file)
        .into_iter()
        .filter(|(n, _)| n.starts_with("/steps/"))
    {
        let v = read_f64(&file, &name);
        assert!(
            v.iter().all(|x| x.is_finite()),
            "{case}: {name} holds a NaN or inf"
        );
        values += v.len();
    }
    assert!(values > 0, "{case}: no step field");
    for entry in std::fs::read_dir(out).expect("output directory").flatten() {
        let path = entry.path();
        if path.extension().is_some_and(|e| e == "csv") {
            assert_csv_finite(case, &path);
        }
    }
    assert!(
        json_finite(&summary(out)),
        "{case}: summary.json holds a null (a NaN or inf written by serde)"
    );
}

/// Whether a JSON value holds no null (serde writes a non-finite f64 as null) at any depth.
fn json_finite(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Null => false,
        serde_json::Value::Array(a) => a.iter().all(json_finite),
        serde_json::Value::Object(o) => o.values().all(json_finite),
        _ => true,
    }
}

/// Every number of a CSV table is finite (cells that are not numbers, e.g. stage names, are
/// skipped; Rust parses `NaN` and `inf` as numbers).
fn assert_csv_finite(case: &str, path: &Path) {
    let text = std::fs::read_to_string(path).expect("csv");
    for (k, line) in text.lines().enumerate().skip(1) {
        let bad = line
            .split(',')
            .filter_map(|c| c.trim().parse::<f64>().ok())
            .any(|v| !v.is_finite());
        assert!(!bad, "{case}: {}:{}: {line}", path.display(), k + 1);
    }
}

/// The largest magnitude of `field` over every step of the run, on the elements of the blocks
/// whose names start with `prefix` (every row for node fields when `prefix` is empty).
fn max_abs(out: &Path, field: &str, prefix: &str) -> f64 {
    let file = out.join("results.h5");
    let rows = element_rows(&file, prefix);
    let mut worst = 0.0f64;
    for (name, shape) in layout(&file)
        .into_iter()
        .filter(|(n, _)| n.ends_with(&format!("/{field}")))
    {
        let v = read_f64(&file, &name);
        let ncomp = shape.get(1).copied().unwrap_or(1);
        for (r, chunk) in v.chunks(ncomp).enumerate() {
            if prefix.is_empty() || rows.contains(&r) {
                worst = chunk.iter().fold(worst, |m, x| m.max(x.abs()));
            }
        }
    }
    worst
}

/// Indices of the elements of the blocks whose names start with `prefix`.
fn element_rows(file: &Path, prefix: &str) -> Vec<usize> {
    let names = block_names(file);
    read_i64(file, "/mesh/element_block")
        .iter()
        .enumerate()
        .filter(|(_, &b)| names[b as usize].starts_with(prefix))
        .map(|(e, _)| e)
        .collect()
}

/// Block names of a results file.
fn block_names(file: &Path) -> Vec<String> {
    let f = hdf5::File::open(file).expect("open results");
    let names: hdf5::types::VarLenUnicode = f
        .group("/mesh")
        .and_then(|g| g.attr("block_names"))
        .and_then(|a| a.read_scalar())
        .expect("block_names");
    names.as_str().split('\n').map(str::to_string).collect()
}

/// Runs `yaml` as `<name>.yaml` on 2 ranks into `<dir>/<name>`; asserts success.
fn run_ok(dir: &Path, name: &str, yaml: &str) -> std::path::PathBuf {
    std::fs::write(dir.join(format!("{name}.yaml")), yaml).unwrap();
    let o = cfrd_mpi(2, dir, &["run", &format!("{name}.yaml"), "-o", name, "-q"]);
    assert!(o.status.success(), "{name}: {}", text(&o));
    dir.join(name)
}

/// The step group (e.g. `/steps/000003`) of the last step of stage `stage`.
fn stage_step(file: &Path, stage: &str) -> String {
    let f = hdf5::File::open(file).expect("open results");
    let mut names = f.group("/steps").and_then(|g| g.member_names()).expect("steps");
    names.sort();
    names
        .into_iter()
        .rev()
        .find(|n| {
            f.group(&format!("/steps/{n}"))
                .and_then(|g| g.attr("stage"))
                .and_then(|a| a.read_scalar::<hdf5::types::VarLenUnicode>())
                .is_ok_and(|s| s.as_str() == stage)
        })
        .map(|n| format!("/steps/{n}"))
        .unwrap_or_else(|| panic!("{}: no step of stage {stage}", file.display()))
}

// ---------------------------------------------------------------------------------------------
// A GP rockfill embankment built in four layers, each in one load step

/// Height of the embankment section (m).
const WEDGE_H: f64 = 40.0;

/// A plane-strain embankment section (H = 40 m, slopes 1:1.4, crest 8 m; 6 × 8 elements) of GP
/// rockfill placed in 4 layers and loaded by a reservoir to 36 m, each stage in **one** load
/// step (the scene's `load_steps: 1`): Newton must take a layer's whole weight, or the whole
/// reservoir, at once, and each new layer is placed at p_min with its slopes and top free.
fn wedge_scene() -> String {
    let mut s = format!(
        "name: gp-wedge
units: SI
mesh:
  dam: {{ height: {WEDGE_H}, crest_width: 8.0, upstream_slope: 1.4, downstream_slope: 1.4, length: 10.0,
         divisions: [6, 1, 8], layers: 4 }}
materials:
  fill: {{ model: rockfill_gp, density: 2150.0 }}
blocks:
"
    );
    for k in 1..=4 {
        s += &format!("  layer_{k}: {{ material: fill }}\n");
    }
    s += "boundary:
  - { set: base, fix: [x, y, z] }
  - { set: ymin, fix: [y] }
  - { set: ymax, fix: [y] }
loads:
  gravity: { g: [0.0, 0.0, -9.81] }
solver: { load_steps: 1, newton_max_iterations: 15, newton_tol: 1.0e-5, linear_solver: canonical_lu }
stages:
";
    for k in 1..=4 {
        s += &format!("  - {{ name: fill_{k}, activate: [layer_{k}] }}\n");
    }
    s + "  - { name: impound, loads: { hydrostatic: [ { faces: upstream, level: 36.0 } ] } }\n"
}

/// The wedge run, shared by the cases that read it (run once, on first use).
fn wedge_run() -> &'static Path {
    static RUN: OnceLock<(tempfile::TempDir, std::path::PathBuf)> = OnceLock::new();
    let (_, out) = RUN.get_or_init(|| {
        let dir = tempdir();
        let out = run_ok(dir.path(), "wedge", &wedge_scene());
        (dir, out)
    });
    out
}

/// Guards against a load step that covers a whole stage: the weight of a layer, or the whole
/// reservoir, in one Newton solve of the GP rockfill. The step control must cut back and regrow
/// (measured: 5 cut-backs, 10 converged steps for 5 stages, 107 Newton iterations) and end at
/// the full load with bounded displacements (below 1 % of H; measured 0.062 m, 0.16 %).
#[test]
fn a_load_step_covering_a_whole_stage_converges_by_cutbacks() {
    let out = wedge_run();
    let cutbacks = assert_converged_with_counted_cutbacks("whole-stage steps", out, 40);
    assert!(
        cutbacks >= 1,
        "one step per stage is too large for one Newton solve"
    );
    assert_no_nan_in_any_output("whole-stage steps", out);
    let u = max_abs(out, "displacement", "");
    println!("whole-stage steps: largest displacement {u:.4} m");
    assert!(u > 0.0 && u < 0.01 * WEDGE_H, "largest displacement {u} m");
}

/// Guards against freshly placed, unconfined layers: each layer starts at p_min with free
/// slopes and top (the state that made the staged GP dam stall before placement was balanced,
/// `placement.rs`). After every fill stage each placed element is in compression and no
/// stress component exceeds 1.5 times the overburden γ·h at the base of the height placed so
/// far (measured: at most 0.90·γh, after the second layer).
#[test]
fn freshly_placed_unconfined_layers_stay_in_compression_and_bounded() {
    let out = wedge_run();
    let file = out.join("results.h5");
    for k in 1..=4 {
        let step = stage_step(&file, &format!("fill_{k}"));
        let stress = read_f64(&file, &format!("{step}/stress"));
        let h = WEDGE_H * k as f64 / 4.0;
        let placed: Vec<&[f64]> = element_rows(&file, "layer_")
            .into_iter()
            .map(|e| &stress[6 * e..6 * e + 6])
            .filter(|s| s.iter().any(|v| *v != 0.0))
            .collect();
        assert_eq!(placed.len(), 12 * k, "fill_{k}: placed elements");
        let p_min = placed
            .iter()
            .map(|s| -(s[0] + s[1] + s[2]) / 3.0)
            .fold(f64::INFINITY, f64::min);
        let s_max = placed
            .iter()
            .flat_map(|s| s.iter())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        println!(
            "fill_{k}: smallest mean pressure {p_min:.0} Pa, largest |σ| {:.2}·γh",
            s_max / (GAMMA_FILL * h)
        );
        assert!(p_min > 0.0, "fill_{k}: an element in tension");
        assert!(s_max < 1.5 * GAMMA_FILL * h, "fill_{k}: |σ| = {s_max:.3e} Pa");
    }
}

// ---------------------------------------------------------------------------------------------
// Rockfill next to the tension cut-off

/// Guards against near-tension rockfill, the state of the crest: a GP rockfill cube (2 × 2 × 2
/// hexahedra on symmetry rollers) loaded to 500/200/200 kPa, unloaded to its placement stress
/// p_min = 5.065 kPa and then pulled by 4 kPa on its three free faces, which leaves
/// p = p_min − 4 kPa = 1.065 kPa, 1.05 times the tension cut-off p_t = 1.013 kPa (defaults,
/// spec §8.6). The homogeneous state is known by equilibrium, so every element's stress must be
/// −1.065 kPa·I to within 1 % of p_min, 51 Pa (measured within 15 Pa), with its cut-backs
/// counted (measured: 11).
#[test]
fn rockfill_pulled_to_just_above_the_tension_cutoff_converges() {
    let dir = tempdir();
    let scene = "name: near-tension
units: SI
mesh:
  box: { size: [2.0, 2.0, 2.0], divisions: [2, 2, 2] }
materials:
  fill: { model: rockfill_gp, density: 2150.0 }
blocks:
  layer_1: { material: fill }
boundary:
  - { set: zmin, fix: [z] }
  - { set: xmin, fix: [x] }
  - { set: ymin, fix: [y] }
loads:
  gravity: { g: [0.0, 0.0, 0.0] }
solver: { load_steps: 4, newton_max_iterations: 15, newton_tol: 1.0e-6, linear_solver: canonical_lu }
stages:
  - { name: load, activate: [layer_1], loads: { pressure: [ { faces: zmax, value: 5.0e5 }, { faces: xmax, value: 2.0e5 }, { faces: ymax, value: 2.0e5 } ] } }
  - { name: unload }
  - { name: pull, loads: { pressure: [ { faces: zmax, value: -4.0e3 }, { faces: xmax, value: -4.0e3 }, { faces: ymax, value: -4.0e3 } ] } }
";
    let out = run_ok(dir.path(), "cube", scene);
    assert_converged_with_counted_cutbacks("near tension", &out, 40);
    assert_no_nan_in_any_output("near tension", &out);
    let file = out.join("results.h5");
    let stress = read_f64(&file, &format!("{}/stress", stage_step(&file, "pull")));
    let expected = -(0.05 * 101_300.0 - 4.0e3);
    let worst = stress
        .chunks(6)
        .flat_map(|s| (0..6).map(move |c| (s[c] - if c < 3 { expected } else { 0.0 }).abs()))
        .fold(0.0f64, f64::max);
    println!("near tension: σ = {expected:.1} Pa·I expected, largest deviation {worst:.2} Pa");
    assert!(worst < 0.01 * 0.05 * 101_300.0, "largest deviation {worst} Pa");
}

// ---------------------------------------------------------------------------------------------
// The generated CFRD: slab, interface and joints

/// The small generated CFRD (4 fill layers, 60 m panels) with elastic rockfill (E = 300 MPa,
/// so the case is about the slab and the interface, and runs in seconds), the slab-cushion
/// interface `law`, slab density `rho_slab`, and `mesh_extra` keys of `mesh.cfrd`.
fn dam_scene(law: &str, rho_slab: f64, mesh_extra: &str) -> String {
    small_dam(
        ELASTIC_FILL,
        law,
        rho_slab,
        mesh_extra,
        "{ newton_tol: 1.0e-5, newton_max_iterations: 15, load_steps: 2, linear_solver: canonical_lu }",
        SEED_FIGURES,
    )
}

/// Guards against slab-cushion interfaces opening at the crest under impoundment: the
/// reservoir (to el. 2760 m, 92 m below the crest) pushes the lower slab into the cushion and a
/// light slab (500 kg/m³, so σ_n ≈ 1 kPa above the water) lifts off near the crest. For each
/// interface law the run converges, some interface elements open, only above the water line,
/// and the openings stay below 1 cm (measured: 6 elements open, at most 3.2 mm with the GP
/// interface's reading before issue 19, 0.2 mm with the other two). The GP interface's bounded
/// default converges too but opens nowhere here (measured: 0 elements): unloaded from its
/// closure it opens only after a large separation (75.7 mm from 100 kPa at the material point,
/// `cfrd::material::interface_gp`), so the opening case runs the GP law in its earlier reading.
#[test]
fn interfaces_opening_at_the_crest_under_impoundment() {
    let level = 2760.0;
    for (name, law, must_open) in [
        ("gp_interface", "gp_interface", false),
        (
            "gp_interface_unbounded",
            "gp_interface, normal_basis: displacement, void_ratio_bound: none, reversal_branch: start",
            true,
        ),
        ("hyperbolic", "hyperbolic", true),
        ("mohr_coulomb", "mohr_coulomb", true),
    ] {
        let dir = tempdir();
        let yaml = dam_scene(law, 500.0, &format!(", impoundment_level: {level}"));
        let out = run_ok(dir.path(), name, &yaml);
        let case = format!("crest opening ({name})");
        assert_converged_with_counted_cutbacks(&case, &out, 40);
        assert_no_nan_in_any_output(&case, &out);
        let file = out.join("results.h5");
        let last = stage_step(&file, "impound_2");
        let opening = read_f64(&file, &format!("{last}/interface_opening"));
        let z = element_centre_z(&file);
        let open: Vec<usize> = element_rows(&file, "interface_")
            .into_iter()
            .filter(|&e| opening[e] > 0.0)
            .collect();
        let widest = open.iter().map(|&e| opening[e]).fold(0.0, f64::max);
        println!(
            "{case}: {} interface elements open, widest {widest:.3e} m",
            open.len()
        );
        assert!(
            !must_open || !open.is_empty(),
            "{case}: no interface element opens"
        );
        assert!(
            open.iter().all(|&e| z[e] > level),
            "{case}: an element opens under water"
        );
        assert!(widest < 0.01, "{case}: opening {widest} m");
    }
}

/// Elevation of every element's centre.
fn element_centre_z(file: &Path) -> Vec<f64> {
    let z: Vec<f64> = read_f64(file, "/mesh/coordinates")
        .chunks(3)
        .map(|c| c[2])
        .collect();
    read_i64(file, "/mesh/topology")
        .chunks(8)
        .map(|t| t.iter().map(|&n| z[n as usize]).sum::<f64>() / 8.0)
        .collect()
}

/// Guards against a slab on a near-vertical abutment: the valley is 199 m wide at the bottom
/// under a 200 m crest, so each abutment rises 171 m over 0.5 m (89.8°), and the edge panels
/// and perimetric joints lie on it. The GP-interface dam converges through its schedule with
/// bounded slab stresses (below 20 MPa; measured 4.6 MPa) and displacements (below 1 m;
/// measured 0.24 m).
#[test]
fn a_slab_on_a_near_vertical_abutment() {
    let dir = tempdir();
    let yaml = dam_scene(
        "gp_interface",
        2400.0,
        ", crest_length: 200.0, valley_bottom_width: 199.0",
    );
    let out = run_ok(dir.path(), "steep", &yaml);
    assert_converged_with_counted_cutbacks("steep abutment", &out, 40);
    assert_no_nan_in_any_output("steep abutment", &out);
    let (s, u) = (
        max_abs(&out, "stress", "slab_"),
        max_abs(&out, "displacement", ""),
    );
    println!("steep abutment: largest slab |σ| {s:.3e} Pa, largest displacement {u:.3} m");
    assert!(s > 0.0 && s < 20.0e6, "slab stress {s} Pa");
    assert!(u < 1.0, "displacement {u} m");
}

// ---------------------------------------------------------------------------------------------
// Zero-thickness elements: nearly coincident faces and vanishing normal stress

/// Gmsh 2.2 text of two 2 × 2 × 1 m elastic blocks, `base` (z in [0, 1]) and `block` (z from
/// 1 + `gap` to 2), with the one-element zero-thickness layer `contact` between them (nodes
/// 1–4 on the block, 5–8 on the base) and the physical surfaces `bottom` and `top`.
fn two_blocks_msh(gap: f64) -> String {
    let planes = [0.0, 1.0, 1.0 + gap, 2.0];
    let mut nodes = Vec::new();
    for (p, z) in planes.iter().enumerate() {
        for (k, (x, y)) in [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]
            .iter()
            .enumerate()
        {
            nodes.push(format!("{} {x} {y} {z:e}", 4 * p + k + 1));
        }
    }
    let quad = |p: usize| {
        (1..=4)
            .map(|k| (4 * p + k).to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let elements = [
        format!("1 3 2 1 1 {}", quad(0)),
        format!("2 3 2 2 2 {}", quad(3)),
        format!("3 5 2 3 3 {} {}", quad(0), quad(1)),
        format!("4 5 2 4 4 {} {}", quad(2), quad(3)),
        format!("5 5 2 5 5 {} {}", quad(2), quad(1)),
    ];
    format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n5\n2 1 \"bottom\"\n2 2 \"top\"\n\
         3 3 \"base\"\n3 4 \"block\"\n3 5 \"contact\"\n$EndPhysicalNames\n$Nodes\n16\n{}\n$EndNodes\n\
         $Elements\n5\n{}\n$EndElements\n",
        nodes.join("\n"),
        elements.join("\n")
    )
}

/// The two blocks with the `contact` law `law`, the base held at its bottom, the top pushed
/// 2 mm sideways, under a normal pressure given by `stages` (YAML list items).
fn two_blocks_scene(law: &str, stages: &str) -> String {
    format!(
        "name: two-blocks
units: SI
mesh: {{ file: blocks.msh }}
materials:
  concrete: {{ model: elastic, young: 2.0e10, poisson: 0.2, density: 2400.0 }}
  contact: {{ model: {law} }}
blocks:
  base: {{ material: concrete }}
  block: {{ material: concrete }}
  contact: {{ material: contact, orientation: [0.0, 0.0, -1.0] }}
boundary:
  - {{ set: bottom, fix: [x, y, z] }}
  - {{ set: top, fix: [x, y], value: [0.002, 0.0] }}
loads:
  gravity: {{ g: [0.0, 0.0, 0.0] }}
solver: {{ load_steps: 4, newton_max_iterations: 25, linear_solver: canonical_lu }}
stages:
{stages}"
    )
}

/// The first stage: place everything under a normal pressure `p` (Pa) on the top.
fn press(p: f64) -> String {
    format!(
        "  - {{ name: press, activate: [base, block, contact], loads: {{ pressure: [ {{ faces: top, value: {p:e} }} ] }} }}\n"
    )
}

/// Runs the two blocks with the mesh of gap `gap` in `dir/<name>`; returns the `cfrd` output.
fn run_two_blocks(dir: &Path, name: &str, gap: f64, yaml: &str) -> std::process::Output {
    let sub = dir.join(name);
    std::fs::create_dir_all(&sub).unwrap();
    std::fs::write(sub.join("blocks.msh"), two_blocks_msh(gap)).unwrap();
    std::fs::write(sub.join("scene.yaml"), yaml).unwrap();
    cfrd_mpi(2, &sub, &["run", "scene.yaml", "-o", "out", "-q"])
}

/// Guards against a zero-thickness element whose faces are nearly, not exactly, coincident (a
/// mesh written with rounded coordinates): faces 1e-10 m apart (3.5e-11 of the face diagonal,
/// inside the zero-thickness tolerance 1e-9) give the exactly coincident mesh's interface
/// traction and jump to 1e-9 relative (Mohr–Coulomb, 100 kPa, 2 mm push); faces 1e-8 m apart
/// the other way (a 3.5e-9 thin hexahedron, beyond the tolerance) are refused with exit code 2
/// and a message naming the block, not solved as a degenerate solid.
#[test]
fn nearly_coincident_interface_faces() {
    let dir = tempdir();
    let yaml = two_blocks_scene("mohr_coulomb", &press(1.0e5));
    let mut fields = Vec::new();
    for (name, gap) in [("exact", 0.0), ("near", 1e-10)] {
        let o = run_two_blocks(dir.path(), name, gap, &yaml);
        assert!(o.status.success(), "{name}: {}", text(&o));
        let out = dir.path().join(name).join("out");
        assert_converged_with_counted_cutbacks(&format!("faces {name}"), &out, 40);
        assert_no_nan_in_any_output(name, &out);
        let file = out.join("results.h5");
        let step = stage_step(&file, "press");
        let mut v = read_f64(&file, &format!("{step}/interface_traction"));
        v.extend(read_f64(&file, &format!("{step}/interface_jump")));
        fields.push(v);
    }
    let scale = fields[0].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = fields[0]
        .iter()
        .zip(&fields[1])
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    println!(
        "nearly coincident faces: largest difference {:.2e} of {scale:.3e}",
        diff / scale
    );
    assert!(scale > 0.0 && diff <= 1e-9 * scale, "{diff:e} of {scale:e}");
    let o = run_two_blocks(dir.path(), "thin", -1e-8, &yaml);
    let msg = text(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("block 'contact'") && !msg.contains("panicked"),
        "{msg}"
    );
}

/// Guards against interfaces at low normal stress: the blocks pushed 2 mm sideways under
/// σ_n = 100 Pa (0.001 p_a), where the hyperbolic law's stiffness ∝ σ_n^n nearly vanishes and
/// every law slides. Each law converges and its shear traction stays below σ_n (tan φ < 1 for
/// the seed parameters; measured τ/σ_n = 0.81 Mohr–Coulomb, 0.88 hyperbolic, 0.54 GP, with 6
/// and 9 cut-backs for the first two).
#[test]
fn interfaces_at_low_normal_stress_slide_and_converge() {
    let dir = tempdir();
    for law in ["mohr_coulomb", "hyperbolic", "gp_interface"] {
        let o = run_two_blocks(dir.path(), law, 0.0, &two_blocks_scene(law, &press(100.0)));
        assert!(o.status.success(), "{law}: {}", text(&o));
        let out = dir.path().join(law).join("out");
        assert_converged_with_counted_cutbacks(&format!("σ_n = 100 Pa ({law})"), &out, 40);
        assert_no_nan_in_any_output(law, &out);
        let t = read_f64(&out.join("results.h5"), "/steps/000001/interface_traction");
        let contact = t.len() / 3 - 1;
        let (tau, t_n) = (t[3 * contact].hypot(t[3 * contact + 1]), t[3 * contact + 2]);
        println!("σ_n = 100 Pa ({law}): τ = {tau:.2} Pa, t_n = {t_n:.2} Pa");
        assert!((t_n + 100.0).abs() < 1e-3 * 100.0, "{law}: t_n = {t_n}");
        assert!(tau > 0.0 && tau < 100.0, "{law}: τ = {tau}");
    }
}

/// Guards against interfaces whose normal stress goes to zero: after the 100 Pa case above, the
/// pressure is released to zero with the 2 mm push held, so the friction and the reactions
/// vanish. **Fails (measured at commit 6ad500c):** every law stalls in the release stage.
/// Mohr–Coulomb at λ = 0.99966 (σ_n = 0.034 Pa) and hyperbolic at λ = 0.99960 (0.040 Pa) after 8
/// cut-backs, with relative residuals 1.07e-8 and 1.89e-8 against newton_tol 1e-8 and absolute
/// out-of-balance forces of 1e-9 N: the residual is measured against max(|f_ext|, |f_int|),
/// which vanishes with σ_n, while the round-off of the stiff blocks' internal forces does not.
/// The GP interface stalls earlier, at λ = 0.456 (σ_n = 54 Pa), relative residual 1.5e-4 at
/// its substepping tolerance STOL = 1e-4 (the stall the solver's message names).
#[test]
#[ignore = "fails: releasing σ_n to 0 stalls every interface law (relative residual against a vanishing reference force; GP at its STOL); measured in the doc comment"]
fn interfaces_released_to_zero_normal_stress() {
    let dir = tempdir();
    for law in ["mohr_coulomb", "hyperbolic", "gp_interface"] {
        let stages = press(100.0) + "  - { name: release }\n";
        let o = run_two_blocks(dir.path(), law, 0.0, &two_blocks_scene(law, &stages));
        assert!(o.status.success(), "{law}: {}", text(&o));
        let out = dir.path().join(law).join("out");
        assert_converged_with_counted_cutbacks(&format!("σ_n → 0 ({law})"), &out, 40);
        assert_no_nan_in_any_output(law, &out);
    }
}

// ---------------------------------------------------------------------------------------------
// 10,000 small cycles through the material-point driver (`cfrd point`)

/// Runs `cfrd point` on `yaml` in `dir` and returns the rows of its one CSV table.
fn point_rows(dir: &Path, yaml: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    std::fs::write(dir.join("cycles.yaml"), yaml).unwrap();
    let o = cfrd(dir, &["point", "cycles.yaml", "-o", "out"]);
    assert!(o.status.success(), "{}", text(&o));
    let csv = std::fs::read_dir(dir.join("out"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|e| e == "csv"))
        .expect("a CSV table");
    assert_csv_finite("10,000 cycles", &csv);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(str::to_string).collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse::<f64>().expect("a number"))
                .collect()
        })
        .collect();
    (header, rows)
}

/// Guards against drift and blow-up under many small cycles at a rockfill GP point: a drained
/// triaxial point at σ3 = 300 kPa cycled 10,000 times between q = 100 and 150 kPa by the
/// mixed-control driver (2 steps per half cycle, 40,002 steps). Every value stays finite, q
/// stays in the cycled range, and the volumetric strain stays bounded (below 5 %; measured
/// 3.41 % at the end, most of it accumulated densification).
#[test]
fn ten_thousand_small_cycles_at_a_rockfill_gp_point() {
    let dir = tempdir();
    let yaml = "solid: { model: rockfill_gp }
test:
  kind: cyclic_triaxial
  confining_pressures: [300.0e3]
  q_min: 100.0e3
  q_max: 150.0e3
  cycles: 10000
  steps_per_half: 2
";
    let (header, rows) = point_rows(dir.path(), yaml);
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{name}"))
    };
    let (q, eps_v) = (col("q_Pa"), col("eps_v"));
    assert!(rows.len() >= 40_000, "{} rows", rows.len());
    let last = rows.last().unwrap();
    println!(
        "10,000 rockfill cycles: {} rows, final eps_v = {:.4e}, q = {:.1} kPa",
        rows.len(),
        last[eps_v],
        last[q] / 1e3
    );
    assert!(rows.iter().all(|r| r[q] > -1.0 && r[q] < 150.0e3 + 1.0));
    assert!(rows.iter().all(|r| r[eps_v].abs() < 0.05));
}

/// Guards against the same 10,000 small cycles at a GP-interface point: direct shear ±0.2 mm
/// under constant normal load 200 kPa, 2 steps per segment. **Fails (measured at commit
/// 6ad500c):** `cfrd point` stops at step 203 of 40,002 with "normal stress did not converge
/// (residual 4.963e0 Pa, target sigma_n 2.0000e5 Pa)" (exit code 2). The driver holds σ_n to
/// 1e-8 relative (2 mPa) while the interface is integrated to STOL = 1e-4: with ±0.5 mm it
/// stops at step 979, with ±0.1 mm at step 3543; with `integration: { stol: 1.0e-6 }` at
/// step 7151, and with `stol: 1.0e-8` all 40,002 steps run (21 s). The model itself runs
/// 10,000 cycles with an explicit normal-stress correction
/// (`interface_gp_tests::if7_ten_thousand_cycles_without_nan`).
#[test]
#[ignore = "fails: the CNL driver's 1e-8 normal-stress tolerance is below the GP interface's integration noise (STOL 1e-4); stops at step 203; measured in the doc comment"]
fn ten_thousand_small_cycles_at_a_gp_interface_point() {
    let dir = tempdir();
    let yaml = "interface: { model: gp_interface }
test:
  kind: direct_shear
  control: cnl
  normal_stresses: [200.0e3]
  path: { kind: cyclic, amplitude: 0.0002, cycles: 10000, steps_per_segment: 2 }
";
    let (header, rows) = point_rows(dir.path(), yaml);
    let sn = header.iter().position(|h| h == "sigma_n_Pa").expect("sigma_n_Pa");
    assert!(rows.len() >= 40_000, "{} rows", rows.len());
    assert!(rows.iter().all(|r| (r[sn] - 200.0e3).abs() < 1.0));
}
