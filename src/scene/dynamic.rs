//! Dynamic stages (spec seismic §3): a ground-acceleration record on a rigid base, integrated
//! in time from the state the previous stages left, with the static loads kept.
//!
//! ```yaml
//! stages:
//!   - name: quake
//!     loads: { hydrostatic: [ { faces: upstream, level: 2840.0 } ] }
//!     dynamic:
//!       record: ../accel/seed_quake.csv     # t,a_x,a_y,a_z in m/s² (cfrd accel writes it)
//!       # or one PEER NGA AT2 file per component (g; a component left out is zero):
//!       # record: { x: RSN6_X.AT2, y: RSN6_Y.AT2, z: RSN6_UP.AT2 }
//!       duration: 20.0                      # s, default the record's length
//!       dt: 0.01                            # s, default the record's sample interval; must
//!       #                                   # divide the duration
//!       damping: { ratio: 0.05, frequencies: [1.0, 5.0] }   # Rayleigh on M and K₀
//!       # or: damping: { ratio: 0.05, modes: [1, 3] }  anchors at the modal frequencies of
//!       # modes 1 and 3 of the stage's start state (a modal analysis runs there, see `modal`)
//!       mass: consistent                    # or lumped
//!       # hht_alpha: -0.05                  # HHT-α instead of Newmark's β, γ (α ∈ [−1/3, 0])
//!       output_every: 10                    # fields every 10 steps (0: at the end only)
//!       # predictor: extrapolate            # start each step's Newton iterations from
//!       #                                   # u₀ + Δt·v₀ (default none: from u₀)
//!       # line_search: secant               # default full_step_first
//!       # linear_solver: canonical_lu       # default distributed_lu (see below)
//!       # newton_tol: 1.0e-5                # default the scene's solver.newton_tol
//! ```
//!
//! A dynamic stage solves its Newton corrections with its own `linear_solver`, not the static
//! stages' `solver.linear_solver`: by default `distributed_lu`, which in a time step is GMRES
//! preconditioned by additive Schwarz with ILU(0) subdomains on the distributed Jacobian
//! (`cfrd::guide`, "Linear solvers and PETSc options"): no rank holds the whole matrix, its factors or a
//! whole vector, so memory and work per rank fall with the rank count. `canonical_lu` gathers
//! the Jacobian onto every rank and gives the same bits at any rank count; `iterative` and
//! `reduced_amg` are the static solvers of the same names.
//!
//! A stage gets what it asks, or the scene is refused (exit 2, naming the stage and the key),
//! or rank 0's log states the rule at the stage's start ([`DynamicStage::notes`]):
//! - AT2 components left out are zero, shorter ones padded with zeros to the longest (stated;
//!   [`super::record`]);
//! - `dt` must divide `duration` to 1e-9 relative (refused, naming the nearest `dt` that does);
//! - after a record shorter than `duration` the ground is at rest, zero ground acceleration to
//!   the stage's end (stated);
//! - a damping ratio needs its two anchors (refused otherwise).

