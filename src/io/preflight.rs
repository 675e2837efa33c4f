//! Checks of `cfrd run`'s file arguments before MPI-IO or HDF5 touch them, so a wrong path gives
//! one clear line instead of the libraries' error stacks.

use std::path::Path;

/// The checkpoint given to `--restart` must be a regular file that can be opened for reading
/// (a directory, for one, makes MPI-IO print some 60 lines before HDF5 fails).
pub fn check_restart_file(path: &Path) -> Result<(), String> {
    let named = |reason: String| format!("restart from {}: {reason}", path.display());
    let meta = std::fs::metadata(path).map_err(|e| named(e.to_string()))?;
    if !meta.is_file() {
        return Err(named(format!(
            "not a checkpoint file ({}); give the checkpoint.h5 a run wrote into its output \
             directory, e.g. out/checkpoint.h5",
            crate::input::file_kind(&meta)
        )));
    }
    std::fs::File::open(path).map_err(|e| named(format!("cannot be read: {e}")))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_directory_or_a_missing_file_is_refused_naming_the_option() {
        let dir = tempfile::tempdir().unwrap();
        let msg = check_restart_file(dir.path()).expect_err("a directory");
        assert!(
            msg.starts_with("restart from ") && msg.contains("a directory"),
            "{msg}"
        );
        let msg = check_restart_file(&dir.path().join("none.h5")).expect_err("missing");
        assert!(msg.contains("none.h5"), "{msg}");
        let file = dir.path().join("checkpoint.h5");
        std::fs::write(&file, b"x").unwrap();
        check_restart_file(&file).expect("a regular file");
    }
}
