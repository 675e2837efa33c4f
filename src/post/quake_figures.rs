//! The seed paper's dynamic outputs (seed Figs. 12–20) from
//! the results of a run with an earthquake stage: the residual deformation (state at the end of
//! the quake minus the state before it) of the dam section, the slab and the slab–cushion
//! interface, and the time histories of the named probes ([`crate::post::profiles::Probe`]). CSV
//! tables and PNG plots, written by `cfrd run` next to `quake_crest.csv` ([`crate::post::quake`]).
//!
//! | output | seed figure | file |
//! |---|---|---|
//! | outline of the central cross-section before and after the quake, residual displacement magnified by the factor in the header | 12 | `fig12_outline.csv/.png` |
//! | slab σ_s, σ_a and deflection vs elevation at the central section before, after and induced by the residual deformation (after − before) | 13 | `fig13_residual_slab.csv/.png` |
//! | σ_s, σ_a history of each slab probe (F-A) | 14 | `fig14_slab_probe_NAME.csv/.png` |
//! | residual interface shear displacement (δ_s, δ_a) of every interface element, vectors on the unfolded face | 15 | `fig15_interface_residual.csv`, `fig15_interface_slip.png` |
//! | residual normal displacement excluding opening (Δδ_n − Δopening) along the axis per elevation row | 16 | `fig16_interface_normal.csv/.png` |
//! | slab–cushion opening after the quake along the axis per elevation row | 17 | `fig17_interface_opening.csv/.png` |
//! | σ_n, τ_s, τ_a and δ_s, δ_a, δ_n, opening history of each interface probe (I-B, I-C) | 18, 19 | `fig18_interface_probe_NAME.csv/.png` |
//! | opening history of every interface probe (I-D at the crest) | 20 | `fig20_opening.csv/.png` |
//! | where each probe lies (element id, centre) | – | `quake_probes.csv` |
//!
//! The three interface tables `fig15/16/17_*.csv` hold the same rows (one per interface element).
//!
//! **Sampling.** The probe histories (Figs. 14, 18–20) are those of every time step of a run
//! ([`crate::post::quake_probes`]); the residual state is that of the results steps before and after
//! the quake, and histories drawn from results files alone are sampled at their results steps,
//! every `output_every` time steps (`earthquake: { output_every: N }`), plus t = 0, the state
//! before the quake (the end of the stage before it). Each history CSV states its sampling in a
//! `#` comment line above the header.
//!
//! Conventions are those of [`crate::post::profiles`] (central section, slab frame, tension +,
//! interface jump cushion relative to slab, δ_n > 0 opening, σ_n compression +).

use crate::mesh::Mesh;
use crate::plot::{Figure, Panel, Series};
use crate::post::output::{csv_out, png_out};
use crate::post::profiles::{
    body_nodes, centre, elements_with_prefix, elevation_groups, section_y, slab_profiles, ProfilesSpec,
    StageFields,
};
use crate::post::quake_fields::{read_quake_fields, residual, QuakeFields};
use crate::post::quake_probes::{probe_elements, write_probe_figures, ProbeHistory, QuakeProbe};
use crate::scene::Scene;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A round magnification (1, 2 or 5 × 10ᵏ, at least 1) that draws a largest displacement of
/// `umax` as about 5 % of `size`.
pub fn magnification(size: f64, umax: f64) -> f64 {
    if umax <= 0.0 || !umax.is_finite() {
        return 1.0;
    }
    let raw = 0.05 * size / umax;
    let decade = 10f64.powf(raw.log10().floor());
    let mantissa = [5.0, 2.0, 1.0]
        .into_iter()
        .find(|m| m * decade <= raw)
        .unwrap_or(1.0);
    (mantissa * decade).max(1.0)
}

