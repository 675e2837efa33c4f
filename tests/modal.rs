//! The modal stage (issue 18, acceptance 2; spec seismic §4 item 4) through `cfrd run` on 1
//! and 2 ranks.
//!
//! The 1D shear column on a rigid base of `tests/dynamics.rs`: H = 50 m, Vs = 200 m/s
//! (G = 8·10⁷ Pa, ρ = 2000 kg/m³), one hexahedron across, every node held vertically and across
//! the axis, so that its lowest modes are those of a chain of N two-node shear elements of
//! height h = H/N with consistent mass. The chain's frequencies have a closed form: with
//! θ_n = (2n − 1)·π/(2N) (fixed base, free top),
//!
//! ```text
//! ω_n² = (6·G/(ρ·h²))·(1 − cos θ_n)/(2 + cos θ_n)
//! ```
//!
//! and they tend to the shear beam's f_n = (2n − 1)·Vs/(4H) = 1, 3, 5 Hz as h → 0, from above
//! by about (k_n·h)²/24. The tests compare with both: the discrete form to the eigensolver's
//! tolerance, the continuous one within 0.1 % (h = 0.5 m for f₁..f₃; the spec's h = 2.5 m for
//! f₁).

mod common;

use common::{cfrd_mpi, read_f64, tempdir, text};
use std::f64::consts::PI;
use std::path::Path;

const H: f64 = 50.0;
const VS: f64 = 200.0;
const G: f64 = 8.0e7;
const RHO: f64 = 2000.0;

/// The column scene with `n` elements up (in `layers` placement blocks) and its `stages:` list.
fn column_scene(dir: &Path, n: usize, layers: usize, stages: &str) {
    let scene = format!(
        "name: shear_column\nunits: SI\n\
         mesh:\n  box: {{ size: [2.5, 2.5, {H}], divisions: [1, 1, {n}], layers: {layers} }}\n\
         materials:\n  soil: {{ model: elastic, young: 2.0e8, poisson: 0.25, density: {RHO} }}\n\
         blocks:\n  layer_*: {{ material: soil }}\n\
         boundary:\n  - {{ set: zmin, fix: [x, y, z] }}\n  - {{ set: xmin, fix: [y, z] }}\n  - {{ set: xmax, fix: [y, z] }}\n\
         solver: {{ petsc_options: '-ksp_type preonly -pc_type lu' }}\n\
         stages:\n{stages}"
    );
    std::fs::write(dir.join("column.yaml"), scene).expect("scene written");
}

/// f_n (Hz) of the chain of `n` consistent-mass shear elements over the height `height`.
fn chain_frequency(mode: usize, n: usize, height: f64) -> f64 {
    let h = height / n as f64;
    let theta = (2 * mode - 1) as f64 * PI / (2 * n) as f64;
    let w2 = 6.0 * G / (RHO * h * h) * (1.0 - theta.cos()) / (2.0 + theta.cos());
    w2.sqrt() / (2.0 * PI)
}

/// f_n (Hz) of the continuous shear beam (spec seismic §4 item 4).
fn beam_frequency(mode: usize, height: f64) -> f64 {
    (2 * mode - 1) as f64 * VS / (4.0 * height)
}

/// Runs `column.yaml` into `out` on `np` ranks and returns the summary's modal frequencies.
fn modal_frequencies(np: usize, dir: &Path, out: &str) -> Vec<f64> {
    let o = cfrd_mpi(np, dir, &["run", "column.yaml", "-o", out, "-q"]);
    assert!(o.status.success(), "cfrd run failed: {}", text(&o));
    let summary: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join(out).join("summary.json")).expect("summary written"),
    )
    .expect("summary is JSON");
    let modal = &summary["modal"];
    let periods = modal["periods_s"].as_array().expect("periods_s");
    let f: Vec<f64> = modal["frequencies_hz"]
        .as_array()
        .expect("frequencies_hz")
        .iter()
        .map(|v| v.as_f64().expect("a number"))
        .collect();
    for (fi, t) in f.iter().zip(periods) {
        assert!((fi * t.as_f64().expect("a number") - 1.0).abs() < 1e-12);
    }
    f
}

