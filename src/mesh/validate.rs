//! Mesh validation, shared by the Gmsh reader and the generators.
//!
//! Two levels:
//! - [`check_element_geometry`]: one hex8 is usable when its 8 nodes are distinct, its volume is
//!   not (near) zero, and `det J > 0` at the 8 corners and the 8 Gauss points (positive corner
//!   Jacobians catch inverted and badly "bow-tied" elements the Gauss points can miss).
//! - [`Mesh::validate`]: the structure (ids unique, indices in range, sets sorted and unique,
//!   faces consistent with their elements) and then the geometry of every element.

use crate::element::hex8::{jacobian_determinants, volume, Coords8, HEX8_FACES};
use crate::mesh::error::{Location, MeshError};
use crate::mesh::{ElementKind, Mesh};
use std::collections::HashSet;

/// Relative size under which a volume counts as zero: `|V| ≤ VOLUME_TOLERANCE · L³`, with `L`
/// the longest edge of the element.
pub const VOLUME_TOLERANCE: f64 = 1e-10;

/// Relative size under which a Jacobian determinant counts as non-positive: `det J ≤
/// JACOBIAN_TOLERANCE · L³` (the reference cube has volume 8, so `det J ≈ V/8`).
pub const JACOBIAN_TOLERANCE: f64 = 1e-12;

/// The 12 edges of a hex8 (local node pairs).
const HEX8_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

