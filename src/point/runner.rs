//! Runs a point-test file: validates it, drives the material, writes one CSV per run and one PNG
//! figure per file.

use super::csv::write_csv;
use super::solid::{oedometer_steps, run_solid_path, triaxial_steps, SolidRow};
use super::spec::{DirectShearTest, JumpPathTest, NormalControlKind, PointTestFile, ScalarPath, TestSpec};
use crate::material::driver_interface::{
    direct_shear, jump_path, jump_path_increments, InterfaceRow, NormalControl,
};
use crate::material::{InterfaceModel, InterfaceVisitor, SolidModel, SolidVisitor};
use crate::plot::{Figure, Panel, PlotError, Series};
use crate::tensor::{Local3, Stress6};
use std::fmt;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A point test that could not be run. Every variant names the file; validation errors name
/// the YAML path of the offending field.
#[derive(Debug, Error)]
pub enum PointError {
    /// The file or an output could not be read/written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The YAML does not match the format (unknown key, wrong type, missing field).
    #[error("{file}: {message}")]
    Parse {
        /// The test file.
        file: PathBuf,
        /// serde_yaml's message, which gives the YAML path and line.
        message: String,
    },
    /// A value is out of range or inconsistent.
    #[error("{file}: {field}: {reason}")]
    Invalid {
        /// The test file.
        file: PathBuf,
        /// YAML path of the field, e.g. `interface.phi` or `test.normal_stresses[1]`.
        field: String,
        /// Why it is rejected.
        reason: String,
    },
    /// The material or the driver failed during a run.
    #[error("{file}: run '{case}': {message}")]
    Run {
        /// The test file.
        file: PathBuf,
        /// Label of the run.
        case: String,
        /// What failed.
        message: String,
    },
    /// The figure could not be written.
    #[error("{file}: {source}")]
    Plot {
        /// The test file.
        file: PathBuf,
        /// The plot error.
        source: PlotError,
    },
}

/// What one run of a test produced.
#[derive(Debug, Clone, PartialEq)]
pub struct CaseSummary {
    /// Label, e.g. `sigma_n = 100 kPa`.
    pub label: String,
    /// Number of steps.
    pub steps: usize,
    /// Largest resultant shear stress (interface) or deviator q (solid) reached, Pa.
    pub peak: f64,
    /// The same quantity at the end of the run, Pa.
    pub last: f64,
    /// The CSV written.
    pub csv: PathBuf,
}

/// What a test file produced.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Title of the test.
    pub title: String,
    /// Model tag, e.g. `hyperbolic`.
    pub model: String,
    /// Test kind, e.g. `direct_shear`.
    pub kind: String,
    /// One entry per run.
    pub cases: Vec<CaseSummary>,
    /// The PNG figure written.
    pub png: PathBuf,
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{} ({} / {})", self.title, self.model, self.kind)?;
        let what = if self.kind == "triaxial" || self.kind == "oedometer" {
            "q"
        } else {
            "tau"
        };
        for c in &self.cases {
            writeln!(
                f,
                "  {:<28} {:>7} steps  peak {what} {:>10.2} kPa  last {:>10.2} kPa  -> {}",
                c.label,
                c.steps,
                c.peak / 1e3,
                c.last / 1e3,
                c.csv.display()
            )?;
        }
        write!(f, "  figure -> {}", self.png.display())
    }
}

