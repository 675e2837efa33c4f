//! Newmark's implicit time integration (spec seismic §3.4) in the relative-displacement form
//! of a rigid base moving with the ground acceleration a_g(t) (spec seismic §3.1–3.2):
//!
//! ```text
//! M·(ü + ι·a_g(t)) + C·u̇ + f_int(u) = f_static
//! a₁ = (u₁ − u₀)/(β·Δt²) − v₀/(β·Δt) − (1/(2β) − 1)·a₀
//! v₁ = v₀ + Δt·((1 − γ)·a₀ + γ·a₁)
//! J  = K_t + (γ/(β·Δt))·C + (1/(β·Δt²))·M,     C = a_M·M + a_K·K₀ (Rayleigh)
//! ```
//! β = 1/4, γ = 1/2 (average acceleration, the default) is unconditionally stable, second-order
//! accurate and conserves the energy of a linear undamped system; its period elongation is
//! ωΔt / (2·atan(ωΔt/2)) (spec seismic §3.4).
//!
//! **HHT-α** (Hilber, Hughes and Taylor 1977), in the force-averaged form of spec architecture
//! that keeps the material states at u₁, with −1/3 ≤ α ≤ 0, β = (1 − α)²/4, γ = 1/2 − α:
//!
//! ```text
//! M·a₁ + (1+α)·(C·v₁ + f_int(u₁) − f_ext) − α·h₀ + M·ι·((1+α)·a_g(t₁) − α·a_g(t₀)) = 0
//! h₀ = C·v₀ + f_int(u₀) − f_ext      (the committed step's, kept between steps)
//! ```
//! divided by 1+α so that f_int and f_ext keep the weight 1 of the Newton step:
//! g = M·(a₁/(1+α) + a_M·v₁ + ι·(a_g(t₁) − α/(1+α)·a_g(t₀))) + a_K·K₀·v₁ − α/(1+α)·h₀ and
//! J = K_t + (γ/(β·Δt))·C + (1/((1+α)·β·Δt²))·M. At convergence the equation gives
//! h₁ = α/(1+α)·h₀ − M·(a₁/(1+α) + ι·(a_g(t₁) − α/(1+α)·a_g(t₀))) (exact up to the Newton
//! residual), so no f_int is stored. The spectral radius at ωΔt → ∞ is (1+α)/(1−α): the
//! modes that the time step cannot resolve are damped, those it resolves hardly at all. h
//! starts at 0 (the static state is in equilibrium) and is part of a step checkpoint.
//! α = 0 is Newmark's average acceleration, bit for bit. The static loads (gravity, water) stay applied
//! (load factor 1). K₀ is the stiffness at the stage's start state, frozen (spec
//! seismic §3.3, not the tangent: damping forces then do not jump as points yield).

use super::{Rates, TimeIntegrator};
use crate::linalg::petsc::{CanonicalProduct, Matrix, PetscError, Vector};

/// Newmark's parameters (β, γ) and HHT-α's α.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewmarkParameters {
    /// β (1/4: average acceleration).
    pub beta: f64,
    /// γ (1/2: no numerical damping).
    pub gamma: f64,
    /// HHT-α's α ∈ [−1/3, 0] (0: Newmark).
    pub alpha: f64,
}

impl Default for NewmarkParameters {
    fn default() -> Self {
        NewmarkParameters {
            beta: 0.25,
            gamma: 0.5,
            alpha: 0.0,
        }
    }
}

impl NewmarkParameters {
    /// HHT-α with `alpha`: β = (1 − α)²/4, γ = 1/2 − α (module docs).
    pub fn hht(alpha: f64) -> Self {
        NewmarkParameters {
            beta: 0.25 * (1.0 - alpha) * (1.0 - alpha),
            gamma: 0.5 - alpha,
            alpha,
        }
    }

    /// 1/(1+α), the weight of the inertia force M·a₁ in the step's equation (module docs).
    pub fn inertia_weight(&self) -> f64 {
        1.0 / (1.0 + self.alpha)
    }

    /// α/(1+α), the weight of the committed step's forces (h₀, a_g(t₀)).
    pub fn history_weight(&self) -> f64 {
        self.alpha / (1.0 + self.alpha)
    }

    /// The acceleration a₁ of the end displacement `u1` from the start state (u₀, v₀, a₀) over
    /// `dt`.
    pub fn acceleration(&self, dt: f64, u1: f64, u0: f64, v0: f64, a0: f64) -> f64 {
        let b = self.beta;
        (u1 - u0) / (b * dt * dt) - v0 / (b * dt) - (0.5 / b - 1.0) * a0
    }

