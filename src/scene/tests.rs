//! Scene tests: block patterns, the generated CFRD schedule, and hostile input (issue: bad input
//! must be an error naming its place).

use super::blocks::block_pattern_matches;
use super::{Scene, SceneError, Term};
use std::path::Path;

/// A `boundary` section that holds a box by its base.
const FIXED_BASE: &str = "boundary: [{ set: zmin, fix: [x, y, z] }]\n";

/// A box of three layers with the given `blocks` section.
fn box_scene(blocks: &str) -> Result<Scene, SceneError> {
    let text = format!(
        "name: t\nunits: SI\nmesh: {{ box: {{ divisions: [1, 1, 3], layers: 3 }} }}\n\
         materials:\n  a: {{ model: elastic, young: 1.0e7, poisson: 0.3, density: 2000.0 }}\n  \
         b: {{ model: elastic, young: 2.0e7, poisson: 0.3, density: 2000.0 }}\n\
         blocks:\n{blocks}{FIXED_BASE}"
    );
    Scene::from_str(&text, "t.yaml", Path::new("."))
}

fn message(r: Result<Scene, SceneError>) -> String {
    r.expect_err("invalid scene").to_string()
}

#[test]
fn block_patterns_match_runs_of_characters() {
    for (p, n, hit) in [
        ("fill_*_cushion", "fill_012_cushion", true),
        ("fill_*_cushion", "fill__cushion", true),
        ("fill_*_cushion", "fill_012_transition", false),
        ("*", "anything", true),
        ("slab_*", "slab_1", true),
        ("slab_*", "xslab_1", false),
        ("*_1", "joint_vertical_1", true),
        ("*_1", "joint_vertical_11", false),
        ("a*b*c", "aXbYc", true),
        ("a*b*c", "aXcYb", false),
        ("exact", "exact", true),
        ("exact", "exactly", false),
    ] {
        assert_eq!(block_pattern_matches(p, n), hit, "{p} vs {n}");
    }
}

#[test]
fn an_exact_block_key_wins_over_a_pattern() {
    let scene = box_scene("  layer_*: { material: a }\n  layer_2: { material: b }\n").expect("scene");
    let young: Vec<f64> = scene
        .block_materials
        .iter()
        .map(|m| match m {
            crate::material::BlockMaterial::Solid(crate::material::SolidParams::Elastic(p)) => p.young,
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(young, [1.0e7, 2.0e7, 1.0e7]);
}

#[test]
fn a_block_matched_by_two_patterns_is_an_error_naming_both() {
    let err = message(box_scene(
        "  layer_*: { material: a }\n  '*_2': { material: b }\n",
    ));
    assert!(
        err.contains("blocks.*_2") && err.contains("blocks.layer_*") && err.contains("'layer_2'"),
        "{err}"
    );
}

#[test]
fn a_pattern_matching_no_block_is_an_error() {
    let err = message(box_scene(
        "  layer_*: { material: a }\n  slab_*: { material: b }\n",
    ));
    assert!(
        err.contains("blocks.slab_*") && err.contains("matches no block"),
        "{err}"
    );
    let err = message(box_scene(
        "  layer_1: { material: a }\n  layer_[23]: { material: b }\n",
    ));
    assert!(err.contains("layer_[23]"), "{err}");
}

#[test]
fn a_cfrd_scene_without_stages_runs_the_generated_schedule() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/inputs/scenes/seed_coarse_gp_interface.yaml"
    );
    let scene = Scene::load(Path::new(path)).expect("seed scene");
    let names: Vec<&str> = scene.stages.iter().map(|s| s.name.as_str()).collect();
    let spec = scene.file.mesh.cfrd.clone().expect("cfrd");
    assert_eq!(
        names.iter().filter(|n| n.starts_with("fill_")).count(),
        spec.fill_layers
    );
    assert_eq!(scene.file.stages.len(), scene.stages.len());
    // every block is placed once, the slab stages place their interface and joints
    let mut placed: Vec<u32> = scene.stages.iter().flat_map(|s| s.activate.clone()).collect();
    placed.sort_unstable();
    assert_eq!(placed, (0..scene.mesh.blocks.len() as u32).collect::<Vec<_>>());
    let slab_3 = &scene.stages[names.iter().position(|n| *n == "slab_3").expect("slab_3")];
    let placed_3: Vec<&str> = slab_3
        .activate
        .iter()
        .map(|&b| scene.mesh.blocks[b as usize].name.as_str())
        .collect();
    assert!(
        placed_3.contains(&"interface_3") && placed_3.contains(&"joint_vertical_3"),
        "{placed_3:?}"
    );
    // gravity everywhere, water on the slab only in the impoundment stages, up to 2840 m
    let mut last_level = None;
    for st in &scene.stages {
        assert!(matches!(st.terms[0], Term::Gravity { .. }), "{}", st.name);
        let water: Vec<f64> = st
            .terms
            .iter()
            .filter_map(|t| match t {
                Term::Hydrostatic { faces, level, .. } if faces == "slab_upstream" => Some(*level),
                _ => None,
            })
            .collect();
        assert_eq!(
            water.len(),
            usize::from(st.name.starts_with("impound_")),
            "{}",
            st.name
        );
        if let Some(&l) = water.first() {
            last_level = Some(l);
        }
    }
    assert_eq!(last_level, Some(2840.0));
    // the interface blocks got their orientations from the generator
    let m = spec.upstream_slope;
    let ib = scene.mesh.block_index("interface_1").expect("interface_1") as usize;
    assert_eq!(
        scene.block_interface[ib].expect("interface").orientation,
        [1.0, 0.0, -m]
    );
}