/// Reads, validates and runs the test file `path`; writes `<stem>_<case>.csv` files and
/// `<stem>.png` into `out_dir` (created if needed).
pub fn run_file(path: &Path, out_dir: &Path) -> Result<Summary, PointError> {
    let file = path.to_path_buf();
    let text = std::fs::read_to_string(path).map_err(|source| PointError::Io {
        path: file.clone(),
        source,
    })?;
    let spec = parse(&text).map_err(|message| PointError::Parse {
        file: file.clone(),
        message,
    })?;
    validate(&spec).map_err(|(field, reason)| PointError::Invalid {
        file: file.clone(),
        field,
        reason,
    })?;
    std::fs::create_dir_all(out_dir).map_err(|source| PointError::Io {
        path: out_dir.to_path_buf(),
        source,
    })?;
    let stem = path
        .file_stem()
        .map_or("point".into(), |s| s.to_string_lossy().into_owned());
    let title = spec.title.clone().unwrap_or_else(|| stem.clone());
    let out = Output {
        file: &file,
        dir: out_dir,
        stem: &stem,
    };
    let (model, cases, figure) = match (&spec.test, &spec.interface, &spec.solid) {
        (TestSpec::DirectShear(t), Some(p), _) => {
            let dir = t.direction_deg.to_radians();
            let (c, s) = (dir.cos(), dir.sin());
            let inc: Vec<[f64; 2]> = t.path.increments().iter().map(|u| [u * c, u * s]).collect();
            let mut runs = Vec::new();
            for &sigma_n in &t.normal_stresses {
                let label = format!("sigma_n = {} kPa", fmt_num(sigma_n / 1e3));
                let rows = p
                    .visit(ShearRun {
                        control: normal_control(t, sigma_n),
                        increments: &inc,
                    })
                    .map_err(|e| out.run_error(&label, e.to_string()))?
                    .map_err(|e| out.run_error(&label, e))?;
                runs.push((label, format!("sn{}kPa", fmt_num(sigma_n / 1e3)), rows));
            }
            let cases = out.interface_csvs(&runs)?;
            (p.name(), cases, shear_figure(&title, p.name(), t, [c, s], &runs))
        }
        (TestSpec::JumpPath(t), Some(p), _) => {
            let label = format!("sigma_n0 = {} kPa", fmt_num(t.sigma_n0 / 1e3));
            let rows = p
                .visit(JumpRun { test: t })
                .map_err(|e| out.run_error(&label, e.to_string()))?
                .map_err(|e| out.run_error(&label, e))?;
            let runs = vec![(label, "path".to_string(), rows)];
            let cases = out.interface_csvs(&runs)?;
            (p.name(), cases, jump_figure(&title, p.name(), &runs))
        }
        (TestSpec::Triaxial(t), _, Some(p)) => {
            let inc = t.path.increments();
            let mut runs = Vec::new();
            for &s3 in &t.confining_pressures {
                let label = format!("sigma_3 = {} kPa", fmt_num(s3 / 1e3));
                let rows = p
                    .visit(SolidRun {
                        sigma0: Stress6::isotropic(-s3),
                        steps: triaxial_steps(s3, &inc),
                    })
                    .map_err(|e| out.run_error(&label, e.to_string()))?
                    .map_err(|(step, e)| out.run_error(&label, format!("step {step}: {e}")))?;
                runs.push((label, format!("s3_{}kPa", fmt_num(s3 / 1e3)), rows));
            }
            let cases = out.solid_csvs(&runs)?;
            (p.name(), cases, solid_figure(&title, p.name(), "triaxial", &runs))
        }
        (TestSpec::Oedometer(t), _, Some(p)) => {
            let label = format!("p0 = {} kPa", fmt_num(t.initial_pressure / 1e3));
            let rows = p
                .visit(SolidRun {
                    sigma0: Stress6::isotropic(-t.initial_pressure),
                    steps: oedometer_steps(&t.path.increments()),
                })
                .map_err(|e| out.run_error(&label, e.to_string()))?
                .map_err(|(step, e)| out.run_error(&label, format!("step {step}: {e}")))?;
            let runs = vec![(label, "oedometer".to_string(), rows)];
            let cases = out.solid_csvs(&runs)?;
            (
                p.name(),
                cases,
                solid_figure(&title, p.name(), "oedometer", &runs),
            )
        }
        _ => unreachable!("validate() pairs the test kind with its material"),
    };
    let png = out_dir.join(format!("{stem}.png"));
    figure.save_png(&png).map_err(|source| PointError::Plot {
        file: file.clone(),
        source,
    })?;
    Ok(Summary {
        title,
        model: model.to_string(),
        kind: spec.test.name().to_string(),
        cases,
        png,
    })
}