    /// The velocity v₁ from v₀, a₀ and the end acceleration `a1`.
    pub fn velocity(&self, dt: f64, v0: f64, a0: f64, a1: f64) -> f64 {
        v0 + dt * ((1.0 - self.gamma) * a0 + self.gamma * a1)
    }

    /// ∂a₁/∂u₁ = 1/(β·Δt²) (times 1/(1+α) in the Jacobian's shift of M).
    pub fn shift_a(&self, dt: f64) -> f64 {
        1.0 / (self.beta * dt * dt)
    }

    /// ∂v₁/∂u₁ = γ/(β·Δt), the shift of C in the Jacobian.
    pub fn shift_v(&self, dt: f64) -> f64 {
        self.gamma / (self.beta * dt)
    }
}

/// Rayleigh damping C = a_M·M + a_K·K₀ (spec seismic §3.3).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Rayleigh {
    /// Mass coefficient a_M (1/s).
    pub mass: f64,
    /// Stiffness coefficient a_K (s).
    pub stiffness: f64,
}

impl Rayleigh {
    /// The coefficients that give the damping ratio `ratio` at the frequencies `f1` and `f2`
    /// (Hz): a_M = 2ζω₁ω₂/(ω₁+ω₂), a_K = 2ζ/(ω₁+ω₂).
    pub fn from_frequencies(ratio: f64, f1: f64, f2: f64) -> Self {
        let (w1, w2) = (2.0 * std::f64::consts::PI * f1, 2.0 * std::f64::consts::PI * f2);
        Rayleigh {
            mass: 2.0 * ratio * w1 * w2 / (w1 + w2),
            stiffness: 2.0 * ratio / (w1 + w2),
        }
    }

    /// The damping ratio at the frequency `f` (Hz): a_M/(2ω) + a_K·ω/2.
    pub fn ratio_at(&self, f: f64) -> f64 {
        let w = 2.0 * std::f64::consts::PI * f;
        self.mass / (2.0 * w) + self.stiffness * w / 2.0
    }
}

/// The ground acceleration (m/s², our axes x, y, z) at a time of the stage.
pub type GroundMotion = Box<dyn Fn(f64) -> [f64; 3]>;

/// The Newmark (or HHT-α) integrator's matrices and state (owned DOFs).
pub struct Newmark {
    params: NewmarkParameters,
    damping: Rayleigh,
    mass: Matrix,
    /// K₀ (only when a_K ≠ 0).
    k0: Option<Matrix>,
    /// M·x and K₀·x summed in the mesh's DOF order (rank-count independent).
    mass_product: CanonicalProduct,
    k0_product: Option<CanonicalProduct>,
    ground: GroundMotion,
    u0: Vector,
    v0: Vector,
    a0: Vector,
    /// HHT-α's committed force history h₀ (only when α ≠ 0; module docs).
    h0: Option<Vector>,
    dt: f64,
    t0: f64,
    t1: f64,
    /// Start a step's Newton iterations from the committed rates ([`Newmark::extrapolating`]).
    extrapolate: bool,
}

impl Newmark {
    /// Starts at rest at the displacement `u` (v₀ = a₀ = 0, h₀ = 0) with mass `mass`, damping
    /// on `mass` and `k0`, and the ground motion `ground`; `mesh_order` lists the PETSc index
    /// of every DOF in the mesh's order, the order in which the products with M and K₀ sum.
    pub fn new(
        params: NewmarkParameters,
        damping: Rayleigh,
        (mass, k0): (Matrix, Option<Matrix>),
        ground: GroundMotion,
        u: &Vector,
        mesh_order: &[i32],
    ) -> Result<Self, PetscError> {
        let zero = || -> Result<Vector, PetscError> {
            let mut z = u.duplicate()?;
            z.set_all(0.0)?;
            Ok(z)
        };
        let mut u0 = u.duplicate()?;
        u0.copy_from(u)?;
        let h0 = match params.alpha != 0.0 {
            true => Some(zero()?),
            false => None,
        };
        let mass_product = CanonicalProduct::new(&mass, u, mesh_order)?;
        let k0_product = match &k0 {
            Some(k) => Some(CanonicalProduct::new(k, u, mesh_order)?),
            None => None,
        };
        Ok(Newmark {
            params,
            damping,
            mass,
            k0,
            mass_product,
            k0_product,
            ground,
            u0,
            v0: zero()?,
            a0: zero()?,
            h0,
            dt: 0.0,
            t0: 0.0,
            t1: 0.0,
            extrapolate: false,
        })
    }

