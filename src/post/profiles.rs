//! The seed paper's static outputs from a run's stage results (seed Figs. 7–11): profiles at
//! the central section of the slab, the interface under it and the dam body, and the stress
//! path of named interface probes through the stages. CSV tables and PNG plots.
//!
//! What is where:
//!
//! | output | seed figure | file |
//! |---|---|---|
//! | settlement and horizontal displacement on the vertical through the crest centre, end of construction and after impoundment | 7 | `fig07_dam_displacement.csv/.png` |
//! | slab stress along the slope σ_s and along the axis σ_a vs elevation, end of construction and after impoundment | 8 | `fig08_slab_stress.csv/.png` |
//! | slab deflection (normal to the slab, towards the dam positive) vs elevation | 9 | `fig09_slab_deflection.csv/.png` |
//! | σ_n–τ path and shear displacement vs stress ratio of each probe interface element through the stages | 10 | `fig10_probe_NAME.csv/.png` |
//! | interface jumps, tractions and opening vs elevation after impoundment | 11 | `fig11_interface.csv/.png` |
//!
//! Conventions (documented choices, \[INF\]):
//! * **Slab and interface elements** are the elements of the blocks whose names start with
//!   [`ProfilesSpec::slab_prefix`] (solid) and [`ProfilesSpec::interface_prefix`] (interface).
//! * **Central section**: the plane y = [`ProfilesSpec::section_y`], by default the middle of the
//!   slab's y-range; an element is in the section when its y-range contains the plane; elements
//!   at the same elevation (both sides of a node line) are averaged.
//! * **Slab frame**: the slab normal is the element's thinnest direction (one element through
//!   the thickness), oriented towards +x (into the dam for an upstream face with x downstream);
//!   the in-plane axes follow the interface frame rule (spec (E3)): e_s up-slope, e_a along the
//!   dam axis. σ_s = e_sᵀσe_s, σ_a = e_aᵀσe_a, tension positive (project convention).
//! * **Deflection** is the mean displacement of the element's nodes along the slab normal
//!   (towards the dam positive), counted from the slab's placement.
//! * **End of construction** is the last stage whose name does not start with
//!   [`ProfilesSpec::impoundment_prefix`]; **after impoundment** is the last stage.

use crate::element::interface_frame::{FrameAxes, LocalFrame};
use crate::mesh::Mesh;
use crate::plot::{Figure, Panel, PlotError, Series};
use crate::post::output::{csv_out, png_out, safe_name, OutputError};
pub use crate::scene::output_spec::{Probe, ProbeAt, ProbeElement, ProfilesSpec};
use nalgebra::{Matrix3, Vector3};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The fields of one stage in global input order (as in the results file).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StageFields {
    /// Stage name.
    pub name: String,
    /// Node displacement, 3 per node (m).
    pub displacement: Vec<f64>,
    /// Element mean stress, 6 per element, Voigt `[xx, yy, zz, xy, yz, zx]` (Pa, tension +).
    pub stress: Vec<f64>,
    /// Interface mean traction (τ_s, τ_a, t_n), 3 per element (Pa); empty without interfaces.
    pub interface_traction: Vec<f64>,
    /// Interface mean jump (δ_s, δ_a, δ_n) since placement, 3 per element (m).
    pub interface_jump: Vec<f64>,
    /// Interface mean opening, 1 per element (m).
    pub interface_opening: Vec<f64>,
}

#[cfg(feature = "native")]
impl StageFields {
    /// Reads the fields of the results step in group `g` of the file `h5` (missing fields are
    /// empty), naming it `stage`.
    pub fn read(g: &hdf5::Group, h5: &Path, stage: String) -> Result<Self, String> {
        let read = |field: &str| -> Result<Vec<f64>, String> {
            if !g.link_exists(field) {
                return Ok(Vec::new());
            }
            g.dataset(field)
                .and_then(|d| d.read_raw::<f64>())
                .map_err(|e| format!("{}: {}/{field}: {e}", h5.display(), g.name()))
        };
        Ok(StageFields {
            name: stage,
            displacement: read("displacement")?,
            stress: read("stress")?,
            interface_traction: read("interface_traction")?,
            interface_jump: read("interface_jump")?,
            interface_opening: read("interface_opening")?,
        })
    }
}

/// One elevation of the slab profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlabRow {
    /// Elevation of the element centres (m).
    pub z: f64,
    /// Stress along the slope σ_s (Pa, tension +).
    pub sigma_slope: f64,
    /// Stress along the dam axis σ_a (Pa, tension +).
    pub sigma_axis: f64,
    /// Deflection along the slab normal, towards the dam positive (m).
    pub deflection: f64,
}

/// One elevation of the interface profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterfaceRow {
    /// Elevation of the element centres (m).
    pub z: f64,
    /// Mean jump (δ_s, δ_a, δ_n) (m), δ_n > 0 opening.
    pub jump: [f64; 3],
    /// Mean shear tractions τ_s, τ_a (Pa).
    pub tau: [f64; 2],
    /// Normal stress σ_n (Pa, compression positive).
    pub sigma_n: f64,
    /// Mean opening (m).
    pub opening: f64,
}

