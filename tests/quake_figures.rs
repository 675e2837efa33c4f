//! The seed's dynamic figures (seed Figs. 12–20, spec seismic §3.6; `cfrd::post::quake_figures`)
//! from a short quake on 2 ranks: the small generated dam of `tests/cfrd_dam.rs` (elastic fill,
//! hyperbolic interface; the canonical LU, whose results do not depend on how the run was
//! split) through its schedule, then 0.5 s cut from the committed seed record.
//! Every figure file is written; the tables are finite, the residual is after − before, the
//! probes lie where the scene puts them and the histories have one row per time step.

mod common;
use common::*;
use std::collections::HashMap;
use std::path::Path;

const MESH: &str = SMALL_DAM_MESH;
/// Seconds of the seed record cut for the test, from `CUT_FROM` s on.
const DURATION: f64 = 0.5;
const CUT_FROM: f64 = 5.0;
const DT: f64 = 0.01;

const PROBES: &str = "[ { name: I-A, elevation: 2711.0 }, \
    { name: I-B, elevation: 2809.0, at: left_bank }, { name: I-C, elevation: 2838.0 }, \
    { name: I-D, elevation: 2852.0 }, { name: F-A, elevation: 2813.0, element: slab } ]";

fn scene() -> String {
    let tail = format!(
        "output: {{ profiles: {{ probes: {PROBES} }} }}\n\
         earthquake: {{ record: record.csv, damping: {{ ratio: 0.02, frequencies: [1.0, 5.0] }}, output_every: 1, linear_solver: canonical_lu }}"
    );
    small_dam(
        ELASTIC_FILL,
        "hyperbolic",
        2400.0,
        "",
        "{ linear_solver: canonical_lu }",
        &tail,
    )
}

/// Writes `record.csv`: the seed record from `CUT_FROM` s for `DURATION` s, time shifted to 0.
fn cut_record(dir: &Path) {
    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/accel/seed_quake.csv");
    let text = std::fs::read_to_string(seed).unwrap();
    let mut out = String::from("t,a_x,a_y,a_z\n");
    for line in text.lines().skip(1) {
        let f: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let t = f[0] - CUT_FROM;
        if (-1e-9..=DURATION + 1e-9).contains(&t) {
            out.push_str(&format!("{},{},{},{}\n", (t / DT).round() * DT, f[1], f[2], f[3]));
        }
    }
    assert_eq!(out.lines().count(), 2 + (DURATION / DT).round() as usize);
    std::fs::write(dir.join("record.csv"), out).unwrap();
}

/// A CSV table without its `#` lines: header names and rows of fields.
struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn read(path: &Path) -> Table {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut lines = text.lines().filter(|l| !l.starts_with('#'));
        let split = |l: &str| l.split(',').map(str::to_string).collect::<Vec<_>>();
        let header = split(lines.next().expect("a header"));
        let rows: Vec<Vec<String>> = lines.map(split).collect();
        assert!(!rows.is_empty(), "{}: no rows", path.display());
        for r in &rows {
            assert_eq!(r.len(), header.len(), "{}: {r:?}", path.display());
        }
        Table { header, rows }
    }

    fn col(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header))
    }

    fn num(&self, row: usize, name: &str) -> f64 {
        self.rows[row][self.col(name)].parse().unwrap()
    }

    /// Every field but those of the named text columns parses as a finite number.
    fn assert_finite(&self, text_columns: &[&str], what: &str) {
        for r in &self.rows {
            for (h, v) in self.header.iter().zip(r) {
                if !text_columns.contains(&h.as_str()) {
                    let x: f64 = v.parse().unwrap_or(f64::NAN);
                    assert!(x.is_finite(), "{what}: {h} = {v}");
                }
            }
        }
    }
}