#[test]
fn a_bad_cfrd_value_names_its_yaml_path_in_the_scene_error() {
    let text = "name: t\nunits: SI\nmesh: { cfrd: { fill_layers: 8, panel_width: -3.0 } }\n\
                materials: {}\nblocks: {}\n";
    let err = message(Scene::from_str(text, "t.yaml", Path::new(".")));
    assert!(err.contains("mesh.cfrd.panel_width"), "{err}");
    let text = "name: t\nunits: SI\nmesh: { cfrd: { fill_layer: 8 } }\nmaterials: {}\nblocks: {}\n";
    let err = message(Scene::from_str(text, "t.yaml", Path::new(".")));
    assert!(err.contains("mesh.cfrd") && err.contains("fill_layer"), "{err}");
}

/// The seed scene `file` of `inputs/scenes` with `from` replaced by `to` (which must occur),
/// parsed from the scenes directory.
fn edited_seed_scene(file: &str, from: &str, to: &str) -> Result<Scene, SceneError> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/scenes");
    let text = std::fs::read_to_string(dir.join(file)).expect("seed scene");
    let edited = text.replace(from, to);
    assert_ne!(edited, text, "{file} no longer holds '{from}'");
    Scene::from_str(&edited, "t.yaml", &dir)
}

#[test]
fn fill_load_steps_apply_to_the_fill_stages_only() {
    let with = |steps: &str| {
        edited_seed_scene(
            "seed_coarse_hyperbolic.yaml",
            "impoundment_stages: 3 }",
            &format!("impoundment_stages: 3, fill_load_steps: {steps} }}"),
        )
    };
    let scene = with("2").expect("valid scene");
    assert_eq!(scene.file.solver.load_steps, 8);
    for st in &scene.stages {
        let expected = if st.name.starts_with("fill_") { 2 } else { 8 };
        assert_eq!(st.load_steps, expected, "{}", st.name);
    }
    let err = message(with("0"));
    assert!(err.contains("mesh.cfrd.fill_load_steps"), "{err}");
}

#[test]
fn step_growth_applies_to_the_static_stages_only() {
    let with = |growth: &str| {
        edited_seed_scene(
            "seed_coarse_mohr_coulomb_quake.yaml",
            "load_steps: 8,",
            &format!("load_steps: 8, step_growth: {growth},"),
        )
    };
    let scene = with("4").expect("valid scene");
    assert!(scene.stages.iter().any(|st| st.dynamic.is_some()));
    for st in &scene.stages {
        let expected = if st.dynamic.is_some() { 1 } else { 4 };
        assert_eq!(st.step_growth, expected, "{}", st.name);
    }
    for bad in ["0", "65"] {
        let err = message(with(bad));
        assert!(err.contains("solver.step_growth"), "{bad}: {err}");
    }
}

