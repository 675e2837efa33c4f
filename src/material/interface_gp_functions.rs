//! Model functions of the 3D state-dependent GP interface (spec §2): elasticity, critical state,
//! the bounding-surface mapping, loading and flow directions, the plastic modulus, breakage,
//! and the [`GpModelFunctions`] implementation used by the generic explicit integrator
//! ([`super::gp_integrator`], spec §8.2).
//!
//! Everything here works in the spec's compression-positive generalized variables
//! `s = (τ_s, τ_a, σ_n)` (Pa) and `ε = (γ_s, γ_a, ε_n)` (−), spec (I1). The conversion from the
//! element's jump and traction is done once, in [`super::interface_gp`].
//!
//! # The interface as a GP model of the integrator
//! * σ = s; κ = (ε (3), ε^p (3), W_p, Δe_c) ([`KAPPA`] = 8; the void ratio follows from ε_n by
//!   (I6)); memory = r_A, η_max, σ_c,max ([`InterfaceMemory`]).
//! * Branch decision (I17)/(I18) at substep starts only ([`GpModelFunctions::begin_substep`]):
//!   nᵀdσ^e > 0 is loading; nᵀdσ^e < 0 moves r_A to the current point, re-maps, and is
//!   loading ("reverse loading") if now nᵀdσ^e > 0, otherwise elastic unloading, reported as
//!   [`Branch::Unloading`] with H = ∞ (so the integrator treats it as elastic and a change to
//!   loading inside the substep is a branch flip); |nᵀdσ^e| ≤ tolN·|n||dσ^e| is neutral.
//! * H returned to the integrator is the guarded H of spec §8.6 item 4 (see
//!   [`PointFunctions::denom`]).
//! * Error measure ([`GpModelFunctions::substep_error`]):
//!   R = max(‖Δs2 − Δs1‖/(2‖s̃‖ + σ_min), ‖Δε^p2 − Δε^p1‖·(1+e0)/(2·max(|ẽ|, 0.01))), i.e. the
//!   stress error and the error of the void ratio through the plastic strain.
//! * Opening (spec §2.12) is a stop inside the substep ([`GpModelFunctions::stop_in_substep`]):
//!   the crossing σ_n = σ_open is interpolated linearly.
//! * After an accepted substep τ is scaled back onto the peak circle |r| = η_p(ψ) when it lies
//!   outside (`stress_ratio_cap = peak`, the default; issue 18), then η_max and σ_c,max are
//!   updated (spec G7). A loading substep that ends on the cap gets the cap's Jacobian in its
//!   continuum tangent ([`GpInterface::capped_tangent`]).

use super::gp_integrator::{cosine, Branch, GpModelFunctions, GpPoint, PlasticData, StageIncrement};
use super::interface_gp::{
    ElasticVoidRatio, FhMode, GpBranch, GpInterface, GpInterfaceState, PeakForm, ReversalBranch,
    StressRatioCap, VoidRatioBound,
};
use crate::error::MaterialError;
use nalgebra::{Matrix3, SVector, Vector2, Vector3};

/// Floor of the void ratio in the elastic factor (1+e)/e under `elastic_void_ratio = current`
/// (caps it at 101), and of |e| in the error measure (spec tag INF).
pub const VOID_RATIO_FLOOR: f64 = 0.01;
/// Floor of the closure factor g of `void_ratio_bound = smooth` (caps the normal stiffening
/// at 10⁶, reached only by a strain-controlled closure beyond the bound).
pub const CLOSURE_FACTOR_FLOOR: f64 = 1e-6;
/// Relative distance below the stress-ratio cap within which an end state counts as on it
/// (the cap leaves |τ| = η_cap·σ̂_n up to rounding).
const CAP_TOUCH: f64 = 1e-9;
/// Cap of √(ρ_max/ρ) (spec (I12): ρ ≥ 0.01·ρ_max).
pub const MAPPING_RATIO_CAP: f64 = 10.0;
/// Below this |r − r_A| the mapping direction is taken from the trial increment (spec (I12)).
const RHO_TINY: f64 = 1e-12;
/// Number of rate-integrated internal variables: ε (3), ε^p (3), W_p, Δe_c.
pub const KAPPA: usize = 8;
/// Index of ε^p_s in κ (ε^p occupies 3..6).
const K_PLASTIC: usize = 3;
/// Index of W_p in κ.
const K_WORK: usize = 6;
/// Index of Δe_c in κ.
const K_BREAKAGE: usize = 7;

