//! Explicit modified-Euler substepping with error control for generalized-plasticity (GP)
//! models (spec §8.2, after Sloan, Abbo & Sheng 2001).
//!
//! A GP model has no yield surface, so there is no drift correction: the scheme only splits
//! the step increment Δε into substeps `dT·Δε`, integrates each substep with a two-stage
//! (forward Euler + modified Euler) estimate on a branch decided at the substep start, and
//! adapts `dT` from the difference of the two estimates.
//!
//! The scheme is generic over [`GpModelFunctions`], the "model functions" of a GP model
//! (elastic matrix, loading direction, flow direction, plastic modulus, internal-variable
//! rates, post-step rules). It works in any dimension `N` (6 for a solid point in Voigt form,
//! 3 for an interface point) and for any number `K` of rate-integrated internal variables.
//! Users: the rockfill model ([`crate::material::rockfill_gp`], N = 6) and the GP interface
//! ([`crate::material::interface_gp`], N = 3; it overrides the branch decision for its
//! reversal rule, the error measure, and stops inside a substep when it opens).
//!
//! ```text
//! input : committed point (σ0, κ0, memory0), total increment Δε
//! T = 0; dT = 1
//! while T < 1:
//!     dε = dT·Δε
//!     De = De(point); dσe = De·dε
//!     (br, c0) = begin_substep(point, dε, dσe)    # may change the memory (reversal point)
//!     stage 1 at point            → (Δσ1, Δκ1)       # branch br frozen
//!     c1 = loading_indicator(point + stage 1)
//!     if dT > DT_MIN and branch(c1) is plastic and ≠ br    # flip L↔U, or neutral → plastic
//!        and fewer than MAX_BRANCH_FLIPS flips were located in this step:
//!         reject; retry with dT ← dT·c0/(c0 − c1) (estimated change point, ≤ 0.9·dT)
//!     stage 2 at point + stage 1  → (Δσ2, Δκ2)       # same branch br
//!     σ̃ = σ + ½(Δσ1+Δσ2);  κ̃ = κ + ½(Δκ1+Δκ2)
//!     R = max(‖Δσ2−Δσ1‖/(2‖σ̃‖+σ_scale), max_j |Δκ2_j−Δκ1_j|/(2|κ̃_j|+κ_scale_j)), R ≥ EPS
//!     R = substep_error(...)                       # the line above is the default
//!     R ≤ STOL: accept; stop_in_substep(start, new) → return at T + f·dT if it says so;
//!               after_accept(point), T += dT, q = min(0.9√(STOL/R), 1.1)
//!     else    : reject, q = max(0.9√(STOL/R), 0.1); a rejection at DT_MIN is a failure
//!     dT = min(max(q·dT, DT_MIN), 1 − T)
//! ```
//!
//! Two refinements of the spec's pseudo-code, both needed for cyclic paths where the
//! deviator passes through zero (the direction n turns over within a substep):
//! * after a branch flip the retry size comes from the linear estimate of the change point
//!   instead of the factor 0.1, and the error-controlled size is kept;
//! * a substep shortened by a flip (or by the end of the step) does not cap the growth of
//!   the next one at 1.1× its own size; the next size is min(previous size, q·dT).
//!
//! Without them every zero crossing of q drove dT to DT_MIN and the following ≈145 substeps
//! grew back at 1.1× each (measured: 130 substeps per cyclic update of 2·10⁻⁴).
//!
//! A third one for the GP interface near its peak, where the loading direction n turns within
//! a small fraction of a substep at almost every substep (the reversal point of (I18) close to
//! the stress ratio, softening, the switch between virgin and cyclic branches at η = η_max):
//! after [`MAX_BRANCH_FLIPS`] flips located in one step, a substep keeps the branch decided at
//! its start, under the error control alone. The spec's scheme locates every flip: on the
//! points of the seed's GP-interface quake the substeps shrank to 10⁻⁴–10⁻⁶ of the step, the
//! branch flipping again after each, and the step failed at NMAX = 10,000 attempts at
//! T = 0.27–0.99 (`interface_gp` test `reversals_past_the_peak_do_not_stall_the_substepping`).
//! With the budget the same steps take 27–764 substeps; the stresses differ from those with a
//! budget of 1,000 flips by at most 0.01 % of |s|.
//!
//! A stage on a plastic branch with plastic data (n, n_g, H) (spec (R16)–(R17), (I19)–(I20)):
//!
//! ```text
//! dλ = nᵀDe dε / (H + nᵀDe n_g)        dσ = De dε − dλ De n_g        dκ = model(dλ, …)
//! ```
//!
//! The denominator is guarded (spec §8.6 item 4): `H + nᵀDe n_g ≥ 0.05·|nᵀDe n_g|`
//! ([`guarded_denominator`]); the same bound is used for the rate and for the tangent, so that
//! a negative denominator never reverses the plastic flow. `H = +∞` (or any non-finite or
//! huge H) means "elastic on this branch" (spec §8.6 item 5: a capped H means elastic).
//!
//! The returned tangent is the continuum operator D^ep of the last accepted substep's branch
//! evaluated at the final state (spec §8.5), or D^e if that substep was elastic.
//!
//! # How another GP model uses this module
//! 1. Split the point state into the stress `σ` (`SVector<f64, N>`), the rate-integrated
//!    internal variables `κ` (`SVector<f64, K>`: everything that grows with dλ or dε and must
//!    enter the error norm), and a `Memory` (everything that changes only at substep starts
//!    or after accepted substeps: memory surfaces, reversal points, flags).
//! 2. Implement [`GpModelFunctions`] on the model (model units are free: kPa for the spec's
//!    models; convert once at the `SolidModel`/`InterfaceModel` boundary).
//! 3. Call [`integrate`] with the committed point, the total step increment and the branch
//!    of the committed state (store [`IntegrationResult::last_branch`] in the model state:
//!    it selects the tangent of a zero increment).
//!
//! Points to know when writing the model functions:
//! * `begin_substep` works on a copy of the point: if the substep is rejected the copy,
//!   with any memory change (e.g. a new reversal point), is dropped and the retry calls
//!   `begin_substep` again from the unchanged point.
//! * `loading_indicator` must be the cosine nᵀdσe/(|n||dσe|) (a value in [−1, 1]); the flip
//!   test compares it with ±tolN and the retry size interpolates it linearly. Use norms that
//!   are invariant for your frame if you want frame-invariant substep sequences.
//! * `plastic_data` may return `h = f64::INFINITY` (elastic branch); the denominator guard
//!   and the "elastic" threshold [`H_ELASTIC`] are applied by the integrator.
//! * `kappa_increment` receives dλ with its sign (negative on unloading: take `abs()` for
//!   accumulated quantities) and is also called on elastic stages.
//! * `after_accept` is the only place for discontinuous updates (cut-offs, memory
//!   surfaces); it may return [`Branch::Elastic`] to make the tangent elastic.
//! * `stop_in_substep` ends the integration inside an accepted substep (the interface opening,
//!   spec §2.12): the model interpolates the point, the result reports the fraction reached.
//! * A model whose indicator and plastic data share costly local quantities (invariants,
//!   Lode angle) may override `begin_substep_with_data` and `indicator_with_data` to hand the
//!   stage the plastic data of the branch it decided, instead of having `plastic_data`
//!   recompute it at the same point; the data must be the same bits `plastic_data` gives
//!   there (the rockfill does this, checked bit for bit by its property test). The defaults
//!   hand over nothing.
//! * `substep_error` replaces the componentwise error measure when the internal variables
//!   need a joint norm or a state-dependent scale.
//! * `error_scales` gives absolute floors: the stress floor in model units (p_a or σ_min),
//!   one floor per κ entry (`f64::INFINITY` excludes an entry).
//!
//! # References
//! Sloan S.W., Abbo A.J., Sheng D. (2001). Refined explicit integration of elastoplastic
//! models with automatic error control. Engineering Computations 18(1/2):121–154.

