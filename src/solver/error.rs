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
    #[error("linear solver diverged (PETSc reason {reason}) after {iterations} iterations")]
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
                | SolveError::Newton { .. }
                | SolveError::LineSearch { .. }
                | SolveError::Linear { .. }
        )
    }
}
