//! `cfrd export` (issue 21): fields of one step of a results file as CSV, for every node or
//! element, a set or probe points, read back against the HDF5 datasets. A small two-layer
//! column runs on 2 ranks; the exports are checked value for value (the CSV holds the stored
//! numbers exactly), and bad requests exit with code 2 and a message naming what is wrong and
//! what there is.

mod common;
use common::*;
use std::collections::HashMap;
use std::path::Path;

/// A 2 × 2 × 4 m elastic column of 2 × 2 × 4 hexahedra built in two layers under gravity, then
/// loaded on top.
const SCENE: &str = "name: export-column
units: SI
mesh:
  box: { size: [2.0, 2.0, 4.0], divisions: [2, 2, 4], layers: 2 }
materials:
  soil: { model: elastic, young: 5.0e7, poisson: 0.3, density: 2000.0 }
blocks:
  layer_1: { material: soil }
  layer_2: { material: soil }
boundary:
  - { set: zmin, fix: [x, y, z] }
  - { set: xmin, fix: [x] }
loads:
  gravity: { g: [0.0, 0.0, -9.81] }
stages:
  - { name: fill_1, activate: [layer_1] }
  - { name: fill_2, activate: [layer_2] }
  - { name: surcharge, loads: { pressure: [ { faces: zmax, value: 1.0e5 } ] } }
";

/// A parsed CSV table: header and rows of cells.
struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn parse(text: &str) -> Table {
        let mut lines = text.lines();
        let header = lines
            .next()
            .expect("a header")
            .split(',')
            .map(str::to_string)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect();
        Table { header, rows }
    }

    /// The values of column `name` as numbers.
    fn column(&self, name: &str) -> Vec<f64> {
        let c = self
            .header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header));
        self.rows
            .iter()
            .map(|r| r[c].parse().expect("a number"))
            .collect()
    }
}

/// Runs `cfrd export ARGS` in `dir` and returns the table it wrote to `-o out.csv`.
fn export(dir: &Path, args: &[&str]) -> Table {
    let mut all = vec!["export", "out/results.h5"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", "out.csv"]);
    let o = cfrd(dir, &all);
    assert!(o.status.success(), "{args:?}: {}", text(&o));
    println!("{args:?}: {}", text(&o).trim());
    Table::parse(&std::fs::read_to_string(dir.join("out.csv")).unwrap())
}

/// The row index of each input id of a results file's `ids` dataset.
fn index_of(file: &Path, ids: &str) -> HashMap<i64, usize> {
    read_i64(file, ids)
        .into_iter()
        .enumerate()
        .map(|(i, id)| (id, i))
        .collect()
}

/// Asserts that the exported components of `field` (columns `<field>_<c>_<units>`) equal the
/// dataset's rows bit for bit, row by row through the ids in column `id_column`.
fn assert_rows_equal(table: &Table, file: &Path, dataset: &str, columns: &[String], ids: (&str, &str)) {
    let data = read_f64(file, dataset);
    let index = index_of(file, ids.1);
    let id_col: Vec<i64> = table.column(ids.0).iter().map(|&v| v as i64).collect();
    for (c, name) in columns.iter().enumerate() {
        for (row, v) in table.column(name).iter().enumerate() {
            let stored = data[columns.len() * index[&id_col[row]] + c];
            assert_eq!(
                v.to_bits(),
                stored.to_bits(),
                "{dataset} {name} of id {}",
                id_col[row]
            );
        }
    }
}

fn names(prefix: &str, components: &[&str], units: &str) -> Vec<String> {
    components
        .iter()
        .map(|c| format!("{prefix}_{c}_{units}"))
        .collect()
}

#[test]
fn export_writes_the_stored_values_by_step_set_and_probe() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("column.yaml"), SCENE).unwrap();
    let o = cfrd_mpi(2, d, &["run", "column.yaml", "-o", "out", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let file = d.join("out/results.h5");
    let n_nodes = read_i64(&file, "/mesh/node_ids").len();
    let n_elements = read_i64(&file, "/mesh/element_ids").len();
    let xyz = ["x", "y", "z"];

    // the last step by default: every node, every solid element
    let u = export(d, &["--field", "displacement"]);
    assert_eq!(u.rows.len(), n_nodes);
    let u_cols = names("displacement", &xyz, "m");
    assert_rows_equal(
        &u,
        &file,
        "/steps/000003/displacement",
        &u_cols,
        ("node_id", "/mesh/node_ids"),
    );
    let s = export(d, &["--field", "stress", "--step", "2"]);
    assert_eq!(s.rows.len(), n_elements);
    let s_cols = names("stress", &["xx", "yy", "zz", "xy", "yz", "zx"], "Pa");
    assert_rows_equal(
        &s,
        &file,
        "/steps/000002/stress",
        &s_cols,
        ("element_id", "/mesh/element_ids"),
    );

    // a stage and a block: the nodes of layer_1 at the end of fill_1
    let l1 = export(
        d,
        &["--stage", "fill_1", "--field", "displacement", "--set", "layer_1"],
    );
    let z = l1.column("z_m");
    assert_eq!(l1.rows.len(), 3 * 3 * 3, "nodes of the lower 2 m");
    assert!(z.iter().all(|&z| z <= 2.0 + 1e-12), "{z:?}");
    assert_rows_equal(
        &l1,
        &file,
        "/steps/000001/displacement",
        &u_cols,
        ("node_id", "/mesh/node_ids"),
    );

    // a node set of the scene, two fields at once
    let top = export(
        d,
        &[
            "--field",
            "displacement",
            "--field",
            "reaction",
            "--set",
            "zmax",
            "--scene",
            "column.yaml",
        ],
    );
    assert_eq!(top.rows.len(), 9);
    assert!(top.column("z_m").iter().all(|&z| (z - 4.0).abs() < 1e-12));
    assert_rows_equal(
        &top,
        &file,
        "/steps/000003/reaction",
        &names("reaction", &xyz, "N"),
        ("node_id", "/mesh/node_ids"),
    );

    // a face set of the scene for an element field: the elements under the top face
    let under = export(
        d,
        &["--field", "stress", "--set", "zmax", "--scene", "column.yaml"],
    );
    assert_eq!(under.rows.len(), 4);
    assert!(under.column("z_m").iter().all(|&z| (z - 3.5).abs() < 1e-12));

    // probes: the nearest node, and the element with the nearest centre
    let p = export(
        d,
        &[
            "--field",
            "displacement",
            "--probe",
            "2.1,1.9,4.2",
            "--probe",
            "0,0,0",
        ],
    );
    assert_eq!(p.rows.len(), 2);
    assert_eq!(
        (p.column("x_m")[0], p.column("y_m")[0], p.column("z_m")[0]),
        (2.0, 2.0, 4.0)
    );
    let expected = (0.1f64 * 0.1 + 0.1 * 0.1 + 0.2 * 0.2).sqrt();
    assert!((p.column("distance_m")[0] - expected).abs() < 1e-12);
    assert_eq!(
        (p.column("x_m")[1], p.column("z_m")[1], p.column("distance_m")[1]),
        (0.0, 0.0, 0.0)
    );
    assert_rows_equal(
        &p,
        &file,
        "/steps/000003/displacement",
        &u_cols,
        ("node_id", "/mesh/node_ids"),
    );
    let e = export(d, &["--field", "stress", "--probe", "0.4,0.6,3.4"]);
    assert_eq!(
        (e.column("x_m")[0], e.column("y_m")[0], e.column("z_m")[0]),
        (0.5, 0.5, 3.5)
    );
    assert_rows_equal(
        &e,
        &file,
        "/steps/000003/stress",
        &s_cols,
        ("element_id", "/mesh/element_ids"),
    );

    // without -o the table goes to standard output, the same bytes
    let o = cfrd(d, &["export", "out", "--field", "displacement"]);
    assert!(o.status.success(), "{}", text(&o));
    export(d, &["--field", "displacement"]);
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        std::fs::read_to_string(d.join("out.csv")).unwrap()
    );
}