/// The outline of the dam body's cross-section in the node plane nearest to the central
/// section: per elevation (node rows within 1 mm), the most upstream nodes from the base up,
/// then the most downstream nodes from the crest down, closed. Node indices.
pub fn section_outline(mesh: &Mesh, spec: &ProfilesSpec) -> Vec<usize> {
    let Some(y) = section_y(mesh, spec) else {
        return Vec::new();
    };
    let body = body_nodes(mesh, spec);
    let nodes: Vec<usize> = (0..mesh.num_nodes()).filter(|&n| body[n]).collect();
    let Some(plane) = nodes
        .iter()
        .map(|&n| mesh.coords[n][1])
        .min_by(|a, b| (a - y).abs().total_cmp(&(b - y).abs()))
    else {
        return Vec::new();
    };
    let tol = 1e-6 * plane.abs().max(1.0);
    let mut rows: std::collections::BTreeMap<i64, (usize, usize)> = Default::default();
    for &n in nodes.iter().filter(|&&n| (mesh.coords[n][1] - plane).abs() < tol) {
        let x = |m: usize| mesh.coords[m][0];
        let key = (mesh.coords[n][2] * 1000.0).round() as i64;
        let row = rows.entry(key).or_insert((n, n));
        if x(n) < x(row.0) {
            row.0 = n;
        }
        if x(n) > x(row.1) {
            row.1 = n;
        }
    }
    let mut outline: Vec<usize> = rows.values().map(|r| r.0).collect();
    outline.extend(rows.values().rev().map(|r| r.1));
    if let Some(&first) = outline.first() {
        outline.push(first);
    }
    outline
}

/// What the residual figures are drawn from, and where.
struct QuakeOut<'a> {
    mesh: &'a Mesh,
    spec: &'a ProfilesSpec,
    q: &'a QuakeFields,
    /// The residual state, after − before the quake.
    res: StageFields,
    dir: &'a Path,
}

/// Fig. 12: the section outline before and after the quake.
fn fig12(out: &QuakeOut, files: &mut Vec<PathBuf>) -> Result<(), String> {
    let (mesh, dir, res) = (out.mesh, out.dir, &out.res);
    let outline = section_outline(mesh, out.spec);
    let du = |n: usize| [res.displacement[3 * n], res.displacement[3 * n + 2]];
    let zs = outline.iter().map(|&n| mesh.coords[n][2]);
    let height = zs.clone().fold(f64::NEG_INFINITY, f64::max) - zs.fold(f64::INFINITY, f64::min);
    let umax = outline
        .iter()
        .map(|&n| du(n)[0].hypot(du(n)[1]))
        .fold(0.0, f64::max);
    let f = magnification(height, umax);
    let mut csv = format!(
        "# central section; before = the mesh coordinates of the section (the static displacement \
         is not drawn), after = before + {f} x the residual displacement (after - before the quake)\n\
         node_id,x_m,z_m,ux_residual_m,uz_residual_m,x_after_m,z_after_m\n"
    );
    let (mut before, mut after) = (Vec::new(), Vec::new());
    for &n in &outline {
        let [x, z] = [mesh.coords[n][0], mesh.coords[n][2]];
        let [ux, uz] = du(n);
        let _ = writeln!(
            csv,
            "{},{x},{z},{ux},{uz},{},{}",
            mesh.node_ids[n],
            x + f * ux,
            z + f * uz
        );
        before.push((x, z));
        after.push((x + f * ux, z + f * uz));
    }
    csv_out(dir, files, "fig12_outline.csv", csv)?;
    let panel = Panel::new(
        format!("Central cross-section, residual displacement x {f}"),
        "x (m, downstream)",
        "z (m)",
    )
    .with(Series::line("before the quake", before))
    .with(Series::line("after the quake", after));
    let fig = Figure::new("Dam outline before and after the earthquake (seed Fig. 12)")
        .with(panel)
        .columns(1);
    png_out(dir, files, "fig12_outline.png", fig)?;
    Ok(())
}

/// Fig. 13: slab profiles before, after and induced by the residual deformation.
fn fig13(out: &QuakeOut, files: &mut Vec<PathBuf>) -> Result<(), String> {
    let states = [
        ("before the quake", &out.q.before),
        ("after the quake", out.q.after()),
        ("residual", &out.res),
    ];
    let (csv, panels) = slab_profiles(out.mesh, out.spec, &states);
    csv_out(out.dir, files, "fig13_residual_slab.csv", csv)?;
    let mut fig =
        Figure::new("Slab at the central section: residual = after - before the quake (seed Fig. 13)");
    for p in panels {
        fig.push(p);
    }
    png_out(out.dir, files, "fig13_residual_slab.png", fig.columns(3))?;
    Ok(())
}