use super::error::SceneError;
use super::record::RecordSpec;
use super::schema::{LineSearch, LinearSolver, Predictor};
use crate::seismic::Accelerogram;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// How a stage is integrated in time (scene key `stages[k].dynamic`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DynamicSpec {
    /// Ground acceleration record, relative to the scene's folder: a CSV file with the header
    /// `t,a_x,a_y,a_z` (m/s², the scene's axes x stream, y dam axis, z up), or one PEER NGA AT2
    /// file per component, `{ x: FILE.AT2, y: FILE.AT2, z: FILE.AT2 }` (in g; a component left
    /// out is zero; [`super::record`]). After the record's end the ground is at rest.
    pub record: RecordSpec,
    /// Factor on all three components of the record (default 1).
    #[serde(default = "one")]
    pub scale: f64,
    /// Duration of the stage (s); default the record's length. Past the record's end the ground
    /// is at rest (zero ground acceleration), which the run's log states.
    #[serde(default)]
    pub duration: Option<f64>,
    /// Time step (s); default the record's sample interval. It must divide the duration (to
    /// 1e-9 relative).
    #[serde(default)]
    pub dt: Option<f64>,
    /// Newmark's β and γ (default 1/4 and 1/2, average acceleration).
    #[serde(default)]
    pub newmark: NewmarkSpec,
    /// HHT-α's α ∈ [−1/3, 0] (Hilber, Hughes and Taylor; spec architecture, the force-averaged
    /// form): numerical damping of the high frequencies, second-order accurate; β = (1 − α)²/4
    /// and γ = 1/2 − α then follow from α and `newmark` must be left out. Default: none
    /// (Newmark).
    #[serde(default)]
    pub hht_alpha: Option<f64>,
    /// Mass matrix: `consistent` (default) or `lumped` (row sums).
    #[serde(default)]
    pub mass: MassKind,
    /// Rayleigh damping C = a_M·M + a_K·K₀ from a ratio at two frequencies; none by default
    /// (the materials' hysteresis only).
    #[serde(default)]
    pub damping: Option<RayleighSpec>,
    /// Write the fields every this many steps besides the stage's end (0: the end only).
    #[serde(default)]
    pub output_every: u32,
    /// Initial guess of a time step's Newton iterations: `none` (the default) starts from the
    /// converged displacement, `extrapolate` carries the committed velocity over the step
    /// (`solver::integrator::Newmark::extrapolating`): fewer Newton iterations and cut-backs,
    /// but on the seed quake more time ([`crate::performance`], "The seed quake (coarse
    /// mesh)").
    #[serde(default)]
    pub predictor: Predictor,
    /// How a time step's Newton corrections are scaled: `full_step_first` (the default),
    /// `secant` or `residual_secant` (the static stages' default; [`LineSearch`]).
    /// `full_step_first` and `secant` agree to within the Newton tolerance's effect on the
    /// path-dependent materials ([`crate::performance`], "The seed quake (coarse mesh)").
    #[serde(default = "full_step_first")]
    pub line_search: LineSearch,
    /// Linear solver of the time steps' Newton corrections: `distributed_lu` (the default:
    /// additive Schwarz with ILU(0) subdomains, nothing global on any rank), `canonical_lu`
    /// (the same bits at any rank count; the Jacobian gathered onto every rank), `iterative` or
    /// `reduced_amg` (the module docs). The static stages' `solver.linear_solver` does not
    /// apply here.
    #[serde(default = "distributed_lu")]
    pub linear_solver: LinearSolver,
    /// Newton's relative residual tolerance in this stage; default the scene's
    /// `solver.newton_tol` (so a quake can be solved more tightly than the construction).
    #[serde(default)]
    pub newton_tol: Option<f64>,
}

fn distributed_lu() -> LinearSolver {
    LinearSolver::DistributedLu
}

fn full_step_first() -> LineSearch {
    LineSearch::FullStepFirst
}

fn one() -> f64 {
    1.0
}

/// Newmark's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NewmarkSpec {
    /// β (1/4: average acceleration, unconditionally stable).
    pub beta: f64,
    /// γ (1/2: no numerical damping).
    pub gamma: f64,
}

impl Default for NewmarkSpec {
    fn default() -> Self {
        NewmarkSpec {
            beta: 0.25,
            gamma: 0.5,
        }
    }
}

/// Consistent or lumped mass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MassKind {
    /// M = Σ ∫ ρ NᵀN dV.
    #[default]
    Consistent,
    /// Row sums on the diagonal.
    Lumped,
}

/// Rayleigh damping: the ratio ζ reached at two frequencies (spec seismic §3.3), given
/// directly or as two modes of the stage's start state. Exactly one of `frequencies` and
/// `modes` is given with the ratio.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RayleighSpec {
    /// Damping ratio ζ at both frequencies (e.g. 0.05).
    pub ratio: f64,
    /// The two anchor frequencies (Hz), f1 < f2.
    #[serde(default)]
    pub frequencies: Option<[f64; 2]>,
    /// The two anchor modes (1-based, i < j): their frequencies from a modal analysis of the
    /// stage's start state ([`crate::scene::modal`]).
    #[serde(default)]
    pub modes: Option<[u32; 2]>,
}