use crate::error::MaterialError;
use crate::material::TangentKind;
use nalgebra::{SMatrix, SVector};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Plastic data a model hands over with its branch decision
/// ([`GpModelFunctions::begin_substep_with_data`]): `None` when it gives none, otherwise what
/// [`GpModelFunctions::plastic_data`] returns at that point (spec (R16), (I19)).
pub type KnownPlasticData<const N: usize> = Option<Result<PlasticData<N>, MaterialError>>;

/// Branch of a GP (sub)step (spec (R15), (I17)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// Neutral or elastic: nᵀdσ^e ≈ 0, or an infinite plastic modulus.
    #[default]
    Elastic,
    /// Loading: nᵀdσ^e > 0.
    Loading,
    /// Unloading: nᵀdσ^e < 0.
    Unloading,
}

/// Options of the substepping scheme (spec §8.2). Every field has a default.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SubstepOptions {
    /// Relative error tolerance STOL of a substep (default 1e-4; sensible 1e-3 … 1e-5).
    pub stol: f64,
    /// Smallest substep size DT_MIN as a fraction of the step (default 1e-6).
    pub dt_min: f64,
    /// Floor EPS of the error measure R (default 1e-12).
    pub eps: f64,
    /// Largest number of substep attempts (accepted + rejected) in one step, NMAX (default
    /// 10000). Input key `max_substeps`; `nmax` is accepted as an alias.
    #[serde(alias = "nmax")]
    pub max_substeps: u32,
    /// Relative tolerance tolN of the branch test nᵀdσ^e ≷ ±tolN·|n||dσ^e| (default 1e-6).
    pub tol_n: f64,
}

impl Default for SubstepOptions {
    fn default() -> Self {
        SubstepOptions {
            stol: 1.0e-4,
            dt_min: 1.0e-6,
            eps: 1.0e-12,
            max_substeps: 10_000,
            tol_n: 1.0e-6,
        }
    }
}

impl SubstepOptions {
    /// Checks the ranges: 0 < STOL < 1, 0 < DT_MIN < 1, EPS ≥ 0, NMAX ≥ 1, tolN ≥ 0.
    /// `prefix` is prepended to the field names of the error (e.g. `"integration."`).
    pub fn validate(&self, prefix: &str) -> Result<(), crate::error::ParamError> {
        use crate::error::{require_non_negative, require_range, ParamError};
        require_range(&format!("{prefix}stol"), self.stol, 1.0e-12, 0.5)?;
        require_range(&format!("{prefix}dt_min"), self.dt_min, 1.0e-15, 0.5)?;
        require_non_negative(&format!("{prefix}eps"), self.eps)?;
        require_non_negative(&format!("{prefix}tol_n"), self.tol_n)?;
        if self.max_substeps == 0 {
            return Err(ParamError::new(
                format!("{prefix}max_substeps"),
                "must be at least 1",
            ));
        }
        Ok(())
    }
}

/// A GP point as the integrator sees it: stress, rate-integrated internal variables, memory.
#[derive(Debug, Clone, PartialEq)]
pub struct GpPoint<const N: usize, const K: usize, M> {
    /// Stress in the model's units and sign convention.
    pub sigma: SVector<f64, N>,
    /// Internal variables integrated by the two Euler stages and checked by the error norm.
    pub kappa: SVector<f64, K>,
    /// Variables changed only by [`GpModelFunctions::begin_substep`] and
    /// [`GpModelFunctions::after_accept`] (memory surfaces, reversal points, flags).
    pub memory: M,
}

/// Plastic data of a branch at a state: loading direction n, flow direction n_g, modulus H.
///
/// `n` multiplies stress increments (nᵀdσ); `n_g` is strain-like (dε^p = dλ·n_g). Both are
/// given in the model's sign convention; flipping the sign of both leaves every result
/// unchanged. `h = f64::INFINITY` means the branch is elastic at this state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlasticData<const N: usize> {
    /// Loading direction n.
    pub n: SVector<f64, N>,
    /// Plastic flow direction n_g of the branch.
    pub n_g: SVector<f64, N>,
    /// Plastic modulus H of the branch (model stress units).
    pub h: f64,
}

/// What one Euler stage hands to [`GpModelFunctions::kappa_increment`].
#[derive(Debug, Clone, Copy)]
pub struct StageIncrement<'a, const N: usize> {
    /// The frozen branch of the substep.
    pub branch: Branch,
    /// The substep strain increment dε = dT·Δε.
    pub d_eps: &'a SVector<f64, N>,
    /// The stress increment of this stage dσ.
    pub d_sig: &'a SVector<f64, N>,
    /// Plastic data of the stage, `None` when the stage is elastic.
    pub plastic: Option<&'a PlasticData<N>>,
    /// Plastic multiplier dλ of the stage (0 when elastic). Its sign follows nᵀdσ^e: it is
    /// negative on the unloading branch.
    pub d_lambda: f64,
}

