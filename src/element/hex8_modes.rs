//! Incompatible modes of the 8-node hexahedron (Wilson's element with Taylor's correction): the
//! slab's element when it has one element through its thickness (spec seismic §4 item 6).
//!
//! The fully integrated trilinear hexahedron cannot bend: under a linear bending strain its
//! shear strain is not zero (parasitic shear), and a slab element tens of times longer than
//! thick is stiffer in bending by a factor that grows with that ratio. Three bubble modes per
//! displacement component are added inside the element,
//!
//! ```text
//! u = Σ_a N_a u_a + Σ_k P_k(ξ) α_k,   P_1 = 1 − ξ²,  P_2 = 1 − η²,  P_3 = 1 − ζ²   (α_k ∈ ℝ³)
//! ε = B u_e + G α,   G_q from ∂P_k/∂x_i = (det J₀ / det J_q) Σ_j (J₀⁻¹)_ji ∂P_k/∂ξ_j
//! ```
//!
//! with J₀ the Jacobian at the element centre. Taylor's factor det J₀ / det J_q makes
//! ∫ G dV = Σ_q G_q w_q det J_q = 0 for any shape, so a constant strain is still represented
//! exactly (the patch test). The nine α are internal: the element equations
//!
//! ```text
//! ⎡ K_uu  K_uα ⎤ ⎡ Δu ⎤   ⎡ f_ext − f_int ⎤       K_xy = Σ_q X_qᵀ D_q Y_q w_q det J_q
//! ⎣ K_αu  K_αα ⎦ ⎣ Δα ⎦ = ⎣    − r_α      ⎦       r_α  = Σ_q G_qᵀ σ_q w_q det J_q
//! ```
//!
//! are condensed: K = K_uu − K_uα K_αα⁻¹ K_αu and Δα = −K_αα⁻¹ (K_αu Δu + r_α). The modes
//! add no mass and no load. They are exact for a linear-elastic material, whose D does not
//! depend on α; the scene accepts them only for elastic blocks.

use crate::element::hex8::{
    jacobian, strain_operator, BMatrix, Coords8, Hex8Geometry, Matrix24, NonPositiveJacobian, Vector24,
};
use crate::element::quadrature::{HEX_GAUSS_2X2X2, HEX_GAUSS_POINTS};
use crate::element::shape::hex8_shape_derivatives;
use crate::tensor::{Strain6, Stress6, Tangent6};
use nalgebra::{SMatrix, SVector};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The formulation of a block's hexahedra.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SolidElement {
    /// The fully integrated trilinear hexahedron (default; locks in bending when long and thin).
    #[default]
    Trilinear,
    /// The trilinear hexahedron with Wilson–Taylor incompatible modes (this module): bends
    /// correctly with one element through a slab's thickness. Elastic blocks only.
    IncompatibleModes,
}

/// The nine internal parameters α (three bubble modes × three components), mode by mode.
pub type Modes9 = SVector<f64, 9>;
/// Strain of the modes at one point, Voigt rows: ε = G α.
pub type GMatrix = SMatrix<f64, 6, 9>;

/// The bubble modes' strain operators at the 8 Gauss points of one element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IncompatibleModes {
    /// Taylor-corrected ∂P_k/∂x_i at each Gauss point: `grad[q][k][i]` (1/m).
    grad: [[[f64; 3]; 3]; HEX_GAUSS_POINTS],
}

/// The element's internal equations at given tangents, ready to be condensed.
#[derive(Debug, Clone, PartialEq)]
pub struct Condensation {
    /// K_uα K_αα⁻¹ (24 × 9).
    k_ua_inv: SMatrix<f64, 24, 9>,
    /// K_αα⁻¹ (9 × 9).
    k_aa_inv: SMatrix<f64, 9, 9>,
    /// K_αu (9 × 24).
    k_au: SMatrix<f64, 9, 24>,
}

impl IncompatibleModes {
    /// The modes' gradients of element `x`. Fails where `det J ≤ 0` (centre or a Gauss point).
    pub fn new(x: &Coords8) -> Result<Self, NonPositiveJacobian> {
        let j0 = jacobian(x, &hex8_shape_derivatives(&[0.0; 3]));
        let det0 = j0.determinant();
        let inv0 = match j0.try_inverse() {
            Some(inv) if det0 > 0.0 => inv,
            _ => {
                return Err(NonPositiveJacobian {
                    gauss_point: 0,
                    det_j: det0,
                })
            }
        };
        let mut grad = [[[0.0; 3]; 3]; HEX_GAUSS_POINTS];
        for (q, point) in HEX_GAUSS_2X2X2.iter().enumerate() {
            let det_q = jacobian(x, &hex8_shape_derivatives(&point.xi)).determinant();
            if det_q <= 0.0 {
                return Err(NonPositiveJacobian {
                    gauss_point: q,
                    det_j: det_q,
                });
            }
            let scale = det0 / det_q;
            for k in 0..3 {
                // ∂P_k/∂ξ_j = −2 ξ_k δ_kj
                let dp = -2.0 * point.xi[k];
                for i in 0..3 {
                    grad[q][k][i] = scale * inv0[(k, i)] * dp;
                }
            }
        }
        Ok(IncompatibleModes { grad })
    }