/// Where the two anchor frequencies of Rayleigh damping come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Anchors {
    /// Given frequencies (Hz), f1 < f2.
    Frequencies([f64; 2]),
    /// Modes i < j (1-based) of the modal analysis at the stage's start.
    Modes([u32; 2]),
}

/// Validated Rayleigh damping: ratio ζ and its anchors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Damping {
    /// Damping ratio ζ at both anchors.
    pub ratio: f64,
    /// The anchor frequencies or modes.
    pub anchors: Anchors,
}

impl DynamicStage {
    /// The scaled ground acceleration at time `t` of the stage (m/s²; zero after the record).
    pub fn ground_acceleration(&self, t: f64) -> [f64; 3] {
        self.record.at(t).map(|a| self.scale * a)
    }

    /// The time step (s): the duration over the steps.
    pub fn dt(&self) -> f64 {
        self.duration / self.steps.max(1) as f64
    }
}

/// A validated dynamic stage.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicStage {
    /// The ground acceleration record (m/s²).
    pub record: Accelerogram,
    /// Factor on the record.
    pub scale: f64,
    /// Duration of the stage (s).
    pub duration: f64,
    /// Time steps of the stage (duration / dt, rounded).
    pub steps: u32,
    /// Newmark's β and γ (unused when `alpha` ≠ 0).
    pub newmark: NewmarkSpec,
    /// HHT-α's α (0: Newmark), which sets β and γ itself.
    pub alpha: f64,
    /// Lumped mass.
    pub lumped: bool,
    /// Rayleigh damping (ratio and anchors).
    pub damping: Option<Damping>,
    /// Output every this many steps (0: the end only).
    pub output_every: u32,
    /// The initial guess of a time step.
    pub predictor: Predictor,
    /// How a time step's Newton corrections are scaled.
    pub line_search: LineSearch,
    /// The linear solver of the time steps' Newton corrections.
    pub linear_solver: LinearSolver,
    /// Newton's tolerance in this stage, if not the scene's.
    pub newton_tol: Option<f64>,
    /// What rank 0's log states at the stage's start about the ground motion, one line each:
    /// how the components of an AT2 record were completed, and where the record ends before
    /// the duration ("the ground is at rest" from there).
    pub notes: Vec<String>,
}

/// Largest number of time steps of one dynamic stage.
pub const MAX_STEPS: f64 = 10_000_000.0;

/// Validates `spec` (YAML path `path`), reading the record relative to `base`.
pub fn resolve(
    spec: &DynamicSpec,
    base: &Path,
    path: &str,
    invalid: &dyn Fn(&str, String) -> SceneError,
) -> Result<DynamicStage, SceneError> {
    let inv = |key: &str, message: String| invalid(&format!("{path}.{key}"), message);
    let super::record::Record {
        accelerogram: record,
        mut notes,
    } = spec.record.read(base, &inv)?;
    if !(spec.scale.is_finite() && spec.scale > 0.0) {
        return Err(inv(
            "scale",
            format!("{} must be finite and positive", spec.scale),
        ));
    }
    let duration = spec.duration.unwrap_or(record.duration());
    if !(duration.is_finite() && duration > 0.0) {
        return Err(inv(
            "duration",
            format!("{duration} s must be finite and positive"),
        ));
    }
    let steps =
        time_steps(spec.dt.unwrap_or(record.dt()), duration, spec.dt.is_some()).map_err(|m| inv("dt", m))?;
    check_newmark(&spec.newmark).map_err(|m| inv("newmark", m))?;
    let alpha = check_hht(spec.hht_alpha, &spec.newmark).map_err(|m| inv("hht_alpha", m))?;
    if let Some(tol) = spec.newton_tol {
        if !(tol.is_finite() && tol > 0.0 && tol < 1.0) {
            return Err(inv("newton_tol", format!("{tol} must lie in (0, 1)")));
        }
    }
    let damping = match &spec.damping {
        Some(d) => Some(check_damping(d).map_err(|m| inv("damping", m))?),
        None => None,
    };
    notes.extend(quiet_tail(&record, duration));
    Ok(DynamicStage {
        record,
        scale: spec.scale,
        duration,
        steps,
        newmark: spec.newmark,
        alpha,
        lumped: spec.mass == MassKind::Lumped,
        damping,
        output_every: spec.output_every,
        predictor: spec.predictor,
        line_search: spec.line_search,
        linear_solver: spec.linear_solver,
        newton_tol: spec.newton_tol,
        notes,
    })
}

