//! What an earthquake stage leaves without a profile definition: the time history of the crest
//! (relative displacement, absolute acceleration, ground acceleration), its residual
//! displacement (end of the quake minus the state before it, the seed's "residual
//! deformation") and the acceleration amplification (peak absolute crest over peak ground
//! acceleration). Written by `cfrd run` after a scene with a dynamic stage: `quake_crest.csv`,
//! `quake_crest.png` and `quake_summary.json`.

use crate::io::results_reader::{open, stage_name, step_names};
use crate::plot::{Figure, Panel, Series};
use crate::post::quake_clock::QuakeClock;
use crate::scene::Scene;
use std::path::{Path, PathBuf};

/// The crest's history over the dynamic stages of a run, on the quake's clock ([`QuakeClock`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CrestHistory {
    /// Index of the crest node ([`crest_node`]).
    pub node: usize,
    /// Time on the quake's clock (s) of every written step.
    pub t: Vec<f64>,
    /// Displacement relative to the base, minus the one before the quake (m).
    pub u: Vec<[f64; 3]>,
    /// Absolute acceleration (m/s²).
    pub a: Vec<[f64; 3]>,
    /// Ground acceleration (m/s²).
    pub ground: Vec<[f64; 3]>,
}

/// The summary written to `quake_summary.json`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct QuakeSummary {
    /// Mesh id of the crest node.
    pub crest_node_id: u64,
    /// Coordinates of the crest node (m; x, y, z).
    pub crest_coordinates_m: [f64; 3],
    /// The dynamic stages the history covers, in order, on one clock ([`QuakeClock`]).
    pub stages: Vec<String>,
    /// Residual crest displacement, end of the quake minus before it (m; x, y, z).
    pub residual_displacement_m: [f64; 3],
    /// Peak absolute crest acceleration (m/s²; x, y, z) over every time step (over the
    /// results steps for a history read back from results files).
    pub peak_crest_acceleration: [f64; 3],
    /// Peak ground acceleration of the records over the dynamic stages (m/s²; x, y, z).
    pub peak_ground_acceleration: [f64; 3],
    /// Peak crest over peak ground acceleration per axis.
    pub amplification: [f64; 3],
    /// Peak of the crest acceleration low-passed at [`SPIKE_CUTOFF_HZ`] (zero-phase
    /// Butterworth of order 4, [`crate::seismic::filter`]; the history on the stage's time
    /// grid), per axis; `null` when the time step cannot resolve that frequency.
    pub peak_crest_acceleration_low_passed: Option<[f64; 3]>,
    /// Raw over low-passed peak per axis: near 1 for a resolved response, well above it when
    /// the raw peak is a single-step spike.
    pub spike_ratio: Option<[f64; 3]>,
}

/// The cut-off (Hz) of the low-passed crest acceleration of [`QuakeSummary`]: above the
/// frequencies a dam's response to a code spectrum carries (spectra end at 0.04 s, 25 Hz),
/// below the Nyquist frequency of the usual 0.01 s step.
pub const SPIKE_CUTOFF_HZ: f64 = 20.0;

/// The peaks per axis of `h.a` low-passed at [`SPIKE_CUTOFF_HZ`], the history put on the grid
/// of step `dt` first; `None` when `dt` cannot resolve the cut-off.
fn low_passed_peaks(h: &CrestHistory, dt: f64) -> Option<[f64; 3]> {
    let mut peaks = [0.0; 3];
    for (c, peak) in peaks.iter_mut().enumerate() {
        let a: Vec<f64> = h.a.iter().map(|x| x[c]).collect();
        let uniform = crate::seismic::filter::on_uniform_grid(&h.t, &a, dt);
        let low = crate::seismic::filter::low_pass_zero_phase(&uniform, dt, SPIKE_CUTOFF_HZ)?;
        *peak = low.iter().map(|v| v.abs()).fold(0.0, f64::max);
    }
    Some(peaks)
}