/// Failures of the profile outputs.
#[derive(Debug, thiserror::Error)]
pub enum ProfilesError {
    /// Nothing to plot.
    #[error("profiles: {0}")]
    Missing(String),
    /// Writing a file failed.
    #[error("profiles: {path}: {source}")]
    Io {
        /// File.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// A plot could not be written.
    #[error(transparent)]
    Plot(#[from] PlotError),
}

/// Elements of the blocks whose names start with `prefix` (input indices).
pub fn elements_with_prefix(mesh: &Mesh, prefix: &str) -> Vec<usize> {
    let blocks: Vec<bool> = mesh.blocks.iter().map(|b| b.name.starts_with(prefix)).collect();
    (0..mesh.elements.len())
        .filter(|&e| blocks[mesh.elements[e].block as usize])
        .collect()
}

/// Centre (mean of the 8 nodes) of element `e`.
pub fn centre(mesh: &Mesh, e: usize) -> Vector3<f64> {
    mesh.element_coords(e)
        .iter()
        .fold(Vector3::zeros(), |a, x| a + Vector3::from(*x))
        / 8.0
}

fn y_range(mesh: &Mesh, e: usize) -> (f64, f64) {
    mesh.element_coords(e)
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x[1]), hi.max(x[1]))
        })
}

/// The section plane: the given y, or the middle of the slab's y-range.
pub fn section_y(mesh: &Mesh, spec: &ProfilesSpec) -> Option<f64> {
    if let Some(y) = spec.section_y {
        return Some(y);
    }
    let slab = elements_with_prefix(mesh, &spec.slab_prefix);
    let (lo, hi) = slab
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &e| {
            let (a, b) = y_range(mesh, e);
            (lo.min(a), hi.max(b))
        });
    (lo <= hi).then_some(0.5 * (lo + hi))
}

/// Elements of `elements` cut by the plane y = `y`, grouped by elevation (ascending): each
/// group holds the elements whose centres lie within 1 mm of the same elevation.
fn section_groups(mesh: &Mesh, elements: &[usize], y: f64) -> Vec<(f64, Vec<usize>)> {
    let cut: Vec<usize> = elements
        .iter()
        .copied()
        .filter(|&e| {
            let (lo, hi) = y_range(mesh, e);
            let tol = 1e-9 * (hi - lo).abs().max(1.0);
            lo - tol <= y && y <= hi + tol
        })
        .collect();
    elevation_groups(mesh, &cut)
}

/// `elements` grouped by elevation (ascending): each group holds the elements whose centres lie
/// within 1 mm of the same elevation, in index order.
pub fn elevation_groups(mesh: &Mesh, elements: &[usize]) -> Vec<(f64, Vec<usize>)> {
    let mut cut: Vec<(f64, usize)> = elements.iter().map(|&e| (centre(mesh, e)[2], e)).collect();
    cut.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut groups: Vec<(f64, Vec<usize>)> = Vec::new();
    for (z, e) in cut {
        match groups.last_mut() {
            Some((z0, g)) if (z - *z0).abs() < 1e-3 => g.push(e),
            _ => groups.push((z, vec![e])),
        }
    }
    groups
}

/// Slab frame of a hex element (module docs): thinnest direction as normal towards +x, in-plane
/// axes by the rule (E3).
pub fn slab_frame(x: &[[f64; 3]; 8]) -> LocalFrame {
    let v = |a: usize| Vector3::from(x[a]);
    let dirs = [
        (v(1) - v(0) + v(2) - v(3) + v(5) - v(4) + v(6) - v(7)) / 4.0,
        (v(3) - v(0) + v(2) - v(1) + v(7) - v(4) + v(6) - v(5)) / 4.0,
        (v(4) - v(0) + v(5) - v(1) + v(6) - v(2) + v(7) - v(3)) / 4.0,
    ];
    let k = (0..3)
        .min_by(|&a, &b| dirs[a].norm().total_cmp(&dirs[b].norm()))
        .unwrap_or(2);
    // the plane's normal from the two in-plane directions (robust for thin elements)
    let (p, q) = ((k + 1) % 3, (k + 2) % 3);
    let mut n = dirs[p].cross(&dirs[q]).normalize();
    if n[0] < 0.0 {
        n = -n;
    }
    LocalFrame::from_normal(&n, &FrameAxes::default())
}

/// The symmetric tensor of a Voigt stress `[xx, yy, zz, xy, yz, zx]`.
pub fn stress_tensor(s: &[f64]) -> Matrix3<f64> {
    Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2])
}

