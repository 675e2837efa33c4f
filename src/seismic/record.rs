//! Three-component ground-acceleration records ([`Accelerogram`]) and their CSV format.
//!
//! Axes and units follow [`crate::conventions`]: `a_x` along the stream, `a_y` along the dam
//! axis, `a_z` up, all in m/s², sampled at t_i = i·dt from t = 0. The CSV file is
//!
//! ```text
//! t,a_x,a_y,a_z
//! 0,0,0,0
//! 0.01,1.2e-3,-4.0e-4,2.1e-4
//! ...
//! ```
//!
//! with the header exactly as shown, t starting at 0 and uniform (|t_i − i·dt| ≤ 1e-6·dt,
//! dt = t_1). Values are written in Rust's shortest round-trip form, so writing and reading
//! back gives the same bits. A reader error names the file and the line and never panics.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The header line of the record CSV format.
pub const CSV_HEADER: &str = "t,a_x,a_y,a_z";
/// Relative tolerance of the uniform-time check of the CSV reader (fraction of dt).
pub const TIME_TOLERANCE: f64 = 1e-6;
/// Relative tolerance within which single components share their time step
/// ([`Accelerogram::from_components`]).
pub const DT_TOLERANCE: f64 = 1e-9;

/// A record that could not be read or written: the file, the 1-based line when the problem is
/// on one line, and what is wrong.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}{}: {message}", file.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
pub struct RecordError {
    /// The file.
    pub file: PathBuf,
    /// 1-based line number, if the error is on a line.
    pub line: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl RecordError {
    /// An error on line `line` (1-based) of `file`.
    pub fn at(file: &Path, line: usize, message: impl Into<String>) -> Self {
        RecordError {
            file: file.to_path_buf(),
            line: Some(line),
            message: message.into(),
        }
    }

    /// An error about the whole file.
    pub fn file(file: &Path, message: impl Into<String>) -> Self {
        RecordError {
            file: file.to_path_buf(),
            line: None,
            message: message.into(),
        }
    }
}

/// One of the three global axes (spec README: x stream, y dam axis, z up).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Stream direction (upstream → downstream).
    X,
    /// Dam axis.
    Y,
    /// Vertical, up.
    Z,
}

impl Axis {
    /// The three axes in order x, y, z.
    pub const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    /// 0, 1, 2 for x, y, z.
    pub fn index(self) -> usize {
        self as usize
    }

    /// `x`, `y` or `z`.
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self.index()]
    }
}

/// One component read from a single-component file (e.g. PEER AT2): dt (s) and the
/// accelerations (m/s²) at t_i = i·dt.
#[derive(Debug, Clone, PartialEq)]
pub struct AccelComponent {
    /// Time step (s).
    pub dt: f64,
    /// Accelerations (m/s²).
    pub values: Vec<f64>,
}

/// A uniformly sampled three-component ground acceleration (m/s², axes of
/// [`crate::conventions`]) at t_i = i·dt, i = 0..len.
#[derive(Debug, Clone, PartialEq)]
pub struct Accelerogram {
    dt: f64,
    components: [Vec<f64>; 3],
}

impl Accelerogram {
    /// A record from dt (s) and the three components (m/s²): equal lengths ≥ 2, finite values.
    pub fn new(dt: f64, a_x: Vec<f64>, a_y: Vec<f64>, a_z: Vec<f64>) -> Result<Self, String> {
        if a_x.len() != a_y.len() || a_x.len() != a_z.len() {
            return Err(format!(
                "components of different lengths: x {}, y {}, z {}",
                a_x.len(),
                a_y.len(),
                a_z.len()
            ));
        }
        if a_x.len() < 2 {
            return Err(format!("at least 2 samples are needed, got {}", a_x.len()));
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(format!("dt must be a positive number of seconds, got {dt}"));
        }
        let components = [a_x, a_y, a_z];
        for (axis, c) in Axis::ALL.iter().zip(&components) {
            if let Some(i) = c.iter().position(|v| !v.is_finite()) {
                return Err(format!("a_{}[{i}] is not finite: {}", axis.name(), c[i]));
            }
        }
        Ok(Accelerogram { dt, components })
    }

    /// A record from up to three single components (a missing one is zero). All given
    /// components must share dt (to [`DT_TOLERANCE`] relative); shorter ones are padded with
    /// zeros to the longest.
    pub fn from_components(components: [Option<AccelComponent>; 3]) -> Result<Self, String> {
        let given: Vec<&AccelComponent> = components.iter().flatten().collect();
        let first = given.first().ok_or("no component given")?;
        let dt = first.dt;
        if let Some(c) = given.iter().find(|c| (c.dt - dt).abs() > DT_TOLERANCE * dt) {
            return Err(format!(
                "components have different time steps: {dt} s and {} s",
                c.dt
            ));
        }
        let n = given.iter().map(|c| c.values.len()).max().unwrap_or(0);
        let [x, y, z] = components.map(|c| {
            let mut v = c.map(|c| c.values).unwrap_or_default();
            v.resize(n, 0.0);
            v
        });
        Accelerogram::new(dt, x, y, z)
    }

