//! The global mesh as read from a file or generated: nodes, elements, element blocks, node sets
//! and face sets. Everything is in **input order**; ids are the input's ids. Indices (`u32`) are
//! 0-based positions in these arrays and are the same on every rank.

use std::collections::BTreeMap;

pub mod error;
pub mod generate;
pub mod gmsh;
pub mod validate;

pub use error::{Location, MeshError};

/// Element types the solver knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum ElementKind {
    /// 8-node trilinear hexahedron (Gmsh type 5), node order as in Gmsh.
    Hex8,
}

impl ElementKind {
    /// Number of nodes.
    pub fn nodes(self) -> usize {
        match self {
            ElementKind::Hex8 => 8,
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
    /// Coordinates of the nodes of element `e`.
    pub fn element_coords(&self, e: usize) -> [[f64; 3]; 8] {
        self.elements[e].nodes.map(|n| self.coords[n as usize])
    }
}
