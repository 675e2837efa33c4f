//! Local frame `[s, a, n]` of an interface or joint point (spec §5.2, eq. (E3)).
//!
//! Given the unit normal `e_n` of the interface mid-surface, already oriented from face B to
//! face A (see [`crate::element::interface8`]), the in-plane axes are
//!
//! ```text
//! e_a = normalize(e_dam − (e_dam·e_n) e_n)       dam axis projected onto the plane
//! e_s = e_a × e_n                                up-slope direction
//! if e_s·e_up < 0: e_s ← −e_s, e_a ← −e_a         (spec: "flip e_s and e_a together")
//!
//! fallback, ‖e_dam − (e_dam·e_n) e_n‖ < 0.1 (faces nearly normal to the dam axis):
//! e_s = normalize(e_up − (e_up·e_n) e_n),  e_a = e_n × e_s
//!
//! R = [e_sᵀ; e_aᵀ; e_nᵀ],   δ_local = R·Δu      (spec (E4))
//! ```
//!
//! Both branches give a right-handed frame, `e_s × e_a = e_n`.
//!
//! # Ties and orientation facts
//! * **Slope undefined** (|e_s·e_up| ≤ [`SLOPE_TIE_TOLERANCE`]; horizontal faces, and faces whose
//!   up-slope line is the projected dam axis itself, e.g. a 45° abutment face): no flip, so
//!   `e_a` keeps the sense of the projected dam axis (`e_a·e_dam > 0`). Deterministic.
//! * **1:1.4 upstream face.** In the seed's axes (X stream, Y up, Z dam axis) the rule gives the
//!   spec's frame exactly: e_s = (1.4, 1, 0)/√2.96, e_a = +Z, e_n = (1, −1.4, 0)/√2.96. In the
//!   project axes ([`crate::conventions`]: x stream, y dam axis, z up) the same physical frame
//!   is e_s = (1.4, 0, 1)/√2.96, e_n = (1, 0, −1.4)/√2.96 and **e_a = −y**: the seed's axes
//!   (X, Y, Z) map to the project's (x, z, y), a reflection, so a right-handed `[s, a, n]` with
//!   s up-slope and n into the dam has its a-axis along −y. An axial jump reported as positive
//!   along the seed's +Z is therefore `−δ_a` of this code.
//! * The frame is discontinuous where the fallback switches on (spec (E3) as written); it is
//!   meant for faces that are either mostly along the dam axis (slab–cushion) or nearly normal
//!   to it (vertical joints).

use nalgebra::{Matrix3, Vector3};
use thiserror::Error;

/// Threshold of ‖e_dam − (e_dam·e_n) e_n‖ below which the fallback of (E3) is used (spec §5.2).
pub const FALLBACK_THRESHOLD: f64 = 0.1;

/// |e_s·e_up| at or below which the slope is taken as undefined and no flip is made.
pub const SLOPE_TIE_TOLERANCE: f64 = 1e-9;

/// The global reference directions of the frame rule (E3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameAxes {
    /// Unit vector of the dam axis, e_dam (the seed's Z, the project's y).
    pub dam_axis: Vector3<f64>,
    /// Unit vector pointing up, e_up (the seed's Y, the project's z).
    pub up: Vector3<f64>,
}

impl Default for FrameAxes {
    /// The project axes ([`crate::conventions`]): dam axis `y`, up `z`.
    fn default() -> Self {
        FrameAxes {
            dam_axis: Vector3::y(),
            up: Vector3::z(),
        }
    }
}

/// Invalid reference directions for the frame rule.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
#[error("frame axes must be two orthogonal non-zero vectors (dam axis {dam_axis:?}, up {up:?})")]
pub struct InvalidFrameAxes {
    /// The dam axis given.
    pub dam_axis: [f64; 3],
    /// The up direction given.
    pub up: [f64; 3],
}

impl FrameAxes {
    /// Normalized axes; fails unless both are finite, non-zero and orthogonal (|cos| ≤ 10⁻⁹).
    pub fn new(dam_axis: [f64; 3], up: [f64; 3]) -> Result<Self, InvalidFrameAxes> {
        let err = InvalidFrameAxes { dam_axis, up };
        let (d, u) = (Vector3::from(dam_axis), Vector3::from(up));
        let (nd, nu) = (d.norm(), u.norm());
        if !(nd.is_finite() && nu.is_finite() && nd > 0.0 && nu > 0.0) {
            return Err(err);
        }
        let (d, u) = (d / nd, u / nu);
        if d.dot(&u).abs() > 1e-9 {
            return Err(err);
        }
        Ok(FrameAxes { dam_axis: d, up: u })
    }
}

/// Orthonormal right-handed local frame `[s, a, n]` of one interface point (spec (E3)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFrame {
    /// Slope direction e_s (up-slope; in-plane).
    pub s: Vector3<f64>,
    /// Axial direction e_a (dam axis projected on the plane, up to sign; in-plane).
    pub a: Vector3<f64>,
    /// Normal e_n, from face B to face A.
    pub n: Vector3<f64>,
}

impl LocalFrame {
    /// The frame of (E3) for the unit normal `n` (oriented from face B to face A).
    pub fn from_normal(n: &Vector3<f64>, axes: &FrameAxes) -> LocalFrame {
        let a_proj = axes.dam_axis - axes.dam_axis.dot(n) * n;
        let a_norm = a_proj.norm();
        if a_norm >= FALLBACK_THRESHOLD {
            let a = a_proj / a_norm;
            let s = a.cross(n);
            if s.dot(&axes.up) < -SLOPE_TIE_TOLERANCE {
                LocalFrame { s: -s, a: -a, n: *n }
            } else {
                LocalFrame { s, a, n: *n }
            }
        } else {
            // Here (e_dam·e_n)² > 1 − 0.1², and e_up ⟂ e_dam gives (e_up·e_n)² ≤ 1 − (e_dam·e_n)²,
            // so |e_up − (e_up·e_n)e_n|² = 1 − (e_up·e_n)² > 0.99: the projection cannot vanish.
            let s_proj = axes.up - axes.up.dot(n) * n;
            let s = s_proj / s_proj.norm();
            LocalFrame {
                s,
                a: n.cross(&s),
                n: *n,
            }
        }
    }

