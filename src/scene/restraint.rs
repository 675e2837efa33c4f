//! Whether every placed body is held against rigid-body motion: a body (a connected set of
//! placed elements) whose fixed DOFs leave one of its six rigid-body motions free has a singular
//! stiffness, so the scene is refused before any solve, with the free motions named.
//!
//! The test, for every stage that places elements: the six rigid-body modes of a body
//! (translations along x, y, z and rotations about x, y, z, in coordinates centred on the mesh
//! and scaled by its size) restricted to the body's fixed DOFs must have rank 6, i.e. the 6×6
//! Gram matrix of those rows must be regular (smallest eigenvalue above 1e-9 of the largest).

use super::stages::Stage;
use crate::mesh::{Element, Mesh};
use nalgebra::{DMatrix, Matrix6, SymmetricEigen, Vector3, Vector6};
use std::collections::HashMap;

/// Relative size below which an eigenvalue (or singular value) counts as zero.
const RANK_TOL: f64 = 1e-9;

/// Checks every stage of `stages` (blocks placed cumulatively) against the fixed DOFs `fixed`
/// (node index, component, value; sorted by node). The error says which stage, which body (an
/// element id and its block) and which motions are free. Only the bodies a stage places or
/// joins are tested again, so the cost is linear in the elements and fixed DOFs.
pub fn check_restraint(mesh: &Mesh, stages: &[Stage], fixed: &[(u32, u8, f64)]) -> Result<(), String> {
    let mut elements_of_block = vec![Vec::new(); mesh.blocks.len()];
    for (e, el) in mesh.elements.iter().enumerate() {
        elements_of_block[el.block as usize].push(e);
    }
    let mut bodies = Bodies::new(mesh, fixed);
    for (k, stage) in stages.iter().enumerate() {
        let elements: Vec<usize> = stage
            .activate
            .iter()
            .flat_map(|&b| elements_of_block[b as usize].iter().copied())
            .collect();
        for root in bodies.place(&elements) {
            let free = free_motions(&bodies.gram[&root]);
            if !free.is_empty() {
                // every body this stage changed holds one of its elements
                let el = elements
                    .iter()
                    .map(|&e| &mesh.elements[e])
                    .find(|el| bodies.sets.find(el.nodes[0]) == root)
                    .expect("a body placed or joined by the stage");
                return Err(message(mesh, el, &stage.name, k, stages.len(), &free));
            }
        }
    }
    Ok(())
}

/// The bodies of the placed elements (disjoint sets of nodes) and the Gram matrix of the
/// rigid-body modes on each body's fixed DOFs (kept at the body's root node).
struct Bodies<'a> {
    mesh: &'a Mesh,
    fixed: &'a [(u32, u8, f64)],
    frame: Frame,
    sets: UnionFind,
    placed: Vec<bool>,
    gram: HashMap<u32, Matrix6<f64>>,
}

impl<'a> Bodies<'a> {
    fn new(mesh: &'a Mesh, fixed: &'a [(u32, u8, f64)]) -> Self {
        Bodies {
            mesh,
            fixed,
            frame: Frame::of(mesh),
            sets: UnionFind::new(mesh.num_nodes()),
            placed: vec![false; mesh.num_nodes()],
            gram: HashMap::new(),
        }
    }

    /// Places `elements`: joins their nodes into bodies, merges the Gram matrices of the bodies
    /// joined and adds the fixed rows of the nodes placed. Returns the roots of the bodies that
    /// changed.
    fn place(&mut self, elements: &[usize]) -> Vec<u32> {
        let mut old_roots = Vec::new();
        let mut new_nodes = Vec::new();
        for &e in elements {
            for &n in &self.mesh.elements[e].nodes {
                if self.placed[n as usize] {
                    old_roots.push(self.sets.find(n));
                } else {
                    self.placed[n as usize] = true;
                    new_nodes.push(n);
                }
            }
        }
        for &e in elements {
            let nodes = self.mesh.elements[e].nodes;
            for &n in &nodes[1..] {
                self.sets.union(nodes[0], n);
            }
        }
        let mut touched = Vec::new();
        for old in old_roots {
            let root = self.sets.find(old);
            if let Some(g) = self.gram.remove(&old) {
                *self.gram.entry(root).or_insert_with(Matrix6::zeros) += g;
            }
            touched.push(root);
        }
        for n in new_nodes {
            let root = self.sets.find(n);
            let rows = self.fixed_rows(n);
            *self.gram.entry(root).or_insert_with(Matrix6::zeros) += rows;
            touched.push(root);
        }
        touched.sort_unstable();
        touched.dedup();
        touched
    }

    /// Σ rowᵀ·row over the fixed components of node `n`.
    fn fixed_rows(&self, n: u32) -> Matrix6<f64> {
        let first = self.fixed.partition_point(|f| f.0 < n);
        let mut g = Matrix6::zeros();
        for &(_, c, _) in self.fixed[first..].iter().take_while(|f| f.0 == n) {
            let row = self.frame.mode_row(self.mesh.coords[n as usize], c as usize);
            g += row * row.transpose();
        }
        g
    }
}

