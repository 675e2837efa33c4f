//! Step control over the time of a stage: the next target time, acceptance, cut-back and
//! regrowth, landing exactly on the stage's end.
//!
//! A stage runs its own time t from 0 to `t_end`: a static stage's time is its load factor λ
//! (`t_end` = 1), a dynamic stage's the time of the record (s). A step goes from the converged
//! t to the target t + dt (the stage's end when that is within a relative 1e-12 of it); a
//! failed step is retried with dt/2 (at most `max_cutbacks` times in a row), and dt doubles
//! back towards the nominal step after two successes in a row. With a growth factor G > 1
//! (`solver.step_growth`, static stages) a step that converged in at most
//! [`EASY_STEP_ITERATIONS`] Newton iterations doubles the next one, up to G times the nominal
//! step, and a step that took more than [`HARD_STEP_ITERATIONS`] halves it again, not below
//! the nominal one. Every decision rests on collective outcomes (converged or not, the
//! iteration count), so all ranks take the same path.

use super::error::SolveError;
use super::report::SolveReport;

/// What a stage's time is, for messages: a static stage's load factor λ or a dynamic stage's
/// time t (s).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepKind {
    /// Load steps over λ ∈ [0, 1].
    Load,
    /// Time steps over t (s).
    Time,
}

impl StepKind {
    /// "λ = 0.500000" or "t = 4.060000 s".
    pub fn at(self, t: f64) -> String {
        match self {
            StepKind::Load => format!("λ = {t:.6}"),
            StepKind::Time => format!("t = {t:.6} s"),
        }
    }

    /// "Δλ = 1.250e-1" or "Δt = 1.000e-2 s": the size of a step, legible however small.
    pub fn span(self, d: f64) -> String {
        match self {
            StepKind::Load => format!("Δλ = {d:.3e}"),
            StepKind::Time => format!("Δt = {d:.3e} s"),
        }
    }

    /// "load step" or "time step".
    pub fn noun(self) -> &'static str {
        match self {
            StepKind::Load => "load step",
            StepKind::Time => "time step",
        }
    }
}

/// Newton iterations of a converged step at most which the next step may grow beyond the
/// nominal one (`solver.step_growth`).
pub const EASY_STEP_ITERATIONS: u32 = 1;

/// Newton iterations of a converged step above which a grown step shrinks back towards the
/// nominal one.
pub const HARD_STEP_ITERATIONS: u32 = 3;

/// Where a step checkpoint left the stepping of a stage ([`StepControl::resumed`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resumed {
    /// Time reached in the stage.
    pub t: f64,
    /// The next increment.
    pub dt: f64,
    /// Converged steps since the increment last changed.
    pub streak: u32,
    /// Converged steps since the stage's start.
    pub steps: u32,
}

/// Where the stepping of a stage stands. Step checkpoints store `t`, `dt`, `streak` and `steps`;
/// `t_end`, `dt_nominal` and `dt_max` follow from the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepControl {
    /// Time reached in the stage (0 at its start).
    pub t: f64,
    /// The next increment of t (`dt_max`, or less after cut-backs).
    pub dt: f64,
    /// Converged steps since the increment last changed (it doubles after two).
    pub streak: u32,
    /// Converged steps of the stage since its start (carried by step checkpoints, so that
    /// what is counted in steps, such as the results every `output_every` time steps, does
    /// not depend on where a run was restarted).
    pub steps: u32,
    /// The stage's end time.
    pub t_end: f64,
    /// The stage's nominal step, t_end over its load (time) steps: where a cut-back grows back to.
    pub dt_nominal: f64,
    /// The largest increment: the nominal step times the growth factor (1: no growth).
    pub dt_max: f64,
}

impl StepControl {
    /// The start of a stage of `n_steps` equal steps from 0 to `t_end`.
    pub fn new(t_end: f64, n_steps: u32) -> Self {
        StepControl::growing(t_end, n_steps, 1)
    }

    /// The start of a stage of `n_steps` nominal steps from 0 to `t_end` whose easy steps may
    /// grow to `growth` times the nominal step (1: equal steps).
    pub fn growing(t_end: f64, n_steps: u32, growth: u32) -> Self {
        let dt = t_end / n_steps.max(1) as f64;
        StepControl {
            t: 0.0,
            dt,
            streak: 0,
            steps: 0,
            t_end,
            dt_nominal: dt,
            dt_max: dt * growth.max(1) as f64,
        }
    }

