//! Scene errors. Each names the YAML path (e.g. `materials.fill.young`) or the file.

use thiserror::Error;

/// An error in a scene file, its mesh, or their cross-references. Input errors exit with code 2.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The scene file cannot be read.
    #[error("{file}: cannot read scene file: {source}")]
    Read {
        /// Scene path.
        file: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// The YAML is malformed or does not match the schema.
    #[error("{file}: {path}: {message}")]
    Parse {
        /// Scene path.
        file: String,
        /// YAML path where the error is (`.` for the root).
        path: String,
        /// Parser message (with line and column where known).
        message: String,
    },
    /// A value is invalid.
    #[error("{file}: {path}: {message}")]
    Invalid {
        /// Scene path.
        file: String,
        /// YAML path of the value.
        path: String,
        /// Why it is rejected.
        message: String,
    },
    /// The mesh cannot be read or is invalid.
    #[error("{file}: mesh: {message}")]
    Mesh {
        /// Scene path.
        file: String,
        /// The mesh error.
        message: String,
    },
}
