//! The `record` key of a dynamic stage: one CSV file of the three components, or one PEER NGA
//! AT2 file per component.
//!
//! ```yaml
//! record: ../accel/seed_quake.csv                 # t,a_x,a_y,a_z in m/s²
//! record: { x: RSN6_X.AT2, y: RSN6_Y.AT2, z: RSN6_UP.AT2 }   # g, each file's own DT
//! record: { x: RSN6_X.AT2 }                       # y and z left out: zero
//! ```
//!
//! Paths are relative to the scene's folder. The AT2 files are read by
//! [`crate::seismic::read_at2`] (the PEER header's `UNITS OF G` and `DT`, values converted to
//! m/s² with [`crate::seismic::at2::STANDARD_GRAVITY`]) and checked like the CSV: every given
//! component has the same DT (to 1e-9 relative) or the scene is refused naming the file and the
//! key; components of different lengths are padded with zeros to the longest, which the run
//! states in its log ([`Record::notes`]).

use super::error::SceneError;
use crate::seismic::{read_at2, AccelComponent, Accelerogram, Axis};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Where a dynamic stage's ground acceleration comes from (scene key `dynamic.record`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum RecordSpec {
    /// A CSV file with the header `t,a_x,a_y,a_z` (m/s², the scene's axes x stream, y dam axis,
    /// z up; `cfrd accel` writes it), relative to the scene's folder.
    Csv(PathBuf),
    /// One PEER NGA AT2 file per component (in g, with its own DT), relative to the scene's
    /// folder: `{ x: FILE.AT2, y: FILE.AT2, z: FILE.AT2 }`. A component left out is zero; at
    /// least one is given.
    At2(At2Files),
}

/// The AT2 files of a record's components (`record: { x: …, y: …, z: … }`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct At2Files {
    /// The stream-direction component a_x (upstream → downstream).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x: Option<PathBuf>,
    /// The dam-axis component a_y.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y: Option<PathBuf>,
    /// The vertical component a_z (up).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<PathBuf>,
}

impl At2Files {
    /// The given components' axes and files, in the order x, y, z.
    fn given(&self) -> Vec<(Axis, &Path)> {
        Axis::ALL
            .into_iter()
            .zip([&self.x, &self.y, &self.z])
            .filter_map(|(axis, file)| Some((axis, file.as_deref()?)))
            .collect()
    }
}

/// The forms of `record` that error messages show.
const RECORD_FORM: &str = "give a CSV file (`record: quake.csv`, t,a_x,a_y,a_z in m/s²) or one \
                           PEER NGA AT2 file per component (`record: { x: FILE.AT2, y: FILE.AT2, \
                           z: FILE.AT2 }`, a component left out is zero)";

impl<'de> Deserialize<'de> for RecordSpec {
    /// A path (string) is a CSV file, a mapping the AT2 files; anything else, or a mapping with
    /// another key, is an error that shows both forms.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error as _;
        match serde_yaml::Value::deserialize(d)? {
            serde_yaml::Value::String(s) => Ok(RecordSpec::Csv(PathBuf::from(s))),
            v @ serde_yaml::Value::Mapping(_) => At2Files::deserialize(v)
                .map(RecordSpec::At2)
                .map_err(|e| D::Error::custom(format!("{e}: {RECORD_FORM}"))),
            _ => Err(D::Error::custom(format!("not a record: {RECORD_FORM}"))),
        }
    }
}

/// A record read for a dynamic stage.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The three components (m/s²).
    pub accelerogram: Accelerogram,
    /// What the run states about the record at the stage's start (components left out, shorter
    /// components padded with zeros), one line each.
    pub notes: Vec<String>,
}

impl RecordSpec {
    /// Reads the record relative to `base`; `inv(key, message)` makes the error of the key
    /// `record` or `record.x` (`.y`, `.z`) of the stage.
    pub fn read(&self, base: &Path, inv: &dyn Fn(&str, String) -> SceneError) -> Result<Record, SceneError> {
        match self {
            RecordSpec::Csv(file) => Ok(Record {
                accelerogram: Accelerogram::read_csv(&base.join(file))
                    .map_err(|e| inv("record", e.to_string()))?,
                notes: Vec::new(),
            }),
            RecordSpec::At2(files) => read_at2_files(files, base, inv),
        }
    }
}