/// Figs. 15–17: the residual interface state of every interface element, as a table and as
/// plots over the unfolded face (y along the axis, z up).
fn figs15_17(out: &QuakeOut, files: &mut Vec<PathBuf>) -> Result<(), String> {
    let (mesh, dir, res) = (out.mesh, out.dir, &out.res);
    let (before, after) = (&out.q.before, out.q.after());
    let iface = elements_with_prefix(mesh, &out.spec.interface_prefix);
    let mut csv = String::from(
        "element_id,x_m,y_m,z_m,delta_s_m,delta_a_m,delta_n_m,opening_before_m,opening_after_m,normal_excluding_opening_m\n",
    );
    for &e in &iface {
        let c = centre(mesh, e);
        let d = &res.interface_jump[3 * e..3 * e + 3];
        let normal = d[2] - res.interface_opening[e];
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{normal}",
            mesh.elements[e].id,
            c[0],
            c[1],
            c[2],
            d[0],
            d[1],
            d[2],
            before.interface_opening[e],
            after.interface_opening[e]
        );
    }
    for name in [
        "fig15_interface_residual.csv",
        "fig16_interface_normal.csv",
        "fig17_interface_opening.csv",
    ] {
        csv_out(dir, files, name, csv.clone())?;
    }
    png_out(
        dir,
        files,
        "fig15_interface_slip.png",
        slip_vectors(mesh, &iface, res),
    )?;
    let rows = face_rows(mesh, &iface);
    let normal = |e: usize| (res.interface_jump[3 * e + 2] - res.interface_opening[e]) * 1e3;
    let fig16 = face_lines(
        mesh,
        &rows,
        "Residual normal displacement (seed Fig. 16)",
        "delta_n - opening (mm, opening +)",
        normal,
    );
    png_out(dir, files, "fig16_interface_normal.png", fig16)?;
    let fig17 = face_lines(
        mesh,
        &rows,
        "Slab-cushion opening after the quake (seed Figs. 16, 17)",
        "opening (mm)",
        |e| after.interface_opening[e] * 1e3,
    );
    png_out(dir, files, "fig17_interface_opening.png", fig17)?;
    Ok(())
}

/// At most 8 elevation rows of `elements` (every k-th row, the top one always included).
fn face_rows(mesh: &Mesh, elements: &[usize]) -> Vec<(f64, Vec<usize>)> {
    let groups = elevation_groups(mesh, elements);
    let step = groups.len().div_ceil(8).max(1);
    let n = groups.len();
    groups
        .into_iter()
        .enumerate()
        .filter(|(i, _)| (n - 1 - i).is_multiple_of(step))
        .map(|(_, g)| g)
        .collect()
}

/// One line per elevation row: `value` of each element against its centre y.
fn face_lines(
    mesh: &Mesh,
    rows: &[(f64, Vec<usize>)],
    title: &str,
    x_label: &str,
    value: impl Fn(usize) -> f64,
) -> Figure {
    let mut panel = Panel::new(
        "along the dam axis, one line per elevation",
        "y (m, dam axis)",
        x_label,
    );
    for (z, row) in rows {
        let mut points: Vec<(f64, f64)> = row.iter().map(|&e| (centre(mesh, e)[1], value(e))).collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        panel.push(Series::line(format!("z = {z:.0} m"), points));
    }
    Figure::new(title).with(panel).columns(1)
}

/// Residual shear-displacement vectors (δ_a, δ_s) at the element centres on the unfolded face,
/// scaled so that the longest is 5 % of the face's width.
fn slip_vectors(mesh: &Mesh, iface: &[usize], res: &StageFields) -> Figure {
    let centres: Vec<(f64, f64)> = iface
        .iter()
        .map(|&e| (centre(mesh, e)[1], centre(mesh, e)[2]))
        .collect();
    let width = centres.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max)
        - centres.iter().map(|c| c.0).fold(f64::INFINITY, f64::min);
    let slip = |e: usize| (res.interface_jump[3 * e + 1], res.interface_jump[3 * e]);
    let longest = iface
        .iter()
        .map(|&e| slip(e).0.hypot(slip(e).1))
        .fold(0.0, f64::max);
    let k = magnification(width, longest);
    let mut segments = Vec::new();
    for (&e, &(y, z)) in iface.iter().zip(&centres) {
        let (da, ds) = slip(e);
        segments.extend([(y, z), (y + k * da, z + k * ds)]);
    }
    let panel = Panel::new(
        format!(
            "cushion relative to slab, (delta_a, delta_s) x {k}, longest {:.1} mm",
            longest * 1e3
        ),
        "y (m, dam axis)",
        "z (m), up the slope",
    )
    .with(Series::markers("", centres))
    .with(Series::segments("residual shear displacement", segments));
    Figure::new("Residual interface shear displacement (seed Fig. 15)")
        .with(panel)
        .columns(1)
}

