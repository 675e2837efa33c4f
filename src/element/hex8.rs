//! The 8-node trilinear hexahedron (Gmsh type 5): geometry, B matrix, strains, internal force,
//! stiffness, gravity load, mass and face pressure load.
//!
//! # Numbering (Gmsh order)
//!
//! ```text
//!                ζ
//!                ^
//!                |
//!                7 ----------- 6
//!               /|            /|            node  (ξ,  η,  ζ)
//!              / |           / |             0    (−1, −1, −1)
//!             4 ----------- 5  |             1    (+1, −1, −1)
//!             |  |          |  |             2    (+1, +1, −1)
//!             |  3 ---------|- 2             3    (−1, +1, −1)
//!             | /           | /              4    (−1, −1, +1)
//!             |/            |/               5    (+1, −1, +1)
//!             0 ----------- 1  ---> ξ        6    (+1, +1, +1)
//!                                            7    (−1, +1, +1)
//!   η points from 0 to 3 (into the page). x = Σ N_a x_a maps ξ, η, ζ to the element.
//!
//!   face  plane    nodes (right-hand normal points OUT of the element)
//!    0    ζ = −1   0 3 2 1
//!    1    η = −1   0 1 5 4
//!    2    ξ = −1   0 4 7 3
//!    3    ξ = +1   1 2 6 5
//!    4    η = +1   2 3 7 6
//!    5    ζ = +1   4 5 6 7
//! ```
//!
//! The face order is Gmsh's. Gauss point `a` of the 2×2×2 rule is the one nearest to node `a`
//! ([`crate::element::quadrature::HEX_GAUSS_2X2X2`]). Element DOFs are ordered node by node,
//! `[u0x, u0y, u0z, u1x, …, u7z]`; strains and stresses use the Voigt order
//! `[xx, yy, zz, xy, yz, zx]` with engineering shear ([`crate::tensor`]).
//!
//! The kernels allocate nothing: they work on fixed-size arrays and nalgebra static matrices.
//! They are standard displacement-based small-strain kernels; the model spec
//! (`spec/models.md`) gives no equation for them, so the weak forms are written above each one.

use crate::element::quadrature::{HEX_GAUSS_2X2X2, HEX_GAUSS_3X3X3, HEX_GAUSS_POINTS, QUAD_GAUSS_2X2};
use crate::element::shape::{hex8_shape, hex8_shape_derivatives, quad4_shape, quad4_shape_derivatives};
use crate::tensor::{Strain6, Stress6, Tangent6};
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use thiserror::Error;

/// Node coordinates of one element (m), Gmsh node order.
pub type Coords8 = [[f64; 3]; 8];
/// Element DOF vector (displacements or forces), node by node.
pub type Vector24 = SVector<f64, 24>;
/// Element matrix (stiffness or mass).
pub type Matrix24 = SMatrix<f64, 24, 24>;
/// Strain–displacement matrix at one point, Voigt rows.
pub type BMatrix = SMatrix<f64, 6, 24>;

/// Local node lists of the 6 faces, ordered so that the right-hand normal points out of the element.
pub const HEX8_FACES: [[usize; 4]; 6] = [
    [0, 3, 2, 1],
    [0, 1, 5, 4],
    [0, 4, 7, 3],
    [1, 2, 6, 5],
    [2, 3, 7, 6],
    [4, 5, 6, 7],
];

/// Grid offsets `(di, dj, dk)` of the 8 nodes of a structured-grid cell, Gmsh order: node `a`
/// sits at `(r + 1) / 2`, `r` its corner in [`crate::element::shape::HEX8_REFERENCE_NODES`],
/// with `i` along ξ, `j` along η and `k` along ζ.
pub const HEX8_CELL_OFFSETS: [[usize; 3]; 8] = [
    [0, 0, 0],
    [1, 0, 0],
    [1, 1, 0],
    [0, 1, 0],
    [0, 0, 1],
    [1, 0, 1],
    [1, 1, 1],
    [0, 1, 1],
];

/// The 8 nodes, Gmsh order, of cell `(i, j, k)` of a structured grid whose grid point
/// `(i, j, k)` is the node `node(i, j, k)`; the nodes are asked for in that order.
pub fn hex8_cell_nodes<T>(i: usize, j: usize, k: usize, node: impl Fn(usize, usize, usize) -> T) -> [T; 8] {
    HEX8_CELL_OFFSETS.map(|[di, dj, dk]| node(i + di, j + dj, k + dk))
}

/// The element map is not invertible at a Gauss point (inverted or degenerate element).
#[derive(Debug, Clone, Copy, PartialEq, Error)]
#[error("non-positive Jacobian determinant {det_j:.6e} at Gauss point {gauss_point}")]
pub struct NonPositiveJacobian {
    /// Gauss point (0..8) where `det J ≤ 0`.
    pub gauss_point: usize,
    /// The determinant found there (m³).
    pub det_j: f64,
}

/// Jacobian `J_ij = ∂x_i/∂ξ_j = Σ_a x_a,i ∂N_a/∂ξ_j` of the map from the reference element.
pub fn jacobian(x: &Coords8, dn_dxi: &[[f64; 3]; 8]) -> Matrix3<f64> {
    let mut jac = Matrix3::zeros();
    for a in 0..8 {
        for i in 0..3 {
            for j in 0..3 {
                jac[(i, j)] += x[a][i] * dn_dxi[a][j];
            }
        }
    }
    jac
}

