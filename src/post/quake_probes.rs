//! The time histories of the named probes through an earthquake (seed Figs. 14, 18–20, spec
//! seismic §3.6): σ_s, σ_a of a slab element (F-A); σ_n, τ_s, τ_a, δ_s, δ_a, δ_n and opening of
//! an interface element (I-B, I-C); the opening of every interface probe (I-D).
//!
//! **Sampling.** `cfrd run` records the probes at every converged time step of the first
//! dynamic stage ([`crate::solver::SolveReport::probes`], kept in step checkpoints, so a
//! restarted run has the whole history): one rank owns each probe element and the values are
//! the same on every rank count. Histories drawn later from results files alone (`cfrd
//! profiles`) are sampled at the results steps, every `output_every` time steps. Either way
//! t = 0 is the state before the quake, and each CSV states its sampling in a `#` line above
//! the header.

use crate::mesh::Mesh;
use crate::plot::{Figure, Panel, Series};
use crate::post::output::{csv_out, png_out, safe_name};
use crate::post::profiles::{
    centre, probe_element, slab_frame, stress_tensor, ProbeElement, ProfilesSpec, StageFields,
};
use crate::post::quake_fields::QuakeFields;
use crate::solver::ELEMENT_STATE;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A probe that lies on an element of its kind.
#[derive(Debug, Clone, PartialEq)]
pub struct QuakeProbe {
    /// The probe's name (file names).
    pub name: String,
    /// Slab or interface element.
    pub kind: ProbeElement,
    /// The element (mesh index).
    pub element: usize,
}

impl QuakeProbe {
    /// Values per sample: the mean stress (6, Voigt) of a slab element; σ_n (compression +),
    /// τ_s, τ_a, δ_s, δ_a, δ_n, opening of an interface element.
    pub fn width(&self) -> usize {
        match self.kind {
            ProbeElement::Slab => 6,
            ProbeElement::Interface => 7,
        }
    }

    /// This probe's values from an element state of [`crate::solver::Problem::element_states`]
    /// (stress 6, traction 3, jump 3, opening 1).
    pub fn values(&self, state: &[f64]) -> Vec<f64> {
        match self.kind {
            ProbeElement::Slab => state[..6].to_vec(),
            ProbeElement::Interface => interface_values(&state[6..9], &state[9..12], state[12]).to_vec(),
        }
    }
}

/// σ_n (compression +), τ_s, τ_a, δ_s, δ_a, δ_n, opening from an interface element's mean
/// traction (τ_s, τ_a, t_n), mean jump and opening.
pub fn interface_values(traction: &[f64], jump: &[f64], opening: f64) -> [f64; 7] {
    // + 0.0 turns the −0 of an unloaded element into 0
    [
        -traction[2] + 0.0,
        traction[0],
        traction[1],
        jump[0],
        jump[1],
        jump[2],
        opening,
    ]
}

/// The probes of `spec` that lie on an element of their kind, in the scene's order (the columns
/// of [`crate::solver::SolveReport::probes`]); a probe without elements of its kind is left out.
pub fn probe_elements(mesh: &Mesh, spec: &ProfilesSpec) -> Vec<QuakeProbe> {
    spec.probes
        .iter()
        .filter_map(|p| {
            probe_element(mesh, spec, p).map(|element| QuakeProbe {
                name: p.name.clone(),
                kind: p.element,
                element,
            })
        })
        .collect()
}

/// A row of [`crate::solver::SolveReport::probes`]: `t`, then the values of each probe from
/// `states`, [`ELEMENT_STATE`] per probe in the order of `probes`.
pub fn probe_row(t: f64, probes: &[QuakeProbe], states: &[f64]) -> Vec<f64> {
    let mut row = vec![t];
    for (p, state) in probes.iter().zip(states.chunks(ELEMENT_STATE)) {
        row.extend(p.values(state));
    }
    row
}

/// The histories of the probes: per sample its time and the probes' values side by side.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeHistory {
    /// The `#` line of the CSV tables saying how the history was sampled.
    pub sampling: String,
    /// Per sample: the time (s), then the values of each probe ([`QuakeProbe::width`]).
    pub rows: Vec<Vec<f64>>,
}