/// The crest node: the highest node of the dam body (the solid elements outside the face slab,
/// [`crate::post::profiles::body_nodes`]; every node when there are none) nearest the middle
/// of the dam axis (y), and of those the one nearest the middle of the crest across the stream
/// (x), the lowest index of a tie. On a CFRD it is the rockfill crest's centre, not the slab's
/// top edge, which stands higher than the fill and where slab, joints and the slab–cushion
/// interface meet.
pub fn crest_node(scene: &Scene) -> usize {
    let (mesh, c) = (&scene.mesh, &scene.mesh.coords);
    let spec = scene.file.output.profiles.clone().unwrap_or_default();
    let body = crate::post::profiles::body_nodes(mesh, &spec);
    let nodes: Vec<usize> = match body.iter().any(|&b| b) {
        true => (0..c.len()).filter(|&i| body[i]).collect(),
        false => (0..c.len()).collect(),
    };
    let top = nodes.iter().map(|&i| c[i][2]).fold(f64::MIN, f64::max);
    let highest: Vec<usize> = nodes
        .iter()
        .copied()
        .filter(|&i| c[i][2] >= top - 1e-6 * top.abs().max(1.0))
        .collect();
    let middle = |axis: usize, of: &[usize]| {
        let (lo, hi) = of.iter().fold((f64::MAX, f64::MIN), |(a, b), &i| {
            (a.min(c[i][axis]), b.max(c[i][axis]))
        });
        0.5 * (lo + hi)
    };
    let (mid_y, mid_x) = (middle(1, &nodes), middle(0, &highest));
    let off = |i: usize| ((c[i][1] - mid_y).abs(), (c[i][0] - mid_x).abs());
    highest
        .iter()
        .copied()
        .min_by(|&a, &b| {
            let ((ya, xa), (yb, xb)) = (off(a), off(b));
            ya.total_cmp(&yb).then(xa.total_cmp(&xb)).then(a.cmp(&b))
        })
        .unwrap_or(0)
}

/// Reads the crest history of the dynamic stages from the closed results file `h5`, on the
/// quake's clock ([`QuakeClock`]), the displacement counted from the last step of the stage
/// before the first dynamic one; `None` when the scene has no dynamic stage or the file no
/// step of one.
pub fn crest_history(scene: &Scene, h5: &Path) -> Result<Option<CrestHistory>, String> {
    let clock = QuakeClock::new(scene);
    let Some(first) = clock.first() else {
        return Ok(None);
    };
    let node = crest_node(scene);
    let file = open(h5)?;
    let mut before = [0.0; 3];
    let mut hist = CrestHistory {
        node,
        ..Default::default()
    };
    for name in step_names(&file, h5)? {
        let g = file.group(&format!("/steps/{name}")).map_err(|e| e.to_string())?;
        let at = |field: &str| -> Result<[f64; 3], String> {
            let v = g
                .dataset(field)
                .and_then(|d| d.read_raw::<f64>())
                .map_err(|e| format!("{}: /steps/{name}/{field}: {e}", h5.display()))?;
            v.get(3 * node..3 * node + 3)
                .map(|s| [s[0], s[1], s[2]])
                .ok_or_else(|| format!("{}: /steps/{name}/{field} is too short", h5.display()))
        };
        let this = stage_name(&g).unwrap_or_default();
        if first > 0 && this == scene.stages[first - 1].name {
            before = at("displacement")?;
            continue;
        }
        let Some((dynamic, t0, local)) = crate::post::quake_fields::quake_step(&clock, scene, &g, &this)?
        else {
            continue;
        };
        let u = at("displacement")?;
        hist.t.push(t0 + local);
        hist.u.push(std::array::from_fn(|c| u[c] - before[c]));
        hist.a.push(at("acceleration")?);
        hist.ground.push(dynamic.ground_acceleration(local));
    }
    Ok((!hist.t.is_empty()).then_some(hist))
}

/// The summary of a crest history (`scene` for the node id and the record's peaks).
pub fn summarize(scene: &Scene, h: &CrestHistory) -> QuakeSummary {
    let peak = |v: &[[f64; 3]]| -> [f64; 3] {
        std::array::from_fn(|c| v.iter().map(|x| x[c].abs()).fold(0.0, f64::max))
    };
    let dynamic = scene.stages.iter().find_map(|s| s.dynamic.as_ref());
    let pga = QuakeClock::new(scene).peak_ground_acceleration(scene);
    let crest = peak(&h.a);
    let low = dynamic.and_then(|d| low_passed_peaks(h, d.dt()));
    let ratio = low.map(|l| std::array::from_fn(|c| if l[c] > 0.0 { crest[c] / l[c] } else { 0.0 }));
    QuakeSummary {
        crest_node_id: scene.mesh.node_ids[h.node],
        crest_coordinates_m: scene.mesh.coords[h.node],
        stages: QuakeClock::new(scene)
            .stages(scene)
            .map(|(_, s, _, _)| s.name.clone())
            .collect(),
        residual_displacement_m: h.u.last().copied().unwrap_or_default(),
        peak_crest_acceleration: crest,
        peak_ground_acceleration: pga,
        amplification: std::array::from_fn(|c| if pga[c] > 0.0 { crest[c] / pga[c] } else { 0.0 }),
        peak_crest_acceleration_low_passed: low,
        spike_ratio: ratio,
    }
}

