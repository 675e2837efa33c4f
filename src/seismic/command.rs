//! `cfrd accel SPEC.yaml -o DIR`: generates the records of a specification file
//! ([`super::spec`]) and writes, per record `<name>`:
//!
//! - `DIR/<name>.csv`: the record, `t,a_x,a_y,a_z` (s, m/s²), see [`super::record`];
//! - `DIR/<name>_compatibility.csv`: `period` and, per component c = x, y, z, `target_c`,
//!   `achieved_c` (5 %-damped Sa, m/s²) and `ratio_c` at the acceptance periods;
//! - `DIR/<name>.png`: the three time histories and the three spectra against the target
//!   with the ±10 % band.
//!
//! Exit codes of the command: 0 success, 1 a record that misses the acceptance of spec
//! seismic §2.3 or an output that cannot be written, 2 bad input (the file and the YAML path
//! are named).

use super::generator::{generate_record, GeneratedRecord, GeneratorError, ACCEPTANCE_MAX_ERROR};
use super::record::Axis;
use super::spec::AccelSpecFile;
use crate::plot::{Figure, Panel, PlotError, Series};
use std::fmt;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A `cfrd accel` run that failed.
#[derive(Debug, Error)]
pub enum AccelError {
    /// The specification cannot be read.
    #[error("{file}: {source}")]
    Read {
        /// The specification file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The YAML does not match the format.
    #[error("{file}: {message}")]
    Parse {
        /// The specification file.
        file: PathBuf,
        /// The YAML path, line and what is wrong.
        message: String,
    },
    /// A value is out of range or inconsistent.
    #[error("{file}: {field}: {reason}")]
    Invalid {
        /// The specification file.
        file: PathBuf,
        /// YAML path of the value.
        field: String,
        /// Why it is rejected, with the unit.
        reason: String,
    },
    /// The generator failed.
    #[error("{file}: record '{record}': {message}")]
    Generate {
        /// The specification file.
        file: PathBuf,
        /// The record's name.
        record: String,
        /// What failed.
        message: String,
    },
    /// An output cannot be written.
    #[error("{path}: {message}")]
    Write {
        /// The output.
        path: PathBuf,
        /// What failed.
        message: String,
    },
}

impl AccelError {
    /// Exit code of the command: 2 for bad input, 4 when an output cannot be written, 1 when
    /// the generator fails.
    pub fn exit_code(&self) -> u8 {
        match self {
            AccelError::Read { .. } | AccelError::Parse { .. } | AccelError::Invalid { .. } => 2,
            AccelError::Write { .. } => 4,
            AccelError::Generate { .. } => 1,
        }
    }
}

/// One generated record and its files.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordOutput {
    /// Record name.
    pub name: String,
    /// Its seed.
    pub seed: u64,
    /// The record and its compatibility report.
    pub generated: GeneratedRecord,
    /// Files written (CSV, compatibility CSV, PNG).
    pub files: Vec<PathBuf>,
}

/// What `cfrd accel` produced.
#[derive(Debug, Clone, PartialEq)]
pub struct AccelSummary {
    /// The specification file.
    pub spec: PathBuf,
    /// One entry per record.
    pub records: Vec<RecordOutput>,
}

impl AccelSummary {
    /// Whether every record meets the acceptance of spec seismic §2.3.
    pub fn accepted(&self) -> bool {
        self.records.iter().all(|r| r.generated.accepted())
    }
}

impl fmt::Display for AccelSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for r in &self.records {
            let g = &r.generated;
            let verdict = if g.accepted() { "accepted" } else { "NOT accepted" };
            writeln!(f, "{} (seed {}): {verdict} (spec seismic §2.3)", r.name, r.seed)?;
            writeln!(
                f,
                "  axis  PGA m/s2 (target)  mean err  max err  range           PGV m/s  PGD m   v_end m/s  iter"
            )?;
            for c in &g.components {
                let (lo, hi) = c.spectral.error_range();
                writeln!(
                    f,
                    "  {:<4}  {:>6.3} ({:>5.3})   {:>6.2} %  {:>5.2} %  {:>+6.2}/{:>+5.2} %  {:>7.3}  {:>6.3}  {:>9.2e}  {:>4}",
                    c.axis.name(),
                    c.measures.pga,
                    c.target.pga,
                    100.0 * c.spectral.mean_abs_error(),
                    100.0 * c.spectral.max_abs_error(),
                    100.0 * lo,
                    100.0 * hi,
                    c.measures.pgv,
                    c.measures.pgd,
                    c.measures.end_velocity,
                    c.iteration
                )?;
            }
            let [xy, yz, zx] = g.correlations;
            writeln!(f, "  correlation: xy {xy:+.3}, yz {yz:+.3}, zx {zx:+.3}")?;
            for file in &r.files {
                writeln!(f, "  -> {}", file.display())?;
            }
        }
        Ok(())
    }
}

