//! Writing the post-processing's files: a table or a figure into the output directory, its
//! path recorded for the run's list of outputs, and names made safe for file names.

use crate::plot::{Figure, PlotError};
use std::path::{Path, PathBuf};

/// A table or figure that could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// Writing a table failed.
    #[error("{path}: {source}")]
    Io {
        /// File.
        path: PathBuf,
        /// Cause.
        source: std::io::Error,
    },
    /// A figure could not be written.
    #[error(transparent)]
    Plot(#[from] PlotError),
}

impl From<OutputError> for String {
    fn from(e: OutputError) -> String {
        e.to_string()
    }
}

/// Writes `text` as `dir/name` (replacing a file there whole) and records the path.
pub fn csv_out(dir: &Path, files: &mut Vec<PathBuf>, name: &str, text: String) -> Result<(), OutputError> {
    let path = dir.join(name);
    crate::input::write_replacing(&path, text.as_bytes()).map_err(|source| OutputError::Io {
        path: path.clone(),
        source,
    })?;
    files.push(path);
    Ok(())
}

/// Saves `figure` as `dir/name` and records the path.
pub fn png_out(dir: &Path, files: &mut Vec<PathBuf>, name: &str, figure: Figure) -> Result<(), OutputError> {
    let path = dir.join(name);
    figure.save_png(&path)?;
    files.push(path);
    Ok(())
}

/// A probe name made safe for a file name: ASCII letters, digits and `-` kept, the rest `_`.
pub fn safe_name(name: &str) -> String {
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
