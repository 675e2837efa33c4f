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
//! ωΔt / (2·atan(ωΔt/2)) (spec seismic §3.4). The static loads (gravity, water) stay applied
//! (load factor 1). K₀ is the stiffness at the stage's start state, frozen (spec
//! seismic §3.3, not the tangent: damping forces then do not jump as points yield).

use super::{Rates, TimeIntegrator};
use crate::linalg::petsc::{Matrix, PetscError, Vector};

/// Newmark's parameters (β, γ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewmarkParameters {
    /// β (1/4: average acceleration).
    pub beta: f64,
    /// γ (1/2: no numerical damping).
    pub gamma: f64,
}

impl Default for NewmarkParameters {
    fn default() -> Self {
        NewmarkParameters {
            beta: 0.25,
            gamma: 0.5,
        }
    }
}

impl NewmarkParameters {
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

    /// ∂a₁/∂u₁ = 1/(β·Δt²), the shift of M in the Jacobian.
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

/// The Newmark integrator's matrices and state (owned DOFs).
pub struct Newmark {
    params: NewmarkParameters,
    damping: Rayleigh,
    mass: Matrix,
    /// K₀ (only when a_K ≠ 0).
    k0: Option<Matrix>,
    ground: GroundMotion,
    u0: Vector,
    v0: Vector,
    a0: Vector,
    dt: f64,
    t1: f64,
}

impl Newmark {
    /// Starts at rest at the displacement `u` (v₀ = a₀ = 0) with mass `mass`, damping on
    /// `mass` and `k0`, and the ground motion `ground`.
    pub fn new(
        params: NewmarkParameters,
        damping: Rayleigh,
        mass: Matrix,
        k0: Option<Matrix>,
        ground: GroundMotion,
        u: &Vector,
    ) -> Result<Self, PetscError> {
        let mut u0 = u.duplicate()?;
        u0.copy_from(u)?;
        let mut v0 = u.duplicate()?;
        v0.set_all(0.0)?;
        let mut a0 = u.duplicate()?;
        a0.set_all(0.0)?;
        Ok(Newmark {
            params,
            damping,
            mass,
            k0,
            ground,
            u0,
            v0,
            a0,
            dt: 0.0,
            t1: 0.0,
        })
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
}

impl TimeIntegrator for Newmark {
    fn load_factor(&self, _t1: f64) -> f64 {
        1.0
    }

    fn begin_step(&mut self, t0: f64, t1: f64) {
        self.dt = t1 - t0;
        self.t1 = t1;
    }

    fn inertia(&self, x: &Vector) -> Result<Option<Vector>, PetscError> {
        let (mut a1, v1) = self.rates_at(x)?;
        // M·(a₁ + a_M·v₁ + ι·a_g(t₁)): the ground acceleration on every node's three components
        let ag = (self.ground)(self.t1);
        let a_m = self.damping.mass;
        let vs = v1.read(|s| s.to_vec())?;
        a1.write(|s| {
            for (i, v) in s.iter_mut().enumerate() {
                *v += a_m * vs[i] + ag[i % 3];
            }
        })?;
        let mut g = x.duplicate()?;
        self.mass.mult(&a1, &mut g)?;
        if let Some(k0) = &self.k0 {
            let mut kv = x.duplicate()?;
            k0.mult(&v1, &mut kv)?;
            g.axpy(self.damping.stiffness, &kv)?;
        }
        Ok(Some(g))
    }

    fn add_shifts(&self, j: &mut Matrix) -> Result<(), PetscError> {
        let (sa, sv) = (self.params.shift_a(self.dt), self.params.shift_v(self.dt));
        j.axpy(sa + sv * self.damping.mass, &self.mass)?;
        if let Some(k0) = &self.k0 {
            j.axpy(sv * self.damping.stiffness, k0)?;
        }
        Ok(())
    }

    fn accept(&mut self, u1: &Vector) -> Result<(), PetscError> {
        let (a1, v1) = self.rates_at(u1)?;
        self.u0.copy_from(u1)?;
        self.v0 = v1;
        self.a0 = a1;
        Ok(())
    }

    fn rates(&self) -> Result<Option<Rates>, PetscError> {
        Ok(Some(Rates {
            velocity: self.v0.read(|s| s.to_vec())?,
            acceleration: self.a0.read(|s| s.to_vec())?,
            ground: (self.ground)(self.t1),
        }))
    }

    fn restore_rates(&mut self, u: &Vector, rates: &Rates) -> Result<(), PetscError> {
        self.u0.copy_from(u)?;
        self.v0.write(|s| s.copy_from_slice(&rates.velocity))?;
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

    #[test]
    fn rayleigh_gives_the_ratio_at_both_anchors() {
        let r = Rayleigh::from_frequencies(0.05, 1.0, 5.0);
        assert!((r.ratio_at(1.0) - 0.05).abs() < 1e-12);
        assert!((r.ratio_at(5.0) - 0.05).abs() < 1e-12);
        assert!(r.ratio_at(2.5) < 0.05);
    }
}
