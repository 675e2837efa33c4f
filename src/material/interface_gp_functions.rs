//! Model functions of the 3D state-dependent GP interface (spec §2): elasticity, critical state,
//! the bounding-surface mapping, loading and flow directions, the plastic modulus, breakage,
//! and the [`SubstepModel`] glue used by the explicit integrator (spec §8.2).
//!
//! Everything here works in the spec's compression-positive generalized variables
//! `s = (τ_s, τ_a, σ_n)` (Pa) and `ε = (γ_s, γ_a, ε_n)` (−), spec (I1). The conversion from the
//! element's jump and traction is done once, in [`super::interface_gp`].

use super::interface_gp::{FhMode, GpBranch, GpInterface, GpInterfaceState, PeakForm};
use super::interface_gp_substep::{Accepted, SubstepModel};
use crate::error::MaterialError;
use nalgebra::{Matrix3, Vector2, Vector3};

/// Floor of the void ratio in the elastic factor (1+e)/e (caps it at 101) (spec tag INF).
pub const VOID_RATIO_FLOOR: f64 = 0.01;
/// Cap of √(ρ_max/ρ) (spec (I12): ρ ≥ 0.01·ρ_max).
pub const MAPPING_RATIO_CAP: f64 = 10.0;
/// Below this |r − r_A| the mapping direction is taken from the trial increment (spec (I12)).
const RHO_TINY: f64 = 1e-12;
/// Relative branch tolerance tolN (spec §8.2).
const TOL_N: f64 = 1e-6;

/// The mapping of spec (I12): reversal point A = r_A, current point B = r, image point C on the
/// max-history circle and D on the peak circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mapping {
    /// Mapping direction u (zero when undefined: pure normal loading from an unsheared state).
    pub u: Vector2<f64>,
    /// ρ = |r − r_A|.
    pub rho: f64,
    /// ρ_max = AC.
    pub rho_max: f64,
    /// 1 − ρ/ρ_p, or its fallback 1 − |r|/η_p when the ray misses the peak circle.
    pub peak_distance: f64,
    /// Image point r_C = r_A + ρ_max·u.
    pub image: Vector2<f64>,
    /// Virgin loading (ρ ≥ ρ_max − tol) versus cyclic (ρ < ρ_max).
    pub virgin: bool,
    /// √(ρ_max/ρ), capped at [`MAPPING_RATIO_CAP`]; 1 when ρ_max = 0.
    pub ratio: f64,
}

/// Ray–circle intersection distance s ≥ 0 from `a` along the unit vector `u` to the circle of
/// radius `radius` centred at the origin (spec (I12)):
///
/// ```text
/// s_R = −(A·u) + √((A·u)² + R² − |A|²)
/// ```
///
/// `None` when the ray does not meet the circle at a positive distance.
pub fn ray_circle(a: &Vector2<f64>, u: &Vector2<f64>, radius: f64) -> Option<f64> {
    let au = a.dot(u);
    let disc = au * au + radius * radius - a.norm_squared();
    if disc < 0.0 {
        return None;
    }
    let s = -au + disc.sqrt();
    if s > 0.0 {
        Some(s)
    } else {
        None
    }
}