/// The model functions of a generalized-plasticity model, in dimension `N` with `K`
/// rate-integrated internal variables (spec §8.2; style guide G.3 "GP split").
///
/// The integrator calls, for each substep:
/// 1. [`elastic_matrix`](Self::elastic_matrix) at the substep start, then
///    [`begin_substep`](Self::begin_substep) once (it decides the branch and may update the
///    memory, e.g. store a reversal point);
/// 2. for each of the two Euler stages (at the start point, then at the Euler-predicted
///    point): [`elastic_matrix`](Self::elastic_matrix),
///    [`plastic_data`](Self::plastic_data) for the frozen branch (plastic branches only) and
///    [`kappa_increment`](Self::kappa_increment);
/// 3. [`loading_indicator`](Self::loading_indicator) at the predicted point (a change to
///    another plastic branch rejects the substep unless dT = DT_MIN);
/// 4. after an accepted substep, [`after_accept`](Self::after_accept) on the new point
///    (floors, cut-offs, memory updates);
/// 5. at the end of the step, [`elastic_matrix`](Self::elastic_matrix) and
///    [`plastic_data`](Self::plastic_data) once more for the tangent.
///
/// All functions must be pure functions of their arguments (no interior mutability): the
/// integrator relies on it for the purity of a material update. Inside the Euler stages the
/// memory is the one fixed at the substep start; only `begin_substep` and `after_accept`
/// change it.
pub trait GpModelFunctions<const N: usize, const K: usize> {
    /// Memory variables of a point (changed only at substep starts and after acceptance).
    type Memory: Clone + core::fmt::Debug;

    /// Elastic matrix D^e at a point (spec (R3), (I5)).
    fn elastic_matrix(&self, point: &GpPoint<N, K, Self::Memory>) -> SMatrix<f64, N, N>;

    /// Loading direction, flow direction and plastic modulus of `branch` (never
    /// [`Branch::Elastic`]) at `point`, for the substep strain increment `d_eps` (used where
    /// a direction is undefined, e.g. q = 0; spec §1.2, (I12)). Return `h = f64::INFINITY`
    /// when the branch is elastic at this point (spec §8.6 item 5).
    fn plastic_data(
        &self,
        point: &GpPoint<N, K, Self::Memory>,
        branch: Branch,
        d_eps: &SVector<f64, N>,
    ) -> Result<PlasticData<N>, MaterialError>;

    /// Loading indicator at a point without changing it (spec (R15), (I17)):
    ///
    /// ```text
    /// c = nᵀ·dσe / (|n|·|dσe|) ∈ [−1, 1]   (0 when n or dσe vanishes),  dσe = De·dε
    /// ```
    ///
    /// The branch is [`classify_indicator`]`(c, tolN)`. The default takes n from the loading
    /// branch's [`plastic_data`](Self::plastic_data). The integrator calls it at the
    /// Euler-predicted point to detect a branch change inside a substep, and uses the values at
    /// both ends to estimate where the change happens.
    fn loading_indicator(
        &self,
        point: &GpPoint<N, K, Self::Memory>,
        d_eps: &SVector<f64, N>,
        d_sig_e: &SVector<f64, N>,
    ) -> Result<f64, MaterialError> {
        let data = self.plastic_data(point, Branch::Loading, d_eps)?;
        Ok(cosine(&data.n, d_sig_e))
    }

    /// Branch decision at a substep start; the branch is then frozen for both Euler stages
    /// (spec §8.2). Returns the branch and the loading indicator at the (possibly updated)
    /// point. It may change the memory: the interface model stores its reversal point and
    /// re-maps here (spec (I18)). The default classifies
    /// [`loading_indicator`](Self::loading_indicator) and changes nothing.
    fn begin_substep(
        &self,
        point: &mut GpPoint<N, K, Self::Memory>,
        d_eps: &SVector<f64, N>,
        d_sig_e: &SVector<f64, N>,
        tol_n: f64,
    ) -> Result<(Branch, f64), MaterialError> {
        let c = self.loading_indicator(point, d_eps, d_sig_e)?;
        Ok((classify_indicator(c, tol_n), c))
    }

    /// [`begin_substep`](Self::begin_substep) together with the plastic data of the branch it
    /// decides, at the (possibly updated) point: for a model whose loading indicator and
    /// plastic data share their costly part (the rockfill's invariants and Lode angle), one
    /// evaluation instead of two. The data, when given, must be bitwise what
    /// [`plastic_data`](Self::plastic_data) returns there (its error included); `None`, the
    /// default, lets the first Euler stage call `plastic_data` itself.
    fn begin_substep_with_data(
        &self,
        point: &mut GpPoint<N, K, Self::Memory>,
        d_eps: &SVector<f64, N>,
        d_sig_e: &SVector<f64, N>,
        tol_n: f64,
    ) -> Result<(Branch, f64, KnownPlasticData<N>), MaterialError> {
        let (branch, c) = self.begin_substep(point, d_eps, d_sig_e, tol_n)?;
        Ok((branch, c, None))
    }

    /// [`loading_indicator`](Self::loading_indicator) at `point` together with the plastic
    /// data of `branch` there (none for [`Branch::Elastic`]), under the same contract as
    /// [`begin_substep_with_data`](Self::begin_substep_with_data): the integrator calls it at
    /// the Euler-predicted point, whose second stage then needs that data.
    fn indicator_with_data(
        &self,
        point: &GpPoint<N, K, Self::Memory>,
        d_eps: &SVector<f64, N>,
        d_sig_e: &SVector<f64, N>,
        _branch: Branch,
    ) -> Result<(f64, KnownPlasticData<N>), MaterialError> {
        Ok((self.loading_indicator(point, d_eps, d_sig_e)?, None))
    }

    /// Increment of the rate-integrated internal variables κ in one Euler stage (spec (R17),
    /// (I20), (I21)). Called for elastic stages too (with `plastic = None`, `d_lambda = 0`),
    /// for variables that change with the total strain (e.g. a void ratio).
    fn kappa_increment(
        &self,
        point: &GpPoint<N, K, Self::Memory>,
        stage: &StageIncrement<'_, N>,
    ) -> SVector<f64, K>;

    /// Rules applied to an accepted substep: floors, cut-offs, memory updates (spec §8.2
    /// "post-step rules", §8.6). Returns the branch to record for this substep (normally
    /// `branch`; e.g. [`Branch::Elastic`] when a cut-off reset the stress). An error aborts
    /// the update.
    fn after_accept(
        &self,
        point: &mut GpPoint<N, K, Self::Memory>,
        branch: Branch,
    ) -> Result<Branch, MaterialError>;

    /// Norm of a stress-like vector used by the error measure. The default is the Euclidean
    /// norm of the components; a Voigt model should use the tensor norm √(σ:σ) so that the
    /// substep sequence does not depend on the orientation of the axes.
    fn stress_norm(&self, sigma: &SVector<f64, N>) -> f64 {
        sigma.norm()
    }