/// `det J` at the 8 corner nodes and at the 8 Gauss points of the 2×2×2 rule (used by the mesh
/// validation: an element is valid when all 16 are positive).
pub fn jacobian_determinants(x: &Coords8) -> ([f64; 8], [f64; 8]) {
    let corners = crate::element::shape::HEX8_REFERENCE_NODES
        .map(|r| jacobian(x, &hex8_shape_derivatives(&r)).determinant());
    let gauss = HEX_GAUSS_2X2X2.map(|q| jacobian(x, &hex8_shape_derivatives(&q.xi)).determinant());
    (corners, gauss)
}

/// Volume `V = ∫ dV = Σ_q w_q det J(ξ_q)` (exact with 2×2×2 points for any hex8).
pub fn volume(x: &Coords8) -> f64 {
    HEX_GAUSS_2X2X2
        .iter()
        .map(|q| q.weight * jacobian(x, &hex8_shape_derivatives(&q.xi)).determinant())
        .sum()
}

/// Strain–displacement matrix from the shape-function gradients `∂N_a/∂x_i` at one point.
///
/// ```text
/// ε = B u_e,  B = [B_0 … B_7],  B_a = ⎡ N,x  0    0   ⎤  εxx
///                                   ⎢ 0    N,y  0   ⎥  εyy
///                                   ⎢ 0    0    N,z ⎥  εzz
///                                   ⎢ N,y  N,x  0   ⎥  γxy
///                                   ⎢ 0    N,z  N,y ⎥  γyz
///                                   ⎣ N,z  0    N,x ⎦  γzx    (N = N_a)
/// ```
pub fn b_matrix(dn_dx: &[[f64; 3]; 8]) -> BMatrix {
    strain_operator(dn_dx)
}

/// The strain operator of any set of vector-valued shape functions with gradients `grads`
/// (3 columns per function, in the pattern of [`b_matrix`]); `C` = 3 × `grads.len()`.
pub fn strain_operator<const C: usize>(grads: &[[f64; 3]]) -> SMatrix<f64, 6, C> {
    let mut b = SMatrix::<f64, 6, C>::zeros();
    for (a, g) in grads.iter().enumerate() {
        let c = 3 * a;
        b[(0, c)] = g[0];
        b[(1, c + 1)] = g[1];
        b[(2, c + 2)] = g[2];
        b[(3, c)] = g[1];
        b[(3, c + 1)] = g[0];
        b[(4, c + 1)] = g[2];
        b[(4, c + 2)] = g[1];
        b[(5, c)] = g[2];
        b[(5, c + 2)] = g[0];
    }
    b
}

/// Geometry of one element at its 2×2×2 Gauss points: shape-function gradients and `w det J`.
/// Built once per element (and per geometry), then used by the strain, force and stiffness kernels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hex8Geometry {
    /// `∂N_a/∂x_i` at each Gauss point: `dn_dx[q][a][i]` (1/m).
    pub dn_dx: [[[f64; 3]; 8]; HEX_GAUSS_POINTS],
    /// `w_q det J(ξ_q)` at each Gauss point (m³); their sum is the element volume.
    pub det_j_w: [f64; HEX_GAUSS_POINTS],
}

impl Hex8Geometry {
    /// Gradients and weights at the Gauss points.
    ///
    /// ```text
    /// ∂N_a/∂x_i = Σ_j ∂N_a/∂ξ_j (J⁻¹)_ji
    /// ```
    /// Fails when `det J ≤ 0` at a Gauss point.
    pub fn new(x: &Coords8) -> Result<Self, NonPositiveJacobian> {
        let mut dn_dx = [[[0.0; 3]; 8]; HEX_GAUSS_POINTS];
        let mut det_j_w = [0.0; HEX_GAUSS_POINTS];
        for (q, point) in HEX_GAUSS_2X2X2.iter().enumerate() {
            let dn_dxi = hex8_shape_derivatives(&point.xi);
            let jac = jacobian(x, &dn_dxi);
            let det_j = jac.determinant();
            let inv = match jac.try_inverse() {
                Some(inv) if det_j > 0.0 => inv,
                _ => {
                    return Err(NonPositiveJacobian {
                        gauss_point: q,
                        det_j,
                    })
                }
            };
            for a in 0..8 {
                for i in 0..3 {
                    dn_dx[q][a][i] = (0..3).map(|j| dn_dxi[a][j] * inv[(j, i)]).sum();
                }
            }
            det_j_w[q] = point.weight * det_j;
        }
        Ok(Hex8Geometry { dn_dx, det_j_w })
    }

    /// Element volume `Σ_q w_q det J_q` (m³).
    pub fn volume(&self) -> f64 {
        self.det_j_w.iter().sum()
    }

    /// B matrix at Gauss point `q` (see [`b_matrix`]).
    pub fn b_matrix(&self, q: usize) -> BMatrix {
        b_matrix(&self.dn_dx[q])
    }

