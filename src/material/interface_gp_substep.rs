//! Explicit modified-Euler substepping with error control for the GP interface (spec §8.2).
//!
//! The scheme is generic over [`SubstepModel`], a small "model functions" interface, so that it
//! can later be unified with the generic GP integrator of the rockfill model
//! (`gp_integrator.rs`). The model supplies the branch decision at a substep start (where the
//! interface applies its reversal rule, spec (I18)), the forward-Euler rate with a frozen branch,
//! the error norm and the post-step rules (history updates, opening test).
//!
//! ```text
//! T = 0; dT = 1
//! while T < 1:
//!     dε = dT·Δε
//!     (κ0, br) = begin(κ, dε)              # branch frozen for both stages
//!     Δ1 = rate(κ0, br, dε)
//!     Δ2 = rate(κ0 + Δ1, br, dε)           # a branch flip at κ0 + Δ1 rejects the substep
//!     κ̃ = κ0 + ½(Δ1 + Δ2);  R = err(κ̃, Δ1, Δ2)
//!     R ≤ STOL: accept (post-step rules), T += dT, q = min(0.9·√(STOL/R), 1.1)
//!     else:     q = max(0.9·√(STOL/R), 0.1)
//!     dT = min(max(q·dT, DT_MIN), 1 − T)
//! ```
//!
//! # References
//! Sloan, Abbo & Sheng (2001), Refined explicit integration of elastoplastic models with automatic
//! error control, Engineering Computations 18:121–154.