    /// Scales of the error norm: the stress scale added to 2‖σ̃‖ (spec §8.2 `pscale`: p_a for
    /// the rockfill, σ_min for the interface) and one scale per internal variable
    /// (`f64::INFINITY` leaves a variable out of the error measure).
    fn error_scales(&self) -> (f64, SVector<f64, K>);

    /// Relative local error R of a substep from its two Euler stages (spec §8.2), at the new
    /// point (σ̃, κ̃) = start + ½(stage 1 + stage 2). The default is the spec's measure with
    /// [`stress_norm`](Self::stress_norm) and [`error_scales`](Self::error_scales):
    ///
    /// ```text
    /// R = max( ‖Δσ2−Δσ1‖ / (2‖σ̃‖ + σ_scale),  max_j |Δκ2_j−Δκ1_j| / (2|κ̃_j| + κ_scale_j) )
    /// ```
    ///
    /// A model whose internal variables need a joint measure (e.g. a vector norm, or a scale
    /// that depends on the state) overrides it. The integrator floors R at EPS.
    fn substep_error(
        &self,
        new_point: (&SVector<f64, N>, &SVector<f64, K>),
        stage1: (&SVector<f64, N>, &SVector<f64, K>),
        stage2: (&SVector<f64, N>, &SVector<f64, K>),
    ) -> f64 {
        let (sig_scale, kappa_scale) = self.error_scales();
        let (sigma, kappa) = new_point;
        let mut err = self.stress_norm(&(stage2.0 - stage1.0)) / (2.0 * self.stress_norm(sigma) + sig_scale);
        for j in 0..K {
            err = err.max((stage2.1[j] - stage1.1[j]).abs() / (2.0 * kappa[j].abs() + kappa_scale[j]));
        }
        err
    }

    /// Stop test of an accepted substep from `before` (the substep start, after
    /// [`begin_substep`](Self::begin_substep)) to `after` (before
    /// [`after_accept`](Self::after_accept)). Returning `Some(f)` ends the integration inside
    /// this substep at the fraction `f` ∈ [0, 1] of it, at the point the model wrote into
    /// `after` (e.g. the interface opens at σ_n = σ_open, spec §2.12);
    /// [`IntegrationResult::reached`] then reports the fraction of the step integrated and
    /// `after_accept` is not called. The default never stops.
    fn stop_in_substep(
        &self,
        before: &GpPoint<N, K, Self::Memory>,
        after: &mut GpPoint<N, K, Self::Memory>,
    ) -> Option<f64> {
        let _ = (before, after);
        None
    }
}

/// Outcome of [`integrate`].
#[derive(Debug, Clone, PartialEq)]
pub struct IntegrationResult<const N: usize, const K: usize, M> {
    /// The point at the end of the step.
    pub point: GpPoint<N, K, M>,
    /// Continuum tangent of the last substep's branch at the end point, or D^e.
    pub tangent: SMatrix<f64, N, N>,
    /// [`TangentKind::Continuum`] or [`TangentKind::Elastic`].
    pub kind: TangentKind,
    /// Branch of the last accepted substep (as returned by `after_accept`).
    pub last_branch: Branch,
    /// Number of accepted substeps.
    pub substeps: u32,
    /// Number of rejected substeps.
    pub rejected: u32,
    /// Fraction of the step increment integrated: 1 unless
    /// [`GpModelFunctions::stop_in_substep`] ended the integration early.
    pub reached: f64,
    /// Strain increment dT·Δε of the last accepted substep (the step increment when none was
    /// taken); the tangent was evaluated with it.
    pub last_d_eps: SVector<f64, N>,
}

/// Cosine nᵀv/(|n||v|) of two vectors, 0 when either vanishes.
pub fn cosine<const N: usize>(n: &SVector<f64, N>, v: &SVector<f64, N>) -> f64 {
    let den = n.norm() * v.norm();
    if den > 0.0 && den.is_finite() {
        (n.dot(v) / den).clamp(-1.0, 1.0)
    } else {
        0.0
    }
}

/// Branch of a loading indicator c = nᵀdσe/(|n||dσe|) (spec (R15), (I17), §8.2):
///
/// ```text
/// c > +tolN → Loading;  c < −tolN → Unloading;  else Elastic (neutral)
/// ```
pub fn classify_indicator(c: f64, tol_n: f64) -> Branch {
    if c > tol_n {
        Branch::Loading
    } else if c < -tol_n {
        Branch::Unloading
    } else {
        Branch::Elastic
    }
}

/// Branch of a stress-increment direction: [`classify_indicator`] of [`cosine`]`(n, dσe)`.
pub fn classify_branch<const N: usize>(n: &SVector<f64, N>, d_sig_e: &SVector<f64, N>, tol_n: f64) -> Branch {
    classify_indicator(cosine(n, d_sig_e), tol_n)
}

/// Branch flips located by retries in one step; later substeps keep the branch decided at their
/// start, under the error control alone (module docs).
pub const MAX_BRANCH_FLIPS: u32 = 100;

/// Fraction of |nᵀD^e n_g| that H + nᵀD^e n_g may not fall below (spec §8.6 item 4).
pub const DENOMINATOR_GUARD: f64 = 0.05;

/// Plastic moduli above this (model units) make a branch elastic (spec §8.6 item 5).
pub const H_ELASTIC: f64 = 1.0e30;

/// The denominator H + nᵀD^e n_g, bounded below by 0.05·|nᵀD^e n_g| (spec §8.6 item 4).
/// Returns `None` when the branch is elastic (H infinite or ≥ [`H_ELASTIC`], or a zero bound).
///
/// ```text
/// a = nᵀ·De·n_g;  d = max(H + a, 0.05·|a|)
/// ```
pub fn guarded_denominator<const N: usize>(dd_e: &SMatrix<f64, N, N>, data: &PlasticData<N>) -> Option<f64> {
    if data.h.is_nan() || data.h >= H_ELASTIC {
        return None;
    }
    let a = data.n.dot(&(dd_e * data.n_g));
    let d = (data.h + a).max(DENOMINATOR_GUARD * a.abs());
    if d > 0.0 && d.is_finite() {
        Some(d)
    } else {
        None
    }
}

