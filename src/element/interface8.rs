//! The 8-node (4+4) zero-thickness interface element of Goodman type (spec §5): geometry,
//! local frame per point, B matrix, jumps, internal force and tangent stiffness. The same
//! element, with the joint law, is the slab joint element (spec §6).
//!
//! # Numbering
//!
//! ```text
//!      face A (nodes 4..7, cushion / dam side, "+")       7 ------------- 6
//!                                                        /               /         e_n (B → A)
//!                                                       4 ------------- 5              ^
//!                                                                                      |
//!      zero thickness: x_{a+4} = x_a                      3 ------------- 2             |
//!                                                        /               /      η      |
//!      face B (nodes 0..3, slab side, "−")              0 ------------- 1   ---> ξ   (η into the page)
//!
//!   node a and its pair a+4 sit at (ξ_a, η_a) = (−1,−1), (+1,−1), (+1,+1), (−1,+1), a = 0..3
//!   (the quad4 order of [`crate::element::shape::QUAD4_REFERENCE_NODES`]).
//! ```
//!
//! Both faces are numbered in the same rotational sense and node `a + 4` pairs with node `a`
//! (spec §5.1). Element DOFs are node by node, `[u0x, u0y, u0z, …, u7z]`, as for the hex8.
//! The spec numbers the slab face 1–4 and the cushion face 5–8; here they are 0–3 and 4–7.
//!
//! # Kinematics (spec (E1)–(E5))
//!
//! ```text
//! N_a(ξ, η) = ¼(1 + ξ_a ξ)(1 + η_a η)                           (E1)
//! x_m = Σ_a N_a (x_a + x_{a+4})/2,  g1 = ∂x_m/∂ξ,  g2 = ∂x_m/∂η,  dA = ‖g1 × g2‖ dξ dη   (E2)
//! Δu = Σ_a N_a (u_{a+4} − u_a)      (face A relative to face B: cushion relative to slab)
//! δ = (δ_s, δ_a, δ_n) = R Δu = B u_e,  B = R [−N_0 I₃ … −N_3 I₃  +N_0 I₃ … +N_3 I₃]   (E4), (E5)
//! ```
//!
//! `R = [e_sᵀ; e_aᵀ; e_nᵀ]` is the frame of (E3) at each integration point
//! ([`crate::element::interface_frame`]). The normal is `±(g1 × g2)/‖g1 × g2‖`, its sign fixed
//! once per element so that the normal at the element centre has a positive component along
//! the caller's `n_ref`, the direction **from face B to face A** (spec §5.2: from the slab into
//! the cushion/dam, e.g. `n_ref` = "into the dam"); every point then takes the sign that agrees
//! with the centre normal. δ_n > 0 is opening.
//!
//! The faces need not coincide: the mid-surface is the average of both. Rigid rotations give
//! δ = 0 only for coincident pairs (the zero-thickness element of spec §5.1); with a finite gap
//! `h` between pairs a rotation ω gives δ = R (ω × h).
//!
//! # Traction, internal force and stiffness (spec (E6), (E7))
//! The interface law maps the local jump δ to the traction `T = (τ_s, τ_a, t_n)` (Pa, t_n = −σ_n
//! tension positive) and its tangent `D = dT/dδ` (Pa/m, possibly non-symmetric); this is the
//! [`crate::material::InterfaceModel`] contract, in which the sign matrix S and, for the GP
//! interface, the thickness t are already applied (`T = S s`, `D = S D^ep S / t`, spec (E7)).
//!
//! ```text
//! δW_int = ∫_Γ δ(δ)ᵀ T dA   ⇒   f_int = Σ_q B_qᵀ T_q w_q ‖g1 × g2‖_q              (N)
//! K = ∂f_int/∂u_e = Σ_q B_qᵀ D_q B_q w_q ‖g1 × g2‖_q                                (N/m)
//! ```
//!
//! # Integration rule (spec §5.4, (E8))
//! [`InterfaceRule::NewtonCotes`] (default): 2×2 nodal (Lobatto) points at the node pairs,
//! weights 1; point `q` sits at node pair `q`, so each point sees only its own pair's jump and
//! the stiffness is "lumped". [`InterfaceRule::Gauss2x2`]: 2×2 Gauss points, point `q` nearest
//! to pair `q`; kept for comparison (it produces traction oscillations with stiff penalty
//! laws, test EL-2).
//!
//! With the nodal rule the nodal force of pair `a` under a uniform traction T on a planar face
//! is `Rᵀ T ‖g1 × g2‖(ξ_a, η_a)`: the tributary area of the rule, equal to A/4 on a
//! parallelogram; the Gauss rule gives the consistent `Rᵀ T ∫ N_a dA`. Both sum to `Rᵀ T A`.
//!
//! # Joints (spec §6)
//! Spec §6.1 defines the joint element as "the same 8-node zero-thickness geometry as §5, with
//! nodal integration", so there is no separate joint kernel: a joint is this element with the
//! joint law ([`crate::material::joint::JointLaw`]) and [`InterfaceRule::NewtonCotes`].
//!
//! The joint law is isotropic in shear (one k_s), so the choice of the two in-plane axes does
//! not change the mechanics, only the labels of the two shear outputs:
//! * **Vertical joint** (normal ≈ ±dam axis): the frame rule takes its fallback,
//!   e_s = e_up projected on the joint plane, e_a = e_n × e_s. With the default axes that is the
//!   vertical, not the slab's up-slope line. To get §6.1's frame (e_1 = up-slope direction of
//!   the slab, e_2 = slab normal) pass `FrameAxes::new(dam_axis, slab_up_slope)`, the slab's
//!   unit up-slope vector as "up" (it is orthogonal to the dam axis): then e_s = e_1 and
//!   e_a = e_n × e_1 = ±e_2 (test `joint_frame_follows_the_slab_slope`).
//! * **Perimeter joint** on the river bed (joint line along the dam axis, normal ≈ slab
//!   up-slope): the main branch gives e_a = ±dam axis (along the joint) and e_s ≈ the slab
//!   normal, i.e. §6.2's (e_1, e_2) = (e_a, e_s), swapped. On the abutments the joint line turns
//!   and the labels follow the rule; project the global jump on the wanted directions for
//!   output (spec §6.2: opening, settlement, shear).
//!
//! # Use by a solver (spec §5.5, §8.1)
//! The geometry is built once per element from the reference coordinates (small displacements,
//! spec §5.5). [`Interface8Geometry::evaluate`] takes an element displacement vector and a
//! closure `(point, δ, frame) → (T, D)`. Because δ = B u_e is linear in u_e, the same call
//! serves the total jump (u_e measured from the activation displacement d_e,ref, spec (E9)) and
//! the step increment: a static solver passes the step increment Δu_e and the closure calls
//! `model.update(&committed[point], δ)`, storing the trial state (as `solver::solid` does for
//! hex8 blocks). The kernel allocates nothing.