    /// A stage resumed at `t` with increment `dt`, success count `streak` and `steps`
    /// converged steps (a step checkpoint), of `n_steps` nominal steps to `t_end` growing to
    /// `growth` times.
    pub fn resumed(at: Resumed, t_end: f64, n_steps: u32, growth: u32) -> Self {
        StepControl {
            t: at.t,
            dt: at.dt,
            streak: at.streak,
            steps: at.steps,
            ..StepControl::growing(t_end, n_steps, growth)
        }
    }

    /// Snapping distance to the stage's end.
    fn tolerance(&self) -> f64 {
        1e-12 * self.t_end.abs().max(1.0)
    }

    /// Whether the stage's end is reached.
    pub fn done(&self) -> bool {
        self.t >= self.t_end - self.tolerance()
    }

    /// The target time of the next attempt: t + dt, or the stage's end when that is within
    /// the snapping distance of it or beyond.
    pub fn target(&self) -> f64 {
        if self.t + self.dt > self.t_end - self.tolerance() {
            self.t_end
        } else {
            self.t + self.dt
        }
    }

    /// Records a step to `t1` converged in `iterations` Newton iterations: below the nominal
    /// step dt grows back after two successes in a row; from it on it doubles after an easy
    /// step up to `dt_max` and halves after a hard one down to the nominal step.
    pub fn accept(&mut self, t1: f64, iterations: u32) {
        self.t = t1;
        self.streak += 1;
        self.steps += 1;
        if self.dt < self.dt_nominal {
            if self.streak >= 2 {
                self.dt = (2.0 * self.dt).min(self.dt_nominal);
                self.streak = 0;
            }
        } else if iterations <= EASY_STEP_ITERATIONS && self.dt < self.dt_max {
            self.dt = (2.0 * self.dt).min(self.dt_max);
            self.streak = 0;
        } else if iterations > HARD_STEP_ITERATIONS && self.dt > self.dt_nominal {
            self.dt = (0.5 * self.dt).max(self.dt_nominal);
            self.streak = 0;
        }
    }

    /// Halves dt after a failed attempt.
    pub fn cut_back(&mut self) {
        self.dt *= 0.5;
        self.streak = 0;
    }