/// Continuum elasto-plastic operator (spec (R16), (I19)) with the guarded denominator:
///
/// ```text
/// D^ep = De − (De·n_g)(nᵀ·De) / max(H + nᵀDe n_g, 0.05·|nᵀDe n_g|)
/// ```
/// Returns D^e and [`TangentKind::Elastic`] when the branch is elastic.
pub fn elastoplastic_matrix<const N: usize>(
    dd_e: &SMatrix<f64, N, N>,
    data: &PlasticData<N>,
) -> (SMatrix<f64, N, N>, TangentKind) {
    match guarded_denominator(dd_e, data) {
        Some(den) => {
            let a = dd_e * data.n_g;
            let b = dd_e.transpose() * data.n;
            (dd_e - a * b.transpose() / den, TangentKind::Continuum)
        }
        None => (*dd_e, TangentKind::Elastic),
    }
}

/// One Euler stage: (dσ, dκ) at `point` on the frozen `branch` (spec (R17)), with the
/// branch's plastic data `known` when the model gave it along with the branch decision.
fn stage<F, const N: usize, const K: usize>(
    model: &F,
    point: &GpPoint<N, K, F::Memory>,
    branch: Branch,
    d_eps: &SVector<f64, N>,
    dd_e: &SMatrix<f64, N, N>,
    known: KnownPlasticData<N>,
) -> Result<(SVector<f64, N>, SVector<f64, K>), MaterialError>
where
    F: GpModelFunctions<N, K> + ?Sized,
{
    let d_sig_e = dd_e * d_eps;
    let plastic = match branch {
        Branch::Elastic => None,
        Branch::Loading | Branch::Unloading => {
            let data = match known {
                Some(data) => data?,
                None => model.plastic_data(point, branch, d_eps)?,
            };
            guarded_denominator(dd_e, &data).map(|den| (data, den))
        }
    };
    match plastic {
        Some((data, den)) => {
            let d_lambda = data.n.dot(&d_sig_e) / den;
            let d_sig = d_sig_e - (dd_e * data.n_g) * d_lambda;
            let d_kappa = model.kappa_increment(
                point,
                &StageIncrement {
                    branch,
                    d_eps,
                    d_sig: &d_sig,
                    plastic: Some(&data),
                    d_lambda,
                },
            );
            Ok((d_sig, d_kappa))
        }
        None => {
            let d_kappa = model.kappa_increment(
                point,
                &StageIncrement {
                    branch,
                    d_eps,
                    d_sig: &d_sig_e,
                    plastic: None,
                    d_lambda: 0.0,
                },
            );
            Ok((d_sig_e, d_kappa))
        }
    }
}

/// True when the branch `b` at the predicted point rejects a substep started on `a`: a sign
/// flip of nᵀdσ^e (Loading ↔ Unloading), or a neutral start that turns plastic.
fn is_flip(a: Branch, b: Branch) -> bool {
    a != b && b != Branch::Elastic
}

/// The continuum tangent of `branch` at `point` for the increment direction `d_eps`
/// (spec §8.5): D^ep of (R16)/(I19), or D^e on the elastic branch.
pub fn continuum_tangent<F, const N: usize, const K: usize>(
    model: &F,
    point: &GpPoint<N, K, F::Memory>,
    branch: Branch,
    d_eps: &SVector<f64, N>,
) -> Result<(SMatrix<f64, N, N>, TangentKind), MaterialError>
where
    F: GpModelFunctions<N, K> + ?Sized,
{
    let dd_e = model.elastic_matrix(point);
    match branch {
        Branch::Elastic => Ok((dd_e, TangentKind::Elastic)),
        Branch::Loading | Branch::Unloading => {
            let data = model.plastic_data(point, branch, d_eps)?;
            Ok(elastoplastic_matrix(&dd_e, &data))
        }
    }
}

/// Integrates a GP model over the total increment `d_eps` from the committed point `start`
/// (spec §8.2). Pure: the same input gives bitwise the same output.
///
/// Errors: a rejected substep at DT_MIN, more than NMAX substep attempts, or a non-finite
/// accepted state give `Err(MaterialError)` (the caller then cuts the global step).
///
/// For a zero increment the start point is returned unchanged, with the tangent of the branch
/// stored by the caller in `last_branch` (the branch of the committed state).
pub fn integrate<F, const N: usize, const K: usize>(
    model: &F,
    start: &GpPoint<N, K, F::Memory>,
    d_eps: &SVector<f64, N>,
    last_branch: Branch,
    opts: &SubstepOptions,
) -> Result<IntegrationResult<N, K, F::Memory>, MaterialError>
where
    F: GpModelFunctions<N, K> + ?Sized,
{
    if !d_eps.iter().all(|x| x.is_finite()) {
        return Err(MaterialError::new("non-finite strain increment"));
    }
    if d_eps.iter().all(|&x| x == 0.0) {
        let (tangent, kind) = continuum_tangent(model, start, last_branch, d_eps)?;
        return Ok(IntegrationResult {
            point: start.clone(),
            tangent,
            kind,
            last_branch,
            substeps: 0,
            rejected: 0,
            reached: 1.0,
            last_d_eps: *d_eps,
        });
    }
    let mut s = Substepping {
        point: start.clone(),
        t: 0.0_f64,
        dt_err: 1.0_f64,
        dt_limit: None,
        accepted: 0_u32,
        rejected: 0_u32,
        branch_out: last_branch,
        last_d_eps: *d_eps,
        flips_left: MAX_BRANCH_FLIPS,
    };
    while 1.0 - s.t > 1.0e-15 {
        if s.accepted + s.rejected >= opts.max_substeps {
            let t = s.t;
            return Err(MaterialError::new(format!(
                "GP substepping: more than NMAX = {} substep attempts (T = {t:.3e})",
                opts.max_substeps
            )));
        }
        let Some(trial) = try_substep(model, d_eps, opts, &mut s)? else {
            continue;
        };
        if trial.r <= opts.stol {
            if let Some(stopped) = accept(model, opts, &mut s, trial)? {
                return Ok(stopped);
            }
        } else {
            reject(&mut s, &trial, opts)?;
        }
    }
    let (tangent, kind) = continuum_tangent(model, &s.point, s.branch_out, &s.last_d_eps)?;
    Ok(IntegrationResult {
        point: s.point,
        tangent,
        kind,
        last_branch: s.branch_out,
        substeps: s.accepted,
        rejected: s.rejected,
        reached: 1.0,
        last_d_eps: s.last_d_eps,
    })
}

/// The state of the substepping of [`integrate`] between two substep attempts.
struct Substepping<const N: usize, const K: usize, M> {
    /// The point at pseudo-time `t`.
    point: GpPoint<N, K, M>,
    /// Pseudo-time T reached, in [0, 1].
    t: f64,
    /// Error-controlled substep size.
    dt_err: f64,
    /// A shorter limit of the substep size set by a detected branch change.
    dt_limit: Option<f64>,
    /// Accepted substeps.
    accepted: u32,
    /// Rejected substep attempts (error too large or a branch change).
    rejected: u32,
    /// Branch recorded by the last accepted substep.
    branch_out: Branch,
    /// Strain increment of the last accepted substep.
    last_d_eps: SVector<f64, N>,
    /// Branch changes that may still shorten a substep.
    flips_left: u32,
}