/// The mapping of spec (I12) with its degenerate cases.
///
/// * `r`: current stress-ratio point; `a`: reversal point; `eta_max`: max-history radius;
///   `eta_p`: peak radius; `trial_dr`: stress-ratio increment of the trial (elastic) increment,
///   used for u when ρ = 0.
pub fn mapping(
    r: &Vector2<f64>,
    a: &Vector2<f64>,
    eta_max: f64,
    eta_p: f64,
    trial_dr: &Vector2<f64>,
) -> Mapping {
    let d = r - a;
    let rho = d.norm();
    let u = if rho > RHO_TINY {
        d / rho
    } else if trial_dr.norm() > RHO_TINY {
        trial_dr / trial_dr.norm()
    } else if r.norm() > RHO_TINY {
        r / r.norm()
    } else {
        Vector2::zeros()
    };
    if u.norm() == 0.0 {
        return Mapping {
            u,
            rho: 0.0,
            rho_max: 0.0,
            peak_distance: 1.0 - r.norm() / eta_p,
            image: *r,
            virgin: true,
            ratio: 1.0,
        };
    }
    // G7: every state is kept inside the max-history circle; |A| ≤ η_max then holds too.
    let radius = eta_max.max(a.norm());
    let mut rho_max = ray_circle(a, &u, radius).unwrap_or(0.0);
    let tol = 1e-9 * (1.0 + radius);
    let virgin = rho >= rho_max - tol;
    if virgin {
        rho_max = rho;
    }
    let peak_distance = match ray_circle(a, &u, eta_p) {
        Some(rho_p) if a.norm() <= eta_p => 1.0 - rho / rho_p,
        _ => 1.0 - r.norm() / eta_p,
    };
    let ratio = if rho_max <= 0.0 {
        1.0
    } else {
        (rho_max / rho.max(rho_max / (MAPPING_RATIO_CAP * MAPPING_RATIO_CAP)))
            .sqrt()
            .min(MAPPING_RATIO_CAP)
    };
    Mapping {
        u,
        rho,
        rho_max,
        peak_distance,
        image: a + u * rho_max,
        virgin,
        ratio,
    }
}

/// Unit direction (shear factor, normal component) from a dilatancy-like ratio d (spec (I14),
/// (I15)):
///
/// ```text
/// d = r_d·α·(m_line − η)·exp(c0/η),   (n_s, n_n) = (1, d)/√(1 + d²)
/// ```
///
/// with the c0 limit of spec §2.7: for η < 2·10⁻⁶ or c0/η > 50 the direction is purely normal,
/// `(0, sign(m_line − η))`.
pub fn direction(m_line: f64, eta: f64, rd_alpha: f64, c0: f64) -> (f64, f64, f64) {
    if eta < 2e-6 || c0 / eta > 50.0 {
        let sign = if m_line - eta >= 0.0 { 1.0 } else { -1.0 };
        return (0.0, sign, sign * f64::INFINITY);
    }
    let d = rd_alpha * (m_line - eta) * (c0 / eta).exp();
    let norm = (1.0 + d * d).sqrt();
    (1.0 / norm, d / norm, d)
}

/// Everything the rate equations need at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointFunctions {
    /// Diagonal of D^e = diag(D_s, D_s, D_n), Pa per unit strain (spec (I3)–(I5)).
    pub de: Vector3<f64>,
    /// Loading direction n (spec (I15)).
    pub n: Vector3<f64>,
    /// Flow direction n_g (spec (I14)).
    pub ng: Vector3<f64>,
    /// Plastic modulus H (spec (I16)), Pa per unit strain.
    pub h: f64,
    /// H + nᵀD^e n_g after the guard of spec §8.6 item 4.
    pub denom: f64,
    /// State parameter ψ (spec (I8)).
    pub psi: f64,
    /// Peak ratio η_p (spec (I9)).
    pub eta_p: f64,
    /// The mapping (spec (I12)).
    pub map: Mapping,
}

impl PointFunctions {
    /// D^e as a matrix.
    pub fn elastic(&self) -> Matrix3<f64> {
        Matrix3::from_diagonal(&self.de)
    }

    /// D^ep = D^e − (D^e n_g)(nᵀD^e)/(H + nᵀD^e n_g) (spec (I19)).
    pub fn elastoplastic(&self) -> Matrix3<f64> {
        let dng = self.de.component_mul(&self.ng);
        let nd = self.de.component_mul(&self.n);
        self.elastic() - dng * nd.transpose() / self.denom
    }

