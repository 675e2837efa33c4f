//! `cfrd compare`: field-by-field differences between two results files (e.g. the same scene
//! on 1 and 2 ranks, or before and after a change). Serial HDF5; no MPI needed.
//!
//! For every step present in both files and every `f64` field of that step present in both,
//! the maximum absolute difference and the field's maximum magnitude are reported. Steps are
//! matched by their `stage` and `time` attributes (a run restarted from a checkpoint numbers
//! its steps from 0 again, so its step of stage `fill_3` is the full run's step of `fill_3`);
//! steps without them are matched by group name. Either argument may be a run's output
//! directory, which stands for its `results.h5`. The
//! relative difference divides the difference by the largest magnitude of any field of the
//! step with the same units (`max |a − b| / scale`), so a field that is zero up to round-off
//! (e.g. the slip of a joint loaded normally) is measured against its physical scale (the
//! displacements), not against its own round-off.

use crate::io::results_reader::{open, results_file, stage_name, step_names};
use std::fmt;
use std::path::Path;

/// The difference of one field of one step.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldDiff {
    /// Step group name (e.g. `000003`; `000003 = 000001` when the second file numbers the
    /// matched step differently) and its stage attribute.
    pub step: String,
    /// Field (dataset) name.
    pub field: String,
    /// max |a − b| over all values.
    pub max_abs_diff: f64,
    /// max |a| over all values.
    pub max_abs: f64,
    /// Units of the field (its `units` attribute).
    pub units: String,
    /// The largest `max_abs` of the fields of the step with the same units.
    pub scale: f64,
}

impl FieldDiff {
    /// `max |a − b| / scale` (the absolute difference when the scale is zero).
    pub fn relative(&self) -> f64 {
        if self.scale > 0.0 {
            self.max_abs_diff / self.scale
        } else {
            self.max_abs_diff
        }
    }
}

/// The differences of all common fields, as a markdown table.
pub struct DiffTable<'a>(pub &'a [FieldDiff]);

impl fmt::Display for DiffTable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "| step | field | units | max abs difference | max magnitude | relative |"
        )?;
        writeln!(f, "|---|---|---|---|---|---|")?;
        for d in self.0 {
            writeln!(
                f,
                "| {} | {} | {} | {:.3e} | {:.3e} | {:.3e} |",
                d.step,
                d.field,
                d.units,
                d.max_abs_diff,
                d.max_abs,
                d.relative()
            )?;
        }
        Ok(())
    }
}

/// The key a step is matched by: its stage name and time (exact bits) when it has both
/// attributes, else its group name.
fn step_key(f: &hdf5::File, name: &str) -> Result<String, String> {
    let g = f.group(&format!("/steps/{name}")).map_err(|e| e.to_string())?;
    let time = g.attr("time").and_then(|x| x.read_scalar::<f64>()).ok();
    Ok(match (stage_name(&g), time) {
        (Some(stage), Some(t)) => format!("{stage}@{:016x}", t.to_bits()),
        _ => name.to_string(),
    })
}

/// Compares the fields of every step that both results files hold (matched as the module
/// docs say). `a` and `b` are results files or run directories.
pub fn compare_results(a: &Path, b: &Path) -> Result<Vec<FieldDiff>, String> {
    let (a, b) = (results_file(a), results_file(b));
    let (a, b) = (a.as_path(), b.as_path());
    let (fa, fb) = (open(a)?, open(b)?);
    let (sa, sb) = (step_names(&fa, a)?, step_names(&fb, b)?);
    let mut keys_b = std::collections::HashMap::new();
    for name in &sb {
        keys_b.entry(step_key(&fb, name)?).or_insert(name.clone());
    }
    let mut out = Vec::new();
    for step in &sa {
        let Some(step_b) = keys_b.get(&step_key(&fa, step)?) else {
            continue;
        };
        let (ga, gb) = (
            fa.group(&format!("/steps/{step}")).map_err(|e| e.to_string())?,
            fb.group(&format!("/steps/{step_b}")).map_err(|e| e.to_string())?,
        );
        let stage = stage_name(&ga).unwrap_or_default();
        let mut fields = ga.member_names().map_err(|e| e.to_string())?;
        fields.sort();
        let mut step_diffs = Vec::new();
        for field in fields {
            if !gb.link_exists(&field) {
                continue;
            }
            let read = |g: &hdf5::Group, p: &Path| {
                g.dataset(&field)
                    .and_then(|d| d.read_raw::<f64>())
                    .map_err(|e| format!("{}: /steps/{step}/{field}: {e}", p.display()))
            };
            let (va, vb) = (read(&ga, a)?, read(&gb, b)?);
            if va.len() != vb.len() {
                return Err(format!(
                    "/steps/{step}/{field}: {} values in {} but {} in {} (step {step_b})",
                    va.len(),
                    a.display(),
                    vb.len(),
                    b.display()
                ));
            }
            let max_abs_diff = va.iter().zip(&vb).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
            let max_abs = va.iter().map(|x| x.abs()).fold(0.0, f64::max);
            let units = ga
                .dataset(&field)
                .and_then(|d| d.attr("units"))
                .and_then(|x| x.read_scalar::<hdf5::types::VarLenUnicode>())
                .map(|s| s.to_string())
                .unwrap_or_default();
            step_diffs.push(FieldDiff {
                step: if step_b == step {
                    format!("{step} ({stage})")
                } else {
                    format!("{step} = {step_b} ({stage})")
                },
                field,
                max_abs_diff,
                max_abs,
                units,
                scale: 0.0,
            });
        }
        for i in 0..step_diffs.len() {
            step_diffs[i].scale = step_diffs
                .iter()
                .filter(|d| d.units == step_diffs[i].units)
                .map(|d| d.max_abs)
                .fold(0.0, f64::max);
        }
        out.append(&mut step_diffs);
    }
    if out.is_empty() {
        return Err(format!(
            "{} and {} have no common step field",
            a.display(),
            b.display()
        ));
    }
    Ok(out)
}
