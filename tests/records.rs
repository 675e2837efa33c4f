//! Ground-motion records in scenes (issue 56): one PEER NGA AT2 file per component gives the
//! same quake, bit for bit, as the same record in CSV; a component left out is zero and a
//! shorter one is padded with zeros, both stated in the log; a record shorter than the stage's
//! duration is followed by ground at rest, stated in the log, the same quake as the record
//! continued with zeros. The AT2 files are written from the committed seed record
//! (`inputs/accel/seed_quake.csv`) in g with 7 significant digits, as PEER writes them; the CSV
//! compared with them holds the values those digits give (g × 9.80665 m/s²), not the seed's own
//! (which 7 digits in g do not round-trip), so both readers give the same f64s.

mod common;

use cfrd::seismic::{Accelerogram, Axis};
use common::{assert_bitwise_equal, cfrd, cfrd_mpi, read_f64, tempdir, text};
use std::path::Path;

/// Standard gravity of the PEER files' `UNITS OF G` (m/s²), written here rather than taken
/// from the reader.
const G: f64 = 9.80665;

/// The tests here run `cfrd` under `mpirun` one at a time (two 2-rank runs at once on two
/// cores slow each other down several times).
static ONE_MPI_TEST_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn mpi_turn() -> std::sync::MutexGuard<'static, ()> {
    ONE_MPI_TEST_AT_A_TIME
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Writes `name` into `dir`: a free-standing elastic column (2.5 × 2.5 × 20 m, eight
/// hexahedra, its base fixed, so it sways in x and y and breathes in z) placed in a first
/// stage and shaken in a second under `record` (a scene value) with Rayleigh damping, the
/// dynamic keys `extra` (", key: value") and its fields every 5 steps.
fn column_scene(dir: &Path, name: &str, record: &str, extra: &str) {
    let scene = format!(
        "name: column\nunits: SI\n\
         mesh:\n  box: {{ size: [2.5, 2.5, 20.0], divisions: [1, 1, 8] }}\n\
         materials:\n  soil: {{ model: elastic, young: 2.0e8, poisson: 0.25, density: 2000.0 }}\n\
         blocks:\n  layer_1: {{ material: soil }}\n\
         boundary:\n  - {{ set: zmin, fix: [x, y, z] }}\n\
         stages:\n  - {{ name: place, activate: [layer_1] }}\n  - name: shake\n    \
         dynamic: {{ record: {record}, damping: {{ ratio: 0.05, frequencies: [1.0, 5.0] }}, \
         linear_solver: canonical_lu, output_every: 5{extra} }}\n"
    );
    std::fs::write(dir.join(name), scene).unwrap();
}

/// The committed seed record (m/s², Δt = 0.01 s).
fn seed_record() -> Accelerogram {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/accel/seed_quake.csv");
    Accelerogram::read_csv(&path).expect("the seed record")
}

/// `v` as PEER writes its values: a mantissa in [0.1, 1) with 7 digits, `.3518795E-02`.
fn peer_number(v: f64) -> String {
    let e = format!("{:.6E}", v.abs());
    let (mantissa, exponent) = e.split_once('E').expect("E notation");
    let exponent: i32 = exponent.parse().expect("exponent");
    let sign = if v < 0.0 { "-" } else { "" };
    format!("{sign}.{}E{:+03}", mantissa.replace('.', ""), exponent + 1)
}

/// One component `a` (m/s²) at Δt = 0.01 s as a PEER AT2 file's text in g (five values a line)
/// and the accelerations (m/s²) its digits stand for.
fn at2_component(axis: Axis, a: &[f64]) -> (String, Vec<f64>) {
    let digits: Vec<String> = a.iter().map(|v| peer_number(v / G)).collect();
    let mut text = format!(
        "PEER NGA STRONG MOTION DATABASE RECORD\n\
         CFRD SEED QUAKE (inputs/accel/seed_quake.csv), COMPONENT {}\n\
         ACCELERATION TIME SERIES IN UNITS OF G\nNPTS= {:5}, DT=   .0100 SEC\n",
        axis.name().to_uppercase(),
        a.len()
    );
    for line in digits.chunks(5) {
        for d in line {
            text.push_str(&format!("{d:>15}"));
        }
        text.push('\n');
    }
    let values = digits.iter().map(|d| d.parse::<f64>().unwrap() * G).collect();
    (text, values)
}

/// Writes `x.AT2`, `y.AT2`, `z.AT2` into `dir`, each the seed's component cut to `len[axis]`
/// samples (all when `None`), and returns the accelerations (m/s²) they stand for.
fn write_at2_files(dir: &Path, len: [Option<usize>; 3]) -> [Vec<f64>; 3] {
    let seed = seed_record();
    Axis::ALL.map(|axis| {
        let a = seed.component(axis);
        let a = &a[..len[axis.index()].unwrap_or(a.len())];
        let (text, values) = at2_component(axis, a);
        for (v, s) in values.iter().zip(a) {
            assert!((v - s).abs() <= 5.1e-7 * s.abs(), "{v} against the seed's {s}");
        }
        std::fs::write(dir.join(format!("{}.AT2", axis.name())), text).unwrap();
        values
    })
}

/// Writes `record.csv` into `dir`: the three components (m/s², Δt = 0.01 s), each padded with
/// zeros to `n` samples.
fn write_csv(dir: &Path, n: usize, components: [Vec<f64>; 3]) {
    let [x, y, z] = components.map(|mut c| {
        c.resize(n, 0.0);
        c
    });
    let record = Accelerogram::new(0.01, x, y, z).unwrap();
    record.write_csv(&dir.join("record.csv")).unwrap();
}

/// Runs `scene` of `dir` on 2 ranks into `out`; its log.
fn run(dir: &Path, scene: &str, out: &str) -> String {
    let o = cfrd_mpi(2, dir, &["run", scene, "-o", out]);
    assert!(o.status.success(), "{scene}: {}", text(&o));
    text(&o)
}

/// Asserts that `a` and `b` of `dir` hold the same results bit for bit (`cfrd compare
/// --tolerance 0` and every step field); the number of quake steps compared.
fn assert_same_results(dir: &Path, a: &str, b: &str) -> usize {
    let (ra, rb) = (format!("{a}/results.h5"), format!("{b}/results.h5"));
    let o = cfrd(dir, &["compare", &ra, &rb, "--tolerance", "0"]);
    assert!(o.status.success(), "{a} against {b}: {}", text(&o));
    let fields = assert_bitwise_equal(&dir.join(&ra), &dir.join(&rb));
    fields.iter().filter(|n| n.ends_with("/velocity")).count()
}

/// The largest |u| of each axis over the nodes at the last step of the run in `out`.
fn peak_displacement(out: &Path) -> [f64; 3] {
    let h5 = out.join("results.h5");
    let file = hdf5::File::open(&h5).unwrap();
    let mut steps = file.group("/steps").unwrap().member_names().unwrap();
    steps.sort();
    let u = read_f64(&h5, &format!("/steps/{}/displacement", steps.last().unwrap()));
    [0, 1, 2].map(|i| u.iter().skip(i).step_by(3).fold(0.0, |m: f64, v| m.max(v.abs())))
}

/// The coarse seed quake's record as three AT2 files gives the quake of the same record in
/// CSV bit for bit: 40 steps (0.4 s) of the column.
#[test]
fn an_at2_record_gives_the_same_quake_as_the_same_record_in_csv() {
    let _turn = mpi_turn();
    let dir = tempdir();
    let d = dir.path();
    let values = write_at2_files(d, [None; 3]);
    let n = values[0].len();
    write_csv(d, n, values);
    column_scene(d, "csv.yaml", "record.csv", ", duration: 0.4");
    column_scene(
        d,
        "at2.yaml",
        "{ x: x.AT2, y: y.AT2, z: z.AT2 }",
        ", duration: 0.4",
    );
    run(d, "csv.yaml", "csv");
    let log = run(d, "at2.yaml", "at2");
    assert!(
        !log.contains("record:") && !log.contains("the ground is at rest"),
        "a complete AT2 record needs no note:\n{log}"
    );
    let quake = assert_same_results(d, "csv", "at2");
    assert_eq!(quake, 8, "quake steps compared");
    let peak = peak_displacement(&d.join("at2"));
    assert!(
        peak.iter().all(|&u| u > 0.0),
        "the column moves in x, y and z: {peak:?}"
    );
    let [px, py, pz] = peak;
    println!("AT2 and CSV: {quake} quake steps identical bit for bit, peaks {px:.3e}, {py:.3e}, {pz:.3e} m");
}

/// A component left out is zero and a shorter one is padded with zeros, and the log says both:
/// x whole, z cut to 0.2 s, y left out is the CSV with a_y = 0 and a_z zero after 0.2 s.
#[test]
fn at2_components_left_out_or_shorter_are_zeros_and_the_log_says_so() {
    let _turn = mpi_turn();
    let dir = tempdir();
    let d = dir.path();
    let [x, _, z] = write_at2_files(d, [None, None, Some(21)]);
    let n = x.len();
    write_csv(d, n, [x, Vec::new(), z]);
    column_scene(d, "csv.yaml", "record.csv", ", duration: 0.4");
    column_scene(d, "at2.yaml", "{ x: x.AT2, z: z.AT2 }", ", duration: 0.4");
    run(d, "csv.yaml", "csv");
    let log = run(d, "at2.yaml", "at2");
    for note in [
        "record: no AT2 file for y: that ground acceleration is zero",
        "record: components of different lengths (x 2001, z 21 samples): the shorter padded \
         with zeros to 2001",
    ] {
        assert_eq!(log.matches(note).count(), 1, "'{note}' once in:\n{log}");
    }
    let quake = assert_same_results(d, "csv", "at2");
    println!("x and a shorter z in AT2: {quake} quake steps identical to the padded CSV");
}

/// Issue 56: a record shorter than the duration was padded with zeros without a word. The
/// ground is at rest after the record's end, one log line says so, and the quake is the same as
/// under the record continued with zeros to the duration.
#[test]
fn after_a_record_shorter_than_the_duration_the_ground_is_at_rest_and_the_log_says_so() {
    let _turn = mpi_turn();
    let dir = tempdir();
    let d = dir.path();
    let seed = seed_record();
    let cut = |n: usize, keep: usize| {
        Axis::ALL.map(|axis| {
            let mut c = seed.component(axis)[..keep].to_vec();
            c.resize(n, 0.0);
            c
        })
    };
    let [x, y, z] = cut(21, 20);
    Accelerogram::new(0.01, x, y, z)
        .unwrap()
        .write_csv(&d.join("short.csv"))
        .unwrap();
    let [x, y, z] = cut(41, 20);
    Accelerogram::new(0.01, x, y, z)
        .unwrap()
        .write_csv(&d.join("long.csv"))
        .unwrap();
    column_scene(d, "short.yaml", "short.csv", ", duration: 0.4");
    column_scene(d, "long.yaml", "long.csv", "");
    let log = run(d, "short.yaml", "short");
    let rule = "record ends at 0.2 s; from 0.2 to 0.4 s the ground is at rest";
    assert_eq!(log.matches(rule).count(), 1, "'{rule}' once in:\n{log}");
    let log = run(d, "long.yaml", "long");
    assert!(!log.contains("the ground is at rest"), "a whole record:\n{log}");
    let quake = assert_same_results(d, "short", "long");
    assert_eq!(quake, 8, "quake steps compared");
}

/// `cfrd schema` shows both forms of `record`: a path (CSV) or the AT2 files of x, y and z.
#[test]
fn the_schema_shows_both_forms_of_a_record() {
    let o = cfrd(Path::new("."), &["schema"]);
    assert!(o.status.success(), "{}", text(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("schema is JSON");
    let forms = v["definitions"]["RecordSpec"]["anyOf"]
        .as_array()
        .expect("record: anyOf");
    assert_eq!(forms.len(), 2, "{forms:?}");
    assert_eq!(forms[0]["type"], "string", "{forms:?}");
    assert_eq!(
        forms[1]["allOf"][0]["$ref"], "#/definitions/At2Files",
        "{forms:?}"
    );
    let files = &v["definitions"]["At2Files"]["properties"];
    for axis in ["x", "y", "z"] {
        assert!(files[axis].is_object(), "At2Files lacks {axis}: {files}");
    }
}