#[test]
fn a_short_quake_writes_the_seed_dynamic_figures() {
    let dir = tempdir();
    let d = dir.path();
    cut_record(d);
    std::fs::write(d.join("dam.yaml"), scene()).unwrap();
    let o = cfrd_mpi(2, d, &["run", "dam.yaml", "-o", "out", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let out = d.join("out");
    for stem in [
        "fig12_outline",
        "fig13_residual_slab",
        "fig14_slab_probe_F-A",
        "fig16_interface_normal",
        "fig17_interface_opening",
        "fig18_interface_probe_I-A",
        "fig18_interface_probe_I-B",
        "fig18_interface_probe_I-C",
        "fig18_interface_probe_I-D",
        "fig20_opening",
    ] {
        let png = std::fs::metadata(out.join(format!("{stem}.png"))).map(|m| m.len());
        assert!(png.as_ref().map_or(0, |l| *l) > 1000, "{stem}.png: {png:?}");
        let csv = Table::read(&out.join(format!("{stem}.csv")));
        csv.assert_finite(&["state"], stem);
    }
    assert!(
        std::fs::metadata(out.join("fig15_interface_slip.png"))
            .unwrap()
            .len()
            > 1000
    );
    check_outline(&out);
    let slab_rows = check_residual_slab(&out);
    let probes = check_probes(&out, &slab_rows);
    check_histories(&out, &probes);
    check_crest(&out);
    check_parts(d, &out);
}

/// `quake_crest.csv` follows the centre of the dam body's crest: a node of the fill (on no
/// slab element), at the fill's highest elevation, nearest the middle of its crest across the
/// stream; not the slab's top edge, which stands higher.
fn check_crest(out: &Path) {
    let h5 = out.join("results.h5");
    let (crest, coords) = crest_node(out);
    let ids = read_i64(&h5, "/mesh/node_ids");
    let (topology, blocks) = (
        read_i64(&h5, "/mesh/topology"),
        read_i64(&h5, "/mesh/element_block"),
    );
    let names = hdf5::File::open(&h5)
        .and_then(|f| f.group("mesh"))
        .and_then(|g| g.attr("block_names"))
        .and_then(|a| a.read_scalar::<hdf5::types::VarLenUnicode>())
        .expect("block names")
        .to_string();
    let names: Vec<&str> = names.lines().collect();
    let mut on_slab = vec![false; ids.len()];
    let mut on_fill = vec![false; ids.len()];
    for (e, &b) in blocks.iter().enumerate() {
        let name = names[b as usize];
        for &n in &topology[8 * e..8 * e + 8] {
            on_slab[n as usize] |= name.starts_with("slab");
            on_fill[n as usize] |= name.starts_with("fill");
        }
    }
    let z = |n: usize| coords[3 * n + 2];
    let fill_top = (0..ids.len())
        .filter(|&n| on_fill[n])
        .map(z)
        .fold(f64::MIN, f64::max);
    let slab_top = (0..ids.len())
        .filter(|&n| on_slab[n])
        .map(z)
        .fold(f64::MIN, f64::max);
    println!(
        "crest node {crest} at {:?}; fill top {fill_top}, slab top {slab_top}",
        &coords[3 * crest..3 * crest + 3]
    );
    assert!(
        on_fill[crest] && !on_slab[crest],
        "the crest node {crest} is a fill node"
    );
    assert!(
        (z(crest) - fill_top).abs() < 1e-6,
        "at the fill's top: {} against {fill_top}",
        z(crest)
    );
    assert!(
        slab_top > fill_top,
        "the slab's edge stands above the fill on this mesh"
    );
    let top_x: Vec<f64> = (0..ids.len())
        .filter(|&n| on_fill[n] && (z(n) - fill_top).abs() < 1e-6)
        .map(|n| coords[3 * n])
        .collect();
    let (lo, hi) = top_x
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    let off = (coords[3 * crest] - 0.5 * (lo + hi)).abs();
    assert!(
        top_x.iter().all(|&x| (x - 0.5 * (lo + hi)).abs() >= off),
        "the crest centre's node"
    );
}

/// The same run in two parts, stopped after the impoundment and restarted into the quake: the
/// restarted part (which holds no static stage) succeeds, and `cfrd profiles` over both parts
/// draws the dynamic figures of the uninterrupted run, byte for byte.
fn check_parts(d: &Path, out: &Path) {
    let spec: cfrd::mesh::dam_spec::CfrdSpec = serde_yaml::from_str(MESH).unwrap();
    let statics = cfrd::mesh::dam_generator::cfrd_mesh(&spec)
        .unwrap()
        .stages
        .len()
        .to_string();
    let o = cfrd_mpi(
        2,
        d,
        &[
            "run",
            "dam.yaml",
            "-o",
            "p1",
            "-q",
            "--stop-after-stage",
            &statics,
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let o = cfrd_mpi(
        2,
        d,
        &[
            "run",
            "dam.yaml",
            "-o",
            "p2",
            "-q",
            "--restart",
            "p1/checkpoint.h5",
        ],
    );
    assert!(o.status.success(), "restarted into the quake: {}", text(&o));
    let o = common::cfrd(d, &["profiles", "dam.yaml", "p1", "p2", "-o", "joined"]);
    assert!(o.status.success(), "{}", text(&o));
    for name in [
        "fig12_outline.csv",
        "fig13_residual_slab.csv",
        "fig15_interface_residual.csv",
    ] {
        let whole = std::fs::read_to_string(out.join(name)).unwrap();
        let joined = std::fs::read_to_string(d.join("joined").join(name)).unwrap();
        assert!(
            whole == joined,
            "{name} differs between the run and its two parts"
        );
    }
    // the run records the probes at every time step, the parts' results hold every step
    // (output_every: 1): the same rows byte for byte, only the sampling notes differ
    for name in [
        "fig14_slab_probe_F-A.csv",
        "fig18_interface_probe_I-B.csv",
        "fig18_interface_probe_I-D.csv",
        "fig20_opening.csv",
    ] {
        let rows = |dir: &Path| -> (String, String) {
            let text = std::fs::read_to_string(dir.join(name)).unwrap();
            let (note, rest) = text.split_once('\n').unwrap();
            (note.to_string(), rest.to_string())
        };
        let (whole, joined) = (rows(out), rows(&d.join("joined")));
        assert!(
            whole.0.contains("every converged time step"),
            "{name}: {}",
            whole.0
        );
        assert!(joined.0.contains("results steps"), "{name}: {}", joined.0);
        assert!(
            whole.1 == joined.1,
            "{name}: the run's history differs from the one of its parts' results"
        );
    }
}

/// Fig. 12: a closed outline whose "after" points are the mesh points plus the stated factor
/// times the residual displacement.
fn check_outline(out: &Path) {
    let text = std::fs::read_to_string(out.join("fig12_outline.csv")).unwrap();
    let note = text.lines().next().unwrap();
    let factor: f64 = note
        .split(" + ")
        .nth(1)
        .and_then(|s| s.split(" x ").next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no factor in {note}"));
    assert!(factor >= 1.0, "{note}");
    let t = Table::read(&out.join("fig12_outline.csv"));
    assert!(t.rows.len() >= 6, "an outline of {} points", t.rows.len());
    assert_eq!(t.rows.first(), t.rows.last(), "closed");
    let mut moved = 0.0_f64;
    for r in 0..t.rows.len() {
        for (x, u, after) in [
            ("x_m", "ux_residual_m", "x_after_m"),
            ("z_m", "uz_residual_m", "z_after_m"),
        ] {
            let expect = t.num(r, x) + factor * t.num(r, u);
            assert!((t.num(r, after) - expect).abs() <= 1e-9 * expect.abs(), "row {r}");
            moved = moved.max(t.num(r, u).abs());
        }
    }
    assert!(moved > 0.0, "the quake leaves a residual displacement");
    let zs: Vec<f64> = (0..t.rows.len()).map(|r| t.num(r, "z_m")).collect();
    let top = zs.iter().copied().fold(f64::MIN, f64::max);
    assert!((top - 2852.0).abs() < 1.0, "the outline reaches the crest: {top}");
}

/// Fig. 13: at every elevation, residual = after − before; returns the elevations of the slab
/// rows at the central section.
fn check_residual_slab(out: &Path) -> Vec<f64> {
    let t = Table::read(&out.join("fig13_residual_slab.csv"));
    let rows = |state: &str| -> Vec<usize> { (0..t.rows.len()).filter(|&r| t.rows[r][0] == state).collect() };
    let (before, after, residual) = (
        rows("before the quake"),
        rows("after the quake"),
        rows("residual"),
    );
    assert!(!before.is_empty());
    assert_eq!(before.len(), after.len());
    assert_eq!(before.len(), residual.len());
    let mut largest = 0.0_f64;
    for ((&b, &a), &r) in before.iter().zip(&after).zip(&residual) {
        assert_eq!(t.num(b, "z_m"), t.num(r, "z_m"));
        for col in ["sigma_slope_Pa", "sigma_axis_Pa", "deflection_m"] {
            let diff = t.num(a, col) - t.num(b, col);
            let scale = t.num(a, col).abs().max(t.num(b, col).abs());
            assert!(
                (t.num(r, col) - diff).abs() <= 1e-9 * scale + 1e-300,
                "{col} at z = {}: {} vs {diff}",
                t.num(r, "z_m"),
                t.num(r, col)
            );
        }
        largest = largest.max(t.num(r, "sigma_axis_Pa").abs());
    }
    assert!(largest > 0.0, "the quake changes the slab's axial stress");
    before.iter().map(|&r| t.num(r, "z_m")).collect()
}

/// `quake_probes.csv`: F-A is the central slab row nearest 2813 m, I-B the leftmost (smallest
/// y) interface element of the row nearest 2809 m, the others in the central section. Returns
/// name → element id.
fn check_probes(out: &Path, slab_rows: &[f64]) -> HashMap<String, String> {
    let p = Table::read(&out.join("quake_probes.csv"));
    p.assert_finite(&["name", "element", "at"], "quake_probes.csv");
    assert_eq!(p.rows.len(), 5, "every probe located");
    let find = |name: &str| (0..p.rows.len()).find(|&r| p.rows[r][0] == name).unwrap();
    let nearest = |rows: &[f64], z: f64| {
        rows.iter()
            .copied()
            .min_by(|a, b| (a - z).abs().total_cmp(&(b - z).abs()))
    };
    let fa = find("F-A");
    assert_eq!(p.rows[fa][1], "slab");
    assert_eq!(Some(p.num(fa, "z_m")), nearest(slab_rows, 2813.0));

    let iface = Table::read(&out.join("fig15_interface_residual.csv"));
    iface.assert_finite(&[], "fig15_interface_residual.csv");
    let centres: Vec<(f64, f64)> = (0..iface.rows.len())
        .map(|r| (iface.num(r, "y_m"), iface.num(r, "z_m")))
        .collect();
    let z_rows: Vec<f64> = centres.iter().map(|c| c.1).collect();
    let ib = find("I-B");
    assert_eq!(p.rows[ib][2], "left_bank");
    let z_ib = nearest(&z_rows, 2809.0).unwrap();
    assert!(
        (p.num(ib, "z_m") - z_ib).abs() < 1e-3,
        "I-B at {} m",
        p.num(ib, "z_m")
    );
    let leftmost = centres
        .iter()
        .filter(|c| (c.1 - z_ib).abs() < 1e-3)
        .map(|c| c.0)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(p.num(ib, "y_m"), leftmost, "I-B at the left bank");

    let (y0, y1) = centres
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), c| (a.min(c.0), b.max(c.0)));
    for name in ["I-A", "I-C", "I-D"] {
        let r = find(name);
        assert_eq!(p.rows[r][2], "centre");
        assert!(
            (p.num(r, "y_m") - 0.5 * (y0 + y1)).abs() < 60.0,
            "{name} in the central section"
        );
    }
    let top = z_rows.iter().copied().fold(f64::MIN, f64::max);
    assert_eq!(p.num(find("I-D"), "z_m"), top, "I-D in the crest row");
    (0..p.rows.len())
        .map(|r| (p.rows[r][0].clone(), p.rows[r][3].clone()))
        .collect()
}

/// The histories: one row per time step plus t = 0; the first and last rows are the states
/// before and after the quake of the residual table.
fn check_histories(out: &Path, probes: &HashMap<String, String>) {
    let steps = (DURATION / DT).round() as usize;
    let iface = Table::read(&out.join("fig15_interface_residual.csv"));
    let fa = Table::read(&out.join("fig14_slab_probe_F-A.csv"));
    assert_eq!(fa.rows.len(), steps + 1);
    for name in ["I-A", "I-B", "I-C", "I-D"] {
        let h = Table::read(&out.join(format!("fig18_interface_probe_{name}.csv")));
        assert_eq!(h.rows.len(), steps + 1, "{name}: one row per time step and t = 0");
        assert_eq!(h.num(0, "t_s"), 0.0);
        assert!((h.num(steps, "t_s") - DURATION).abs() < 1e-9);
        for r in 1..=steps {
            assert!((h.num(r, "t_s") - r as f64 * DT).abs() < 1e-9, "{name} row {r}");
        }
        let e = (0..iface.rows.len())
            .find(|&r| iface.rows[r][0] == probes[name])
            .unwrap();
        assert_eq!(h.num(0, "opening_m"), iface.num(e, "opening_before_m"), "{name}");
        assert_eq!(
            h.num(steps, "opening_m"),
            iface.num(e, "opening_after_m"),
            "{name}"
        );
        let slip = h.num(steps, "delta_s_m") - h.num(0, "delta_s_m");
        assert!(
            (slip - iface.num(e, "delta_s_m")).abs() <= 1e-12 * slip.abs().max(1e-12),
            "{name}"
        );
        if name == "I-A" {
            assert!(
                h.num(0, "sigma_n_Pa") > 0.0,
                "I-A below the water line is compressed"
            );
        }
    }
    let open = Table::read(&out.join("fig20_opening.csv"));
    assert_eq!(open.rows.len(), steps + 1);
    assert_eq!(open.header.len(), 5, "t and one column per interface probe");
}