/// Top level of a test file, sections kept as YAML values so that each is parsed on its own and
/// its errors carry the section's path (serde loses the path inside tagged enums).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    #[serde(default)]
    title: Option<String>,
    #[serde(default)]
    interface: Option<serde_yaml::Value>,
    #[serde(default)]
    solid: Option<serde_yaml::Value>,
    test: serde_yaml::Value,
}

/// Parses a test file; the message names the YAML path of the error.
fn parse(text: &str) -> Result<PointTestFile, String> {
    fn section<T: serde::de::DeserializeOwned>(value: serde_yaml::Value, path: &str) -> Result<T, String> {
        serde_yaml::from_value(value).map_err(|e| format!("{path}: {e}"))
    }
    let raw: RawFile = serde_yaml::from_str(text).map_err(|e| e.to_string())?;
    if let Some(path) = raw.test.get("path") {
        section::<ScalarPath>(path.clone(), "test.path")?;
    }
    Ok(PointTestFile {
        title: raw.title,
        interface: raw.interface.map(|v| section(v, "interface")).transpose()?,
        solid: raw.solid.map(|v| section(v, "solid")).transpose()?,
        test: section(raw.test, "test")?,
    })
}

/// Checks the file beyond its format; errors are (YAML path, reason).
fn validate(spec: &PointTestFile) -> Result<(), (String, String)> {
    let err = |f: &str, r: &str| Err((f.to_string(), r.to_string()));
    match (&spec.interface, &spec.solid) {
        (Some(_), Some(_)) => return err("solid", "give either `interface` or `solid`, not both"),
        (None, None) => return err("interface", "missing: give an `interface` or a `solid` material"),
        _ => {}
    }
    if let Some(p) = &spec.interface {
        p.validate()
            .map_err(|e| (format!("interface.{}", e.field), e.reason))?;
        if !spec.test.is_interface() {
            return err(
                "test.kind",
                &format!(
                    "`{}` is a solid test; this file has an interface law",
                    spec.test.name()
                ),
            );
        }
    }
    if let Some(p) = &spec.solid {
        p.validate()
            .map_err(|e| (format!("solid.{}", e.field), e.reason))?;
        if spec.test.is_interface() {
            return err(
                "test.kind",
                &format!(
                    "`{}` is an interface test; this file has a solid model",
                    spec.test.name()
                ),
            );
        }
    }
    let list = |name: &str, values: &[f64], positive: bool| -> Result<(), (String, String)> {
        if values.is_empty() {
            return Err((format!("test.{name}"), "must list at least one value".into()));
        }
        for (i, v) in values.iter().enumerate() {
            if !(v.is_finite() && (*v > 0.0 || (!positive && *v == 0.0))) {
                let what = if positive { "> 0" } else { ">= 0" };
                return Err((
                    format!("test.{name}[{i}]"),
                    format!("must be a finite number {what} (Pa, compression positive), got {v}"),
                ));
            }
        }
        Ok(())
    };
    match &spec.test {
        TestSpec::DirectShear(t) => {
            list("normal_stresses", &t.normal_stresses, false)?;
            match (t.control, t.normal_stiffness) {
                (NormalControlKind::Cns, None) => {
                    return err("test.normal_stiffness", "required by `control: cns` (Pa/m)")
                }
                (NormalControlKind::Cns, Some(k)) if !(k.is_finite() && k >= 0.0) => {
                    return err("test.normal_stiffness", "must be a finite number >= 0 (Pa/m)")
                }
                (NormalControlKind::Cnl, Some(_)) => {
                    return err("test.normal_stiffness", "only used with `control: cns`")
                }
                _ => {}
            }
            if !t.direction_deg.is_finite() {
                return err("test.direction_deg", "must be finite");
            }
            t.path.validate("test.path")
        }
        TestSpec::JumpPath(t) => {
            list("sigma_n0", &[t.sigma_n0], false).map_err(|(_, r)| ("test.sigma_n0".to_string(), r))?;
            if t.waypoints.is_empty() || t.waypoints.iter().flatten().any(|v| !v.is_finite()) {
                return err(
                    "test.waypoints",
                    "must list at least one finite point [d_s, d_a, d_n] (m)",
                );
            }
            if t.steps_per_segment == 0 {
                return err("test.steps_per_segment", "must be at least 1");
            }
            Ok(())
        }
        TestSpec::Triaxial(t) => {
            list("confining_pressures", &t.confining_pressures, true)?;
            t.path.validate("test.path")
        }
        TestSpec::Oedometer(t) => {
            list("initial_pressure", &[t.initial_pressure], false)
                .map_err(|(_, r)| ("test.initial_pressure".to_string(), r))?;
            t.path.validate("test.path")
        }
    }
}

