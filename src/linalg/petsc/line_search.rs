//! The line searches of the Newton corrections ([`LineSearch`]): PETSc's `l2`, or cfrd's own
//! as PETSc's shell line search, whose step rules are pure functions of the merit values.
#![allow(unsafe_code)]

use super::error::{call, callback_code, PetscError};
use super::problem::SnesProblem;
use super::vector::Vector;
use crate::linalg::ffi as p;
use std::ffi::c_void;
use std::ptr::null_mut;

/// How a Newton correction δ is scaled before it is applied (x ← x − λ·δ). Both rest on the
/// problem's own merit function ‖F‖² ([`SnesProblem::objective`], exact sums), so every
/// decision is the same at any rank count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineSearch {
    /// PETSc's `l2`: the secant minimum of ‖F(x − λδ)‖² from λ = 1 and ½, at every
    /// iteration (three residual evaluations per iteration).
    Secant,
    /// The full step when it lowers ‖F‖² (one residual evaluation); otherwise the minimum
    /// of the parabola through λ = 0, ½, 1 (two more), halving while F cannot be evaluated.
    FullStepFirst,
    /// The full step, or a longer one, from the secant through F(x) and F(x − δ)
    /// (`residual_secant_step`) when the full step lowers ‖F‖²: one or two residual
    /// evaluations; otherwise `Secant`'s step (three). A full step whose residual already
    /// meets the convergence test ([`SnesProblem::last_residual_converged`]) is kept as it is.
    ResidualSecant,
}

impl LineSearch {
    /// PETSc's line search type for this one: `l2`, or the shell whose function
    /// [`shell_function`] gives.
    pub(super) fn petsc_type(self) -> &'static [u8] {
        match self {
            LineSearch::Secant => p::SNESLINESEARCHL2,
            LineSearch::FullStepFirst | LineSearch::ResidualSecant => p::SNESLINESEARCHSHELL,
        }
    }
}

/// PETSc's shell line search function.
pub(super) type ShellFunction = unsafe extern "C" fn(p::SNESLineSearch, *mut c_void) -> p::PetscErrorCode;

/// The function of the shell line search for `kind` on the problem `P`
/// ([`LineSearch::ResidualSecant`]'s, else [`LineSearch::FullStepFirst`]'s); its context is
/// the `&mut P` of the running `SNESSolve`.
pub(super) fn shell_function<P: SnesProblem>(kind: LineSearch) -> ShellFunction {
    match kind {
        LineSearch::ResidualSecant => residual_secant::<P>,
        _ => full_step_first::<P>,
    }
}

/// [`LineSearch::FullStepFirst`] as PETSc's shell line search: X ← X − λ·Y with F(X) in F.
unsafe extern "C" fn full_step_first<P: SnesProblem>(
    ls: p::SNESLineSearch,
    ctx: *mut c_void,
) -> p::PetscErrorCode {
    // SAFETY: ctx is the `&mut P` of the running SNESSolve (`shell_function`).
    unsafe { full_step_shell::<P>(ls, ctx, false) }
}

/// [`LineSearch::ResidualSecant`] as PETSc's shell line search.
unsafe extern "C" fn residual_secant<P: SnesProblem>(
    ls: p::SNESLineSearch,
    ctx: *mut c_void,
) -> p::PetscErrorCode {
    // SAFETY: ctx is the `&mut P` of the running SNESSolve (`shell_function`).
    unsafe { full_step_shell::<P>(ls, ctx, true) }
}

/// The shell line searches; `secant`: [`LineSearch::ResidualSecant`], else
/// [`LineSearch::FullStepFirst`].
///
/// # Safety
/// `ctx` is the `&mut P` of the running SNESSolve.
unsafe fn full_step_shell<P: SnesProblem>(
    ls: p::SNESLineSearch,
    ctx: *mut c_void,
    secant: bool,
) -> p::PetscErrorCode {
    // SAFETY: the caller's contract
    let problem = unsafe { &mut *(ctx as *mut P) };
    callback_code(shell_line_search_apply(ls, problem, secant))
}

