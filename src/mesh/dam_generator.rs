//! Generator of a complete concrete-faced rockfill dam model in a trapezoidal canyon: zoned
//! rockfill body, face slab, slab–cushion interface, vertical and perimetric joints, and the
//! construction/impoundment schedule of the seed paper (`seed/summary.md` §2.1,
//! `spec/seismic.md` §5, `spec/models.md` §5–§6).
//!
//! # Coordinates
//! x along the river (downstream positive), y along the dam axis, z up. **z is the absolute
//! elevation** (m a.s.l.), so the reservoir levels of the schedule and of a scene's
//! `hydrostatic` loads are elevations too (`level: 2840`). x = 0 at the upstream toe of the
//! rockfill (the cushion face at the base), y = 0 at the centre of the valley bottom.
//!
//! ```text
//!  section (x–z)                                      valley (y–z, looking downstream)
//!            slab (outside the cushion face)           y_l(z)                    y_r(z)
//!        crest_width                                    \  fan  |  central  |  fan  /
//!      |<-->|                                            \ cols |   cols    | cols /
//!     /|c|t|  rockfill  \                                 \     | (vertical)|     /
//!    / |u|r|             \   1:m_d                         \    |           |    /
//!   /  |s|a|              \                                 \___|___________|___/
//!  x=0 (base_elevation)                                        -b/2         b/2
//! ```
//!
//! # Mesh
//! * **Rockfill body**: hexahedra on a structured (x, y, z) grid. Element layer `k` (one per
//!   fill step) lies between two elevations; the layer boundaries include the slab stage tops
//!   and the fill elevation at which slab stage I is cast, the remaining layers are spread
//!   over the height (largest remainder). Across the section: one element of cushion (constant
//!   horizontal width), one of transition, `rockfill_elements` of main rockfill between the
//!   transition and the downstream face. Along the axis the columns follow the canyon: the
//!   central columns are vertical planes y = const inside the valley bottom, the columns of
//!   the two abutment "fans" are spread evenly between the abutment y_l(z) (or y_r(z)) and the
//!   edge of the central part, so every element layer spans the valley width at its
//!   elevation. x depends only on (i, z) and y only on (j, z), hence
//!   det J = ∂x/∂ξ·∂y/∂η·∂z/∂ζ > 0 for every element.
//! * **Slab**: one hexahedron through the thickness on every upstream face quad, its inner
//!   face on the cushion face, its outer face offset along the outward normal by
//!   t(z) = t_crest + g·(z_crest − z) (seed: 0.30 m + 0.0035·H). Panels (strips between
//!   vertical joints) are `elements_per_panel` columns wide; each panel has its own nodes.
//! * **Slab–cushion interface** (`interface_S`): one zero-thickness [`ElementKind::Interface8`]
//!   per slab hex, face B (nodes 0–3) = the slab's inner face, face A (nodes 4–7) = the cushion
//!   nodes at the same places; orientation (1, 0, −m_u), from the slab into the dam.
//! * **Vertical joints** (`joint_vertical_S`): Interface8 between the side faces of adjacent
//!   panels, face B on the panel with the smaller y; orientation +y.
//! * **Perimetric joint** (`joint_perimetric_{bottom,left,right}_S`): Interface8 between the
//!   slab's lower end faces (the bottom row on the valley floor, the end columns on the
//!   abutments) and a **rigid plinth**: face A is a copy of the slab's end nodes, collected in
//!   the node set `plinth`, which a scene fixes (spec §6.2, gap G4). Orientations: down-slope
//!   (−m_u, 0, −1) at the bottom, −y on the left bank, +y on the right bank.
//!
//! Slab stage `S` (1-based) covers the element rows between the previous stage top and
//! `slab_stage_tops[S-1]`. The slab is continuous across the stage tops (no horizontal
//! construction joints).
//!
//! # Blocks, sets and numbering
//! Blocks: `fill_KKK_cushion`, `fill_KKK_transition`, `fill_KKK_rockfill` (KKK = 001 … from the
//! bottom), then per slab stage `slab_S`, `interface_S`, `joint_vertical_S`,
//! `joint_perimetric_bottom_S` (stage 1 only), `joint_perimetric_left_S`,
//! `joint_perimetric_right_S`; every interface/joint block carries its orientation. Node sets:
//! `foundation` (rockfill nodes on the base and on both abutments), `plinth`. Face set:
//! `slab_upstream` (outer slab faces, outward normal upstream; water pressure). Nodes: rockfill
//! grid (i fastest, then j, then k), slab nodes panel by panel, plinth nodes; elements: fill
//! (k, j, i), then per stage slab, interface, joints. Ids are index + 1. Same spec, same mesh.
//!
//! # Schedule
//! One fill stage per element layer (`fill_KKK`); slab stage 1 (`slab_1`: slab, interface and
//! joints of stage 1) right after the layer whose top is `slab_cast_elevation`; the other slab
//! stages after the last fill layer; then `impoundment_stages` stages with the reservoir at
//! z_base + (level − z_base)·n/N, n = 1 … N.
//!
//! # Simplifications (documented on purpose)
//! * The canyon is prismatic along the river (abutments are planes y = y_l(z), y_r(z) for every
//!   x); the foundation is rigid (fixed `foundation` set) and the plinth is rigid.
//! * Fan columns near the abutments are not vertical: their panels are narrower at the base
//!   than at the crest (the crest widths are near `panel_width`, the central panels have it
//!   exactly). Joints follow the mesh lines.
//! * Structured grid: elements of the main rockfill get thin near the crest (the section
//!   narrows to `crest_width − cushion_width − transition_width`), no degenerated elements.
//! * One element through the slab; the slab's outer face at the crest lies t·m/√(1+m²) above
//!   the crest elevation (the slab is offset normal to the face).
//! * No upstream blanket/ballast, no parapet wall, no secondary downstream rockfill zone.
//! * Fill layers have equal thickness within each elevation segment, so with 86 layers slab
//!   stage I is cast after layer 50 (the layer that ends at 2780 m), where the paper's
//!   (non-uniform) layers put it after step 54.
//! * Impoundment levels rise in equal increments; within a stage the solver interpolates the
//!   water force linearly between the two levels.