    /// The same integrator, predicting each step with the committed velocity kept over it
    /// (spec seismic §3.4):
    ///
    /// ```text
    /// x⁰ = u₀ + Δt·v₀
    /// ```
    ///
    /// With average acceleration Newmark's relations give v₁ = v₀ at the guess. The velocity
    /// is part of a step checkpoint, so a restart predicts the same. The guess changes the
    /// Newton iterations, not what they converge to: every iteration integrates the materials
    /// from the committed state (spec models §8.1). Carrying the acceleration too
    /// (x⁰ = u₀ + Δt·v₀ + Δt²/2·a₀, a₁ = a₀) was measured and dropped: average acceleration
    /// keeps the unresolved modes' noise in a₀, and the seed quake took 13 % more Newton
    /// iterations with it ([`crate::performance`], "The seed quake (coarse mesh)").
    pub fn extrapolating(self) -> Self {
        Newmark {
            extrapolate: true,
            ..self
        }
    }

    /// a₁ and v₁ of the end displacement `x` (owned DOFs).
    fn rates_at(&self, x: &Vector) -> Result<(Vector, Vector), PetscError> {
        let (p, dt) = (self.params, self.dt);
        let mut a1 = x.duplicate()?;
        let mut v1 = x.duplicate()?;
        let xs = x.read(|s| s.to_vec())?;
        let u0 = self.u0.read(|s| s.to_vec())?;
        let v0 = self.v0.read(|s| s.to_vec())?;
        let a0 = self.a0.read(|s| s.to_vec())?;
        let acc: Vec<f64> = (0..xs.len())
            .map(|i| p.acceleration(dt, xs[i], u0[i], v0[i], a0[i]))
            .collect();
        a1.write(|s| s.copy_from_slice(&acc))?;
        v1.write(|s| {
            for i in 0..s.len() {
                s[i] = p.velocity(dt, v0[i], a0[i], acc[i]);
            }
        })?;
        Ok((a1, v1))
    }

    /// The ground acceleration of the step's equation: a_g(t₁), and with HHT-α
    /// a_g(t₁) − α/(1+α)·a_g(t₀) (module docs).
    fn ground_term(&self) -> [f64; 3] {
        let g1 = (self.ground)(self.t1);
        if self.params.alpha == 0.0 {
            return g1;
        }
        let (g0, w) = ((self.ground)(self.t0), self.params.history_weight());
        [g1[0] - w * g0[0], g1[1] - w * g0[1], g1[2] - w * g0[2]]
    }

    /// M·(a₁/(1+α) + ι·ground_term + a_M·`v1`) into a new vector (`v1` `None`: without the
    /// damping term), overwriting `a1`.
    fn mass_force(&self, a1: &mut Vector, v1: Option<&Vector>) -> Result<Vector, PetscError> {
        let (wi, ag, a_m) = (
            self.params.inertia_weight(),
            self.ground_term(),
            self.damping.mass,
        );
        let vs = match v1 {
            Some(v) => v.read(|s| s.to_vec())?,
            None => Vec::new(),
        };
        a1.write(|s| {
            for (i, v) in s.iter_mut().enumerate() {
                let damping = vs.get(i).map_or(0.0, |vi| a_m * vi);
                *v = wi * *v + (damping + ag[i % 3]);
            }
        })?;
        let mut g = a1.duplicate()?;
        self.mass_product.mult(a1, &mut g)?;
        Ok(g)
    }
}

impl TimeIntegrator for Newmark {
    fn load_factor(&self, _t1: f64) -> f64 {
        1.0
    }

    fn begin_step(&mut self, t0: f64, t1: f64) {
        self.dt = t1 - t0;
        self.t0 = t0;
        self.t1 = t1;
    }

    fn predict(&mut self, x: &mut Vector) -> Result<(), PetscError> {
        if !self.extrapolate {
            return Ok(());
        }
        let dt = self.dt;
        let v0 = self.v0.read(|s| s.to_vec())?;
        x.write(|s| {
            for (i, xi) in s.iter_mut().enumerate() {
                *xi += dt * v0[i];
            }
        })
    }

    fn inertia(&self, x: &Vector) -> Result<Option<Vector>, PetscError> {
        let (mut a1, v1) = self.rates_at(x)?;
        // M·(a₁/(1+α) + a_M·v₁ + ι·a_g): the ground acceleration on every node's three components
        let mut g = self.mass_force(&mut a1, Some(&v1))?;
        if let Some(k0) = &self.k0_product {
            let mut kv = x.duplicate()?;
            k0.mult(&v1, &mut kv)?;
            g.axpy(self.damping.stiffness, &kv)?;
        }
        if let Some(h0) = &self.h0 {
            g.axpy(-self.params.history_weight(), h0)?;
        }
        Ok(Some(g))
    }

