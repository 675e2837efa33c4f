//! The part of the mesh one rank owns and the paths of the mesh datasets.

use crate::io::error::IoError;
use crate::mesh::Mesh;

/// The part of the mesh one rank owns, in global input-order indices.
///
/// Every node and every element must be owned by exactly one rank. Connectivity uses global
/// 0-based node indices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OwnedMesh {
    /// Number of nodes of the whole mesh.
    pub n_nodes: u64,
    /// Number of elements of the whole mesh.
    pub n_elements: u64,
    /// Global indices of the owned nodes; node fields are given in this order.
    pub nodes: Vec<u32>,
    /// Coordinates (m) of the owned nodes.
    pub coords: Vec<[f64; 3]>,
    /// Input ids of the owned nodes.
    pub node_ids: Vec<u64>,
    /// Global indices of the owned elements; element fields are given in this order.
    pub elements: Vec<u32>,
    /// Hex8 connectivity of the owned elements (global node indices, Gmsh node order).
    pub connectivity: Vec<[u32; 8]>,
    /// Input ids of the owned elements.
    pub element_ids: Vec<u64>,
    /// Block index of each owned element.
    pub element_blocks: Vec<u32>,
    /// Names of all blocks (the same on every rank).
    pub block_names: Vec<String>,
}

impl OwnedMesh {
    /// Extracts the owned part of a global mesh held by this rank.
    pub fn from_mesh(mesh: &Mesh, nodes: Vec<u32>, elements: Vec<u32>) -> Self {
        OwnedMesh {
            n_nodes: mesh.num_nodes() as u64,
            n_elements: mesh.elements.len() as u64,
            coords: nodes.iter().map(|&n| mesh.coords[n as usize]).collect(),
            node_ids: nodes.iter().map(|&n| mesh.node_ids[n as usize]).collect(),
            connectivity: elements
                .iter()
                .map(|&e| mesh.elements[e as usize].nodes)
                .collect(),
            element_ids: elements.iter().map(|&e| mesh.elements[e as usize].id).collect(),
            element_blocks: elements
                .iter()
                .map(|&e| mesh.elements[e as usize].block)
                .collect(),
            block_names: mesh.blocks.iter().map(|b| b.name.clone()).collect(),
            nodes,
            elements,
        }
    }

    /// The whole mesh owned by one rank.
    pub fn whole(mesh: &Mesh) -> Self {
        let nodes = (0..mesh.num_nodes() as u32).collect();
        let elements = (0..mesh.elements.len() as u32).collect();
        Self::from_mesh(mesh, nodes, elements)
    }

    pub(super) fn check(&self) -> Result<(), IoError> {
        let n = self.nodes.len();
        let e = self.elements.len();
        let lens = [
            ("coords", self.coords.len(), n),
            ("node_ids", self.node_ids.len(), n),
            ("connectivity", self.connectivity.len(), e),
            ("element_ids", self.element_ids.len(), e),
            ("element_blocks", self.element_blocks.len(), e),
        ];
        for (name, got, want) in lens {
            if got != want {
                return Err(IoError::Usage(format!(
                    "owned mesh: {name} has {got} rows, expected {want}"
                )));
            }
        }
        for (k, conn) in self.connectivity.iter().enumerate() {
            if let Some(bad) = conn.iter().find(|&&v| u64::from(v) >= self.n_nodes) {
                return Err(IoError::Usage(format!(
                    "owned mesh: element {} refers to node index {bad} of {}",
                    self.element_ids[k], self.n_nodes
                )));
            }
        }
        if let Some(b) = self
            .element_blocks
            .iter()
            .find(|&&b| b as usize >= self.block_names.len())
        {
            return Err(IoError::Usage(format!(
                "owned mesh: block index {b} but only {} block names",
                self.block_names.len()
            )));
        }
        Ok(())
    }
}

/// Dataset path of the node coordinates.
pub const COORDINATES: &str = "/mesh/coordinates";
/// Dataset path of the connectivity.
pub const TOPOLOGY: &str = "/mesh/topology";
/// Dataset path of the node input ids.
pub const NODE_IDS: &str = "/mesh/node_ids";
/// Dataset path of the element input ids.
pub const ELEMENT_IDS: &str = "/mesh/element_ids";
/// Dataset path of the element block indices.
pub const ELEMENT_BLOCK: &str = "/mesh/element_block";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn owned_mesh_checks_lengths_and_references() {
        let mut m = OwnedMesh {
            n_nodes: 8,
            n_elements: 1,
            nodes: (0..8).collect(),
            coords: vec![[0.0; 3]; 8],
            node_ids: (1..=8).collect(),
            elements: vec![0],
            connectivity: vec![[0, 1, 2, 3, 4, 5, 6, 7]],
            element_ids: vec![1],
            element_blocks: vec![0],
            block_names: vec!["fill".to_string()],
        };
        assert!(m.check().is_ok());
        m.connectivity[0][3] = 8;
        assert!(m.check().unwrap_err().to_string().contains("node index 8"));
        m.connectivity[0][3] = 3;
        m.coords.pop();
        assert!(m.check().unwrap_err().to_string().contains("coords"));
        m.coords.push([0.0; 3]);
        m.element_blocks[0] = 1;
        assert!(m.check().is_err());
    }
}
