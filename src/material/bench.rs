//! Benchmark of integration-point updates per second per core (issue 3 acceptance).
//!
//! For each model at its seed parameters, two realistic paths are first run once through the
//! material-point drivers (the mixed-control solid driver, the CNL interface driver) to record
//! the sequence of total step increments a solver would hand to the model:
//!
//! ```text
//! solids (rockfill_gp, elastic), virgin isotropic start at p0 = σ3 = 1000 kPa:
//!   monotonic: drained triaxial compression, Δε_a = 5·10⁻⁴ (0.05 %) per step, to ε_a = 10 %
//!   cyclic:    drained cyclic triaxial, q 0 ↔ 2500 kPa, Δq = 100 kPa per step, 5 cycles
//! interfaces (gp_interface, hyperbolic, mohr_coulomb, joint), CNL σ_n = 400 kPa:
//!   monotonic: direct shear, Δu = 0.2 mm per step, to 60 mm
//!   cyclic:    direct shear ±10 mm, Δu = 0.2 mm per step, 3 cycles
//! ```
//!
//! The timed loop then replays the path as the solver does at a converged step: every update
//! starts from the **committed** state of the previous step (`state = update(state, Δ).state`),
//! with the increment, the returned tangent (which the solver assembles) and the final state
//! passed through [`std::hint::black_box`], so that nothing is hoisted or discarded. One repetition replays the path as many times
//! as needed to last a minimum time (calibrated during the warm-up pass); the reported rate is
//! the median over the repetitions, on one thread (per core).

use super::driver_interface::{direct_shear, NormalControl};
use super::driver_solid::{cyclic_triaxial, triaxial_compression, MaterialPointDriver};
use super::elastic::{ElasticParams, LinearElastic};
use super::interface_gp::{GpInterface, GpInterfaceParams};
use super::interface_hyperbolic::{HyperbolicInterface, HyperbolicParams};
use super::interface_mc::{MohrCoulombInterface, MohrCoulombParams};
use super::joint::{JointLaw, JointParams};
use super::rockfill_gp::{RockfillGp, RockfillGpParams};
use super::{InterfaceModel, SolidModel};
use crate::error::MaterialError;
use crate::tensor::{Local3, Strain6, Stress6, Vector6};
use std::fmt;
use std::hint::black_box;
use std::time::Instant;

/// Confining pressure of the solid paths (Pa, compression positive).
const SIGMA3: f64 = 1000e3;
/// Normal stress of the interface paths (Pa, compression positive).
const SIGMA_N: f64 = 400e3;

/// One line of the benchmark.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchRow {
    /// Model tag, e.g. `rockfill_gp`.
    pub model: String,
    /// `monotonic` or `cyclic`.
    pub path: String,
    /// The path and its increment size, in words.
    pub description: String,
    /// Updates in one pass of the path.
    pub updates: usize,
    /// Timed repetitions (the median is reported).
    pub repetitions: usize,
    /// Passes of the path per repetition.
    pub passes: usize,
    /// Median time of one update (s).
    pub seconds_per_update: f64,
    /// Median updates per second on one core.
    pub updates_per_second: f64,
    /// Mean number of accepted model substeps per update.
    pub substeps_per_update: f64,
    /// Why the row could not be measured (then the rates are NaN).
    pub error: Option<String>,
}

/// Markdown table of benchmark rows (`format!("{}", BenchTable(&rows))`).
pub struct BenchTable<'a>(pub &'a [BenchRow]);

impl fmt::Display for BenchTable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "| model | path | updates/s (1 core) | µs/update | substeps/update | updates × passes × reps | path and increments |"
        )?;
        writeln!(f, "|---|---|---:|---:|---:|---:|---|")?;
        for r in self.0 {
            match &r.error {
                Some(e) => writeln!(
                    f,
                    "| {} | {} | failed: {e} | | | | {} |",
                    r.model, r.path, r.description
                )?,
                None => writeln!(
                    f,
                    "| {} | {} | {:.3e} | {:.3} | {:.2} | {} × {} × {} | {} |",
                    r.model,
                    r.path,
                    r.updates_per_second,
                    r.seconds_per_update * 1e6,
                    r.substeps_per_update,
                    r.updates,
                    r.passes,
                    r.repetitions,
                    r.description
                )?,
            }
        }
        Ok(())
    }
}

