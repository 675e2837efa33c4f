//! Mixed-control material-point driver for any [`SolidModel`] (spec §9 preamble).
//!
//! A path is a list of [`StepControl`]s. In each step every Voigt component
//! `[xx, yy, zz, xy, yz, zx]` is either strain controlled (a prescribed strain *increment*) or
//! stress controlled (a prescribed stress *value* at the end of the step, Pa, tension positive).
//! The unknown strain increments of the stress-controlled components are found by Newton's
//! method with the model's tangent, to a relative residual of 10⁻⁸ (of max(‖σ‖, 1 kPa)).
//! Every Newton iterate re-integrates the model from the committed state of the step with the
//! total step increment (spec §8.1). If Newton fails (no convergence, or the model returns an
//! error), the driver retries with the elastic tangent when one was supplied
//! ([`MaterialPointDriver::with_elastic_tangent`]), then halves the step (recursively, up to
//! [`DriverOptions::max_halvings`] levels).
//!
//! The results are [`DriverRow`]s, one per user step, holding plain numbers (SI, tension
//! positive, except p, q, ε_v, ε_q which are the geotechnical compression-positive invariants).
//!
//! The path helpers take **compression-positive pressures in Pa** (as a geotechnical test is
//! described) and use **z (index 2) as the axial direction**, x and y as the lateral ones.
//!
//! ```text
//! let model = RockfillGp::new(RockfillGpParams::default())?;
//! let mut driver = MaterialPointDriver::new(&model, &Stress6::isotropic(-100e3))?;
//! driver.run(&isotropic_compression(100e3, 2000e3, 100))?;
//! driver.run(&triaxial_compression(2000e3, 0.15, 1500))?;
//! for row in driver.rows() { println!("{} {} {}", row.eps_q, row.q, row.eps_v); }
//! ```

use super::rockfill_gp::{deviatoric_invariant, invariants_compression_positive};
use super::SolidModel;
use crate::error::MaterialError;
use crate::tensor::{Strain6, Stress6, Tangent6, Vector6};
use nalgebra::DMatrix;
use nalgebra::DVector;

/// Control of one Voigt component in one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Control {
    /// Prescribed strain increment of the step (tension positive, engineering shear).
    Strain(f64),
    /// Prescribed stress at the end of the step (Pa, tension positive).
    Stress(f64),
}

/// The control of the six Voigt components `[xx, yy, zz, xy, yz, zx]` in one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepControl(pub [Control; 6]);

impl StepControl {
    /// A fully strain-controlled step with the increment `d_eps`.
    pub fn strain(d_eps: [f64; 6]) -> Self {
        StepControl(d_eps.map(Control::Strain))
    }
    /// A fully stress-controlled step to the stress `sigma` (Pa, tension positive).
    pub fn stress(sigma: [f64; 6]) -> Self {
        StepControl(sigma.map(Control::Stress))
    }
}

/// One output row (the state at the end of a user step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriverRow {
    /// Step number, 1-based over the driver's life (0 is the initial state).
    pub step: usize,
    /// Total strain since the start of the driver (tension positive, engineering shear).
    pub strain: [f64; 6],
    /// Stress (Pa, tension positive).
    pub stress: [f64; 6],
    /// Mean pressure p (Pa, compression positive).
    pub p: f64,
    /// Deviatoric stress q = √(3J2) (Pa).
    pub q: f64,
    /// Volumetric strain ε_v (compression positive).
    pub eps_v: f64,
    /// Deviatoric strain invariant ε_q = √(2/3·e:e).
    pub eps_q: f64,
}

/// Options of the driver's Newton solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriverOptions {
    /// Relative tolerance on the stress-controlled residual (default 10⁻⁸).
    pub tolerance: f64,
    /// Stress scale below which the tolerance is absolute (Pa, default 10³).
    pub stress_floor: f64,
    /// Largest number of Newton iterations per attempt (default 30).
    pub max_iterations: u32,
    /// Largest number of recursive step halvings (default 12).
    pub max_halvings: u32,
}

impl Default for DriverOptions {
    fn default() -> Self {
        DriverOptions {
            tolerance: 1.0e-8,
            stress_floor: 1.0e3,
            max_iterations: 30,
            max_halvings: 12,
        }
    }
}

/// A fallback tangent provider: the elastic tangent of a state.
pub type ElasticTangentFn<'a, S> = Box<dyn Fn(&S) -> Tangent6 + 'a>;