use super::dam_spec::{CfrdSpec, Layout, ZONES};
use super::dam_stages::{schedule, CfrdStage};
use crate::element::hex8::HEX8_FACES;
use crate::mesh::error::MeshError;
use crate::mesh::{Block, Element, ElementKind, Face, Mesh};
use std::collections::BTreeMap;

/// Local face of the slab hex that is its outer (upstream) face (`HEX8_FACES[2]`, ξ = −1).
const SLAB_OUTER_FACE: u8 = 2;

/// What [`cfrd_mesh`] returns besides the mesh: the schedule and a few derived numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct CfrdModel {
    /// The mesh.
    pub mesh: Mesh,
    /// Fill, slab and impoundment stages, in order.
    pub stages: Vec<CfrdStage>,
    /// Elevations of the element-layer boundaries (m), bottom to top (`fill_layers + 1`).
    pub layer_elevations: Vec<f64>,
    /// y of the panel boundaries (vertical joints and slab ends) at the crest (m).
    pub panel_edges_at_crest: Vec<f64>,
}

/// Builds the dam mesh and its construction/impoundment schedule (see the module docs).
/// Every element is checked ([`Mesh::validate`]) before the mesh is returned.
pub fn cfrd_mesh(spec: &CfrdSpec) -> Result<CfrdModel, MeshError> {
    let lay = spec.layout()?;
    let grid = Grid::new(spec, &lay);
    let mut b = Builder::default();
    grid.push_fill_nodes(&mut b.mesh);
    grid.push_slab_nodes(&mut b.mesh);
    grid.push_fill(&mut b);
    let stage_blocks: Vec<Vec<String>> = (lay.stage_rows.iter().enumerate())
        .map(|(s, &rows)| grid.push_slab_stage(&mut b, s + 1, rows))
        .collect();
    let mesh = grid.finish_sets(b)?;
    let stages = schedule(spec, &lay, &stage_blocks);
    let panel_edges_at_crest: Vec<f64> = (0..=grid.n_panels)
        .map(|p| grid.y_col(p * grid.e, spec.height))
        .collect();
    Ok(CfrdModel {
        mesh,
        stages,
        layer_elevations: lay.h.iter().map(|h| spec.base_elevation + h).collect(),
        panel_edges_at_crest,
    })
}

/// Counts, node numbering and node positions of the structured grid of a checked spec.
struct Grid<'a> {
    /// The spec.
    spec: &'a CfrdSpec,
    /// Its layout.
    lay: &'a Layout,
    /// Element layers.
    nz: usize,
    /// Elements across the main rockfill.
    nr: usize,
    /// Elements across the section (cushion, transition, main rockfill).
    nx: usize,
    /// Elements along the axis per panel.
    e: usize,
    /// Panels.
    n_panels: usize,
    /// Elements along the axis.
    ny: usize,
    /// Upstream slope.
    mu: f64,
    /// Downstream slope.
    md: f64,
    /// Width of the section at the base.
    base_width: f64,
    /// Columns of the left fan.
    nl: usize,
    /// Columns of the central part.
    nc: usize,
    /// Index of the first slab node (the number of rockfill grid nodes).
    slab_base: usize,
}

