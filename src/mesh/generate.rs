//! Structured hex8 mesh generators: a box (patch tests, columns, staged-construction tests) and a
//! dam-like trapezoidal prism (benchmarks and scaling runs up to millions of DOFs).
//!
//! Both number nodes with `i` (x) fastest, then `j` (y), then `k` (z), and elements the same
//! way, so the element layers `layer_1 … layer_k` (bottom to top) are contiguous. Node ids are
//! `index + 1`, element ids `index + 1`. Element node order is Gmsh's (`crate::element::hex8`),
//! with ξ along x (or along the stream), η along y and ζ along z, so `det J > 0`.

use crate::element::hex8::hex8_cell_nodes;
use crate::mesh::error::MeshError;
use crate::mesh::{Block, Element, ElementKind, Face, Mesh};
use std::collections::BTreeMap;

/// Most nodes of a generated mesh (`mesh.box`, `mesh.dam`, `mesh.cfrd`): 2^25, about 10^8
/// DOFs, checked before any memory is reserved.
pub const MAX_GENERATED_NODES: usize = 1 << 25;

/// Local face numbers (`crate::element::hex8::HEX8_FACES`) of the faces normal to the axes.
const FACE_ZMIN: u8 = 0;
const FACE_YMIN: u8 = 1;
const FACE_XMIN: u8 = 2;
const FACE_XMAX: u8 = 3;
const FACE_YMAX: u8 = 4;
const FACE_ZMAX: u8 = 5;

/// Parameters of [`box_mesh`] (also the scene's `mesh.box`; omitted keys take the defaults).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BoxSpec {
    /// Corner with the smallest coordinates (m).
    pub origin: [f64; 3],
    /// Edge lengths along x, y, z (m).
    pub size: [f64; 3],
    /// Number of elements along x, y, z; the mesh may have at most [`MAX_GENERATED_NODES`] nodes.
    pub divisions: [usize; 3],
    /// Number of horizontal element blocks `layer_1 … layer_k` (bottom to top), `1 ≤ k ≤ nz`.
    pub layers: usize,
    /// Random node displacement as a fraction of the cell size, in `[0, 0.2]`: each coordinate
    /// of a node moves by up to `jitter · h`, except the coordinates that keep it on the box
    /// boundary (boundary faces stay plane). Gives distorted elements for patch tests.
    pub jitter: f64,
    /// Seed of the jitter's pseudo-random sequence (same seed, same mesh).
    pub seed: u64,
}

impl Default for BoxSpec {
    /// The unit cube as one element, one layer, no jitter.
    fn default() -> Self {
        BoxSpec {
            origin: [0.0; 3],
            size: [1.0; 3],
            divisions: [1; 3],
            layers: 1,
            jitter: 0.0,
            seed: 1,
        }
    }
}

/// Parameters of [`dam_mesh`]: a trapezoidal dam section in the x–z plane extruded along y.
///
/// ```text
///  z                 crest_width
///  ^               |<--------->|
///  |    upstream  /|           |\  downstream         slopes 1:m (1 vertical, m horizontal)
///  |    face     / |           | \  face
///  |  1:m_u     /  height      |  \  1:m_d
///  |           /   |           |   \
///  +----------*----------------------*------> x (stream)
///            x=0     (base, z = 0)     x = m_u H + crest_width + m_d H
/// ```
/// The dam axis runs along y from 0 to `length`. Every horizontal row of elements has `nx`
/// elements across the section, so element widths shrink linearly from base to crest.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DamSpec {
    /// Dam height `H` (m).
    pub height: f64,
    /// Crest width (m), > 0.
    pub crest_width: f64,
    /// Upstream slope `m_u` (horizontal per vertical), ≥ 0.
    pub upstream_slope: f64,
    /// Downstream slope `m_d` (horizontal per vertical), ≥ 0.
    pub downstream_slope: f64,
    /// Extrusion length along the dam axis `L` (m).
    pub length: f64,
    /// Elements across the section (x), along the axis (y) and over the height (z); the mesh may
    /// have at most [`MAX_GENERATED_NODES`] nodes.
    pub divisions: [usize; 3],
    /// Number of horizontal element blocks `layer_1 … layer_k`, `1 ≤ k ≤ nz` (default 1).
    #[serde(default = "one_layer")]
    pub layers: usize,
}

