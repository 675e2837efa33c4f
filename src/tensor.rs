//! Small fixed-size tensors in Voigt notation (see [`crate::conventions`]).
//!
//! Voigt order is `[xx, yy, zz, xy, yz, zx]`. Strain-like vectors carry engineering shear
//! (γ = 2ε), so that σᵀε is the work density. Stress and strain are **tension positive**.
//! The newtypes keep stress, strain and tangent from being mixed up.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use serde::{Deserialize, Serialize};

/// Plain 6-vector used inside the newtypes.
pub type Vector6 = SVector<f64, 6>;
/// Plain 6×6 matrix used inside [`Tangent6`].
pub type Matrix6 = SMatrix<f64, 6, 6>;

/// Stress in Voigt order `[σxx, σyy, σzz, σxy, σyz, σzx]`, Pa, tension positive.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Stress6(pub Vector6);

/// Strain in Voigt order `[εxx, εyy, εzz, γxy, γyz, γzx]` with engineering shear, tension positive.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Strain6(pub Vector6);

/// Material tangent dσ/dε in Voigt form (Pa), mapping [`Strain6`] to [`Stress6`].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Tangent6(pub Matrix6);

/// Interface jump or traction in the local frame `[s, a, n]` (see [`crate::conventions`]).
pub type Local3 = Vector3<f64>;
/// Interface tangent dT/dδ in the local frame (Pa/m).
pub type Tangent3 = Matrix3<f64>;

impl Stress6 {
    /// Isotropic stress `σ = s·I` (tension positive: a compressive pressure p gives `s = −p`).
    pub fn isotropic(s: f64) -> Self {
        Stress6(Vector6::new(s, s, s, 0.0, 0.0, 0.0))
    }
    /// Full symmetric 3×3 matrix.
    pub fn to_matrix(&self) -> Matrix3<f64> {
        let v = &self.0;
        Matrix3::new(v[0], v[3], v[5], v[3], v[1], v[4], v[5], v[4], v[2])
    }
    /// From a symmetric 3×3 matrix (the upper triangle is read).
    pub fn from_matrix(m: &Matrix3<f64>) -> Self {
        Stress6(Vector6::new(
            m[(0, 0)],
            m[(1, 1)],
            m[(2, 2)],
            m[(0, 1)],
            m[(1, 2)],
            m[(0, 2)],
        ))
    }
}

impl Strain6 {
    /// Full symmetric strain tensor (tensorial shear ε = γ/2).
    pub fn to_matrix(&self) -> Matrix3<f64> {
        let v = &self.0;
        Matrix3::new(
            v[0],
            0.5 * v[3],
            0.5 * v[5],
            0.5 * v[3],
            v[1],
            0.5 * v[4],
            0.5 * v[5],
            0.5 * v[4],
            v[2],
        )
    }
    /// From a symmetric strain tensor (engineering shear γ = 2ε is stored).
    pub fn from_matrix(m: &Matrix3<f64>) -> Self {
        Strain6(Vector6::new(
            m[(0, 0)],
            m[(1, 1)],
            m[(2, 2)],
            2.0 * m[(0, 1)],
            2.0 * m[(1, 2)],
            2.0 * m[(0, 2)],
        ))
    }
}

/// Rotation of Voigt stress under the orthogonal map `R` (σ' = R σ Rᵀ).
pub fn rotate_stress(r: &Matrix3<f64>, s: &Stress6) -> Stress6 {
    Stress6::from_matrix(&(r * s.to_matrix() * r.transpose()))
}

/// Rotation of Voigt strain under the orthogonal map `R` (ε' = R ε Rᵀ).
pub fn rotate_strain(r: &Matrix3<f64>, e: &Strain6) -> Strain6 {
    Strain6::from_matrix(&(r * e.to_matrix() * r.transpose()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    #[test]
    fn matrix_round_trip_and_rotation_preserves_work() {
        let s = Stress6(Vector6::new(1.0, -2.0, 3.0, 0.5, -0.25, 0.75));
        let e = Strain6(Vector6::new(1e-3, 2e-3, -1e-3, 4e-4, -2e-4, 6e-4));
        assert_eq!(Stress6::from_matrix(&s.to_matrix()), s);
        let back = Strain6::from_matrix(&e.to_matrix());
        assert!((back.0 - e.0).norm() < 1e-18);
        let r = *Rotation3::from_euler_angles(0.3, -0.7, 1.1).matrix();
        let w0 = s.0.dot(&e.0);
        let w1 = rotate_stress(&r, &s).0.dot(&rotate_strain(&r, &e).0);
        assert!((w0 - w1).abs() < 1e-14, "{w0} vs {w1}");
    }
}