impl<'a> Grid<'a> {
    /// The grid of `spec` laid out as `lay`.
    fn new(spec: &'a CfrdSpec, lay: &'a Layout) -> Self {
        let nz = spec.fill_layers;
        let nr = spec.rockfill_elements;
        let nx = 2 + nr;
        let e = spec.elements_per_panel;
        let n_panels = lay.panels.iter().sum::<usize>();
        let ny = n_panels * e;
        let (mu, md) = (spec.upstream_slope, spec.downstream_slope);
        let base_width = (mu + md) * spec.height + spec.crest_width;
        let [nl, nc, _] = lay.panels.map(|p| p * e);
        Grid {
            spec,
            lay,
            nz,
            nr,
            nx,
            e,
            n_panels,
            ny,
            mu,
            md,
            base_width,
            nl,
            nc,
            slab_base: (nx + 1) * (ny + 1) * (nz + 1),
        }
    }

    /// y of the left abutment at height `h` above the base.
    fn y_left(&self, h: f64) -> f64 {
        -0.5 * self.spec.valley_bottom_width - self.lay.run[0] * h
    }

    /// y of the right abutment at height `h` above the base.
    fn y_right(&self, h: f64) -> f64 {
        0.5 * self.spec.valley_bottom_width + self.lay.run[1] * h
    }

    /// y of grid column `j` at height `h` above the base.
    fn y_col(&self, j: usize, h: f64) -> f64 {
        let (nl, nc, central) = (self.nl, self.nc, self.lay.central);
        if j <= nl {
            let a = self.y_left(h);
            a + (central[0] - a) * j as f64 / nl as f64
        } else if j <= nl + nc {
            central[0] + self.spec.panel_width * (j - nl) as f64 / self.e as f64
        } else {
            let b = self.y_right(h);
            central[1] + (b - central[1]) * (j - nl - nc) as f64 / (self.ny - nl - nc) as f64
        }
    }

    /// x of grid line `i` across the section at height `h` above the base.
    fn x_col(&self, i: usize, h: f64) -> f64 {
        let spec = self.spec;
        let x0 = self.mu * h;
        match i {
            0 => x0,
            1 => x0 + spec.cushion_width,
            _ => {
                let a = x0 + spec.cushion_width + spec.transition_width;
                let b = self.base_width - self.md * h;
                a + (b - a) * (i - 2) as f64 / self.nr as f64
            }
        }
    }

    /// Index of the rockfill grid node (i, j, k).
    fn fill_node(&self, i: usize, j: usize, k: usize) -> u32 {
        (i + (self.nx + 1) * (j + (self.ny + 1) * k)) as u32
    }

    /// Index of the slab node of panel `p`, local column `jj` ∈ 0..=e, row `k`, side 0 outer /
    /// 1 inner.
    fn slab_node(&self, p: usize, jj: usize, k: usize, side: usize) -> u32 {
        (self.slab_base + side + 2 * (jj + (self.e + 1) * (k + (self.nz + 1) * p))) as u32
    }

    /// A side face of panel `p` at local column `jj`, row `k`: outer/inner at k, then at k + 1.
    fn side(&self, p: usize, jj: usize, k: usize) -> [u32; 4] {
        [
            self.slab_node(p, jj, k, 0),
            self.slab_node(p, jj, k, 1),
            self.slab_node(p, jj, k + 1, 1),
            self.slab_node(p, jj, k + 1, 0),
        ]
    }

    /// Pushes the rockfill grid nodes (i fastest, then j, then k).
    fn push_fill_nodes(&self, mesh: &mut Mesh) {
        let zb = self.spec.base_elevation;
        for k in 0..=self.nz {
            let h = self.lay.h[k];
            for j in 0..=self.ny {
                let y = self.y_col(j, h);
                for i in 0..=self.nx {
                    mesh.coords.push([self.x_col(i, h), y, zb + h]);
                }
            }
        }
        debug_assert_eq!(mesh.coords.len(), self.slab_base);
    }

    /// Pushes the slab nodes panel by panel: the inner one on the cushion face, the outer one
    /// offset by the slab thickness along the outward normal.
    fn push_slab_nodes(&self, mesh: &mut Mesh) {
        let mu = self.mu;
        let norm = (1.0 + mu * mu).sqrt();
        let n_out = [-1.0 / norm, 0.0, mu / norm];
        for p in 0..self.n_panels {
            for k in 0..=self.nz {
                for jj in 0..=self.e {
                    let inner = mesh.coords[self.fill_node(0, p * self.e + jj, k) as usize];
                    let t = self.spec.slab_thickness(inner[2]);
                    let outer = [0, 1, 2].map(|c| inner[c] + t * n_out[c]);
                    mesh.coords.push(outer);
                    mesh.coords.push(inner);
                }
            }
        }
    }

    /// Adds the fill blocks (three zones per layer) and the fill hexahedra (k, j, i).
    fn push_fill(&self, b: &mut Builder) {
        for k in 0..self.nz {
            for zone in ZONES {
                b.add_block(format!("fill_{:03}_{zone}", k + 1), ElementKind::Hex8, None);
            }
        }
        for k in 0..self.nz {
            for j in 0..self.ny {
                for i in 0..self.nx {
                    let zone = i.min(2);
                    let nodes = [
                        self.fill_node(i, j, k),
                        self.fill_node(i + 1, j, k),
                        self.fill_node(i + 1, j + 1, k),
                        self.fill_node(i, j + 1, k),
                        self.fill_node(i, j, k + 1),
                        self.fill_node(i + 1, j, k + 1),
                        self.fill_node(i + 1, j + 1, k + 1),
                        self.fill_node(i, j + 1, k + 1),
                    ];
                    b.push(ElementKind::Hex8, nodes, (3 * k + zone) as u32);
                }
            }
        }
    }