use crate::element::hex8::{Coords8, Matrix24, Vector24};
use crate::element::interface_frame::{FrameAxes, LocalFrame};
use crate::element::quadrature::{FacePoint, QUAD_GAUSS_2X2, QUAD_NEWTON_COTES_2X2};
use crate::element::shape::{quad4_shape, quad4_shape_derivatives};
use crate::tensor::{Local3, Tangent3};
use nalgebra::{SMatrix, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Number of integration points of either rule.
pub const INTERFACE_POINTS: usize = 4;

/// Interface strain–displacement matrix at one point (3 × 24): δ = B u_e (spec (E5)).
pub type InterfaceBMatrix = SMatrix<f64, 3, 24>;

/// Smallest ‖g1 × g2‖ accepted, relative to the squared longer mid-surface diagonal.
pub const DEGENERATE_AREA_RATIO: f64 = 1e-10;

/// Smallest |cos| accepted between the centre normal and the orientation vector `n_ref`.
pub const MIN_REFERENCE_COSINE: f64 = 1e-3;

/// Integration rule of the interface element (spec §5.4, eq. (E8)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum InterfaceRule {
    /// 2×2 nodal Newton–Cotes (Lobatto) points, one per node pair (default, spec (E8)).
    #[default]
    NewtonCotes,
    /// 2×2 Gauss points (comparison option; oscillates with stiff laws, spec §5.4).
    #[serde(rename = "gauss2x2")]
    Gauss2x2,
}