/// The body of the shell line searches: X ← X − λ·Y with F(X) in F. Without `secant`
/// ([`LineSearch::FullStepFirst`]): λ = 1 when the full step lowers ‖F‖², else
/// [`fallback_step`]'s with the parabola's vertex kept in [0.1, 1]. With `secant`
/// ([`LineSearch::ResidualSecant`]): [`secant_choice`]'s λ, else the vertex as PETSc's `l2`
/// takes it; the full step where its residual meets Newton's tolerance ([`after_full_step`]).
fn shell_line_search_apply<P: SnesProblem>(
    ls: p::SNESLineSearch,
    problem: &mut P,
    secant: bool,
) -> Result<(), PetscError> {
    let (mut x, mut f, mut y, mut w, mut g) = (null_mut(), null_mut(), null_mut(), null_mut(), null_mut());
    call!(SNESLineSearchGetVecs(ls, &mut x, &mut f, &mut y, &mut w, &mut g))?;
    let borrowed = Vector::borrowed;
    let (x, mut f, y, mut w, mut g) = (borrowed(x), borrowed(f), borrowed(y), borrowed(w), borrowed(g));
    let f0 = problem.objective(&x)?.unwrap_or(f64::INFINITY);
    let g1 = merit(problem, &x, &y, &mut w, 1.0)?;
    let rule = if secant {
        L2_FALLBACK
    } else {
        FULL_STEP_FIRST_FALLBACK
    };
    let chosen = match after_full_step(secant, f0, g1, problem.last_residual_converged()) {
        AfterFullStep::Keep => Some(1.0),
        AfterFullStep::Secant => secant_choice(problem, [&x, &y, &f], &mut w, &mut g, g1)?,
        AfterFullStep::Fallback => None,
    };
    let lambda = match chosen {
        Some(l) => Some(l),
        None => fallback_step(f0, g1, rule, &mut |l| merit(problem, &x, &y, &mut w, l))?,
    };
    let Some(lambda) = lambda else {
        return call!(SNESLineSearchSetReason(ls, p::SNES_LINESEARCH_FAILED_DOMAIN));
    };
    call!(VecWAXPY(w.raw, -lambda, y.raw, x.raw))?;
    // F at the chosen point: known from its merit evaluation unless λ is new
    if !problem.residual(&w, &mut f)? {
        return call!(SNESLineSearchSetReason(ls, p::SNES_LINESEARCH_FAILED_DOMAIN));
    }
    call!(VecCopy(w.raw, x.raw))?;
    let (mut xnorm, mut fnorm, mut ynorm) = (0.0, 0.0, 0.0);
    call!(VecNorm(x.raw, p::NORM_2, &mut xnorm))?;
    call!(VecNorm(f.raw, p::NORM_2, &mut fnorm))?;
    call!(VecNorm(y.raw, p::NORM_2, &mut ynorm))?;
    call!(SNESLineSearchSetNorms(ls, xnorm, fnorm, ynorm))?;
    call!(SNESLineSearchSetReason(ls, p::SNES_LINESEARCH_SUCCEEDED))
}

/// What a shell line search does once it knows φ(1) = `g1` (φ(0) = `f0`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum AfterFullStep {
    /// Take the full step.
    Keep,
    /// Try [`secant_choice`]'s longer step.
    Secant,
    /// The full step does not lower φ: [`fallback_step`].
    Fallback,
}

/// The full step when it lowers φ and either the line search is
/// [`LineSearch::FullStepFirst`] (`secant` false) or its residual already meets Newton's
/// convergence test (`converged`: an extension would only spend an evaluation); the residual
/// secant's step when it lowers φ otherwise; the fallback when it does not lower φ.
fn after_full_step(secant: bool, f0: f64, g1: f64, converged: bool) -> AfterFullStep {
    if g1 < f0 {
        if secant && !converged {
            AfterFullStep::Secant
        } else {
            AfterFullStep::Keep
        }
    } else {
        AfterFullStep::Fallback
    }
}

/// The merit φ(λ) = ‖F(x − λy)‖² (∞ where F cannot be evaluated), with x − λy left in `w`.
fn merit<P: SnesProblem>(
    problem: &mut P,
    x: &Vector,
    y: &Vector,
    w: &mut Vector,
    lambda: f64,
) -> Result<f64, PetscError> {
    call!(VecWAXPY(w.raw, -lambda, y.raw, x.raw))?;
    Ok(problem.objective(w)?.unwrap_or(f64::INFINITY))
}