    /// Adds slab stage `sn` (1-based) over the element rows `[k0, k1)`: slab, interface,
    /// vertical and perimetric joints; returns the names of its blocks.
    fn push_slab_stage(&self, b: &mut Builder, sn: usize, (k0, k1): (usize, usize)) -> Vec<String> {
        let mut names = vec![format!("slab_{sn}"), format!("interface_{sn}")];
        let slab_b = b.add_block(names[0].clone(), ElementKind::Hex8, None);
        let iface_b = b.add_block(
            names[1].clone(),
            ElementKind::Interface8,
            Some([1.0, 0.0, -self.mu]),
        );
        let slab_hexes = self.push_slab_hexes(b, slab_b, (k0, k1));
        self.push_slab_interface(b, iface_b, &slab_hexes);
        if self.n_panels > 1 {
            names.push(self.push_vertical_joints(b, sn, (k0, k1)));
        }
        let (e, last) = (self.e, self.n_panels - 1);
        if k0 == 0 {
            let faces = (0..self.n_panels)
                .flat_map(|p| (0..e).map(move |jj| (p, jj)))
                .map(|(p, jj)| {
                    [
                        self.slab_node(p, jj, 0, 0),
                        self.slab_node(p, jj, 0, 1),
                        self.slab_node(p, jj + 1, 0, 1),
                        self.slab_node(p, jj + 1, 0, 0),
                    ]
                })
                .collect();
            names.push(b.perimetric(sn, "bottom", [-self.mu, 0.0, -1.0], faces));
        }
        let left = (k0..k1).map(|k| self.side(0, 0, k)).collect();
        names.push(b.perimetric(sn, "left", [0.0, -1.0, 0.0], left));
        let right = (k0..k1).map(|k| self.side(last, e, k)).collect();
        names.push(b.perimetric(sn, "right", [0.0, 1.0, 0.0], right));
        names
    }

    /// Adds the slab hexahedra of rows `[k0, k1)` to block `slab_b` and their outer faces to
    /// the face set; returns their (panel, local column, row).
    fn push_slab_hexes(
        &self,
        b: &mut Builder,
        slab_b: u32,
        (k0, k1): (usize, usize),
    ) -> Vec<(usize, usize, usize)> {
        let mut slab_hexes = Vec::new();
        for p in 0..self.n_panels {
            for k in k0..k1 {
                for jj in 0..self.e {
                    let nodes = [
                        self.slab_node(p, jj, k, 0),
                        self.slab_node(p, jj, k, 1),
                        self.slab_node(p, jj + 1, k, 1),
                        self.slab_node(p, jj + 1, k, 0),
                        self.slab_node(p, jj, k + 1, 0),
                        self.slab_node(p, jj, k + 1, 1),
                        self.slab_node(p, jj + 1, k + 1, 1),
                        self.slab_node(p, jj + 1, k + 1, 0),
                    ];
                    b.slab_faces.push(Face {
                        element: b.mesh.elements.len() as u32,
                        local_face: SLAB_OUTER_FACE,
                        nodes: HEX8_FACES[SLAB_OUTER_FACE as usize].map(|a| nodes[a]),
                    });
                    b.push(ElementKind::Hex8, nodes, slab_b);
                    slab_hexes.push((p, jj, k));
                }
            }
        }
        slab_hexes
    }

    /// Adds the slab–cushion interface elements of `slab_hexes` to block `iface_b`: face B on
    /// the slab's inner face, face A on the cushion nodes.
    fn push_slab_interface(&self, b: &mut Builder, iface_b: u32, slab_hexes: &[(usize, usize, usize)]) {
        for &(p, jj, k) in slab_hexes {
            let j = p * self.e + jj;
            let nodes = [
                self.slab_node(p, jj, k, 1),
                self.slab_node(p, jj + 1, k, 1),
                self.slab_node(p, jj + 1, k + 1, 1),
                self.slab_node(p, jj, k + 1, 1),
                self.fill_node(0, j, k),
                self.fill_node(0, j + 1, k),
                self.fill_node(0, j + 1, k + 1),
                self.fill_node(0, j, k + 1),
            ];
            b.push(ElementKind::Interface8, nodes, iface_b);
        }
    }