    fn add_shifts(&self, j: &mut Matrix) -> Result<(), PetscError> {
        let p = self.params;
        let (sa, sv) = (p.inertia_weight() * p.shift_a(self.dt), p.shift_v(self.dt));
        j.axpy(sa + sv * self.damping.mass, &self.mass)?;
        if let Some(k0) = &self.k0 {
            j.axpy(sv * self.damping.stiffness, k0)?;
        }
        Ok(())
    }

    fn accept(&mut self, u1: &Vector) -> Result<(), PetscError> {
        let (mut a1, v1) = self.rates_at(u1)?;
        if self.h0.is_some() {
            // h₁ = α/(1+α)·h₀ − M·(a₁/(1+α) + ι·ground_term) (module docs)
            let mut a_scaled = a1.duplicate()?;
            a_scaled.copy_from(&a1)?;
            let m_term = self.mass_force(&mut a_scaled, None)?;
            let w = self.params.history_weight();
            if let Some(h0) = &mut self.h0 {
                let m: Vec<f64> = m_term.read(|m| m.to_vec())?;
                h0.write(|h| h.iter_mut().zip(&m).for_each(|(h, m)| *h = w * *h - m))?;
            }
        }
        self.u0.copy_from(u1)?;
        self.v0 = v1;
        std::mem::swap(&mut self.a0, &mut a1);
        Ok(())
    }

    fn rates(&self) -> Result<Option<Rates>, PetscError> {
        Ok(Some(Rates {
            velocity: self.v0.read(|s| s.to_vec())?,
            acceleration: self.a0.read(|s| s.to_vec())?,
            ground: (self.ground)(self.t1),
            history: match &self.h0 {
                Some(h) => h.read(|s| s.to_vec())?,
                None => Vec::new(),
            },
        }))
    }