/// Slab stress and deflection vs elevation at the central section (seed Figs. 8, 9).
pub fn slab_profile(mesh: &Mesh, spec: &ProfilesSpec, f: &StageFields) -> Vec<SlabRow> {
    let Some(y) = section_y(mesh, spec) else {
        return Vec::new();
    };
    let slab = elements_with_prefix(mesh, &spec.slab_prefix);
    section_groups(mesh, &slab, y)
        .into_iter()
        .map(|(z, g)| {
            let w = 1.0 / g.len() as f64;
            let mut row = SlabRow {
                z,
                sigma_slope: 0.0,
                sigma_axis: 0.0,
                deflection: 0.0,
            };
            for e in g {
                let frame = slab_frame(&mesh.element_coords(e));
                let sig = stress_tensor(&f.stress[6 * e..6 * e + 6]);
                row.sigma_slope += w * frame.s.dot(&(sig * frame.s));
                row.sigma_axis += w * frame.a.dot(&(sig * frame.a));
                let u = mesh.elements[e].nodes.iter().fold(Vector3::zeros(), |a, &n| {
                    let n = n as usize;
                    a + Vector3::new(
                        f.displacement[3 * n],
                        f.displacement[3 * n + 1],
                        f.displacement[3 * n + 2],
                    )
                }) / 8.0;
                row.deflection += w * frame.n.dot(&u);
            }
            row
        })
        .collect()
}

/// Interface jumps, tractions and opening vs elevation at the central section (seed Fig. 11).
pub fn interface_profile(mesh: &Mesh, spec: &ProfilesSpec, f: &StageFields) -> Vec<InterfaceRow> {
    let Some(y) = section_y(mesh, spec) else {
        return Vec::new();
    };
    if f.interface_jump.is_empty() {
        return Vec::new();
    }
    let iface = elements_with_prefix(mesh, &spec.interface_prefix);
    section_groups(mesh, &iface, y)
        .into_iter()
        .map(|(z, g)| {
            let w = 1.0 / g.len() as f64;
            let mut row = InterfaceRow {
                z,
                jump: [0.0; 3],
                tau: [0.0; 2],
                sigma_n: 0.0,
                opening: 0.0,
            };
            for e in g {
                for c in 0..3 {
                    row.jump[c] += w * f.interface_jump[3 * e + c];
                }
                row.tau[0] += w * f.interface_traction[3 * e];
                row.tau[1] += w * f.interface_traction[3 * e + 1];
                row.sigma_n -= w * f.interface_traction[3 * e + 2];
                row.opening += w * f.interface_opening[e];
            }
            row
        })
        .collect()
}

/// Nodes of the dam body: of the solid elements outside the slab.
pub fn body_nodes(mesh: &Mesh, spec: &ProfilesSpec) -> Vec<bool> {
    let slab: Vec<bool> = mesh
        .blocks
        .iter()
        .map(|b| b.name.starts_with(&spec.slab_prefix))
        .collect();
    let mut body = vec![false; mesh.num_nodes()];
    for el in &mesh.elements {
        if el.kind == crate::mesh::ElementKind::Hex8 && !slab[el.block as usize] {
            for &n in &el.nodes {
                body[n as usize] = true;
            }
        }
    }
    body
}

/// Settlement and horizontal displacement on the vertical through the crest centre at the
/// central section (seed Fig. 7): `(z, u_x, u_z)` of the solid nodes nearest to that line at
/// each elevation, excluding the slab.
pub fn axis_profile(mesh: &Mesh, spec: &ProfilesSpec, f: &StageFields) -> Vec<(f64, f64, f64)> {
    let Some(y) = section_y(mesh, spec) else {
        return Vec::new();
    };
    let body = body_nodes(mesh, spec);
    // the crest centre: the middle of the x-range of the highest body nodes
    let zmax = (0..mesh.num_nodes())
        .filter(|&n| body[n])
        .map(|n| mesh.coords[n][2])
        .fold(f64::NEG_INFINITY, f64::max);
    let top: Vec<usize> = (0..mesh.num_nodes())
        .filter(|&n| body[n] && (mesh.coords[n][2] - zmax).abs() < 1e-6)
        .collect();
    let (x0, x1) = top.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &n| {
        (a.min(mesh.coords[n][0]), b.max(mesh.coords[n][0]))
    });
    let xc = 0.5 * (x0 + x1);
    let mut best: std::collections::BTreeMap<i64, (f64, usize)> = std::collections::BTreeMap::new();
    for n in (0..mesh.num_nodes()).filter(|&n| body[n]) {
        let x = mesh.coords[n];
        let d = (x[0] - xc).powi(2) + (x[1] - y).powi(2);
        let key = (x[2] * 1000.0).round() as i64;
        let entry = best.entry(key).or_insert((f64::INFINITY, n));
        if d < entry.0 {
            *entry = (d, n);
        }
    }
    best.values()
        .map(|&(_, n)| {
            (
                mesh.coords[n][2],
                f.displacement[3 * n],
                f.displacement[3 * n + 2],
            )
        })
        .collect()
}