    /// Adds the block `joint_vertical_{sn}` and its joints between adjacent panels over the
    /// rows `[k0, k1)`; returns the block's name.
    fn push_vertical_joints(&self, b: &mut Builder, sn: usize, (k0, k1): (usize, usize)) -> String {
        let name = format!("joint_vertical_{sn}");
        let block = b.add_block(name.clone(), ElementKind::Interface8, Some([0.0, 1.0, 0.0]));
        for p in 0..self.n_panels - 1 {
            for k in k0..k1 {
                let (fb, fa) = (self.side(p, self.e, k), self.side(p + 1, 0, k));
                let nodes = [fb[0], fb[1], fb[2], fb[3], fa[0], fa[1], fa[2], fa[3]];
                b.push(ElementKind::Interface8, nodes, block);
            }
        }
        name
    }

    /// Adds the node sets `foundation` and `plinth` and the face set `slab_upstream`, numbers
    /// the nodes and checks the mesh.
    fn finish_sets(&self, b: Builder) -> Result<Mesh, MeshError> {
        let Builder {
            mut mesh,
            plinth_of,
            slab_faces,
        } = b;
        let (nx, ny) = (self.nx, self.ny);
        let mut foundation = Vec::new();
        for k in 0..=self.nz {
            for j in 0..=ny {
                if k == 0 || j == 0 || j == ny {
                    foundation.extend((0..=nx).map(|i| self.fill_node(i, j, k)));
                }
            }
        }
        foundation.sort_unstable();
        let plinth_nodes: Vec<u32> = plinth_of
            .values()
            .copied()
            .collect::<std::collections::BTreeSet<u32>>()
            .into_iter()
            .collect();
        mesh.node_sets.insert("foundation".into(), foundation);
        mesh.node_sets.insert("plinth".into(), plinth_nodes);
        mesh.face_sets.insert("slab_upstream".into(), slab_faces);
        mesh.node_ids = (1..=mesh.coords.len() as u64).collect();
        mesh.validate()?;
        Ok(mesh)
    }
}

/// The mesh under construction, with the plinth copies of slab nodes and the outer slab faces.
#[derive(Default)]
struct Builder {
    /// The mesh so far.
    mesh: Mesh,
    /// Plinth node of each slab node on the perimetric joint.
    plinth_of: BTreeMap<u32, u32>,
    /// Outer faces of the slab hexahedra (the face set `slab_upstream`).
    slab_faces: Vec<Face>,
}

impl Builder {
    /// Adds a block; returns its index.
    fn add_block(&mut self, name: String, kind: ElementKind, orientation: Option<[f64; 3]>) -> u32 {
        self.mesh.blocks.push(Block {
            name,
            kind,
            orientation,
        });
        (self.mesh.blocks.len() - 1) as u32
    }

    /// Adds an element of `block`, its id the next one.
    fn push(&mut self, kind: ElementKind, nodes: [u32; 8], block: u32) {
        self.mesh.elements.push(Element {
            id: self.mesh.elements.len() as u64 + 1,
            kind,
            nodes,
            block,
        });
    }

    /// The plinth copy of slab node `n`, made at its first use.
    fn plinth(&mut self, n: u32) -> u32 {
        let mesh = &mut self.mesh;
        *self.plinth_of.entry(n).or_insert_with(|| {
            mesh.coords.push(mesh.coords[n as usize]);
            (mesh.coords.len() - 1) as u32
        })
    }