/// A box of three layers of GP rockfill (own STOL `stol`) with the solver section `solver`.
fn gp_box_scene(stol: &str, solver: &str) -> Result<Scene, SceneError> {
    let text = format!(
        "name: t\nunits: SI\nmesh: {{ box: {{ divisions: [1, 1, 3], layers: 3 }} }}\n\
         materials:\n  a: {{ model: rockfill_gp, integration: {{ stol: {stol} }} }}\n\
         blocks:\n  layer_*: {{ material: a }}\nsolver: {solver}\n{FIXED_BASE}"
    );
    Scene::from_str(&text, "t.yaml", Path::new("."))
}

fn gp_stols(scene: &Scene) -> Vec<f64> {
    scene
        .block_materials
        .iter()
        .map(|m| match m {
            crate::material::BlockMaterial::Solid(crate::material::SolidParams::RockfillGp(p)) => {
                p.integration.stol
            }
            other => panic!("{other:?}"),
        })
        .collect()
}

#[test]
fn the_gp_substepping_tolerance_is_capped_at_a_multiple_of_the_newton_tolerance() {
    // off by default: each material's own STOL
    let own = gp_box_scene("1.0e-4", "{ newton_tol: 1.0e-5 }").expect("scene");
    assert_eq!(gp_stols(&own), [1.0e-4; 3]);
    // the fine seed scenes' remedy: STOL 1e-4 with newton_tol 1e-5 and R = 0.1 integrate at 1e-6
    let capped = gp_box_scene("1.0e-4", "{ newton_tol: 1.0e-5, integration_tol_ratio: 0.1 }").expect("scene");
    assert_eq!(gp_stols(&capped), [0.1 * 1.0e-5; 3]);
    // a tolerance already below the cap is kept
    let tight = gp_box_scene("1.0e-7", "{ newton_tol: 1.0e-5, integration_tol_ratio: 0.1 }").expect("scene");
    assert_eq!(gp_stols(&tight), [1.0e-7; 3]);
}

#[test]
fn the_command_line_cap_tightens_without_changing_the_scene_hash() {
    let mut scene = gp_box_scene("1.0e-4", "{ newton_tol: 1.0e-5 }").expect("scene");
    let hash = scene.hash.clone();
    scene.cap_integration_tol(0.1).expect("valid ratio");
    // the same value as the scene key gives, bit for bit
    assert_eq!(gp_stols(&scene), [0.1 * 1.0e-5; 3]);
    assert_eq!(scene.file.solver.integration_tol_ratio, 0.1);
    assert_eq!(scene.hash, hash, "a restart must accept the capped run");
    // a looser ratio does not undo a tighter one
    scene.cap_integration_tol(0.5).expect("valid ratio");
    assert_eq!(gp_stols(&scene), [0.1 * 1.0e-5; 3]);
    let err = scene
        .cap_integration_tol(2.0)
        .expect_err("out of range")
        .to_string();
    assert!(err.contains("--integration-tol-ratio"), "{err}");
}

#[test]
fn a_bad_integration_tolerance_ratio_names_its_yaml_path() {
    for bad in ["-0.1", "2.0", ".nan", "1.0e-9"] {
        let err = message(gp_box_scene(
            "1.0e-4",
            &format!("{{ newton_tol: 1.0e-5, integration_tol_ratio: {bad} }}"),
        ));
        assert!(err.contains("solver.integration_tol_ratio"), "{bad}: {err}");
    }
}

/// A box of three layers, one material, with `extra` appended (boundary, loads, stages).
fn layered_box(extra: &str) -> Result<Scene, SceneError> {
    let text = format!(
        "name: t\nunits: SI\nmesh: {{ box: {{ divisions: [1, 1, 3], layers: 3 }} }}\n\
         materials:\n  a: {{ model: elastic, young: 1.0e7, poisson: 0.3, density: 2000.0 }}\n\
         blocks:\n  layer_*: {{ material: a }}\n{extra}"
    );
    Scene::from_str(&text, "t.yaml", Path::new("."))
}