/// Timing options of a run.
#[derive(Debug, Clone, Copy)]
struct Timing {
    repetitions: usize,
    /// Minimum duration of one repetition (s).
    min_seconds: f64,
    /// Fraction of each path kept (quick mode shortens the paths).
    steps_divisor: usize,
}

/// Runs the benchmark: 6 models × (monotonic, cyclic). `quick` shortens the paths, times one
/// short repetition set (for tests); otherwise 7 repetitions of at least 50 ms each.
pub fn run(quick: bool) -> Vec<BenchRow> {
    let timing = if quick {
        Timing {
            repetitions: 3,
            min_seconds: 1e-4,
            steps_divisor: 10,
        }
    } else {
        Timing {
            repetitions: 7,
            min_seconds: 0.05,
            steps_divisor: 1,
        }
    };
    let mut rows = Vec::new();
    match RockfillGp::new(RockfillGpParams::default()) {
        Ok(m) => solid_rows(&m, "rockfill_gp", timing, &mut rows),
        Err(e) => rows.extend(failed_pair("rockfill_gp", e.to_string())),
    }
    match GpInterface::new(GpInterfaceParams::default()) {
        Ok(m) => interface_rows(&m, "gp_interface", timing, &mut rows),
        Err(e) => rows.extend(failed_pair("gp_interface", e.to_string())),
    }
    interface_rows(
        &HyperbolicInterface::new(&HyperbolicParams::default()),
        "hyperbolic",
        timing,
        &mut rows,
    );
    interface_rows(
        &MohrCoulombInterface::new(&MohrCoulombParams::default()),
        "mohr_coulomb",
        timing,
        &mut rows,
    );
    interface_rows(
        &JointLaw::new(&JointParams::default()),
        "joint",
        timing,
        &mut rows,
    );
    let elastic = LinearElastic::new(&ElasticParams {
        young: 100e6,
        poisson: 0.3,
        density: 2100.0,
    });
    solid_rows(&elastic, "elastic", timing, &mut rows);
    rows
}

fn failed_pair(model: &str, error: String) -> Vec<BenchRow> {
    ["monotonic", "cyclic"]
        .iter()
        .map(|path| failed(model, path, String::new(), error.clone()))
        .collect()
}

fn failed(model: &str, path: &str, description: String, error: String) -> BenchRow {
    BenchRow {
        model: model.to_string(),
        path: path.to_string(),
        description,
        updates: 0,
        repetitions: 0,
        passes: 0,
        seconds_per_update: f64::NAN,
        updates_per_second: f64::NAN,
        substeps_per_update: f64::NAN,
        error: Some(error),
    }
}

/// Records the strain increments of the two solid paths through the mixed-control driver.
fn solid_rows<M: SolidModel>(model: &M, name: &str, timing: Timing, rows: &mut Vec<BenchRow>) {
    let sigma0 = Stress6::isotropic(-SIGMA3);
    let n_mono = 200 / timing.steps_divisor;
    let cycles = if timing.steps_divisor > 1 { 1 } else { 5 };
    let paths = [
        (
            "monotonic",
            format!(
                "drained triaxial, sigma3 = 1000 kPa, d eps_a = 5e-4 per step to {} %",
                0.05 * n_mono as f64
            ),
            triaxial_compression(SIGMA3, 5e-4 * n_mono as f64, n_mono),
        ),
        (
            "cyclic",
            format!("drained cyclic triaxial, sigma3 = 1000 kPa, q 0-2500 kPa, dq = 100 kPa per step, {cycles} cycles"),
            cyclic_triaxial(SIGMA3, 0.0, 2500e3, cycles, 25),
        ),
    ];
    let recorded = paths.into_iter().map(|(path, description, steps)| {
        let incs = MaterialPointDriver::new(model, &sigma0).and_then(|mut d| {
            d.run(&steps)?;
            Ok(d.rows()
                .windows(2)
                .map(|w| Strain6(Vector6::from_fn(|i, _| w[1].strain[i] - w[0].strain[i])))
                .collect::<Vec<_>>())
        });
        (path, description, incs)
    });
    let init = || model.init_state(&sigma0);
    let update = |s: &M::State, d: &Strain6| {
        model
            .update(s, d)
            .map(|u| assembled(u.state, &u.tangent, u.substeps))
    };
    time_paths(name, timing, recorded, &init, &update, rows);
}