/// One stage of a probe's history.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeRow {
    /// Stage name.
    pub stage: String,
    /// Normal stress σ_n (Pa, compression positive).
    pub sigma_n: f64,
    /// Shear stress magnitude |τ| (Pa).
    pub tau: f64,
    /// Shear jump along the slope δ_s (m).
    pub slip: f64,
    /// Stress ratio τ/σ_n (0 when σ_n ≤ 0).
    pub ratio: f64,
}

/// Probe history: per stage, the state of the interface element in the central section nearest
/// to the probe's elevation (seed Fig. 10).
pub fn probe_history(
    mesh: &Mesh,
    spec: &ProfilesSpec,
    probe: &Probe,
    stages: &[StageFields],
) -> Option<Vec<ProbeRow>> {
    if probe.element != ProbeElement::Interface {
        return None;
    }
    let e = probe_element(mesh, spec, probe)?;
    Some(
        stages
            .iter()
            .filter(|f| !f.interface_traction.is_empty())
            .map(|f| {
                let t = &f.interface_traction[3 * e..3 * e + 3];
                // + 0.0 turns the −0 of an unloaded element into 0
                let sigma_n = -t[2] + 0.0;
                let tau = t[0].hypot(t[1]);
                ProbeRow {
                    stage: f.name.clone(),
                    sigma_n,
                    tau,
                    slip: f.interface_jump[3 * e],
                    ratio: if sigma_n > 0.0 { tau / sigma_n } else { 0.0 },
                }
            })
            .collect(),
    )
}

/// The group of `groups` (elevation, elements) nearest to elevation `z`.
fn nearest_row(groups: &[(f64, Vec<usize>)], z: f64) -> Option<&[usize]> {
    groups
        .iter()
        .min_by(|a, b| (a.0 - z).abs().total_cmp(&(b.0 - z).abs()))
        .map(|(_, g)| g.as_slice())
}

/// The element a probe follows (input index; [`Probe`]): in the central section, the first
/// element of the elevation group nearest to the probe's elevation; at a bank, the element of
/// that row (centres within 1 mm of the nearest elevation over the whole face) with the
/// smallest (left) or largest (right) centre y. `None` without elements of the probe's kind.
pub fn probe_element(mesh: &Mesh, spec: &ProfilesSpec, probe: &Probe) -> Option<usize> {
    let prefix = match probe.element {
        ProbeElement::Interface => &spec.interface_prefix,
        ProbeElement::Slab => &spec.slab_prefix,
    };
    let elements = elements_with_prefix(mesh, prefix);
    let groups = match probe.at {
        ProbeAt::Centre => section_groups(mesh, &elements, section_y(mesh, spec)?),
        ProbeAt::LeftBank | ProbeAt::RightBank => elevation_groups(mesh, &elements),
    };
    let row = nearest_row(&groups, probe.elevation)?;
    let y = |e: &usize| centre(mesh, *e)[1];
    match probe.at {
        ProbeAt::Centre => row.first().copied(),
        ProbeAt::LeftBank => row.iter().copied().min_by(|a, b| y(a).total_cmp(&y(b))),
        ProbeAt::RightBank => row.iter().copied().max_by(|a, b| y(a).total_cmp(&y(b))),
    }
}

/// Index of the end-of-construction stage (module docs).
pub fn construction_end(spec: &ProfilesSpec, stages: &[StageFields]) -> Option<usize> {
    stages
        .iter()
        .rposition(|f| !f.name.starts_with(&spec.impoundment_prefix))
}

/// One row of a `fig08_slab_stress.csv` table.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SlabTableRow {
    /// "end of construction" or "after impoundment".
    pub(crate) state: String,
    /// Elevation (m).
    pub(crate) z: f64,
    /// Stress along the slope (Pa, tension +).
    pub(crate) sigma_slope: f64,
    /// Stress along the dam axis (Pa, tension +).
    pub(crate) sigma_axis: f64,
    /// Deflection (m, towards the dam +).
    pub(crate) deflection: f64,
}

/// Which slab table of a run [`overlay_slab_profiles`] reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlabTable {
    /// `fig08_slab_stress.csv`: end of construction and after impoundment (seed Figs. 8, 9).
    Static,
    /// `fig13_residual_slab.csv`: before, after and residual of a quake (seed Fig. 13).
    Quake,
}

impl SlabTable {
    /// The table's file in a run directory and the figures it stands for.
    fn file_and_figures(self) -> (&'static str, &'static str) {
        match self {
            SlabTable::Static => ("fig08_slab_stress.csv", "seed Figs. 8, 9"),
            SlabTable::Quake => ("fig13_residual_slab.csv", "seed Fig. 13"),
        }
    }
}

