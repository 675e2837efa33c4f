//! Reader of one component of a PEER NGA strong-motion record (`.AT2`).
//!
//! ```text
//! PEER NGA STRONG MOTION DATABASE RECORD                  line 1: free text
//! IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #6, 140  line 2: free text (event, station)
//! ACCELERATION TIME SERIES IN UNITS OF G                  line 3: must say UNITS OF G
//! NPTS=  3901, DT=   .0100 SEC                            line 4 (or the older `3901 .0100 NPTS, DT`)
//!   .1234E-02  -.5678E-03 ...                             whitespace-separated values in g
//! ```
//!
//! Values are converted from g to m/s² with [`STANDARD_GRAVITY`]. Errors name the file and the
//! line; a declared NPTS larger than the rest of the file could hold (two bytes per value) is
//! refused before anything is allocated.

use super::record::{AccelComponent, RecordError};
use std::path::Path;

/// Standard gravity (m/s²) used to convert g to m/s².
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Reads one component from a PEER NGA AT2 file (format in the module docs): a regular file of
/// at most [`crate::input::MAX_RECORD_BYTES`].
pub fn read_at2(path: &Path) -> Result<AccelComponent, RecordError> {
    parse_at2(&super::record::read_record_text(path)?, path)
}

/// Parses the text of an AT2 file; `file` names it in errors.
pub fn parse_at2(text: &str, file: &Path) -> Result<AccelComponent, RecordError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let mut header = Vec::with_capacity(4);
    for _ in 0..4 {
        let (n, line) = lines
            .next()
            .ok_or_else(|| RecordError::file(file, "the 4 header lines are incomplete"))?;
        header.push((n, line));
    }
    let (units_line, units) = header[2];
    if !units.to_ascii_uppercase().contains("UNITS OF G") {
        return Err(RecordError::at(
            file,
            units_line,
            format!("expected acceleration in UNITS OF G, got '{}'", units.trim()),
        ));
    }
    let (npts_line, npts_text) = header[3];
    let (npts, dt) = parse_npts_dt(npts_text).map_err(|m| RecordError::at(file, npts_line, m))?;
    let consumed: usize = header.iter().map(|(_, l)| l.len() + 1).sum();
    let capacity = text.len().saturating_sub(consumed) / 2 + 1;
    if npts > capacity {
        return Err(RecordError::at(
            file,
            npts_line,
            format!("NPTS = {npts}, but the rest of the file can hold at most {capacity} values"),
        ));
    }
    let mut values = Vec::with_capacity(npts);
    for (n, line) in lines {
        for token in line.split_whitespace() {
            let g: f64 = token
                .parse()
                .map_err(|_| RecordError::at(file, n, format!("'{token}' is not a number")))?;
            if !g.is_finite() {
                return Err(RecordError::at(file, n, format!("'{token}' is not finite")));
            }
            if values.len() == npts {
                return Err(RecordError::at(
                    file,
                    n,
                    format!("more values than NPTS = {npts}"),
                ));
            }
            values.push(g * STANDARD_GRAVITY);
        }
    }
    if values.len() < npts {
        return Err(RecordError::file(
            file,
            format!(
                "NPTS = {npts} declared on line {npts_line}, but only {} values found",
                values.len()
            ),
        ));
    }
    Ok(AccelComponent { dt, values })
}

/// NPTS and DT from the fourth header line: `NPTS= 3901, DT= .0100 SEC` or `3901 .0100 NPTS, DT`.
fn parse_npts_dt(line: &str) -> Result<(usize, f64), String> {
    let upper = line.to_ascii_uppercase();
    let (npts, dt) = if upper.contains('=') {
        (keyed_value(&upper, "NPTS")?, keyed_value(&upper, "DT")?)
    } else {
        let mut it = upper.split_whitespace();
        let mut next = |what: &str| it.next().ok_or(format!("{what} missing in '{}'", line.trim()));
        (next("NPTS")?.to_string(), next("DT")?.to_string())
    };
    let npts: usize = npts
        .parse()
        .map_err(|_| format!("NPTS: '{npts}' is not a non-negative integer"))?;
    let dt: f64 = dt.parse().map_err(|_| format!("DT: '{dt}' is not a number"))?;
    if npts == 0 {
        return Err("NPTS must be at least 1".into());
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(format!("DT must be a positive number of seconds, got {dt}"));
    }
    Ok((npts, dt))
}

/// The value after `KEY=` in a comma-separated line, without a trailing unit word.
fn keyed_value(line: &str, key: &str) -> Result<String, String> {
    line.split(',')
        .filter_map(|field| field.split_once('='))
        .find(|(k, _)| k.trim() == key)
        .and_then(|(_, v)| v.split_whitespace().next())
        .map(str::to_string)
        .ok_or(format!("{key}= missing in '{}'", line.trim()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "PEER NGA STRONG MOTION DATABASE RECORD
HAND-WRITTEN SAMPLE, NOT A REAL RECORD
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=    7, DT=   .0200 SEC
  .1000E+00 -.2000E-01  .0000E+00
  .5000E-01 -.1000E+00
  .2500E-02  -.3E-2
";

    fn parse(text: &str) -> Result<AccelComponent, RecordError> {
        parse_at2(text, Path::new("rec.AT2"))
    }

    #[test]
    fn reads_a_hand_written_sample_in_m_per_s2() {
        let c = parse(SAMPLE).unwrap();
        assert_eq!(c.dt, 0.02);
        let g = [0.1, -0.02, 0.0, 0.05, -0.1, 0.0025, -0.003];
        assert_eq!(c.values.len(), 7);
        for (v, g) in c.values.iter().zip(g) {
            assert!((v - g * STANDARD_GRAVITY).abs() < 1e-15, "{v}");
        }
        let old = SAMPLE.replace("NPTS=    7, DT=   .0200 SEC", "    7   .0200   NPTS, DT");
        assert_eq!(parse(&old).unwrap(), c);
    }

    /// Malformed files name the line; a huge NPTS is refused without allocating.
    #[test]
    fn malformed_at2_names_the_line() {
        let cases = [
            (SAMPLE.replace("UNITS OF G", "CM/S/S"), Some(3), "UNITS OF G"),
            (
                SAMPLE.replace("NPTS=    7", "NPTS= 1000000000000"),
                Some(4),
                "can hold at most",
            ),
            (SAMPLE.replace("NPTS=    7", "NPTS= -7"), Some(4), "NPTS"),
            (
                SAMPLE.replace("DT=   .0200", "DT= 0"),
                Some(4),
                "DT must be a positive",
            ),
            (
                SAMPLE.replace("-.2000E-01", "-.2000X-01"),
                Some(5),
                "not a number",
            ),
            (SAMPLE.replace("-.2000E-01", "NaN"), Some(5), "not finite"),
            (SAMPLE.replace("NPTS=    7", "NPTS=    6"), Some(7), "more values"),
            (SAMPLE.replace("NPTS=    7", "NPTS=    9"), None, "only 7 values"),
            ("PEER\nx\n".to_string(), None, "header lines"),
        ];
        for (text, line, what) in cases {
            let e = parse(&text).unwrap_err();
            assert_eq!(e.line, line, "{e}");
            assert!(
                e.to_string().starts_with("rec.AT2") && e.to_string().contains(what),
                "{e}"
            );
        }
    }
}