    /// G at Gauss point `q`: the B-matrix pattern of [`crate::element::hex8::b_matrix`] with the
    /// three modes in place of the eight nodes.
    pub fn g_matrix(&self, q: usize) -> GMatrix {
        strain_operator(&self.grad[q])
    }

    /// K_uα, K_αα and K_αu at the tangents `D_q`. `None` when K_αα is singular (a zero tangent).
    pub fn condense(
        &self,
        geo: &Hex8Geometry,
        tangents: &[Tangent6; HEX_GAUSS_POINTS],
    ) -> Option<Condensation> {
        let mut k_ua = SMatrix::<f64, 24, 9>::zeros();
        let mut k_au = SMatrix::<f64, 9, 24>::zeros();
        let mut k_aa = SMatrix::<f64, 9, 9>::zeros();
        for q in 0..HEX_GAUSS_POINTS {
            let (b, g): (BMatrix, GMatrix) = (geo.b_matrix(q), self.g_matrix(q));
            let w = geo.det_j_w[q];
            let dg = tangents[q].0 * g;
            k_ua.gemm_tr(w, &b, &dg, 1.0);
            k_aa.gemm_tr(w, &g, &dg, 1.0);
            k_au.gemm_tr(w, &g, &(tangents[q].0 * b), 1.0);
        }
        let k_aa_inv = k_aa.try_inverse()?;
        Some(Condensation {
            k_ua_inv: k_ua * k_aa_inv,
            k_aa_inv,
            k_au,
        })
    }

    /// r_α = Σ_q G_qᵀ σ_q w_q det J_q: the out-of-balance of the internal equations at stresses σ.
    pub fn residual(&self, geo: &Hex8Geometry, sig: &[Stress6; HEX_GAUSS_POINTS]) -> Modes9 {
        let mut r = Modes9::zeros();
        for (q, s) in sig.iter().enumerate() {
            r.gemv_tr(geo.det_j_w[q], &self.g_matrix(q), &s.0, 1.0);
        }
        r
    }

    /// Strain increments at the 8 Gauss points: Δε_q = B_q Δu + G_q Δα.
    pub fn strain_increments(
        &self,
        geo: &Hex8Geometry,
        d_u: &Vector24,
        d_alpha: &Modes9,
    ) -> [Strain6; HEX_GAUSS_POINTS] {
        std::array::from_fn(|q| Strain6(geo.b_matrix(q) * d_u + self.g_matrix(q) * d_alpha))
    }
}

impl Condensation {
    /// The condensed stiffness K = K_uu − K_uα K_αα⁻¹ K_αu (N/m).
    pub fn stiffness(&self, k_uu: &Matrix24) -> Matrix24 {
        k_uu - self.k_ua_inv * self.k_au
    }