fn one_layer() -> usize {
    1
}

impl DamSpec {
    /// A dam section with the seed dam's shape (`spec/seismic.md` §5.1: H = 171 m, slopes
    /// 1:1.4, crest 10 m), extruded over `length`, with the given divisions and layers.
    pub fn seed_like(length: f64, divisions: [usize; 3], layers: usize) -> Self {
        DamSpec {
            height: 171.0,
            crest_width: 10.0,
            upstream_slope: 1.4,
            downstream_slope: 1.4,
            length,
            divisions,
            layers,
        }
    }

    /// Width of the base (m): `m_u H + crest_width + m_d H`.
    pub fn base_width(&self) -> f64 {
        (self.upstream_slope + self.downstream_slope) * self.height + self.crest_width
    }

    /// Number of nodes of the mesh.
    pub fn num_nodes(&self) -> usize {
        let [nx, ny, nz] = self.divisions;
        (nx + 1) * (ny + 1) * (nz + 1)
    }

    /// Number of displacement DOFs (3 per node).
    pub fn num_dofs(&self) -> usize {
        3 * self.num_nodes()
    }

    /// Chooses the divisions for about `target_dofs` DOFs with elements of roughly equal size
    /// `h` along the mean section width, the axis and the height (keeps `layers ≤ nz`).
    pub fn with_target_dofs(mut self, target_dofs: usize) -> Result<Self, MeshError> {
        self.check_geometry()?;
        if target_dofs < 24 {
            return Err(invalid(
                "target_dofs",
                format!("{target_dofs} is below one element (24)"),
            ));
        }
        let mean_width = 0.5 * (self.base_width() + self.crest_width);
        let dims = [mean_width, self.length, self.height];
        let dofs = |h: f64| -> f64 {
            3.0 * dims
                .iter()
                .map(|d| (d / h).round().max(1.0) + 1.0)
                .product::<f64>()
        };
        // dofs(h) decreases with h: bisection on log h.
        let (mut lo, mut hi) = (1e-6 * dims[2], 1e3 * dims.iter().fold(0.0f64, |a, &d| a.max(d)));
        for _ in 0..200 {
            let mid = (lo * hi).sqrt();
            if dofs(mid) > target_dofs as f64 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let pick = if (dofs(lo) - target_dofs as f64).abs() < (dofs(hi) - target_dofs as f64).abs() {
            lo
        } else {
            hi
        };
        let n = dims.map(|d| ((d / pick).round() as usize).max(1));
        self.divisions = [n[0], n[1], n[2].max(self.layers)];
        Ok(self)
    }

    fn check_geometry(&self) -> Result<(), MeshError> {
        positive("height", self.height)?;
        positive("crest_width", self.crest_width)?;
        positive("length", self.length)?;
        non_negative("upstream_slope", self.upstream_slope)?;
        non_negative("downstream_slope", self.downstream_slope)?;
        if self.layers == 0 {
            return Err(invalid("layers", "must be at least 1".into()));
        }
        Ok(())
    }
}

fn invalid(field: &str, reason: String) -> MeshError {
    MeshError::InvalidParameter {
        field: field.into(),
        reason,
    }
}

/// `v` must be finite and > 0; the error names `field` (a YAML path).
pub(crate) fn positive(field: &str, v: f64) -> Result<(), MeshError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(field, format!("must be a positive number, got {v}")))
    }
}

/// `v` must be finite and ≥ 0; the error names `field` (a YAML path).
pub(crate) fn non_negative(field: &str, v: f64) -> Result<(), MeshError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(invalid(field, format!("must be a non-negative number, got {v}")))
    }
}