/// Material-point driver over a [`SolidModel`]: holds the committed state, the total strain,
/// the last tangent and the output rows.
pub struct MaterialPointDriver<'a, M: SolidModel> {
    model: &'a M,
    state: M::State,
    strain: Vector6,
    tangent: Option<Tangent6>,
    elastic_tangent: Option<ElasticTangentFn<'a, M::State>>,
    options: DriverOptions,
    rows: Vec<DriverRow>,
    substeps: u64,
}

impl<'a, M: SolidModel> MaterialPointDriver<'a, M> {
    /// Starts at the stress `sigma0` (Pa, tension positive) through `model.init_state`.
    /// Row 0 is the initial state.
    pub fn new(model: &'a M, sigma0: &Stress6) -> Result<Self, MaterialError> {
        let state = model.init_state(sigma0)?;
        Ok(Self::from_state(model, state))
    }

    /// Starts from a given state (zero strain). Row 0 is that state.
    pub fn from_state(model: &'a M, state: M::State) -> Self {
        let mut d = MaterialPointDriver {
            model,
            state,
            strain: Vector6::zeros(),
            tangent: None,
            elastic_tangent: None,
            options: DriverOptions::default(),
            rows: Vec::new(),
            substeps: 0,
        };
        d.rows.push(d.row(0));
        d
    }

    /// Sets the Newton options.
    pub fn with_options(mut self, options: DriverOptions) -> Self {
        self.options = options;
        self
    }

    /// Supplies an elastic tangent, used as the first fallback when Newton fails.
    pub fn with_elastic_tangent(mut self, f: impl Fn(&M::State) -> Tangent6 + 'a) -> Self {
        self.elastic_tangent = Some(Box::new(f));
        self
    }

    /// The committed state.
    pub fn state(&self) -> &M::State {
        &self.state
    }

    /// All rows so far (row 0 = initial state).
    pub fn rows(&self) -> &[DriverRow] {
        &self.rows
    }

    /// The last row.
    pub fn last(&self) -> &DriverRow {
        self.rows.last().expect("row 0 always exists")
    }

    /// Total model substeps used so far (sum of `SolidUpdate::substeps`).
    pub fn substeps(&self) -> u64 {
        self.substeps
    }

    /// The tangent returned by the last converged update, if any.
    pub fn tangent(&self) -> Option<&Tangent6> {
        self.tangent.as_ref()
    }

    /// Runs the steps in order; a row is appended after each. Stops at the first failure.
    pub fn run(&mut self, steps: &[StepControl]) -> Result<(), MaterialError> {
        for s in steps {
            self.step(s)?;
        }
        Ok(())
    }

    /// Runs one step (with fallbacks), commits it and appends a row.
    pub fn step(&mut self, control: &StepControl) -> Result<&DriverRow, MaterialError> {
        self.step_recursive(control, 0)?;
        let n = self.rows.len();
        self.rows.push(self.row(n));
        Ok(self.last())
    }

    /// Solves a step; on failure splits it into two halves (strain increments halved, stress
    /// targets first at the midpoint between the current stress and the target).
    fn step_recursive(&mut self, control: &StepControl, depth: u32) -> Result<(), MaterialError> {
        match self.solve(control) {
            Ok(()) => Ok(()),
            Err(e) if depth >= self.options.max_halvings => Err(MaterialError::new(format!(
                "driver: step failed after {depth} halvings: {e}"
            ))),
            Err(_) => {
                let here = M::stress(&self.state).0;
                let first = StepControl(std::array::from_fn(|i| match control.0[i] {
                    Control::Strain(d) => Control::Strain(0.5 * d),
                    Control::Stress(t) => Control::Stress(0.5 * (here[i] + t)),
                }));
                let second = StepControl(control.0.map(|c| match c {
                    Control::Strain(d) => Control::Strain(0.5 * d),
                    other => other,
                }));
                self.step_recursive(&first, depth + 1)?;
                self.step_recursive(&second, depth + 1)
            }
        }
    }

    /// Newton on the stress-controlled components of one (sub)step; commits on success.
    fn solve(&mut self, control: &StepControl) -> Result<(), MaterialError> {
        match self.newton(control, false) {
            Ok(()) => Ok(()),
            Err(e) if self.elastic_tangent.is_some() => self.newton(control, true).map_err(|_| e),
            Err(e) => Err(e),
        }
    }

