//! Failures of a nonlinear step and which of them a smaller step may cure.

/// Failures of a step (static or dynamic).
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// PETSc failed.
    #[error(transparent)]
    Petsc(#[from] crate::linalg::petsc::PetscError),
    /// A material update failed (element id and reason).
    #[error("element {element}: {reason}")]
    Material {
        /// Input id of the element.
        element: u64,
        /// Why.
        reason: String,
    },
    /// An element has a non-positive Jacobian.
    #[error("element {element}: non-positive Jacobian")]
    Geometry {
        /// Input id of the element.
        element: u64,
    },
    /// The linear solver diverged.
    #[error(
        "linear solver diverged: {} (PETSc reason {reason}) after {iterations} iterations",
        ksp_reason_name(*reason)
    )]
    Linear {
        /// PETSc's converged reason.
        reason: i32,
        /// Iterations done.
        iterations: u32,
    },
    /// Newton did not converge.
    #[error(
        "Newton did not converge in {iterations} iterations (relative residual {residual:.3e}); \
         {worst}{hint}"
    )]
    Newton {
        /// Iterations done.
        iterations: u32,
        /// Last relative residual.
        residual: f64,
        /// Where the out-of-balance force of the last iterate is largest.
        worst: String,
        /// Empty, or why the residual may not fall further (the GP integration noise, spec §8.2).
        hint: String,
    },
    /// The line search found no step that reduces the residual.
    #[error(
        "line search failed after {iterations} Newton iterations (relative residual \
         {residual:.3e}); {worst}"
    )]
    LineSearch {
        /// Iterations done.
        iterations: u32,
        /// Last relative residual.
        residual: f64,
        /// Where the out-of-balance force of the last iterate is largest.
        worst: String,
    },
    /// A material update failed on some rank (message of the lowest failing rank).
    #[error("{0}")]
    Collective(String),
    /// A material update failed on some rank at the step's initial guess, before any Newton
    /// iteration (message of the lowest failing rank): a predicted start is then dropped for
    /// the last converged state ([`crate::solver::Problem::solve_step`]).
    #[error("{0}")]
    AtStart(String),
    /// A load step could not be completed even after cutting it back.
    #[error(
        "{} from {} to {} ({}) failed after {cutbacks} cut-back(s); the last converged state is {}: \
         {source}",
        kind.noun(), kind.at(*from), kind.at(*to), kind.span(*to - *from), kind.at(*from)
    )]
    Step {
        /// Load or time steps (for the message).
        kind: super::step_control::StepKind,
        /// Last converged load factor.
        from: f64,
        /// Load factor of the failed attempt.
        to: f64,
        /// Cut-backs tried.
        cutbacks: u32,
        /// Why the last attempt failed.
        source: Box<SolveError>,
    },
}

impl SolveError {
    /// Whether a smaller step may succeed (material failure, Newton or linear divergence).
    pub fn recoverable(&self) -> bool {
        matches!(
            self,
            SolveError::Material { .. }
                | SolveError::Collective(_)
                | SolveError::AtStart(_)
                | SolveError::Newton { .. }
                | SolveError::LineSearch { .. }
                | SolveError::Linear { .. }
        )
    }
}

/// The name of a value of PETSc's `KSPConvergedReason` (PETSc 3.18), as `-ksp_converged_reason`
/// prints it, e.g. `KSP_DIVERGED_ITS` for −3.
pub fn ksp_reason_name(reason: i32) -> &'static str {
    match reason {
        -2 => "KSP_DIVERGED_NULL",
        -3 => "KSP_DIVERGED_ITS: the iteration limit",
        -4 => "KSP_DIVERGED_DTOL: the residual grew",
        -5 => "KSP_DIVERGED_BREAKDOWN",
        -6 => "KSP_DIVERGED_BREAKDOWN_BICG",
        -7 => "KSP_DIVERGED_NONSYMMETRIC",
        -8 => "KSP_DIVERGED_INDEFINITE_PC",
        -9 => "KSP_DIVERGED_NANORINF",
        -10 => "KSP_DIVERGED_INDEFINITE_MAT",
        -11 => "KSP_DIVERGED_PC_FAILED: the preconditioner failed",
        0 => "KSP_CONVERGED_ITERATING",
        r if r > 0 => "KSP_CONVERGED",
        _ => "an unknown reason",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_failure_names_petscs_reason_and_is_recoverable() {
        let e = SolveError::Linear {
            reason: -3,
            iterations: 30,
        };
        assert_eq!(
            e.to_string(),
            "linear solver diverged: KSP_DIVERGED_ITS: the iteration limit (PETSc reason -3) after 30 iterations"
        );
        assert!(e.recoverable());
        assert!(ksp_reason_name(-11).starts_with("KSP_DIVERGED_PC_FAILED"));
        assert_eq!(ksp_reason_name(-99), "an unknown reason");
    }
}