/// The crest history of every converged time step (the run's [`crate::solver::SolveReport::crest`]
/// rows), from t = 0, the state before the quake (at rest relative to the base); `None`
/// without rows.
pub fn crest_steps(scene: &Scene, rows: &[[f64; 10]]) -> Option<CrestHistory> {
    let dynamic = scene.stages.iter().find_map(|s| s.dynamic.as_ref())?;
    if rows.is_empty() {
        return None;
    }
    let ground0 = dynamic.ground_acceleration(0.0);
    let start = [
        0.0, 0.0, 0.0, 0.0, ground0[0], ground0[1], ground0[2], ground0[0], ground0[1], ground0[2],
    ];
    let all = || std::iter::once(&start).chain(rows);
    let part = |o: usize| all().map(|r| [r[o], r[o + 1], r[o + 2]]).collect();
    Some(CrestHistory {
        node: crest_node(scene),
        t: all().map(|r| r[0]).collect(),
        u: part(1),
        a: part(4),
        ground: part(7),
    })
}

/// Writes `quake_crest.csv`, `quake_crest.png` and `quake_summary.json` into `dir` for a run
/// whose results are `h5`: from the crest's motion at every time step (`steps`, the run's
/// record) when given, else from the results steps; nothing for a scene without a dynamic
/// stage.
pub fn write_quake_outputs(
    scene: &Scene,
    h5: &Path,
    steps: &[[f64; 10]],
    dir: &Path,
) -> Result<Vec<PathBuf>, String> {
    let history = match crest_steps(scene, steps) {
        Some(h) => Some(h),
        None => crest_history(scene, h5)?,
    };
    let Some(h) = history else {
        return Ok(Vec::new());
    };
    let mut csv = String::from("t,u_x,u_y,u_z,a_x,a_y,a_z,ag_x,ag_y,ag_z\n");
    for i in 0..h.t.len() {
        let row: Vec<String> = std::iter::once(h.t[i])
            .chain(h.u[i])
            .chain(h.a[i])
            .chain(h.ground[i])
            .map(|v| v.to_string())
            .collect();
        csv.push_str(&row.join(","));
        csv.push('\n');
    }
    let files = [
        dir.join("quake_crest.csv"),
        dir.join("quake_crest.png"),
        dir.join("quake_summary.json"),
    ];
    crate::input::write_replacing(&files[0], csv.as_bytes())
        .map_err(|e| format!("{}: {e}", files[0].display()))?;
    crest_figure(&h)
        .save_png(&files[1])
        .map_err(|e| format!("{}: {e}", files[1].display()))?;
    let json = serde_json::to_string_pretty(&summarize(scene, &h)).map_err(|e| e.to_string())?;
    crate::input::write_replacing(&files[2], json.as_bytes())
        .map_err(|e| format!("{}: {e}", files[2].display()))?;
    Ok(files.to_vec())
}

/// Crest acceleration against the ground's (stream direction) and the crest's displacement
/// since the quake began.
fn crest_figure(h: &CrestHistory) -> Figure {
    let series = |v: &[[f64; 3]], c: usize| h.t.iter().zip(v).map(|(&t, x)| (t, x[c])).collect::<Vec<_>>();
    Figure::new("Earthquake: crest history")
        .with(
            Panel::new("absolute acceleration, stream direction (x)", "t (s)", "a (m/s2)")
                .with(Series::line("crest", series(&h.a, 0)))
                .with(Series::line("ground", series(&h.ground, 0))),
        )
        .with(
            Panel::new("crest displacement since the quake began", "t (s)", "u (m)")
                .with(Series::line("u_x (stream)", series(&h.u, 0)))
                .with(Series::line("u_y (axis)", series(&h.u, 1)))
                .with(Series::line("u_z (settlement < 0)", series(&h.u, 2))),
        )
        .columns(1)
}