    /// Rotation R = [e_sᵀ; e_aᵀ; e_nᵀ] from global to local components (spec §5.2).
    pub fn rotation(&self) -> Matrix3<f64> {
        Matrix3::from_rows(&[self.s.transpose(), self.a.transpose(), self.n.transpose()])
    }

    /// Local components `R·v` of a global vector.
    pub fn to_local(&self, v: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(self.s.dot(v), self.a.dot(v), self.n.dot(v))
    }

    /// Global components `Rᵀ·t` of a local vector.
    pub fn to_global(&self, t: &Vector3<f64>) -> Vector3<f64> {
        self.s * t[0] + self.a * t[1] + self.n * t[2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_orthonormal_right_handed(f: &LocalFrame) {
        let r = f.rotation();
        assert!(
            (r * r.transpose() - Matrix3::identity()).amax() < 1e-14,
            "R Rᵀ ≠ I: {r}"
        );
        assert!(
            (r.determinant() - 1.0).abs() < 1e-14,
            "det R = {}",
            r.determinant()
        );
        assert!((f.s.cross(&f.a) - f.n).amax() < 1e-14, "s × a ≠ n");
    }

    #[test]
    fn slope_face_in_seed_axes_is_the_spec_frame() {
        // Seed axes: X stream, Y up, Z dam axis; 1:1.4 upstream face, n into the dam.
        let axes = FrameAxes::new([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]).expect("valid");
        let r = 2.96f64.sqrt();
        let n = Vector3::new(1.0, -1.4, 0.0) / r;
        let f = LocalFrame::from_normal(&n, &axes);
        println!(
            "seed axes 1:1.4: e_s = {:?}, e_a = {:?}, e_n = {:?}",
            f.s, f.a, f.n
        );
        assert!((f.s - Vector3::new(1.4, 1.0, 0.0) / r).amax() < 1e-15);
        assert!((f.a - Vector3::z()).amax() < 1e-15);
        assert_orthonormal_right_handed(&f);
    }

    #[test]
    fn slope_face_in_project_axes_has_a_along_minus_y() {
        let r = 2.96f64.sqrt();
        let n = Vector3::new(1.0, 0.0, -1.4) / r;
        let f = LocalFrame::from_normal(&n, &FrameAxes::default());
        println!(
            "project axes 1:1.4: e_s = {:?}, e_a = {:?}, e_n = {:?}",
            f.s, f.a, f.n
        );
        assert!((f.s - Vector3::new(1.4, 0.0, 1.0) / r).amax() < 1e-15);
        assert!((f.a + Vector3::y()).amax() < 1e-15);
        assert!(f.s.z > 0.0);
        assert_orthonormal_right_handed(&f);
    }

    #[test]
    fn horizontal_face_keeps_the_dam_axis_sense_and_vertical_joint_uses_the_fallback() {
        let axes = FrameAxes::default();
        for nz in [1.0, -1.0] {
            let f = LocalFrame::from_normal(&Vector3::new(0.0, 0.0, nz), &axes);
            println!("horizontal n = {nz:+}z: e_s = {:?}, e_a = {:?}", f.s, f.a);
            assert_eq!(f.a, Vector3::y());
            assert_orthonormal_right_handed(&f);
        }
        // Vertical joint: normal along ±y (the dam axis); e_s = up, e_a = n × up.
        for ny in [1.0, -1.0] {
            let n = Vector3::new(0.0, ny, 0.0);
            let f = LocalFrame::from_normal(&n, &axes);
            println!("vertical joint n = {ny:+}y: e_s = {:?}, e_a = {:?}", f.s, f.a);
            assert_eq!(f.s, Vector3::z());
            assert_eq!(f.a, n.cross(&Vector3::z()));
            assert_orthonormal_right_handed(&f);
        }
    }

    #[test]
    fn frame_is_orthonormal_with_up_slope_s_for_many_normals() {
        let axes = FrameAxes::default();
        let mut fallbacks = 0;
        for i in 0..40 {
            for j in 0..20 {
                let (phi, theta) = (i as f64 * 0.157 + 0.01, j as f64 * 0.157 + 0.003);
                let n = Vector3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
                let f = LocalFrame::from_normal(&n, &axes);
                assert_orthonormal_right_handed(&f);
                assert!(
                    f.s.dot(&axes.up) >= -SLOPE_TIE_TOLERANCE,
                    "s points down for n = {n}"
                );
                if (axes.dam_axis - axes.dam_axis.dot(&n) * n).norm() < FALLBACK_THRESHOLD {
                    fallbacks += 1;
                }
            }
        }
        println!("800 normals checked, {fallbacks} through the fallback");
        assert!(fallbacks > 0);
    }

    #[test]
    fn invalid_axes_are_rejected() {
        assert!(FrameAxes::new([0.0, 1.0, 0.0], [0.0, 1.0, 1.0]).is_err());
        assert!(FrameAxes::new([0.0; 3], [0.0, 0.0, 1.0]).is_err());
        assert!(FrameAxes::new([f64::NAN, 1.0, 0.0], [0.0, 0.0, 1.0]).is_err());
        let ok = FrameAxes::new([0.0, 2.0, 0.0], [0.0, 0.0, 3.0]).expect("orthogonal");
        assert_eq!(ok, FrameAxes::default());
    }
}