/// A substep of the modified Euler scheme, computed by [`try_substep`], before its error
/// decides whether it is taken.
struct Trial<const N: usize, const K: usize, M> {
    /// Substep size dT.
    dt: f64,
    /// Whether dT is at DT_MIN.
    at_dt_min: bool,
    /// Strain increment dT·Δε.
    de: SVector<f64, N>,
    /// The start point after the model's branch decision.
    trial: GpPoint<N, K, M>,
    /// The point after the first Euler stage (it carries the substep's memory).
    predicted: GpPoint<N, K, M>,
    /// The substep's branch.
    branch: Branch,
    /// Stress at the end of the substep (mean of the two stages).
    new_sigma: SVector<f64, N>,
    /// Internal variables at the end of the substep.
    new_kappa: SVector<f64, K>,
    /// Relative error R of the substep.
    r: f64,
    /// Unlimited step-size factor 0.9·√(STOL/R).
    q_raw: f64,
}

/// Computes the next substep from `s`: both Euler stages and the error. A branch change
/// detected at the predicted point counts a rejection, limits the size to the estimated change
/// point and gives `None`.
#[inline]
fn try_substep<F, const N: usize, const K: usize>(
    model: &F,
    d_eps: &SVector<f64, N>,
    opts: &SubstepOptions,
    s: &mut Substepping<N, K, F::Memory>,
) -> Result<Option<Trial<N, K, F::Memory>>, MaterialError>
where
    F: GpModelFunctions<N, K> + ?Sized,
{
    let t = s.t;
    let dt = s
        .dt_err
        .min(s.dt_limit.unwrap_or(1.0))
        .max(opts.dt_min)
        .min(1.0 - t);
    let at_dt_min = dt <= opts.dt_min * (1.0 + 1.0e-12);
    let de = d_eps * dt;
    let mut trial = s.point.clone();
    let dd_e = model.elastic_matrix(&trial);
    let d_sig_e = dd_e * de;
    let (branch, c0, data1) = model.begin_substep_with_data(&mut trial, &de, &d_sig_e, opts.tol_n)?;
    let (ds1, dk1) = stage(model, &trial, branch, &de, &dd_e, data1)?;
    let mut predicted = trial.clone();
    predicted.sigma += ds1;
    predicted.kappa += dk1;
    let dd_e_pred = model.elastic_matrix(&predicted);
    let mut data2 = None;
    if !at_dt_min && s.flips_left > 0 {
        let (c1, data) = model.indicator_with_data(&predicted, &de, &(dd_e_pred * de), branch)?;
        if is_flip(branch, classify_indicator(c1, opts.tol_n)) {
            // Branch change inside the substep: retry up to the estimated change point,
            // without touching dt_err.
            s.rejected += 1;
            s.flips_left -= 1;
            s.dt_limit = Some(change_point(c0, c1) * dt);
            return Ok(None);
        }
        data2 = data;
    }
    let (ds2, dk2) = stage(model, &predicted, branch, &de, &dd_e_pred, data2)?;
    let new_sigma = trial.sigma + (ds1 + ds2) * 0.5;
    let new_kappa = trial.kappa + (dk1 + dk2) * 0.5;
    let err = model.substep_error((&new_sigma, &new_kappa), (&ds1, &dk1), (&ds2, &dk2));
    let r = if err.is_finite() {
        err.max(opts.eps)
    } else {
        f64::INFINITY
    };
    let q_raw = 0.9 * (opts.stol / r).sqrt();
    Ok(Some(Trial {
        dt,
        at_dt_min,
        de,
        trial,
        predicted,
        branch,
        new_sigma,
        new_kappa,
        r,
        q_raw,
    }))
}

/// Takes the substep `c` (its error is within STOL) and grows the error-controlled size; a
/// stop inside the substep ends the integration with its result.
#[inline]
fn accept<F, const N: usize, const K: usize>(
    model: &F,
    opts: &SubstepOptions,
    s: &mut Substepping<N, K, F::Memory>,
    c: Trial<N, K, F::Memory>,
) -> Result<Option<IntegrationResult<N, K, F::Memory>>, MaterialError>
where
    F: GpModelFunctions<N, K> + ?Sized,
{
    let (t, dt, branch) = (s.t, c.dt, c.branch);
    // The predicted point carries the substep's memory; it becomes the new point.
    let mut next = c.predicted;
    next.sigma = c.new_sigma;
    next.kappa = c.new_kappa;
    if let Some(fraction) = model.stop_in_substep(&c.trial, &mut next) {
        if !is_finite_point(&next) {
            return Err(MaterialError::new(
                "GP substepping: non-finite state at a stop inside a substep",
            ));
        }
        let (tangent, kind) = continuum_tangent(model, &next, branch, &c.de)?;
        return Ok(Some(IntegrationResult {
            point: next,
            tangent,
            kind,
            last_branch: branch,
            substeps: s.accepted + 1,
            rejected: s.rejected,
            reached: (t + fraction.clamp(0.0, 1.0) * dt).min(1.0),
            last_d_eps: c.de,
        }));
    }
    let recorded = model.after_accept(&mut next, branch)?;
    if !is_finite_point(&next) {
        return Err(MaterialError::new(
            "GP substepping: non-finite state after an accepted substep",
        ));
    }
    s.point = next;
    s.branch_out = recorded;
    s.last_d_eps = c.de;
    s.accepted += 1;
    s.t += dt;
    // A substep shortened by a branch change or by the end of the step does not
    // throttle the error-controlled size; otherwise dT ← min(q, 1.1)·dT (spec §8.2).
    s.dt_err = if dt < s.dt_err {
        s.dt_err.min(c.q_raw * dt)
    } else {
        c.q_raw.min(1.1) * dt
    };
    s.dt_err = s.dt_err.max(opts.dt_min);
    s.dt_limit = None;
    Ok(None)
}

