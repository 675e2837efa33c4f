//! `cfrd compare`: field-by-field differences between two results files (e.g. the same scene
//! on 1 and 2 ranks, or before and after a change). Serial HDF5; no MPI needed.
//!
//! For every step present in both files and every `f64` field of that step present in both,
//! the maximum absolute difference and the field's maximum magnitude are reported, with the
//! number of steps compared. A step or field that only one file holds is named; the command
//! then fails (exit code 1) unless it is asked to compare the common steps only (`--common`,
//! e.g. a run restarted from a stage checkpoint, which holds the later stages only). Steps are
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

/// What `cfrd compare` found: the differences of the steps and fields both runs hold, how many
/// steps that was, and what only one of them holds.
#[derive(Debug, Clone, Default)]
pub struct Comparison {
    /// The differences of every field both runs hold, step by step.
    pub diffs: Vec<FieldDiff>,
    /// Steps held by both runs (and compared).
    pub compared_steps: usize,
    /// Steps and fields held by one run only, e.g. `step 000003 (fill_3) only in a/results.h5`.
    pub unmatched: Vec<String>,
}

/// Compares the fields of every step that both results files hold (matched as the module
/// docs say) and lists what only one of them holds. `a` and `b` are results files or run
/// directories.
pub fn compare_results(a: &Path, b: &Path) -> Result<Comparison, String> {
    let (a, b) = (results_file(a), results_file(b));
    let (a, b) = (a.as_path(), b.as_path());
    let (fa, fb) = (open(a)?, open(b)?);
    let (sa, sb) = (step_names(&fa, a)?, step_names(&fb, b)?);
    let mut keys_b = std::collections::HashMap::new();
    for name in &sb {
        keys_b.entry(step_key(&fb, name)?).or_insert(name.clone());
    }
    let mut out = Comparison::default();
    let mut matched_b = std::collections::HashSet::new();
    for step in &sa {
        let Some(step_b) = keys_b.get(&step_key(&fa, step)?) else {
            out.unmatched.push(only_in(&fa, step, a));
            continue;
        };
        matched_b.insert(step_b.clone());
        let files = Pair {
            fa: &fa,
            fb: &fb,
            a,
            b,
        };
        let (mut step_diffs, mut fields_unmatched) = files.compare_step(step, step_b)?;
        out.diffs.append(&mut step_diffs);
        out.unmatched.append(&mut fields_unmatched);
        out.compared_steps += 1;
    }
    for step in sb.iter().filter(|s| !matched_b.contains(*s)) {
        out.unmatched.push(only_in(&fb, step, b));
    }
    if out.diffs.is_empty() {
        return Err(format!(
            "{} and {} have no common step field",
            a.display(),
            b.display()
        ));
    }
    Ok(out)
}

/// `step 000003 (fill_3) only in FILE`.
fn only_in(f: &hdf5::File, step: &str, p: &Path) -> String {
    let stage = f
        .group(&format!("/steps/{step}"))
        .ok()
        .and_then(|g| stage_name(&g))
        .unwrap_or_default();
    format!("step {step} ({stage}) only in {}", p.display())
}

/// The two open results files and their paths.
struct Pair<'f> {
    fa: &'f hdf5::File,
    fb: &'f hdf5::File,
    a: &'f Path,
    b: &'f Path,
}

impl Pair<'_> {
    /// The differences of the fields that step `step` of `a` and its match `step_b` of `b`
    /// both hold, and the fields only one of them holds.
    fn compare_step(&self, step: &str, step_b: &str) -> Result<(Vec<FieldDiff>, Vec<String>), String> {
        let (a, b) = (self.a, self.b);
        let (ga, gb) = (
            self.fa
                .group(&format!("/steps/{step}"))
                .map_err(|e| e.to_string())?,
            self.fb
                .group(&format!("/steps/{step_b}"))
                .map_err(|e| e.to_string())?,
        );
        let stage = stage_name(&ga).unwrap_or_default();
        let label = if step_b == step {
            format!("{step} ({stage})")
        } else {
            format!("{step} = {step_b} ({stage})")
        };
        let mut fields = ga.member_names().map_err(|e| e.to_string())?;
        fields.sort();
        let mut unmatched: Vec<String> = gb
            .member_names()
            .map_err(|e| e.to_string())?
            .into_iter()
            .filter(|f| !ga.link_exists(f))
            .map(|f| format!("field {f} of step {label} only in {}", b.display()))
            .collect();
        let mut step_diffs = Vec::new();
        for field in fields {
            if !gb.link_exists(&field) {
                unmatched.push(format!("field {field} of step {label} only in {}", a.display()));
                continue;
            }
            step_diffs.push(field_diff(&ga, &gb, &field, &label, [a, b])?);
        }
        for i in 0..step_diffs.len() {
            step_diffs[i].scale = step_diffs
                .iter()
                .filter(|d| d.units == step_diffs[i].units)
                .map(|d| d.max_abs)
                .fold(0.0, f64::max);
        }
        Ok((step_diffs, unmatched))
    }
}

/// The difference of one field of a matched pair of steps (its scale is set by the caller).
fn field_diff(
    ga: &hdf5::Group,
    gb: &hdf5::Group,
    field: &str,
    label: &str,
    paths: [&Path; 2],
) -> Result<FieldDiff, String> {
    let read = |g: &hdf5::Group, p: &Path| {
        g.dataset(field)
            .and_then(|d| d.read_raw::<f64>())
            .map_err(|e| format!("{}: step {label}: {field}: {e}", p.display()))
    };
    let (va, vb) = (read(ga, paths[0])?, read(gb, paths[1])?);
    if va.len() != vb.len() {
        return Err(format!(
            "step {label}: {field}: {} values in {} but {} in {}",
            va.len(),
            paths[0].display(),
            vb.len(),
            paths[1].display()
        ));
    }
    let max_abs_diff = va.iter().zip(&vb).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    let max_abs = va.iter().map(|x| x.abs()).fold(0.0, f64::max);
    let units = ga
        .dataset(field)
        .and_then(|d| d.attr("units"))
        .and_then(|x| x.read_scalar::<hdf5::types::VarLenUnicode>())
        .map(|s| s.to_string())
        .unwrap_or_default();
    Ok(FieldDiff {
        step: label.to_string(),
        field: field.to_string(),
        max_abs_diff,
        max_abs,
        units,
        scale: 0.0,
    })
}