    /// Time step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.components[0].len()
    }

    /// Whether there are no samples (never true for a constructed record).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Duration (len − 1)·dt (s).
    pub fn duration(&self) -> f64 {
        (self.len() - 1) as f64 * self.dt
    }

    /// The samples of one component (m/s²).
    pub fn component(&self, axis: Axis) -> &[f64] {
        &self.components[axis.index()]
    }

    /// Ground acceleration a_g(t) = (a_x, a_y, a_z) in m/s², linearly interpolated between
    /// samples; zero before t = 0 and after the end of the record (or for a non-finite t).
    pub fn at(&self, t: f64) -> [f64; 3] {
        let pos = t / self.dt;
        if !(pos.is_finite() && pos >= 0.0 && pos <= (self.len() - 1) as f64) {
            return [0.0; 3];
        }
        let i = (pos.floor() as usize).min(self.len() - 2);
        let s = pos - i as f64;
        self.components.each_ref().map(|c| c[i] + (c[i + 1] - c[i]) * s)
    }

    /// The record in the CSV format of the module docs.
    pub fn to_csv_string(&self) -> String {
        let mut out = String::with_capacity(self.len() * 64);
        out.push_str(CSV_HEADER);
        out.push('\n');
        for i in 0..self.len() {
            let [x, y, z] = self.components.each_ref().map(|c| c[i]);
            let _ = writeln!(out, "{},{x},{y},{z}", i as f64 * self.dt);
        }
        out
    }

    /// Writes the record as CSV to `path`.
    pub fn write_csv(&self, path: &Path) -> Result<(), RecordError> {
        std::fs::write(path, self.to_csv_string()).map_err(|e| RecordError::file(path, e.to_string()))
    }

    /// Reads a record CSV file (format in the module docs): a regular file of at most
    /// [`crate::input::MAX_RECORD_BYTES`].
    pub fn read_csv(path: &Path) -> Result<Self, RecordError> {
        Accelerogram::from_csv_str(&read_record_text(path)?, path)
    }

    /// Parses the CSV text of a record; `file` names it in errors.
    pub fn from_csv_str(text: &str, file: &Path) -> Result<Self, RecordError> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim_end_matches('\r')));
        match lines.next() {
            Some((_, h)) if h.trim() == CSV_HEADER => {}
            Some((n, h)) => {
                return Err(RecordError::at(
                    file,
                    n,
                    format!("header must be '{CSV_HEADER}', got '{h}'"),
                ))
            }
            None => return Err(RecordError::file(file, "empty file")),
        }
        let mut times = Vec::new();
        let mut comps: [Vec<f64>; 3] = Default::default();
        for (n, line) in lines.filter(|(_, l)| !l.trim().is_empty()) {
            let row = parse_row(line).map_err(|m| RecordError::at(file, n, m))?;
            check_time(&times, row[0]).map_err(|m| RecordError::at(file, n, m))?;
            times.push(row[0]);
            for (c, v) in comps.iter_mut().zip(&row[1..]) {
                c.push(*v);
            }
        }
        let [x, y, z] = comps;
        Accelerogram::new(times.get(1).copied().unwrap_or(0.0), x, y, z)
            .map_err(|m| RecordError::file(file, m))
    }
}

/// The UTF-8 text of the record file `path`, a regular file of at most
/// [`crate::input::MAX_RECORD_BYTES`] (a device or FIFO is refused, not read without end).
pub fn read_record_text(path: &Path) -> Result<String, RecordError> {
    let bytes = crate::input::read_bounded(path, crate::input::MAX_RECORD_BYTES)
        .map_err(|reason| RecordError::file(path, reason))?;
    String::from_utf8(bytes).map_err(|e| RecordError::file(path, format!("not UTF-8 text: {e}")))
}

/// The four finite numbers of a CSV data row.
fn parse_row(line: &str) -> Result<[f64; 4], String> {
    let fields: Vec<&str> = line.split(',').collect();
    if fields.len() != 4 {
        return Err(format!(
            "expected 4 comma-separated values (t,a_x,a_y,a_z), got {}",
            fields.len()
        ));
    }
    let mut row = [0.0; 4];
    for ((slot, field), name) in row.iter_mut().zip(&fields).zip(CSV_HEADER.split(',')) {
        let v: f64 = field
            .trim()
            .parse()
            .map_err(|_| format!("{name}: '{}' is not a number", field.trim()))?;
        if !v.is_finite() {
            return Err(format!("{name}: '{}' is not finite", field.trim()));
        }
        *slot = v;
    }
    Ok(row)
}