/// Memory of an interface point: changed only at substep starts (the reversal point) and after
/// accepted substeps (the max-history surfaces).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterfaceMemory {
    /// Reversal point r_A (spec (I12)).
    pub reversal_point: Vector2<f64>,
    /// Radius η_max of the max-history circle (spec (I11), G7).
    pub eta_max: f64,
    /// σ_c,max of the τ–σ_n max-history surface (Pa, spec (I13)).
    pub sigma_c_max: f64,
}

/// An interface point as the integrator sees it: s (Pa), κ = (ε, ε^p, W_p, Δe_c), memory.
pub type InterfacePoint = GpPoint<3, KAPPA, InterfaceMemory>;

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

/// Mapping direction u and ρ = |r − r_A| (spec (I12)), with the degenerate cases: u from the
/// trial increment when ρ = 0 (evaluated only then), from r when that vanishes too, and u = 0
/// when r = r_A = 0.
fn mapping_direction(
    r: &Vector2<f64>,
    a: &Vector2<f64>,
    trial_dr: impl FnOnce() -> Vector2<f64>,
) -> (Vector2<f64>, f64) {
    let d = r - a;
    let rho = d.norm();
    if rho > RHO_TINY {
        return (d / rho, rho);
    }
    let t = trial_dr();
    let u = if t.norm() > RHO_TINY {
        t / t.norm()
    } else if r.norm() > RHO_TINY {
        r / r.norm()
    } else {
        Vector2::zeros()
    };
    (u, rho)
}