/// The x components of mode `k` (1-based) at the nodes of one column edge (x = y = 0), bottom
/// to top, and the largest |y| or |z| component of the mode anywhere.
fn mode_shape(out: &Path, k: usize) -> (Vec<f64>, f64) {
    let h5 = out.join("modes.h5");
    let coords = read_f64(&h5, "/mesh/coordinates");
    let file = hdf5::File::open(&h5).expect("modes open");
    let mut steps: Vec<String> = file
        .group("/steps")
        .expect("steps")
        .member_names()
        .expect("names");
    steps.sort();
    let phi = read_f64(&h5, &format!("/steps/{}/mode_shape", steps[k - 1]));
    let mut edge: Vec<(f64, f64)> = (0..coords.len() / 3)
        .filter(|&i| coords[3 * i].abs() < 1e-9 && coords[3 * i + 1].abs() < 1e-9)
        .map(|i| (coords[3 * i + 2], phi[3 * i]))
        .collect();
    edge.sort_by(|a, b| a.0.total_cmp(&b.0));
    let off_axis = (0..coords.len() / 3)
        .flat_map(|i| [phi[3 * i + 1].abs(), phi[3 * i + 2].abs()])
        .fold(0.0f64, f64::max);
    (edge.into_iter().map(|(_, x)| x).collect(), off_axis)
}

#[test]
fn shear_column_modal_frequencies_match_the_closed_forms_at_one_and_two_ranks() {
    let dir = tempdir();
    let modes = "  - { name: place, activate: [layer_1] }\n  - { name: modes, modal: { modes: 3 } }\n";
    for (n, checked) in [(100usize, 3usize), (20, 1)] {
        column_scene(dir.path(), n, 1, modes);
        for np in [1, 2] {
            let f = modal_frequencies(np, dir.path(), &format!("out{n}_{np}"));
            assert_eq!(f.len(), 3, "{n} elements, {np} rank(s): {f:?}");
            for (i, &fi) in f.iter().enumerate() {
                let (chain, beam) = (chain_frequency(i + 1, n, H), beam_frequency(i + 1, H));
                eprintln!(
                    "{n} elements, {np} rank(s): f{} = {fi:.7} Hz, chain {chain:.7} ({:+.1e}), beam {beam} ({:+.3} %)",
                    i + 1,
                    fi / chain - 1.0,
                    100.0 * (fi / beam - 1.0)
                );
                assert!(
                    (fi / chain - 1.0).abs() < 1e-8,
                    "{n} elements, {np} rank(s): f{} = {fi} Hz, the chain's closed form {chain} Hz",
                    i + 1
                );
                if i < checked {
                    assert!(
                        (fi / beam - 1.0).abs() < 1e-3,
                        "{n} elements, {np} rank(s): f{} = {fi} Hz, the shear beam's {beam} Hz",
                        i + 1
                    );
                }
            }
        }
    }
    // the first mode of the chain is sin(j·θ₁) at node j, here with its peak +1 at the top
    let (edge, off_axis) = mode_shape(&dir.path().join("out20_2"), 1);
    assert_eq!(edge.len(), 21);
    for (j, &x) in edge.iter().enumerate() {
        let want = (j as f64 * PI / 40.0).sin();
        assert!((x - want).abs() < 1e-7, "node {j} up: mode 1 is {x}, want {want}");
    }
    assert_eq!(off_axis, 0.0, "the held components move in mode 1");
}

#[test]
fn constrained_dofs_and_unplaced_nodes_give_no_mode() {
    // a 40-element column in two placement blocks; the modes are taken when only the lower
    // half (25 m, 20 elements) is placed: the upper half's nodes are held and must not show
    let dir = tempdir();
    let stages = "  - { name: place, activate: [layer_1] }\n  - { name: modes, modal: { modes: 4 } }\n  - { name: rest, activate: [layer_2] }\n";
    column_scene(dir.path(), 40, 2, stages);
    let f = modal_frequencies(2, dir.path(), "out");
    for (i, &fi) in f.iter().enumerate() {
        let chain = chain_frequency(i + 1, 20, H / 2.0);
        eprintln!("lower half placed: f{} = {fi:.6} Hz, chain {chain:.6} Hz", i + 1);
        assert!(
            (fi / chain - 1.0).abs() < 1e-8,
            "f{} = {fi} Hz, the 25 m chain's {chain} Hz",
            i + 1
        );
    }
    let xdmf = std::fs::read_to_string(dir.path().join("out/modes.xdmf")).expect("modes.xdmf");
    for k in 1..=4 {
        let item = format!("modes.h5:/steps/{k:06}/mode_shape");
        assert!(xdmf.contains(&item), "modes.xdmf lacks {item}:\n{xdmf}");
    }
    assert!(!xdmf.contains("/steps/000005/"), "a fifth mode in modes.xdmf");
    for k in 1..=4 {
        let (edge, off_axis) = mode_shape(&dir.path().join("out"), k);
        assert_eq!(edge[0], 0.0, "mode {k}: the fixed base moves");
        assert!(
            edge[21..].iter().all(|&x| x == 0.0),
            "mode {k}: unplaced nodes move: {:?}",
            &edge[21..]
        );
        assert!(edge[20] != 0.0, "mode {k}: the placed top is still");
        assert_eq!(off_axis, 0.0, "mode {k}: held components move");
    }
}

