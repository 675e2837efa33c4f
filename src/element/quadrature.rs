//! Gauss–Legendre rules on the reference hexahedron `[−1, 1]³` and quadrilateral `[−1, 1]²`,
//! and the nodal (Newton–Cotes) rule on the quadrilateral used by the interface elements.
//!
//! ```text
//! ∫_{[−1,1]³} f(ξ) dξ ≈ Σ_q w_q f(ξ_q)
//! 2-point rule: ξ = ±1/√3, w = 1            (exact for degree ≤ 3 in each variable)
//! 3-point rule: ξ = 0, ±√(3/5), w = 8/9, 5/9 (exact for degree ≤ 5 in each variable)
//! ```
//!
//! The 2×2×2 points are numbered like the hex8 corner nodes: point `a` lies at
//! `HEX8_REFERENCE_NODES[a] / √3`, so Gauss-point `a` is the one nearest to node `a`.

use crate::element::shape::{HEX8_REFERENCE_NODES, QUAD4_REFERENCE_NODES};

/// One quadrature point in the reference hexahedron.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraturePoint {
    /// Reference coordinates `(ξ, η, ζ)`.
    pub xi: [f64; 3],
    /// Weight.
    pub weight: f64,
}

/// One quadrature point in the reference quadrilateral.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacePoint {
    /// Reference coordinates `(s, t)`.
    pub st: [f64; 2],
    /// Weight.
    pub weight: f64,
}

/// Abscissa of the 2-point Gauss rule, `1/√3`.
pub const GAUSS_2_ABSCISSA: f64 = 0.577_350_269_189_625_8;

/// Abscissa of the outer points of the 3-point Gauss rule, `√(3/5)`.
pub const GAUSS_3_ABSCISSA: f64 = 0.774_596_669_241_483_4;

/// Number of points of [`HEX_GAUSS_2X2X2`].
pub const HEX_GAUSS_POINTS: usize = 8;

/// The 2×2×2 Gauss rule, point `a` nearest to hex node `a`; all weights are 1.
pub const HEX_GAUSS_2X2X2: [QuadraturePoint; HEX_GAUSS_POINTS] = {
    let mut pts = [QuadraturePoint {
        xi: [0.0; 3],
        weight: 1.0,
    }; HEX_GAUSS_POINTS];
    let mut a = 0;
    while a < HEX_GAUSS_POINTS {
        let r = HEX8_REFERENCE_NODES[a];
        pts[a].xi = [
            r[0] * GAUSS_2_ABSCISSA,
            r[1] * GAUSS_2_ABSCISSA,
            r[2] * GAUSS_2_ABSCISSA,
        ];
        a += 1;
    }
    pts
};

/// The 3×3×3 Gauss rule (used for the consistent mass, which it integrates exactly on any hex8).
pub const HEX_GAUSS_3X3X3: [QuadraturePoint; 27] = {
    let x = [-GAUSS_3_ABSCISSA, 0.0, GAUSS_3_ABSCISSA];
    let w = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let mut pts = [QuadraturePoint {
        xi: [0.0; 3],
        weight: 0.0,
    }; 27];
    let mut q = 0;
    while q < 27 {
        let (i, j, k) = (q % 3, (q / 3) % 3, q / 9);
        pts[q] = QuadraturePoint {
            xi: [x[i], x[j], x[k]],
            weight: w[i] * w[j] * w[k],
        };
        q += 1;
    }
    pts
};

/// A 2×2 face rule with unit weights whose point `a` lies at quad node `a` scaled by `scale`
/// (the nodes are at ±1, so `scale = 1` puts the points exactly on the nodes).
const fn quad_rule_at_scaled_nodes(scale: f64) -> [FacePoint; 4] {
    let mut pts = [FacePoint {
        st: [0.0; 2],
        weight: 1.0,
    }; 4];
    let mut a = 0;
    while a < 4 {
        let r = QUAD4_REFERENCE_NODES[a];
        pts[a].st = [r[0] * scale, r[1] * scale];
        a += 1;
    }
    pts
}

/// The 2×2 Gauss rule on a face, point `a` nearest to quad node `a`; all weights are 1.
pub const QUAD_GAUSS_2X2: [FacePoint; 4] = quad_rule_at_scaled_nodes(GAUSS_2_ABSCISSA);

/// The 2×2 Newton–Cotes (Lobatto, nodal) rule on a face: point `a` at quad node `a`, all
/// weights 1 (the trapezoidal rule in each direction; exact for degree ≤ 1 in each variable).
/// Used by the interface elements (spec §5.4, eq. (E8)).
pub const QUAD_NEWTON_COTES_2X2: [FacePoint; 4] = quad_rule_at_scaled_nodes(1.0);

#[cfg(test)]
mod tests {
    use super::*;

    fn monomial(xi: &[f64; 3], p: [i32; 3]) -> f64 {
        xi[0].powi(p[0]) * xi[1].powi(p[1]) * xi[2].powi(p[2])
    }

    fn exact_1d(p: i32) -> f64 {
        if p % 2 == 1 {
            0.0
        } else {
            2.0 / (p as f64 + 1.0)
        }
    }

    #[test]
    fn abscissae_are_the_gauss_points() {
        assert!((GAUSS_2_ABSCISSA - (1.0f64 / 3.0).sqrt()).abs() <= f64::EPSILON);
        assert!((GAUSS_3_ABSCISSA - 0.6f64.sqrt()).abs() <= f64::EPSILON);
    }

    #[test]
    fn rules_integrate_their_polynomial_degree_exactly() {
        for (rule, deg) in [(&HEX_GAUSS_2X2X2[..], 3), (&HEX_GAUSS_3X3X3[..], 5)] {
            for px in 0..=deg {
                for py in 0..=deg {
                    for pz in 0..=deg {
                        let p = [px, py, pz];
                        let q: f64 = rule.iter().map(|g| g.weight * monomial(&g.xi, p)).sum();
                        let e = exact_1d(px) * exact_1d(py) * exact_1d(pz);
                        assert!((q - e).abs() < 1e-14, "degree {p:?}: {q} vs {e}");
                    }
                }
            }
        }
        // each face rule integrates every monomial up to its degree per direction exactly
        for (name, rule, degree, tol) in [
            ("Gauss", &QUAD_GAUSS_2X2, 3, 1e-14),
            ("Newton-Cotes", &QUAD_NEWTON_COTES_2X2, 1, 1e-15),
        ] {
            for px in 0..=degree {
                for py in 0..=degree {
                    let q: f64 = rule
                        .iter()
                        .map(|g| g.weight * g.st[0].powi(px) * g.st[1].powi(py))
                        .sum();
                    let e = exact_1d(px) * exact_1d(py);
                    assert!((q - e).abs() < tol, "{name} degree ({px},{py})");
                }
            }
        }
        // Not exact for degree 2: on the square Σ ξ_q² = 4 instead of ∫ ξ² = 4/3.
        let q2: f64 = QUAD_NEWTON_COTES_2X2
            .iter()
            .map(|g| g.weight * g.st[0].powi(2))
            .sum();
        assert!((q2 - 4.0).abs() < 1e-15);
        // the nodal rule sits exactly on the nodes, the Gauss rule at the nodes over √3
        assert_eq!(QUAD_NEWTON_COTES_2X2.map(|g| g.st), QUAD4_REFERENCE_NODES);
        assert_eq!(
            QUAD_GAUSS_2X2.map(|g| g.st),
            QUAD4_REFERENCE_NODES.map(|r| [r[0] * GAUSS_2_ABSCISSA, r[1] * GAUSS_2_ABSCISSA])
        );
    }
}