impl InterfaceRule {
    /// The 4 points of the rule on the reference square, point `q` at or nearest to pair `q`.
    pub fn points(&self) -> &'static [FacePoint; INTERFACE_POINTS] {
        match self {
            InterfaceRule::NewtonCotes => &QUAD_NEWTON_COTES_2X2,
            InterfaceRule::Gauss2x2 => &QUAD_GAUSS_2X2,
        }
    }
}

/// An interface element whose geometry cannot be used.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum InterfaceGeometryError {
    /// The mid-surface is degenerate at an integration point (collapsed edge or zero area).
    #[error(
        "degenerate interface mid-surface at integration point {point}: |g1 x g2| = {area_density:.3e} m2"
    )]
    Degenerate {
        /// Integration point (0..4).
        point: usize,
        /// ‖g1 × g2‖ found there (m²).
        area_density: f64,
    },
    /// The mid-surface is degenerate at the element centre.
    #[error("degenerate interface mid-surface at the element centre: |g1 x g2| = {area_density:.3e} m2")]
    DegenerateCentre {
        /// ‖g1 × g2‖ at the centre (m²).
        area_density: f64,
    },
    /// The orientation vector is (nearly) in the interface plane, or not a finite vector.
    #[error("orientation vector n_ref is (nearly) in the interface plane or invalid: |cos| = {cosine:.3e}")]
    ReferenceInPlane {
        /// |cos| of the angle between n_ref and the centre normal.
        cosine: f64,
    },
    /// The normal at an integration point opposes the normal at the centre (folded element).
    #[error("folded interface element: the normal at integration point {point} opposes the centre normal")]
    Folded {
        /// Integration point (0..4).
        point: usize,
    },
}

/// Jump and traction at one integration point, for output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointResult {
    /// Local jump δ = (δ_s, δ_a, δ_n) passed to the law (m).
    pub jump: Local3,
    /// Local traction T = (τ_s, τ_a, t_n) returned by the law (Pa).
    pub traction: Local3,
}

/// What [`Interface8Geometry::evaluate`] returns.
#[derive(Debug, Clone, PartialEq)]
pub struct InterfaceResponse {
    /// Internal force f_int (N).
    pub f_int: Vector24,
    /// Tangent stiffness K = ∂f_int/∂u_e (N/m), non-symmetric when a D is.
    pub k: Matrix24,
    /// Jump and traction at each integration point.
    pub points: [PointResult; INTERFACE_POINTS],
}

/// Geometry of one interface element at the points of its rule: shape values, local frames
/// and `w ‖g1 × g2‖`. Built once per element from the reference coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interface8Geometry {
    /// The integration rule.
    pub rule: InterfaceRule,
    /// `N_a` at each point: `shape[q][a]`.
    pub shape: [[f64; 4]; INTERFACE_POINTS],
    /// Local frame `[s, a, n]` at each point (spec (E3)).
    pub frames: [LocalFrame; INTERFACE_POINTS],
    /// `w_q ‖g1 × g2‖_q` at each point (m²); their sum is the mid-surface area.
    pub area_w: [f64; INTERFACE_POINTS],
    /// Mid-surface position of each point (m).
    pub positions: [[f64; 3]; INTERFACE_POINTS],
}