    /// Adds the block `joint_perimetric_{which}_{sn}` and a joint between each slab face of
    /// `faces` (face B) and its plinth copy (face A); returns the block's name.
    fn perimetric(&mut self, sn: usize, which: &str, orientation: [f64; 3], faces: Vec<[u32; 4]>) -> String {
        let name = format!("joint_perimetric_{which}_{sn}");
        let block = self.add_block(name.clone(), ElementKind::Interface8, Some(orientation));
        for fb in faces {
            let fa = fb.map(|n| self.plinth(n));
            let nodes = [fb[0], fb[1], fb[2], fb[3], fa[0], fa[1], fa[2], fa[3]];
            self.push(ElementKind::Interface8, nodes, block);
        }
        name
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8::{face_coords, quad_area_vector};
    use crate::element::interface8::{Interface8Geometry, InterfaceRule};
    use crate::element::interface_frame::FrameAxes;
    use std::collections::{BTreeSet, HashMap};

    /// The `mesh.cfrd` of a committed seed scene.
    fn scene_spec(resolution: &str) -> CfrdSpec {
        let path = format!(
            "{}/inputs/scenes/seed_{resolution}_hyperbolic.yaml",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(&path).expect("seed scene");
        let file = crate::scene::parse::parse(&text, &path).expect("parse");
        file.mesh.cfrd.expect("mesh.cfrd")
    }

    fn centroid(x: &[[f64; 3]]) -> [f64; 3] {
        [0, 1, 2].map(|c| x.iter().map(|p| p[c]).sum::<f64>() / x.len() as f64)
    }

    fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    fn block_elements<'a>(mesh: &'a Mesh, prefix: &'a str) -> impl Iterator<Item = usize> + 'a {
        (0..mesh.elements.len()).filter(move |&e| {
            mesh.blocks[mesh.elements[e].block as usize]
                .name
                .starts_with(prefix)
        })
    }

    #[test]
    fn seed_scene_meshes_validate_and_the_fine_one_matches_the_paper_size() {
        for res in ["coarse", "medium", "fine"] {
            let spec = scene_spec(res);
            let model = cfrd_mesh(&spec).expect("mesh");
            let mesh = &model.mesh;
            let count = |kind: ElementKind| mesh.elements.iter().filter(|e| e.kind == kind).count();
            eprintln!(
                "seed {res}: {} elements ({} hex8, {} interface8), {} nodes, {} blocks, {} stages",
                mesh.elements.len(),
                count(ElementKind::Hex8),
                count(ElementKind::Interface8),
                mesh.num_nodes(),
                mesh.blocks.len(),
                model.stages.len()
            );
            mesh.validate().expect("valid");
            // every block has elements and every element's kind is its block's
            let mut used = vec![0usize; mesh.blocks.len()];
            for el in &mesh.elements {
                used[el.block as usize] += 1;
                assert_eq!(el.kind, mesh.blocks[el.block as usize].kind);
            }
            assert!(used.iter().all(|&n| n > 0), "empty block");
            for b in &mesh.blocks {
                assert_eq!(
                    b.orientation.is_some(),
                    b.kind == ElementKind::Interface8,
                    "{}",
                    b.name
                );
            }
            if res == "fine" {
                let ratio = mesh.elements.len() as f64 / 74_521.0;
                assert!((ratio - 1.0).abs() <= 0.15, "{} elements", mesh.elements.len());
            }
        }
        let again = cfrd_mesh(&scene_spec("coarse")).expect("mesh");
        assert_eq!(
            again,
            cfrd_mesh(&scene_spec("coarse")).expect("mesh"),
            "deterministic"
        );
    }

    #[test]
    fn interface_normals_point_from_the_slab_into_the_dam() {
        for spec in [scene_spec("coarse"), scene_spec("medium")] {
            let model = cfrd_mesh(&spec).expect("mesh");
            let mesh = &model.mesh;
            let m = spec.upstream_slope;
            let into_dam = [1.0 / (1.0 + m * m).sqrt(), 0.0, -m / (1.0 + m * m).sqrt()];
            // the solid element on each side of every interface face, by its face nodes
            let mut owner: HashMap<BTreeSet<u32>, Vec<usize>> = HashMap::new();
            for (e, el) in mesh.elements.iter().enumerate() {
                if el.kind == ElementKind::Hex8 {
                    for f in HEX8_FACES {
                        owner
                            .entry(f.iter().map(|&a| el.nodes[a]).collect())
                            .or_default()
                            .push(e);
                    }
                }
            }
            let mut checked = 0;
            for (e, el) in mesh.elements.iter().enumerate() {
                if el.kind != ElementKind::Interface8 {
                    continue;
                }
                let block = &mesh.blocks[el.block as usize];
                let n_ref = block.orientation.expect("orientation");
                let geo = Interface8Geometry::new(
                    &mesh.element_coords(e),
                    &n_ref,
                    &FrameAxes::default(),
                    InterfaceRule::NewtonCotes,
                )
                .unwrap_or_else(|err| panic!("{}: element {}: {err}", block.name, el.id));
                assert!(mesh.zero_thickness(e), "element {} is not flat", el.id);
                let n: [f64; 3] = geo.frames[0].n.into();
                let mid = centroid(&geo.positions);
                // face B belongs to a slab hex, which lies on the −n side
                let face_b: BTreeSet<u32> = el.nodes[..4].iter().copied().collect();
                let slab = owner[&face_b][0];
                assert!(mesh.blocks[mesh.elements[slab].block as usize]
                    .name
                    .starts_with("slab_"));
                let c = centroid(&mesh.element_coords(slab));
                assert!(
                    dot(&[c[0] - mid[0], c[1] - mid[1], c[2] - mid[2]], &n) < 0.0,
                    "element {}",
                    el.id
                );
                // face A: the cushion (slab-cushion interface), the next panel (joints) or the plinth
                let face_a: BTreeSet<u32> = el.nodes[4..].iter().copied().collect();
                if block.name.starts_with("interface_") {
                    let err = (0..3).map(|i| (n[i] - into_dam[i]).abs()).fold(0.0, f64::max);
                    assert!(err < 1e-9, "element {}: normal {n:?}", el.id);
                    let cushion = owner[&face_a][0];
                    let name = &mesh.blocks[mesh.elements[cushion].block as usize].name;
                    assert!(name.ends_with("_cushion"), "{name}");
                    let c = centroid(&mesh.element_coords(cushion));
                    assert!(dot(&[c[0] - mid[0], c[1] - mid[1], c[2] - mid[2]], &n) > 0.0);
                } else if block.name.starts_with("joint_vertical_") {
                    assert!(n[1] > 0.8, "element {}: normal {n:?}", el.id);
                    let next = owner[&face_a][0];
                    assert!(mesh.blocks[mesh.elements[next].block as usize]
                        .name
                        .starts_with("slab_"));
                } else {
                    assert!(block.name.starts_with("joint_perimetric_"), "{}", block.name);
                    assert!(dot(&n, &n_ref) > 0.5 * dot(&n_ref, &n_ref).sqrt());
                    let plinth = &mesh.node_sets["plinth"];
                    assert!(el.nodes[4..].iter().all(|n| plinth.binary_search(n).is_ok()));
                    assert!(!owner.contains_key(&face_a), "plinth nodes belong to no solid");
                }
                checked += 1;
            }
            assert!(checked > 0);
        }
    }

    #[test]
    fn slab_thickness_is_030_at_the_crest_and_090_at_the_base() {
        let spec = scene_spec("medium");
        let mesh = cfrd_mesh(&spec).expect("mesh").mesh;
        let (zb, zc) = (spec.base_elevation, spec.crest_elevation());
        let (mut at_crest, mut at_base) = (Vec::new(), Vec::new());
        for e in block_elements(&mesh, "slab_") {
            let x = mesh.element_coords(e);
            // node 1 (inner) − node 0 (outer) at the bottom, node 5 − node 4 at the top
            for (outer, inner) in [(0, 1), (4, 5)] {
                let d = [0, 1, 2].map(|c| x[inner][c] - x[outer][c]);
                let t = dot(&d, &d).sqrt();
                if (x[inner][2] - zc).abs() < 1e-9 {
                    at_crest.push(t);
                }
                if (x[inner][2] - zb).abs() < 1e-9 {
                    at_base.push(t);
                }
            }
        }
        assert!(!at_crest.is_empty() && !at_base.is_empty());
        assert!(at_crest.iter().all(|t| (t - 0.30).abs() < 1e-12), "{at_crest:?}");
        assert!(at_base.iter().all(|t| (t - 0.8985).abs() < 1e-12), "{at_base:?}");
    }

    #[test]
    fn panels_have_the_requested_widths_and_joints_sit_on_their_edges() {
        for res in ["medium", "fine"] {
            let spec = scene_spec(res);
            let model = cfrd_mesh(&spec).expect("mesh");
            let edges = &model.panel_edges_at_crest;
            let widths: Vec<f64> = edges.windows(2).map(|w| w[1] - w[0]).collect();
            eprintln!("seed {res}: panel widths at the crest {widths:.2?}");
            // spec/seismic.md §5.2: vertical joints every 12-18 m
            assert!(widths.iter().all(|&w| (12.0..=18.0).contains(&w)), "{widths:?}");
            let central = widths
                .iter()
                .filter(|&&w| (w - spec.panel_width).abs() < 1e-9)
                .count();
            assert!(central >= 4, "{central} panels of exactly {} m", spec.panel_width);
            assert!((edges[edges.len() - 1] - edges[0] - spec.crest_length).abs() < 1e-9);
            // every vertical joint node at the crest sits on an inner panel edge
            let mesh = &model.mesh;
            let zc = spec.crest_elevation();
            let mut seen = BTreeSet::new();
            for e in block_elements(mesh, "joint_vertical_") {
                for x in mesh.element_coords(e) {
                    if (x[2] - zc).abs() < 1e-9 {
                        let k = edges[1..edges.len() - 1]
                            .iter()
                            .position(|y| (y - x[1]).abs() < 1e-9);
                        seen.insert(
                            k.unwrap_or_else(|| panic!("joint node at y = {} is off the panel edges", x[1])),
                        );
                    }
                }
            }
            assert_eq!(seen.len(), edges.len() - 2, "every inner panel edge has a joint");
        }
    }

    #[test]
    fn schedule_casts_the_slab_stages_and_impounds_as_in_the_seed() {
        let spec = scene_spec("fine");
        let model = cfrd_mesh(&spec).expect("mesh");
        let names: Vec<&str> = model.stages.iter().map(|s| s.name.as_str()).collect();
        let fills: Vec<usize> = (0..names.len())
            .filter(|&i| names[i].starts_with("fill_"))
            .collect();
        assert_eq!(fills.len(), 86);
        for (k, &i) in fills.iter().enumerate() {
            assert_eq!(names[i], format!("fill_{:03}", k + 1));
        }
        let pos = |n: &str| names.iter().position(|s| *s == n).expect(n);
        // slab stage 1 right after the fill stage whose layer top is 2780 m
        let s1 = pos("slab_1");
        let fill_before = s1 - 1;
        assert!(names[fill_before].starts_with("fill_"));
        let layer: usize = names[fill_before][5..].parse().expect("layer");
        assert!(
            (model.layer_elevations[layer] - 2780.0).abs() < 1e-9,
            "{}",
            model.layer_elevations[layer]
        );
        eprintln!("seed fine: slab stage I cast after fill stage {layer} of 86");
        let last_fill = *fills.last().expect("fills");
        assert!(pos("slab_2") > last_fill && pos("slab_3") == pos("slab_2") + 1);
        // slab blocks of stage 1 span the rows up to 2737 m
        let tops = &model.layer_elevations;
        assert!(
            tops.iter().any(|z| (z - 2737.0).abs() < 1e-9) && tops.iter().any(|z| (z - 2805.0).abs() < 1e-9)
        );
        for (s, top) in [(1, 2737.0), (2, 2805.0), (3, 2852.0)] {
            let b = model.mesh.block_index(&format!("slab_{s}")).expect("slab block");
            let zmax = model
                .mesh
                .elements
                .iter()
                .filter(|el| el.block == b)
                .flat_map(|el| [1, 2, 5, 6].map(|a| model.mesh.coords[el.nodes[a] as usize][2]))
                .fold(f64::MIN, f64::max);
            assert!(
                (zmax - top).abs() < 1e-9,
                "slab_{s}: top of the inner face {zmax}"
            );
            assert!(model.stages[pos(&format!("slab_{s}"))]
                .activate
                .contains(&format!("interface_{s}")));
        }
        // impoundment: after the slabs, rising to 2840 m
        let levels: Vec<f64> = model.stages.iter().filter_map(|s| s.water_level).collect();
        assert_eq!(levels.len(), spec.impoundment_stages);
        assert!(levels.windows(2).all(|w| w[1] > w[0]));
        assert!((levels[levels.len() - 1] - 2840.0).abs() < 1e-9);
        assert!(model.stages[pos("slab_3") + 1..]
            .iter()
            .all(|s| s.water_level.is_some()));
        // every block is placed exactly once
        let placed: Vec<&String> = model.stages.iter().flat_map(|s| &s.activate).collect();
        let unique: BTreeSet<&String> = placed.iter().copied().collect();
        assert_eq!(placed.len(), unique.len());
        assert_eq!(unique.len(), model.mesh.blocks.len());
    }

    #[test]
    fn interfaces_cover_the_slab_face_exactly_once() {
        let spec = scene_spec("medium");
        let mesh = cfrd_mesh(&spec).expect("mesh").mesh;
        let m = spec.upstream_slope;
        // the upstream face: a trapezoid of slope length H√(1+m²) between widths b and L
        let exact = 0.5 * (spec.valley_bottom_width + spec.crest_length) * spec.height * (1.0 + m * m).sqrt();
        let mut quads = BTreeSet::new();
        let mut area = 0.0;
        for e in block_elements(&mesh, "interface_") {
            let el = &mesh.elements[e];
            let geo = Interface8Geometry::new(
                &mesh.element_coords(e),
                &mesh.blocks[el.block as usize].orientation.expect("n_ref"),
                &FrameAxes::default(),
                InterfaceRule::NewtonCotes,
            )
            .expect("geometry");
            area += geo.area();
            assert!(
                quads.insert(el.nodes[..4].iter().copied().collect::<BTreeSet<u32>>()),
                "face twice"
            );
        }
        // the inner faces (local face 3, ξ = +1) of the slab hexes are exactly the faces B
        let mut slab_area = 0.0;
        let mut slab_quads = BTreeSet::new();
        for e in block_elements(&mesh, "slab_") {
            let x = mesh.element_coords(e);
            let a = quad_area_vector(&face_coords(&x, 3));
            slab_area += dot(&a, &a).sqrt();
            slab_quads.insert(
                HEX8_FACES[3]
                    .iter()
                    .map(|&a| mesh.elements[e].nodes[a])
                    .collect::<BTreeSet<u32>>(),
            );
        }
        assert_eq!(quads, slab_quads);
        assert!(
            (area - exact).abs() < 1e-9 * exact,
            "interface area {area} vs face {exact}"
        );
        assert!(
            (slab_area - exact).abs() < 1e-9 * exact,
            "slab face {slab_area} vs {exact}"
        );
        // water acts on the outer faces, one per slab hex
        assert_eq!(mesh.face_sets["slab_upstream"].len(), slab_quads.len());
    }

    #[test]
    fn asymmetric_narrow_valleys_give_valid_meshes() {
        for (b, share, w, e) in [(20.0, 0.3, 12.0, 1), (300.0, 0.8, 15.0, 3), (40.0, 0.5, 50.0, 2)] {
            let spec = CfrdSpec {
                valley_bottom_width: b,
                left_share: share,
                panel_width: w,
                elements_per_panel: e,
                fill_layers: 6,
                rockfill_elements: 2,
                ..CfrdSpec::default()
            };
            let model = cfrd_mesh(&spec).unwrap_or_else(|err| panic!("b {b}: {err}"));
            let edges = &model.panel_edges_at_crest;
            let left = -0.5 * b - share * (spec.crest_length - b);
            assert!((edges[0] - left).abs() < 1e-9, "{edges:?}");
        }
    }
}