/// ρ_max = AC along u (spec (I12)) and the virgin flag ρ ≥ ρ_max − tol (then ρ_max = ρ).
fn max_history_distance(a: &Vector2<f64>, u: &Vector2<f64>, rho: f64, eta_max: f64) -> (f64, bool) {
    // G7: every state is kept inside the max-history circle; |A| ≤ η_max then holds too.
    let radius = eta_max.max(a.norm());
    let rho_max = ray_circle(a, u, radius).unwrap_or(0.0);
    let tol = 1e-9 * (1.0 + radius);
    if rho >= rho_max - tol {
        (rho, true)
    } else {
        (rho_max, false)
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
    let (u, rho) = mapping_direction(r, a, || *trial_dr);
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
    let (rho_max, virgin) = max_history_distance(a, &u, rho, eta_max);
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
    /// H + nᵀD^e n_g after the guard of spec §8.6 item 4:
    /// max(H + a, 0.05·max(a, 0.01·min(D_s, D_n))) with a = nᵀD^e n_g.
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
}

impl GpInterface {
    /// Elastic moduli (D_s, D_n) at a state with void ratio `void_ratio`, Pa per unit strain
    /// (spec (I3), (I4)):
    ///
    /// ```text
    /// D_s = D_s0·((1+ê)/ê)·[(σ̂_n/p_a)² + (τ/p_a)²]^0.5,   D_n = (D_n0/D_s0)·D_s,   σ̂_n = max(σ_n, σ_min)
    /// ```
    ///
    /// times the stiffness-basis factors (λ_s for D_s, λ_n for D_n: t under `displacement`,
    /// 1 under `strain`), with ê = e0 under `elastic_void_ratio = initial` and
    /// ê = max(e, 0.01) under `current`; D_n is divided by the closure factor g(e) of
    /// [`Self::closure_factor`].
    pub fn elastic_moduli(&self, sigma_n: f64, tau: f64, void_ratio: f64) -> (f64, f64) {
        let p = &self.params;
        let sig = sigma_n.max(p.sigma_min);
        let e = match p.elastic_void_ratio {
            ElasticVoidRatio::Initial => p.e0,
            ElasticVoidRatio::Current => void_ratio.max(VOID_RATIO_FLOOR),
        };
        let d = p.ds0 * (1.0 + e) / e * ((sig / p.pa).powi(2) + (tau / p.pa).powi(2)).sqrt();
        let dn = self.normal_factor * d * p.dn0 / p.ds0 / self.closure_factor(void_ratio);
        (self.basis_factor * d, dn)
    }

    /// Closure factor g of `void_ratio_bound = smooth` (issue 19; module docs of
    /// [`super::interface_gp`], "Normal response"):
    ///
    /// ```text
    /// x = clamp((e − e_min)/(e0 − e_min), 0, 1),   g = max(1 − (1 − x)², CLOSURE_FACTOR_FLOOR)
    /// ```
    ///
    /// g = 1 for e ≥ e0 and under `void_ratio_bound = none`.
    pub fn closure_factor(&self, void_ratio: f64) -> f64 {
        let p = &self.params;
        match p.void_ratio_bound {
            VoidRatioBound::None => 1.0,
            VoidRatioBound::Smooth => {
                let x = ((void_ratio - p.e_min) / (p.e0 - p.e_min)).clamp(0.0, 1.0);
                (1.0 - (1.0 - x) * (1.0 - x)).max(CLOSURE_FACTOR_FLOOR)
            }
            VoidRatioBound::Bandis => {
                let x = ((void_ratio - p.e_min) / (p.e0 - p.e_min)).clamp(0.0, 1.0);
                (x * x).max(CLOSURE_FACTOR_FLOOR)
            }
        }
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
        self.functions_at(&self.to_point(st), d_eps)
    }

    /// Void ratio of a point, e = e0 − ε_n·(1 + e0) (spec (I6)).
    pub fn void_ratio_at(&self, pt: &InterfacePoint) -> f64 {
        self.params.e0 - pt.kappa[2] * (1.0 + self.params.e0)
    }

    /// σ̂_n, the stress ratio r (I2) and the diagonal of D^e (I3)–(I5) at a point.
    fn elastic_at(&self, pt: &InterfacePoint) -> (f64, Vector2<f64>, Vector3<f64>) {
        let s = &pt.sigma;
        let sig = s[2].max(self.params.sigma_min);
        let r = Vector2::new(s[0], s[1]) / sig;
        let (ds, dn) = self.elastic_moduli(s[2], r.norm() * sig, self.void_ratio_at(pt));
        (sig, r, Vector3::new(ds, ds, dn))
    }

    /// Virgin loading at a point (spec (I12): ρ ≥ ρ_max), without the rest of the mapping:
    /// χ of the breakage rate (I21).
    fn virgin_at(&self, pt: &InterfacePoint, d_eps: &Vector3<f64>) -> bool {
        let sig = pt.sigma[2].max(self.params.sigma_min);
        let r = Vector2::new(pt.sigma[0], pt.sigma[1]) / sig;
        let a = &pt.memory.reversal_point;
        let (u, rho) = mapping_direction(&r, a, || {
            let dse = self.elastic_at(pt).2.component_mul(d_eps);
            (Vector2::new(dse[0], dse[1]) - r * dse[2]) / sig
        });
        u.norm() == 0.0 || max_history_distance(a, &u, rho, pt.memory.eta_max).1
    }

    /// All model functions at an integrator point (spec (I3)–(I16)).
    pub fn functions_at(&self, pt: &InterfacePoint, d_eps: &Vector3<f64>) -> PointFunctions {
        let p = &self.params;
        let s = &pt.sigma;
        let (sig, r, de) = self.elastic_at(pt);
        let eta = r.norm();
        let void_ratio = self.void_ratio_at(pt);
        let dse = de.component_mul(d_eps);
        let trial_dr = (Vector2::new(dse[0], dse[1]) - r * dse[2]) / sig;
        let psi = self.state_parameter(s[2], void_ratio, pt.kappa[K_BREAKAGE]);
        let eta_p = self.peak_ratio(psi).max(1e-6);
        let map = mapping(&r, &pt.memory.reversal_point, pt.memory.eta_max, eta_p, &trial_dr);
        let rd_alpha = p.rd * p.alpha;
        // (I14): flow direction, shear unit vector at the image point, current η.
        let e_img = if map.image.norm() > RHO_TINY {
            map.image / map.image.norm()
        } else {
            map.u
        };
        let (gs, gn, _) = direction((p.mc + p.km * psi) * map.ratio, eta, rd_alpha, p.c0);
        let ng = Vector3::new(e_img[0] * gs, e_img[1] * gs, self.normal_flow(gn, void_ratio));
        // (I15): loading direction at the image point, η̄ = |r_C|.
        let eta_bar = map.image.norm();
        let (fs, fnn, _) = direction((p.mf + p.km * psi) * map.ratio, eta_bar, rd_alpha, p.c0);
        let n = Vector3::new(e_img[0] * fs, e_img[1] * fs, fnn);
        // (I16): plastic modulus.
        let fh = match p.fh_mode {
            FhMode::Literal => p.fh,
            FhMode::Memory => (map.ratio * map.ratio).powf(p.fh),
        };
        let h = self.directional_basis(&n) * p.h0 / (1.0 + psi).max(0.05)
            * (sig / p.pa)
            * map.peak_distance
            * (1.0 + map.rho).powi(-2)
            * fh;
        // §8.6 item 4: H + nᵀD^e n_g ≥ 0.05·nᵀD^e n_g (and a positive floor when nᵀD^e n_g ≤ 0).
        let a_dn = n.dot(&de.component_mul(&ng));
        let floor = 0.05 * a_dn.max(0.01 * de[0].min(de[2]));
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

    /// Normal component of the flow direction n_g (I14): the unit-vector component `gn`,
    /// times the square of the closure factor g(e) of [`Self::closure_factor`] where it is
    /// contractive (gn > 0), so that cyclic compaction slows down as x² near e_min.
    fn normal_flow(&self, gn: f64, void_ratio: f64) -> f64 {
        if gn > 0.0 {
            gn * self.closure_factor(void_ratio).powi(2)
        } else {
            gn
        }
    }

    /// Strain-space factor of H0 (I16) along the unit loading direction n (I15):
    ///
    /// ```text
    /// λ_H = λ_s·(n_s² + n_a²) + λ_n·n_n²
    /// ```
    ///
    /// λ_s under shear loading, λ_n under pure normal loading (τ = 0, the c0 limit); the same
    /// λ as D^e when both bases agree.
    fn directional_basis(&self, n: &Vector3<f64>) -> f64 {
        self.basis_factor * (n[0] * n[0] + n[1] * n[1]) + self.normal_factor * n[2] * n[2]
    }

    /// The integrator point of a (closed) state.
    pub fn to_point(&self, st: &GpInterfaceState) -> InterfacePoint {
        let mut kappa = SVector::<f64, KAPPA>::zeros();
        for i in 0..3 {
            kappa[i] = st.strain[i];
            kappa[K_PLASTIC + i] = st.plastic_strain[i];
        }
        kappa[K_WORK] = st.plastic_work;
        kappa[K_BREAKAGE] = st.delta_e_c;
        InterfacePoint {
            sigma: Vector3::from(st.stress),
            kappa,
            memory: InterfaceMemory {
                reversal_point: Vector2::from(st.reversal_point),
                eta_max: st.eta_max,
                sigma_c_max: st.sigma_c_max,
            },
        }
    }

    /// Writes an integrator point into a state (the other fields are left unchanged).
    pub fn write_point(&self, pt: &InterfacePoint, st: &mut GpInterfaceState) {
        for i in 0..3 {
            st.stress[i] = pt.sigma[i];
            st.strain[i] = pt.kappa[i];
            st.plastic_strain[i] = pt.kappa[K_PLASTIC + i];
        }
        st.plastic_work = pt.kappa[K_WORK];
        st.delta_e_c = pt.kappa[K_BREAKAGE];
        st.void_ratio = self.void_ratio_at(pt);
        st.reversal_point = [pt.memory.reversal_point[0], pt.memory.reversal_point[1]];
        st.eta_max = pt.memory.eta_max;
        st.sigma_c_max = pt.memory.sigma_c_max;
    }

    /// The bound of η = |τ|/σ̂_n at a point: η_p(ψ) (spec (I9)) under
    /// `stress_ratio_cap = peak`, none otherwise.
    pub fn ratio_cap(&self, pt: &InterfacePoint) -> Option<f64> {
        match self.params.stress_ratio_cap {
            StressRatioCap::None => None,
            StressRatioCap::Peak => {
                let psi = self.state_parameter(pt.sigma[2], self.void_ratio_at(pt), pt.kappa[K_BREAKAGE]);
                Some(self.peak_ratio(psi))
            }
        }
    }

    /// Scales τ back to |τ| = η_cap·σ̂_n when the point lies outside the cap, σ_n unchanged.
    fn apply_ratio_cap(&self, pt: &mut InterfacePoint) {
        let Some(cap) = self.ratio_cap(pt) else {
            return;
        };
        let limit = cap * pt.sigma[2].max(self.params.sigma_min);
        let tau = pt.sigma[0].hypot(pt.sigma[1]);
        if tau > limit {
            pt.sigma[0] *= limit / tau;
            pt.sigma[1] *= limit / tau;
        }
    }

    /// The continuum tangent of a loading substep that ended on the cap: the Jacobian of the
    /// cap's scaling at the end state times D^ep,
    ///
    /// ```text
    /// D_cap = J·D^ep,   J = [[I − t·tᵀ, η_cap·t·[σ_n > σ_min]], [0, 0, 1]],   t = τ/|τ|,
    /// ```
    ///
    /// so that a point sliding on the peak circle carries no shear stiffness along τ beyond
    /// η_cap·dσ_n (the dependence of η_cap on ψ is left out). Other points keep `d`.
    pub fn capped_tangent(&self, st: &GpInterfaceState, br: Branch, d: Matrix3<f64>) -> Matrix3<f64> {
        let pt = self.to_point(st);
        let (Branch::Loading, Some(cap)) = (br, self.ratio_cap(&pt)) else {
            return d;
        };
        let sig = st.stress[2].max(self.params.sigma_min);
        let tau = st.stress[0].hypot(st.stress[1]);
        if tau < (1.0 - CAP_TOUCH) * cap * sig || tau == 0.0 {
            return d;
        }
        let t = Vector2::new(st.stress[0], st.stress[1]) / tau;
        let normal = if st.stress[2] > self.params.sigma_min {
            cap
        } else {
            0.0
        };
        let j = Matrix3::new(
            1.0 - t[0] * t[0],
            -t[0] * t[1],
            normal * t[0],
            -t[1] * t[0],
            1.0 - t[1] * t[1],
            normal * t[1],
            0.0,
            0.0,
            1.0,
        );
        j * d
    }

    /// Branch flag of a state after a substep on `br` (for output): virgin or cyclic loading
    /// by the mapping (spec (I12)), elastic otherwise.
    pub fn branch_flag(&self, st: &GpInterfaceState, br: Branch, d_eps: &Vector3<f64>) -> GpBranch {
        match br {
            Branch::Loading => {
                if self.virgin_at(&self.to_point(st), d_eps) {
                    GpBranch::Virgin
                } else {
                    GpBranch::Cyclic
                }
            }
            Branch::Elastic | Branch::Unloading => GpBranch::Elastic,
        }
    }
}

impl GpModelFunctions<3, KAPPA> for GpInterface {
    type Memory = InterfaceMemory;

    /// D^e = diag(D_s, D_s, D_n) (spec (I3)–(I5)).
    fn elastic_matrix(&self, pt: &InterfacePoint) -> Matrix3<f64> {
        Matrix3::from_diagonal(&self.elastic_at(pt).2)
    }

    /// Loading: n (I15), n_g (I14) and the guarded H (I16, §8.6 item 4). Unloading (elastic
    /// after the reversal rule): H = ∞.
    fn plastic_data(
        &self,
        pt: &InterfacePoint,
        branch: Branch,
        d_eps: &Vector3<f64>,
    ) -> Result<PlasticData<3>, MaterialError> {
        match branch {
            Branch::Loading => {
                let f = self.functions_at(pt, d_eps);
                let a_dn = f.n.dot(&f.de.component_mul(&f.ng));
                let h = f.denom - a_dn;
                if h.is_nan() || !f.n.iter().chain(f.ng.iter()).all(|x| x.is_finite()) {
                    return Err(MaterialError::new("GP interface: non-finite plastic data"));
                }
                Ok(PlasticData { n: f.n, n_g: f.ng, h })
            }
            Branch::Unloading => Ok(PlasticData {
                n: Vector3::zeros(),
                n_g: Vector3::zeros(),
                h: f64::INFINITY,
            }),
            Branch::Elastic => Err(MaterialError::new(
                "GP interface: plastic data of the elastic branch",
            )),
        }
    }

    /// Cosine of n (I15, at the point's mapping) and dσ^e (spec (I17)).
    fn loading_indicator(
        &self,
        pt: &InterfacePoint,
        d_eps: &Vector3<f64>,
        d_sig_e: &Vector3<f64>,
    ) -> Result<f64, MaterialError> {
        Ok(cosine(&self.functions_at(pt, d_eps).n, d_sig_e))
    }

    /// Loading criterion and reversal rule (spec (I17), (I18)); with `reversal_branch = trial`
    /// a reversal that is not loading at the start is read again at σ + dσe.
    fn begin_substep(
        &self,
        pt: &mut InterfacePoint,
        d_eps: &Vector3<f64>,
        d_sig_e: &Vector3<f64>,
        tol_n: f64,
    ) -> Result<(Branch, f64), MaterialError> {
        let c = self.loading_indicator(pt, d_eps, d_sig_e)?;
        if c > tol_n {
            return Ok((Branch::Loading, c));
        }
        if c < -tol_n {
            pt.memory.reversal_point = self.stress_ratio(&pt.sigma.into());
            let mut c2 = self.loading_indicator(pt, d_eps, d_sig_e)?;
            if c2 <= tol_n && self.params.reversal_branch == ReversalBranch::Trial {
                let mut trial = pt.clone();
                trial.sigma += d_sig_e;
                c2 = self.loading_indicator(&trial, d_eps, d_sig_e)?;
            }
            let br = if c2 > tol_n {
                Branch::Loading
            } else {
                Branch::Unloading
            };
            return Ok((br, c2));
        }
        Ok((Branch::Elastic, c))
    }

    /// dε = dT·Δε; dε^p = dλ·n_g (I20); ⟨dW_p⟩ = ⟨s·dε^p⟩ (I20); dΔe_c = χ⟨dW_p⟩/(a + bW_p)²
    /// with χ = c on cyclic branches (I21).
    fn kappa_increment(&self, pt: &InterfacePoint, stage: &StageIncrement<'_, 3>) -> SVector<f64, KAPPA> {
        let pr = &self.params;
        let mut dk = SVector::<f64, KAPPA>::zeros();
        for i in 0..3 {
            dk[i] = stage.d_eps[i];
        }
        let Some(data) = stage.plastic else {
            return dk;
        };
        let d_plastic = data.n_g * stage.d_lambda;
        for i in 0..3 {
            dk[K_PLASTIC + i] = d_plastic[i];
        }
        let d_work = pt.sigma.dot(&d_plastic).max(0.0);
        let chi = if self.virgin_at(pt, stage.d_eps) {
            1.0
        } else {
            pr.c
        };
        dk[K_WORK] = d_work;
        dk[K_BREAKAGE] = chi * d_work / (pr.a + pr.b * pt.kappa[K_WORK]).powi(2);
        dk
    }

    /// The stress-ratio cap (issue 18, [`StressRatioCap`]), then η_max and σ_c,max updated
    /// (spec G7, (I13)).
    fn after_accept(&self, pt: &mut InterfacePoint, branch: Branch) -> Result<Branch, MaterialError> {
        self.apply_ratio_cap(pt);
        let eta = self.stress_ratio(&pt.sigma.into()).norm();
        pt.memory.eta_max = pt.memory.eta_max.max(eta);
        pt.memory.sigma_c_max = pt.memory.sigma_c_max.max(self.surface_size(pt.sigma[2], eta));
        Ok(branch)
    }

    /// Not used: [`Self::substep_error`] is overridden (σ_min is the stress scale).
    fn error_scales(&self) -> (f64, SVector<f64, KAPPA>) {
        (self.params.sigma_min, SVector::repeat(f64::INFINITY))
    }

    /// R = max(‖Δs2 − Δs1‖/(2‖s̃‖ + σ_min), ‖Δε^p2 − Δε^p1‖·(1+e0)/(2·max(|ẽ|, 0.01)))
    /// (spec §8.2; the second term is the error of the void ratio through ε^p).
    fn substep_error(
        &self,
        new_point: (&Vector3<f64>, &SVector<f64, KAPPA>),
        stage1: (&Vector3<f64>, &SVector<f64, KAPPA>),
        stage2: (&Vector3<f64>, &SVector<f64, KAPPA>),
    ) -> f64 {
        let pr = &self.params;
        let es = (stage2.0 - stage1.0).norm() / (2.0 * new_point.0.norm() + pr.sigma_min);
        let dp = stage2.1.fixed_rows::<3>(K_PLASTIC) - stage1.1.fixed_rows::<3>(K_PLASTIC);
        let e_new = pr.e0 - new_point.1[2] * (1.0 + pr.e0);
        let ee = dp.norm() * (1.0 + pr.e0) / (2.0 * e_new.abs().max(VOID_RATIO_FLOOR));
        es.max(ee)
    }

    /// Opening test (spec §2.12): σ_n ≤ σ_open ends the integration at the crossing,
    /// interpolated linearly in the substep (stress kept at the substep start; the caller
    /// sets it to zero).
    fn stop_in_substep(&self, before: &InterfacePoint, after: &mut InterfacePoint) -> Option<f64> {
        let s_open = self.params.sigma_open;
        if after.sigma[2] > s_open {
            return None;
        }
        let span = before.sigma[2] - after.sigma[2];
        let frac = if span > 0.0 {
            ((before.sigma[2] - s_open) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        after.kappa = before.kappa + (after.kappa - before.kappa) * frac;
        after.sigma = before.sigma;
        after.memory = before.memory;
        Some(frac)
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

    #[test]
    fn closure_factor_is_one_above_e0_and_linear_near_e_min() {
        use crate::material::interface_gp::GpInterfaceParams;
        let m = GpInterface::new(GpInterfaceParams {
            void_ratio_bound: VoidRatioBound::Smooth,
            ..GpInterfaceParams::default()
        })
        .expect("valid");
        let (e0, e_min) = (m.params.e0, m.params.e_min);
        assert_eq!(m.closure_factor(e0), 1.0);
        assert_eq!(m.closure_factor(e0 + 0.1), 1.0);
        // C1 at e0: g = 1 − (1 − x)².
        let x = 0.99;
        let g = m.closure_factor(e_min + x * (e0 - e_min));
        assert!((1.0 - g - (1.0 - x) * (1.0 - x)).abs() < 1e-12, "{g}");
        // g ≈ 2x near e_min, monotonic in between, floored beyond the bound.
        let x = 1e-3;
        let g = m.closure_factor(e_min + x * (e0 - e_min));
        assert!((g / (2.0 * x) - 1.0).abs() < 1e-3, "{g}");
        let samples: Vec<f64> = (0..=100)
            .map(|i| m.closure_factor(e_min + i as f64 * 0.01 * (e0 - e_min)))
            .collect();
        assert!(samples.windows(2).all(|w| w[1] >= w[0]));
        assert_eq!(m.closure_factor(e_min - 0.05), CLOSURE_FACTOR_FLOOR);
        let none = GpInterface::new(GpInterfaceParams {
            void_ratio_bound: VoidRatioBound::None,
            ..GpInterfaceParams::default()
        })
        .expect("valid");
        assert_eq!(none.closure_factor(e_min - 0.05), 1.0);
    }

    #[test]
    fn bandis_closure_factor_is_quadratic_below_e0() {
        use crate::material::interface_gp::GpInterfaceParams;
        let m = GpInterface::new(GpInterfaceParams::default()).expect("valid");
        assert_eq!(m.params.void_ratio_bound, VoidRatioBound::Bandis);
        let (e0, e_min) = (m.params.e0, m.params.e_min);
        assert_eq!(m.closure_factor(e0), 1.0);
        assert_eq!(m.closure_factor(e0 + 0.1), 1.0);
        for x in [0.9, 0.5, 0.1, 1e-2] {
            let g = m.closure_factor(e_min + x * (e0 - e_min));
            assert!((g / (x * x) - 1.0).abs() < 1e-9, "x = {x}: g = {g}");
        }
        assert_eq!(m.closure_factor(e_min - 0.05), CLOSURE_FACTOR_FLOOR);
    }
}
