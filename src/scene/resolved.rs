//! The resolved scene: [`Scene`], loaded from its text, checked and resolved against its mesh;
//! the mesh it reads or generates, its constrained DOFs and the hash of its text.

use super::blocks::{cap_integration_tolerance, check_interface_geometry, resolve_blocks, InterfaceBlock};
use super::checks::{check_integration_tol_ratio, check_values};
use super::error::SceneError;
use super::parse::parse;
use super::schema::{MeshSource, SceneFile};
use super::stages::{append_earthquake, resolve_stages, schedule_stages, Stage};
use crate::element::hex8_modes::SolidElement;
use crate::material::BlockMaterial;
use crate::mesh::dam_generator::cfrd_mesh;
use crate::mesh::dam_stages::CfrdStage;
use crate::mesh::{generate, Mesh};
use std::path::{Path, PathBuf};

/// A loaded, validated and resolved scene.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The file as written; a `mesh.cfrd` scene without `stages` gets the generator's schedule
    /// as its `stages`.
    pub file: SceneFile,
    /// Where it was read from (for messages); `<embedded>` for the built-in default.
    pub source: String,
    /// The mesh.
    pub mesh: Mesh,
    /// Material of every mesh block (indexed like `mesh.blocks`).
    pub block_materials: Vec<BlockMaterial>,
    /// Options of every interface block (`None` for solid blocks; indexed like `mesh.blocks`).
    pub block_interface: Vec<Option<InterfaceBlock>>,
    /// The hexahedron of every block (indexed like `mesh.blocks`; `trilinear` for interfaces).
    pub block_element: Vec<SolidElement>,
    /// The stages, in order (one stage that places every block when the scene has none).
    pub stages: Vec<Stage>,
    /// Constrained DOFs: (node index, component, prescribed value), sorted and unique.
    pub fixed: Vec<(u32, u8, f64)>,
    /// FNV-1a hash of the scene text (checkpoints refuse another scene).
    pub hash: String,
    /// Directory that relative paths of the scene (mesh, partition) are taken from.
    pub base: PathBuf,
    /// The files the scene reads besides its text, with their content hashes (checkpoints
    /// refuse a restart with changed ones: [`super::inputs`]).
    pub inputs: Vec<super::inputs::InputFile>,
}

impl Scene {
    /// A path of the scene resolved against the scene file's directory.
    pub fn resolve(&self, p: &Path) -> PathBuf {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.base.join(p)
        }
    }
}

impl Scene {
    /// Reads, parses, validates and resolves a scene file (a regular file of at most
    /// [`crate::input::MAX_SCENE_BYTES`]).
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let read_error = |reason: String| SceneError::Read {
            file: path.display().to_string(),
            source: std::io::Error::other(reason),
        };
        let bytes = crate::input::read_bounded(path, crate::input::MAX_SCENE_BYTES).map_err(read_error)?;
        let text = String::from_utf8(bytes).map_err(|e| read_error(format!("not UTF-8 text: {e}")))?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Scene::from_str(&text, &path.display().to_string(), &base)
    }

    /// Parses, validates and resolves scene text; relative paths are taken from `base`. A
    /// leading byte order mark is dropped; nesting deeper than the limits of [`super::text`]
    /// and a key given twice in a mapping are errors.
    pub fn from_str(text: &str, source: &str, base: &Path) -> Result<Scene, SceneError> {
        let text = super::text::strip_bom(text);
        super::text::check_depth(text, source)?;
        super::text::check_duplicate_keys(text, source)?;
        let mut file = parse(text, source)?;
        let inv = |path: &str, message: String| SceneError::Invalid {
            file: source.to_string(),
            path: path.to_string(),
            message,
        };
        check_values(&file, &inv)?;
        let (mesh, schedule) = build_mesh(&file.mesh, base).map_err(|message| SceneError::Mesh {
            file: source.to_string(),
            message,
        })?;
        if file.stages.is_empty() {
            if let Some(schedule) = schedule {
                file.stages = schedule_stages(&schedule, &file.mesh);
            }
        }
        append_earthquake(&mut file, &inv)?;
        let (block_materials, block_interface, block_element) = resolve_blocks(&file, &mesh, &inv)?;
        check_interface_geometry(&mesh, &block_interface, &inv)?;
        let fixed = resolve_boundary(&file, &mesh, &inv)?;
        let stages = resolve_stages(&file, &mesh, base, &inv)?;
        super::restraint::check_restraint(&mesh, &stages, &fixed).map_err(|m| inv("boundary", m))?;
        let inputs = super::inputs::input_files(&file, base).map_err(|(key, m)| inv(&key, m))?;

        Ok(Scene {
            file,
            source: source.to_string(),
            mesh,
            block_materials,
            block_interface,
            block_element,
            stages,
            fixed,
            hash: fnv1a(text.as_bytes()),
            base: base.to_path_buf(),
            inputs,
        })
    }
}