/// [`LineSearch::ResidualSecant`]'s step when the full step lowered the merit, right after
/// φ(1) = `g1` was evaluated at `w` = x − y (`xyf` = [x, y, F(x)]; `g` is a work vector): 1
/// when [`residual_secant_step`] gives 1; its longer step when φ there is below φ(1), else 1;
/// `None` when it gives a shorter one (the caller takes PETSc's `l2` step instead).
fn secant_choice<P: SnesProblem>(
    problem: &mut P,
    xyf: [&Vector; 3],
    w: &mut Vector,
    g: &mut Vector,
    g1: f64,
) -> Result<Option<f64>, PetscError> {
    let [x, y, f] = xyf;
    // F(x − y) is the problem's last residual: copied, not evaluated again
    if !problem.residual(w, g)? {
        return Ok(None);
    }
    call!(VecAYPX(g.raw, -1.0, f.raw))?;
    let (along, squared) = (problem.dot(f, g)?, problem.dot(g, g)?);
    let lambda = residual_secant_step(along, squared).unwrap_or(0.0);
    if lambda <= 1.0 {
        return Ok((lambda == 1.0).then_some(1.0));
    }
    let gl = merit(problem, x, y, w, lambda)?;
    Ok(Some(if gl < g1 { lambda } else { 1.0 }))
}

/// The full step within `SECANT_SNAP` of [`residual_secant_step`]'s λ, and its largest λ,
/// `SECANT_LAMBDA_MAX`. PETSc's `l2` (the `Secant` line search, whose λ is unbounded) took
/// λ > 1.05 in 349 and λ > 3 in 17 of the 565 Newton iterations of the coarse hyperbolic seed
/// scene: the continuum tangent is stiffer than the consistent one, so Newton's corrections
/// fall short. Shorter steps are left to `l2`'s rule: on interfaces sliding at 100 Pa
/// (`tests/hard_cases.rs`) it took λ = 0.07, 0.008 and 1e-4 in successive iterations, and a
/// residual secant with a floor of 0.1, or of 1e-6, failed the step.
const SECANT_SNAP: f64 = 0.1;
/// See [`SECANT_SNAP`].
const SECANT_LAMBDA_MAX: f64 = 1.0e4;

/// The minimum of ‖F(0) − λ·d‖² over λ for d = F(0) − F(1) (F taken linear along the
/// correction, the secant through the two residual vectors): λ = F(0)ᵀd / ‖d‖² from
/// `along` = F(0)ᵀd and `squared` = ‖d‖², at most 1e4 and snapped to 1 within 0.1; `None`
/// when it is not a positive finite number.
fn residual_secant_step(along: f64, squared: f64) -> Option<f64> {
    let lambda = along / squared;
    if !(lambda.is_finite() && lambda > 0.0) {
        return None;
    }
    if (lambda - 1.0).abs() <= SECANT_SNAP {
        return Some(1.0);
    }
    Some(lambda.min(SECANT_LAMBDA_MAX))
}

/// [`LineSearch::FullStepFirst`]'s step from the merit φ at λ = 0, ½, 1: the vertex of the
/// parabola through them in [0.1, 1], or the smaller of φ(½) and φ(1) where it has none.
fn clamped_vertex(f0: f64, h: f64, g1: f64) -> f64 {
    let c = 2.0 * f0 - 4.0 * h + 2.0 * g1;
    let b = -3.0 * f0 + 4.0 * h - g1;
    if c > 0.0 {
        (-b / (2.0 * c)).clamp(0.1, 1.0)
    } else if h < g1 {
        0.5
    } else {
        1.0
    }
}

/// PETSc's `l2` step (one secant iteration, `-snes_linesearch_max_it 1`) from the merit φ
/// at λ = 0, ½, 1: λ = 1 − φ'(1)/|φ''| with the derivatives of the parabola through them,
/// downhill also where it is concave; ½ below `l2`'s least step 1e-12, 1 where λ is not finite
/// or above its largest step 1e8.
fn l2_vertex(f0: f64, h: f64, g1: f64) -> f64 {
    let slope = 3.0 * g1 - 4.0 * h + f0;
    let curvature = 4.0 * g1 - 8.0 * h + 4.0 * f0;
    let lambda = if curvature > 0.0 {
        1.0 - slope / curvature
    } else {
        1.0 + slope / curvature
    };
    if lambda < 1.0e-12 {
        0.5
    } else if !lambda.is_finite() || lambda > 1.0e8 {
        1.0
    } else {
        lambda
    }
}