impl ProbeHistory {
    /// The history recorded at every time step of the stages `stage` (`rows` of
    /// [`crate::solver::SolveReport::probes`]); `None` without rows or when a row does not fit
    /// `probes`.
    pub fn from_steps(stage: &str, probes: &[QuakeProbe], rows: &[Vec<f64>]) -> Option<Self> {
        let width = 1 + probes.iter().map(QuakeProbe::width).sum::<usize>();
        if rows.is_empty() || rows.iter().any(|r| r.len() != width) {
            return None;
        }
        Some(ProbeHistory {
            sampling: format!(
                "# sampled at every converged time step of {} '{stage}' ({} rows); t = 0 is the state before the quake",
                crate::post::quake_fields::stage_word(stage),
                rows.len()
            ),
            rows: rows.to_vec(),
        })
    }

    /// The history at the results steps of `q`; interface probes read zeros when the results
    /// hold no interface fields.
    pub fn from_results(q: &QuakeFields, probes: &[QuakeProbe]) -> Self {
        let rows = q
            .times()
            .zip(q.states())
            .map(|(t, f)| {
                let states: Vec<f64> = probes.iter().flat_map(|p| element_state(f, p.element)).collect();
                probe_row(t, probes, &states)
            })
            .collect();
        ProbeHistory {
            sampling: q.sampling(),
            rows,
        }
    }

    /// Time and values of the probe whose values start at column `offset` of the values.
    fn series<'a>(&'a self, offset: usize, width: usize) -> impl Iterator<Item = (f64, &'a [f64])> + 'a {
        self.rows
            .iter()
            .map(move |r| (r[0], &r[1 + offset..1 + offset + width]))
    }
}

/// The element state of [`crate::solver::Problem::element_states`] of element `e` from the
/// fields of a results step (zeros for fields the step lacks).
fn element_state(f: &StageFields, e: usize) -> [f64; ELEMENT_STATE] {
    let mut s = [0.0; ELEMENT_STATE];
    let mut copy = |field: &[f64], n: usize, at: usize| {
        if let Some(v) = field.get(n * e..n * e + n) {
            s[at..at + n].copy_from_slice(v);
        }
    };
    copy(&f.stress, 6, 0);
    copy(&f.interface_traction, 3, 6);
    copy(&f.interface_jump, 3, 9);
    copy(&f.interface_opening, 1, 12);
    s
}

/// Writes Figs. 14, 18–19 of each probe and Fig. 20 of the interface probes (module docs) from
/// `h` into `dir`; returns nothing for probes that are not there.
pub fn write_probe_figures(
    mesh: &Mesh,
    probes: &[QuakeProbe],
    h: &ProbeHistory,
    dir: &Path,
    files: &mut Vec<PathBuf>,
) -> Result<(), String> {
    let mut out = ProbeOut {
        mesh,
        sampling: &h.sampling,
        dir,
        files,
    };
    let mut offset = 0;
    let mut openings = Vec::new();
    for p in probes {
        match p.kind {
            ProbeElement::Slab => fig14(&mut out, p, h.series(offset, 6))?,
            ProbeElement::Interface => {
                fig18(&mut out, p, h.series(offset, 7))?;
                openings.push((p.name.as_str(), offset + 6));
            }
        }
        offset += p.width();
    }
    if !openings.is_empty() {
        fig20(&openings, h, dir, out.files)?;
    }
    Ok(())
}

/// Where a probe's figures go, and the sampling note of their tables.
struct ProbeOut<'a> {
    mesh: &'a Mesh,
    sampling: &'a str,
    dir: &'a Path,
    files: &'a mut Vec<PathBuf>,
}

/// Fig. 14: σ_s, σ_a history of a slab probe.
fn fig14<'a>(
    out: &mut ProbeOut,
    p: &QuakeProbe,
    series: impl Iterator<Item = (f64, &'a [f64])>,
) -> Result<(), String> {
    let (mesh, sampling, dir) = (out.mesh, out.sampling, out.dir);
    let files = &mut *out.files;
    let frame = slab_frame(&mesh.element_coords(p.element));
    let mut csv = format!("{sampling}\nt_s,sigma_slope_Pa,sigma_axis_Pa\n");
    let (mut s, mut a) = (Vec::new(), Vec::new());
    for (t, v) in series {
        let sig = stress_tensor(v);
        let (ss, sa) = (frame.s.dot(&(sig * frame.s)), frame.a.dot(&(sig * frame.a)));
        let _ = writeln!(csv, "{t},{ss},{sa}");
        s.push((t, ss / 1e6));
        a.push((t, sa / 1e6));
    }
    let (name, safe) = (&p.name, safe_name(&p.name));
    csv_out(dir, files, &format!("fig14_slab_probe_{safe}.csv"), csv)?;
    let z = centre(mesh, p.element)[2];
    let fig = Figure::new(format!("Slab element {name} at z = {z:.0} m (seed Fig. 14)"))
        .with(
            Panel::new("Stress along the slope (tension +)", "t (s)", "sigma_s (MPa)")
                .with(Series::line("", s)),
        )
        .with(
            Panel::new("Stress along the dam axis (tension +)", "t (s)", "sigma_a (MPa)")
                .with(Series::line("", a)),
        )
        .columns(1);
    png_out(dir, files, &format!("fig14_slab_probe_{safe}.png"), fig)?;
    Ok(())
}