/// Rejects the substep `c` (its error exceeds STOL) and shrinks the error-controlled size;
/// an error at DT_MIN.
#[inline]
fn reject<const N: usize, const K: usize, M>(
    s: &mut Substepping<N, K, M>,
    c: &Trial<N, K, M>,
    opts: &SubstepOptions,
) -> Result<(), MaterialError> {
    let (t, r) = (s.t, c.r);
    if c.at_dt_min {
        return Err(MaterialError::new(format!(
            "GP substepping: substep size fell below DT_MIN = {:.1e} (T = {t:.4}, R = {r:.3e})",
            opts.dt_min
        )));
    }
    s.rejected += 1;
    s.dt_err = (if r.is_finite() { c.q_raw.max(0.1) } else { 0.1 }) * c.dt;
    s.dt_limit = None;
    Ok(())
}

/// Fraction of a substep at which the loading indicator, c0 at its start and c1 at the
/// predicted point, changes sign (linear interpolation), in [0, 0.9].
fn change_point(c0: f64, c1: f64) -> f64 {
    let alpha = if (c0 - c1).abs() > 0.0 {
        c0 / (c0 - c1)
    } else {
        0.5
    };
    if alpha.is_finite() {
        alpha.clamp(0.0, 0.9)
    } else {
        0.5
    }
}