#[test]
fn the_free_dofs_bound_the_number_of_modes() {
    // 4 elements: 16 free DOFs (x of the 4 nodes of each level above the base); the shear
    // chain's 4 modes come first, then the 11 modes of the level's nodes moving apart
    let dir = tempdir();
    let place = "  - { name: place, activate: [layer_1] }\n";
    column_scene(
        dir.path(),
        4,
        1,
        &format!("{place}  - {{ name: m, modal: {{ modes: 15 }} }}\n"),
    );
    let f = modal_frequencies(2, dir.path(), "out15");
    assert_eq!(f.len(), 15);
    for (i, &fi) in f.iter().take(4).enumerate() {
        let chain = chain_frequency(i + 1, 4, H);
        assert!(
            (fi / chain - 1.0).abs() < 1e-8,
            "f{} = {fi} Hz, chain {chain} Hz",
            i + 1
        );
    }
    assert!(f.windows(2).all(|w| w[0] <= w[1] && w[0] > 0.0), "{f:?}");
    column_scene(
        dir.path(),
        4,
        1,
        &format!("{place}  - {{ name: m, modal: {{ modes: 16 }} }}\n"),
    );
    let o = cfrd_mpi(2, dir.path(), &["run", "column.yaml", "-o", "out16", "-q"]);
    assert!(!o.status.success(), "16 modes of 16 free DOFs: {}", text(&o));
    assert!(
        text(&o).contains("asks for 16 modes, but the stage has 16 free DOFs: at most 15"),
        "{}",
        text(&o)
    );
}

