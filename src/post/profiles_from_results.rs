//! The static figures of a run from its closed results files: every static stage read back,
//! the parts of a run restarted from checkpoints joined in order, and the tables and plots of
//! [`crate::post::profiles`] written (`cfrd run` at its end, `cfrd profiles` afterwards).

use crate::io::results_reader::{open, stage_name, step_names};
use crate::post::profiles::{write_profiles, ProfilesSpec, StageFields};
use crate::scene::Scene;
use std::path::{Path, PathBuf};

/// Reads every stage of the closed results files `h5s` (serial HDF5), in order, and writes the
/// profile tables and plots of [`crate::post::profiles`] into `dir`. Several files are the parts of a
/// run restarted from checkpoints (`cfrd profiles`): their stages are joined in the order given,
/// and a stage found again in a later file replaces the earlier one (a part killed after it
/// published a stage's results but before that stage's checkpoint, so the next part ran the
/// stage again; or a second restart from the same checkpoint).
pub fn write_profiles_from_results(
    scene: &Scene,
    spec: &ProfilesSpec,
    h5s: &[PathBuf],
    dir: &Path,
) -> Result<Vec<PathBuf>, String> {
    let mut stages: Vec<StageFields> = Vec::new();
    for h5 in h5s {
        let file = open(h5)?;
        let elements = file
            .dataset("/mesh/element_ids")
            .map(|d| d.size())
            .map_err(|e| format!("{}: /mesh/element_ids: {e}", h5.display()))?;
        if elements != scene.mesh.elements.len() {
            return Err(format!(
                "{}: {elements} elements, the scene's mesh has {}: results of another scene?",
                h5.display(),
                scene.mesh.elements.len()
            ));
        }
        for name in step_names(&file, h5)? {
            let g = file.group(&format!("/steps/{name}")).map_err(|e| e.to_string())?;
            let stage = stage_name(&g).unwrap_or_else(|| name.clone());
            // Figs. 7-11 are the static states: a dynamic stage's steps are not theirs
            let dynamic = scene
                .stages
                .iter()
                .any(|s| s.name == stage && s.dynamic.is_some());
            if dynamic {
                continue;
            }
            stages.retain(|s| s.name != stage);
            stages.push(StageFields::read(&g, h5, stage)?);
        }
    }
    // a part that ran only dynamic stages (restarted into a quake) has no static figures
    if stages.is_empty() {
        return Ok(Vec::new());
    }
    write_profiles(&scene.mesh, spec, &stages, dir).map_err(|e| e.to_string())
}
