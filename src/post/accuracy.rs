//! Accuracy against cost (`cfrd accuracy`, `scripts/accuracy_cost.sh`): the error of a run's
//! seed-figure results against a reference run of the same dam, next to the run's wall time.
//!
//! Quantities (from each run's `output.profiles` tables, [`crate::post::profiles`]):
//!
//! * slab stress along the slope σ_s, along the axis σ_a and the deflection at the central
//!   section after impoundment (seed Figs. 8, 9; `fig08_slab_stress.csv`): the largest
//!   difference over the reference's slab points, the run interpolated linearly in elevation
//!   onto them (so runs on other meshes compare too), relative to the reference's largest
//!   magnitude;
//! * the crest settlement after impoundment (the highest point of the central vertical of seed
//!   Fig. 7, `fig07_dam_displacement.csv`): relative difference.
//!
//! With [`Study::Quake`] (`cfrd accuracy --quake`) the same four quantities are those the
//! earthquake leaves behind: the slab stresses and deflection
//! induced by the residual deformation (after − before the quake, seed Fig. 13, the rows
//! `residual` of `fig13_residual_slab.csv`) and the residual crest settlement (−u_z of
//! `residual_displacement_m` in `quake_summary.json`).
//!
//! The wall time is `total_seconds` of the run's `summary.json`.

use crate::plot::{Figure, Panel, Series};
use crate::post::profiles::{read_slab_csv, SlabTableRow};
use std::path::{Path, PathBuf};

/// The state compared by the static study: the end of the schedule.
const STATE: &str = "after impoundment";

/// What a study compares (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Study {
    /// The state after impoundment (seed Figs. 7–9).
    Static,
    /// What the earthquake leaves: residual slab stresses, deflection and crest settlement
    /// (seed Fig. 13).
    Quake,
}

impl Study {
    /// The slab table, its state label and a word for the figure's title.
    fn slab_source(self) -> (&'static str, &'static str, &'static str) {
        match self {
            Study::Static => ("fig08_slab_stress.csv", STATE, "after impoundment"),
            Study::Quake => ("fig13_residual_slab.csv", "residual", "residual after the quake"),
        }
    }
}

/// The compared quantities of one run (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutcome {
    /// Slab rows after impoundment, by elevation.
    slab: Vec<SlabTableRow>,
    /// Crest settlement after impoundment (m, down +).
    crest_settlement: f64,
    /// Wall time of the run (s).
    pub wall_seconds: f64,
}

/// Relative errors of one run against the reference (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Errors {
    /// σ_s along the slope.
    pub sigma_slope: f64,
    /// σ_a along the axis.
    pub sigma_axis: f64,
    /// Slab deflection.
    pub deflection: f64,
    /// Crest settlement.
    pub crest_settlement: f64,
}

impl Errors {
    /// The errors in the order of [`QUANTITIES`].
    pub fn values(&self) -> [f64; 4] {
        [
            self.sigma_slope,
            self.sigma_axis,
            self.deflection,
            self.crest_settlement,
        ]
    }
}

/// Names of the compared quantities (CSV columns and panel titles).
pub const QUANTITIES: [&str; 4] = ["sigma_slope", "sigma_axis", "deflection", "crest_settlement"];

/// Reads the quantities of `study` from the finished run in `dir`.
pub fn read_run(dir: &Path, study: Study) -> Result<RunOutcome, String> {
    let (table, state, _) = study.slab_source();
    let mut slab: Vec<SlabTableRow> = read_slab_csv(&dir.join(table))
        .map_err(|e| e.to_string())?
        .into_iter()
        .filter(|r| r.state == state)
        .collect();
    slab.sort_by(|a, b| a.z.total_cmp(&b.z));
    if slab.is_empty() {
        return Err(format!("{}: no slab rows '{state}' in {table}", dir.display()));
    }
    let crest_settlement = match study {
        Study::Static => crest_settlement(&dir.join("fig07_dam_displacement.csv"))?,
        Study::Quake => residual_crest_settlement(&dir.join("quake_summary.json"))?,
    };
    Ok(RunOutcome {
        slab,
        crest_settlement,
        wall_seconds: json_number(&dir.join("summary.json"), "total_seconds")?,
    })
}

/// −u_z of `residual_displacement_m` in a `quake_summary.json` (m, down +).
fn residual_crest_settlement(path: &Path) -> Result<f64, String> {
    let json = read_json(path)?;
    json.get("residual_displacement_m")
        .and_then(|u| u.get(2))
        .and_then(serde_json::Value::as_f64)
        .map(|uz| -uz)
        .ok_or_else(|| format!("{}: no residual_displacement_m", path.display()))
}

