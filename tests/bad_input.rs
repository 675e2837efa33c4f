//! Issue 2, acceptance 4: bad input gives a clear message naming the place, exit code 2, no
//! panic and no hang, under `mpirun -n 2`.

mod common;
use common::*;

const GOOD: &str = "name: t
units: SI
mesh:
  box: { size: [1.0, 1.0, 2.0], divisions: [1, 1, 2] }
materials:
  soil: { model: elastic, young: 5.0e7, poisson: 0.3, density: 2000.0 }
blocks:
  layer_1: { material: soil }
boundary:
  - { set: zmin, fix: [x, y, z] }
loads:
  gravity: { g: [0.0, 0.0, -9.81] }
";

/// A hex element of the given node order in a Gmsh 2.2 file with physical groups.
fn msh(nodes: [u32; 8]) -> String {
    let n: Vec<String> = nodes.iter().map(|v| v.to_string()).collect();
    format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"base\"\n3 2 \"core\"\n$EndPhysicalNames\n\
         $Nodes\n8\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n$EndNodes\n\
         $Elements\n2\n1 3 2 1 1 1 2 3 4\n2 5 2 2 1 {}\n$EndElements\n",
        n.join(" ")
    )
}

/// One bad-input case: name, scene text, extra files (name, body), text the message must contain.
type Case = (&'static str, String, Vec<(&'static str, String)>, &'static str);

fn cases() -> Vec<Case> {
    let gmsh_scene = |file: &str, block: &str| {
        format!(
            "name: g\nunits: SI\nmesh: {{ file: {file} }}\nmaterials:\n  soil: {{ model: elastic, young: 5.0e7, poisson: 0.3, density: 2000.0 }}\n\
             blocks:\n  {block}: {{ material: soil }}\nboundary:\n  - {{ set: base, fix: [x, y, z] }}\n"
        )
    };
    vec![
        (
            "malformed yaml",
            "name: t\n  units: [SI\nmesh: {\n".to_string(),
            vec![],
            "line",
        ),
        (
            "unknown key",
            GOOD.replace("loads:", "lods:"),
            vec![],
            "unknown field `lods`",
        ),
        (
            "unknown material key",
            GOOD.replace("poisson: 0.3", "poisson: 0.3, youngs: 1.0"),
            vec![],
            "materials.soil",
        ),
        (
            "missing mesh",
            gmsh_scene("nowhere.msh", "core"),
            vec![],
            "nowhere.msh",
        ),
        (
            "inverted element",
            gmsh_scene("inverted.msh", "core"),
            vec![("inverted.msh", msh([5, 6, 7, 8, 1, 2, 3, 4]))],
            "element 2",
        ),
        (
            "unknown physical group",
            gmsh_scene("good.msh", "dam_core"),
            vec![("good.msh", msh([1, 2, 3, 4, 5, 6, 7, 8]))],
            "blocks.dam_core",
        ),
        (
            "wrong unit system",
            GOOD.replace("units: SI", "units: kPa"),
            vec![],
            "units",
        ),
        (
            "modulus in MPa",
            GOOD.replace("young: 5.0e7", "young: 50.0"),
            vec![],
            "materials.soil.young",
        ),
        (
            "negative modulus",
            GOOD.replace("young: 5.0e7", "young: -5.0e7"),
            vec![],
            "materials.soil.young",
        ),
        (
            "unknown set",
            GOOD.replace("set: zmin", "set: bottom"),
            vec![],
            "boundary[0].set",
        ),
        (
            "bad integration tolerance ratio",
            GOOD.replace("loads:", "solver: { integration_tol_ratio: 2.0 }\nloads:"),
            vec![],
            "solver.integration_tol_ratio",
        ),
        (
            "bad petsc option",
            GOOD.replace(
                "loads:",
                "solver: { petsc_options: '-ksp_type nonsense' }\nloads:",
            ),
            vec![],
            "PETSc",
        ),
    ]
}

#[test]
fn bad_input_exits_2_with_a_clear_message_at_two_ranks() {
    for (case, scene, files, expect) in cases() {
        let dir = tempdir();
        std::fs::write(dir.path().join("scene.yaml"), &scene).unwrap();
        for (name, body) in &files {
            std::fs::write(dir.path().join(name), body).unwrap();
        }
        for args in [
            vec!["run", "scene.yaml", "-o", "out"],
            vec!["check", "scene.yaml"],
        ] {
            if case == "bad petsc option" && args[0] == "check" {
                continue; // PETSc options are checked when the solver is set up
            }
            let t = std::time::Instant::now();
            let o = cfrd_mpi(2, dir.path(), &args);
            let msg = text(&o);
            assert_eq!(
                o.status.code(),
                Some(2),
                "{case} ({}): exit {:?}\n{msg}",
                args[0],
                o.status.code()
            );
            assert!(
                msg.contains(expect),
                "{case} ({}): message lacks '{expect}':\n{msg}",
                args[0]
            );
            assert!(msg.contains("error:"), "{case}: no error line:\n{msg}");
            assert!(!msg.contains("panicked"), "{case}: panic:\n{msg}");
            assert!(t.elapsed().as_secs() < 60, "{case}: took {:?}", t.elapsed());
            println!(
                "{case} ({}): {}",
                args[0],
                msg.lines().find(|l| l.contains("error:")).unwrap_or("")
            );
        }
        assert!(
            !dir.path().join("out/results.h5").exists(),
            "{case}: results written despite the error"
        );
    }
}

/// The command line's `--integration-tol-ratio` is checked like the scene key, on both ranks.
#[test]
fn a_bad_integration_tolerance_ratio_on_the_command_line_exits_2() {
    let dir = tempdir();
    std::fs::write(dir.path().join("scene.yaml"), GOOD).unwrap();
    let o = cfrd_mpi(
        2,
        dir.path(),
        &[
            "run",
            "scene.yaml",
            "-o",
            "out",
            "--integration-tol-ratio",
            "1.0e-9",
        ],
    );
    let msg = text(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("--integration-tol-ratio") && msg.contains("1e-12"),
        "{msg}"
    );
    assert!(!msg.contains("panicked"), "{msg}");
    assert!(!dir.path().join("out/results.h5").exists());
}

#[test]
fn check_accepts_a_good_scene_and_schema_is_json() {
    let dir = tempdir();
    std::fs::write(dir.path().join("scene.yaml"), GOOD).unwrap();
    let o = cfrd(dir.path(), &["check", "scene.yaml"]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("ok (27 nodes") || text(&o).contains("ok (12 nodes"),
        "{}",
        text(&o)
    );
    let o = cfrd(dir.path(), &["schema"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("schema is JSON");
    assert!(v["properties"]["materials"].is_object(), "schema lacks materials");
    assert!(v["required"].as_array().unwrap().iter().any(|r| r == "mesh"));
}

#[test]
fn every_example_scene_passes_check() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "yaml") {
            let o = cfrd(&dir, &["check", path.to_str().unwrap()]);
            assert!(o.status.success(), "{}: {}", path.display(), text(&o));
            n += 1;
        }
    }
    assert!(n >= 4, "expected the example scenes in {}", dir.display());
}