/// Figs. 18–19: stress and displacement history of an interface probe.
fn fig18<'a>(
    out: &mut ProbeOut,
    p: &QuakeProbe,
    series: impl Iterator<Item = (f64, &'a [f64])>,
) -> Result<(), String> {
    let header = "t_s,sigma_n_Pa,tau_s_Pa,tau_a_Pa,delta_s_m,delta_a_m,delta_n_m,opening_m";
    let mut csv = format!("{}\n{header}\n", out.sampling);
    let (mesh, dir, files) = (out.mesh, out.dir, &mut *out.files);
    let mut cols: [Vec<(f64, f64)>; 7] = Default::default();
    let scale = [1e-3, 1e-3, 1e-3, 1e3, 1e3, 1e3, 1e3];
    for (t, v) in series {
        let row: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        let _ = writeln!(csv, "{t},{}", row.join(","));
        for (c, col) in cols.iter_mut().enumerate() {
            col.push((t, v[c] * scale[c]));
        }
    }
    let (name, safe) = (&p.name, safe_name(&p.name));
    csv_out(dir, files, &format!("fig18_interface_probe_{safe}.csv"), csv)?;
    let [sn, ts, ta, ds, da, dn, op] = cols;
    let z = centre(mesh, p.element)[2];
    let fig = Figure::new(format!(
        "Interface element {name} at z = {z:.0} m (seed Figs. 18-20)"
    ))
    .with(
        Panel::new("Stresses", "t (s)", "kPa")
            .with(Series::line("sigma_n (compression +)", sn))
            .with(Series::line("tau_s (slope)", ts))
            .with(Series::line("tau_a (axis)", ta)),
    )
    .with(
        Panel::new("Displacements (cushion relative to slab)", "t (s)", "mm")
            .with(Series::line("delta_s (up-slope)", ds))
            .with(Series::line("delta_a (axis)", da))
            .with(Series::line("delta_n (opening +)", dn)),
    )
    .with(Panel::new("Opening", "t (s)", "mm").with(Series::line("", op)))
    .columns(1);
    png_out(dir, files, &format!("fig18_interface_probe_{safe}.png"), fig)?;
    Ok(())
}

/// Fig. 20: opening history of every interface probe (`openings`: name, column of its opening
/// among the values).
fn fig20(
    openings: &[(&str, usize)],
    h: &ProbeHistory,
    dir: &Path,
    files: &mut Vec<PathBuf>,
) -> Result<(), String> {
    let names: Vec<String> = openings
        .iter()
        .map(|(n, _)| format!("opening_{}_m", safe_name(n)))
        .collect();
    let mut csv = format!("{}\nt_s,{}\n", h.sampling, names.join(","));
    for (t, v) in h.series(0, h.rows.first().map_or(0, |r| r.len() - 1)) {
        let row: Vec<String> = openings.iter().map(|(_, c)| v[*c].to_string()).collect();
        let _ = writeln!(csv, "{t},{}", row.join(","));
    }
    csv_out(dir, files, "fig20_opening.csv", csv)?;
    let mut panel = Panel::new("Slab-cushion opening", "t (s)", "opening (mm)");
    for (name, c) in openings {
        let points = h.series(*c, 1).map(|(t, v)| (t, v[0] * 1e3)).collect();
        panel.push(Series::line(name.to_string(), points));
    }
    let fig = Figure::new("Opening history of the interface probes (seed Fig. 20)")
        .with(panel)
        .columns(1);
    png_out(dir, files, "fig20_opening.png", fig)?;
    Ok(())
}