/// Reads, validates and runs the specification `path`; writes the outputs into `out_dir`
/// (created if needed).
pub fn run_file(path: &Path, out_dir: &Path) -> Result<AccelSummary, AccelError> {
    let file = path.to_path_buf();
    let text =
        crate::input::read_text(path, crate::input::MAX_SCENE_BYTES).map_err(|source| AccelError::Read {
            file: file.clone(),
            source,
        })?;
    let spec = AccelSpecFile::parse(&text).map_err(|message| AccelError::Parse {
        file: file.clone(),
        message,
    })?;
    let resolved = spec.resolve().map_err(|e| AccelError::Invalid {
        file: file.clone(),
        field: e.field,
        reason: e.reason,
    })?;
    std::fs::create_dir_all(out_dir).map_err(|e| AccelError::Write {
        path: out_dir.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut records = Vec::new();
    for r in &resolved.records {
        eprintln!(
            "record '{}': {} samples per component, generating",
            r.name,
            resolved.settings.n_samples()
        );
        let generated =
            generate_record(&resolved.targets, &resolved.settings, r.seed).map_err(|e| match e {
                GeneratorError::Invalid(p) => AccelError::Invalid {
                    file: file.clone(),
                    field: p.field,
                    reason: p.reason,
                },
                other => AccelError::Generate {
                    file: file.clone(),
                    record: r.name.clone(),
                    message: other.to_string(),
                },
            })?;
        let title = spec.title.clone().unwrap_or_else(|| r.name.clone());
        let files = write_outputs(&generated, out_dir, &r.name, &title)?;
        records.push(RecordOutput {
            name: r.name.clone(),
            seed: r.seed,
            generated,
            files,
        });
    }
    Ok(AccelSummary { spec: file, records })
}

/// Writes the CSV, the compatibility table and the figure of one record.
fn write_outputs(
    g: &GeneratedRecord,
    dir: &Path,
    name: &str,
    title: &str,
) -> Result<Vec<PathBuf>, AccelError> {
    let write_error = |path: &Path, message: String| AccelError::Write {
        path: path.to_path_buf(),
        message,
    };
    let csv = dir.join(format!("{name}.csv"));
    g.record
        .write_csv(&csv)
        .map_err(|e| write_error(&csv, e.message))?;
    let compat = dir.join(format!("{name}_compatibility.csv"));
    std::fs::write(&compat, compatibility_csv(g)).map_err(|e| write_error(&compat, e.to_string()))?;
    let png = dir.join(format!("{name}.png"));
    figure(g, title)
        .save_png(&png)
        .map_err(|e: PlotError| write_error(&png, e.to_string()))?;
    Ok(vec![csv, compat, png])
}

/// The compatibility table: period, then target, achieved and ratio of x, y, z.
pub fn compatibility_csv(g: &GeneratedRecord) -> String {
    let mut out = String::from("period");
    for axis in Axis::ALL {
        let c = axis.name();
        let _ = write!(out, ",target_{c},achieved_{c},ratio_{c}");
    }
    out.push('\n');
    let periods = &g.components[0].spectral.periods;
    for (j, t) in periods.iter().enumerate() {
        let _ = write!(out, "{t}");
        for c in &g.components {
            let (target, achieved) = (c.spectral.target[j], c.spectral.achieved[j]);
            let _ = write!(out, ",{target},{achieved},{}", achieved / target);
        }
        out.push('\n');
    }
    out
}

/// Per component: the time history, and the spectrum against the target with the ±10 % band.
fn figure(g: &GeneratedRecord, title: &str) -> Figure {
    let dt = g.record.dt();
    let mut fig = Figure::new(format!("{title}: time histories and 5 %-damped spectra")).columns(2);
    for c in &g.components {
        let axis = c.axis.name();
        let history: Vec<(f64, f64)> = g
            .record
            .component(c.axis)
            .iter()
            .enumerate()
            .map(|(i, a)| (i as f64 * dt, *a))
            .collect();
        fig.push(
            Panel::new(
                format!("a_{axis} (PGA {:.3} m/s2)", c.measures.pga),
                "t (s)",
                "a (m/s2)",
            )
            .with(Series::line("", history)),
        );
        let s = &c.spectral;
        let curve = |values: &[f64], factor: f64| -> Vec<(f64, f64)> {
            s.periods
                .iter()
                .zip(values)
                .map(|(t, v)| (*t, v * factor))
                .collect()
        };
        let band = 100.0 * ACCEPTANCE_MAX_ERROR;
        fig.push(
            Panel::new(
                format!(
                    "Sa_{axis}: mean error {:.1} %, max {:.1} %",
                    100.0 * s.mean_abs_error(),
                    100.0 * s.max_abs_error()
                ),
                "T (s)",
                "Sa (m/s2)",
            )
            .with(Series::line("target", curve(&s.target, 1.0)))
            .with(Series::line("achieved", curve(&s.achieved, 1.0)))
            .with(Series::line(
                format!("target -{band:.0} %"),
                curve(&s.target, 1.0 - ACCEPTANCE_MAX_ERROR),
            ))
            .with(Series::line(
                format!("target +{band:.0} %"),
                curve(&s.target, 1.0 + ACCEPTANCE_MAX_ERROR),
            )),
        );
    }
    fig
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A short variant of the seed spec (few iterations) to exercise the command quickly.
    fn short_spec() -> String {
        include_str!("../../inputs/accel/seed_quake.yaml")
            .replace("duration: 20.0", "duration: 6.0")
            .replace("{ t1: 2.0, t2: 12.0, c: 0.35 }", "{ t1: 1.0, t2: 4.0, c: 0.5 }")
            .replace(
                "band: { f_lo: 0.2, f_hi: 40.0 }",
                "band: { f_lo: 0.4, f_hi: 40.0 }\niterations: 2\nwavelet_iterations: 1",
            )
    }

    #[test]
    fn writes_the_record_table_and_figure() {
        let dir = tempfile::tempdir().unwrap();
        let spec = dir.path().join("short.yaml");
        std::fs::write(&spec, short_spec()).unwrap();
        let out = dir.path().join("out");
        let summary = run_file(&spec, &out).unwrap();
        let names: Vec<String> = summary.records[0]
            .files
            .iter()
            .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            names,
            ["seed_quake.csv", "seed_quake_compatibility.csv", "seed_quake.png"]
        );
        let record = crate::seismic::Accelerogram::read_csv(&out.join("seed_quake.csv")).unwrap();
        assert_eq!(record, summary.records[0].generated.record);
        let table = std::fs::read_to_string(out.join("seed_quake_compatibility.csv")).unwrap();
        let header =
            "period,target_x,achieved_x,ratio_x,target_y,achieved_y,ratio_y,target_z,achieved_z,ratio_z";
        assert!(
            table.starts_with(header) && table.lines().count() == 61,
            "{table}"
        );
        let text = summary.to_string();
        assert!(
            text.contains("seed_quake (seed 2015)") && text.contains("correlation"),
            "{text}"
        );
    }

    #[test]
    fn bad_input_names_the_file_and_path_with_exit_code_2() {
        let dir = tempfile::tempdir().unwrap();
        let spec = dir.path().join("bad.yaml");
        std::fs::write(&spec, short_spec().replace("dt: 0.01", "dt: 0.5")).unwrap();
        let e = run_file(&spec, dir.path()).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        let msg = e.to_string();
        assert!(
            msg.contains("bad.yaml") && msg.contains("dt: must lie in [0.0001, 0.1] s"),
            "{msg}"
        );
        let missing = run_file(&dir.path().join("none.yaml"), dir.path()).unwrap_err();
        assert!(
            missing.exit_code() == 2 && missing.to_string().contains("none.yaml"),
            "{missing}"
        );
    }
}