/// Checks one hex8: distinct nodes, non-zero volume, `det J > 0` at corners and Gauss points.
/// `nodes` are the element's node indices, `node_ids` the mesh's node ids (for messages).
pub fn check_element_geometry(
    x: &Coords8,
    nodes: &[u32; 8],
    node_ids: &[u64],
    element_id: u64,
    at: &dyn Fn() -> Location,
) -> Result<(), MeshError> {
    for a in 0..8 {
        for b in a + 1..8 {
            if nodes[a] == nodes[b] {
                return Err(MeshError::DegenerateElement {
                    at: at(),
                    element_id,
                    detail: format!(
                        "node {} appears twice (local nodes {a} and {b})",
                        node_ids[nodes[a] as usize]
                    ),
                });
            }
        }
    }
    let edge = HEX8_EDGES
        .iter()
        .map(|&[a, b]| (0..3).map(|i| (x[a][i] - x[b][i]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0f64, f64::max);
    let vol = volume(x);
    if !vol.is_finite() || !edge.is_finite() {
        return Err(MeshError::DegenerateElement {
            at: at(),
            element_id,
            detail: "non-finite node coordinates".into(),
        });
    }
    let scale = edge.powi(3);
    if vol.abs() <= VOLUME_TOLERANCE * scale {
        return Err(MeshError::DegenerateElement {
            at: at(),
            element_id,
            detail: format!("volume {vol:.3e} m^3 is zero for its longest edge {edge:.3e} m"),
        });
    }
    let (corners, gauss) = jacobian_determinants(x);
    let tol = JACOBIAN_TOLERANCE * scale;
    if let Some(a) = (0..8).find(|&a| corners[a] <= tol) {
        return Err(MeshError::InvertedElement {
            at: at(),
            element_id,
            detail: format!(
                "Jacobian determinant {:.3e} at corner node {} (local node {a}), volume {vol:.3e} m^3",
                corners[a], node_ids[nodes[a] as usize]
            ),
        });
    }
    if let Some(q) = (0..8).find(|&q| gauss[q] <= tol) {
        return Err(MeshError::InvertedElement {
            at: at(),
            element_id,
            detail: format!(
                "Jacobian determinant {:.3e} at Gauss point {q}, volume {vol:.3e} m^3",
                gauss[q]
            ),
        });
    }
    Ok(())
}

/// Checks one zero-thickness interface element (spec §5.1): its 4 node pairs are distinct
/// nodes at the same positions, and its face is a non-degenerate quadrilateral
/// (`‖d₁ × d₂‖ > VOLUME_TOLERANCE · L²` for the diagonals d₁, d₂ of length up to L).
pub fn check_interface_geometry(mesh: &Mesh, e: usize, at: &dyn Fn() -> Location) -> Result<(), MeshError> {
    let el = &mesh.elements[e];
    let bad = |detail: String| MeshError::DegenerateElement {
        at: at(),
        element_id: el.id,
        detail,
    };
    for a in 0..8 {
        for b in a + 1..8 {
            if el.nodes[a] == el.nodes[b] {
                return Err(bad(format!(
                    "interface element: node {} appears twice (local nodes {a} and {b})",
                    mesh.node_ids[el.nodes[a] as usize]
                )));
            }
        }
    }
    if !mesh.zero_thickness(e) {
        return Err(bad(
            "interface element: node a + 4 is not at the position of node a (not zero-thickness)".into(),
        ));
    }
    let x = mesh.element_coords(e);
    let d1: [f64; 3] = std::array::from_fn(|i| x[2][i] - x[0][i]);
    let d2: [f64; 3] = std::array::from_fn(|i| x[3][i] - x[1][i]);
    let c = [
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ];
    let area2 = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let l2 = d1
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .max(d2.iter().map(|v| v * v).sum::<f64>());
    if !(area2.is_finite() && area2 > VOLUME_TOLERANCE * l2) {
        return Err(bad(format!(
            "interface element: face area {:.3e} m^2 is zero",
            0.5 * area2
        )));
    }
    Ok(())
}

/// Checks the geometry of every element; `locate(e)` gives the place of element `e` for messages.
pub fn check_all_elements(mesh: &Mesh, locate: &dyn Fn(usize) -> Location) -> Result<(), MeshError> {
    for (e, element) in mesh.elements.iter().enumerate() {
        if element.kind == ElementKind::Interface8 {
            check_interface_geometry(mesh, e, &|| locate(e))?;
            continue;
        }
        check_element_geometry(
            &mesh.element_coords(e),
            &element.nodes,
            &mesh.node_ids,
            element.id,
            &|| locate(e),
        )?;
    }
    Ok(())
}

impl Mesh {
    /// Checks the whole mesh: structure (see [`Mesh::validate_structure`]) and the geometry of
    /// every element ([`check_element_geometry`]).
    pub fn validate(&self) -> Result<(), MeshError> {
        self.validate_structure()?;
        check_all_elements(self, &|e| {
            Location::in_memory(&format!("mesh (element index {e})"))
        })
    }

    /// Checks ids, indices, blocks, node sets and face sets for consistency.
    pub fn validate_structure(&self) -> Result<(), MeshError> {
        let bad = |reason: String| MeshError::Inconsistent {
            at: Location::in_memory("mesh"),
            reason,
        };
        let n = self.num_nodes();
        if self.node_ids.len() != n {
            return Err(bad(format!(
                "{} node ids for {n} coordinates",
                self.node_ids.len()
            )));
        }
        let mut seen = HashSet::with_capacity(n);
        for (i, id) in self.node_ids.iter().enumerate() {
            if !seen.insert(*id) {
                return Err(bad(format!("duplicate node id {id} (node index {i})")));
            }
            if self.coords[i].iter().any(|c| !c.is_finite()) {
                return Err(bad(format!("node {id} has non-finite coordinates")));
            }
        }
        let mut seen = HashSet::with_capacity(self.elements.len());
        for el in &self.elements {
            if !seen.insert(el.id) {
                return Err(bad(format!("duplicate element id {}", el.id)));
            }
            if let Some(&k) = el.nodes.iter().find(|&&k| k as usize >= n) {
                return Err(bad(format!("element {} references node index {k} >= {n}", el.id)));
            }
            match self.blocks.get(el.block as usize) {
                None => return Err(bad(format!("element {} has block index {}", el.id, el.block))),
                Some(b) if b.kind != el.kind => {
                    return Err(bad(format!(
                        "element {} differs in kind from block '{}'",
                        el.id, b.name
                    )))
                }
                Some(_) => {}
            }
        }
        for (name, set) in &self.node_sets {
            if set.windows(2).any(|w| w[0] >= w[1]) {
                return Err(bad(format!("node set '{name}' is not sorted and unique")));
            }
            if set.last().is_some_and(|&k| k as usize >= n) {
                return Err(bad(format!("node set '{name}' has a node index >= {n}")));
            }
        }
        for (name, faces) in &self.face_sets {
            for face in faces {
                let el = self.elements.get(face.element as usize).ok_or_else(|| {
                    bad(format!(
                        "face set '{name}' references element index {}",
                        face.element
                    ))
                })?;
                let local = HEX8_FACES
                    .get(face.local_face as usize)
                    .ok_or_else(|| bad(format!("face set '{name}' has local face {}", face.local_face)))?;
                if local.map(|a| el.nodes[a]) != face.nodes {
                    return Err(bad(format!(
                        "face set '{name}': nodes of face {} of element {} are not its outward nodes",
                        face.local_face, el.id
                    )));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::mesh::generate::{box_mesh, BoxSpec};
    use crate::mesh::Mesh;

    fn two_by_one() -> Mesh {
        box_mesh(&BoxSpec {
            size: [2.0, 1.0, 1.0],
            divisions: [2, 1, 1],
            ..BoxSpec::default()
        })
        .expect("box")
    }

    fn message(mesh: &Mesh) -> String {
        mesh.validate().expect_err("invalid mesh").to_string()
    }

    #[test]
    fn generated_box_is_valid() {
        two_by_one().validate().expect("valid");
    }

    #[test]
    fn structural_defects_are_reported() {
        let mut m = two_by_one();
        m.node_ids[3] = m.node_ids[0];
        assert!(message(&m).contains("duplicate node id 1"), "{}", message(&m));

        let mut m = two_by_one();
        m.elements[1].id = 1;
        assert!(message(&m).contains("duplicate element id 1"));

        let mut m = two_by_one();
        m.elements[0].nodes[5] = 99;
        assert!(message(&m).contains("element 1 references node index 99"));

        let mut m = two_by_one();
        m.elements[0].block = 7;
        assert!(message(&m).contains("block index 7"));

        let mut m = two_by_one();
        m.node_sets.get_mut("xmin").expect("set").reverse();
        assert!(message(&m).contains("node set 'xmin' is not sorted"));

        let mut m = two_by_one();
        m.face_sets.get_mut("zmax").expect("set")[0].nodes.reverse();
        assert!(message(&m).contains("face set 'zmax'"), "{}", message(&m));

        let mut m = two_by_one();
        m.coords[2][1] = f64::NAN;
        assert!(message(&m).contains("non-finite"));
    }

    #[test]
    fn inverted_and_degenerate_generated_elements_are_named() {
        let mut m = two_by_one();
        // Push a top corner of element 2 below its base: a folded corner.
        let n = m.elements[1].nodes[6] as usize;
        m.coords[n][2] = -0.5;
        let msg = message(&m);
        assert!(
            msg.contains("element index 1") && msg.contains("element 2 is inverted"),
            "{msg}"
        );

        let mut m = two_by_one();
        m.face_sets.clear();
        m.elements[0].nodes[7] = m.elements[0].nodes[6];
        let msg = message(&m);
        assert!(
            msg.contains("element 1 is degenerate") && msg.contains("appears twice"),
            "{msg}"
        );
    }
}