fn check_divisions(divisions: [usize; 3], layers: usize) -> Result<(), MeshError> {
    if divisions.contains(&0) {
        return Err(invalid(
            "divisions",
            format!("{divisions:?}: every division must be at least 1"),
        ));
    }
    if layers == 0 || layers > divisions[2] {
        return Err(invalid(
            "layers",
            format!("{layers} must lie in [1, nz = {}]", divisions[2]),
        ));
    }
    let nodes = divisions.iter().map(|&n| n as u128 + 1).product::<u128>();
    if nodes > MAX_GENERATED_NODES as u128 {
        return Err(invalid(
            "divisions",
            format!("{divisions:?} gives {nodes} nodes, more than the limit of {MAX_GENERATED_NODES}"),
        ));
    }
    Ok(())
}

/// Structured grid topology shared by both generators: elements, blocks and the sets on the
/// six sides `xmin, xmax, ymin, ymax, zmin, zmax` (renamed by the caller as needed).
struct Grid {
    n: [usize; 3],
}

impl Grid {
    fn node(&self, i: usize, j: usize, k: usize) -> u32 {
        (i + (self.n[0] + 1) * (j + (self.n[1] + 1) * k)) as u32
    }

    /// Elements in `i, j, k` order with layered blocks, and the empty mesh around them.
    fn topology(&self, layers: usize) -> Mesh {
        let [nx, ny, nz] = self.n;
        let mut elements = Vec::with_capacity(nx * ny * nz);
        for k in 0..nz {
            let block = (k * layers / nz) as u32;
            for j in 0..ny {
                for i in 0..nx {
                    let nodes = hex8_cell_nodes(i, j, k, |a, b, c| self.node(a, b, c));
                    elements.push(Element {
                        id: elements.len() as u64 + 1,
                        kind: ElementKind::Hex8,
                        nodes,
                        block,
                    });
                }
            }
        }
        let blocks = (1..=layers)
            .map(|l| Block {
                name: format!("layer_{l}"),
                kind: ElementKind::Hex8,
                orientation: None,
            })
            .collect();
        Mesh {
            elements,
            blocks,
            ..Mesh::default()
        }
    }

    /// Node indices with a fixed grid index `fixed` along `axis`, sorted.
    fn side_nodes(&self, axis: usize, fixed: usize) -> Vec<u32> {
        let [nx, ny, nz] = self.n;
        let mut set = Vec::new();
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    if [i, j, k][axis] == fixed {
                        set.push(self.node(i, j, k));
                    }
                }
            }
        }
        set
    }

    /// Faces on the side with grid index `fixed` along `axis` (0 or n), outward.
    fn side_faces(&self, mesh: &Mesh, axis: usize, at_max: bool) -> Vec<Face> {
        let [nx, ny, nz] = self.n;
        let local_face = match (axis, at_max) {
            (0, false) => FACE_XMIN,
            (0, true) => FACE_XMAX,
            (1, false) => FACE_YMIN,
            (1, true) => FACE_YMAX,
            (_, false) => FACE_ZMIN,
            (_, true) => FACE_ZMAX,
        };
        let fixed = if at_max { self.n[axis] - 1 } else { 0 };
        let local = crate::element::hex8::HEX8_FACES[local_face as usize];
        let mut faces = Vec::new();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    if [i, j, k][axis] == fixed {
                        let e = i + nx * (j + ny * k);
                        faces.push(Face {
                            element: e as u32,
                            local_face,
                            nodes: local.map(|a| mesh.elements[e].nodes[a]),
                        });
                    }
                }
            }
        }
        faces
    }

    /// Adds node and face sets `names[2·axis + side]` for the six sides.
    fn add_side_sets(&self, mesh: &mut Mesh, names: [&str; 6]) {
        let mut node_sets = BTreeMap::new();
        let mut face_sets = BTreeMap::new();
        for axis in 0..3 {
            for (side, at_max) in [(0, false), (1, true)] {
                let name = names[2 * axis + side].to_string();
                let fixed = if at_max { self.n[axis] } else { 0 };
                node_sets.insert(name.clone(), self.side_nodes(axis, fixed));
                face_sets.insert(name, self.side_faces(mesh, axis, at_max));
            }
        }
        mesh.node_sets = node_sets;
        mesh.face_sets = face_sets;
    }
}