/// True when the stress and the internal variables of a point are finite.
fn is_finite_point<const N: usize, const K: usize, M>(p: &GpPoint<N, K, M>) -> bool {
    p.sigma.iter().all(|x| x.is_finite()) && p.kappa.iter().all(|x| x.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix1, Vector1};

    /// 1D linear-hardening GP toy model: D^e = E, n = n_g = 1, H = h (loading), elastic
    /// unloading. Exact solution: σ = E·H/(E+H)·ε in loading.
    struct Toy {
        e: f64,
        h: f64,
    }

    impl GpModelFunctions<1, 1> for Toy {
        type Memory = u32;
        fn elastic_matrix(&self, _p: &GpPoint<1, 1, u32>) -> Matrix1<f64> {
            Matrix1::new(self.e)
        }
        fn plastic_data(
            &self,
            _p: &GpPoint<1, 1, u32>,
            branch: Branch,
            _d: &Vector1<f64>,
        ) -> Result<PlasticData<1>, MaterialError> {
            let h = if branch == Branch::Loading {
                self.h
            } else {
                f64::INFINITY
            };
            Ok(PlasticData {
                n: Vector1::new(1.0),
                n_g: Vector1::new(1.0),
                h,
            })
        }
        fn kappa_increment(&self, _p: &GpPoint<1, 1, u32>, s: &StageIncrement<'_, 1>) -> Vector1<f64> {
            Vector1::new(s.d_lambda)
        }
        fn after_accept(&self, p: &mut GpPoint<1, 1, u32>, b: Branch) -> Result<Branch, MaterialError> {
            p.memory += 1;
            Ok(b)
        }
        fn error_scales(&self) -> (f64, Vector1<f64>) {
            (1.0, Vector1::new(1.0e-3))
        }
    }

    #[test]
    fn linear_hardening_is_exact_and_tangent_is_continuum() {
        let toy = Toy { e: 100.0, h: 25.0 };
        let start = GpPoint {
            sigma: Vector1::new(0.0),
            kappa: Vector1::new(0.0),
            memory: 0_u32,
        };
        let res = integrate(
            &toy,
            &start,
            &Vector1::new(0.01),
            Branch::Elastic,
            &SubstepOptions::default(),
        )
        .expect("integrates");
        assert!((res.point.sigma[0] - 0.2).abs() < 1e-14, "{}", res.point.sigma[0]);
        assert!((res.point.kappa[0] - 0.008).abs() < 1e-15);
        assert!((res.tangent[(0, 0)] - 20.0).abs() < 1e-12);
        assert_eq!(res.kind, TangentKind::Continuum);
        assert_eq!(res.point.memory, res.substeps);
        let back = integrate(
            &toy,
            &res.point,
            &Vector1::new(-0.01),
            Branch::Loading,
            &SubstepOptions::default(),
        )
        .expect("unloads");
        assert!((back.point.sigma[0] - (0.2 - 1.0)).abs() < 1e-13);
        assert_eq!(back.kind, TangentKind::Elastic);
        assert_eq!(back.last_branch, Branch::Unloading);
    }

    /// The toy model with a stop when σ reaches `stop_at` (linear interpolation in the substep).
    struct Stopper(Toy, f64);

    impl GpModelFunctions<1, 1> for Stopper {
        type Memory = u32;
        fn elastic_matrix(&self, p: &GpPoint<1, 1, u32>) -> Matrix1<f64> {
            self.0.elastic_matrix(p)
        }
        fn plastic_data(
            &self,
            p: &GpPoint<1, 1, u32>,
            branch: Branch,
            d: &Vector1<f64>,
        ) -> Result<PlasticData<1>, MaterialError> {
            self.0.plastic_data(p, branch, d)
        }
        fn kappa_increment(&self, p: &GpPoint<1, 1, u32>, s: &StageIncrement<'_, 1>) -> Vector1<f64> {
            self.0.kappa_increment(p, s)
        }
        fn after_accept(&self, p: &mut GpPoint<1, 1, u32>, b: Branch) -> Result<Branch, MaterialError> {
            self.0.after_accept(p, b)
        }
        fn error_scales(&self) -> (f64, Vector1<f64>) {
            self.0.error_scales()
        }
        fn stop_in_substep(
            &self,
            before: &GpPoint<1, 1, u32>,
            after: &mut GpPoint<1, 1, u32>,
        ) -> Option<f64> {
            if after.sigma[0] < self.1 {
                return None;
            }
            let f = (self.1 - before.sigma[0]) / (after.sigma[0] - before.sigma[0]);
            after.sigma[0] = self.1;
            after.kappa = before.kappa + (after.kappa - before.kappa) * f;
            Some(f)
        }
    }

    #[test]
    fn a_stop_inside_a_substep_reports_the_reached_fraction() {
        // Loading from σ = 0.1: σ = 0.1 + E·H/(E+H)·ε = 0.1 + 20·ε reaches 0.2 at ε = 0.005.
        let m = Stopper(Toy { e: 100.0, h: 25.0 }, 0.2);
        let start = GpPoint {
            sigma: Vector1::new(0.1),
            kappa: Vector1::new(0.0),
            memory: 0_u32,
        };
        let opts = SubstepOptions::default();
        let res = integrate(&m, &start, &Vector1::new(0.01), Branch::Loading, &opts).expect("stops");
        assert!((res.reached - 0.5).abs() < 1e-12, "reached {}", res.reached);
        assert_eq!(res.point.sigma[0], 0.2);
        // κ = ε^p = 0.8·(ε − 0) on the plastic branch: 0.004 at the stop.
        assert!(
            (res.point.kappa[0] - 0.004).abs() < 1e-14,
            "{}",
            res.point.kappa[0]
        );
        assert_eq!(
            res.point.memory,
            res.substeps - 1,
            "after_accept skipped at the stop"
        );
        let full = integrate(&m.0, &start, &Vector1::new(0.01), Branch::Loading, &opts).expect("full");
        assert_eq!((full.reached, full.rejected), (1.0, 0));
    }

    #[test]
    fn guard_bounds_the_denominator() {
        let dd_e = Matrix1::new(100.0);
        let data = PlasticData {
            n: Vector1::new(1.0),
            n_g: Vector1::new(1.0),
            h: -99.0,
        };
        assert_eq!(guarded_denominator(&dd_e, &data), Some(5.0));
        let (d, kind) = elastoplastic_matrix(&dd_e, &data);
        assert_eq!(kind, TangentKind::Continuum);
        assert!((d[(0, 0)] - (100.0 - 100.0 * 100.0 / 5.0)).abs() < 1e-9);
        let elastic = PlasticData {
            h: f64::INFINITY,
            ..data
        };
        assert_eq!(elastoplastic_matrix(&dd_e, &elastic).1, TangentKind::Elastic);
    }

    #[test]
    fn options_validate_and_deserialize_with_defaults() {
        let o: SubstepOptions = serde_json::from_str(r#"{"stol": 1e-5}"#).expect("parses");
        assert_eq!(o.stol, 1e-5);
        assert_eq!(o.dt_min, 1e-6);
        assert!(o.validate("").is_ok());
        let bad = SubstepOptions { stol: 0.0, ..o };
        assert_eq!(
            bad.validate("integration.").unwrap_err().field,
            "integration.stol"
        );
        assert!(serde_json::from_str::<SubstepOptions>(r#"{"stl": 1e-5}"#).is_err());
        let alias: SubstepOptions = serde_json::from_str(r#"{"nmax": 7}"#).expect("alias");
        assert_eq!(alias.max_substeps, 7);
    }

    /// A 3-component model (the interface dimension): D^e = E·I, n = n_g = σ/|σ| (radial),
    /// H = h·(1 + |σ|) (nonlinear hardening), elastic unloading. Checks the generic N, the
    /// error control against a fine reference, and the NMAX failure.
    struct Radial3 {
        e: f64,
        h: f64,
    }

    impl GpModelFunctions<3, 1> for Radial3 {
        type Memory = ();
        fn elastic_matrix(&self, _p: &GpPoint<3, 1, ()>) -> nalgebra::Matrix3<f64> {
            nalgebra::Matrix3::identity() * self.e
        }
        fn plastic_data(
            &self,
            p: &GpPoint<3, 1, ()>,
            branch: Branch,
            d: &nalgebra::Vector3<f64>,
        ) -> Result<PlasticData<3>, MaterialError> {
            let norm = p.sigma.norm();
            let dir = if norm > 0.0 { p.sigma / norm } else { d.normalize() };
            let h = if branch == Branch::Loading {
                self.h * (1.0 + norm)
            } else {
                f64::INFINITY
            };
            Ok(PlasticData { n: dir, n_g: dir, h })
        }
        fn kappa_increment(&self, _p: &GpPoint<3, 1, ()>, s: &StageIncrement<'_, 3>) -> Vector1<f64> {
            Vector1::new(s.d_lambda.abs())
        }
        fn after_accept(&self, _p: &mut GpPoint<3, 1, ()>, b: Branch) -> Result<Branch, MaterialError> {
            Ok(b)
        }
        fn error_scales(&self) -> (f64, Vector1<f64>) {
            (1.0e-3, Vector1::new(1.0e-3))
        }
    }

    #[test]
    fn generic_dimension_three_converges_and_fails_cleanly() {
        let m = Radial3 { e: 100.0, h: 10.0 };
        let start = GpPoint {
            sigma: nalgebra::Vector3::new(0.1, 0.0, 0.0),
            kappa: Vector1::new(0.0),
            memory: (),
        };
        let d_eps = nalgebra::Vector3::new(0.02, 0.01, 0.0);
        let fine = SubstepOptions {
            stol: 1e-9,
            max_substeps: 1_000_000,
            ..SubstepOptions::default()
        };
        let reference = integrate(&m, &start, &d_eps, Branch::Elastic, &fine).expect("fine");
        let coarse =
            integrate(&m, &start, &d_eps, Branch::Elastic, &SubstepOptions::default()).expect("default");
        let err = (coarse.point.sigma - reference.point.sigma).norm() / reference.point.sigma.norm();
        assert!(err < 2e-4, "relative error {err}");
        assert!(reference.substeps > coarse.substeps && coarse.substeps > 1);
        assert_eq!(coarse.kind, TangentKind::Continuum);
        let starved = SubstepOptions {
            max_substeps: 2,
            ..SubstepOptions::default()
        };
        let e = integrate(&m, &start, &d_eps, Branch::Elastic, &starved).unwrap_err();
        assert!(e.reason.contains("NMAX"), "{}", e.reason);
        let nan = integrate(
            &m,
            &start,
            &nalgebra::Vector3::new(f64::NAN, 0.0, 0.0),
            Branch::Elastic,
            &fine,
        );
        assert!(nan.is_err());
    }

    /// A reversal inside the step: loading then unloading along the same axis in one step is
    /// impossible (the increment is straight), but a radial model started at σ = −0.05 e1 with
    /// Δε = +0.1 e1 passes through σ = 0, where n turns over: the substep containing the
    /// change is rejected and retried up to the estimated change point.
    #[test]
    fn branch_change_inside_a_step_is_located() {
        let m = Radial3 { e: 100.0, h: 10.0 };
        let start = GpPoint {
            sigma: nalgebra::Vector3::new(-0.05, 0.0, 0.0),
            kappa: Vector1::new(0.0),
            memory: (),
        };
        let d_eps = nalgebra::Vector3::new(0.1, 0.0, 0.0);
        let res =
            integrate(&m, &start, &d_eps, Branch::Loading, &SubstepOptions::default()).expect("integrates");
        assert!(res.rejected >= 1, "the flip was detected");
        assert_eq!(res.last_branch, Branch::Loading);
        // Elastic unloading to σ = 0 takes 0.0005 of strain; the rest is plastic loading with
        // dσ/dε = E·H/(E+H) and H = h(1+σ): σ stays well below the elastic value E·Δε.
        let s = res.point.sigma[0];
        assert!(s > 0.0 && s < 100.0 * 0.0995 * 0.5, "σ = {s}");
        assert!(res.point.sigma[1].abs() < 1e-12);
    }
}
