//! Reading a closed results file serially (rank 0, or without MPI): its steps in order and
//! their stages. Every post-processing reader and `cfrd compare` open results through here.

use std::path::Path;

/// Opens a results file for serial reading (rank 0 or no MPI).
/// A FIFO, device or directory is refused before HDF5 opens (and would block on) it.
pub fn open(p: &Path) -> Result<hdf5::File, String> {
    crate::input::require_regular(p).map_err(|m| format!("{}: {m}", p.display()))?;
    hdf5::File::open(p).map_err(|e| format!("{}: {e}", p.display()))
}

/// The step group names (`000001`, ...) of a results file, in order.
pub fn step_names(f: &hdf5::File, p: &Path) -> Result<Vec<String>, String> {
    let g = f
        .group("/steps")
        .map_err(|e| format!("{}: /steps: {e}", p.display()))?;
    let mut v = g.member_names().map_err(|e| e.to_string())?;
    v.sort();
    Ok(v)
}

/// The `stage` attribute of a step group, if it has one.
pub fn stage_name(g: &hdf5::Group) -> Option<String> {
    g.attr("stage")
        .and_then(|x| x.read_scalar::<hdf5::types::VarLenUnicode>())
        .map(|s| s.to_string())
        .ok()
}

/// A results file, or the `results.h5` of a run's output directory.
pub fn results_file(p: &Path) -> std::path::PathBuf {
    if p.is_dir() {
        p.join("results.h5")
    } else {
        p.to_path_buf()
    }
}