/// SplitMix64 pseudo-random numbers (deterministic jitter without a dependency).
struct SplitMix64(u64);

impl SplitMix64 {
    /// Uniform in `[−1, 1)`.
    fn next_symmetric(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        2.0 * ((z >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }
}

/// A structured box of hex8 elements.
///
/// Blocks: `layer_1 … layer_k` by z (bottom first). Node sets and face sets (outward faces):
/// `xmin, xmax, ymin, ymax, zmin, zmax`. With `jitter > 0` the mesh is validated before it is
/// returned.
pub fn box_mesh(spec: &BoxSpec) -> Result<Mesh, MeshError> {
    check_divisions(spec.divisions, spec.layers)?;
    for (i, (&o, &s)) in spec.origin.iter().zip(&spec.size).enumerate() {
        positive(&format!("size[{i}]"), s)?;
        if !o.is_finite() {
            return Err(invalid(
                &format!("origin[{i}]"),
                format!("must be finite, got {o}"),
            ));
        }
    }
    if !(0.0..=0.2).contains(&spec.jitter) {
        return Err(invalid(
            "jitter",
            format!("must lie in [0, 0.2], got {}", spec.jitter),
        ));
    }
    let grid = Grid { n: spec.divisions };
    let mut mesh = grid.topology(spec.layers);
    let [nx, ny, nz] = spec.divisions;
    let h = [0, 1, 2].map(|a| spec.size[a] / spec.divisions[a] as f64);
    let mut rng = SplitMix64(spec.seed);
    let num_nodes = (nx + 1) * (ny + 1) * (nz + 1);
    mesh.coords.reserve_exact(num_nodes);
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let idx = [i, j, k];
                let mut p = [0.0; 3];
                for a in 0..3 {
                    p[a] = spec.origin[a] + idx[a] as f64 * h[a];
                    if spec.jitter > 0.0 && idx[a] > 0 && idx[a] < spec.divisions[a] {
                        p[a] += spec.jitter * h[a] * rng.next_symmetric();
                    }
                }
                mesh.coords.push(p);
            }
        }
    }
    mesh.node_ids = (1..=num_nodes as u64).collect();
    grid.add_side_sets(&mut mesh, ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]);
    if spec.jitter > 0.0 {
        mesh.validate()?;
    }
    Ok(mesh)
}