#[test]
fn a_body_free_to_move_rigidly_is_refused_naming_the_free_motions() {
    let err = message(layered_box("boundary: []\n"));
    assert!(
        err.contains("t.yaml: boundary:")
            && err.contains("not restrained")
            && err.contains("every translation"),
        "{err}"
    );
    let err = message(layered_box("boundary: [{ set: zmin, fix: [z] }]\n"));
    for free in [
        "translation along x",
        "translation along y",
        "rotation about an axis along z",
    ] {
        assert!(err.contains(free), "{free}: {err}");
    }
    assert!(
        !err.contains("along z,") && !err.contains("axis along x"),
        "{err}"
    );
    layered_box(FIXED_BASE).expect("held by its base");
}

#[test]
fn a_stage_is_checked_on_its_placed_elements_only() {
    let stages =
        "stages:\n  - { name: one, activate: [layer_1] }\n  - { name: two, activate: [layer_2, layer_3] }\n";
    layered_box(&format!("{FIXED_BASE}{stages}")).expect("every stage held by the base");
    let top_first =
        "stages:\n  - { name: top, activate: [layer_3] }\n  - { name: rest, activate: [layer_1, layer_2] }\n";
    let err = message(layered_box(&format!("{FIXED_BASE}{top_first}")));
    assert!(
        err.contains("stage 1 'top'") && err.contains("block 'layer_3'"),
        "{err}"
    );
    // a body not connected to the restrained one is free even with the other held
    let apart = "stages:\n  - { name: one, activate: [layer_1] }\n  - { name: gap, activate: [layer_3] }\n";
    let err = message(layered_box(&format!("{FIXED_BASE}{apart}")));
    assert!(
        err.contains("stage 2 'gap'") && err.contains("every translation"),
        "{err}"
    );
}

#[test]
fn every_load_and_stage_value_is_range_checked_with_its_path_and_unit() {
    let cases = [
        ("loads: { hydrostatic: [{ faces: zmax, level: .nan }] }\n", "loads.hydrostatic[0].level", "m"),
        ("loads: { hydrostatic: [{ faces: zmax, level: -.inf }] }\n", "loads.hydrostatic[0].level", "m"),
        ("loads: { gravity: { g: [0.0, 0.0, 1.0e300] } }\n", "loads.gravity.g", "1e300"),
        ("loads: { pressure: [{ faces: zmax, value: .inf }] }\n", "loads.pressure[0].value", "Pa"),
        (
            "stages: [{ name: s, activate: [layer_1, layer_2, layer_3], loads: { pressure: [{ faces: zmax, value: .nan }] } }]\n",
            "stages[0].loads.pressure[0].value",
            "Pa",
        ),
        (
            "stages: [{ name: s, activate: [layer_1, layer_2, layer_3], loads: { hydrostatic: [{ faces: zmax, level: .inf }] } }]\n",
            "stages[0].loads.hydrostatic[0].level",
            "m",
        ),
        (
            "stages: [{ name: s, activate: [layer_1, layer_2, layer_3], load_steps: 4294967295 }]\n",
            "stages[0].load_steps",
            "1000000",
        ),
        ("solver: { max_cutbacks: 4000000000 }\n", "solver.max_cutbacks", "60"),
        ("solver: { newton_max_iterations: 0 }\n", "solver.newton_max_iterations", "at least 1"),
    ];
    for (extra, path, unit) in cases {
        let err = message(layered_box(&format!("{FIXED_BASE}{extra}")));
        assert!(err.contains(path) && err.contains(unit), "{extra}: {err}");
    }
    let err = message(layered_box(
        "boundary: [{ set: zmin, fix: [x, y, z], value: [0.0, .nan, 0.0] }]\n",
    ));
    assert!(
        err.contains("boundary[0].value[1]") && err.contains(" m "),
        "{err}"
    );
}

