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

/// A mesh file of `inputs/meshes` with the (unique) line `old` replaced by `new`.
fn mesh_with(file: &str, old: &str, new: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("inputs/meshes")
        .join(file);
    let text = std::fs::read_to_string(path).unwrap();
    assert_eq!(
        text.lines().filter(|l| l.trim() == old).count(),
        1,
        "{file}: '{old}'"
    );
    let lines: Vec<&str> = text
        .lines()
        .map(|l| if l.trim() == old { new } else { l })
        .collect();
    lines.join("\n")
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
            "physical-tag count 2^64-1 of an MSH 4.1 entity",
            gmsh_scene("tags.msh", "left"),
            vec![(
                "tags.msh",
                mesh_with(
                    "two_hex_v41.msh",
                    "2 1 0 0 2 1 1 1 7 0",
                    "2 1 0 0 2 1 1 18446744073709551615 7 0",
                ),
            )],
            "tags.msh:22",
        ),
        (
            "MSH 4.1 node block of 10^12 nodes",
            gmsh_scene("nodes.msh", "left"),
            vec![("nodes.msh", mesh_with("two_hex_v41.msh", "3 1 0 12", "3 1 0 1000000000000"))],
            "node block header: nodes: the count 1000000000000",
        ),
        (
            "MSH 4.1 $Nodes header of 10^12 nodes",
            gmsh_scene("header.msh", "left"),
            vec![("header.msh", mesh_with("two_hex_v41.msh", "1 12 1 12", "1 1000000000000 1 12"))],
            "$Nodes header: nodes: the count 1000000000000",
        ),
        (
            "MSH 2.2 $Elements count of 10^12",
            gmsh_scene("elements.msh", "left"),
            vec![("elements.msh", mesh_with("two_hex_v22.msh", "9", "1000000000000"))],
            "$Elements count: the count 1000000000000",
        ),
        (
            "MSH 2.2 $Nodes count of 10^12",
            gmsh_scene("nodes22.msh", "left"),
            vec![("nodes22.msh", mesh_with("two_hex_v22.msh", "12", "1000000000000"))],
            "$Nodes count: the count 1000000000000",
        ),
        (
            "infinite coordinate",
            gmsh_scene("inf.msh", "core"),
            vec![("inf.msh", msh([1, 2, 3, 4, 5, 6, 7, 8]).replace("5 0 0 1\n", "5 0 0 inf\n"))],
            "node 5: coordinate z = 'inf'",
        ),
        (
            "negative node id",
            gmsh_scene("neg.msh", "core"),
            vec![("neg.msh", msh([1, 2, 3, 4, 5, 6, 7, 8]).replace("5 6 7 8\n$End", "5 6 7 -3\n$End"))],
            "node id -3",
        ),
        (
            "mesh file is a device",
            gmsh_scene("/dev/zero", "core"),
            vec![],
            "/dev/zero: cannot read mesh file: not a regular file",
        ),
        (
            "impoundment stages 2^32",
            "name: c\nunits: SI\nmesh: { cfrd: { fill_layers: 8, impoundment_stages: 4294967296 } }\n\
             materials: {}\nblocks: {}\n"
                .to_string(),
            vec![],
            "mesh.cfrd.impoundment_stages: 4294967296",
        ),
        (
            "block named twice",
            GOOD.replace("  layer_1: { material: soil }\n", "  layer_1: { material: soil }\n  layer_1: { material: rock }\n"),
            vec![],
            "blocks: the key 'layer_1' is given twice, on lines 8 and 9",
        ),
        (
            "material named twice",
            GOOD.replace("blocks:", "  soil: { model: elastic, young: 5.0e9, poisson: 0.3, density: 2000.0 }\nblocks:"),
            vec![],
            "materials: the key 'soil' is given twice, on lines 6 and 7",
        ),
        (
            "water level nan",
            GOOD.replace("loads:\n", "loads:\n  hydrostatic: [{ faces: zmax, level: .nan }]\n"),
            vec![],
            "loads.hydrostatic[0].level: NaN m",
        ),
        (
            "stage pressure inf",
            GOOD.replace(
                "loads:",
                "stages: [{ name: s, activate: [layer_1], loads: { pressure: [{ faces: zmax, value: -.inf }] } }]\nloads:",
            ),
            vec![],
            "stages[0].loads.pressure[0].value: -inf Pa",
        ),
        (
            "gravity 1e300",
            GOOD.replace("g: [0.0, 0.0, -9.81]", "g: [0.0, 0.0, 1.0e300]"),
            vec![],
            "[0.0, 0.0, 1e300] m/s²",
        ),
        (
            "gravity as a scalar",
            GOOD.replace("gravity: { g: [0.0, 0.0, -9.81] }", "gravity: 9.81"),
            vec![],
            "loads.gravity: a number (9.81) is not a gravity vector: write it as `gravity: { g: [gx, gy, gz] }`",
        ),
        (
            "gravity g as a scalar",
            GOOD.replace("g: [0.0, 0.0, -9.81]", "g: 9.81"),
            vec![],
            "e.g. `gravity: { g: [0.0, 0.0, -9.81] }`",
        ),
        (
            "no boundary",
            GOOD.replace("  - { set: zmin, fix: [x, y, z] }\n", "").replace("boundary:", "boundary: []"),
            vec![],
            "not restrained against rigid-body motion: every translation and rotation",
        ),
        (
            "base on rollers",
            GOOD.replace("fix: [x, y, z]", "fix: [z]"),
            vec![],
            "translation along x, translation along y, rotation about an axis along z free",
        ),
        (
            "deep nesting",
            format!("name: {}\n", "[".repeat(100_000)),
            vec![],
            "brackets nested more than 64 deep",
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
        assert_exits_2(case, &scene, &files, expect);
    }
}