    /// Loading indicator nᵀD^e dε and its tolerance tolN·|n|·|D^e dε| (spec (I17), §8.2).
    pub fn indicator(&self, d_eps: &Vector3<f64>) -> (f64, f64) {
        let dse = self.de.component_mul(d_eps);
        (self.n.dot(&dse), TOL_N * self.n.norm() * dse.norm())
    }
}

impl GpInterface {
    /// Elastic moduli (D_s, D_n) at a state, Pa per unit strain (spec (I3), (I4)):
    ///
    /// ```text
    /// D_s = D_s0·((1+e)/e)·[(σ̂_n/p_a)² + (τ/p_a)²]^0.5,   D_n = (D_n0/D_s0)·D_s,   σ̂_n = max(σ_n, σ_min)
    /// ```
    ///
    /// times the stiffness-basis factor (t under `displacement`, 1 under `strain`).
    pub fn elastic_moduli(&self, sigma_n: f64, tau: f64, void_ratio: f64) -> (f64, f64) {
        let p = &self.params;
        let sig = sigma_n.max(p.sigma_min);
        let e = void_ratio.max(VOID_RATIO_FLOOR);
        let ds =
            self.basis_factor * p.ds0 * (1.0 + e) / e * ((sig / p.pa).powi(2) + (tau / p.pa).powi(2)).sqrt();
        (ds, ds * p.dn0 / p.ds0)
    }

    /// State parameter ψ = e − e_c with e_c = e_Γ − Δe_c − λ·ln(σ̂_n/p_a) (spec (I6)–(I8)).
    pub fn state_parameter(&self, sigma_n: f64, void_ratio: f64, delta_e_c: f64) -> f64 {
        let p = &self.params;
        let sig = sigma_n.max(p.sigma_min);
        let e_c = p.e_gamma - delta_e_c - p.lambda * (sig / p.pa).ln();
        void_ratio - e_c
    }

    /// Peak stress ratio η_p (spec (I9)): M_c·exp(−kψ) (`exp`) or M_c − kψ (`linear`, floored at
    /// 0.05·M_c).
    pub fn peak_ratio(&self, psi: f64) -> f64 {
        let p = &self.params;
        match p.peak_form {
            PeakForm::Exp => p.mc * (-p.k * psi).exp(),
            PeakForm::Linear => (p.mc - p.k * psi).max(0.05 * p.mc),
        }
    }

    /// Size of the loading surface (1) through the state, σ_c (spec (I13)):
    ///
    /// ```text
    /// σ_c = σ_n·[1 − (α − 1)·η/(α·M_f)]^(−1/(α−1))
    /// ```
    pub fn surface_size(&self, sigma_n: f64, eta: f64) -> f64 {
        let p = &self.params;
        let am1 = p.alpha - 1.0;
        if am1.abs() < 1e-12 {
            return sigma_n * (eta / p.mf).exp();
        }
        let base = (1.0 - am1 * eta / (p.alpha * p.mf)).max(1e-12);
        sigma_n * base.powf(-1.0 / am1)
    }

    /// Stress ratio vector r = (τ_s, τ_a)/σ̂_n (spec (I2)).
    pub fn stress_ratio(&self, s: &[f64; 3]) -> Vector2<f64> {
        Vector2::new(s[0], s[1]) / s[2].max(self.params.sigma_min)
    }

