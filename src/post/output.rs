//! Writing the post-processing's files: a table or a figure into the output directory, its
//! path recorded for the run's list of outputs, and file names made safe.

use crate::plot::Figure;
use std::path::{Path, PathBuf};

/// Writes `text` as `dir/name` and records the path.
pub(crate) fn csv_out(dir: &Path, files: &mut Vec<PathBuf>, name: &str, text: String) -> Result<(), String> {
    let path = dir.join(name);
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    files.push(path);
    Ok(())
}

/// Saves `figure` as `dir/name` and records the path.
pub(crate) fn png_out(
    dir: &Path,
    files: &mut Vec<PathBuf>,
    name: &str,
    figure: Figure,
) -> Result<(), String> {
    let path = dir.join(name);
    figure.save_png(&path).map_err(|e| e.to_string())?;
    files.push(path);
    Ok(())
}

/// A probe name made safe for a file name.
pub(crate) fn safe_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