/// Checks that `t` continues the uniform sampling of `times` (t_0 = 0, dt = t_1 > 0).
fn check_time(times: &[f64], t: f64) -> Result<(), String> {
    match times {
        [] if t != 0.0 => Err(format!("t must start at 0 s, got {t}")),
        [_] if t <= 0.0 => Err(format!("t must increase: the second time is {t} s")),
        [_, dt, ..] => {
            let expected = times.len() as f64 * dt;
            if (t - expected).abs() > TIME_TOLERANCE * dt {
                Err(format!(
                    "non-uniform time: t = {t} s, expected {expected} s (dt = {dt} s)"
                ))
            } else {
                Ok(())
            }
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Accelerogram {
        let n = 501;
        let f = |k: f64| -> Vec<f64> {
            (0..n)
                .map(|i| (k * i as f64 * 0.013).sin() / 3.0 * 9.81)
                .collect()
        };
        Accelerogram::new(0.01, f(1.0), f(2.3), f(0.7)).unwrap()
    }

    /// Write then read gives the same bits.
    #[test]
    fn csv_round_trip_is_bitwise() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.csv");
        let a = sample();
        a.write_csv(&path).unwrap();
        let b = Accelerogram::read_csv(&path).unwrap();
        assert_eq!(a.dt().to_bits(), b.dt().to_bits());
        for axis in Axis::ALL {
            let bits = |r: &Accelerogram| r.component(axis).iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&a), bits(&b), "{}", axis.name());
        }
        assert_eq!(std::fs::read_to_string(&path).unwrap(), b.to_csv_string());
    }

    /// A device is refused, not read without end (CSV and AT2 alike).
    #[test]
    fn devices_are_refused() {
        let dev = Path::new("/dev/zero");
        let msg = Accelerogram::read_csv(dev).expect_err("a device").to_string();
        assert!(msg.contains("not a regular file"), "{msg}");
        let msg = crate::seismic::read_at2(dev).expect_err("a device").to_string();
        assert!(msg.contains("not a regular file"), "{msg}");
    }

    /// a_g(t) interpolates linearly and is zero outside the record.
    #[test]
    fn evaluates_between_samples() {
        let a = Accelerogram::new(0.5, vec![0.0, 1.0, 3.0], vec![2.0; 3], vec![0.0, -1.0, 0.0]).unwrap();
        assert_eq!(a.at(0.75), [2.0, 2.0, -0.5]);
        assert_eq!(a.at(1.0), [3.0, 2.0, 0.0]);
        assert_eq!(a.at(1.01), [0.0; 3]);
        assert_eq!(a.at(-0.1), [0.0; 3]);
        assert_eq!(a.at(f64::NAN), [0.0; 3]);
        assert_eq!(a.duration(), 1.0);
    }

    fn read(text: &str) -> RecordError {
        Accelerogram::from_csv_str(text, Path::new("bad.csv")).unwrap_err()
    }

    /// Each malformed input names the file and the line.
    #[test]
    fn malformed_csv_names_the_line() {
        let cases = [
            ("time,ax,ay,az\n0,0,0,0\n", 1, "header"),
            (
                "t,a_x,a_y,a_z\n0,0,0,0\n0.01,1,x,0\n",
                3,
                "a_y: 'x' is not a number",
            ),
            ("t,a_x,a_y,a_z\n0,0,0,0\n0.01,1,NaN,0\n", 3, "not finite"),
            (
                "t,a_x,a_y,a_z\n0,0,0,0\n0.01,1,2,0\n0.025,1,2,0\n",
                4,
                "non-uniform time",
            ),
            ("t,a_x,a_y,a_z\n0.5,0,0,0\n", 2, "start at 0"),
            ("t,a_x,a_y,a_z\n0,0,0,0\n0.01,1,2\n", 3, "expected 4"),
            ("t,a_x,a_y,a_z\n0,0,0,0\n0,1,2,3\n", 3, "must increase"),
        ];
        for (text, line, what) in cases {
            let e = read(text);
            assert_eq!(e.line, Some(line), "{e}");
            let msg = e.to_string();
            assert!(
                msg.starts_with(&format!("bad.csv:{line}: ")) && msg.contains(what),
                "{msg}"
            );
        }
        let e = read("t,a_x,a_y,a_z\n0,0,0,0\n");
        assert!(
            e.line.is_none() && e.to_string().contains("at least 2 samples"),
            "{e}"
        );
        assert!(read("").to_string().contains("empty"));
    }

    #[test]
    fn components_combine_with_zero_padding() {
        let x = AccelComponent {
            dt: 0.02,
            values: vec![1.0, 2.0, 3.0],
        };
        let z = AccelComponent {
            dt: 0.02,
            values: vec![4.0, 5.0],
        };
        let a = Accelerogram::from_components([Some(x.clone()), None, Some(z)]).unwrap();
        assert_eq!(a.component(Axis::Y), &[0.0; 3]);
        assert_eq!(a.component(Axis::Z), &[4.0, 5.0, 0.0]);
        let other = AccelComponent {
            dt: 0.01,
            values: vec![0.0; 3],
        };
        let e = Accelerogram::from_components([Some(x), Some(other), None]).unwrap_err();
        assert!(e.contains("different time steps"), "{e}");
    }
}
