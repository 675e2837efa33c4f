//! Resolution of the scene's blocks: the entry, material, interface options and hexahedron of
//! every mesh block.

use super::error::SceneError;
use super::schema::{BlockSpec, SceneFile, SolverSpec};
use crate::element::hex8_modes::SolidElement;
use crate::element::interface8::{Interface8Geometry, InterfaceRule};
use crate::element::interface_frame::FrameAxes;
use crate::material::{BlockMaterial, SolidParams};
use crate::mesh::Mesh;
use crate::mesh::{Block, ElementKind};
use std::collections::BTreeMap;

/// The resolved blocks of a scene: the material, interface options and hexahedron of every
/// mesh block (indexed like `mesh.blocks`).
pub(super) type ResolvedBlocks = (Vec<BlockMaterial>, Vec<Option<InterfaceBlock>>, Vec<SolidElement>);

/// Matches the scene's blocks to the mesh blocks and resolves their materials, interface
/// options and hexahedra; a block whose material is unknown or of the wrong kind for its
/// elements is an error.
pub(super) fn resolve_blocks(
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
pub(super) fn block_interface_of(
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
pub(super) fn check_interface_geometry(
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

/// The hexahedron of every block: `element` is for solid blocks, and `incompatible_modes` for
/// elastic ones only (the modes are condensed exactly for a constant D, `crate::element::hex8_modes`).
pub(super) fn block_elements(
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
pub(super) fn match_blocks<'a>(
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
pub(super) fn interface_block(
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

/// Applies `solver.integration_tol_ratio` to a block's material: a GP model (rockfill or
/// interface) integrates at min(its STOL, ratio·newton_tol) ([`SolverSpec::capped_stol`],
/// spec §8.1–§8.2).
pub(super) fn cap_integration_tolerance(material: &mut BlockMaterial, solver: &SolverSpec) {
    if let Some(o) = material.gp_integration_mut() {
        o.stol = solver.capped_stol(o.stol);
    }
}