/// Records the jump increments of the two interface paths through the CNL driver.
fn interface_rows<M: InterfaceModel>(model: &M, name: &str, timing: Timing, rows: &mut Vec<BenchRow>) {
    let du = 2e-4;
    let n_mono = 300 / timing.steps_divisor;
    let cycles = if timing.steps_divisor > 1 { 1 } else { 3 };
    let amplitude_steps = 50;
    let mut cyclic = Vec::new();
    for _ in 0..cycles {
        cyclic.extend(std::iter::repeat_n([du, 0.0], amplitude_steps));
        cyclic.extend(std::iter::repeat_n([-du, 0.0], 2 * amplitude_steps));
        cyclic.extend(std::iter::repeat_n([du, 0.0], amplitude_steps));
    }
    let paths = [
        (
            "monotonic",
            format!(
                "CNL direct shear, sigma_n = 400 kPa, du = 0.2 mm per step to {} mm",
                0.2 * n_mono as f64
            ),
            vec![[du, 0.0]; n_mono],
        ),
        (
            "cyclic",
            format!("CNL direct shear, sigma_n = 400 kPa, +-10 mm, du = 0.2 mm per step, {cycles} cycles"),
            cyclic,
        ),
    ];
    let control = NormalControl::ConstantLoad { sigma_n: SIGMA_N };
    let recorded = paths.into_iter().map(|(path, description, shear)| {
        let incs = direct_shear(model, control, &shear).map(|driven| {
            driven
                .windows(2)
                .map(|w| Local3::from_fn(|i, _| w[1].jump[i] - w[0].jump[i]))
                .collect::<Vec<_>>()
        });
        (path, description, incs)
    });
    let init = || model.init_state(SIGMA_N);
    let update = |s: &M::State, d: &Local3| {
        model
            .update(s, d)
            .map(|u| assembled(u.state, &u.tangent, u.substeps))
    };
    time_paths(name, timing, recorded, &init, &update, rows);
}

/// What the solver does with an update at a converged step: assembles the tangent (here passed
/// through [`black_box`] so that it is not discarded) and keeps the state; with the substeps.
fn assembled<S, T>(state: S, tangent: &T, substeps: u32) -> (S, u32) {
    black_box(tangent);
    (state, substeps)
}

/// Times each recorded path `(path, description, increments)` of model `name` and appends its
/// row, in order; a path whose recording failed gets a failed row.
fn time_paths<'p, S, D, E: fmt::Display>(
    name: &str,
    timing: Timing,
    recorded: impl Iterator<Item = (&'p str, String, Result<Vec<D>, E>)>,
    init: &InitFn<'_, S>,
    update: &UpdateFn<'_, S, D>,
    rows: &mut Vec<BenchRow>,
) {
    for (path, description, incs) in recorded {
        let row = match incs {
            Ok(incs) => time_path(name, path, description, timing, &incs, init, update),
            Err(e) => failed(name, path, description, format!("recording the path: {e}")),
        };
        rows.push(row);
    }
}

/// Builds the initial state of a replay.
type InitFn<'a, S> = dyn Fn() -> Result<S, MaterialError> + 'a;
/// One update from a committed state: the new state and its substep count.
type UpdateFn<'a, S, D> = dyn Fn(&S, &D) -> Result<(S, u32), MaterialError> + 'a;

/// Passes of the path from the initial state, each update from the committed state of the
/// previous one; returns the total substeps, or the first error.
fn replay<S, D>(
    increments: &[D],
    init: &InitFn<'_, S>,
    update: &UpdateFn<'_, S, D>,
    passes: usize,
) -> Result<u64, MaterialError> {
    let mut substeps = 0_u64;
    for _ in 0..passes {
        let mut state = init()?;
        for inc in increments {
            let (next, n) = update(&state, black_box(inc))?;
            substeps += u64::from(n);
            state = next;
        }
        black_box(&state);
    }
    Ok(substeps)
}