/// The constrained DOFs of the scene's `boundary`: (node index, component, prescribed value),
/// sorted and unique; a DOF fixed twice with different values is an error.
fn resolve_boundary(
    file: &SceneFile,
    mesh: &Mesh,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Vec<(u32, u8, f64)>, SceneError> {
    let mut fixed = Vec::new();
    for (i, f) in file.boundary.iter().enumerate() {
        let Some(nodes) = mesh.node_sets.get(&f.set) else {
            let known: Vec<&String> = mesh.node_sets.keys().collect();
            return Err(inv(
                &format!("boundary[{i}].set"),
                format!("the mesh has no node set '{}'; it has: {known:?}", f.set),
            ));
        };
        if f.fix.is_empty() {
            return Err(inv(&format!("boundary[{i}].fix"), "lists no component".into()));
        }
        if !f.value.is_empty() && f.value.len() != f.fix.len() {
            return Err(inv(
                &format!("boundary[{i}].value"),
                format!("has {} entries but fix has {}", f.value.len(), f.fix.len()),
            ));
        }
        for (k, axis) in f.fix.iter().enumerate() {
            let v = f.value.get(k).copied().unwrap_or(0.0);
            fixed.extend(nodes.iter().map(|&n| (n, axis.index() as u8, v)));
        }
    }
    fixed.sort_by_key(|a| (a.0, a.1));
    for w in fixed.windows(2) {
        if (w[0].0, w[0].1) == (w[1].0, w[1].1) && w[0].2 != w[1].2 {
            return Err(inv(
                "boundary",
                format!(
                    "node {} component {} is fixed twice with different values",
                    mesh.node_ids[w[0].0 as usize], w[0].1
                ),
            ));
        }
    }
    fixed.dedup_by(|a, b| (a.0, a.1) == (b.0, b.1));
    Ok(fixed)
}

impl Scene {
    /// Caps the substepping tolerance of every GP material further at `ratio`·newton_tol (the
    /// command line's `--integration-tol-ratio`, see
    /// [`super::schema::SolverSpec::integration_tol_ratio`]); the scene text and its hash stay, so a run
    /// stalled at the integration noise can be continued from its checkpoint. An invalid ratio
    /// is an input error naming the option.
    pub fn cap_integration_tol(&mut self, ratio: f64) -> Result<(), SceneError> {
        let mut solver = self.file.solver.clone();
        solver.integration_tol_ratio = ratio;
        let inv = |path: &str, message: String| SceneError::Invalid {
            file: self.source.clone(),
            path: path.to_string(),
            message,
        };
        check_integration_tol_ratio(&solver, "--integration-tol-ratio", &inv)?;
        for m in &mut self.block_materials {
            cap_integration_tolerance(m, &solver);
        }
        if ratio > 0.0 {
            let own = self.file.solver.integration_tol_ratio;
            self.file.solver.integration_tol_ratio = if own > 0.0 { own.min(ratio) } else { ratio };
        }
        Ok(())
    }
}

/// Reads or generates the mesh, then validates it; a generated CFRD also gives its schedule.
fn build_mesh(src: &MeshSource, base: &Path) -> Result<(Mesh, Option<Vec<CfrdStage>>), String> {
    let (mesh, schedule) = match (&src.file, &src.box_, &src.dam, &src.cfrd) {
        (Some(p), None, None, None) => (read_mesh_file(p, base)?, None),
        (None, Some(b), None, None) => (generate::box_mesh(b).map_err(|e| e.to_string())?, None),
        (None, None, Some(d), None) => (generate::dam_mesh(d).map_err(|e| e.to_string())?, None),
        (None, None, None, Some(c)) => {
            let model = cfrd_mesh(c).map_err(|e| e.to_string())?;
            (model.mesh, Some(model.stages))
        }
        _ => return Err("give exactly one of mesh.file, mesh.box, mesh.dam or mesh.cfrd".into()),
    };
    mesh.validate().map_err(|e| e.to_string())?;
    Ok((mesh, schedule))
}

/// Reads the Gmsh file `p` of a scene in the folder `base`. A file that cannot be read is named
/// as written and, for a relative path, as resolved against the scene's folder.
fn read_mesh_file(p: &Path, base: &Path) -> Result<Mesh, String> {
    let path: PathBuf = if p.is_absolute() {
        p.to_path_buf()
    } else {
        base.join(p)
    };
    crate::mesh::gmsh::read_gmsh(&path).map_err(|e| match e {
        crate::mesh::MeshError::Unreadable { reason, .. } if !p.is_absolute() => {
            let resolved = std::path::absolute(&path).unwrap_or(path);
            format!(
                "file '{}' (as written; a relative path is taken from the scene's folder) is {}: \
                 cannot read mesh file: {reason}",
                p.display(),
                resolved.display()
            )
        }
        other => other.to_string(),
    })
}

/// FNV-1a hash (hex) of bytes.
pub fn fnv1a(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}