    fn newton(&mut self, control: &StepControl, use_elastic: bool) -> Result<(), MaterialError> {
        let stress_idx: Vec<usize> = (0..6)
            .filter(|&i| matches!(control.0[i], Control::Stress(_)))
            .collect();
        let mut d_eps = Vector6::zeros();
        let mut target = Vector6::zeros();
        for i in 0..6 {
            match control.0[i] {
                Control::Strain(d) => d_eps[i] = d,
                Control::Stress(s) => target[i] = s,
            }
        }
        let sig0 = M::stress(&self.state).0;
        // Predictor with the last tangent (or the model's tangent at zero increment).
        let mut tangent = match (use_elastic, &self.elastic_tangent, &self.tangent) {
            (true, Some(elastic), _) => elastic(&self.state),
            (_, _, Some(t)) => *t,
            _ => self.model.update(&self.state, &Strain6::default())?.tangent,
        };
        if !stress_idx.is_empty() {
            let rhs_full = target - sig0 - tangent.0 * d_eps;
            let corr = solve_sub(&tangent, &stress_idx, &rhs_full)?;
            for (k, &i) in stress_idx.iter().enumerate() {
                d_eps[i] += corr[k];
            }
        }
        for _ in 0..=self.options.max_iterations {
            let up = self.model.update(&self.state, &Strain6(d_eps))?;
            let sig = M::stress(&up.state).0;
            let scale = sig.amax().max(target.amax()).max(self.options.stress_floor);
            let mut res_norm = 0.0_f64;
            for &i in &stress_idx {
                res_norm = res_norm.max((target[i] - sig[i]).abs());
            }
            if !res_norm.is_finite() {
                return Err(MaterialError::new("driver: non-finite residual"));
            }
            if res_norm <= self.options.tolerance * scale {
                self.state = up.state;
                self.strain += d_eps;
                self.tangent = Some(up.tangent);
                self.substeps += u64::from(up.substeps);
                return Ok(());
            }
            if !use_elastic {
                tangent = up.tangent;
            }
            let corr = solve_sub(&tangent, &stress_idx, &(target - sig))?;
            for (k, &i) in stress_idx.iter().enumerate() {
                d_eps[i] += corr[k];
            }
        }
        Err(MaterialError::new("driver: Newton did not converge"))
    }

    fn row(&self, step: usize) -> DriverRow {
        let sig = M::stress(&self.state).0;
        let inv = invariants_compression_positive(&sig);
        let e = &self.strain;
        DriverRow {
            step,
            strain: std::array::from_fn(|i| e[i]),
            stress: std::array::from_fn(|i| sig[i]),
            p: inv.p,
            q: inv.q,
            eps_v: -(e[0] + e[1] + e[2]),
            eps_q: deviatoric_invariant(e),
        }
    }
}

/// Solves D[S,S]·x = rhs[S] for the stress-controlled components S.
fn solve_sub(tangent: &Tangent6, idx: &[usize], rhs: &Vector6) -> Result<DVector<f64>, MaterialError> {
    let n = idx.len();
    let a = DMatrix::from_fn(n, n, |r, c| tangent.0[(idx[r], idx[c])]);
    let b = DVector::from_fn(n, |r, _| rhs[idx[r]]);
    a.lu()
        .solve(&b)
        .filter(|x| x.iter().all(|v| v.is_finite()))
        .ok_or_else(|| MaterialError::new("driver: singular tangent on the stress-controlled components"))
}

/// Isotropic compression (or unloading) from p_from to p_to (Pa, compression positive) in
/// `steps` fully stress-controlled steps.
pub fn isotropic_compression(p_from: f64, p_to: f64, steps: usize) -> Vec<StepControl> {
    (1..=steps)
        .map(|k| {
            let p = p_from + (p_to - p_from) * k as f64 / steps as f64;
            StepControl::stress([-p, -p, -p, 0.0, 0.0, 0.0])
        })
        .collect()
}

/// Lateral stress control at σ3 (compression positive, Pa) with the axial (z) strain
/// increment `d_ez` (tension positive).
fn axial_strain_step(sigma3: f64, d_ez: f64) -> StepControl {
    StepControl([
        Control::Stress(-sigma3),
        Control::Stress(-sigma3),
        Control::Strain(d_ez),
        Control::Stress(0.0),
        Control::Stress(0.0),
        Control::Stress(0.0),
    ])
}

/// Drained triaxial compression: σ_x = σ_y = σ3 constant (compression positive, Pa), axial
/// (z) compressive strain increased by `axial_strain` (> 0, compression) in `steps` equal steps.
pub fn triaxial_compression(sigma3: f64, axial_strain: f64, steps: usize) -> Vec<StepControl> {
    vec![axial_strain_step(sigma3, -axial_strain / steps as f64); steps]
}

