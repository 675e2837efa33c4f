//! The global mesh as read from a file or generated: nodes, elements, element blocks, node sets
//! and face sets. Everything is in **input order**; ids are the input's ids. Indices (`u32`) are
//! 0-based positions in these arrays and are the same on every rank.

use std::collections::BTreeMap;

pub mod dam_generator;
pub mod dam_spec;
pub mod dam_stages;
pub mod error;
pub mod generate;
pub mod gmsh;
pub mod validate;

pub use error::{Location, MeshError};

/// Relative tolerance under which a hexahedron's paired nodes count as coincident (zero
/// thickness), relative to its longest face diagonal.
pub const ZERO_THICKNESS: f64 = 1e-9;

/// Element types the solver knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum ElementKind {
    /// 8-node trilinear hexahedron (Gmsh type 5), node order as in Gmsh.
    Hex8,
    /// Zero-thickness 8-node interface or joint element (spec §5.1): nodes 0–3 on face B (the
    /// slab side), nodes 4–7 on face A (the cushion side), node `a + 4` paired with node `a` at
    /// the same position. In a Gmsh file it is a hexahedron whose top face (nodes 5–8)
    /// coincides with its bottom face (nodes 1–4); [`Mesh::classify_zero_thickness`] finds them.
    Interface8,
}

impl ElementKind {
    /// Number of nodes.
    pub fn nodes(self) -> usize {
        match self {
            ElementKind::Hex8 | ElementKind::Interface8 => 8,
        }
    }
}

/// One volume element.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    /// The element's id in the input file.
    pub id: u64,
    /// Element type.
    pub kind: ElementKind,
    /// Node indices (into [`Mesh::coords`]), in the element type's local order.
    pub nodes: [u32; 8],
    /// Index of the block (into [`Mesh::blocks`]) the element belongs to.
    pub block: u32,
}

/// A boundary face of a volume element (for surface loads), e.g. the upstream face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Face {
    /// Index of the volume element that owns the face.
    pub element: u32,
    /// Local face number of that element (see [`crate::element::hex8`]).
    pub local_face: u8,
    /// The face's 4 node indices, ordered so that the right-hand normal points **out** of the element.
    pub nodes: [u32; 4],
}

/// A named element block (a Gmsh physical volume).
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Name of the physical group.
    pub name: String,
    /// Element type of every element in the block.
    pub kind: ElementKind,
    /// For interface blocks: the orientation vector n_ref, pointing from face B (slab) into
    /// face A (cushion/dam) (spec (E3)); generators set it, a scene can give or override it.
    pub orientation: Option<[f64; 3]>,
}

/// The global mesh.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Input id of each node.
    pub node_ids: Vec<u64>,
    /// Coordinates (m) of each node: x stream, y dam axis, z up.
    pub coords: Vec<[f64; 3]>,
    /// Volume elements in input order.
    pub elements: Vec<Element>,
    /// Element blocks, in order of first appearance.
    pub blocks: Vec<Block>,
    /// Named node sets (sorted, unique node indices) from physical points, curves and surfaces.
    pub node_sets: BTreeMap<String, Vec<u32>>,
    /// Named face sets from physical surfaces, each quad matched to the volume element it bounds.
    pub face_sets: BTreeMap<String, Vec<Face>>,
}

impl Mesh {
    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.coords.len()
    }
    /// Index of the block called `name`.
    pub fn block_index(&self, name: &str) -> Option<u32> {
        self.blocks.iter().position(|b| b.name == name).map(|i| i as u32)
    }
    /// Whether element `e` is a zero-thickness interface or joint element.
    pub fn is_interface(&self, e: usize) -> bool {
        self.elements[e].kind == ElementKind::Interface8
    }
    /// Marks as [`ElementKind::Interface8`] every block whose hexahedra all have zero thickness
    /// (node `a + 4` at the position of node `a`, within `ZERO_THICKNESS · L`, L the longest
    /// face diagonal). A block that mixes zero-thickness and solid hexahedra is an error (the
    /// id of the first element that differs from the block's first element is returned).
    pub fn classify_zero_thickness(&mut self) -> Result<(), (String, u64)> {
        let mut kind: Vec<Option<bool>> = vec![None; self.blocks.len()];
        for e in 0..self.elements.len() {
            if self.elements[e].kind == ElementKind::Interface8 {
                continue;
            }
            let flat = self.zero_thickness(e);
            let b = self.elements[e].block as usize;
            match kind[b] {
                None => kind[b] = Some(flat),
                Some(k) if k != flat => return Err((self.blocks[b].name.clone(), self.elements[e].id)),
                Some(_) => {}
            }
        }
        for (b, k) in kind.iter().enumerate() {
            if *k == Some(true) {
                self.blocks[b].kind = ElementKind::Interface8;
            }
        }
        for el in &mut self.elements {
            if self.blocks[el.block as usize].kind == ElementKind::Interface8 {
                el.kind = ElementKind::Interface8;
            }
        }
        Ok(())
    }
    /// Whether the paired nodes of element `e` coincide (see [`Mesh::classify_zero_thickness`]).
    pub fn zero_thickness(&self, e: usize) -> bool {
        let x = self.element_coords(e);
        let dist = |a: &[f64; 3], b: &[f64; 3]| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        };
        let l = dist(&x[0], &x[2]).max(dist(&x[1], &x[3]));
        (0..4).all(|a| dist(&x[a], &x[a + 4]) <= ZERO_THICKNESS * l)
    }
    /// Coordinates of the nodes of element `e`.
    pub fn element_coords(&self, e: usize) -> [[f64; 3]; 8] {
        self.elements[e].nodes.map(|n| self.coords[n as usize])
    }
}