    /// Strain increments at the 8 Gauss points from the element displacement increments.
    ///
    /// ```text
    /// Δε_q = B(ξ_q) Δu_e
    /// ```
    ///
    /// Summed over B's nonzero entries only, in the dense product's order: the same values.
    pub fn strain_increments(&self, d_u: &Vector24) -> [Strain6; HEX_GAUSS_POINTS] {
        std::array::from_fn(|q| {
            let mut e = [0.0; 6];
            for (g, u) in self.dn_dx[q].iter().zip(d_u.as_slice().chunks_exact(3)) {
                e[0] += g[0] * u[0];
                e[1] += g[1] * u[1];
                e[2] += g[2] * u[2];
                e[3] += g[1] * u[0];
                e[3] += g[0] * u[1];
                e[4] += g[2] * u[1];
                e[4] += g[1] * u[2];
                e[5] += g[2] * u[0];
                e[5] += g[0] * u[2];
            }
            Strain6(e.into())
        })
    }

    /// Internal force vector from the 8 Gauss-point stresses (Pa).
    ///
    /// ```text
    /// δW_int = ∫_Ωe δεᵀ σ dV   ⇒   f_int = Σ_q B_qᵀ σ_q w_q det J_q      (N)
    /// ```
    ///
    /// Summed over B's nonzero entries only, in the dense product's order: the same values.
    pub fn internal_force(&self, sig: &[Stress6; HEX_GAUSS_POINTS]) -> Vector24 {
        let mut f = Vector24::zeros();
        for q in 0..HEX_GAUSS_POINTS {
            let (w, s) = (self.det_j_w[q], &sig[q].0);
            for (g, fa) in self.dn_dx[q].iter().zip(f.as_mut_slice().chunks_exact_mut(3)) {
                fa[0] += w * (0.0 + g[0] * s[0] + g[1] * s[3] + g[2] * s[5]);
                fa[1] += w * (0.0 + g[1] * s[1] + g[0] * s[3] + g[2] * s[4]);
                fa[2] += w * (0.0 + g[2] * s[2] + g[1] * s[4] + g[0] * s[5]);
            }
        }
        f
    }

    /// Stiffness matrix from the 8 Gauss-point tangents `D_q = ∂σ/∂ε` (Pa). `D` need not be
    /// symmetric (non-associated plasticity); `K` is then non-symmetric too.
    ///
    /// ```text
    /// K = ∂f_int/∂u_e = Σ_q B_qᵀ D_q B_q w_q det J_q      (N/m)
    /// ```
    ///
    /// Only the three nonzero entries of each column of B enter the sums ([`b_matrix`]), in
    /// the order of the dense product, so K has the same bits as `Σ_q w_q Bᵀ(D_q B)`
    /// evaluated densely (nalgebra's `gemm_tr` of `D·B`; the zeros add nothing) in less than
    /// half its time.
    pub fn stiffness(&self, tangents: &[Tangent6; HEX_GAUSS_POINTS]) -> Matrix24 {
        let mut k = Matrix24::zeros();
        for q in 0..HEX_GAUSS_POINTS {
            let db = d_times_b(&tangents[q], &self.dn_dx[q]);
            let w = self.det_j_w[q];
            for (j, x) in db.iter().enumerate() {
                let column = &mut k.as_mut_slice()[24 * j..24 * j + 24];
                for (a, g) in self.dn_dx[q].iter().enumerate() {
                    let kj = &mut column[3 * a..3 * a + 3];
                    kj[0] += w * (0.0 + g[0] * x[0] + g[1] * x[3] + g[2] * x[5]);
                    kj[1] += w * (0.0 + g[1] * x[1] + g[0] * x[3] + g[2] * x[4]);
                    kj[2] += w * (0.0 + g[2] * x[2] + g[1] * x[4] + g[0] * x[5]);
                }
            }
        }
        k
    }
}

/// The 24 columns of D·B at a Gauss point with gradients `g` ([`b_matrix`]): each the sum
/// of B's three nonzero entries of the column times D's columns, added as the dense product
/// adds them (the first term alone, then each next one added to it).
fn d_times_b(d: &Tangent6, g: &[[f64; 3]; 8]) -> [[f64; 6]; 24] {
    let d = &d.0;
    let mut db = [[0.0; 6]; 24];
    for (a, g) in g.iter().enumerate() {
        for i in 0..6 {
            db[3 * a][i] = d[(i, 5)] * g[2] + (d[(i, 3)] * g[1] + d[(i, 0)] * g[0]);
            db[3 * a + 1][i] = d[(i, 4)] * g[2] + (d[(i, 3)] * g[0] + d[(i, 1)] * g[1]);
            db[3 * a + 2][i] = d[(i, 5)] * g[0] + (d[(i, 4)] * g[1] + d[(i, 2)] * g[2]);
        }
    }
    db
}