    /// One converged step: `attempt(t0, t1, report)` solves the step from the converged time
    /// `t0` to `t1` (and leaves the problem at its committed state when it fails); a
    /// recoverable failure is cut back, at most `max_cutbacks` times in a row. `monitor` prints
    /// each cut-back (rank 0 only); `kind` names the stage's time in messages.
    pub fn advance(
        &mut self,
        max_cutbacks: u32,
        monitor: bool,
        kind: StepKind,
        report: &mut SolveReport,
        mut attempt: impl FnMut(f64, f64, &mut SolveReport) -> Result<(), SolveError>,
    ) -> Result<(), SolveError> {
        let mut cuts = 0u32;
        loop {
            let next = self.target();
            let before = report.newton_iterations;
            match attempt(self.t, next, report) {
                Ok(()) => {
                    let iterations = report.newton_iterations - before;
                    report.steps += 1;
                    report.newton_per_step.push(iterations);
                    self.accept(next, iterations);
                    return Ok(());
                }
                Err(e) if e.recoverable() && cuts < max_cutbacks => {
                    if monitor {
                        eprintln!("{} to {} cut back: {e}", kind.noun(), kind.at(next));
                    }
                    cuts += 1;
                    report.cutbacks += 1;
                    self.cut_back();
                }
                Err(e) => {
                    return Err(SolveError::Step {
                        kind,
                        from: self.t,
                        to: next,
                        cutbacks: cuts,
                        source: Box::new(e),
                    });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_steps_land_on_the_end() {
        let mut s = StepControl::new(1.0, 4);
        let mut times = Vec::new();
        while !s.done() {
            let t1 = s.target();
            s.accept(t1, 1);
            times.push(t1);
        }
        assert_eq!(times, vec![0.25, 0.5, 0.75, 1.0]);
    }

    #[test]
    fn a_cut_back_halves_and_two_successes_grow_back() {
        let mut s = StepControl::new(2.0, 2);
        s.cut_back();
        assert_eq!(s.target(), 0.5);
        s.accept(0.5, 1);
        assert_eq!(s.dt, 0.5);
        s.accept(s.target(), 1);
        assert_eq!((s.t, s.dt), (1.0, 1.0));
        s.accept(s.target(), 1);
        assert!(s.done());
    }

    #[test]
    fn easy_steps_grow_to_the_cap_and_hard_ones_shrink_to_the_nominal_step() {
        let mut s = StepControl::growing(1.0, 8, 4);
        s.accept(s.target(), EASY_STEP_ITERATIONS);
        assert_eq!((s.t, s.dt), (0.125, 0.25));
        s.accept(s.target(), EASY_STEP_ITERATIONS);
        assert_eq!((s.t, s.dt), (0.375, 0.5));
        s.accept(s.target(), EASY_STEP_ITERATIONS);
        assert_eq!((s.t, s.dt), (0.875, 0.5), "capped at 4 × 1/8");
        assert_eq!(s.target(), 1.0, "lands on the stage's end");
        let mut s = StepControl::growing(1.0, 8, 4);
        s.dt = 0.5;
        s.accept(s.target(), HARD_STEP_ITERATIONS + 1);
        assert_eq!(s.dt, 0.25);
        s.accept(s.target(), HARD_STEP_ITERATIONS + 1);
        s.accept(s.target(), HARD_STEP_ITERATIONS + 1);
        assert_eq!(s.dt, 0.125, "not below the nominal step");
        s.accept(s.target(), HARD_STEP_ITERATIONS);
        assert_eq!(s.dt, 0.125, "neither easy nor hard: kept");
    }

    #[test]
    fn a_grown_stage_resumed_from_a_step_checkpoint_takes_the_same_steps() {
        let iterations = [1, 1, 2, 4, 1, 1];
        let mut full = StepControl::growing(1.0, 16, 4);
        let mut times = Vec::new();
        for (k, &n) in iterations.iter().enumerate() {
            if k == 3 {
                // what a step checkpoint stores, and what a restart rebuilds from it
                let (t, dt, streak, steps) = (full.t, full.dt, full.streak, full.steps);
                let resumed = StepControl::resumed(Resumed { t, dt, streak, steps }, 1.0, 16, 4);
                assert_eq!(resumed.steps, 3);
                assert_eq!(resumed, full, "resumed with its growth");
            }
            let t1 = full.target();
            full.accept(t1, n);
            times.push(t1);
        }
        assert_eq!(times, [0.0625, 0.1875, 0.4375, 0.6875, 0.8125, 1.0]);
        assert!(full.done());
    }

    #[test]
    fn without_growth_easy_steps_keep_the_nominal_step() {
        let mut s = StepControl::new(1.0, 8);
        s.accept(s.target(), 0);
        assert_eq!(s.dt, 0.125);
        s.cut_back();
        s.accept(s.target(), 0);
        assert_eq!(s.dt, 0.0625, "a cut-back grows back after two successes only");
        s.accept(s.target(), 0);
        assert_eq!(s.dt, 0.125);
    }

    #[test]
    fn advance_cuts_back_recoverable_failures_only() {
        let mut s = StepControl::new(1.0, 1);
        let mut report = SolveReport::default();
        let mut calls = 0;
        let r = s.advance(3, false, StepKind::Load, &mut report, |_, t1, _| {
            calls += 1;
            if t1 > 0.3 {
                Err(SolveError::Collective("too far".into()))
            } else {
                Ok(())
            }
        });
        assert!(r.is_ok());
        assert_eq!((calls, report.cutbacks, s.t), (3, 2, 0.25));
        let r = s.advance(0, false, StepKind::Load, &mut report, |_, _, _| {
            Err(SolveError::Collective("no".into()))
        });
        assert!(matches!(r, Err(SolveError::Step { cutbacks: 0, .. })));
    }

    #[test]
    fn a_failed_time_step_is_named_in_seconds() {
        let mut s = StepControl::new(20.0, 2000);
        s.accept(s.target(), 1);
        let mut report = SolveReport::default();
        let e = s
            .advance(0, false, StepKind::Time, &mut report, |_, _, _| {
                Err(SolveError::Collective("no".into()))
            })
            .expect_err("fails");
        let m = e.to_string();
        assert!(
            m.starts_with(
                "time step from t = 0.010000 s to t = 0.020000 s (Δt = 1.000e-2 s) failed after 0 cut-back(s)"
            )
                && m.contains("the last converged state is t = 0.010000 s: no"),
            "{m}"
        );
    }
}