/// −u_z at the highest row after impoundment of a `fig07_dam_displacement.csv`.
fn crest_settlement(path: &Path) -> Result<f64, String> {
    let text = crate::input::read_text(path, crate::input::MAX_SCENE_BYTES)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut top: Option<(f64, f64)> = None;
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |k: usize| f.get(k).and_then(|v| v.trim().parse::<f64>().ok());
        if let (Some(&STATE), Some(z), Some(uz)) = (f.first(), num(1), num(3)) {
            if top.is_none_or(|(zt, _)| z > zt) {
                top = Some((z, -uz));
            }
        }
    }
    top.map(|(_, s)| s)
        .ok_or_else(|| format!("{}: no row '{STATE}' with z_m and uz_m", path.display()))
}

/// A JSON file.
fn read_json(path: &Path) -> Result<serde_json::Value, String> {
    let text = crate::input::read_text(path, crate::input::MAX_SCENE_BYTES)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// The number `key` of a JSON file (e.g. `total_seconds` of a `summary.json`).
fn json_number(path: &Path, key: &str) -> Result<f64, String> {
    read_json(path)?
        .get(key)
        .and_then(serde_json::Value::as_f64)
        .ok_or_else(|| format!("{}: no {key}", path.display()))
}

/// `y` at `z` on the polyline `(z, y)` sorted by z; constant beyond its ends.
fn interpolate(points: &[(f64, f64)], z: f64) -> f64 {
    let k = points.partition_point(|p| p.0 < z);
    match k {
        0 => points[0].1,
        k if k == points.len() => points[k - 1].1,
        k => {
            let ((z0, y0), (z1, y1)) = (points[k - 1], points[k]);
            y0 + (y1 - y0) * (z - z0) / (z1 - z0)
        }
    }
}

/// Largest |run − reference| over the reference's points, over the reference's largest
/// magnitude, for the quantity `pick`.
fn profile_error(run: &[SlabTableRow], reference: &[SlabTableRow], pick: fn(&SlabTableRow) -> f64) -> f64 {
    let line: Vec<(f64, f64)> = run.iter().map(|r| (r.z, pick(r))).collect();
    let scale = reference.iter().map(|r| pick(r).abs()).fold(0.0, f64::max);
    let worst = reference
        .iter()
        .map(|r| (interpolate(&line, r.z) - pick(r)).abs())
        .fold(0.0, f64::max);
    worst / scale
}

/// The errors of `run` against `reference` (see the module docs).
pub fn errors(run: &RunOutcome, reference: &RunOutcome) -> Errors {
    Errors {
        sigma_slope: profile_error(&run.slab, &reference.slab, |r| r.sigma_slope),
        sigma_axis: profile_error(&run.slab, &reference.slab, |r| r.sigma_axis),
        deflection: profile_error(&run.slab, &reference.slab, |r| r.deflection),
        crest_settlement: (run.crest_settlement - reference.crest_settlement).abs()
            / reference.crest_settlement.abs(),
    }
}

/// Writes `accuracy_cost.csv` and `accuracy_cost.png` into `out` for the runs `(label, dir)`
/// against the run in `reference`, comparing what `study` names; returns the files written.
pub fn write_study(
    study: Study,
    reference: &Path,
    runs: &[(String, PathBuf)],
    out: &Path,
) -> Result<Vec<PathBuf>, String> {
    let reference = read_run(reference, study)?;
    let mut rows = Vec::new();
    for (label, dir) in runs {
        let run = read_run(dir, study)?;
        rows.push((label.clone(), run.wall_seconds, errors(&run, &reference)));
    }
    let mut csv = format!("run,wall_s,{}\n", QUANTITIES.join(","));
    csv += &format!("reference,{:.1},0,0,0,0\n", reference.wall_seconds);
    for (label, wall, e) in &rows {
        let v = e.values().map(|x| format!("{x:.3e}"));
        csv += &format!("{label},{wall:.1},{}\n", v.join(","));
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let files = [out.join("accuracy_cost.csv"), out.join("accuracy_cost.png")];
    crate::input::write_replacing(&files[0], csv.as_bytes())
        .map_err(|e| format!("{}: {e}", files[0].display()))?;
    figure(&rows, reference.wall_seconds, study.slab_source().2)
        .save_png(&files[1])
        .map_err(|e| e.to_string())?;
    Ok(files.to_vec())
}

/// The family of a run label: the part before its last `_` (`steps_4` → `steps`), or the label.
fn family(label: &str) -> &str {
    label.rsplit_once('_').map_or(label, |(f, _)| f)
}

/// One panel per quantity: log10 of the relative error against the wall time, one marker
/// series per family of runs, and the reference run's wall time as a vertical line over the
/// whole decades that hold the errors (so the axis spans at least one decade).
fn figure(rows: &[(String, f64, Errors)], reference_wall: f64, state: &str) -> Figure {
    let mut families: Vec<&str> = Vec::new();
    for (label, _, _) in rows {
        if !families.contains(&family(label)) {
            families.push(family(label));
        }
    }
    let title = format!("Error against the reference run ({reference_wall:.0} s) and wall time, {state}");
    let mut fig = Figure::new(title).columns(2);
    for (q, name) in QUANTITIES.iter().enumerate() {
        let mut panel = Panel::new(*name, "wall time (s)", "log10 relative error").legend_lower_right();
        for f in &families {
            let points = rows
                .iter()
                .filter(|(l, _, e)| family(l) == *f && e.values()[q] > 0.0)
                .map(|(_, w, e)| (*w, e.values()[q].log10()))
                .collect();
            panel.push(Series::markers(*f, points));
        }
        let logs = rows
            .iter()
            .map(|(_, _, e)| e.values()[q])
            .filter(|e| *e > 0.0)
            .map(f64::log10);
        let (lo, hi) = logs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
        if lo.is_finite() {
            let (lo, hi) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
            panel.push(Series::line(
                "reference run",
                vec![(reference_wall, lo), (reference_wall, hi)],
            ));
        }
        fig.push(panel);
    }
    fig
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(z: f64, s: f64) -> SlabTableRow {
        SlabTableRow {
            state: STATE.into(),
            z,
            sigma_slope: s,
            sigma_axis: 2.0 * s,
            deflection: -s,
        }
    }

    #[test]
    fn profiles_on_other_elevations_are_interpolated_onto_the_reference() {
        let reference = RunOutcome {
            slab: vec![row(0.0, 0.0), row(10.0, 10.0), row(20.0, 0.0)],
            crest_settlement: 0.5,
            wall_seconds: 9.0,
        };
        // a coarser run: the hat sampled at 0 and 20 only misses the peak by 10
        let coarse = RunOutcome {
            slab: vec![row(0.0, 0.0), row(20.0, 0.0)],
            crest_settlement: 0.4,
            wall_seconds: 1.0,
        };
        let e = errors(&coarse, &reference);
        assert_eq!(e.sigma_slope, 1.0);
        assert_eq!(e.sigma_axis, 1.0);
        assert_eq!(e.deflection, 1.0);
        assert!((e.crest_settlement - 0.2).abs() < 1e-15);
        // a finer run on the same linear hat: no error at the reference's points
        let fine = RunOutcome {
            slab: [0.0, 5.0, 10.0, 15.0, 20.0]
                .map(|z: f64| row(z, 10.0 - (z - 10.0).abs()))
                .to_vec(),
            ..reference.clone()
        };
        assert_eq!(errors(&fine, &reference).values(), [0.0; 4]);
        assert_eq!(errors(&reference, &reference).values(), [0.0; 4]);
    }

    #[test]
    fn a_quake_run_is_read_from_its_residual_tables() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let slab = "state,z_m,sigma_slope_Pa,sigma_axis_Pa,deflection_m\n\
                    before the quake,10,1,2,3\nresidual,20,-4,-5,0.25\nresidual,10,-6,-7,0.5\n";
        std::fs::write(d.join("fig13_residual_slab.csv"), slab).unwrap();
        std::fs::write(
            d.join("quake_summary.json"),
            r#"{"residual_displacement_m": [0.1, 0.0, -0.18]}"#,
        )
        .unwrap();
        std::fs::write(d.join("summary.json"), r#"{"total_seconds": 600.5}"#).unwrap();
        let run = read_run(d, Study::Quake).expect("quake run");
        let z: Vec<f64> = run.slab.iter().map(|r| r.z).collect();
        assert_eq!(z, [10.0, 20.0], "the residual rows, by elevation");
        assert_eq!(run.slab[0].sigma_axis, -7.0);
        assert_eq!(run.crest_settlement, 0.18);
        assert_eq!(run.wall_seconds, 600.5);
    }

    #[test]
    fn families_group_the_variants_of_one_setting() {
        assert_eq!(family("steps_16"), "steps");
        assert_eq!(family("stol_1.0e-5"), "stol");
        assert_eq!(family("gauss"), "gauss");
    }

    #[test]
    fn a_run_without_its_tables_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let err = read_run(dir.path(), Study::Static).unwrap_err();
        assert!(err.contains("fig08_slab_stress.csv"), "{err}");
        let err = read_run(dir.path(), Study::Quake).unwrap_err();
        assert!(err.contains("fig13_residual_slab.csv"), "{err}");
    }
}