/// `cfrd run` and `cfrd check` of `scene` (with the extra `files`) on 2 ranks exit 2 within a
/// minute, with an error line holding `expect`, no panic and no results.
fn assert_exits_2(case: &str, scene: &str, files: &[(&str, String)], expect: &str) {
    let dir = tempdir();
    std::fs::write(dir.path().join("scene.yaml"), scene).unwrap();
    for (name, body) in files {
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

/// [`GOOD`] placed in a first stage and shaken in a second, `shake`, with the stage keys
/// `keys` (`dynamic: {...}` among them).
fn quake_scene(keys: &str) -> String {
    format!("{GOOD}stages:\n  - {{ name: place, activate: [layer_1] }}\n  - {{ name: shake, {keys} }}\n")
}

/// A record of 0.03 s at Δt = 0.01 s (`r.csv`).
fn short_record() -> Vec<(&'static str, String)> {
    vec![(
        "r.csv",
        "t,a_x,a_y,a_z\n0,0,0,0\n0.01,0.1,0,0\n0.02,0,0,0\n0.03,0,0,0\n".into(),
    )]
}

/// Issue 56: `dt: 0.21` over `duration: 0.3` ran one step of 0.3 s; a `dt` that does not
/// divide the duration is now refused naming dt, the duration and the nearest dt that does
/// (here 0.015 s, two steps), also when dt is the record's sample interval.
#[test]
fn a_dt_that_does_not_divide_the_duration_exits_2_naming_the_nearest_that_does() {
    assert_exits_2(
        "dt 0.021 over 0.03 s",
        &quake_scene("dynamic: { record: r.csv, dt: 0.021 }"),
        &short_record(),
        "stages[1].dynamic.dt: 0.021 s does not divide the duration 0.03 s (1.4286 steps): \
         give `dt: 0.015` (2 steps)",
    );
    assert_exits_2(
        "the record's dt over 0.025 s",
        &quake_scene("dynamic: { record: r.csv, duration: 0.025 }"),
        &short_record(),
        "stages[1].dynamic.dt: the record's sample interval 0.01 s (`dt` not given) does not \
         divide the duration 0.025 s",
    );
}

/// Issue 56: `load_steps` on a dynamic stage was ignored; now it is refused naming the key.
#[test]
fn load_steps_on_a_dynamic_stage_exits_2() {
    assert_exits_2(
        "load_steps on a dynamic stage",
        &quake_scene("load_steps: 8, dynamic: { record: r.csv }"),
        &short_record(),
        "stages[1].load_steps: a dynamic stage steps in time: its 3 steps are \
         `dynamic.duration` over `dynamic.dt`",
    );
}

/// Issue 56: a damping ratio with neither anchor was refused with "…not both"; now the message
/// asks for one of them.
#[test]
fn a_damping_ratio_without_anchors_exits_2_asking_for_frequencies_or_modes() {
    assert_exits_2(
        "damping ratio alone",
        &quake_scene("dynamic: { record: r.csv, damping: { ratio: 0.05 } }"),
        &short_record(),
        "stages[1].dynamic.damping: ratio 0.05 needs its two anchors: give one of \
         `frequencies: [f1, f2]` (Hz) or `modes: [i, j]`",
    );
}

/// A PEER AT2 component of `npts` values of 0.01 g at `dt` (s, as the header writes it).
fn at2(dt: &str, npts: usize) -> String {
    let values = vec![".1000000E-01"; npts].join(" ");
    format!(
        "PEER NGA STRONG MOTION DATABASE RECORD\nTEST\nACCELERATION TIME SERIES IN UNITS OF G\n\
         NPTS= {npts}, DT= {dt} SEC\n{values}\n"
    )
}

/// AT2 components are checked like the CSV: a time step other than the first component's, a
/// file not in g, a record without a component and an unknown axis exit 2 naming the key (and
/// the file).
#[test]
fn bad_at2_components_exit_2_naming_the_file_and_the_key() {
    let cases = [
        (
            "AT2 components of different time steps",
            "dynamic: { record: { x: x.AT2, z: z.AT2 } }",
            "stages[1].dynamic.record.z: z.AT2: DT = 0.02 s, but record.x (x.AT2) has DT = 0.01 s",
        ),
        (
            "an AT2 component not in g",
            "dynamic: { record: { y: cm.AT2 } }",
            "stages[1].dynamic.record.y: cm.AT2:3: expected acceleration in UNITS OF G",
        ),
        (
            "an AT2 record without a component",
            "dynamic: { record: {} }",
            "stages[1].dynamic.record: no component file given",
        ),
        (
            "an AT2 record with an unknown axis",
            "dynamic: { record: { w: x.AT2 } }",
            "stages[1].dynamic.record: unknown field `w`, expected one of `x`, `y`, `z`",
        ),
    ];
    let files = vec![
        ("x.AT2", at2(".0100", 4)),
        ("z.AT2", at2(".0200", 4)),
        ("cm.AT2", at2(".0100", 4).replace("UNITS OF G", "UNITS OF CM/S/S")),
    ];
    for (case, keys, expect) in cases {
        assert_exits_2(case, &quake_scene(keys), &files, expect);
    }
}

/// A mesh file that is missing is named as the scene wrote it and as resolved against the
/// scene's folder (not the working directory), absolute, so the user sees where it was looked
/// for.
#[test]
fn a_missing_mesh_is_named_as_written_and_as_resolved_against_the_scene_folder() {
    let dir = tempdir();
    std::fs::create_dir_all(dir.path().join("dams")).unwrap();
    let scene = GOOD.replace(
        "box: { size: [1.0, 1.0, 2.0], divisions: [1, 1, 2] }",
        "{ file: meshes/dam.msh }",
    );
    assert!(scene.contains("meshes/dam.msh"));
    std::fs::write(dir.path().join("dams/scene.yaml"), scene).unwrap();
    let resolved = dir.path().join("dams/meshes/dam.msh");
    let expect = format!(
        "dams/scene.yaml: mesh: file 'meshes/dam.msh' (as written; a relative path is taken from \
         the scene's folder) is {}: cannot read mesh file: No such file or directory",
        resolved.display()
    );
    for args in [["check", "dams/scene.yaml"], ["run", "dams/scene.yaml"]] {
        let o = cfrd_mpi(2, dir.path(), &args);
        let msg = text(&o);
        println!("{}: {}", args[0], msg.lines().next().unwrap_or(""));
        assert_eq!(o.status.code(), Some(2), "{msg}");
        assert!(
            msg.contains(&expect),
            "{}: message lacks\n{expect}\n{msg}",
            args[0]
        );
        assert!(!msg.contains("panicked"), "{msg}");
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

/// `--checkpoint-every` takes a count ≥ 1 and step checkpoints only: exit 2 naming the flag on
/// both ranks, nothing written.
#[test]
fn a_bad_checkpoint_interval_on_the_command_line_exits_2() {
    let dir = tempdir();
    std::fs::write(dir.path().join("scene.yaml"), GOOD).unwrap();
    for extra in [
        &["--checkpoint-every", "0"][..],
        &["--checkpoint-every", "5", "--checkpoint", "none"],
    ] {
        let mut args = vec!["run", "scene.yaml", "-o", "out"];
        args.extend(extra);
        let o = cfrd_mpi(2, dir.path(), &args);
        let msg = text(&o);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {msg}");
        assert!(msg.contains("--checkpoint-every"), "{msg}");
        assert!(!msg.contains("panicked"), "{msg}");
        assert!(!dir.path().join("out/results.h5").exists());
    }
}

/// `cfrd compare --tolerance` takes a finite number ≥ 0 only.
#[test]
fn a_compare_tolerance_that_is_not_a_finite_non_negative_number_exits_2() {
    let dir = tempdir();
    for bad in ["nan", "-1e-8", "inf"] {
        let o = cfrd(dir.path(), &["compare", "a", "b", &format!("--tolerance={bad}")]);
        let msg = text(&o);
        assert_eq!(o.status.code(), Some(2), "{bad}: {msg}");
        assert!(
            msg.contains("--tolerance") && msg.contains("finite"),
            "{bad}: {msg}"
        );
    }
}

/// Negative numbers after a PETSc option are its value, not options of cfrd's; an option that
/// no solver object read is named in a warning, but not `-log_view`, which PETSc reads when it
/// finalizes.
#[test]
fn negative_petsc_option_values_reach_petsc() {
    let dir = tempdir();
    std::fs::write(dir.path().join("scene.yaml"), GOOD).unwrap();
    for (out, value) in [("a", "-5"), ("b", "-1e-8")] {
        let o = cfrd(
            dir.path(),
            &["run", "scene.yaml", "-o", out, "-q", "-ksp_rtol", value],
        );
        assert!(o.status.success(), "-ksp_rtol {value}: {}", text(&o));
        assert!(!text(&o).contains("not used"), "{}", text(&o));
    }
    // a misspelled option is named at the end of the run (PETSc's unused-option record)
    let o = cfrd(
        dir.path(),
        &["run", "scene.yaml", "-o", "c", "-q", "-ksp_rtoll", "1e-8"],
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("warning: PETSc option(s) set but not used by any solver object: -ksp_rtoll 1e-8"),
        "{}",
        text(&o)
    );
    // PETSc reads -log_view when it finalizes: not named, and its performance log is printed
    let o = cfrd(dir.path(), &["run", "scene.yaml", "-o", "d", "-q", "-log_view"]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(!text(&o).contains("not used"), "{}", text(&o));
    assert!(text(&o).contains("PETSc Performance Summary"), "{}", text(&o));
}

/// A directory given to `--restart` is one clear line, not the MPI-IO error stack.
#[test]
fn a_directory_given_to_restart_exits_2_with_one_line() {
    let dir = tempdir();
    std::fs::write(dir.path().join("scene.yaml"), GOOD).unwrap();
    std::fs::create_dir(dir.path().join("ckpt")).unwrap();
    let o = cfrd(
        dir.path(),
        &["run", "scene.yaml", "-o", "out", "--restart", "ckpt"],
    );
    let msg = text(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("error: restart from ckpt: not a checkpoint file (a directory)"),
        "{msg}"
    );
    assert_eq!(msg.lines().count(), 1, "{msg}");
}

/// A run does not write over another run's files without `--overwrite`; with it, the old
/// checkpoint goes first; temporary files of killed runs are named and removed.
#[test]
fn an_output_directory_of_another_run_is_refused_without_overwrite() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("scene.yaml"), GOOD).unwrap();
    let o = cfrd_mpi(2, d, &["run", "scene.yaml", "-o", "out", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let before = std::fs::read(d.join("out/results.h5")).unwrap();
    let o = cfrd_mpi(2, d, &["run", "scene.yaml", "-o", "out", "-q"]);
    let msg = text(&o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(
        msg.contains("results.h5, summary.json") && msg.contains("--overwrite"),
        "{msg}"
    );
    assert_eq!(std::fs::read(d.join("out/results.h5")).unwrap(), before);
    // a checkpoint of another scene and a killed run's temporary file
    std::fs::write(d.join("out/checkpoint.h5"), b"another scene").unwrap();
    let stale = format!(".results.h5.partial-{}", u32::MAX - 1);
    std::fs::write(d.join("out").join(&stale), b"").unwrap();
    let o = cfrd_mpi(2, d, &["run", "scene.yaml", "-o", "out", "--overwrite"]);
    let msg = text(&o);
    assert!(o.status.success(), "{msg}");
    assert!(msg.contains(&stale) && msg.contains("checkpoint.h5"), "{msg}");
    assert!(!d.join("out/checkpoint.h5").exists() && !d.join("out").join(&stale).exists());
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
    // a byte order mark at the start is dropped
    std::fs::write(dir.path().join("bom.yaml"), format!("\u{feff}{GOOD}")).unwrap();
    let o = cfrd(dir.path(), &["check", "bom.yaml"]);
    assert!(o.status.success(), "{}", text(&o));
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

/// Runs `cmd` and waits at most 5 s: the test fails (and the processes are killed) if it
/// has not ended by then.
fn within_5_s(mut cmd: std::process::Command, what: &str) -> (Option<i32>, String) {
    use std::process::Stdio;
    let out = tempfile::NamedTempFile::new().expect("temporary file");
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(out.reopen().expect("reopen"))
        .stderr(out.reopen().expect("reopen"))
        .spawn()
        .expect("starts");
    let t0 = std::time::Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if t0.elapsed() > std::time::Duration::from_secs(5) {
            kill_tree(&mut child);
            panic!("{what}: still running after 5 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let code = child.wait().expect("wait").code();
    (code, std::fs::read_to_string(out.path()).unwrap_or_default())
}

/// A FIFO given where cfrd reads a file (scene, mesh, partition, record, `cfrd accel` and
/// `cfrd point` specifications, `cfrd compare` and `cfrd export` arguments) ends within 5 s
/// with exit code 2 and a message that says it is a FIFO, alone and under `mpirun -n 2`.
#[test]
fn a_fifo_in_place_of_any_input_file_exits_2_within_5_s() {
    let dir = tempdir();
    let d = dir.path();
    let made = std::process::Command::new("mkfifo").arg(d.join("fifo")).status();
    assert!(made.expect("mkfifo").success());
    let mesh = GOOD.replace(
        "  box: { size: [1.0, 1.0, 2.0], divisions: [1, 1, 2] }",
        "  file: fifo",
    );
    std::fs::write(d.join("mesh.yaml"), mesh).unwrap();
    std::fs::write(d.join("partition.yaml"), format!("{GOOD}partition: fifo\n")).unwrap();
    let quake = "stages:\n  - name: quake\n    dynamic: { record: fifo }\n";
    std::fs::write(d.join("record.yaml"), format!("{GOOD}{quake}")).unwrap();
    let cases: [&[&str]; 10] = [
        &["check", "fifo"],
        &["check", "mesh.yaml"],
        &["run", "partition.yaml", "-o", "q"],
        &["check", "record.yaml"],
        &["accel", "fifo", "-o", "a"],
        &["point", "fifo", "-o", "p"],
        &["compare", "fifo", "fifo"],
        &["export", "fifo", "-f", "displacement"],
        &["run", "record.yaml", "-o", "r"],
        &["run", "record.yaml", "-o", "s", "--restart", "fifo"],
    ];
    for args in cases {
        let mut alone = std::process::Command::new(cfrd_bin());
        alone.args(args).current_dir(d);
        let mut two = cfrd::parallel::mpirun_command(2, 60);
        two.arg(cfrd_bin()).args(args).current_dir(d);
        for (how, cmd) in [("alone", alone), ("2 ranks", two)] {
            let what = format!("cfrd {} ({how})", args.join(" "));
            let (code, msg) = within_5_s(cmd, &what);
            assert_eq!(code, Some(2), "{what}: {msg}");
            assert!(msg.contains("FIFO"), "{what}: {msg}");
        }
    }
}

/// A path argument that is not UTF-8 is named with exit code 2, not a panic.
#[test]
fn a_non_utf8_argument_exits_2_naming_it() {
    use std::os::unix::ffi::OsStrExt;
    let dir = tempdir();
    let bad = std::ffi::OsStr::from_bytes(b"d\xffm.yaml");
    for args in [
        vec!["check".as_ref(), bad],
        vec!["run".as_ref(), bad, "-o".as_ref(), "o".as_ref()],
    ] {
        let o = std::process::Command::new(cfrd_bin())
            .args(args)
            .current_dir(dir.path())
            .output()
            .expect("cfrd starts");
        let msg = text(&o);
        assert_eq!(o.status.code(), Some(2), "{msg}");
        assert!(
            msg.contains("argument 2 ('d\u{FFFD}m.yaml') is not valid UTF-8"),
            "{msg}"
        );
        assert!(!msg.contains("panicked"), "{msg}");
    }
}

/// One run per output directory: while another process holds its lock a run exits 2 naming it;
/// of two runs started at once into one `-o`, in 20 trials exactly one runs and the other
/// exits 2 (the lock, or the first run's finished files, refuses it).
#[test]
fn two_runs_into_one_output_directory_never_race() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("scene.yaml"), GOOD).unwrap();
    std::fs::create_dir(d.join("held")).unwrap();
    let mut holder = std::process::Command::new("flock")
        .args(["held/.cfrd.lock", "sleep", "30"])
        .current_dir(d)
        .spawn()
        .expect("flock(1) starts");
    std::thread::sleep(std::time::Duration::from_millis(300));
    let o = cfrd_mpi(2, d, &["run", "scene.yaml", "-o", "held", "-q"]);
    let msg = text(&o);
    kill_tree(&mut holder);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(msg.contains("another cfrd run is writing into it"), "{msg}");
    assert!(!d.join("held/results.h5").exists(), "{msg}");
    for trial in 0..20 {
        let out = format!("race_{trial}");
        let spawn = || {
            std::process::Command::new(cfrd_bin())
                .args(["run", "scene.yaml", "-o", &out, "-q"])
                .current_dir(d)
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .expect("cfrd starts")
        };
        let (a, b) = (spawn(), spawn());
        let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
        let mut codes = [a.status.code(), b.status.code()];
        codes.sort();
        assert_eq!(
            codes,
            [Some(0), Some(2)],
            "trial {trial}: {}\n{}",
            text(&a),
            text(&b)
        );
    }
}

/// `cfrd accel` exits 4 when it cannot write its outputs, and refuses at once (exit 2, naming
/// `dt`) a valid spec whose record would be too long to make in reasonable time.
#[test]
fn cfrd_accel_exits_4_when_it_cannot_write_and_2_for_a_record_too_long() {
    let dir = tempdir();
    let d = dir.path();
    let seed = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/accel/seed_quake.yaml"),
    )
    .unwrap();
    std::fs::write(
        d.join("short.yaml"),
        seed.replace("duration: 20.0", "duration: 6.0")
            .replace("t2: 12.0", "t2: 4.0")
            .replace("t1: 2.0", "t1: 1.0"),
    )
    .unwrap();
    std::fs::write(d.join("a_file"), b"").unwrap();
    let o = cfrd(d, &["accel", "short.yaml", "-o", "a_file/out"]);
    assert_eq!(o.status.code(), Some(4), "{}", text(&o));
    assert!(text(&o).contains("a_file"), "{}", text(&o));
    std::fs::write(
        d.join("huge.yaml"),
        seed.replace("duration: 20.0", "duration: 600.0")
            .replace("dt: 0.01", "dt: 0.0001"),
    )
    .unwrap();
    let t0 = std::time::Instant::now();
    let o = cfrd(d, &["accel", "huge.yaml", "-o", "out"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("dt: 600 s at dt = 0.0001 s is 6000001 samples"),
        "{}",
        text(&o)
    );
    assert!(t0.elapsed().as_secs() < 5, "refused at once: {:?}", t0.elapsed());
}