    /// All model functions at state `st` for the strain increment direction `d_eps`
    /// (spec (I3)–(I16), (I19)).
    pub fn functions(&self, st: &GpInterfaceState, d_eps: &Vector3<f64>) -> PointFunctions {
        let p = &self.params;
        let s = &st.stress;
        let sig = s[2].max(p.sigma_min);
        let r = self.stress_ratio(s);
        let eta = r.norm();
        let (ds, dn) = self.elastic_moduli(s[2], eta * sig, st.void_ratio);
        let de = Vector3::new(ds, ds, dn);
        let dse = de.component_mul(d_eps);
        let trial_dr = (Vector2::new(dse[0], dse[1]) - r * dse[2]) / sig;
        let psi = self.state_parameter(s[2], st.void_ratio, st.delta_e_c);
        let eta_p = self.peak_ratio(psi).max(1e-6);
        let a = Vector2::new(st.reversal_point[0], st.reversal_point[1]);
        let map = mapping(&r, &a, st.eta_max, eta_p, &trial_dr);
        let rd_alpha = p.rd * p.alpha;
        // (I14): flow direction, shear unit vector at the image point, current η.
        let e_img = if map.image.norm() > RHO_TINY {
            map.image / map.image.norm()
        } else {
            map.u
        };
        let (gs, gn, _) = direction((p.mc + p.km * psi) * map.ratio, eta, rd_alpha, p.c0);
        let ng = Vector3::new(e_img[0] * gs, e_img[1] * gs, gn);
        // (I15): loading direction at the image point, η̄ = |r_C|.
        let eta_bar = map.image.norm();
        let (fs, fnn, _) = direction((p.mf + p.km * psi) * map.ratio, eta_bar, rd_alpha, p.c0);
        let n = Vector3::new(e_img[0] * fs, e_img[1] * fs, fnn);
        // (I16): plastic modulus.
        let fh = match p.fh_mode {
            FhMode::Literal => p.fh,
            FhMode::Memory => (map.ratio * map.ratio).powf(p.fh),
        };
        let h = self.basis_factor * p.h0 / (1.0 + psi).max(0.05)
            * (sig / p.pa)
            * map.peak_distance
            * (1.0 + map.rho).powi(-2)
            * fh;
        // §8.6 item 4: H + nᵀD^e n_g ≥ 0.05·nᵀD^e n_g (and a positive floor when nᵀD^e n_g ≤ 0).
        let a_dn = n.dot(&de.component_mul(&ng));
        let floor = 0.05 * a_dn.max(0.01 * ds.min(dn));
        let denom = (h + a_dn).max(floor);
        PointFunctions {
            de,
            n,
            ng,
            h,
            denom,
            psi,
            eta_p,
            map,
        }
    }
}

/// Branch frozen over one substep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SubstepBranch {
    /// nᵀdσ^e ≤ 0 after the reversal rule, or neutral: elastic.
    Elastic,
    /// Plastic loading (virgin or reverse/cyclic loading).
    Load,
}

/// Increment of the state over one Euler stage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateRate {
    /// ds (Pa).
    pub d_stress: Vector3<f64>,
    /// dε (−).
    pub d_strain: Vector3<f64>,
    /// dε^p (−).
    pub d_plastic: Vector3<f64>,
    /// ⟨dW_p⟩ (Pa).
    pub d_work: f64,
    /// dΔe_c (−).
    pub d_breakage: f64,
}

fn add3(a: &[f64; 3], b: &Vector3<f64>, w: f64) -> [f64; 3] {
    [a[0] + w * b[0], a[1] + w * b[1], a[2] + w * b[2]]
}

impl SubstepModel for GpInterface {
    type Point = GpInterfaceState;
    type Branch = SubstepBranch;
    type Rate = StateRate;

    /// Branch decision with the reversal rule (spec (I17), (I18)).
    fn begin(
        &self,
        p: &GpInterfaceState,
        d_eps: &Vector3<f64>,
    ) -> Result<(GpInterfaceState, SubstepBranch), MaterialError> {
        let f = self.functions(p, d_eps);
        let (l, tol) = f.indicator(d_eps);
        if l > tol {
            return Ok((p.clone(), SubstepBranch::Load));
        }
        if l < -tol {
            let r = self.stress_ratio(&p.stress);
            let mut q = p.clone();
            q.reversal_point = [r[0], r[1]];
            let f2 = self.functions(&q, d_eps);
            let (l2, tol2) = f2.indicator(d_eps);
            let br = if l2 > tol2 {
                SubstepBranch::Load
            } else {
                SubstepBranch::Elastic
            };
            return Ok((q, br));
        }
        Ok((p.clone(), SubstepBranch::Elastic))
    }