/// Relative tolerance within which `dt` must divide the duration.
pub const DIVIDES_TOLERANCE: f64 = 1e-9;

/// The number of time steps of `duration` at `dt` (`given` in the scene, or else the record's
/// sample interval): finite, positive, at most the duration, at most [`MAX_STEPS`] steps, and
/// dividing the duration to [`DIVIDES_TOLERANCE`] (else the message names the nearest `dt`
/// that does).
fn time_steps(dt: f64, duration: f64, given: bool) -> Result<u32, String> {
    let n = (duration / dt).round();
    if !(dt.is_finite() && dt > 0.0 && dt <= duration) || n > MAX_STEPS {
        return Err(format!("{dt} s must be finite, positive, at most the duration {duration} s and give at most {MAX_STEPS} steps"));
    }
    if (n * dt - duration).abs() <= DIVIDES_TOLERANCE * duration {
        return Ok(n as u32);
    }
    let ratio = duration / dt;
    let (k, nearest) = [ratio.floor(), ratio.ceil()]
        .into_iter()
        .filter(|&k| k >= 1.0)
        .map(|k| (k, duration / k))
        .min_by(|a, b| (a.1 - dt).abs().total_cmp(&(b.1 - dt).abs()))
        .unwrap_or((1.0, duration));
    let which = if given {
        format!("{dt} s")
    } else {
        format!("the record's sample interval {dt} s (`dt` not given)")
    };
    Err(format!(
        "{which} does not divide the duration {duration} s ({ratio:.4} steps): give `dt: \
         {nearest}` ({k} steps), the nearest that does, or a duration that is a multiple of dt"
    ))
}

/// The log line of a record that ends before `duration`: the ground is at rest from its end.
fn quiet_tail(record: &Accelerogram, duration: f64) -> Option<String> {
    let end = record.duration();
    (end < duration * (1.0 - DIVIDES_TOLERANCE))
        .then(|| format!("record ends at {end} s; from {end} to {duration} s the ground is at rest"))
}

/// β > 0 and γ ≥ 1/2 (unconditional stability needs 2β ≥ γ ≥ 1/2; conditional schemes are
/// allowed but not below γ = 1/2, which would amplify).
fn check_newmark(n: &NewmarkSpec) -> Result<(), String> {
    if n.beta.is_finite()
        && n.gamma.is_finite()
        && n.beta > 0.0
        && n.gamma >= 0.5
        && n.beta <= 1.0
        && n.gamma <= 1.0
    {
        Ok(())
    } else {
        Err(format!(
            "beta {} must be in (0, 1] and gamma {} in [0.5, 1]",
            n.beta, n.gamma
        ))
    }
}

/// −1/3 ≤ α ≤ 0 (the unconditionally stable, second-order range of HHT-α), and no
/// `newmark` of its own beside it; the α to use (0 without HHT-α).
fn check_hht(alpha: Option<f64>, newmark: &NewmarkSpec) -> Result<f64, String> {
    let Some(alpha) = alpha else { return Ok(0.0) };
    if !(alpha.is_finite() && (-1.0 / 3.0..=0.0).contains(&alpha)) {
        return Err(format!("{alpha} must be in [-1/3, 0]"));
    }
    if *newmark != NewmarkSpec::default() {
        return Err("HHT-α sets β and γ itself: give either `newmark` or `hht_alpha`".into());
    }
    Ok(alpha)
}