    /// The modes' increment that keeps the internal equations in balance:
    /// Δα = −K_αα⁻¹ (K_αu Δu + r_α).
    pub fn modes(&self, d_u: &Vector24, r_alpha: &Modes9) -> Modes9 {
        -(self.k_aa_inv * (self.k_au * d_u + r_alpha))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8::tests::distorted;

    fn elastic_d(e: f64, nu: f64) -> Tangent6 {
        let l = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let g = e / (2.0 * (1.0 + nu));
        let mut d = SMatrix::<f64, 6, 6>::zeros();
        for i in 0..3 {
            for j in 0..3 {
                d[(i, j)] = l;
            }
            d[(i, i)] = l + 2.0 * g;
            d[(i + 3, i + 3)] = g;
        }
        Tangent6(d)
    }

    fn brick(a: f64, b: f64, c: f64) -> Coords8 {
        crate::element::shape::HEX8_REFERENCE_NODES.map(|r| {
            [
                0.5 * a * (r[0] + 1.0),
                0.5 * b * (r[1] + 1.0),
                0.5 * c * (r[2] + 1.0),
            ]
        })
    }

    fn nodal(x: &Coords8, f: impl Fn(&[f64; 3]) -> [f64; 3]) -> Vector24 {
        Vector24::from_iterator(x.iter().flat_map(f))
    }

    #[test]
    fn the_modes_integrate_to_zero_strain_on_a_distorted_element() {
        let x = distorted();
        let (geo, modes) = (
            Hex8Geometry::new(&x).unwrap(),
            IncompatibleModes::new(&x).unwrap(),
        );
        let mut sum = GMatrix::zeros();
        for q in 0..HEX_GAUSS_POINTS {
            sum += modes.g_matrix(q) * geo.det_j_w[q];
        }
        let scale = modes.g_matrix(0).abs().max() * geo.volume();
        assert!(sum.abs().max() < 1e-13 * scale, "∫ G dV = {sum}");
    }

    #[test]
    fn a_constant_strain_leaves_the_modes_at_rest_on_a_distorted_element() {
        let x = distorted();
        let (geo, modes) = (
            Hex8Geometry::new(&x).unwrap(),
            IncompatibleModes::new(&x).unwrap(),
        );
        let d = elastic_d(30e9, 0.2);
        let c = modes.condense(&geo, &[d; 8]).unwrap();
        let u = nodal(&x, |p| {
            [1e-3 * p[0] + 2e-4 * p[1], -3e-4 * p[2], 5e-4 * p[0] + 1e-4 * p[2]]
        });
        let alpha = c.modes(&u, &Modes9::zeros());
        assert!(alpha.abs().max() < 1e-15, "α = {alpha}");
        let k_full = geo.stiffness(&[d; 8]);
        let f = c.stiffness(&k_full) * u;
        let f_plain = k_full * u;
        assert!((f - f_plain).abs().max() < 1e-9 * f_plain.abs().max());
    }

    #[test]
    fn a_brick_bends_without_parasitic_shear() {
        // pure bending in the x–z plane about the centre (ν = 0): u_x = κ x z, u_z = −κ x²/2
        let (a, t) = (10.0, 0.5);
        let x = brick(a, t, t);
        let (geo, modes) = (
            Hex8Geometry::new(&x).unwrap(),
            IncompatibleModes::new(&x).unwrap(),
        );
        let d = elastic_d(25.5e9, 0.0);
        let c = modes.condense(&geo, &[d; 8]).unwrap();
        let kappa = 1e-4;
        let u = nodal(&x, |p| {
            let (xc, zc) = (p[0] - 0.5 * a, p[2] - 0.5 * t);
            [kappa * xc * zc, 0.0, -0.5 * kappa * xc * xc]
        });
        let energy = |k: &Matrix24| 0.5 * u.dot(&(k * u));
        let exact = 0.5 * 25.5e9 * (t.powi(4) / 12.0) * kappa * kappa * a;
        let k_full = geo.stiffness(&[d; 8]);
        let plain = energy(&k_full) / exact;
        let enhanced = energy(&c.stiffness(&k_full)) / exact;
        println!("bending energy / exact: trilinear {plain:.1}, incompatible modes {enhanced:.12}");
        assert!(plain > 100.0, "the trilinear brick locks: {plain}");
        assert!(
            (enhanced - 1.0).abs() < 1e-10,
            "bending energy / exact = {enhanced}"
        );
        let alpha = c.modes(&u, &Modes9::zeros());
        let eps = modes.strain_increments(&geo, &u, &alpha);
        for e in &eps {
            assert!(
                e.0[5].abs() < 1e-12 * kappa * t,
                "parasitic shear γzx = {}",
                e.0[5]
            );
        }
    }

    #[test]
    fn the_condensed_stiffness_is_symmetric_with_six_rigid_modes() {
        let x = distorted();
        let (geo, modes) = (
            Hex8Geometry::new(&x).unwrap(),
            IncompatibleModes::new(&x).unwrap(),
        );
        let k = modes
            .condense(&geo, &[elastic_d(30e9, 0.25); 8])
            .unwrap()
            .stiffness(&geo.stiffness(&[elastic_d(30e9, 0.25); 8]));
        assert!((k - k.transpose()).abs().max() < 1e-9 * k.abs().max());
        let eig = k.symmetric_eigenvalues();
        let zero = eig.iter().filter(|v| v.abs() < 1e-9 * k.abs().max()).count();
        assert_eq!(zero, 6, "{eig}");
        assert!(eig.iter().all(|v| *v > -1e-9 * k.abs().max()));
    }

    #[test]
    fn a_degenerate_element_is_rejected() {
        let mut x = brick(1.0, 1.0, 1.0);
        x[6] = x[0];
        assert!(IncompatibleModes::new(&x).is_err());
    }
}