/// Reads a slab table with the columns `state,z_m,sigma_slope_Pa,sigma_axis_Pa,deflection_m`
/// (`fig08_slab_stress.csv`, and `fig13_residual_slab.csv` of a quake).
pub(crate) fn read_slab_csv(path: &Path) -> Result<Vec<SlabTableRow>, ProfilesError> {
    let path = path.to_path_buf();
    let text = crate::input::read_text(&path, crate::input::MAX_SCENE_BYTES).map_err(|source| {
        ProfilesError::Io {
            path: path.clone(),
            source,
        }
    })?;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |k: usize| f.get(k).and_then(|v| v.trim().parse::<f64>().ok());
        match (f.first(), num(1), num(2), num(3), num(4)) {
            (Some(state), Some(z), Some(s), Some(a), Some(d)) if f.len() == 5 => rows.push(SlabTableRow {
                state: state.to_string(),
                z,
                sigma_slope: s,
                sigma_axis: a,
                deflection: d,
            }),
            _ => {
                return Err(ProfilesError::Missing(format!(
                    "{}: line {}: expected state,z_m,sigma_slope_Pa,sigma_axis_Pa,deflection_m",
                    path.display(),
                    i + 1
                )))
            }
        }
    }
    if rows.is_empty() {
        return Err(ProfilesError::Missing(format!("{}: no rows", path.display())));
    }
    Ok(rows)
}

/// Overlays the slab profiles of several runs, e.g. one per interface model: σ_s, σ_a and the
/// deflection versus elevation for each state of the table (end of construction and after
/// impoundment, seed Figs. 8 and 9; or before, after and residual of a quake, seed Fig. 13),
/// one panel each, one line per run. `runs` are (label, run directory holding the table).
/// Returns the number of rows read.
pub fn overlay_slab_profiles(
    runs: &[(String, PathBuf)],
    table: SlabTable,
    png: &Path,
) -> Result<usize, ProfilesError> {
    let (file, figures) = table.file_and_figures();
    let tables = runs
        .iter()
        .map(|(label, dir)| Ok((label.as_str(), read_slab_csv(&dir.join(file))?)))
        .collect::<Result<Vec<_>, ProfilesError>>()?;
    let mut states: Vec<String> = Vec::new();
    for (_, rows) in &tables {
        for r in rows {
            if !states.contains(&r.state) {
                states.push(r.state.clone());
            }
        }
    }
    type Pick = fn(&SlabTableRow) -> f64;
    let quantities: [(&str, &str, Pick); 3] = [
        ("Slab stress along the slope", "sigma_s (MPa, tension +)", |r| {
            r.sigma_slope / 1e6
        }),
        (
            "Slab stress along the dam axis",
            "sigma_a (MPa, tension +)",
            |r| r.sigma_axis / 1e6,
        ),
        ("Slab deflection", "deflection (cm, towards the dam +)", |r| {
            r.deflection * 100.0
        }),
    ];
    let mut figure = Figure::new(format!(
        "Slab at the central section, one line per run ({figures})"
    ))
    .columns(states.len().min(3));
    for (title, x_label, pick) in quantities {
        for state in &states {
            let mut panel = Panel::new(format!("{title}, {state}"), x_label, "z (m)");
            for (label, rows) in &tables {
                let points: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| &r.state == state)
                    .map(|r| (pick(r), r.z))
                    .collect();
                panel.push(Series::line(*label, points));
            }
            figure.push(panel);
        }
    }
    figure.save_png(png)?;
    Ok(tables.iter().map(|(_, rows)| rows.len()).sum())
}

impl From<OutputError> for ProfilesError {
    fn from(e: OutputError) -> Self {
        match e {
            OutputError::Io { path, source } => ProfilesError::Io { path, source },
            OutputError::Plot(p) => ProfilesError::Plot(p),
        }
    }
}

/// The states the static figures show: the end of construction and, when the run has one,
/// the state after impoundment (labels and stage indices).
fn figure_states(
    spec: &ProfilesSpec,
    stages: &[StageFields],
) -> Result<Vec<(&'static str, usize)>, ProfilesError> {
    let last = stages
        .len()
        .checked_sub(1)
        .ok_or_else(|| ProfilesError::Missing("no stage results".into()))?;
    let end = construction_end(spec, stages).unwrap_or(last);
    let mut states = vec![("end of construction", end)];
    if end != last {
        states.push(("after impoundment", last));
    }
    Ok(states)
}

/// Writes the CSV tables and PNG plots of the module docs into `dir`; returns the files written.
/// `stages` are all stages of the run in order.
pub fn write_profiles(
    mesh: &Mesh,
    spec: &ProfilesSpec,
    stages: &[StageFields],
    dir: &Path,
) -> Result<Vec<PathBuf>, ProfilesError> {
    let states: Vec<(&str, &StageFields)> = figure_states(spec, stages)?
        .into_iter()
        .map(|(label, k)| (label, &stages[k]))
        .collect();
    let out = StaticFigures { mesh, spec, dir };
    let mut files = Vec::new();
    out.fig07(&states, &mut files)?;
    out.figs08_09(&states, &mut files)?;
    out.fig11(stages.last().expect("a stage"), &mut files)?;
    for probe in &spec.probes {
        out.fig10(probe, stages, &mut files)?;
    }
    Ok(files)
}