/// The probes' elements (`quake_probes.csv`, [`crate::post::quake_probes::probe_elements`]).
fn write_probe_table(
    mesh: &Mesh,
    spec: &ProfilesSpec,
    probes: &[QuakeProbe],
    dir: &Path,
    files: &mut Vec<PathBuf>,
) -> Result<(), String> {
    let mut csv = String::from("name,element,at,element_id,x_m,y_m,z_m\n");
    for p in probes {
        let Some(probe) = spec.probes.iter().find(|q| q.name == p.name) else {
            continue;
        };
        let c = centre(mesh, p.element);
        let kind = serde_json::to_value(probe.element).map_err(|e| e.to_string())?;
        let at = serde_json::to_value(probe.at).map_err(|e| e.to_string())?;
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{}",
            probe.name,
            kind.as_str().unwrap_or_default(),
            at.as_str().unwrap_or_default(),
            mesh.elements[p.element].id,
            c[0],
            c[1],
            c[2]
        );
    }
    csv_out(dir, files, "quake_probes.csv", csv)?;
    Ok(())
}

/// Writes the tables and plots of the module docs into `dir` from the closed results files `h5s`
/// (the parts of a run, [`read_quake_fields`]) and the probes' state at every time step
/// (`steps`, [`crate::solver::SolveReport::probes`]; when empty or not of these probes, the
/// probe histories are read at the results steps); returns the files written (none when no
/// quake is found or the mesh has no face slab; the probe histories alone when the results
/// lack the state before the quake, as those of a run restarted inside it do).
pub fn write_quake_figures(
    scene: &Scene,
    spec: &ProfilesSpec,
    h5s: &[PathBuf],
    steps: &[Vec<f64>],
    dir: &Path,
) -> Result<Vec<PathBuf>, String> {
    // without a face slab (no central section) none of the seed's dam figures applies
    if section_y(&scene.mesh, spec).is_none() {
        return Ok(Vec::new());
    }
    let mesh = &scene.mesh;
    let mut files = Vec::new();
    let q = read_quake_fields(scene, h5s)?;
    if let Some(q) = &q {
        let out = QuakeOut {
            mesh,
            spec,
            q,
            res: residual(&q.before, q.after()),
            dir,
        };
        fig12(&out, &mut files)?;
        fig13(&out, &mut files)?;
        if !q.before.interface_jump.is_empty() && !q.after().interface_jump.is_empty() {
            figs15_17(&out, &mut files)?;
        }
    }
    // a run restarted inside the quake lacks the state before it in its results, but its
    // probe histories are whole
    let probes = probe_elements(mesh, spec);
    let clock = crate::post::quake_clock::QuakeClock::new(scene);
    let stages = (!clock.is_empty()).then(|| clock.names(scene));
    let history = stages
        .and_then(|stages| ProbeHistory::from_steps(&stages, &probes, steps))
        .or_else(|| q.as_ref().map(|q| ProbeHistory::from_results(q, &probes)));
    if let Some(h) = history {
        write_probe_table(mesh, spec, &probes, dir, &mut files)?;
        write_probe_figures(mesh, &probes, &h, dir, &mut files)?;
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn magnification_is_round_and_draws_the_largest_displacement_at_about_5_percent() {
        assert_eq!(magnification(171.0, 0.5), 10.0);
        assert_eq!(magnification(171.0, 0.01), 500.0);
        assert_eq!(magnification(100.0, 0.02), 200.0);
        assert_eq!(magnification(10.0, 5.0), 1.0);
        assert_eq!(magnification(10.0, 0.0), 1.0);
        for (size, u) in [(171.0, 0.37), (355.0, 0.0042), (50.0, 1e-5)] {
            let f = magnification(size, u);
            assert!(
                f * u <= 0.05 * size * (1.0 + 1e-12) && f * u > 0.01 * size,
                "{size} {u} {f}"
            );
        }
    }

    #[test]
    fn residual_is_after_minus_before_field_by_field() {
        let before = StageFields {
            name: "impound_2".into(),
            displacement: vec![1.0, 2.0, 3.0],
            stress: vec![-1.0; 6],
            interface_opening: vec![0.5],
            ..Default::default()
        };
        let after = StageFields {
            name: "quake".into(),
            displacement: vec![1.5, 1.0, 3.25],
            stress: vec![-3.0; 6],
            interface_opening: vec![0.75],
            interface_jump: vec![1.0, 2.0, 3.0],
            ..Default::default()
        };
        let r = residual(&before, &after);
        assert_eq!(r.displacement, vec![0.5, -1.0, 0.25]);
        assert_eq!(r.stress, vec![-2.0; 6]);
        assert_eq!(r.interface_opening, vec![0.25]);
        assert!(
            r.interface_jump.is_empty(),
            "a field missing before the quake has no residual"
        );
    }
}