/// How [`fallback_step`] picks λ: the vertex rule on φ at 0, ½, 1, the least λ to which it
/// halves where F cannot be evaluated, and whether it then applies the vertex rule on [0, λ].
#[derive(Clone, Copy)]
struct Fallback {
    vertex: fn(f64, f64, f64) -> f64,
    least: f64,
    rescale: bool,
}

/// [`LineSearch::FullStepFirst`]'s fallback: [`clamped_vertex`], halving to 1/64.
const FULL_STEP_FIRST_FALLBACK: Fallback = Fallback {
    vertex: clamped_vertex,
    least: 1.0 / 64.0,
    rescale: false,
};

/// [`LineSearch::ResidualSecant`]'s fallback, PETSc's `l2`: [`l2_vertex`], halving to its
/// least step 1e-12 and the vertex on [0, λ] from there (on a GP column under 30 MPa `l2`
/// found F only at λ = 1/512 of a first correction).
const L2_FALLBACK: Fallback = Fallback {
    vertex: l2_vertex,
    least: 1.0e-12,
    rescale: true,
};

/// The step length when the full step did not lower the merit φ (φ(0) = `f0`, φ(1) = `g1`),
/// or when the residual secant leaves it to the parabola: `rule.vertex(φ(0), φ(½), φ(1))`;
/// where φ is not finite, the first λ = ½, ¼, … ≥ `rule.least` where it is (with
/// `rule.rescale`, λ times the vertex rule on φ(0), φ(λ/2), φ(λ) unless that reaches 0.95 of
/// the last λ where φ was not finite); `None` if there is none.
/// `merit(λ)` evaluates φ.
fn fallback_step(
    f0: f64,
    g1: f64,
    rule: Fallback,
    merit: &mut dyn FnMut(f64) -> Result<f64, PetscError>,
) -> Result<Option<f64>, PetscError> {
    let h = merit(0.5)?;
    if h.is_finite() && g1.is_finite() && f0.is_finite() {
        return Ok(Some((rule.vertex)(f0, h, g1)));
    }
    let mut lambda = 0.5;
    let mut value = h;
    while !value.is_finite() {
        lambda *= 0.5;
        if lambda < rule.least {
            return Ok(None);
        }
        value = merit(lambda)?;
    }
    if rule.rescale && f0.is_finite() {
        let mid = merit(0.5 * lambda)?;
        // as `l2`: never back to 0.95 of the last λ where F failed (2λ)
        let vertex = lambda * (rule.vertex)(f0, mid, value);
        if mid.is_finite() && vertex <= 1.9 * lambda {
            return Ok(Some(vertex));
        }
    }
    Ok(Some(lambda))
}

#[cfg(test)]
mod tests {
    use super::fallback_step;

    /// The merit values at the fallback's trial points, recorded.
    fn step_of(f0: f64, g1: f64, phi: impl Fn(f64) -> f64) -> (Option<f64>, Vec<f64>) {
        let mut asked = Vec::new();
        let step = fallback_step(f0, g1, super::FULL_STEP_FIRST_FALLBACK, &mut |l| {
            asked.push(l);
            Ok(phi(l))
        })
        .expect("no PETSc call");
        (step, asked)
    }

    #[test]
    fn an_overshooting_step_is_cut_to_the_parabolas_minimum() {
        // φ(λ) = 1 − 2λ + 3λ² (the full step overshoots: φ(1) = 2 > φ(0) = 1), minimum at 1/3
        let phi = |l: f64| 1.0 - 2.0 * l + 3.0 * l * l;
        let (step, asked) = step_of(phi(0.0), phi(1.0), phi);
        assert_eq!(asked, vec![0.5]);
        assert!((step.unwrap() - 1.0 / 3.0).abs() < 1e-15, "{step:?}");
        // a minimum close to zero is kept at 0.1
        let steep = |l: f64| 1.0 - 2.0 * l + 50.0 * l * l;
        assert_eq!(step_of(steep(0.0), steep(1.0), steep).0, Some(0.1));
    }

    #[test]
    fn a_concave_merit_takes_the_lower_of_the_two_trial_points() {
        // φ(λ) = 1 + 2λ − λ²: φ(½) = 1.75 < φ(1) = 2
        let phi = |l: f64| 1.0 + 2.0 * l - l * l;
        assert_eq!(step_of(phi(0.0), phi(1.0), phi).0, Some(0.5));
        // φ(λ) = 1 + 2λ − 1.9λ²: φ(1) = 1.1 < φ(½) = 1.525
        let phi = |l: f64| 1.0 + 2.0 * l - 1.9 * l * l;
        assert_eq!(step_of(phi(0.0), phi(1.0), phi).0, Some(1.0));
    }