/// The refusal: the stage, the body (by its element `el`) and its free motions.
fn message(mesh: &Mesh, el: &Element, stage: &str, k: usize, n_stages: usize, free: &[String]) -> String {
    let when = if n_stages > 1 {
        format!("in stage {} '{stage}', ", k + 1)
    } else {
        String::new()
    };
    format!(
        "{when}the body of placed elements that holds element {} (block '{}') is not restrained \
         against rigid-body motion: {} free; fix more displacement components of its nodes",
        el.id,
        mesh.blocks[el.block as usize].name,
        free.join(", ")
    )
}

/// Centre and size of the mesh, to scale the rotation modes.
struct Frame {
    centre: [f64; 3],
    size: f64,
}

impl Frame {
    fn of(mesh: &Mesh) -> Frame {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for x in &mesh.coords {
            for a in 0..3 {
                lo[a] = lo[a].min(x[a]);
                hi[a] = hi[a].max(x[a]);
            }
        }
        let size = (0..3).map(|a| (hi[a] - lo[a]).powi(2)).sum::<f64>().sqrt();
        Frame {
            centre: [0, 1, 2].map(|a| 0.5 * (lo[a] + hi[a])),
            size: if size > 0.0 { size } else { 1.0 },
        }
    }

    /// Component `c` of the six rigid-body modes at the point `x`.
    fn mode_row(&self, x: [f64; 3], c: usize) -> Vector6<f64> {
        let r = Vector3::from_fn(|a, _| (x[a] - self.centre[a]) / self.size);
        let mut row = Vector6::zeros();
        row[c] = 1.0;
        for axis in 0..3 {
            row[3 + axis] = Vector3::ith(axis, 1.0).cross(&r)[c];
        }
        row
    }
}

/// The rigid-body motions that the Gram matrix `g` of the fixed rows leaves free, in words.
fn free_motions(g: &Matrix6<f64>) -> Vec<String> {
    let eig = SymmetricEigen::new(*g);
    let largest = eig.eigenvalues.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let null: Vec<Vector6<f64>> = (0..6)
        .filter(|&i| largest == 0.0 || eig.eigenvalues[i] <= RANK_TOL * largest)
        .map(|i| eig.eigenvectors.column(i).into_owned())
        .collect();
    if null.is_empty() {
        return Vec::new();
    }
    if null.len() == 6 {
        return vec!["every translation and rotation (none of its displacements is fixed)".into()];
    }
    // null = [T; R] with orthonormal columns: the eigenvectors c of RᵀR with eigenvalue 0 give
    // the free translations T·c, the others the axes R·c of the free rotations
    let n = DMatrix::from_fn(6, null.len(), |i, j| null[j][i]);
    let (t, r) = (n.rows(0, 3).into_owned(), n.rows(3, 3).into_owned());
    let eig = (r.transpose() * &r).symmetric_eigen();
    let (mut translations, mut axes) = (Vec::new(), Vec::new());
    for (j, &lambda) in eig.eigenvalues.iter().enumerate() {
        let c = eig.eigenvectors.column(j);
        if lambda <= 1e-6 {
            translations.push(Vector3::from_iterator((&t * c).iter().copied()));
        } else {
            axes.push(Vector3::from_iterator((&r * c).iter().copied()).normalize());
        }
    }
    let mut out: Vec<String> = name_directions(&translations)
        .into_iter()
        .map(|d| format!("translation along {d}"))
        .collect();
    out.extend(
        name_directions(&axes)
            .into_iter()
            .map(|d| format!("rotation about an axis along {d}")),
    );
    out
}

/// Names of the directions of an orthonormal basis: the coordinate axes `x`, `y`, `z` when they
/// span the same space, else the basis vectors' components.
fn name_directions(basis: &[Vector3<f64>]) -> Vec<String> {
    let in_span = |e: &Vector3<f64>| basis.iter().map(|b| b.dot(e).powi(2)).sum::<f64>() > 1.0 - 1e-6;
    let axes: Vec<String> = (0..3)
        .filter(|&a| in_span(&Vector3::ith(a, 1.0)))
        .map(|a| ["x", "y", "z"][a].to_string())
        .collect();
    if axes.len() == basis.len() {
        return axes;
    }
    basis
        .iter()
        .map(|v| format!("({:.3}, {:.3}, {:.3})", v[0], v[1], v[2]))
        .collect()
}

/// Disjoint sets of node indices (path halving, union by size).
struct UnionFind {
    parent: Vec<u32>,
    size: Vec<u32>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n as u32).collect(),
            size: vec![1; n],
        }
    }

    fn find(&mut self, mut a: u32) -> u32 {
        while self.parent[a as usize] != a {
            let up = self.parent[self.parent[a as usize] as usize];
            self.parent[a as usize] = up;
            a = up;
        }
        a
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        let (big, small) = if self.size[ra as usize] >= self.size[rb as usize] {
            (ra, rb)
        } else {
            (rb, ra)
        };
        self.parent[small as usize] = big;
        self.size[big as usize] += self.size[small as usize];
    }
}