/// Body-force (gravity) load for density `rho` (kg/m³) and acceleration `g` (m/s², e.g.
/// `[0, 0, −9.81]`). Exact with 2×2×2 points for any hex8.
///
/// ```text
/// δW_ext = ∫_Ωe δuᵀ ρ g dV   ⇒   f_a = Σ_q N_a(ξ_q) ρ g w_q det J_q      (N)
/// ```
pub fn gravity_load(x: &Coords8, rho: f64, g: &[f64; 3]) -> Vector24 {
    let mut f = Vector24::zeros();
    for q in &HEX_GAUSS_2X2X2 {
        let n = hex8_shape(&q.xi);
        let dv = q.weight * jacobian(x, &hex8_shape_derivatives(&q.xi)).determinant();
        for a in 0..8 {
            for i in 0..3 {
                f[3 * a + i] += n[a] * rho * g[i] * dv;
            }
        }
    }
    f
}

/// Consistent mass matrix, integrated exactly with 3×3×3 points (`N_a N_b det J` has degree 4
/// in each reference variable).
///
/// ```text
/// δW_inertia = ∫_Ωe δuᵀ ρ ü dV   ⇒   M_(3a+i)(3b+j) = δ_ij ∫_Ωe ρ N_a N_b dV      (kg)
/// ```
pub fn consistent_mass(x: &Coords8, rho: f64) -> Matrix24 {
    let mut m = Matrix24::zeros();
    for q in &HEX_GAUSS_3X3X3 {
        let n = hex8_shape(&q.xi);
        let dm = rho * q.weight * jacobian(x, &hex8_shape_derivatives(&q.xi)).determinant();
        for a in 0..8 {
            for b in 0..8 {
                let mab = n[a] * n[b] * dm;
                for i in 0..3 {
                    m[(3 * a + i, 3 * b + i)] += mab;
                }
            }
        }
    }
    m
}

/// Lumped (row-sum) mass: the diagonal of the lumped mass matrix in element DOF order.
/// Every entry is positive for a valid hex8 and the 8 nodal masses sum to `ρ V`.
///
/// ```text
/// m_a = Σ_b ∫_Ωe ρ N_a N_b dV = ∫_Ωe ρ N_a dV      (kg, the same for the 3 DOFs of node a)
/// ```
pub fn lumped_mass(x: &Coords8, rho: f64) -> Vector24 {
    let mut m = Vector24::zeros();
    for q in &HEX_GAUSS_2X2X2 {
        let n = hex8_shape(&q.xi);
        let dm = rho * q.weight * jacobian(x, &hex8_shape_derivatives(&q.xi)).determinant();
        for a in 0..8 {
            for i in 0..3 {
                m[3 * a + i] += n[a] * dm;
            }
        }
    }
    m
}

/// Coordinates of the 4 nodes of local face `face` (outward order, [`HEX8_FACES`]).
pub fn face_coords(x: &Coords8, face: usize) -> [[f64; 3]; 4] {
    HEX8_FACES[face].map(|a| x[a])
}

/// Area vector `∫_Γ n dA` of a bilinear quad whose nodes are in right-hand order (m²).
/// Exact for non-planar faces: half the cross product of the diagonals.
pub fn quad_area_vector(xf: &[[f64; 3]; 4]) -> [f64; 3] {
    let d1 = Vector3::from(xf[2]) - Vector3::from(xf[0]);
    let d2 = Vector3::from(xf[3]) - Vector3::from(xf[1]);
    (0.5 * d1.cross(&d2)).into()
}

/// Nodal forces of a normal pressure on a bilinear face. The face nodes are in right-hand order
/// with the normal pointing out of the loaded body; the pressure, interpolated bilinearly from
/// the nodal values `p` (Pa, > 0 pushes against the face, along the inward normal), acts as the
/// traction `t = −p n`. Exact with 2×2 points for bilinear faces and bilinear pressure.
///
/// ```text
/// δW_ext = ∫_Γ δuᵀ t dA   ⇒   f_a = −Σ_q N_a(s_q) p(s_q) (g_s × g_t)(s_q) w_q      (N)
/// g_s = ∂x/∂s, g_t = ∂x/∂t,  n dA = g_s × g_t ds dt
/// ```
pub fn quad_pressure_load(xf: &[[f64; 3]; 4], p: &[f64; 4]) -> [[f64; 3]; 4] {
    let mut f = [[0.0; 3]; 4];
    for q in &QUAD_GAUSS_2X2 {
        let n = quad4_shape(&q.st);
        let dn = quad4_shape_derivatives(&q.st);
        let mut g_s = Vector3::zeros();
        let mut g_t = Vector3::zeros();
        for a in 0..4 {
            let xa = Vector3::from(xf[a]);
            g_s += xa * dn[a][0];
            g_t += xa * dn[a][1];
        }
        let area_normal = g_s.cross(&g_t) * q.weight;
        let pq: f64 = (0..4).map(|a| n[a] * p[a]).sum();
        for a in 0..4 {
            for i in 0..3 {
                f[a][i] -= n[a] * pq * area_normal[i];
            }
        }
    }
    f
}