/// Drained triaxial extension: σ_x = σ_y = σ3 constant (compression positive, Pa), axial (z)
/// strain *extended* by `axial_strain` (> 0) in `steps` equal steps.
pub fn triaxial_extension(sigma3: f64, axial_strain: f64, steps: usize) -> Vec<StepControl> {
    vec![axial_strain_step(sigma3, axial_strain / steps as f64); steps]
}

/// Drained triaxial steps at σ3 (compression positive, Pa) with the given axial (z)
/// *compression* strain increments (positive shortens), e.g. of a cyclic strain path.
pub fn triaxial_strain_steps(sigma3: f64, axial_compression_increments: &[f64]) -> Vec<StepControl> {
    axial_compression_increments
        .iter()
        .map(|&d| axial_strain_step(sigma3, -d))
        .collect()
}

/// Triaxial stress state with σ_x = σ_y = σ3 and σ_z = σ3 + q (compression positive, Pa),
/// as a fully stress-controlled step.
pub fn triaxial_stress_step(sigma3: f64, q: f64) -> StepControl {
    StepControl::stress([-sigma3, -sigma3, -(sigma3 + q), 0.0, 0.0, 0.0])
}

/// Drained cyclic triaxial at σ3 (Pa): q goes from `q_min` to `q_max` and back, `cycles`
/// times, in `steps_per_half` stress-controlled steps per half cycle. The path starts at
/// q = q_min (the driver must already be there).
pub fn cyclic_triaxial(
    sigma3: f64,
    q_min: f64,
    q_max: f64,
    cycles: usize,
    steps_per_half: usize,
) -> Vec<StepControl> {
    let mut out = Vec::with_capacity(2 * cycles * steps_per_half);
    for _ in 0..cycles {
        for k in 1..=steps_per_half {
            let q = q_min + (q_max - q_min) * k as f64 / steps_per_half as f64;
            out.push(triaxial_stress_step(sigma3, q));
        }
        for k in 1..=steps_per_half {
            let q = q_max - (q_max - q_min) * k as f64 / steps_per_half as f64;
            out.push(triaxial_stress_step(sigma3, q));
        }
    }
    out
}

/// Oedometric (K0) compression: axial (z) compressive strain `axial_strain` (> 0) in `steps`
/// steps, all other strains fixed.
pub fn oedometer(axial_strain: f64, steps: usize) -> Vec<StepControl> {
    vec![StepControl::strain([0.0, 0.0, -axial_strain / steps as f64, 0.0, 0.0, 0.0]); steps]
}

/// Oedometric steps with the given axial (z) *compression* strain increments (positive
/// shortens), all other strains fixed.
pub fn oedometer_steps(axial_compression_increments: &[f64]) -> Vec<StepControl> {
    axial_compression_increments
        .iter()
        .map(|&d| StepControl::strain([0.0, 0.0, -d, 0.0, 0.0, 0.0]))
        .collect()
}

/// Isotropic stress path from p0 through the pressures `points` (Pa, compression positive),
/// `steps_per_segment` fully stress-controlled steps per segment.
pub fn isotropic_path(p0: f64, points: &[f64], steps_per_segment: usize) -> Vec<StepControl> {
    let mut out = Vec::with_capacity(points.len() * steps_per_segment);
    let mut from = p0;
    for &to in points {
        out.extend(isotropic_compression(from, to, steps_per_segment));
        from = to;
    }
    out
}