/// A dam-like hex8 mesh (see [`DamSpec`]).
///
/// Blocks `layer_1 … layer_k` by height. Node sets and face sets (outward faces):
/// `upstream` (inclined upstream face, outward normal `(−1, 0, m_u)/√(1 + m_u²)`),
/// `downstream` (`(1, 0, m_d)/√(1 + m_d²)`), `base` (z = 0, foundation contact), `crest`
/// (z = H), `ymin` and `ymax` (the two ends of the extrusion, e.g. abutment contacts).
///
/// Valid (`det J > 0`) for every admissible spec: in each row the section width is positive at
/// both levels and `z` depends on ζ only, so `det J = (∂x/∂ξ)(∂y/∂η)(∂z/∂ζ) > 0`. Cost is linear
/// in the size, without validation (call [`Mesh::validate`] if needed).
pub fn dam_mesh(spec: &DamSpec) -> Result<Mesh, MeshError> {
    spec.check_geometry()?;
    check_divisions(spec.divisions, spec.layers)?;
    let grid = Grid { n: spec.divisions };
    let mut mesh = grid.topology(spec.layers);
    let [nx, ny, nz] = spec.divisions;
    let base = spec.base_width();
    let num_nodes = spec.num_nodes();
    mesh.coords.reserve_exact(num_nodes);
    for k in 0..=nz {
        let z = spec.height * k as f64 / nz as f64;
        let x_left = spec.upstream_slope * z;
        let x_right = base - spec.downstream_slope * z;
        for j in 0..=ny {
            let y = spec.length * j as f64 / ny as f64;
            for i in 0..=nx {
                let s = i as f64 / nx as f64;
                mesh.coords.push([x_left + (x_right - x_left) * s, y, z]);
            }
        }
    }
    mesh.node_ids = (1..=num_nodes as u64).collect();
    grid.add_side_sets(
        &mut mesh,
        ["upstream", "downstream", "ymin", "ymax", "base", "crest"],
    );
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8::{face_coords, quad_area_vector, volume};

    fn total_volume(mesh: &Mesh) -> f64 {
        (0..mesh.elements.len())
            .map(|e| volume(&mesh.element_coords(e)))
            .sum()
    }

    fn centroid(mesh: &Mesh, e: usize) -> [f64; 3] {
        let x = mesh.element_coords(e);
        [0, 1, 2].map(|i| x.iter().map(|p| p[i]).sum::<f64>() / 8.0)
    }

    /// Unit outward normal of a face and the centre of its nodes.
    fn face_normal(mesh: &Mesh, f: &Face) -> ([f64; 3], [f64; 3]) {
        let x = mesh.element_coords(f.element as usize);
        let xf = face_coords(&x, f.local_face as usize);
        let a = quad_area_vector(&xf);
        let n = a.iter().map(|v| v * v).sum::<f64>().sqrt();
        let c = [0, 1, 2].map(|i| xf.iter().map(|p| p[i]).sum::<f64>() / 4.0);
        (a.map(|v| v / n), c)
    }

    #[test]
    fn box_sizes_sets_and_layers() {
        let spec = BoxSpec {
            origin: [1.0, -2.0, 0.5],
            size: [3.0, 2.0, 4.0],
            divisions: [3, 2, 4],
            layers: 3,
            ..BoxSpec::default()
        };
        let mesh = box_mesh(&spec).expect("box");
        mesh.validate().expect("valid");
        assert_eq!(mesh.num_nodes(), 4 * 3 * 5);
        assert_eq!(mesh.elements.len(), 24);
        assert!((total_volume(&mesh) - 24.0).abs() < 1e-12);
        let names: Vec<&str> = mesh.blocks.iter().map(|b| b.name.as_str()).collect();
        assert_eq!(names, ["layer_1", "layer_2", "layer_3"]);
        // Layers are horizontal, ordered by z, each non-empty.
        let mut z_range = [[f64::MAX, f64::MIN]; 3];
        for (e, el) in mesh.elements.iter().enumerate() {
            let z = centroid(&mesh, e)[2];
            let r = &mut z_range[el.block as usize];
            r[0] = r[0].min(z);
            r[1] = r[1].max(z);
        }
        for l in 1..3 {
            assert!(
                z_range[l][0] > z_range[l - 1][1],
                "layer {l} below layer {}",
                l - 1
            );
        }
        let sides = [
            ("xmin", 0, 1.0),
            ("xmax", 0, 4.0),
            ("ymin", 1, -2.0),
            ("ymax", 1, 0.0),
        ];
        for (name, axis, value) in sides.into_iter().chain([("zmin", 2, 0.5), ("zmax", 2, 4.5)]) {
            let nodes = &mesh.node_sets[name];
            let expect = (0..3)
                .filter(|&a| a != axis)
                .map(|a| spec.divisions[a] + 1)
                .product::<usize>();
            assert_eq!(nodes.len(), expect, "{name}");
            assert!(nodes
                .iter()
                .all(|&n| (mesh.coords[n as usize][axis] - value).abs() < 1e-12));
            let faces = &mesh.face_sets[name];
            let area: f64 = faces
                .iter()
                .map(|f| {
                    let x = mesh.element_coords(f.element as usize);
                    quad_area_vector(&face_coords(&x, f.local_face as usize))[axis]
                })
                .sum();
            let side_area: f64 = (0..3).filter(|&a| a != axis).map(|a| spec.size[a]).product();
            let sign = if name.ends_with("min") { -1.0 } else { 1.0 };
            assert!(
                (area - sign * side_area).abs() < 1e-12,
                "{name}: area vector {area}"
            );
        }
    }

    #[test]
    fn jittered_box_is_valid_distorted_and_keeps_plane_sides() {
        let spec = BoxSpec {
            divisions: [4, 3, 5],
            size: [2.0, 1.5, 2.5],
            layers: 5,
            jitter: 0.2,
            seed: 42,
            ..BoxSpec::default()
        };
        let mesh = box_mesh(&spec).expect("jittered box");
        mesh.validate().expect("valid");
        assert!(
            (total_volume(&mesh) - 7.5).abs() < 1e-12,
            "volume {}",
            total_volume(&mesh)
        );
        let regular = box_mesh(&BoxSpec {
            jitter: 0.0,
            ..spec.clone()
        })
        .expect("box");
        let moved = mesh
            .coords
            .iter()
            .zip(&regular.coords)
            .filter(|(a, b)| a != b)
            .count();
        assert!(moved > mesh.num_nodes() / 2, "only {moved} nodes moved");
        let again = box_mesh(&spec).expect("box");
        assert_eq!(again, mesh, "same seed, same mesh");
    }

    #[test]
    fn generator_parameters_are_checked() {
        let bad = [
            BoxSpec {
                divisions: [0, 1, 1],
                ..BoxSpec::default()
            },
            BoxSpec {
                layers: 2,
                ..BoxSpec::default()
            },
            BoxSpec {
                jitter: 0.3,
                ..BoxSpec::default()
            },
            BoxSpec {
                size: [1.0, -1.0, 1.0],
                ..BoxSpec::default()
            },
        ];
        let fields = ["divisions", "layers", "jitter", "size[1]"];
        for (spec, field) in bad.iter().zip(fields) {
            let err = box_mesh(spec).expect_err("invalid spec");
            assert!(err.to_string().contains(field), "{err}");
        }
        let dam = DamSpec {
            crest_width: 0.0,
            ..DamSpec::seed_like(50.0, [2, 2, 2], 1)
        };
        assert!(dam_mesh(&dam)
            .expect_err("zero crest")
            .to_string()
            .contains("crest_width"));
    }

    #[test]
    fn dam_is_valid_for_a_range_of_shapes() {
        for (h, c, mu, md, l) in [
            (171.0, 10.0, 1.4, 1.4, 355.0),
            (30.0, 0.5, 3.0, 0.0, 5.0),
            (10.0, 40.0, 0.0, 0.0, 1.0),
            (100.0, 0.01, 2.5, 1.8, 200.0),
        ] {
            for divisions in [[1, 1, 1], [3, 2, 7], [8, 1, 3]] {
                let spec = DamSpec {
                    height: h,
                    crest_width: c,
                    upstream_slope: mu,
                    downstream_slope: md,
                    length: l,
                    divisions,
                    layers: divisions[2].min(3),
                };
                let mesh = dam_mesh(&spec).expect("dam");
                mesh.validate().unwrap_or_else(|e| panic!("{spec:?}: {e}"));
                let v = 0.5 * (spec.base_width() + c) * h * l;
                assert!((total_volume(&mesh) - v).abs() < 1e-10 * v, "{spec:?}");
                assert_eq!(mesh.num_nodes() * 3, spec.num_dofs());
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig {
            cases: 64,
            failure_persistence: crate::test_support::proptest_persistence(),
            ..proptest::prelude::ProptestConfig::default()
        })]

        /// Any admissible dam shape and division gives valid elements and the exact volume.
        #[test]
        fn dam_is_valid_for_random_parameters(
            height in 0.5f64..300.0,
            crest in 1e-3f64..50.0,
            m_u in 0.0f64..4.0,
            m_d in 0.0f64..4.0,
            length in 0.1f64..500.0,
            nx in 1usize..9,
            ny in 1usize..4,
            nz in 1usize..9,
        ) {
            let spec = DamSpec {
                height,
                crest_width: crest,
                upstream_slope: m_u,
                downstream_slope: m_d,
                length,
                divisions: [nx, ny, nz],
                layers: nz.min(4),
            };
            let mesh = dam_mesh(&spec).expect("dam");
            proptest::prop_assert!(mesh.validate().is_ok(), "{:?}", mesh.validate());
            let v = 0.5 * (spec.base_width() + crest) * height * length;
            proptest::prop_assert!((total_volume(&mesh) - v).abs() < 1e-10 * v);
        }

        /// Jitter up to its bound keeps every element valid.
        #[test]
        fn jittered_box_is_valid_for_random_seeds(seed in 0u64..u64::MAX, jitter in 0.0f64..=0.2) {
            let spec = BoxSpec { divisions: [3, 3, 3], jitter, seed, ..BoxSpec::default() };
            let mesh = box_mesh(&spec);
            proptest::prop_assert!(mesh.is_ok(), "{:?}", mesh.err());
        }
    }

    #[test]
    fn dam_sets_and_outward_normals() {
        let spec = DamSpec::seed_like(60.0, [6, 3, 5], 5);
        let mesh = dam_mesh(&spec).expect("dam");
        let m = spec.upstream_slope;
        let up_n = [-1.0 / (1.0 + m * m).sqrt(), 0.0, m / (1.0 + m * m).sqrt()];
        let down_n = [-up_n[0], 0.0, up_n[2]];
        for (name, normal, count) in [
            ("upstream", up_n, 15),
            ("downstream", down_n, 15),
            ("base", [0.0, 0.0, -1.0], 18),
            ("crest", [0.0, 0.0, 1.0], 18),
            ("ymin", [0.0, -1.0, 0.0], 30),
            ("ymax", [0.0, 1.0, 0.0], 30),
        ] {
            let faces = &mesh.face_sets[name];
            assert_eq!(faces.len(), count, "{name}");
            for f in faces {
                let (n, c) = face_normal(&mesh, f);
                let err = (0..3).map(|i| (n[i] - normal[i]).abs()).fold(0.0, f64::max);
                assert!(err < 1e-12, "{name}: normal {n:?} vs {normal:?}");
                // Outward: the face centre lies beyond the element centroid along n.
                let g = centroid(&mesh, f.element as usize);
                assert!((0..3).map(|i| (c[i] - g[i]) * n[i]).sum::<f64>() > 0.0);
            }
        }
        let base = &mesh.node_sets["base"];
        assert_eq!(base.len(), 7 * 4);
        assert!(base.iter().all(|&n| mesh.coords[n as usize][2] == 0.0));
        for &n in &mesh.node_sets["upstream"] {
            let p = mesh.coords[n as usize];
            assert!(
                (p[0] - m * p[2]).abs() < 1e-9,
                "upstream node off the face: {p:?}"
            );
        }
        assert_eq!(mesh.blocks.len(), 5);
        mesh.validate().expect("valid");
    }

    #[test]
    fn dam_target_dofs_is_met_within_ten_percent() {
        for target in [3_000, 100_000, 1_000_000, 5_000_000] {
            let spec = DamSpec::seed_like(355.0, [1, 1, 1], 4)
                .with_target_dofs(target)
                .expect("spec");
            let dofs = spec.num_dofs() as f64;
            assert!(
                (dofs / target as f64 - 1.0).abs() < 0.1,
                "target {target}: {dofs} ({:?})",
                spec.divisions
            );
            assert!(spec.divisions[2] >= 4);
        }
    }

    #[test]
    fn dam_million_dofs_is_built_quickly() {
        let spec = DamSpec::seed_like(355.0, [1, 1, 1], 10)
            .with_target_dofs(1_000_000)
            .expect("spec");
        let start = std::time::Instant::now();
        let mesh = dam_mesh(&spec).expect("dam");
        let secs = start.elapsed().as_secs_f64();
        eprintln!(
            "dam mesh {:?}: {} DOFs, {} elements in {secs:.3} s",
            spec.divisions,
            spec.num_dofs(),
            mesh.elements.len()
        );
        assert_eq!(mesh.num_nodes() * 3, spec.num_dofs());
        assert!(secs < 3.0, "{secs} s for {} DOFs", spec.num_dofs());
    }
}