/// Mid-surface covariant base vectors `g1 = ∂x_m/∂ξ`, `g2 = ∂x_m/∂η` and position at `st`.
fn mid_surface(xm: &[Vector3<f64>; 4], st: &[f64; 2]) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let n = quad4_shape(st);
    let dn = quad4_shape_derivatives(st);
    let mut g1 = Vector3::zeros();
    let mut g2 = Vector3::zeros();
    let mut x = Vector3::zeros();
    for a in 0..4 {
        g1 += xm[a] * dn[a][0];
        g2 += xm[a] * dn[a][1];
        x += xm[a] * n[a];
    }
    (g1, g2, x)
}

impl Interface8Geometry {
    /// Builds the geometry of the element with node coordinates `x` (face B = nodes 0..3,
    /// face A = nodes 4..7), orientation vector `n_ref` (from face B towards face A), frame
    /// axes `axes` and integration rule `rule` (spec (E1)–(E3)).
    pub fn new(
        x: &Coords8,
        n_ref: &[f64; 3],
        axes: &FrameAxes,
        rule: InterfaceRule,
    ) -> Result<Self, InterfaceGeometryError> {
        let xm: [Vector3<f64>; 4] =
            std::array::from_fn(|a| (Vector3::from(x[a]) + Vector3::from(x[a + 4])) * 0.5);
        let scale = (xm[2] - xm[0]).norm_squared().max((xm[3] - xm[1]).norm_squared());
        let min_area = DEGENERATE_AREA_RATIO * scale;

        let (g1, g2, _) = mid_surface(&xm, &[0.0, 0.0]);
        let c = g1.cross(&g2);
        let c_norm = c.norm();
        if !(c_norm.is_finite() && c_norm > min_area) {
            return Err(InterfaceGeometryError::DegenerateCentre { area_density: c_norm });
        }
        let n_centre = c / c_norm;
        let r = Vector3::from(*n_ref);
        let cosine = n_centre.dot(&r) / r.norm();
        if !(cosine.is_finite() && cosine.abs() >= MIN_REFERENCE_COSINE) {
            return Err(InterfaceGeometryError::ReferenceInPlane { cosine: cosine.abs() });
        }
        let sign = cosine.signum();
        let n_centre = n_centre * sign;

        let mut geo = Interface8Geometry {
            rule,
            shape: [[0.0; 4]; INTERFACE_POINTS],
            frames: [LocalFrame::from_normal(&n_centre, axes); INTERFACE_POINTS],
            area_w: [0.0; INTERFACE_POINTS],
            positions: [[0.0; 3]; INTERFACE_POINTS],
        };
        for (q, point) in rule.points().iter().enumerate() {
            let (g1, g2, xq) = mid_surface(&xm, &point.st);
            let c = g1.cross(&g2);
            let area_density = c.norm();
            if !(area_density.is_finite() && area_density > min_area) {
                return Err(InterfaceGeometryError::Degenerate {
                    point: q,
                    area_density,
                });
            }
            let n = c * (sign / area_density);
            if n.dot(&n_centre) <= 0.0 {
                return Err(InterfaceGeometryError::Folded { point: q });
            }
            geo.shape[q] = quad4_shape(&point.st);
            geo.frames[q] = LocalFrame::from_normal(&n, axes);
            geo.area_w[q] = point.weight * area_density;
            geo.positions[q] = xq.into();
        }
        Ok(geo)
    }

    /// Mid-surface area `Σ_q w_q ‖g1 × g2‖_q` (m²). Exact with either rule for any planar
    /// quadrilateral, where ‖g1 × g2‖ is linear in ξ and η.
    pub fn area(&self) -> f64 {
        self.area_w.iter().sum()
    }

    /// B matrix at point `q` (spec (E5)): δ_q = B_q u_e.
    pub fn b_matrix(&self, q: usize) -> InterfaceBMatrix {
        let rot = self.frames[q].rotation();
        let mut b = InterfaceBMatrix::zeros();
        for a in 0..4 {
            let na = self.shape[q][a];
            for i in 0..3 {
                for j in 0..3 {
                    b[(i, 3 * a + j)] = -na * rot[(i, j)];
                    b[(i, 3 * (a + 4) + j)] = na * rot[(i, j)];
                }
            }
        }
        b
    }