/// Constant stress ratio η = q/p, triaxial compression form (z axial), p from `p_from` to
/// `p_to` (Pa, compression positive) in `steps` stress-controlled steps.
pub fn constant_eta(eta: f64, p_from: f64, p_to: f64, steps: usize) -> Vec<StepControl> {
    (1..=steps)
        .map(|k| {
            let p = p_from + (p_to - p_from) * k as f64 / steps as f64;
            let q = eta * p;
            StepControl::stress([
                -(p - q / 3.0),
                -(p - q / 3.0),
                -(p + 2.0 * q / 3.0),
                0.0,
                0.0,
                0.0,
            ])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::elastic::{ElasticParams, LinearElastic};
    use crate::material::rockfill_gp::{RockfillGp, RockfillGpParams};
    use crate::material::SolidUpdate;

    /// Linear elastic model that refuses increments larger than `limit` (to exercise halving).
    struct Picky {
        inner: LinearElastic,
        limit: f64,
    }

    impl SolidModel for Picky {
        type State = <LinearElastic as SolidModel>::State;
        fn symmetric_tangent(&self) -> bool {
            true
        }
        fn init_state(&self, sigma0: &Stress6) -> Result<Self::State, MaterialError> {
            self.inner.init_state(sigma0)
        }
        fn update(
            &self,
            prev: &Self::State,
            d_eps: &Strain6,
        ) -> Result<SolidUpdate<Self::State>, MaterialError> {
            if d_eps.0.amax() > self.limit {
                return Err(MaterialError::new("increment too large"));
            }
            self.inner.update(prev, d_eps)
        }
        fn stress(state: &Self::State) -> Stress6 {
            state.stress
        }
        fn elastic_tangent(&self, state: &Self::State) -> crate::tensor::Tangent6 {
            self.inner.elastic_tangent(state)
        }
    }

    fn elastic() -> LinearElastic {
        LinearElastic::new(&ElasticParams {
            young: 100e6,
            poisson: 0.25,
            density: 2000.0,
        })
    }

    #[test]
    fn uniaxial_stress_recovers_young_and_poisson() {
        let m = elastic();
        let mut d = MaterialPointDriver::new(&m, &Stress6::default()).expect("zero stress");
        let step = StepControl([
            Control::Stress(0.0),
            Control::Stress(0.0),
            Control::Strain(-1e-3),
            Control::Stress(0.0),
            Control::Stress(0.0),
            Control::Stress(0.0),
        ]);
        let r = *d.step(&step).expect("step");
        assert!((r.stress[2] / r.strain[2] - 100e6).abs() < 1e-6 * 100e6);
        assert!((-r.strain[0] / r.strain[2] - 0.25).abs() < 1e-10);
        assert!(r.stress[0].abs() < 1e-8 * 1e5 && r.stress[1].abs() < 1e-3);
        // Invariants of the row: p = σ_a/3, q = |σ_a|, ε_v = −tr ε, ε_q of the strain.
        assert!((r.p - 1e5 / 3.0).abs() < 1e-6 && (r.q - 1e5).abs() < 1e-6);
        assert!((r.eps_v - 1e-3 * (1.0 - 2.0 * 0.25)).abs() < 1e-12);
        assert!((r.eps_q - 2.0 / 3.0 * 1e-3 * 1.25).abs() < 1e-12);
        assert_eq!(d.rows().len(), 2);
        assert_eq!(d.rows()[1].step, 1);
    }

    #[test]
    fn failing_updates_are_halved_until_they_pass() {
        let m = Picky {
            inner: elastic(),
            limit: 1.1e-4,
        };
        let mut d = MaterialPointDriver::new(&m, &Stress6::default()).expect("init");
        d.run(&oedometer(1e-3, 1)).expect("halving to 1/16 of the step");
        assert!((d.last().strain[2] + 1e-3).abs() < 1e-15);
        assert_eq!(d.rows().len(), 2, "one row per user step");
        let strict = Picky {
            inner: elastic(),
            limit: 1e-9,
        };
        let mut d = MaterialPointDriver::new(&strict, &Stress6::default())
            .expect("init")
            .with_options(DriverOptions {
                max_halvings: 3,
                ..DriverOptions::default()
            });
        let err = d.run(&oedometer(1e-3, 1)).unwrap_err();
        assert!(err.reason.contains("halvings"), "{}", err.reason);
    }

    #[test]
    fn path_helpers_produce_the_stated_paths() {
        let m = RockfillGp::new(RockfillGpParams::default()).expect("seed");
        let mut d = MaterialPointDriver::new(&m, &Stress6::isotropic(-200e3))
            .expect("p0 = 200 kPa")
            .with_elastic_tangent(|s| m.elastic_tangent(s));
        d.run(&constant_eta(0.8, 200e3, 400e3, 10)).expect("constant η");
        assert!((d.last().q / d.last().p - 0.8).abs() < 1e-7);
        assert!((d.last().p - 400e3).abs() < 1e-2);
        let cyc = cyclic_triaxial(400e3, 0.0, 100e3, 3, 5);
        assert_eq!(cyc.len(), 30);
        d.run(&triaxial_compression(400e3, 0.01, 20)).expect("triaxial");
        let r = d.last();
        assert!((r.stress[0] + 400e3).abs() < 1e-8 * 1e6 && (r.stress[1] + 400e3).abs() < 1e-2);
        assert!(r.stress[3].abs() < 1e-2 && r.stress[4].abs() < 1e-2 && r.stress[5].abs() < 1e-2);
        assert!(d.substeps() >= 30);
        assert!(d.tangent().is_some());
    }
}
