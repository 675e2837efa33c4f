//! Lagrange shape functions of the 8-node trilinear hexahedron and the 4-node bilinear
//! quadrilateral (its faces), in the reference coordinates `ξ, η, ζ ∈ [−1, 1]`.
//!
//! Node order is Gmsh's (see the drawing in [`crate::element::hex8`]).
//!
//! ```text
//! hex8:  N_a(ξ, η, ζ) = ⅛ (1 + ξ_a ξ)(1 + η_a η)(1 + ζ_a ζ),   a = 0..7
//! quad4: N_a(s, t)    = ¼ (1 + s_a s)(1 + t_a t),              a = 0..3
//! ```
//! with `(ξ_a, η_a, ζ_a)` the reference corner of node `a`
//! ([`HEX8_REFERENCE_NODES`], [`QUAD4_REFERENCE_NODES`]).

/// Reference coordinates `(ξ_a, η_a, ζ_a)` of the 8 hex nodes, Gmsh order.
pub const HEX8_REFERENCE_NODES: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// Reference coordinates `(s_a, t_a)` of the 4 quad nodes (counter-clockwise).
pub const QUAD4_REFERENCE_NODES: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Trilinear shape functions `N_a(ξ)` of the hex8 at the reference point `xi = (ξ, η, ζ)`.
pub fn hex8_shape(xi: &[f64; 3]) -> [f64; 8] {
    HEX8_REFERENCE_NODES.map(|r| 0.125 * (1.0 + r[0] * xi[0]) * (1.0 + r[1] * xi[1]) * (1.0 + r[2] * xi[2]))
}

/// Derivatives `∂N_a/∂ξ_j` of the hex8 shape functions (row `a`, column `j`).
///
/// ```text
/// ∂N_a/∂ξ = ⅛ ξ_a (1 + η_a η)(1 + ζ_a ζ), and cyclically for η, ζ
/// ```
pub fn hex8_shape_derivatives(xi: &[f64; 3]) -> [[f64; 3]; 8] {
    HEX8_REFERENCE_NODES.map(|r| {
        let a = 1.0 + r[0] * xi[0];
        let b = 1.0 + r[1] * xi[1];
        let c = 1.0 + r[2] * xi[2];
        [0.125 * r[0] * b * c, 0.125 * a * r[1] * c, 0.125 * a * b * r[2]]
    })
}

/// Bilinear shape functions `N_a(s, t)` of the quad4 at `st = (s, t)`.
pub fn quad4_shape(st: &[f64; 2]) -> [f64; 4] {
    QUAD4_REFERENCE_NODES.map(|r| 0.25 * (1.0 + r[0] * st[0]) * (1.0 + r[1] * st[1]))
}

/// Derivatives `∂N_a/∂s`, `∂N_a/∂t` of the quad4 shape functions (row `a`).
pub fn quad4_shape_derivatives(st: &[f64; 2]) -> [[f64; 2]; 4] {
    QUAD4_REFERENCE_NODES.map(|r| {
        [
            0.25 * r[0] * (1.0 + r[1] * st[1]),
            0.25 * (1.0 + r[0] * st[0]) * r[1],
        ]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const POINTS: [[f64; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [0.3, -0.7, 0.11],
        [-0.95, 0.42, 0.8],
        [1.0, -1.0, 0.5],
    ];

    #[test]
    fn hex8_partition_of_unity_and_kronecker_property() {
        for p in POINTS {
            let n = hex8_shape(&p);
            let s: f64 = n.iter().sum();
            assert!((s - 1.0).abs() < 1e-15, "sum N = {s} at {p:?}");
            let d = hex8_shape_derivatives(&p);
            for j in 0..3 {
                let sd: f64 = d.iter().map(|r| r[j]).sum();
                assert!(sd.abs() < 1e-15, "sum dN/dxi_{j} = {sd}");
            }
        }
        for (a, r) in HEX8_REFERENCE_NODES.iter().enumerate() {
            let n = hex8_shape(r);
            for (b, nb) in n.iter().enumerate() {
                let expect = if a == b { 1.0 } else { 0.0 };
                assert_eq!(*nb, expect, "N_{b} at node {a}");
            }
        }
    }

    #[test]
    fn hex8_derivatives_match_central_differences() {
        let h = 1e-6;
        for p in POINTS {
            let d = hex8_shape_derivatives(&p);
            for j in 0..3 {
                let mut pp = p;
                let mut pm = p;
                pp[j] += h;
                pm[j] -= h;
                let (np, nm) = (hex8_shape(&pp), hex8_shape(&pm));
                for a in 0..8 {
                    let fd = (np[a] - nm[a]) / (2.0 * h);
                    assert!(
                        (fd - d[a][j]).abs() < 1e-9,
                        "node {a} dir {j}: {fd} vs {}",
                        d[a][j]
                    );
                }
            }
        }
    }

    #[test]
    fn quad4_partition_of_unity_and_derivatives() {
        let h = 1e-6;
        for p in [[0.0, 0.0], [0.4, -0.8], [-1.0, 0.3]] {
            let n = quad4_shape(&p);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            let d = quad4_shape_derivatives(&p);
            for j in 0..2 {
                let mut pp = p;
                let mut pm = p;
                pp[j] += h;
                pm[j] -= h;
                let (np, nm) = (quad4_shape(&pp), quad4_shape(&pm));
                for a in 0..4 {
                    let fd = (np[a] - nm[a]) / (2.0 * h);
                    assert!((fd - d[a][j]).abs() < 1e-9, "node {a} dir {j}");
                }
            }
        }
        for (a, r) in QUAD4_REFERENCE_NODES.iter().enumerate() {
            assert_eq!(quad4_shape(r)[a], 1.0);
        }
    }
}