fn normal_control(t: &DirectShearTest, sigma_n: f64) -> NormalControl {
    match t.control {
        NormalControlKind::Cnl => NormalControl::ConstantLoad { sigma_n },
        NormalControlKind::Cns => NormalControl::ConstantStiffness {
            sigma_n0: sigma_n,
            stiffness: t.normal_stiffness.unwrap_or(0.0),
        },
    }
}

/// Number without trailing zeros (at most 3 decimals).
fn fmt_num(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

struct ShearRun<'a> {
    control: NormalControl,
    increments: &'a [[f64; 2]],
}

impl InterfaceVisitor for ShearRun<'_> {
    type Output = Result<Vec<InterfaceRow>, String>;
    fn visit<M: InterfaceModel>(self, model: &M) -> Self::Output {
        direct_shear(model, self.control, self.increments).map_err(|e| e.to_string())
    }
}

struct JumpRun<'a> {
    test: &'a JumpPathTest,
}

impl InterfaceVisitor for JumpRun<'_> {
    type Output = Result<Vec<InterfaceRow>, String>;
    fn visit<M: InterfaceModel>(self, model: &M) -> Self::Output {
        let inc: Vec<Local3> = jump_path_increments(&self.test.waypoints, self.test.steps_per_segment);
        jump_path(model, self.test.sigma_n0, &inc).map_err(|e| e.to_string())
    }
}

struct SolidRun {
    sigma0: Stress6,
    steps: Vec<[super::solid::Control; 6]>,
}

impl SolidVisitor for SolidRun {
    type Output = Result<Vec<SolidRow>, (usize, crate::error::MaterialError)>;
    fn visit<M: SolidModel>(self, model: &M) -> Self::Output {
        run_solid_path(model, &self.sigma0, &self.steps)
    }
}

/// Where results go.
struct Output<'a> {
    file: &'a Path,
    dir: &'a Path,
    stem: &'a str,
}

/// Interface CSV header (SI; σ_n compression positive, t_n tension positive).
const INTERFACE_HEADER: [&str; 14] = [
    "step",
    "delta_s_m",
    "delta_a_m",
    "delta_n_m",
    "tau_s_Pa",
    "tau_a_Pa",
    "t_n_Pa",
    "sigma_n_Pa",
    "tau_Pa",
    "slip_s_m",
    "slip_a_m",
    "normal_m",
    "opening_m",
    "substeps",
];

/// Solid CSV header (SI, tension positive, except p, q, eps_a, eps_v: compression positive).
const SOLID_HEADER: [&str; 17] = [
    "step",
    "eps_xx",
    "eps_yy",
    "eps_zz",
    "gam_xy",
    "gam_yz",
    "gam_zx",
    "sig_xx_Pa",
    "sig_yy_Pa",
    "sig_zz_Pa",
    "sig_xy_Pa",
    "sig_yz_Pa",
    "sig_zx_Pa",
    "p_Pa",
    "q_Pa",
    "eps_a",
    "eps_v",
];

