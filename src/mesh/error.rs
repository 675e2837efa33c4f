//! Errors of mesh input, generation and validation. Every message names its place: the file and
//! line (or the generator), and the element or node id involved.

use std::fmt;
use thiserror::Error;

/// Where in the input a problem was found: a file and line, or a generated/in-memory mesh.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// File name as given by the caller, or a description such as `generated mesh`.
    pub file: String,
    /// 1-based line number, when the mesh came from a file.
    pub line: Option<usize>,
}

impl Location {
    /// A place in a file.
    pub fn file_line(file: &str, line: usize) -> Self {
        Location {
            file: file.to_string(),
            line: Some(line),
        }
    }
    /// A mesh that does not come from a file (e.g. a generator).
    pub fn in_memory(what: &str) -> Self {
        Location {
            file: what.to_string(),
            line: None,
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{}", self.file, line),
            None => write!(f, "{}", self.file),
        }
    }
}

/// A mesh that cannot be read, generated or used.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeshError {
    /// The file is missing or unreadable.
    #[error("{file}: cannot read mesh file: {reason}")]
    Unreadable {
        /// File name.
        file: String,
        /// The operating system's reason.
        reason: String,
    },
    /// A section or line does not follow the format.
    #[error("{at}: malformed mesh file: {reason}")]
    Malformed {
        /// Place of the problem.
        at: Location,
        /// What was expected.
        reason: String,
    },
    /// A format version other than MSH 4.1 or 2.2 (ASCII).
    #[error("{at}: unsupported MSH format version {version}; only ASCII MSH 4.1 and 2.2 are read")]
    UnsupportedVersion {
        /// Place of the `$MeshFormat` line.
        at: Location,
        /// The version found.
        version: String,
    },
    /// A binary MSH file.
    #[error("{at}: binary MSH files are not supported; save the mesh as ASCII (gmsh option -bin 0 or Mesh.Binary = 0)")]
    Binary {
        /// Place of the `$MeshFormat` line.
        at: Location,
    },
    /// An element type the solver does not know where it matters (volume elements, faces).
    #[error("{at}: unsupported element type {gmsh_type} ({type_name}) for element {element_id} {context}")]
    UnsupportedElementType {
        /// Place of the element.
        at: Location,
        /// Gmsh element type number.
        gmsh_type: u32,
        /// Its name in words.
        type_name: String,
        /// Element id.
        element_id: u64,
        /// Where it was found, e.g. `in physical volume 'rockfill'`.
        context: String,
    },
    /// A node id given twice.
    #[error("{at}: duplicate node id {node_id}")]
    DuplicateNode {
        /// Place of the second definition.
        at: Location,
        /// Node id.
        node_id: u64,
    },
    /// An element id given twice.
    #[error("{at}: duplicate element id {element_id}")]
    DuplicateElement {
        /// Place of the second definition.
        at: Location,
        /// Element id.
        element_id: u64,
    },
    /// An element refers to a node that is not defined.
    #[error("{at}: element {element_id} references unknown node {node_id}")]
    UnknownNode {
        /// Place of the element.
        at: Location,
        /// Element id.
        element_id: u64,
        /// The unknown node id.
        node_id: u64,
    },
    /// A hexahedron that belongs to no physical volume (so to no block).
    #[error("{at}: hexahedron {element_id} is in no physical volume; every volume element must belong to a named physical volume (element block)")]
    ElementWithoutBlock {
        /// Place of the element.
        at: Location,
        /// Element id.
        element_id: u64,
    },
    /// A volume element in two physical volumes.
    #[error("{at}: element {element_id} is in two physical volumes, '{first}' and '{second}'")]
    AmbiguousBlock {
        /// Place of the element (or of its entity).
        at: Location,
        /// Element id.
        element_id: u64,
        /// First physical volume.
        first: String,
        /// Second physical volume.
        second: String,
    },
    /// A physical group without a name in `$PhysicalNames`.
    #[error("{at}: physical group (dimension {dim}, tag {tag}) has no name; name every physical group in the .geo file")]
    UnnamedPhysical {
        /// Place where the group is used.
        at: Location,
        /// Dimension of the group.
        dim: u8,
        /// Physical tag.
        tag: i64,
    },
    /// Negative (or zero) Jacobian at a corner or Gauss point.
    #[error("{at}: element {element_id} is inverted: {detail}")]
    InvertedElement {
        /// Place of the element.
        at: Location,
        /// Element id.
        element_id: u64,
        /// Where the Jacobian determinant is not positive.
        detail: String,
    },
    /// Zero or near-zero volume, or a repeated node.
    #[error("{at}: element {element_id} is degenerate: {detail}")]
    DegenerateElement {
        /// Place of the element.
        at: Location,
        /// Element id.
        element_id: u64,
        /// What is degenerate.
        detail: String,
    },
    /// A quad of a physical surface that bounds no hexahedron.
    #[error("{at}: quadrangle {element_id} of physical surface '{set}' is not a face of any hexahedron")]
    UnmatchedFace {
        /// Place of the quad.
        at: Location,
        /// Element id of the quad.
        element_id: u64,
        /// Physical surface name.
        set: String,
    },
    /// An inconsistent in-memory mesh (indices out of range, unsorted sets, wrong face nodes).
    #[error("{at}: inconsistent mesh: {reason}")]
    Inconsistent {
        /// The mesh.
        at: Location,
        /// What is wrong.
        reason: String,
    },
    /// Generator parameters that cannot give a mesh.
    #[error("mesh generator: {field}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        field: String,
        /// Why it is rejected.
        reason: String,
    },
}