/// [`quad_pressure_load`] on local face `face` of an element, scattered into the element DOF
/// vector (`p` holds the pressures at the face's nodes, in [`HEX8_FACES`] order).
pub fn face_pressure_load(x: &Coords8, face: usize, p: &[f64; 4]) -> Vector24 {
    let f_face = quad_pressure_load(&face_coords(x, face), p);
    let mut f = Vector24::zeros();
    for (k, &a) in HEX8_FACES[face].iter().enumerate() {
        for i in 0..3 {
            f[3 * a + i] = f_face[k][i];
        }
    }
    f
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::element::shape::HEX8_REFERENCE_NODES;
    use crate::tensor::Vector6;

    /// The cell offsets are the reference corners mapped from [−1, 1] to {0, 1}.
    #[test]
    fn cell_offsets_follow_the_reference_corners() {
        for (off, r) in HEX8_CELL_OFFSETS.iter().zip(HEX8_REFERENCE_NODES) {
            assert_eq!(off.map(|d| 2.0 * d as f64 - 1.0), r);
        }
        assert_eq!(hex8_cell_nodes(1, 2, 3, |i, j, k| (i, j, k))[6], (2, 3, 4));
    }

    /// A strongly distorted (non-parallelepiped, non-planar faces) but valid hex.
    pub(crate) fn distorted() -> Coords8 {
        [
            [0.0, 0.0, 0.0],
            [2.1, 0.2, -0.1],
            [2.4, 1.9, 0.15],
            [-0.2, 1.6, 0.05],
            [0.1, -0.15, 1.3],
            [1.8, 0.1, 1.1],
            [2.2, 2.0, 1.7],
            [0.3, 1.7, 1.4],
        ]
    }

    /// An isotropic elastic D (E = 30 GPa, ν = 0.2), plus an optional non-symmetric part.
    fn elastic_d(nonsym: f64) -> Tangent6 {
        let (e, nu) = (30e9, 0.2);
        let mut d = crate::material::elastic::isotropic_stiffness(e, nu);
        d[(0, 4)] += nonsym * e;
        d[(2, 3)] -= 0.5 * nonsym * e;
        Tangent6(d)
    }

    /// The sparse stiffness, strain and force kernels give the bits of the dense products they
    /// replace, for a full non-symmetric D with entries of both signs at every Gauss point, a
    /// distorted element and an increment with entries of both signs.
    #[test]
    fn sparse_kernels_have_the_bits_of_the_dense_products() {
        let g = Hex8Geometry::new(&distorted()).expect("valid");
        let d: [Tangent6; HEX_GAUSS_POINTS] = std::array::from_fn(|q| {
            let mut d = elastic_d(0.3 + 0.1 * q as f64).0;
            for (k, v) in d.iter_mut().enumerate() {
                *v += ((k * 7 + q * 3) % 11) as f64 * 1.3e8 - 6.1e8;
            }
            Tangent6(d)
        });
        let mut dense = Matrix24::zeros();
        for q in 0..HEX_GAUSS_POINTS {
            let b = g.b_matrix(q);
            let db: BMatrix = d[q].0 * b;
            dense.gemm_tr(g.det_j_w[q], &b, &db, 1.0);
        }
        let sparse = g.stiffness(&d);
        for (a, b) in sparse.iter().zip(dense.iter()) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a:e} against {b:e}");
        }
        let u = Vector24::from_fn(|i, _| ((i * 5 + 1) % 7) as f64 * 1e-4 - 3e-4);
        let strains = g.strain_increments(&u);
        let sig = std::array::from_fn(|q| Stress6(d[q].0 * strains[q].0));
        let mut f_dense = Vector24::zeros();
        for q in 0..HEX_GAUSS_POINTS {
            let b = g.b_matrix(q);
            for (a, b) in strains[q].0.iter().zip((b * u).iter()) {
                assert_eq!(a.to_bits(), b.to_bits(), "strain {a:e} against {b:e}");
            }
            f_dense.gemv_tr(g.det_j_w[q], &b, &sig[q].0, 1.0);
        }
        for (a, b) in g.internal_force(&sig).iter().zip(f_dense.iter()) {
            assert_eq!(a.to_bits(), b.to_bits(), "force {a:e} against {b:e}");
        }
    }

    /// Nodal values of the linear field `u = u0 + A x`.
    fn linear_field(x: &Coords8, u0: [f64; 3], a: &Matrix3<f64>) -> Vector24 {
        let mut u = Vector24::zeros();
        for n in 0..8 {
            let v = Vector3::from(u0) + a * Vector3::from(x[n]);
            for i in 0..3 {
                u[3 * n + i] = v[i];
            }
        }
        u
    }

    /// The six rigid-body modes (3 translations, 3 infinitesimal rotations about the origin).
    fn rigid_modes(x: &Coords8) -> [Vector24; 6] {
        std::array::from_fn(|m| {
            if m < 3 {
                let mut t = [0.0; 3];
                t[m] = 1.0;
                linear_field(x, t, &Matrix3::zeros())
            } else {
                let mut w = Vector3::zeros();
                w[m - 3] = 1.0;
                linear_field(x, [0.0; 3], &w.cross_matrix())
            }
        })
    }

    #[test]
    fn jacobian_of_the_reference_cube_is_identity() {
        let g = Hex8Geometry::new(&HEX8_REFERENCE_NODES).expect("valid");
        assert!((g.volume() - 8.0).abs() < 1e-14);
        let (corners, gauss) = jacobian_determinants(&HEX8_REFERENCE_NODES);
        for d in corners.iter().chain(gauss.iter()) {
            assert!((d - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn faces_are_outward_and_close_the_surface() {
        let x = distorted();
        let mut total = Vector3::zeros();
        let centre: Vector3<f64> = x.iter().map(|p| Vector3::from(*p)).sum::<Vector3<f64>>() / 8.0;
        for f in 0..6 {
            let xf = face_coords(&x, f);
            let av = Vector3::from(quad_area_vector(&xf));
            let fc: Vector3<f64> = xf.iter().map(|p| Vector3::from(*p)).sum::<Vector3<f64>>() / 4.0;
            assert!(av.dot(&(fc - centre)) > 0.0, "face {f} normal points inwards");
            total += av;
        }
        assert!(total.norm() < 1e-14, "closed surface: Σ A n = {total}");
    }

    #[test]
    fn rigid_body_modes_give_zero_strain_on_distorted_element() {
        let x = distorted();
        let g = Hex8Geometry::new(&x).expect("valid");
        for (m, u) in rigid_modes(&x).iter().enumerate() {
            for eps in g.strain_increments(u) {
                assert!(eps.0.norm() < 1e-13, "mode {m}: strain {}", eps.0);
            }
        }
    }

    #[test]
    fn strain_of_a_linear_field_is_exact() {
        let x = distorted();
        let g = Hex8Geometry::new(&x).expect("valid");
        let a = Matrix3::new(
            1e-3, -2e-3, 0.5e-3, 0.7e-3, -1.1e-3, 2.5e-3, -0.3e-3, 1.9e-3, 0.4e-3,
        );
        let u = linear_field(&x, [0.1, -0.2, 0.3], &a);
        let exact = Strain6::from_matrix(&(0.5 * (a + a.transpose())));
        for (q, eps) in g.strain_increments(&u).iter().enumerate() {
            let err = (eps.0 - exact.0).amax();
            assert!(err < 1e-12 * exact.0.amax(), "gp {q}: error {err:e}");
        }
    }

    #[test]
    fn b_matrix_matches_finite_difference_of_the_displacement_field() {
        let x = distorted();
        let g = Hex8Geometry::new(&x).expect("valid");
        let u = Vector24::from_fn(|i, _| ((i * 7 + 3) % 11) as f64 * 1e-3 - 5e-3);
        let eps = g.strain_increments(&u);
        // Displacement gradient by central differences in the reference frame, mapped with J⁻¹.
        for (q, point) in HEX_GAUSS_2X2X2.iter().enumerate() {
            let h = 1e-6;
            let disp = |xi: &[f64; 3]| -> Vector3<f64> {
                let n = hex8_shape(xi);
                (0..8)
                    .map(|a| Vector3::new(u[3 * a], u[3 * a + 1], u[3 * a + 2]) * n[a])
                    .sum()
            };
            let mut du_dxi = Matrix3::zeros();
            for j in 0..3 {
                let (mut p, mut m) = (point.xi, point.xi);
                p[j] += h;
                m[j] -= h;
                du_dxi.set_column(j, &((disp(&p) - disp(&m)) / (2.0 * h)));
            }
            let jac = jacobian(&x, &hex8_shape_derivatives(&point.xi));
            let grad = du_dxi * jac.try_inverse().expect("invertible");
            let fd = Strain6::from_matrix(&(0.5 * (grad + grad.transpose())));
            assert!(
                (fd.0 - eps[q].0).amax() < 1e-9,
                "gp {q}: {} vs {}",
                fd.0,
                eps[q].0
            );
        }
    }

    #[test]
    fn stiffness_is_symmetric_for_symmetric_d_and_has_six_zero_energy_modes() {
        let x = distorted();
        let g = Hex8Geometry::new(&x).expect("valid");
        let k = g.stiffness(&[elastic_d(0.0); 8]);
        let scale = k.amax();
        assert!((k - k.transpose()).amax() < 1e-14 * scale, "K not symmetric");
        for (m, u) in rigid_modes(&x).iter().enumerate() {
            let ku = k * u;
            assert!(
                ku.amax() < 1e-12 * scale * u.amax(),
                "mode {m}: |K u| = {}",
                ku.amax()
            );
        }
        // Exactly 6 zero eigenvalues: the 7th smallest is well away from zero.
        let mut ev: Vec<f64> = k.symmetric_eigenvalues().iter().copied().collect();
        ev.sort_by(f64::total_cmp);
        assert!(ev[5].abs() < 1e-9 * scale, "6th eigenvalue {}", ev[5]);
        assert!(ev[6] > 1e-4 * scale, "7th eigenvalue {} (spurious mode)", ev[6]);
    }

    #[test]
    fn stiffness_with_nonsymmetric_d_matches_finite_difference_of_internal_force() {
        let x = distorted();
        let g = Hex8Geometry::new(&x).expect("valid");
        let d = elastic_d(0.3);
        assert!((d.0 - d.0.transpose()).amax() > 1e9);
        let k = g.stiffness(&[d; 8]);
        assert!(
            (k - k.transpose()).amax() > 1e-3 * k.amax(),
            "K should be non-symmetric"
        );
        // For a linear material, f_int(u) = Σ Bᵀ D B u w detJ: K u must equal f_int(u).
        let u = Vector24::from_fn(|i, _| ((i * 5 + 1) % 7) as f64 * 1e-4);
        let sig = g.strain_increments(&u).map(|e| Stress6(d.0 * e.0));
        let f = g.internal_force(&sig);
        assert!((k * u - f).amax() < 1e-12 * f.amax());
    }

    /// Patch test: a linear displacement field on a distorted element gives
    /// K u = ∮ Nᵀ σ n dA (the boundary-consistent nodal forces of the constant stress σ = D ε).
    #[test]
    fn patch_test_single_distorted_element() {
        let x = distorted();
        let g = Hex8Geometry::new(&x).expect("valid");
        let d = elastic_d(0.0);
        let a = Matrix3::new(2e-3, 1e-3, -0.5e-3, 0.0, -1e-3, 0.8e-3, 0.3e-3, 0.6e-3, 1.5e-3);
        let u = linear_field(&x, [0.0; 3], &a);
        let eps = Strain6::from_matrix(&(0.5 * (a + a.transpose())));
        let sig = Stress6(d.0 * eps.0).to_matrix();
        let ku = g.stiffness(&[d; 8]) * u;
        // Boundary integral with the traction t = σ n on each face (exact with 2×2 points).
        let mut f = Vector24::zeros();
        for (face, nodes) in HEX8_FACES.iter().enumerate() {
            let xf = face_coords(&x, face);
            for q in &QUAD_GAUSS_2X2 {
                let n = quad4_shape(&q.st);
                let dn = quad4_shape_derivatives(&q.st);
                let g_s: Vector3<f64> = (0..4).map(|k| Vector3::from(xf[k]) * dn[k][0]).sum();
                let g_t: Vector3<f64> = (0..4).map(|k| Vector3::from(xf[k]) * dn[k][1]).sum();
                let t = sig * g_s.cross(&g_t) * q.weight;
                for (k, &node) in nodes.iter().enumerate() {
                    for i in 0..3 {
                        f[3 * node + i] += n[k] * t[i];
                    }
                }
            }
        }
        assert!(
            (ku - f).amax() < 1e-12 * f.amax(),
            "K u - f_boundary = {:e}",
            (ku - f).amax()
        );
    }

    /// Patch test on a 2×2×2 patch of elements with a displaced interior node: a linear field
    /// gives zero force at the interior node and the exact constant strain everywhere.
    #[test]
    fn patch_test_distorted_patch_interior_node_is_in_equilibrium() {
        let node = |i: usize, j: usize, k: usize| i + 3 * (j + 3 * k);
        let mut coords = [[0.0; 3]; 27];
        for k in 0..3 {
            for j in 0..3 {
                for i in 0..3 {
                    coords[node(i, j, k)] = [i as f64, 1.2 * j as f64, 0.8 * k as f64];
                }
            }
        }
        coords[node(1, 1, 1)] = [1.23, 1.05, 0.93];
        let a = Matrix3::new(1e-3, 2e-3, 0.0, -1e-3, 0.5e-3, 3e-3, 0.2e-3, -0.7e-3, -2e-3);
        let eps_exact = Strain6::from_matrix(&(0.5 * (a + a.transpose())));
        let d = elastic_d(0.0);
        let mut f_global = [Vector3::<f64>::zeros(); 27];
        let mut f_scale = 0.0f64;
        for (ei, ej, ek) in (0..8).map(|e| (e % 2, (e / 2) % 2, e / 4)) {
            let conn = hex8_cell_nodes(ei, ej, ek, node);
            let x = conn.map(|n| coords[n]);
            let g = Hex8Geometry::new(&x).expect("valid");
            let u = linear_field(&x, [0.01, 0.02, -0.03], &a);
            for eps in g.strain_increments(&u) {
                assert!((eps.0 - eps_exact.0).amax() < 1e-12 * eps_exact.0.amax());
            }
            let fe = g.stiffness(&[d; 8]) * u;
            f_scale = f_scale.max(fe.amax());
            for (l, &n) in conn.iter().enumerate() {
                f_global[n] += Vector3::new(fe[3 * l], fe[3 * l + 1], fe[3 * l + 2]);
            }
        }
        let interior = f_global[node(1, 1, 1)].amax();
        assert!(
            interior < 1e-12 * f_scale,
            "interior force {interior:e} vs scale {f_scale:e}"
        );
    }

    #[test]
    fn internal_force_of_a_uniform_stress_is_self_equilibrated() {
        let x = distorted();
        let g = Hex8Geometry::new(&x).expect("valid");
        let sig = Stress6(Vector6::new(1e6, -2e6, 3e5, 4e5, -1e5, 2e5));
        let f = g.internal_force(&[sig; 8]);
        // A self-equilibrated element: resultant force and moment vanish.
        let mut resultant = Vector3::zeros();
        let mut moment = Vector3::zeros();
        for a in 0..8 {
            let fa = Vector3::new(f[3 * a], f[3 * a + 1], f[3 * a + 2]);
            resultant += fa;
            moment += Vector3::from(x[a]).cross(&fa);
        }
        assert!(resultant.amax() < 1e-8 * f.amax(), "resultant {resultant}");
        assert!(moment.amax() < 1e-8 * f.amax(), "moment {moment}");
    }

    #[test]
    fn gravity_load_sums_to_rho_g_v_on_a_trapezoidal_prism() {
        // Trapezoid in x-z (bottom width 3, top width 1, height 2) extruded 1.5 along y.
        let x: Coords8 = [
            [0.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 1.5, 0.0],
            [0.0, 1.5, 0.0],
            [1.2, 0.0, 2.0],
            [2.2, 0.0, 2.0],
            [2.2, 1.5, 2.0],
            [1.2, 1.5, 2.0],
        ];
        let v_exact = 0.5 * (3.0 + 1.0) * 2.0 * 1.5;
        assert!((volume(&x) - v_exact).abs() < 1e-13 * v_exact);
        let (rho, g) = (2150.0, [0.3, -0.1, -9.81]);
        let f = gravity_load(&x, rho, &g);
        for i in 0..3 {
            let sum: f64 = (0..8).map(|a| f[3 * a + i]).sum();
            let expect = rho * g[i] * v_exact;
            assert!(
                (sum - expect).abs() < 1e-12 * expect.abs(),
                "dir {i}: {sum} vs {expect}"
            );
        }
    }

    #[test]
    fn masses_sum_to_rho_v_and_lumped_is_row_sum_of_consistent() {
        let x = distorted();
        let rho = 1900.0;
        let v = volume(&x);
        let lumped = lumped_mass(&x, rho);
        let consistent = consistent_mass(&x, rho);
        assert!(lumped.iter().all(|&m| m > 0.0));
        for i in 0..3 {
            let sum: f64 = (0..8).map(|a| lumped[3 * a + i]).sum();
            assert!((sum - rho * v).abs() < 1e-12 * rho * v, "lumped dir {i}: {sum}");
        }
        assert!((consistent.sum() - 3.0 * rho * v).abs() < 1e-12 * rho * v);
        assert!((consistent - consistent.transpose()).amax() < 1e-12 * consistent.amax());
        for r in 0..24 {
            let row: f64 = consistent.row(r).sum();
            assert!((row - lumped[r]).abs() < 1e-12 * lumped[r], "row {r}");
        }
        // A rigid translation has kinetic energy ½ m v² with m = ρV.
        let t = rigid_modes(&x)[0];
        assert!(((t.transpose() * consistent * t)[0] - rho * v).abs() < 1e-12 * rho * v);
    }

    #[test]
    fn pressure_on_a_skewed_face_sums_to_minus_p_a_n() {
        let x = distorted();
        let p = 2.5e5;
        for face in 0..6 {
            let xf = face_coords(&x, face);
            let f = quad_pressure_load(&xf, &[p; 4]);
            let area = Vector3::from(quad_area_vector(&xf));
            let sum: Vector3<f64> = f.iter().map(|fa| Vector3::from(*fa)).sum();
            assert!(
                (sum + p * area).amax() < 1e-12 * p * area.norm(),
                "face {face}: {sum}"
            );
            let fe = face_pressure_load(&x, face, &[p; 4]);
            assert!((fe.sum() - sum.sum()).abs() < 1e-9 * p);
        }
        // A planar parallelogram face tilted out of every coordinate plane.
        let e1 = Vector3::new(2.0, 0.5, 0.3);
        let e2 = Vector3::new(0.4, 1.5, -0.7);
        let o = Vector3::new(1.0, -1.0, 2.0);
        let xf = [o, o + e1, o + e1 + e2, o + e2].map(|v| [v.x, v.y, v.z]);
        let f = quad_pressure_load(&xf, &[p; 4]);
        let an = e1.cross(&e2); // = A n with n the right-hand normal
        let sum: Vector3<f64> = f.iter().map(|fa| Vector3::from(*fa)).sum();
        assert!(
            (sum + p * an).amax() < 1e-12 * p * an.norm(),
            "{sum} vs {}",
            -p * an
        );
        // A linearly varying pressure on a rectangle: the resultant is −p̄ A n with p̄ the mean.
        let xr = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 3.0, 0.0], [0.0, 3.0, 0.0]];
        let pr = [1e5, 3e5, 3e5, 1e5];
        let f = quad_pressure_load(&xr, &pr);
        let fz: f64 = f.iter().map(|fa| fa[2]).sum();
        assert!((fz + 2e5 * 6.0).abs() < 1e-12 * 2e5 * 6.0);
        // Moment about x = 0 of p(x) = 1e5 (1 + x) on [0, 2] × [0, 3]: ∫ x p dA = 3e5 (2 + 8/3).
        let mx: f64 = f.iter().zip(&xr).map(|(fa, xa)| -fa[2] * xa[0]).sum();
        assert!((mx - 3e5 * (2.0 + 8.0 / 3.0)).abs() < 1e-9 * mx.abs());
    }

    #[test]
    fn inverted_element_is_rejected_with_its_gauss_point() {
        let mut x = distorted();
        x.swap(0, 4);
        x.swap(1, 5);
        x.swap(2, 6);
        x.swap(3, 7);
        let err = Hex8Geometry::new(&x).expect_err("inverted");
        assert!(err.det_j < 0.0);
        assert!(err.to_string().contains("Gauss point 0"), "{err}");
    }
}