/// The slab's profiles at the central section for each of `states` (label, fields): the CSV
/// table (`state,z_m,sigma_slope_Pa,sigma_axis_Pa,deflection_m`) and the three panels σ_s,
/// σ_a and deflection against elevation (seed Figs. 8, 9 and 13).
pub(crate) fn slab_profiles(
    mesh: &Mesh,
    spec: &ProfilesSpec,
    states: &[(&str, &StageFields)],
) -> (String, [Panel; 3]) {
    let mut csv = String::from("state,z_m,sigma_slope_Pa,sigma_axis_Pa,deflection_m\n");
    let mut panels = [
        ("Slab stress along the slope (tension +)", "sigma_s (MPa)"),
        ("Slab stress along the dam axis (tension +)", "sigma_a (MPa)"),
        ("Slab deflection (towards the dam +)", "deflection (cm)"),
    ]
    .map(|(title, x)| Panel::new(title, x, "z (m)"));
    for (label, fields) in states {
        let prof = slab_profile(mesh, spec, fields);
        for r in &prof {
            let _ = writeln!(
                csv,
                "{label},{},{},{},{}",
                r.z, r.sigma_slope, r.sigma_axis, r.deflection
            );
        }
        let line = |f: fn(&SlabRow) -> f64| Series::line(*label, prof.iter().map(|r| (f(r), r.z)).collect());
        panels[0].push(line(|r| r.sigma_slope / 1e6));
        panels[1].push(line(|r| r.sigma_axis / 1e6));
        panels[2].push(line(|r| r.deflection * 100.0));
    }
    (csv, panels)
}

/// Where and from what the static figures are drawn.
struct StaticFigures<'a> {
    mesh: &'a Mesh,
    spec: &'a ProfilesSpec,
    dir: &'a Path,
}