/// The components of `files` read and checked (module docs) into one record.
fn read_at2_files(
    files: &At2Files,
    base: &Path,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Record, SceneError> {
    let given = files.given();
    if given.is_empty() {
        return Err(inv("record", format!("no component file given: {RECORD_FORM}")));
    }
    let mut components: [Option<AccelComponent>; 3] = Default::default();
    let mut first: Option<(Axis, PathBuf, f64)> = None;
    for &(axis, file) in &given {
        let key = format!("record.{}", axis.name());
        let path = base.join(file);
        let c = read_at2(&path).map_err(|e| inv(&key, e.to_string()))?;
        if c.values.len() < 2 {
            let m = format!(
                "{}: NPTS = {}: a component needs at least 2 samples",
                path.display(),
                c.values.len()
            );
            return Err(inv(&key, m));
        }
        match &first {
            Some((a0, p0, dt0)) if (c.dt - dt0).abs() > crate::seismic::record::DT_TOLERANCE * dt0 => {
                return Err(inv(
                    &key,
                    format!(
                        "{}: DT = {} s, but record.{} ({}) has DT = {dt0} s: the components of a \
                         record must share their time step",
                        path.display(),
                        c.dt,
                        a0.name(),
                        p0.display()
                    ),
                ));
            }
            Some(_) => {}
            None => first = Some((axis, path, c.dt)),
        }
        components[axis.index()] = Some(c);
    }
    let notes = notes(&components, &given);
    let accelerogram = Accelerogram::from_components(components).map_err(|m| inv("record", m))?;
    Ok(Record { accelerogram, notes })
}

/// The log lines of an AT2 record: the components left out (zero) and, when the given ones
/// differ in length, their lengths and the padding.
fn notes(components: &[Option<AccelComponent>; 3], given: &[(Axis, &Path)]) -> Vec<String> {
    let mut notes = Vec::new();
    let missing: Vec<&str> = Axis::ALL
        .iter()
        .filter(|a| components[a.index()].is_none())
        .map(|a| a.name())
        .collect();
    if !missing.is_empty() {
        notes.push(format!(
            "record: no AT2 file for {}: that ground acceleration is zero",
            missing.join(", ")
        ));
    }
    let lengths: Vec<(Axis, usize)> = given
        .iter()
        .filter_map(|&(a, _)| Some((a, components[a.index()].as_ref()?.values.len())))
        .collect();
    let longest = lengths.iter().map(|&(_, n)| n).max().unwrap_or(0);
    if lengths.iter().any(|&(_, n)| n != longest) {
        let each: Vec<String> = lengths
            .iter()
            .map(|&(a, n)| format!("{} {n}", a.name()))
            .collect();
        notes.push(format!(
            "record: components of different lengths ({} samples): the shorter padded with zeros \
             to {longest}",
            each.join(", ")
        ));
    }
    notes
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(yaml: &str) -> Result<RecordSpec, String> {
        serde_yaml::from_str(yaml).map_err(|e| e.to_string())
    }

    /// A path is a CSV file, a mapping of x, y, z the AT2 files; both serialize back to the same
    /// form, and anything else shows both forms.
    #[test]
    fn a_record_is_a_csv_path_or_the_at2_files_of_its_components() {
        let csv = RecordSpec::Csv("r.csv".into());
        assert_eq!(parse("r.csv"), Ok(csv.clone()));
        let at2 = RecordSpec::At2(At2Files {
            x: Some("a.AT2".into()),
            y: None,
            z: Some("b.AT2".into()),
        });
        assert_eq!(parse("{ x: a.AT2, z: b.AT2 }"), Ok(at2.clone()));
        for form in [csv, at2] {
            let text = serde_yaml::to_string(&form).unwrap();
            assert!(!text.contains("null"), "{text}");
            assert_eq!(parse(&text), Ok(form));
        }
        for bad in ["3", "[a.AT2, b.AT2]", "{ w: a.AT2 }", "{ x: [a] }"] {
            let e = parse(bad).expect_err(bad);
            assert!(e.contains("one PEER NGA AT2 file per component"), "{bad}: {e}");
        }
    }

    /// The notes name the components left out and, for components of different lengths, each
    /// length and the padding; equal lengths need no note.
    #[test]
    fn notes_state_the_components_left_out_and_the_padding() {
        let c = |n: usize| {
            Some(AccelComponent {
                dt: 0.01,
                values: vec![1.0; n],
            })
        };
        let (x, z) = (Path::new("x.AT2"), Path::new("z.AT2"));
        let given = [(Axis::X, x), (Axis::Z, z)];
        assert_eq!(
            notes(&[c(5), None, c(3)], &given),
            [
                "record: no AT2 file for y: that ground acceleration is zero",
                "record: components of different lengths (x 5, z 3 samples): the shorter padded \
                 with zeros to 5"
            ]
        );
        let all = [(Axis::X, x), (Axis::Y, x), (Axis::Z, z)];
        assert!(notes(&[c(4), c(4), c(4)], &all).is_empty());
    }
}