impl Output<'_> {
    fn run_error(&self, case: &str, message: String) -> PointError {
        PointError::Run {
            file: self.file.to_path_buf(),
            case: case.to_string(),
            message,
        }
    }

    fn csv(&self, suffix: &str, header: &[&str], rows: &[Vec<f64>]) -> Result<PathBuf, PointError> {
        let path = self.dir.join(format!("{}_{suffix}.csv", self.stem));
        write_csv(&path, header, rows).map_err(|source| PointError::Io {
            path: path.clone(),
            source,
        })?;
        Ok(path)
    }

    fn interface_csvs(
        &self,
        runs: &[(String, String, Vec<InterfaceRow>)],
    ) -> Result<Vec<CaseSummary>, PointError> {
        runs.iter()
            .map(|(label, suffix, rows)| {
                let table: Vec<Vec<f64>> = rows
                    .iter()
                    .map(|r| {
                        vec![
                            r.step as f64,
                            r.jump[0],
                            r.jump[1],
                            r.jump[2],
                            r.traction[0],
                            r.traction[1],
                            r.traction[2],
                            r.sigma_n,
                            r.tau,
                            r.slip[0],
                            r.slip[1],
                            r.normal,
                            r.opening,
                            r.substeps as f64,
                        ]
                    })
                    .collect();
                Ok(CaseSummary {
                    label: label.clone(),
                    steps: rows.len() - 1,
                    peak: rows.iter().map(|r| r.tau).fold(0.0, f64::max),
                    last: rows.last().map_or(0.0, |r| r.tau),
                    csv: self.csv(suffix, &INTERFACE_HEADER, &table)?,
                })
            })
            .collect()
    }

    fn solid_csvs(&self, runs: &[(String, String, Vec<SolidRow>)]) -> Result<Vec<CaseSummary>, PointError> {
        runs.iter()
            .map(|(label, suffix, rows)| {
                let table: Vec<Vec<f64>> = rows
                    .iter()
                    .map(|r| {
                        let (p, q, ea, ev) = solid_invariants(r);
                        let mut v = vec![r.step as f64];
                        v.extend_from_slice(&r.strain);
                        v.extend_from_slice(&r.stress);
                        v.extend_from_slice(&[p, q, ea, ev]);
                        v
                    })
                    .collect();
                Ok(CaseSummary {
                    label: label.clone(),
                    steps: rows.len() - 1,
                    peak: rows
                        .iter()
                        .map(|r| solid_invariants(r).1)
                        .fold(f64::MIN, f64::max),
                    last: rows.last().map_or(0.0, |r| solid_invariants(r).1),
                    csv: self.csv(suffix, &SOLID_HEADER, &table)?,
                })
            })
            .collect()
    }
}

/// Compression-positive triaxial quantities of a row: p = −tr σ/3, q = σ_a − σ_r with
/// σ_a = −σ_zz and σ_r = −(σ_xx + σ_yy)/2, ε_a = −ε_zz, ε_v = −tr ε.
fn solid_invariants(r: &SolidRow) -> (f64, f64, f64, f64) {
    let s = &r.stress;
    let p = -(s[0] + s[1] + s[2]) / 3.0;
    let q = 0.5 * (s[0] + s[1]) - s[2];
    (p, q, -r.strain[2], -(r.strain[0] + r.strain[1] + r.strain[2]))
}