#[test]
fn bad_export_requests_exit_2_and_say_what_there_is() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::write(d.join("column.yaml"), SCENE).unwrap();
    let o = cfrd_mpi(1, d, &["run", "column.yaml", "-o", "out", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let cases: [(&[&str], &str); 8] = [
        (&["--field", "stres"], "--field stres: no such field in step 000003 (stage surcharge); it has displacement, reaction, strain, stress"),
        (&["--field", "stress", "--stage", "fill_9"], "--stage fill_9: no such stage; the file has fill_1, fill_2, surcharge"),
        (&["--field", "stress", "--step", "7"], "--step 7: no such step; the file has steps 1 to 3"),
        (&["--field", "stress", "--set", "layer_9"], "--set layer_9: no block of the results file matches; blocks: layer_1, layer_2"),
        (&["--field", "displacement", "--set", "base", "--scene", "column.yaml"], "--set base: no block, node set or face set of column.yaml has this name; it has layer_1, layer_2, xmax, xmin, ymax, ymin, zmax, zmin\n"),
        (&["--field", "displacement", "--field", "stress"], "a node field and an element field cannot share a table"),
        (&["--field", "stress", "--probe", "1,2"], "'1,2': expected three finite coordinates X,Y,Z in m"),
        (&["--field", "stress", "--stage", "fill_1", "--step", "1"], "cannot be used with"),
    ];
    for (args, expect) in cases {
        let mut all = vec!["export", "out"];
        all.extend_from_slice(args);
        let o = cfrd(d, &all);
        let msg = text(&o);
        println!("{args:?}: {}", msg.lines().next().unwrap_or(""));
        assert_eq!(o.status.code(), Some(2), "{args:?}: {msg}");
        assert!(msg.contains(expect), "{args:?}: message lacks '{expect}':\n{msg}");
        assert!(!msg.contains("panicked"), "{args:?}: {msg}");
    }
    let o = cfrd(d, &["export", "nowhere/results.h5", "--field", "stress"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("nowhere/results.h5"), "{}", text(&o));
}