#[test]
fn rayleigh_damping_on_modes_equals_damping_on_their_frequencies() {
    let dir = tempdir();
    let d = dir.path();
    let mut csv = String::from("t,a_x,a_y,a_z\n");
    for i in 0..=100 {
        let t = i as f64 * 0.01;
        csv.push_str(&format!("{t},{},0,0\n", (2.0 * PI * t).sin()));
    }
    std::fs::write(d.join("record.csv"), csv).expect("record written");
    let shake = |damping: &str| {
        format!(
            "  - {{ name: place, activate: [layer_1] }}\n  - name: shake\n    dynamic: {{ record: record.csv, damping: {damping} }}\n"
        )
    };
    column_scene(d, 20, 1, &shake("{ ratio: 0.05, modes: [1, 3] }"));
    let f = modal_frequencies(2, d, "by_modes");
    assert_eq!(f.len(), 3);
    column_scene(
        d,
        20,
        1,
        &shake(&format!(
            "{{ ratio: 0.05, frequencies: [{:?}, {:?}] }}",
            f[0], f[2]
        )),
    );
    let o = cfrd_mpi(2, d, &["run", "column.yaml", "-o", "by_frequencies", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let o = common::cfrd(
        d,
        &[
            "compare",
            "by_modes/results.h5",
            "by_frequencies/results.h5",
            "--tolerance",
            "0",
        ],
    );
    assert!(o.status.success(), "damping on modes differs: {}", text(&o));
}

#[test]
fn bad_modal_input_exits_2_naming_the_place() {
    let place = "  - { name: place, activate: [layer_1] }\n";
    let cases = [
        ("  - { name: m, modal: { modes: 0 } }\n", "stages[1].modal.modes: 0 must be from 1 to 1000"),
        ("  - { name: m, modal: { modes: 3, shape: x } }\n", "stages[1].modal"),
        (
            "  - { name: m, modal: { modes: 2 } }\n  - { name: n, modal: { modes: 2 } }\n",
            "stages[2]: a modal analysis runs already in stage 2 'm'",
        ),
        (
            "  - { name: q, dynamic: { record: r.csv, damping: { ratio: 0.05, modes: [3, 1] } } }\n",
            "stages[1].dynamic.damping: modes [3, 1] must be numbered from 1 with i < j",
        ),
        (
            "  - { name: q, dynamic: { record: r.csv, damping: { ratio: 0.05, modes: [1, 2], frequencies: [1.0, 2.0] } } }\n",
            "stages[1].dynamic.damping: give either",
        ),
        (
            "  - { name: q, dynamic: { record: r.csv, damping: { ratio: 0.05 } } }\n",
            "stages[1].dynamic.damping: ratio 0.05 needs its two anchors: give one of",
        ),
    ];
    for (stages, expect) in cases {
        let dir = tempdir();
        std::fs::write(dir.path().join("r.csv"), "t,a_x,a_y,a_z\n0,0,0,0\n0.01,0,0,0\n").unwrap();
        column_scene(dir.path(), 4, 1, &format!("{place}{stages}"));
        for args in [
            vec!["run", "column.yaml", "-o", "out"],
            vec!["check", "column.yaml"],
        ] {
            let o = cfrd_mpi(2, dir.path(), &args);
            let msg = text(&o);
            assert_eq!(o.status.code(), Some(2), "{stages} ({}): {msg}", args[0]);
            assert!(
                msg.contains(expect),
                "{stages} ({}): lacks '{expect}':\n{msg}",
                args[0]
            );
            assert!(!msg.contains("panicked"), "{stages}: panic:\n{msg}");
        }
    }
}

/// A modal or dynamic stage before any block is placed says so (exit 2) instead of failing on
/// "0 free DOFs".
#[test]
fn a_modal_or_dynamic_stage_before_any_block_is_placed_exits_2_saying_so() {
    let cases = [
        (
            "  - { name: m, modal: { modes: 2 } }\n",
            "stages[0]: a modal analysis needs placed blocks",
        ),
        (
            "  - { name: q, dynamic: { record: r.csv } }\n",
            "stages[0]: a dynamic stage needs placed blocks",
        ),
    ];
    for (stages, expect) in cases {
        let dir = tempdir();
        std::fs::write(dir.path().join("r.csv"), "t,a_x,a_y,a_z\n0,0,0,0\n0.01,0,0,0\n").unwrap();
        column_scene(dir.path(), 4, 1, stages);
        let o = cfrd_mpi(2, dir.path(), &["check", "column.yaml"]);
        assert_eq!(o.status.code(), Some(2), "{stages}: {}", text(&o));
        assert!(
            text(&o).contains(expect),
            "{stages}: lacks '{expect}':\n{}",
            text(&o)
        );
    }
}

#[test]
fn a_quake_damped_on_modes_restarts_bitwise_from_a_step_checkpoint() {
    // the restart recomputes the modes of the restored state: for the elastic column the same
    // frequencies, hence the same damping and the same results bit for bit
    let dir = tempdir();
    let d = dir.path();
    let mut csv = String::from("t,a_x,a_y,a_z\n");
    for i in 0..=100 {
        let t = i as f64 * 0.01;
        csv.push_str(&format!("{t},{},0,0\n", 2.0 * (2.0 * PI * 1.3 * t).sin()));
    }
    std::fs::write(d.join("record.csv"), csv).expect("record written");
    let stages = "  - { name: place, activate: [layer_1] }\n  - name: shake\n    dynamic: { record: record.csv, damping: { ratio: 0.05, modes: [1, 3] }, output_every: 50 }\n";
    column_scene(d, 20, 1, stages);
    let yaml = std::fs::read_to_string(d.join("column.yaml")).expect("scene");
    std::fs::write(
        d.join("column.yaml"),
        yaml.replace("units: SI", "units: SI\noutput: { checkpoint: step }"),
    )
    .expect("scene written");
    modal_frequencies(2, d, "full");
    common::run_and_kill(d, "column.yaml", "killed", None, 0.3);
    let ckpt = d.join("killed/checkpoint.h5");
    let t = common::time_in_second_stage(&ckpt).expect("a step checkpoint in the shake");
    eprintln!("killed at t = {t} s");
    common::restart_matches_bitwise(d, "column.yaml", "killed/checkpoint.h5", "rest", "full");
}

/// The lowest frequency (Hz) of a cantilever of square section `t` × `t` and length `length`,
/// fixed at x = 0, meshed with `nx` hexahedra along it and `nt` × `nt` across (`element`: the
/// block's `element` key), by the modal stage on 1 rank; and Euler–Bernoulli's
/// f₁ = (1.8751²/2π)·√(EI/(ρAL⁴)) (spec seismic §4 item 6).
fn cantilever_f1(dir: &Path, length: f64, t: f64, nx: usize, nt: usize, element: &str) -> (f64, f64) {
    let (e, rho) = (25.5e9, 2400.0);
    let scene = format!(
        "name: cantilever\nunits: SI\n\
         mesh:\n  box: {{ size: [{length}, {t}, {t}], divisions: [{nx}, {nt}, {nt}], layers: 1 }}\n\
         materials:\n  slab: {{ model: elastic, young: {e}, poisson: 0.167, density: {rho} }}\n\
         blocks:\n  layer_1: {{ material: slab, element: {element} }}\n\
         boundary:\n  - {{ set: xmin, fix: [x, y, z] }}\n\
         solver: {{ petsc_options: '-ksp_type preonly -pc_type lu' }}\n\
         stages:\n  - {{ name: modes, activate: [layer_1], modal: {{ modes: 2 }} }}\n"
    );
    std::fs::write(dir.join("column.yaml"), scene).expect("scene written");
    let f = modal_frequencies(1, dir, &format!("cantilever_{nx}_{nt}_{element}"));
    let inertia = t.powi(4) / 12.0;
    let exact = 1.8751f64.powi(2) / (2.0 * PI) * (e * inertia / (rho * t * t * length.powi(4))).sqrt();
    (f[0], exact)
}

/// The slab's element (spec seismic §4 item 6): a cantilever of 8-node hexahedra with one
/// element through its thickness. The fully integrated trilinear hexahedron locks in bending
/// (parasitic shear): the first frequency lies above beam theory by a factor that grows with the
/// elements' length over the thickness, and only falls towards it as the elements get shorter
/// than thick. Measured (40 m × 0.5 m × 0.5 m; 10 m for a/t ≤ 1): f₁ / f₁,beam = 6.62 at
/// a/t = 10, 3.43 at 5, 1.21 at 1, 1.07 at 0.5; two or four elements through the thickness do
/// not help (1.20 at a/t = 1). The remedy is the block key `element: incompatible_modes`
/// ([`a_thin_slab_with_one_element_through_its_thickness_bends_as_a_beam`]).
#[test]
fn the_trilinear_hexahedron_locks_in_bending_and_converges_as_its_elements_shorten() {
    let dir = tempdir();
    let d = dir.path();
    let ratio = |length: f64, nx: usize| {
        let (f, exact) = cantilever_f1(d, length, 0.5, nx, 1, "trilinear");
        f / exact
    };
    let ratios = [ratio(40.0, 8), ratio(40.0, 16), ratio(10.0, 20), ratio(10.0, 40)];
    println!("f1 / f1,beam at a/t = 10, 5, 1, 0.5: {ratios:.3?}");
    assert!(ratios[0] > 5.0, "a/t = 10 locks: {ratios:?}");
    assert!(ratios.windows(2).all(|w| w[1] < w[0]), "{ratios:?}");
    assert!((ratios[3] - 1.0).abs() < 0.08, "a/t = 0.5 within 8 %: {ratios:?}");
}

/// What the slab needs (spec seismic §4 item 6): with one element through its thickness and
/// elements 10, 20 and 40 times longer than thick (the seed meshes' slab: a/t ≈ 4–120), the
/// cantilever's first frequency within 5 % of beam theory, with the hexahedron's incompatible
/// modes (`element: incompatible_modes`, `cfrd::element::hex8_modes`).
#[test]
fn a_thin_slab_with_one_element_through_its_thickness_bends_as_a_beam() {
    let dir = tempdir();
    for (length, nx) in [(40.0, 8), (40.0, 4), (40.0, 2)] {
        let (f, exact) = cantilever_f1(dir.path(), length, 0.5, nx, 1, "incompatible_modes");
        println!(
            "a/t = {}: f1 / f1,beam = {:.4}",
            length / nx as f64 / 0.5,
            f / exact
        );
        assert!(
            (f / exact - 1.0).abs() < 0.05,
            "a/t = {}: f1 {f} Hz, beam theory {exact} Hz",
            length / nx as f64 / 0.5
        );
    }
}