    /// Relative displacement Δu = Σ_a N_a (u_{a+4} − u_a) at point `q`, global components (m).
    pub fn relative_displacement(&self, q: usize, u: &Vector24) -> Vector3<f64> {
        let mut du = Vector3::zeros();
        for a in 0..4 {
            let na = self.shape[q][a];
            for i in 0..3 {
                du[i] += na * (u[3 * (a + 4) + i] - u[3 * a + i]);
            }
        }
        du
    }

    /// Local jumps δ_q = R_q Δu_q at the 4 points (spec (E4)).
    pub fn jumps(&self, u: &Vector24) -> [Local3; INTERFACE_POINTS] {
        std::array::from_fn(|q| self.frames[q].to_local(&self.relative_displacement(q, u)))
    }

    /// Internal force from the local tractions at the 4 points (spec (E7)):
    ///
    /// ```text
    /// f_int = Σ_q B_qᵀ T_q w_q ‖g1 × g2‖_q:   f_{a+4} = +Σ_q N_a(q) R_qᵀ T_q w_q ‖g1 × g2‖_q,  f_a = −f_{a+4}
    /// ```
    pub fn internal_force(&self, tractions: &[Local3; INTERFACE_POINTS]) -> Vector24 {
        let mut f = Vector24::zeros();
        for q in 0..INTERFACE_POINTS {
            let g = self.frames[q].to_global(&tractions[q]) * self.area_w[q];
            for a in 0..4 {
                let na = self.shape[q][a];
                for i in 0..3 {
                    f[3 * (a + 4) + i] += na * g[i];
                    f[3 * a + i] -= na * g[i];
                }
            }
        }
        f
    }

    /// Stiffness from the local tangents D_q = dT/dδ at the 4 points (spec (E7)); D need not be
    /// symmetric.
    ///
    /// ```text
    /// K = Σ_q B_qᵀ D_q B_q w_q ‖g1 × g2‖_q
    /// ```
    pub fn stiffness(&self, tangents: &[Tangent3; INTERFACE_POINTS]) -> Matrix24 {
        let mut k = Matrix24::zeros();
        for q in 0..INTERFACE_POINTS {
            let b = self.b_matrix(q);
            let db: InterfaceBMatrix = tangents[q] * b;
            k.gemm_tr(self.area_w[q], &b, &db, 1.0);
        }
        k
    }

    /// Evaluates the element for the displacement vector `u` (total since activation, or the
    /// step increment; see the module docs): computes the jump at each point, calls
    /// `law(point, δ, frame)` for the traction and tangent, and returns f_int, K and the
    /// per-point jumps and tractions. The first error of `law` is returned unchanged.
    pub fn evaluate<F, E>(&self, u: &Vector24, mut law: F) -> Result<InterfaceResponse, E>
    where
        F: FnMut(usize, &Local3, &LocalFrame) -> Result<(Local3, Tangent3), E>,
    {
        let jumps = self.jumps(u);
        let mut tractions = [Local3::zeros(); INTERFACE_POINTS];
        let mut tangents = [Tangent3::zeros(); INTERFACE_POINTS];
        for q in 0..INTERFACE_POINTS {
            let (t, d) = law(q, &jumps[q], &self.frames[q])?;
            tractions[q] = t;
            tangents[q] = d;
        }
        Ok(InterfaceResponse {
            f_int: self.internal_force(&tractions),
            k: self.stiffness(&tangents),
            points: std::array::from_fn(|q| PointResult {
                jump: jumps[q],
                traction: tractions[q],
            }),
        })
    }
}

#[cfg(test)]
#[path = "interface8_tests.rs"]
mod tests;