    /// Rate equations (spec (I19)–(I21)).
    fn rate(
        &self,
        p: &GpInterfaceState,
        br: SubstepBranch,
        d_eps: &Vector3<f64>,
    ) -> Result<(StateRate, bool), MaterialError> {
        let pr = &self.params;
        let f = self.functions(p, d_eps);
        let (l, tol) = f.indicator(d_eps);
        let (d_plastic, agrees) = match br {
            SubstepBranch::Load => (f.ng * (l.max(0.0) / f.denom), l >= -tol),
            SubstepBranch::Elastic => (Vector3::zeros(), l <= tol),
        };
        let d_stress = f.de.component_mul(&(d_eps - d_plastic));
        let s = Vector3::new(p.stress[0], p.stress[1], p.stress[2]);
        let d_work = s.dot(&d_plastic).max(0.0);
        let chi = if f.map.virgin { 1.0 } else { pr.c };
        let d_breakage = chi * d_work / (pr.a + pr.b * p.plastic_work).powi(2);
        let rate = StateRate {
            d_stress,
            d_strain: *d_eps,
            d_plastic,
            d_work,
            d_breakage,
        };
        if !rate.d_stress.iter().all(|v| v.is_finite()) {
            return Err(MaterialError::new("GP interface: non-finite stress rate"));
        }
        Ok((rate, agrees))
    }

    fn advance(&self, p: &GpInterfaceState, r: &StateRate, w: f64) -> GpInterfaceState {
        let mut q = p.clone();
        q.stress = add3(&p.stress, &r.d_stress, w);
        q.strain = add3(&p.strain, &r.d_strain, w);
        q.plastic_strain = add3(&p.plastic_strain, &r.d_plastic, w);
        q.plastic_work = p.plastic_work + w * r.d_work;
        q.delta_e_c = p.delta_e_c + w * r.d_breakage;
        q.void_ratio = self.params.e0 - q.strain[2] * (1.0 + self.params.e0);
        q
    }

    fn average(&self, p: &GpInterfaceState, r1: &StateRate, r2: &StateRate) -> GpInterfaceState {
        let mean = StateRate {
            d_stress: 0.5 * (r1.d_stress + r2.d_stress),
            d_strain: 0.5 * (r1.d_strain + r2.d_strain),
            d_plastic: 0.5 * (r1.d_plastic + r2.d_plastic),
            d_work: 0.5 * (r1.d_work + r2.d_work),
            d_breakage: 0.5 * (r1.d_breakage + r2.d_breakage),
        };
        self.advance(p, &mean, 1.0)
    }

    /// R = max(‖Δs2 − Δs1‖/(2‖s̃‖ + σ_min), |Δε^p2 − Δε^p1|·(1+e0)/(2ẽ)) (spec §8.2).
    fn error(&self, p_new: &GpInterfaceState, r1: &StateRate, r2: &StateRate) -> f64 {
        let s = Vector3::new(p_new.stress[0], p_new.stress[1], p_new.stress[2]);
        let es = (r2.d_stress - r1.d_stress).norm() / (2.0 * s.norm() + self.params.sigma_min);
        let ee = (r2.d_plastic - r1.d_plastic).norm() * (1.0 + self.params.e0)
            / (2.0 * p_new.void_ratio.abs().max(VOID_RATIO_FLOOR));
        es.max(ee)
    }