    #[test]
    fn the_residual_secant_extrapolates_a_short_correction() {
        use super::residual_secant_step;
        // F linear along the correction, the full step removing 70 % of it: F(λ) = (1 − 0.7λ)F(0)
        // with F(0) = (3, 4): d = 0.7·F(0), λ = 1 / 0.7
        let f0 = [3.0, 4.0];
        let d = [0.7 * 3.0, 0.7 * 4.0];
        let along = f0[0] * d[0] + f0[1] * d[1];
        let squared = d[0] * d[0] + d[1] * d[1];
        let lambda = residual_secant_step(along, squared).unwrap();
        assert!((lambda - 1.0 / 0.7).abs() < 1e-12, "{lambda}");
        // a correction within 10 % of the root is the full step; far ones are clamped
        assert_eq!(residual_secant_step(1.05, 1.0), Some(1.0));
        assert_eq!(residual_secant_step(10.0, 1.0), Some(10.0));
        assert_eq!(residual_secant_step(1.0e6, 1.0), Some(1.0e4));
        assert_eq!(residual_secant_step(0.01, 1.0), Some(0.01));
        // no descent along the correction, or no change of F: no secant step
        assert_eq!(residual_secant_step(-1.0, 1.0), None);
        assert_eq!(residual_secant_step(0.0, 0.0), None);
    }

    #[test]
    fn a_full_step_that_meets_the_tolerance_is_not_extended() {
        use super::{after_full_step, AfterFullStep};
        // the residual secant extends a full step that lowered φ, unless Newton ends there
        assert_eq!(after_full_step(true, 1.0, 0.5, false), AfterFullStep::Secant);
        assert_eq!(after_full_step(true, 1.0, 0.5, true), AfterFullStep::Keep);
        // full_step_first keeps every full step that lowered φ
        assert_eq!(after_full_step(false, 1.0, 0.5, false), AfterFullStep::Keep);
        // a full step that does not lower φ (or where F failed) falls back, converged or not
        for secant in [true, false] {
            assert_eq!(after_full_step(secant, 1.0, 1.0, true), AfterFullStep::Fallback);
            assert_eq!(
                after_full_step(secant, 1.0, f64::INFINITY, false),
                AfterFullStep::Fallback
            );
        }
    }

    #[test]
    fn the_l2_vertex_is_petscs_secant_step() {
        use super::l2_vertex;
        // φ(λ) = 1 − 2λ + 3λ²: minimum at 1/3; a long one (φ = 1 − 2λ + 0.5λ²) at 2, beyond
        // the full step; a steep one at 1e-4, below the clamped vertex's 0.1
        let at = |phi: &dyn Fn(f64) -> f64| l2_vertex(phi(0.0), phi(0.5), phi(1.0));
        assert!((at(&|l| 1.0 - 2.0 * l + 3.0 * l * l) - 1.0 / 3.0).abs() < 1e-15);
        assert!((at(&|l| 1.0 - 2.0 * l + 0.5 * l * l) - 2.0).abs() < 1e-14);
        assert!((at(&|l| 1.0 - 2.0 * l + 1.0e4 * l * l) - 1.0e-4).abs() < 1e-15);
        // concave: downhill past the full step; no decrease from λ = 0: the midpoint
        assert!(at(&|l| 1.0 + 2.0 * l - 1.9 * l * l) > 1.0);
        assert_eq!(at(&|l| 1.0 + 2.0 * l + l * l), 0.5);
    }

    #[test]
    fn points_where_the_residual_fails_are_halved_away_or_reported() {
        // F cannot be evaluated beyond λ = 0.2: the first finite point of ½, ¼, ⅛
        let (step, asked) = step_of(1.0, f64::INFINITY, |l| if l > 0.2 { f64::INFINITY } else { 0.5 });
        assert_eq!(step, Some(0.125));
        assert_eq!(asked, vec![0.5, 0.25, 0.125]);
        // nowhere down to 1/64: no step
        let (step, asked) = step_of(1.0, f64::INFINITY, |_| f64::INFINITY);
        assert_eq!(step, None);
        assert_eq!(asked.last().copied(), Some(1.0 / 64.0));
    }
}