/// 0 ≤ ζ < 1 and either 0 < f1 < f2, all finite, or modes 1 ≤ i < j.
fn check_damping(d: &RayleighSpec) -> Result<Damping, String> {
    if !(d.ratio.is_finite() && (0.0..1.0).contains(&d.ratio)) {
        return Err(format!("ratio {} must be in [0, 1)", d.ratio));
    }
    let anchors = match (d.frequencies, d.modes) {
        (Some([f1, f2]), None) => {
            if !(f1.is_finite() && f2.is_finite() && f1 > 0.0 && f2 > f1) {
                return Err(format!(
                    "frequencies [{f1}, {f2}] Hz must be finite with 0 < f1 < f2"
                ));
            }
            Anchors::Frequencies([f1, f2])
        }
        (None, Some([i, j])) => {
            if !(i >= 1 && j > i && j <= super::modal::MAX_MODES) {
                return Err(format!(
                    "modes [{i}, {j}] must be numbered from 1 with i < j ≤ {}",
                    super::modal::MAX_MODES
                ));
            }
            Anchors::Modes([i, j])
        }
        (None, None) => {
            return Err(format!(
                "ratio {} needs its two anchors: give one of `frequencies: [f1, f2]` (Hz) or \
                 `modes: [i, j]`",
                d.ratio
            ))
        }
        (Some(_), Some(_)) => {
            return Err("give either `frequencies: [f1, f2]` or `modes: [i, j]`, not both".into())
        }
    };
    Ok(Damping {
        ratio: d.ratio,
        anchors,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `dt` divides the duration to 1e-9 relative, or the message names the nearest `dt` that
    /// does (issue 56: `dt: 0.21` over `duration: 0.3` ran one step of 0.3 s).
    #[test]
    fn a_dt_must_divide_the_duration_and_the_message_names_the_nearest_that_does() {
        assert_eq!(time_steps(0.01, 0.3, true), Ok(30));
        assert_eq!(time_steps(0.01, 20.0, false), Ok(2000));
        assert_eq!(time_steps(0.01 * (1.0 + 1e-12), 0.3, true), Ok(30));
        let e = time_steps(0.21, 0.3, true).expect_err("1.43 steps");
        assert!(
            e.starts_with("0.21 s does not divide the duration 0.3 s (1.4286 steps)")
                && e.contains("give `dt: 0.15` (2 steps)"),
            "{e}"
        );
        let e = time_steps(0.01, 0.025, false).expect_err("2.5 steps");
        assert!(
            e.contains("the record's sample interval 0.01 s (`dt` not given)") && e.contains("(3 steps)"),
            "{e}"
        );
        let e = time_steps(0.5, 0.3, true).expect_err("more than the duration");
        assert!(e.contains("at most the duration 0.3 s"), "{e}");
    }

    #[test]
    fn hht_alpha_is_checked_and_excludes_a_newmark_of_its_own() {
        let average = NewmarkSpec::default();
        assert_eq!(check_hht(None, &average), Ok(0.0));
        assert_eq!(check_hht(Some(-0.1), &average), Ok(-0.1));
        assert_eq!(check_hht(Some(-1.0 / 3.0), &average), Ok(-1.0 / 3.0));
        for bad in [-0.34, 0.05, f64::NAN, f64::NEG_INFINITY] {
            let e = check_hht(Some(bad), &average).expect_err("out of range");
            assert!(e.contains("[-1/3, 0]"), "{e}");
        }
        let own = NewmarkSpec {
            beta: 0.3,
            gamma: 0.6,
        };
        let e = check_hht(Some(0.0), &own).expect_err("both given");
        assert!(e.contains("either `newmark` or `hht_alpha`"), "{e}");
    }
}