#[test]
fn generator_counts_are_bounded_before_memory_is_reserved() {
    let text = "name: t\nunits: SI\nmesh: { cfrd: { fill_layers: 8, impoundment_stages: 4294967296 } }\n\
                materials: {}\nblocks: {}\n";
    let err = message(Scene::from_str(text, "t.yaml", Path::new(".")));
    assert!(
        err.contains("mesh.cfrd.impoundment_stages") && err.contains("4294967296"),
        "{err}"
    );
    let text = "name: t\nunits: SI\nmesh: { cfrd: { fill_layers: 8, elements_per_panel: 100000000 } }\n\
                materials: {}\nblocks: {}\n";
    let err = message(Scene::from_str(text, "t.yaml", Path::new(".")));
    assert!(
        err.contains("mesh.cfrd.fill_layers") && err.contains("limit"),
        "{err}"
    );
    let text = "name: t\nunits: SI\nmesh: { box: { divisions: [100000, 100000, 100000] } }\n\
                materials: {}\nblocks: {}\n";
    let err = message(Scene::from_str(text, "t.yaml", Path::new(".")));
    assert!(err.contains("divisions") && err.contains("limit"), "{err}");
}

#[test]
fn a_block_or_material_named_twice_is_an_error_naming_both_lines() {
    let err = message(layered_box(&format!(
        "  layer_*: {{ material: a }}\n{FIXED_BASE}"
    )));
    assert!(
        err.contains("blocks") && err.contains("'layer_*'") && err.contains("lines 7 and 8"),
        "{err}"
    );
    let text = "name: t\nunits: SI\nmesh: { box: {} }\nmaterials:\n  a: { model: elastic, young: 1.0e7, poisson: 0.3, density: 2000.0 }\n  \
                a: { model: elastic, young: 2.0e7, poisson: 0.3, density: 2000.0 }\nblocks: { layer_1: { material: a } }\n";
    let err = message(Scene::from_str(text, "t.yaml", Path::new(".")));
    assert!(
        err.contains("materials") && err.contains("lines 5 and 6"),
        "{err}"
    );
}

#[test]
fn a_byte_order_mark_and_deep_nesting_are_handled_before_parsing() {
    let text = format!(
        "{}name: t\nunits: SI\nmesh: {{ box: {{}} }}\nmaterials:\n  a: {{ model: elastic, young: 1.0e7, poisson: 0.3, density: 2000.0 }}\n\
         blocks: {{ layer_1: {{ material: a }} }}\n{FIXED_BASE}",
        '\u{feff}'
    );
    Scene::from_str(&text, "bom.yaml", Path::new(".")).expect("a BOM is dropped");
    let text = format!("name: {}\n", "[".repeat(100_000));
    let t = std::time::Instant::now();
    let err = message(Scene::from_str(&text, "deep.yaml", Path::new(".")));
    assert!(t.elapsed().as_secs_f64() < 1.0, "{:?}", t.elapsed());
    assert!(err.contains("deep.yaml") && err.contains("nested"), "{err}");
}

#[test]
fn a_device_is_not_read_as_a_scene() {
    let err = message(Scene::load(Path::new("/dev/zero")));
    assert!(
        err.contains("/dev/zero") && err.contains("not a regular file"),
        "{err}"
    );
}

#[test]
fn incompatible_modes_are_taken_for_elastic_blocks_and_refused_elsewhere_naming_the_block() {
    use crate::element::hex8_modes::SolidElement;
    let scene =
        box_scene("  layer_1: { material: a, element: incompatible_modes }\n  layer_*: { material: b }\n")
            .expect("scene");
    assert_eq!(
        scene.block_element,
        [
            SolidElement::IncompatibleModes,
            SolidElement::Trilinear,
            SolidElement::Trilinear
        ]
    );
    let text = "name: t\nunits: SI\nmesh: { box: { divisions: [1, 1, 1], layers: 1 } }\n\
                materials:\n  fill: { model: rockfill_gp }\n\
                blocks:\n  layer_1: { material: fill, element: incompatible_modes }\n"
        .to_string()
        + FIXED_BASE;
    let err = message(Scene::from_str(&text, "t.yaml", Path::new(".")));
    assert!(
        err.contains("blocks.layer_1.element") && err.contains("needs an elastic material"),
        "{err}"
    );
    let err = message(box_scene("  layer_*: { material: a, element: quadratic }\n"));
    assert!(err.contains("quadratic"), "{err}");
}