use crate::error::MaterialError;
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Options of the explicit substepping (spec §8.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SubstepOptions {
    /// Relative error tolerance STOL (spec: 1e-4, range 1e-3 … 1e-5).
    pub stol: f64,
    /// Smallest substep, as a fraction of the step (spec: 1e-6).
    pub dt_min: f64,
    /// Largest number of substep attempts per update (spec: 10 000).
    pub max_substeps: u32,
}

impl Default for SubstepOptions {
    fn default() -> Self {
        SubstepOptions {
            stol: 1e-4,
            dt_min: 1e-6,
            max_substeps: 10_000,
        }
    }
}

/// What the model says after an accepted substep.
#[derive(Debug, Clone, PartialEq)]
pub enum Accepted<P> {
    /// Continue with this point (post-step rules applied).
    Continue(P),
    /// Stop the integration at `fraction` ∈ [0, 1] of the accepted substep, at `point`
    /// (e.g. the interface opened, spec §2.12).
    Stop {
        /// The point where the integration stops.
        point: P,
        /// Fraction of the substep that was consumed.
        fraction: f64,
    },
}

/// Model functions seen by the integrator.
pub trait SubstepModel {
    /// Stress and internal variables at a point.
    type Point: Clone;
    /// Branch decision frozen over a substep.
    type Branch: Copy + PartialEq;
    /// An increment of the point over a substep (one Euler stage).
    type Rate;

    /// Branch at a substep start for the strain increment `d_eps`. May modify the point (the
    /// interface reversal rule (I18) moves its mapping origin).
    fn begin(
        &self,
        p: &Self::Point,
        d_eps: &Vector3<f64>,
    ) -> Result<(Self::Point, Self::Branch), MaterialError>;

    /// Forward-Euler increment at `p` with the frozen branch `br`; the flag is false when the
    /// branch test at `p` disagrees with `br` (a sign flip of the loading indicator).
    fn rate(
        &self,
        p: &Self::Point,
        br: Self::Branch,
        d_eps: &Vector3<f64>,
    ) -> Result<(Self::Rate, bool), MaterialError>;

    /// `p + w·Δ`.
    fn advance(&self, p: &Self::Point, rate: &Self::Rate, w: f64) -> Self::Point;

    /// `p + ½(Δ1 + Δ2)`.
    fn average(&self, p: &Self::Point, r1: &Self::Rate, r2: &Self::Rate) -> Self::Point;

    /// Relative local error estimate R of the two Euler stages at the new point.
    fn error(&self, p_new: &Self::Point, r1: &Self::Rate, r2: &Self::Rate) -> f64;

    /// Post-step rules after an accepted substep from `before` to `after`.
    fn accept(&self, before: &Self::Point, after: Self::Point) -> Accepted<Self::Point>;
}

/// Result of [`integrate`].
#[derive(Debug, Clone, PartialEq)]
pub struct Integrated<P, B> {
    /// The integrated point.
    pub point: P,
    /// Fraction of the increment integrated (1 unless the model stopped the integration).
    pub reached: f64,
    /// Branch of the last accepted substep (`None` when no substep was taken).
    pub last_branch: Option<B>,
    /// Strain increment of the last accepted substep.
    pub last_d_eps: Vector3<f64>,
    /// Number of accepted substeps.
    pub substeps: u32,
}

/// Integrates `d_eps_total` from `start` with modified Euler and error control (spec §8.2).
pub fn integrate<M: SubstepModel>(
    model: &M,
    start: &M::Point,
    d_eps_total: &Vector3<f64>,
    opt: &SubstepOptions,
) -> Result<Integrated<M::Point, M::Branch>, MaterialError> {
    const EPS: f64 = 1e-12;
    let mut point = start.clone();
    let mut t = 0.0_f64;
    let mut dt = 1.0_f64;
    let mut accepted = 0_u32;
    let mut attempts = 0_u32;
    let mut last_branch = None;
    let mut last_d_eps = Vector3::zeros();
    if d_eps_total.norm() == 0.0 {
        return Ok(Integrated {
            point,
            reached: 1.0,
            last_branch,
            last_d_eps,
            substeps: 0,
        });
    }
    while t < 1.0 {
        attempts += 1;
        if attempts > opt.max_substeps {
            return Err(MaterialError::new(format!(
                "GP interface: more than {} substep attempts (T = {t:.3e})",
                opt.max_substeps
            )));
        }
        let d_eps = d_eps_total * dt;
        let (p0, br) = model.begin(&point, &d_eps)?;
        let (r1, _) = model.rate(&p0, br, &d_eps)?;
        let p1 = model.advance(&p0, &r1, 1.0);
        let (r2, same_branch) = model.rate(&p1, br, &d_eps)?;
        let at_min = dt <= opt.dt_min * (1.0 + 1e-12);
        let p_new = model.average(&p0, &r1, &r2);
        let mut err = if !same_branch && !at_min {
            f64::INFINITY
        } else {
            model.error(&p_new, &r1, &r2).max(EPS)
        };
        if err.is_nan() {
            err = f64::INFINITY;
        }
        if err <= opt.stol {
            accepted += 1;
            last_branch = Some(br);
            last_d_eps = d_eps;
            match model.accept(&p0, p_new) {
                Accepted::Continue(p) => point = p,
                Accepted::Stop { point: p, fraction } => {
                    return Ok(Integrated {
                        point: p,
                        reached: (t + fraction.clamp(0.0, 1.0) * dt).min(1.0),
                        last_branch,
                        last_d_eps,
                        substeps: accepted,
                    });
                }
            }
            t += dt;
            let q = (0.9 * (opt.stol / err).sqrt()).min(1.1);
            dt = (q * dt).max(opt.dt_min);
        } else {
            if at_min {
                return Err(MaterialError::new(format!(
                    "GP interface: substep error {err:.3e} above STOL at the smallest substep (T = {t:.3e})"
                )));
            }
            let q = if err.is_finite() {
                (0.9 * (opt.stol / err).sqrt()).max(0.1)
            } else {
                0.1
            };
            dt = (q * dt).max(opt.dt_min);
        }
        dt = dt.min(1.0 - t);
        if 1.0 - t < 1e-14 {
            break;
        }
    }
    Ok(Integrated {
        point,
        reached: 1.0,
        last_branch,
        last_d_eps,
        substeps: accepted,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// dy/dε = −y (exact y = e^{−ε}); stops when y falls below `stop_below`.
    struct Decay {
        stop_below: f64,
    }

    impl SubstepModel for Decay {
        type Point = f64;
        type Branch = ();
        type Rate = f64;
        fn begin(&self, p: &f64, _d: &Vector3<f64>) -> Result<(f64, ()), MaterialError> {
            Ok((*p, ()))
        }
        fn rate(&self, p: &f64, _br: (), d: &Vector3<f64>) -> Result<(f64, bool), MaterialError> {
            Ok((-p * d[0], true))
        }
        fn advance(&self, p: &f64, r: &f64, w: f64) -> f64 {
            p + w * r
        }
        fn average(&self, p: &f64, r1: &f64, r2: &f64) -> f64 {
            p + 0.5 * (r1 + r2)
        }
        fn error(&self, p_new: &f64, r1: &f64, r2: &f64) -> f64 {
            (r2 - r1).abs() / (2.0 * p_new.abs())
        }
        fn accept(&self, before: &f64, after: f64) -> Accepted<f64> {
            if after < self.stop_below {
                let fraction = (before - self.stop_below) / (before - after);
                Accepted::Stop {
                    point: self.stop_below,
                    fraction,
                }
            } else {
                Accepted::Continue(after)
            }
        }
    }

    #[test]
    fn modified_euler_error_control_converges_with_stol() {
        let total = Vector3::new(3.0, 0.0, 0.0);
        let exact = (-3.0_f64).exp();
        let mut last = (f64::INFINITY, 0);
        for stol in [1e-3, 1e-4, 1e-5, 1e-6] {
            let opt = SubstepOptions {
                stol,
                ..SubstepOptions::default()
            };
            let out = integrate(&Decay { stop_below: -1.0 }, &1.0, &total, &opt).expect("integrates");
            let err = (out.point - exact).abs() / exact;
            assert!(err < 50.0 * stol, "STOL {stol}: relative error {err}");
            assert!(
                err < last.0 && out.substeps > last.1,
                "error falls, substeps grow"
            );
            assert_eq!(out.reached, 1.0);
            last = (err, out.substeps);
        }
    }

    #[test]
    fn a_stop_reports_the_reached_fraction() {
        let total = Vector3::new(3.0, 0.0, 0.0);
        let opt = SubstepOptions {
            stol: 1e-6,
            ..SubstepOptions::default()
        };
        let out = integrate(&Decay { stop_below: 0.5 }, &1.0, &total, &opt).expect("integrates");
        // y = 0.5 at ε = ln 2, i.e. at the fraction ln 2 / 3 of the increment.
        assert!((out.reached - 2.0_f64.ln() / 3.0).abs() < 1e-3, "{}", out.reached);
        assert_eq!(out.point, 0.5);
        let zero = integrate(&Decay { stop_below: 0.5 }, &1.0, &Vector3::zeros(), &opt).expect("no-op");
        assert_eq!((zero.point, zero.substeps, zero.reached), (1.0, 0, 1.0));
    }

    #[test]
    fn too_many_attempts_is_an_error_not_a_panic() {
        let opt = SubstepOptions {
            stol: 1e-9,
            dt_min: 1e-6,
            max_substeps: 5,
        };
        let out = integrate(
            &Decay { stop_below: -1.0 },
            &1.0,
            &Vector3::new(3.0, 0.0, 0.0),
            &opt,
        );
        assert!(out.is_err());
    }
}