fn shear_figure(
    title: &str,
    model: &str,
    t: &DirectShearTest,
    dir: [f64; 2],
    runs: &[(String, String, Vec<InterfaceRow>)],
) -> Figure {
    let control = match t.control {
        NormalControlKind::Cnl => "CNL",
        NormalControlKind::Cns => "CNS",
    };
    let path = match t.path {
        ScalarPath::Monotonic(_) => "monotonic",
        ScalarPath::Cyclic(_) => "cyclic",
        ScalarPath::Waypoints(_) => "waypoints",
    };
    let u = |r: &InterfaceRow| 1e3 * (r.jump[0] * dir[0] + r.jump[1] * dir[1]);
    let tau = |r: &InterfaceRow| 1e-3 * (r.traction[0] * dir[0] + r.traction[1] * dir[1]);
    let mut stress = Panel::new(
        "Shear stress - displacement",
        "shear displacement u (mm)",
        "shear stress tau (kPa)",
    );
    let mut normal = Panel::new(
        "Normal displacement",
        "shear displacement u (mm)",
        "normal jump delta_n (mm, + opening)",
    );
    let mut spath = Panel::new(
        "Stress path",
        "normal stress sigma_n (kPa, compression +)",
        "shear stress tau (kPa)",
    );
    let mut ratio = Panel::new("Stress ratio", "shear displacement u (mm)", "tau / sigma_n (-)");
    for (label, _, rows) in runs {
        stress.push(Series::line(
            label.clone(),
            rows.iter().map(|r| (u(r), tau(r))).collect(),
        ));
        normal.push(Series::line(
            label.clone(),
            rows.iter().map(|r| (u(r), 1e3 * r.jump[2])).collect(),
        ));
        spath.push(Series::line(
            label.clone(),
            rows.iter().map(|r| (1e-3 * r.sigma_n, tau(r))).collect(),
        ));
        ratio.push(Series::line(
            label.clone(),
            rows.iter()
                .filter(|r| r.sigma_n > 0.0)
                .map(|r| (u(r), 1e3 * tau(r) / r.sigma_n))
                .collect(),
        ));
    }
    Figure::new(format!("{title}  [{model}, {control} {path} direct shear]"))
        .with(stress)
        .with(normal)
        .with(spath)
        .with(ratio)
}

fn jump_figure(title: &str, model: &str, runs: &[(String, String, Vec<InterfaceRow>)]) -> Figure {
    let mut tr = Panel::new("Tractions", "step", "stress (kPa)");
    let mut jumps = Panel::new("Prescribed jump", "step", "jump (mm, delta_n + opening)");
    let mut spath = Panel::new(
        "Stress path",
        "normal stress sigma_n (kPa, compression +)",
        "resultant shear tau (kPa)",
    );
    let mut normal = Panel::new("Normal deformation and opening", "step", "(mm)");
    for (_, _, rows) in runs {
        let by_step = |f: &dyn Fn(&InterfaceRow) -> f64| -> Vec<(f64, f64)> {
            rows.iter().map(|r| (r.step as f64, f(r))).collect()
        };
        tr.push(Series::line("tau_s", by_step(&|r| 1e-3 * r.traction[0])));
        tr.push(Series::line("tau_a", by_step(&|r| 1e-3 * r.traction[1])));
        tr.push(Series::line("sigma_n", by_step(&|r| 1e-3 * r.sigma_n)));
        for (i, name) in ["delta_s", "delta_a", "delta_n"].iter().enumerate() {
            jumps.push(Series::line(*name, by_step(&|r| 1e3 * r.jump[i])));
        }
        spath.push(Series::line(
            "",
            rows.iter().map(|r| (1e-3 * r.sigma_n, 1e-3 * r.tau)).collect(),
        ));
        normal.push(Series::line(
            "normal deformation (closure +)",
            by_step(&|r| 1e3 * r.normal),
        ));
        normal.push(Series::line("opening", by_step(&|r| 1e3 * r.opening)));
    }
    Figure::new(format!("{title}  [{model}, jump path]"))
        .with(tr)
        .with(jumps)
        .with(spath)
        .with(normal)
}