/// Times a recorded path: a warm-up pass (which also sizes the repetitions), then the
/// repetitions; the median time per update.
fn time_path<S, D>(
    model: &str,
    path: &str,
    description: String,
    timing: Timing,
    increments: &[D],
    init: &InitFn<'_, S>,
    update: &UpdateFn<'_, S, D>,
) -> BenchRow {
    let n = increments.len();
    if n == 0 {
        return failed(model, path, description, "empty path".to_string());
    }
    let start = Instant::now();
    let substeps = match replay(increments, init, update, 1) {
        Ok(s) => s,
        Err(e) => return failed(model, path, description, format!("replay: {e}")),
    };
    let one_pass = start.elapsed().as_secs_f64().max(1e-9);
    let passes = ((timing.min_seconds / one_pass).ceil() as usize).clamp(1, 1_000_000);
    let mut per_update = Vec::with_capacity(timing.repetitions);
    for _ in 0..timing.repetitions {
        let t0 = Instant::now();
        if let Err(e) = replay(increments, init, update, passes) {
            return failed(model, path, description, format!("replay: {e}"));
        }
        per_update.push(t0.elapsed().as_secs_f64() / (passes * n) as f64);
    }
    per_update.sort_by(f64::total_cmp);
    let median = per_update[per_update.len() / 2];
    BenchRow {
        model: model.to_string(),
        path: path.to_string(),
        description,
        updates: n,
        repetitions: timing.repetitions,
        passes,
        seconds_per_update: median,
        updates_per_second: 1.0 / median,
        substeps_per_update: substeps as f64 / n as f64,
        error: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Quick mode: 12 rows (6 models × 2 paths), each measured, with positive finite rates and
    /// at least one substep per update; the markdown table has a header, a rule and 12 lines.
    #[test]
    fn quick_bench_rows_are_positive_and_finite() {
        let rows = run(true);
        assert_eq!(rows.len(), 12);
        for r in &rows {
            assert!(r.error.is_none(), "{r:?}");
            assert!(r.updates > 0 && r.passes > 0 && r.repetitions == 3, "{r:?}");
            assert!(
                r.updates_per_second.is_finite() && r.updates_per_second > 0.0,
                "{r:?}"
            );
            assert!(
                (r.seconds_per_update * r.updates_per_second - 1.0).abs() < 1e-12,
                "{r:?}"
            );
            assert!(
                r.substeps_per_update.is_finite() && r.substeps_per_update >= 1.0,
                "{r:?}"
            );
        }
        let models: Vec<&str> = rows.iter().step_by(2).map(|r| r.model.as_str()).collect();
        assert_eq!(
            models,
            [
                "rockfill_gp",
                "gp_interface",
                "hyperbolic",
                "mohr_coulomb",
                "joint",
                "elastic"
            ]
        );
        let table = BenchTable(&rows).to_string();
        assert_eq!(table.lines().count(), 14, "{table}");
        assert!(table.starts_with("| model | path | updates/s"));
    }

    /// The full benchmark (about 10 s in release); prints the markdown table.
    /// `cargo test --release --no-default-features --lib bench_full -- --ignored --nocapture`
    #[test]
    #[ignore = "takes about 10 s; prints the benchmark table"]
    fn bench_full() {
        let rows = run(false);
        println!("{}", BenchTable(&rows));
        assert!(rows
            .iter()
            .all(|r| r.error.is_none() && r.updates_per_second > 0.0));
    }

    /// Replaying a recorded CNL path from committed states reproduces the driver's end state.
    #[test]
    fn replay_reproduces_the_driven_path() {
        let m = HyperbolicInterface::new(&HyperbolicParams::default());
        let control = NormalControl::ConstantLoad { sigma_n: SIGMA_N };
        let driven = direct_shear(&m, control, &vec![[2e-4, 0.0]; 50]).unwrap();
        let incs: Vec<Local3> = driven
            .windows(2)
            .map(|w| Local3::from_fn(|i, _| w[1].jump[i] - w[0].jump[i]))
            .collect();
        let mut state = m.init_state(SIGMA_N).unwrap();
        for inc in &incs {
            state = m.update(&state, inc).unwrap().state;
        }
        let end = driven.last().unwrap();
        let t = HyperbolicInterface::traction(&state);
        assert!(
            (t[0] - end.traction[0]).abs() < 1e-6 * SIGMA_N,
            "{t:?} vs {end:?}"
        );
        assert!((t[2] - end.traction[2]).abs() < 1e-6 * SIGMA_N);
    }
}
