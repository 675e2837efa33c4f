//! Loading, validating and resolving a scene.

use super::dynamic;
use super::error::SceneError;
use super::modal;
use super::schema::{BlockSpec, HydrostaticSpec, LoadsSpec, MeshSource, SceneFile, SolverSpec, StageSpec};
use super::term::Term;
use crate::element::hex8_modes::SolidElement;
use crate::element::interface8::{Interface8Geometry, InterfaceRule};
use crate::element::interface_frame::FrameAxes;
use crate::material::{BlockMaterial, MaterialParams, SolidParams};
use crate::mesh::cfrd::{cfrd_mesh, CfrdStage};
use crate::mesh::{generate, Mesh};
use crate::mesh::{Block, ElementKind};
use std::collections::BTreeMap;
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
        })
    }
}

/// The resolved blocks of a scene: the material, interface options and hexahedron of every
/// mesh block (indexed like `mesh.blocks`).
type ResolvedBlocks = (Vec<BlockMaterial>, Vec<Option<InterfaceBlock>>, Vec<SolidElement>);

/// Matches the scene's blocks to the mesh blocks and resolves their materials, interface
/// options and hexahedra; a block whose material is unknown or of the wrong kind for its
/// elements is an error.
fn resolve_blocks(
    file: &SceneFile,
    mesh: &Mesh,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<ResolvedBlocks, SceneError> {
    let mut block_materials = Vec::with_capacity(mesh.blocks.len());
    for (name, spec) in &file.blocks {
        if !file.materials.contains_key(&spec.material) {
            return Err(inv(
                &format!("blocks.{name}.material"),
                format!("unknown material '{}'", spec.material),
            ));
        }
    }
    let block_specs = match_blocks(&file.blocks, mesh, inv)?;
    let mut block_interface = Vec::with_capacity(mesh.blocks.len());
    for (b, (key, spec)) in mesh.blocks.iter().zip(&block_specs) {
        let mut material = file.materials[&spec.material].split();
        cap_integration_tolerance(&mut material, &file.solver);
        block_interface.push(block_interface_of(mesh, b, key, spec, &material, inv)?);
        block_materials.push(material);
    }
    let block_element = block_elements(&block_specs, &block_materials, inv)?;
    Ok((block_materials, block_interface, block_element))
}

/// The interface options of mesh block `b` (scene key `key`, entry `spec`) of `material`:
/// `None` for a solid block, which must give no interface option; a material of the other kind
/// than the block's elements is an error.
fn block_interface_of(
    mesh: &Mesh,
    b: &Block,
    key: &str,
    spec: &BlockSpec,
    material: &BlockMaterial,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Option<InterfaceBlock>, SceneError> {
    let path = format!("blocks.{key}");
    match (b.kind, material) {
        (ElementKind::Hex8, BlockMaterial::Solid(_)) => {
            for (given, key) in [
                (spec.orientation.is_some(), "orientation"),
                (spec.rule.is_some(), "rule"),
                (spec.initial_normal_stress.is_some(), "initial_normal_stress"),
            ] {
                if given {
                    return Err(inv(
                        &format!("{path}.{key}"),
                        format!(
                            "'{}' is a block of solid elements; {key} applies to interface blocks only",
                            b.name
                        ),
                    ));
                }
            }
            Ok(None)
        }
        (ElementKind::Interface8, BlockMaterial::Interface(_)) => {
            Ok(Some(interface_block(mesh, b.name.as_str(), spec, &path, inv)?))
        }
        (ElementKind::Hex8, BlockMaterial::Interface(p)) => Err(inv(
            &format!("{path}.material"),
            format!(
                "'{}' is an interface law ({}) but block '{}' has solid (non-zero-thickness) elements",
                spec.material,
                p.name(),
                b.name
            ),
        )),
        (ElementKind::Interface8, BlockMaterial::Solid(p)) => Err(inv(
            &format!("{path}.material"),
            format!(
                "'{}' is a solid model ({}) but block '{}' has zero-thickness (interface) elements; \
                 give an interface or joint law (hyperbolic, mohr_coulomb, joint, gp_interface)",
                spec.material,
                p.name(),
                b.name
            ),
        )),
    }
}

/// Every interface element must have a usable geometry for its block's orientation.
fn check_interface_geometry(
    mesh: &Mesh,
    block_interface: &[Option<InterfaceBlock>],
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<(), SceneError> {
    for (e, el) in mesh.elements.iter().enumerate() {
        if let Some(ib) = &block_interface[el.block as usize] {
            if let Err(err) = Interface8Geometry::new(
                &mesh.element_coords(e),
                &ib.orientation,
                &FrameAxes::default(),
                ib.rule,
            ) {
                return Err(inv(
                    &format!("blocks.{}", mesh.blocks[el.block as usize].name),
                    format!("interface element {}: {err}", el.id),
                ));
            }
        }
    }
    Ok(())
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

/// The stages of the scene with their terms; a scene without stages has one stage `static`
/// that places every block.
fn resolve_stages(
    file: &SceneFile,
    mesh: &Mesh,
    base: &Path,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Vec<Stage>, SceneError> {
    let mut stages = Vec::new();
    if file.stages.is_empty() {
        stages.push(Stage {
            name: "static".into(),
            activate: (0..mesh.blocks.len() as u32).collect(),
            terms: resolve_loads(&file.loads, None, mesh, "loads", inv)?,
            load_steps: file.solver.load_steps,
            step_growth: file.solver.step_growth,
            dynamic: None,
            modal: None,
        });
    } else {
        let mut placed = vec![None::<usize>; mesh.blocks.len()];
        for k in 0..file.stages.len() {
            let stage = resolve_stage(file, mesh, base, k, &mut placed, &stages, inv)?;
            stages.push(stage);
        }
    }
    Ok(stages)
}

/// Resolves `file.stages[k]` after the stages `before`; `placed` holds the stage that placed
/// each block so far. A name used twice, an unknown block, a block placed twice and a second
/// modal analysis are errors.
fn resolve_stage(
    file: &SceneFile,
    mesh: &Mesh,
    base: &Path,
    k: usize,
    placed: &mut [Option<usize>],
    before: &[Stage],
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Stage, SceneError> {
    let st = &file.stages[k];
    if file.stages[..k].iter().any(|o| o.name == st.name) {
        return Err(inv(
            &format!("stages[{k}].name"),
            format!("stage name '{}' is used twice", st.name),
        ));
    }
    let mut activate = Vec::new();
    for (i, b) in st.activate.iter().enumerate() {
        let path = format!("stages[{k}].activate[{i}]");
        let Some(bi) = mesh.block_index(b) else {
            return Err(inv(&path, format!("the mesh has no block '{b}'")));
        };
        if let Some(first) = placed[bi as usize] {
            return Err(inv(
                &path,
                format!("block '{b}' is already placed in stage {first}"),
            ));
        }
        placed[bi as usize] = Some(k);
        activate.push(bi);
    }
    let dynamic = match &st.dynamic {
        Some(d) => Some(dynamic::resolve(d, base, &format!("stages[{k}].dynamic"), inv)?),
        None => None,
    };
    let (load_steps, step_growth) = match &dynamic {
        Some(d) => (d.steps, 1),
        None => (
            st.load_steps.unwrap_or(file.solver.load_steps),
            file.solver.step_growth,
        ),
    };
    let stage_path = format!("stages[{k}]");
    let modal = modal::resolve(st.modal.as_ref(), dynamic.as_ref(), &stage_path, inv)?;
    if let (Some(_), Some(first)) = (modal, before.iter().position(|s: &Stage| s.modal.is_some())) {
        return Err(inv(
            &stage_path,
            format!(
                "a modal analysis runs already in stage {} '{}'; a scene runs at most one",
                first + 1,
                before[first].name
            ),
        ));
    }
    Ok(Stage {
        name: st.name.clone(),
        activate,
        terms: resolve_loads(
            &file.loads,
            Some(&st.loads),
            mesh,
            &format!("stages[{k}].loads"),
            inv,
        )?,
        load_steps,
        step_growth,
        dynamic,
        modal,
    })
}

/// The hexahedron of every block: `element` is for solid blocks, and `incompatible_modes` for
/// elastic ones only (the modes are condensed exactly for a constant D, `crate::element::hex8_modes`).
fn block_elements(
    block_specs: &[(&str, &BlockSpec)],
    block_materials: &[BlockMaterial],
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Vec<SolidElement>, SceneError> {
    let resolve = |((key, spec), material): (&(&str, &BlockSpec), &BlockMaterial)| {
        let path = format!("blocks.{key}.element");
        match (spec.element, material) {
            (None, _) => Ok(SolidElement::Trilinear),
            (Some(_), BlockMaterial::Interface(_)) => Err(inv(
                &path,
                "applies to blocks of solid elements only; this block has zero-thickness elements".into(),
            )),
            (Some(SolidElement::IncompatibleModes), BlockMaterial::Solid(p))
                if !matches!(p, SolidParams::Elastic(_)) =>
            {
                Err(inv(
                    &path,
                    format!(
                        "incompatible_modes needs an elastic material; '{}' is {}",
                        spec.material,
                        p.name()
                    ),
                ))
            }
            (Some(e), BlockMaterial::Solid(_)) => Ok(e),
        }
    };
    block_specs.iter().zip(block_materials).map(resolve).collect()
}

/// Whether `name` matches the block pattern `pattern` (`*` matches any run of characters,
/// including none; every other character matches itself).
pub fn block_pattern_matches(pattern: &str, name: &str) -> bool {
    let (p, n): (Vec<char>, Vec<char>) = (pattern.chars().collect(), name.chars().collect());
    // matched[j]: pattern prefix p[..i] matches name prefix n[..j]
    let mut matched = vec![false; n.len() + 1];
    matched[0] = true;
    for &c in &p {
        if c == '*' {
            for j in 1..=n.len() {
                matched[j] = matched[j] || matched[j - 1];
            }
        } else {
            for j in (1..=n.len()).rev() {
                matched[j] = matched[j - 1] && n[j - 1] == c;
            }
            matched[0] = false;
        }
    }
    matched[n.len()]
}

/// The scene entry of every mesh block (in mesh order) with its key in `blocks`: the exact key
/// if there is one, else the single pattern that matches the name. An exact key that names no
/// block, a pattern that matches no block, a block matched by two patterns and a block without
/// an entry are errors naming the YAML paths.
fn match_blocks<'a>(
    blocks: &'a BTreeMap<String, BlockSpec>,
    mesh: &Mesh,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Vec<(&'a str, &'a BlockSpec)>, SceneError> {
    let patterns: Vec<(&String, &BlockSpec)> = blocks.iter().filter(|(k, _)| k.contains('*')).collect();
    for (name, _) in blocks.iter().filter(|(k, _)| !k.contains('*')) {
        if mesh.block_index(name).is_none() {
            let known: Vec<&str> = mesh.blocks.iter().map(|b| b.name.as_str()).collect();
            let shown = if known.len() > 20 {
                format!("{} ... ({} blocks)", known[..20].join(", "), known.len())
            } else {
                known.join(", ")
            };
            return Err(inv(
                &format!("blocks.{name}"),
                format!("the mesh has no block (physical volume) '{name}'; it has: {shown}"),
            ));
        }
    }
    for (pattern, _) in &patterns {
        if !mesh
            .blocks
            .iter()
            .any(|b| block_pattern_matches(pattern, &b.name))
        {
            return Err(inv(
                &format!("blocks.{pattern}"),
                format!("the pattern '{pattern}' matches no block of the mesh"),
            ));
        }
    }
    let mut out = Vec::with_capacity(mesh.blocks.len());
    for b in &mesh.blocks {
        if let Some((key, spec)) = blocks.get_key_value(&b.name) {
            out.push((key.as_str(), spec));
            continue;
        }
        let mut hits = patterns.iter().filter(|(p, _)| block_pattern_matches(p, &b.name));
        match (hits.next(), hits.next()) {
            (Some((key, spec)), None) => out.push((key.as_str(), *spec)),
            (Some((first, _)), Some((second, _))) => {
                return Err(inv(
                    &format!("blocks.{second}"),
                    format!(
                        "block '{}' is matched by two patterns, blocks.{first} and blocks.{second}; \
                         give the block its own key or make the patterns disjoint",
                        b.name
                    ),
                ))
            }
            _ => {
                return Err(inv(
                    "blocks",
                    format!("mesh block '{}' has no material assigned", b.name),
                ))
            }
        }
    }
    Ok(out)
}

/// Appends the scene's `earthquake` as a dynamic stage after the last stage, with that
/// stage's own loads (the scene-wide loads apply to every stage anyway).
fn append_earthquake(
    file: &mut SceneFile,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<(), SceneError> {
    let Some(quake) = file.earthquake.clone() else {
        return Ok(());
    };
    let Some(last) = file.stages.last() else {
        return Err(inv(
            "earthquake",
            "needs stages before it (`stages`, or the schedule of `mesh.cfrd`)".into(),
        ));
    };
    let loads = last.loads.clone();
    file.stages.push(StageSpec {
        name: "earthquake".into(),
        activate: Vec::new(),
        loads,
        load_steps: None,
        dynamic: Some(quake),
        modal: None,
    });
    Ok(())
}

/// The stages of a generated schedule as scene stages (impoundment levels become hydrostatic
/// loads on the slab face set `slab_upstream`).
fn schedule_stages(schedule: &[CfrdStage], src: &MeshSource) -> Vec<StageSpec> {
    let unit_weight = src.cfrd.as_ref().map_or(9810.0, |c| c.water_unit_weight);
    schedule
        .iter()
        .map(|st| StageSpec {
            name: st.name.clone(),
            activate: st.activate.clone(),
            loads: LoadsSpec {
                hydrostatic: st
                    .water_level
                    .map(|level| HydrostaticSpec {
                        faces: "slab_upstream".into(),
                        level,
                        unit_weight,
                    })
                    .into_iter()
                    .collect(),
                ..LoadsSpec::default()
            },
            load_steps: st.load_steps,
            dynamic: None,
            modal: None,
        })
        .collect()
}

/// Options of an interface block, resolved from the scene and the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterfaceBlock {
    /// Orientation vector n_ref, from the slab side into the cushion side (spec (E3)).
    pub orientation: [f64; 3],
    /// Integration rule (spec (E8)).
    pub rule: InterfaceRule,
    /// Normal stress σ_n0 (Pa, compression positive) of the points when placed (spec (E9)).
    pub initial_normal_stress: f64,
}

/// Resolves the options of interface block `name`.
fn interface_block(
    mesh: &Mesh,
    name: &str,
    spec: &super::schema::BlockSpec,
    path: &str,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<InterfaceBlock, SceneError> {
    let from_mesh = mesh
        .block_index(name)
        .and_then(|b| mesh.blocks[b as usize].orientation);
    let Some(orientation) = spec.orientation.or(from_mesh) else {
        return Err(inv(
            &format!("{path}.orientation"),
            format!(
                "block '{name}' has zero-thickness (interface) elements: give its orientation vector \
                 from the slab side (nodes 1-4) into the cushion side (nodes 5-8), e.g. [1, 0, -1.4]"
            ),
        ));
    };
    let n = orientation.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !(n.is_finite() && n > 0.0) {
        return Err(inv(
            &format!("{path}.orientation"),
            format!("must be a finite non-zero vector, got {orientation:?}"),
        ));
    }
    let sigma0 = spec.initial_normal_stress.unwrap_or(0.0);
    if !(sigma0.is_finite() && sigma0 >= 0.0) {
        return Err(inv(
            &format!("{path}.initial_normal_stress"),
            format!("must be finite and ≥ 0 (Pa, compression positive), got {sigma0}"),
        ));
    }
    Ok(InterfaceBlock {
        orientation,
        rule: spec.rule.unwrap_or_default(),
        initial_normal_stress: sigma0,
    })
}

/// One resolved stage: blocks placed at its start, the loads at its end, and its load steps.
///
/// Within a stage the external force goes linearly from the force at the end of the previous
/// stage to the force of this stage's terms on every active element (load factor λ ∈ (0, 1]).
#[derive(Debug, Clone, PartialEq)]
pub struct Stage {
    /// Stage name.
    pub name: String,
    /// Block indices placed (activated, strain-free) at the start of the stage.
    pub activate: Vec<u32>,
    /// The physics terms at the end of the stage (besides the internal force, always present).
    pub terms: Vec<Term>,
    /// Number of equal load steps (time steps of a dynamic stage).
    pub load_steps: u32,
    /// How far an easy load step may grow over the nominal one (`solver.step_growth`; 1 for a
    /// dynamic stage, whose time steps stay equal).
    pub step_growth: u32,
    /// How a dynamic stage is integrated in time; `None` for a static stage.
    pub dynamic: Option<super::dynamic::DynamicStage>,
    /// The modal analysis at the stage's start, if any ([`super::modal`]).
    pub modal: Option<super::modal::ModalRequest>,
}

impl Stage {
    /// The end of the stage's time: 1 for a static stage (its time is the load factor), the
    /// duration (s) of a dynamic one.
    pub fn t_end(&self) -> f64 {
        self.dynamic.as_ref().map_or(1.0, |d| d.duration)
    }
}

/// The terms of the scene-wide loads plus a stage's own loads; face sets are checked.
fn resolve_loads(
    base: &LoadsSpec,
    stage: Option<&LoadsSpec>,
    mesh: &Mesh,
    path: &str,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<Vec<Term>, SceneError> {
    let mut terms = Vec::new();
    for (which, loads) in [(String::from("loads"), Some(base)), (path.to_string(), stage)] {
        let Some(loads) = loads else { continue };
        if let Some(g) = &loads.gravity {
            if terms.iter().any(|t| matches!(t, Term::Gravity { .. })) {
                return Err(inv(
                    &format!("{which}.gravity"),
                    "gravity is already given in the scene's loads".into(),
                ));
            }
            terms.push(Term::Gravity { g: g.g });
        }
        for (i, p) in loads.pressure.iter().enumerate() {
            if !mesh.face_sets.contains_key(&p.faces) {
                return Err(inv(
                    &format!("{which}.pressure[{i}].faces"),
                    format!("the mesh has no face set '{}'", p.faces),
                ));
            }
            terms.push(Term::Pressure {
                faces: p.faces.clone(),
                value: p.value,
            });
        }
        for (i, h) in loads.hydrostatic.iter().enumerate() {
            if !mesh.face_sets.contains_key(&h.faces) {
                return Err(inv(
                    &format!("{which}.hydrostatic[{i}].faces"),
                    format!("the mesh has no face set '{}'", h.faces),
                ));
            }
            terms.push(Term::Hydrostatic {
                faces: h.faces.clone(),
                level: h.level,
                unit_weight: h.unit_weight,
            });
        }
    }
    Ok(terms)
}

/// Parses scene text with the YAML path of any error.
pub fn parse(text: &str, source: &str) -> Result<SceneFile, SceneError> {
    let de = serde_yaml::Deserializer::from_str(text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = match e.path().to_string() {
            p if p == "?" || p == "." => "(document)".to_string(),
            p => p,
        };
        let message = e.into_inner().to_string();
        // serde_yaml may start its message with (part of) the path again
        let message = match message.split_once(": ") {
            Some((head, rest)) if path.starts_with(head) => rest.to_string(),
            _ => message,
        };
        SceneError::Parse {
            file: source.to_string(),
            path,
            message,
        }
    })
}

/// Value checks that need no mesh: units, ranges, plausibility of SI magnitudes.
fn check_values(f: &SceneFile, inv: &dyn Fn(&str, String) -> SceneError) -> Result<(), SceneError> {
    for (name, m) in &f.materials {
        m.validate()
            .map_err(|e| inv(&format!("materials.{name}.{}", e.field), e.reason))?;
        if let MaterialParams::Elastic(p) = m {
            if !(1.0e5..=1.0e13).contains(&p.young) {
                return Err(inv(
                    &format!("materials.{name}.young"),
                    format!(
                        "{} Pa is not a plausible Young's modulus; values are in Pa (SI), e.g. 25.5e9",
                        p.young
                    ),
                ));
            }
        }
        let BlockMaterial::Solid(solid) = m.split() else {
            continue;
        };
        let rho = solid.density();
        if !(100.0..=30_000.0).contains(&rho) {
            return Err(inv(
                &format!("materials.{name}.density"),
                format!("{rho} kg/m³ is not a plausible density; values are in kg/m³ (SI), e.g. 2150"),
            ));
        }
    }
    super::ranges::check_loads(&f.loads, "loads", inv)?;
    super::ranges::check_stages_and_counts(f, inv)?;
    let s = &f.solver;
    if !(s.rtol > 0.0 && s.rtol < 1.0) {
        return Err(inv("solver.rtol", format!("must lie in (0, 1), got {}", s.rtol)));
    }
    if !(s.newton_tol > 0.0 && s.newton_tol < 1.0) {
        return Err(inv(
            "solver.newton_tol",
            format!("must lie in (0, 1), got {}", s.newton_tol),
        ));
    }
    check_integration_tol_ratio(s, "solver.integration_tol_ratio", inv)
}

/// `solver.integration_tol_ratio` (or the command line's value, named `path`) is 0 or in
/// (0, 1] with ratio·newton_tol ≥ 1e-12, the smallest substepping tolerance.
fn check_integration_tol_ratio(
    s: &SolverSpec,
    path: &str,
    inv: &dyn Fn(&str, String) -> SceneError,
) -> Result<(), SceneError> {
    let r = s.integration_tol_ratio;
    if !(r.is_finite() && (r == 0.0 || (r * s.newton_tol >= 1.0e-12 && r <= 1.0))) {
        return Err(inv(
            path,
            format!(
                "must be 0 (off) or lie in (0, 1] with ratio·newton_tol ≥ 1e-12 (the smallest \
                 substepping tolerance), got {r} (newton_tol {})",
                s.newton_tol
            ),
        ));
    }
    Ok(())
}

/// Applies `solver.integration_tol_ratio` to a block's material: a GP model (rockfill or
/// interface) integrates at min(its STOL, ratio·newton_tol) ([`SolverSpec::capped_stol`],
/// spec §8.1–§8.2).
fn cap_integration_tolerance(material: &mut BlockMaterial, solver: &SolverSpec) {
    if let Some(o) = material.gp_integration_mut() {
        o.stol = solver.capped_stol(o.stol);
    }
}

impl Scene {
    /// Caps the substepping tolerance of every GP material further at `ratio`·newton_tol (the
    /// command line's `--integration-tol-ratio`, see
    /// [`SolverSpec::integration_tol_ratio`]); the scene text and its hash stay, so a run
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