fn solid_figure(title: &str, model: &str, kind: &str, runs: &[(String, String, Vec<SolidRow>)]) -> Figure {
    let mut q_ea = Panel::new(
        "Deviator stress",
        "axial strain eps_a (%, compression +)",
        "q = sigma_a - sigma_r (kPa)",
    );
    let mut ev_ea = Panel::new(
        "Volumetric strain",
        "axial strain eps_a (%, compression +)",
        "eps_v (%, compression +)",
    );
    let mut pq = Panel::new("Stress path", "p (kPa, compression +)", "q (kPa)");
    let mut sv = Panel::new(
        "Axial stress",
        "axial strain eps_a (%, compression +)",
        "sigma_a (kPa, compression +)",
    );
    for (label, _, rows) in runs {
        let inv: Vec<(f64, f64, f64, f64, f64)> = rows
            .iter()
            .map(|r| {
                let (p, q, ea, ev) = solid_invariants(r);
                (p, q, ea, ev, -r.stress[2])
            })
            .collect();
        q_ea.push(Series::line(
            label.clone(),
            inv.iter().map(|v| (100.0 * v.2, 1e-3 * v.1)).collect(),
        ));
        ev_ea.push(Series::line(
            label.clone(),
            inv.iter().map(|v| (100.0 * v.2, 100.0 * v.3)).collect(),
        ));
        pq.push(Series::line(
            label.clone(),
            inv.iter().map(|v| (1e-3 * v.0, 1e-3 * v.1)).collect(),
        ));
        sv.push(Series::line(
            label.clone(),
            inv.iter().map(|v| (100.0 * v.2, 1e-3 * v.4)).collect(),
        ));
    }
    Figure::new(format!("{title}  [{model}, {kind}]"))
        .with(q_ea)
        .with(ev_ea)
        .with(pq)
        .with(sv)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn examples() -> Vec<PathBuf> {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/point");
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "yaml"))
            .collect();
        files.sort();
        files
    }

    /// Every example in inputs/point runs and writes non-empty CSVs and a PNG (into
    /// `$CFRD_POINT_OUT` when set, to look at them; else a temporary directory).
    #[test]
    fn examples_run_and_write_csv_and_png() {
        let tmp = tempfile::tempdir().unwrap();
        let out_dir = std::env::var_os("CFRD_POINT_OUT").map_or(tmp.path().to_path_buf(), PathBuf::from);
        let out = out_dir.as_path();
        let files = examples();
        assert!(files.len() >= 8, "{files:?}");
        let mut kinds = std::collections::BTreeSet::new();
        for f in &files {
            let s = run_file(f, out).unwrap_or_else(|e| panic!("{e}"));
            kinds.insert(s.kind.clone());
            assert!(!s.cases.is_empty());
            for c in &s.cases {
                let text = std::fs::read_to_string(&c.csv).unwrap();
                assert_eq!(text.lines().count(), c.steps + 2, "{}", c.csv.display());
                assert!(c.steps > 0 && c.peak.is_finite());
            }
            let png = std::fs::read(&s.png).unwrap();
            assert!(
                png.starts_with(b"\x89PNG") && png.len() > 10_000,
                "{}",
                s.png.display()
            );
            assert!(s.to_string().contains(&s.title));
        }
        assert_eq!(kinds.len(), 4, "{kinds:?}");
    }

    /// HY-1 through the runner: the CSV of the 100 kPa run holds τ(30 mm) ≈ 63 kPa.
    #[test]
    fn hyperbolic_example_reproduces_hy1() {
        let out = tempfile::tempdir().unwrap();
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs/point/hyperbolic_cnl_monotonic.yaml");
        let s = run_file(&file, out.path()).unwrap();
        let text = std::fs::read_to_string(&s.cases[0].csv).unwrap();
        let row: Vec<f64> = text
            .lines()
            .nth(151)
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert!(
            (row[1] - 0.03).abs() < 1e-12 && (row[8] - 63e3).abs() < 0.01 * 63e3,
            "{row:?}"
        );
    }

    fn run_text(text: &str) -> PointError {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("bad.yaml");
        std::fs::write(&file, text).unwrap();
        run_file(&file, dir.path()).unwrap_err()
    }

    const GOOD_TEST: &str = "test:\n  kind: direct_shear\n  normal_stresses: [1.0e5]\n  path: {kind: monotonic, target: 0.01, steps: 5}\n";

    /// Bad files give errors that name the file and the YAML path of the field.
    #[test]
    fn bad_yaml_names_the_path() {
        let cases = [
            (format!("interface:\n  model: hyperbolic\n  k3: 1.0\n{GOOD_TEST}"), vec!["bad.yaml", "interface", "k3"]),
            (format!("interface:\n  model: hyperbolic\n  phi: 120.0\n{GOOD_TEST}"), vec!["bad.yaml", "interface.phi"]),
            (format!("interface:\n  model: cam_clay\n{GOOD_TEST}"), vec!["interface", "cam_clay"]),
            (
                "interface: {model: joint}\ntest:\n  kind: direct_shear\n  normal_stresses: [1.0e5]\n  path: {kind: monotonic, target: 0.01, steps: 5, extra: 1}\n".to_string(),
                vec!["test.path", "extra"],
            ),
            (
                "interface: {model: joint}\ntest:\n  kind: direct_shear\n  normal_stresses: [1.0e5, -2.0]\n  path: {kind: monotonic, target: 0.01, steps: 5}\n".to_string(),
                vec!["test.normal_stresses[1]"],
            ),
            (
                "interface: {model: joint}\ntest:\n  kind: direct_shear\n  control: cns\n  normal_stresses: [1.0e5]\n  path: {kind: monotonic, target: 0.01, steps: 5}\n".to_string(),
                vec!["test.normal_stiffness"],
            ),
            (
                "interface: {model: joint}\ntest:\n  kind: direct_shear\n  normal_stresses: [1.0e5]\n  path: {kind: monotonic, target: 0.01, steps: 0}\n".to_string(),
                vec!["test.path.steps"],
            ),
            (
                "solid: {model: elastic, young: 1.0e7, poisson: 0.3, density: 2000.0}\n".to_string() + GOOD_TEST,
                vec!["test.kind", "direct_shear"],
            ),
            (
                "solid: {model: elastic, young: -1.0, poisson: 0.3, density: 2000.0}\ntest: {kind: oedometer, initial_pressure: 1.0e5, path: {kind: monotonic, target: 0.01, steps: 3}}\n".to_string(),
                vec!["solid.young"],
            ),
            (GOOD_TEST.to_string(), vec!["interface", "missing"]),
        ];
        for (text, needles) in cases {
            let msg = run_text(&text).to_string();
            for n in needles {
                assert!(msg.contains(n), "'{msg}' does not name '{n}'");
            }
        }
        let missing = run_file(Path::new("/nonexistent/x.yaml"), Path::new("/tmp")).unwrap_err();
        assert!(missing.to_string().contains("/nonexistent/x.yaml"));
    }

    /// A run that fails (an update needing more than the allowed substeps) names the run.
    #[test]
    fn failing_run_names_the_case() {
        let e = run_text(
            "interface: {model: hyperbolic}\ntest:\n  kind: direct_shear\n  normal_stresses: [1.0e5]\n  path: {kind: monotonic, target: 1000.0, steps: 1}\n",
        );
        assert!(matches!(e, PointError::Run { .. }), "{e}");
        let msg = e.to_string();
        assert!(
            msg.contains("bad.yaml") && msg.contains("sigma_n = 100 kPa") && msg.contains("substeps"),
            "{msg}"
        );
    }

    #[test]
    fn schema_lists_the_models() {
        let s = crate::point::schema_json();
        for m in [
            "hyperbolic",
            "mohr_coulomb",
            "joint",
            "elastic",
            "direct_shear",
            "oedometer",
        ] {
            assert!(s.contains(m), "{m}");
        }
    }
}