    fn restore_rates(&mut self, u: &Vector, rates: &Rates) -> Result<(), PetscError> {
        self.u0.copy_from(u)?;
        self.v0.write(|s| s.copy_from_slice(&rates.velocity))?;
        if let Some(h0) = &mut self.h0 {
            h0.write(|s| s.copy_from_slice(&rates.history))?;
        }
        self.a0.write(|s| s.copy_from_slice(&rates.acceleration))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Free vibration of an undamped unit oscillator (ω = 2π) from u = 1 by the scalar
    /// Newmark update: the measured period over `n` cycles.
    fn measured_period(p: NewmarkParameters, dt: f64, cycles: usize) -> f64 {
        let w2 = (2.0 * std::f64::consts::PI).powi(2);
        let (mut u, mut v, mut a) = (1.0f64, 0.0f64, -w2);
        let mut crossings = Vec::new();
        let mut t = 0.0;
        while crossings.len() < 2 * cycles + 1 {
            // linear SDOF: solve (shift_a + ω²)·u₁ = shift_a·u₀ + … in closed form
            let sa = p.shift_a(dt);
            let rhs = sa * u + v / (p.beta * dt) + (0.5 / p.beta - 1.0) * a;
            let u1 = rhs / (sa + w2);
            let a1 = p.acceleration(dt, u1, u, v, a);
            let v1 = p.velocity(dt, v, a, a1);
            if u > 0.0 && u1 <= 0.0 || u < 0.0 && u1 >= 0.0 {
                crossings.push(t + dt * u / (u - u1));
            }
            (u, v, a, t) = (u1, v1, a1, t + dt);
        }
        (crossings[2 * cycles] - crossings[0]) / cycles as f64
    }

    #[test]
    fn average_acceleration_period_elongation_matches_the_closed_form() {
        // spec seismic §4 item 3: 1.00033, 1.00817, 1.03207 at Δt/T = 0.01, 0.05, 0.10
        for (ratio, want) in [(0.01, 1.00033), (0.05, 1.00817), (0.10, 1.03207)] {
            let t = measured_period(NewmarkParameters::default(), ratio, 200);
            assert!(
                (t - want).abs() < 2e-5,
                "Δt/T = {ratio}: period {t}, closed form {want}"
            );
        }
    }

    #[test]
    fn average_acceleration_conserves_the_energy_of_a_linear_oscillator() {
        let p = NewmarkParameters::default();
        let (w2, dt) = ((2.0 * std::f64::consts::PI).powi(2), 0.07);
        let (mut u, mut v, mut a) = (1.0f64, 0.0f64, -w2);
        let energy = |u: f64, v: f64| 0.5 * v * v + 0.5 * w2 * u * u;
        let e0 = energy(u, v);
        for _ in 0..10_000 {
            let sa = p.shift_a(dt);
            let u1 = (sa * u + v / (p.beta * dt) + (0.5 / p.beta - 1.0) * a) / (sa + w2);
            let a1 = p.acceleration(dt, u1, u, v, a);
            (v, a, u) = (p.velocity(dt, v, a, a1), a1, u1);
            assert!((energy(u, v) / e0 - 1.0).abs() < 1e-10);
        }
    }

    /// One HHT-α step of the unit-mass undamped oscillator k = ω² from (u₀, v₀, a₀), with
    /// h₀ = k·u₀: the scalar form of [`Newmark::inertia`] solved exactly (module docs).
    fn hht_step(p: NewmarkParameters, w2: f64, dt: f64, (u, v, a): (f64, f64, f64)) -> (f64, f64, f64) {
        let sa = p.shift_a(dt);
        let known = sa * u + v / (p.beta * dt) + (0.5 / p.beta - 1.0) * a;
        let u1 = (p.inertia_weight() * known + p.history_weight() * w2 * u) / (w2 + p.inertia_weight() * sa);
        let a1 = p.acceleration(dt, u1, u, v, a);
        (u1, p.velocity(dt, v, a, a1), a1)
    }

    /// Spectral radius of the step's amplification matrix on (u, v, a) at ω·Δt = `wdt`.
    fn spectral_radius(p: NewmarkParameters, wdt: f64) -> f64 {
        let (w2, dt) = (wdt * wdt, 1.0);
        let columns: Vec<(f64, f64, f64)> = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
            .into_iter()
            .map(|x| hht_step(p, w2, dt, x))
            .collect();
        let m = nalgebra::Matrix3::from_fn(|i, j| {
            let c = columns[j];
            [c.0, c.1, c.2][i]
        });
        m.complex_eigenvalues()
            .iter()
            .map(|z| z.norm())
            .fold(0.0, f64::max)
    }

    #[test]
    fn hht_damps_the_unresolved_modes_by_its_closed_form_spectral_radius() {
        // ρ∞ = (1 + α)/(1 − α) (Hilber, Hughes and Taylor 1977); α = 0: ρ = 1 at every ωΔt
        for alpha in [0.0, -0.05, -0.1, -1.0 / 3.0] {
            let p = NewmarkParameters::hht(alpha);
            let rho = spectral_radius(p, 1e6);
            let want = (1.0 + alpha) / (1.0 - alpha);
            println!("HHT α = {alpha:.4}: ρ(ωΔt = 1e6) = {rho:.6}, closed form {want:.6}");
            assert!(
                (rho - want).abs() < 1e-3,
                "α = {alpha}: ρ(ωΔt = 1e6) = {rho}, closed form {want}"
            );
            assert!(
                spectral_radius(p, 0.1) <= 1.0 + 1e-12,
                "α = {alpha}: unstable at ωΔt = 0.1"
            );
        }
        assert_eq!(NewmarkParameters::hht(0.0), NewmarkParameters::default());
    }

    #[test]
    fn hht_is_second_order_accurate_on_a_free_vibration() {
        // largest error of u against cos(2πt) over 10 periods: halving Δt divides it by 4
        // (second order)
        let p = NewmarkParameters::hht(-0.1);
        let w2 = (2.0 * std::f64::consts::PI).powi(2);
        let error = |steps_per_period: usize| {
            let dt = 1.0 / steps_per_period as f64;
            let (mut x, mut worst) = ((1.0, 0.0, -w2), 0.0f64);
            for n in 1..=10 * steps_per_period {
                x = hht_step(p, w2, dt, x);
                let exact = (2.0 * std::f64::consts::PI * n as f64 * dt).cos();
                worst = worst.max((x.0 - exact).abs());
            }
            worst
        };
        let (coarse, fine) = (error(100), error(200));
        let order = (coarse / fine).log2();
        println!("HHT α = -0.1, 100 / 200 steps per period: largest errors {coarse:.3e} / {fine:.3e}, order {order:.3}");
        assert!(
            (order - 2.0).abs() < 0.1,
            "errors {coarse:e} and {fine:e}: order {order}"
        );
    }

    #[test]
    fn rayleigh_gives_the_ratio_at_both_anchors() {
        let r = Rayleigh::from_frequencies(0.05, 1.0, 5.0);
        assert!((r.ratio_at(1.0) - 0.05).abs() < 1e-12);
        assert!((r.ratio_at(5.0) - 0.05).abs() < 1e-12);
        assert!(r.ratio_at(2.5) < 0.05);
    }
}