    /// Post-step rules: η_max and σ_c,max updated every accepted substep (spec G7), opening test
    /// with linear interpolation of the crossing (spec §2.12).
    fn accept(&self, before: &GpInterfaceState, after: GpInterfaceState) -> Accepted<GpInterfaceState> {
        let pr = &self.params;
        let s_open = pr.sigma_open;
        if after.stress[2] <= s_open {
            let span = before.stress[2] - after.stress[2];
            let frac = if span > 0.0 {
                ((before.stress[2] - s_open) / span).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let lerp = |a: f64, b: f64| a + frac * (b - a);
            let mut q = before.clone();
            for i in 0..3 {
                q.strain[i] = lerp(before.strain[i], after.strain[i]);
                q.plastic_strain[i] = lerp(before.plastic_strain[i], after.plastic_strain[i]);
            }
            q.plastic_work = lerp(before.plastic_work, after.plastic_work);
            q.delta_e_c = lerp(before.delta_e_c, after.delta_e_c);
            q.void_ratio = pr.e0 - q.strain[2] * (1.0 + pr.e0);
            return Accepted::Stop {
                point: q,
                fraction: frac,
            };
        }
        let mut q = after;
        let r = self.stress_ratio(&q.stress);
        q.eta_max = q.eta_max.max(r.norm());
        q.sigma_c_max = q.sigma_c_max.max(self.surface_size(q.stress[2], r.norm()));
        Accepted::Continue(q)
    }
}

impl GpInterface {
    /// Branch flag of a state after a substep on branch `br` (for output).
    pub fn branch_flag(&self, st: &GpInterfaceState, br: SubstepBranch, d_eps: &Vector3<f64>) -> GpBranch {
        match br {
            SubstepBranch::Elastic => GpBranch::Elastic,
            SubstepBranch::Load => {
                if self.functions(st, d_eps).map.virgin {
                    GpBranch::Virgin
                } else {
                    GpBranch::Cyclic
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_circle_on_circle_outward_and_inward() {
        let a = Vector2::new(0.5, 0.0);
        let out = ray_circle(&a, &Vector2::new(1.0, 0.0), 0.5).unwrap_or(-1.0);
        assert!(out.abs() < 1e-15 || out < 0.0);
        let inward = ray_circle(&a, &Vector2::new(-1.0, 0.0), 0.5).unwrap();
        assert!((inward - 1.0).abs() < 1e-14, "{inward}");
        // From the centre the distance is the radius in every direction.
        let s = ray_circle(&Vector2::zeros(), &Vector2::new(0.6, 0.8), 0.7).unwrap();
        assert!((s - 0.7).abs() < 1e-14);
    }

    #[test]
    fn mapping_degenerate_cases_are_finite() {
        let z = Vector2::zeros();
        let m = mapping(&z, &z, 0.0, 0.9, &z);
        assert_eq!(m.u, z);
        assert!(m.virgin && m.ratio == 1.0 && m.rho_max == 0.0);
        // Right at a reversal on the circle, moving inward: ρ = 0, ρ_max = 2|A·u|, capped ratio.
        let a = Vector2::new(0.4, 0.0);
        let m = mapping(&a, &a, 0.4, 0.9, &Vector2::new(-1e-3, 0.0));
        assert!(!m.virgin);
        assert!((m.rho_max - 0.8).abs() < 1e-12);
        assert_eq!(m.ratio, MAPPING_RATIO_CAP);
        assert!((m.image - Vector2::new(-0.4, 0.0)).norm() < 1e-12);
        // Reversal point outside a shrunken peak circle: the fallback 1 − |r|/η_p.
        let m = mapping(&Vector2::new(0.5, 0.0), &Vector2::new(0.95, 0.0), 0.95, 0.9, &z);
        assert!((m.peak_distance - (1.0 - 0.5 / 0.9)).abs() < 1e-12);
    }

    #[test]
    fn direction_limit_is_purely_normal() {
        let (s, n, _) = direction(0.8, 1e-7, 0.13, 1e-4);
        assert_eq!((s, n), (0.0, 1.0));
        let (s, n, _) = direction(0.8, 0.3, 0.13, 1e-4);
        assert!((s * s + n * n - 1.0).abs() < 1e-14 && n > 0.0);
        let (_, n, _) = direction(0.8, 1.2, 0.13, 1e-4);
        assert!(n < 0.0, "dilation above the phase-transformation line");
    }
}