impl StaticFigures<'_> {
    /// Fig. 7: settlement and horizontal displacement on the crest-centre vertical.
    fn fig07(&self, states: &[(&str, &StageFields)], files: &mut Vec<PathBuf>) -> Result<(), ProfilesError> {
        let mut csv = String::from("state,z_m,ux_m,uz_m\n");
        let mut p_set = Panel::new(
            "Settlement on the crest-centre vertical",
            "settlement (m)",
            "z (m)",
        );
        let mut p_hor = Panel::new("Horizontal displacement (x)", "u_x (m)", "z (m)");
        for (label, fields) in states {
            let prof = axis_profile(self.mesh, self.spec, fields);
            for (z, ux, uz) in &prof {
                let _ = writeln!(csv, "{label},{z},{ux},{uz}");
            }
            p_set.push(Series::line(*label, prof.iter().map(|r| (-r.2, r.0)).collect()));
            p_hor.push(Series::line(*label, prof.iter().map(|r| (r.1, r.0)).collect()));
        }
        csv_out(self.dir, files, "fig07_dam_displacement.csv", csv)?;
        let figure = Figure::new("Dam displacement at the central section (seed Fig. 7)")
            .with(p_set)
            .with(p_hor);
        png_out(self.dir, files, "fig07_dam_displacement.png", figure)?;
        Ok(())
    }

    /// Figs. 8 and 9: slab stresses along the slope and the axis, and the slab's deflection.
    fn figs08_09(
        &self,
        states: &[(&str, &StageFields)],
        files: &mut Vec<PathBuf>,
    ) -> Result<(), ProfilesError> {
        let (csv, [p_s, p_a, p_d]) = slab_profiles(self.mesh, self.spec, states);
        csv_out(self.dir, files, "fig08_slab_stress.csv", csv.clone())?;
        csv_out(self.dir, files, "fig09_slab_deflection.csv", csv)?;
        let stress = Figure::new("Slab stresses at the central section (seed Fig. 8)")
            .with(p_s)
            .with(p_a);
        png_out(self.dir, files, "fig08_slab_stress.png", stress)?;
        let deflection = Figure::new("Slab deflection at the central section (seed Fig. 9)")
            .with(p_d)
            .columns(1);
        png_out(self.dir, files, "fig09_slab_deflection.png", deflection)?;
        Ok(())
    }

    /// Fig. 11: the interface's jumps and opening at the central section after the last stage.
    fn fig11(&self, last: &StageFields, files: &mut Vec<PathBuf>) -> Result<(), ProfilesError> {
        let prof = interface_profile(self.mesh, self.spec, last);
        if prof.is_empty() {
            return Ok(());
        }
        let mut csv =
            String::from("z_m,delta_s_m,delta_a_m,delta_n_m,tau_s_Pa,tau_a_Pa,sigma_n_Pa,opening_m\n");
        for r in &prof {
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{}",
                r.z, r.jump[0], r.jump[1], r.jump[2], r.tau[0], r.tau[1], r.sigma_n, r.opening
            );
        }
        csv_out(self.dir, files, "fig11_interface.csv", csv)?;
        let line = |name: &str, f: fn(&InterfaceRow) -> f64| {
            Series::line(name, prof.iter().map(|r| (f(r) * 1e3, r.z)).collect())
        };
        let figure = Figure::new(format!(
            "Interface at the central section, stage '{}' (seed Fig. 11)",
            last.name
        ))
        .with(
            Panel::new("Normal jump (opening +) and opening", "mm", "z (m)")
                .with(line("delta_n", |r| r.jump[2]))
                .with(line("opening", |r| r.opening)),
        )
        .with(
            Panel::new("Shear jump (cushion relative to slab)", "mm", "z (m)")
                .with(line("delta_s (up-slope)", |r| r.jump[0]))
                .with(line("delta_a (axis)", |r| r.jump[1])),
        );
        png_out(self.dir, files, "fig11_interface.png", figure)?;
        Ok(())
    }

    /// Fig. 10: the stress path and the shear displacement against the stress ratio of a probe
    /// interface element through the stages (nothing when the probe finds no element).
    fn fig10(
        &self,
        probe: &Probe,
        stages: &[StageFields],
        files: &mut Vec<PathBuf>,
    ) -> Result<(), ProfilesError> {
        let Some(hist) = probe_history(self.mesh, self.spec, probe, stages) else {
            return Ok(());
        };
        let mut csv = String::from("stage,sigma_n_Pa,tau_Pa,delta_s_m,tau_over_sigma_n\n");
        for h in &hist {
            let _ = writeln!(csv, "{},{},{},{},{}", h.stage, h.sigma_n, h.tau, h.slip, h.ratio);
        }
        let safe = safe_name(&probe.name);
        csv_out(self.dir, files, &format!("fig10_probe_{safe}.csv"), csv)?;
        let figure = Figure::new(format!("Interface element {} (seed Fig. 10)", probe.name))
            .with(
                Panel::new("Stress path", "sigma_n (kPa)", "tau (kPa)").with(Series::line(
                    "",
                    hist.iter().map(|h| (h.sigma_n / 1e3, h.tau / 1e3)).collect(),
                )),
            )
            .with(
                Panel::new(
                    "Shear displacement vs stress ratio",
                    "tau / sigma_n",
                    "delta_s (mm)",
                )
                .with(Series::line(
                    "",
                    hist.iter().map(|h| (h.ratio, h.slip * 1e3)).collect(),
                )),
            );
        png_out(self.dir, files, &format!("fig10_probe_{safe}.png"), figure)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::{box_mesh, BoxSpec};

    /// `cfrd overlay`: the tables of two runs become one figure; a malformed row is an error
    /// that names the file and the line.
    #[test]
    fn overlay_reads_the_slab_tables_of_several_runs() {
        let tmp = tempfile::tempdir().unwrap();
        let header = "state,z_m,sigma_slope_Pa,sigma_axis_Pa,deflection_m\n";
        let mut runs = Vec::new();
        for (k, label) in ["hyperbolic", "mohr_coulomb"].iter().enumerate() {
            let dir = tmp.path().join(label);
            std::fs::create_dir(&dir).unwrap();
            let mut text = header.to_string();
            for state in ["end of construction", "after impoundment"] {
                for z in [2700.0, 2750.0, 2800.0] {
                    let _ = writeln!(text, "{state},{z},{},{},{}", -1e6 * (k + 1) as f64, 2e5, 0.01);
                }
            }
            std::fs::write(dir.join("fig08_slab_stress.csv"), text).unwrap();
            runs.push((label.to_string(), dir));
        }
        let png = tmp.path().join("overlay.png");
        assert_eq!(
            overlay_slab_profiles(&runs, SlabTable::Static, &png).expect("overlay"),
            12
        );
        assert!(std::fs::metadata(&png).expect("png written").len() > 1000);
        // a quake's table, three states
        for (k, (_, dir)) in runs.iter().enumerate() {
            let mut text = header.to_string();
            for state in ["before the quake", "after the quake", "residual"] {
                let _ = writeln!(text, "{state},2800,{},-3e6,0.05", -1e6 * (k + 1) as f64);
            }
            std::fs::write(dir.join("fig13_residual_slab.csv"), text).unwrap();
        }
        std::fs::remove_file(&png).unwrap();
        assert_eq!(
            overlay_slab_profiles(&runs, SlabTable::Quake, &png).expect("quake overlay"),
            6
        );
        assert!(std::fs::metadata(&png).expect("png written").len() > 1000);

        std::fs::write(
            runs[1].1.join("fig08_slab_stress.csv"),
            format!("{header}after impoundment,2700,-1e6,oops,0.01\n"),
        )
        .unwrap();
        let e = overlay_slab_profiles(&runs, SlabTable::Static, &png)
            .unwrap_err()
            .to_string();
        assert!(e.contains("mohr_coulomb") && e.contains("line 2"), "{e}");
    }

    /// Probes pick the row nearest to their elevation, then the central section or the
    /// element nearest a bank; a slab probe finds no interface element and vice versa.
    #[test]
    fn probes_at_the_centre_and_at_the_banks() {
        let mut mesh = box_mesh(&BoxSpec {
            size: [0.2, 40.0, 30.0],
            divisions: [1, 4, 3],
            ..Default::default()
        })
        .unwrap();
        mesh.blocks[0].name = "interface_1".into();
        // no slab to take the section from: the section is given
        let spec = ProfilesSpec {
            section_y: Some(20.0),
            ..Default::default()
        };
        let probe = |at: ProbeAt, element: ProbeElement| Probe {
            name: "P".into(),
            elevation: 14.0,
            at,
            element,
        };
        let at = |e: Option<usize>| e.map(|e| [centre(&mesh, e)[1], centre(&mesh, e)[2]]);
        let centre_probe = probe_element(&mesh, &spec, &probe(ProbeAt::Centre, ProbeElement::Interface));
        let cut = at(centre_probe).expect("a central element");
        assert_eq!(cut[1], 15.0, "the row nearest 14 m");
        assert!(
            (cut[0] - 20.0).abs() <= 10.0,
            "cut by the section y = 20 m: {cut:?}"
        );
        let left = probe_element(&mesh, &spec, &probe(ProbeAt::LeftBank, ProbeElement::Interface));
        assert_eq!(at(left), Some([5.0, 15.0]));
        let right = probe_element(&mesh, &spec, &probe(ProbeAt::RightBank, ProbeElement::Interface));
        assert_eq!(at(right), Some([35.0, 15.0]));
        assert_eq!(
            probe_element(&mesh, &spec, &probe(ProbeAt::Centre, ProbeElement::Slab)),
            None
        );
        let yaml = "{ name: I-B, elevation: 2809.0, at: left_bank }";
        let parsed: Probe = serde_yaml::from_str(yaml).unwrap();
        assert_eq!(
            (parsed.at, parsed.element),
            (ProbeAt::LeftBank, ProbeElement::Interface)
        );
    }

    #[test]
    fn slab_frame_of_a_thin_element_on_the_upstream_slope() {
        // a 1:1.4 slope element, thickness 0.5 m normal to the face
        let n = Vector3::new(1.0, 0.0, -1.4).normalize();
        let s = Vector3::new(1.4, 0.0, 1.0).normalize();
        let y = Vector3::y();
        let base = |a: f64, b: f64| s * a + y * b;
        let bottom = [base(0.0, 0.0), base(10.0, 0.0), base(10.0, 8.0), base(0.0, 8.0)];
        let x: [[f64; 3]; 8] = std::array::from_fn(|k| {
            let p = if k < 4 { bottom[k] - n * 0.5 } else { bottom[k - 4] };
            [p[0], p[1], p[2]]
        });
        let f = slab_frame(&x);
        assert!((f.n - n).norm() < 1e-12, "{:?}", f.n);
        assert!((f.s - s).norm() < 1e-12, "{:?}", f.s);
        assert!((f.a.dot(&y)).abs() > 1.0 - 1e-12);
    }

    #[test]
    fn section_profiles_of_a_uniform_field() {
        // a 'slab' block of 2 x 2 x 3 elements with a uniform stress: the slab profile at the
        // middle section averages the two elements at each elevation and rotates the stress
        let mut mesh = box_mesh(&BoxSpec {
            size: [0.2, 4.0, 6.0],
            divisions: [1, 2, 3],
            ..Default::default()
        })
        .unwrap();
        mesh.blocks[0].name = "slab".into();
        let ne = mesh.elements.len();
        let mut f = StageFields {
            name: "impound_1".into(),
            displacement: vec![0.0; 3 * mesh.num_nodes()],
            stress: Vec::new(),
            ..Default::default()
        };
        for _ in 0..ne {
            // σ_yy = −2 MPa (along the axis), σ_zz = −5 MPa (along the "slope": vertical wall)
            f.stress.extend([0.0, -2.0e6, -5.0e6, 0.0, 0.0, 0.0]);
        }
        for n in 0..mesh.num_nodes() {
            f.displacement[3 * n] = 0.01;
        }
        let spec = ProfilesSpec::default();
        assert_eq!(section_y(&mesh, &spec), Some(2.0));
        let prof = slab_profile(&mesh, &spec, &f);
        assert_eq!(prof.len(), 3);
        for (k, r) in prof.iter().enumerate() {
            assert!((r.z - (1.0 + 2.0 * k as f64)).abs() < 1e-12);
            assert!((r.sigma_slope + 5.0e6).abs() < 1e-6, "{r:?}");
            assert!((r.sigma_axis + 2.0e6).abs() < 1e-6, "{r:?}");
            assert!((r.deflection - 0.01).abs() < 1e-15, "{r:?}");
        }
        assert_eq!(construction_end(&spec, std::slice::from_ref(&f)), None);
    }
}
