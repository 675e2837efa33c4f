//! The problem on this rank: the model, its constraints and loads, the nonlinear solver and
//! the time integrator of the current stage, composed; a stage advances by the step control
//! ([`StepControl::advance`]) through [`Problem::solve_step`].

use super::constraints::Constraints;
use super::discretization::Discretization;
use super::error::SolveError;
use super::integrator::{QuasiStatic, TimeIntegrator};
use super::loads::{add_placement_force, Loads};
use super::model::Model;
use super::newton::{self, StepTarget};
use super::report::{InterfaceCounts, SolveReport};
use super::step_control::{StepControl, StepKind};
use crate::linalg::petsc::{CanonicalSettings, LinearMethod, Petsc, Snes, Vector};
use crate::scene::schema::LinearSolver;
use crate::scene::Scene;
use mpi::topology::SimpleCommunicator;
use mpi::traits::Communicator;
use partition::Cells;

/// The rank-local problem of a staged run.
pub struct Problem<'a> {
    pub(super) scene: &'a Scene,
    pub(super) comm: &'a SimpleCommunicator,
    pub(super) model: Model<'a>,
    pub(super) constraints: Constraints,
    pub(super) loads: Loads,
    /// The nonlinear solver (taken out while it runs a step).
    pub(super) snes: Option<Snes>,
    /// The time integrator of the current stage.
    pub(super) integrator: Box<dyn TimeIntegrator>,
    /// Index of the current stage in `scene.stages`.
    pub(super) stage: usize,
    /// In a dynamic stage of a linear scene: the Δt at which the kept Jacobian was built
    /// (`None`: not yet built since the last reset of the solver).
    pub(super) kept_jacobian_dt: Option<f64>,
    /// The external and placement forces of the current stage at the load factor of the
    /// last step (its bits), kept for the next step at the same factor: every step of a
    /// dynamic stage (cleared when a stage begins or a state is restored).
    pub(super) f_ext_kept: Option<(u64, Vector)>,
    /// Per owned node: displacement at the end of the stage that placed it; reported
    /// displacements count from there (the surface of a new lift starts at zero).
    pub(super) node_offset: Vec<[f64; 3]>,
    /// Per owned node: whether it is part of a placed element already at the start of the stage.
    pub(super) node_was_active: Vec<bool>,
    /// Displacement of the owned DOFs at the start of the stage (for step checkpoints: the
    /// fixed DOFs' start values are recomputed from it on a restart within the stage).
    pub(super) u_stage_start: Vec<f64>,
    /// The modes of the current stage's start state, when the stage asks for a modal analysis.
    pub(super) modes: Option<super::modal::Modes>,
    /// Encoded point states of the owned elements at the start of a dynamic stage: K₀ of
    /// Rayleigh damping and the stage's modes are those of this state, so a restart from a step
    /// checkpoint rebuilds them from it (`None` in a static stage).
    pub(super) start_states: Option<Vec<Vec<u8>>>,
}

impl<'a> Problem<'a> {
    /// Sets up the rank-local problem for a given element partition on the ranks of `comm`.
    /// The scene's and the command line's PETSc options are applied here, so a bad one is an
    /// input error.
    pub fn new(
        petsc: &Petsc,
        comm: &'a SimpleCommunicator,
        scene: &'a Scene,
        cells: Cells,
        disc: Discretization,
    ) -> Result<Self, SolveError> {
        let constraints = Constraints::new(&disc, &scene.fixed);
        let n_owned_nodes = disc.owned_nodes.len();
        let model = Model::new(petsc, comm, scene, &cells, disc)?;
        let snes = Self::nonlinear_solver(petsc, scene, &model)?;
        let loads = Loads::new(&model.u)?;
        Ok(Problem {
            scene,
            comm,
            model,
            constraints,
            loads,
            snes: Some(snes),
            integrator: Box::new(QuasiStatic::default()),
            stage: 0,
            kept_jacobian_dt: None,
            f_ext_kept: None,
            node_offset: vec![[0.0; 3]; n_owned_nodes],
            node_was_active: vec![false; n_owned_nodes],
            u_stage_start: Vec::new(),
            start_states: None,
            modes: None,
        })
    }

    /// SNES with the scene's solver settings: CG only when every tangent is symmetric (the
    /// non-associated GP models are not), the static stages' linear solver (a dynamic stage
    /// sets its own, [`Problem::linear_method`]).
    fn nonlinear_solver(petsc: &Petsc, scene: &Scene, model: &Model) -> Result<Snes, SolveError> {
        let method = Self::linear_method(scene, model, scene.file.solver.linear_solver);
        Ok(Snes::new(
            petsc,
            scene.file.solver.newton_max_iterations,
            scene.file.solver.rtol,
            scene.file.solver.max_iterations,
            model.symmetric_tangent(),
            method,
        )?)
    }

    /// The linear solver `choice` of the scene, with what it needs of the model.
    pub(super) fn linear_method(scene: &Scene, model: &Model, choice: LinearSolver) -> LinearMethod {
        match choice {
            LinearSolver::Iterative => LinearMethod::Krylov,
            LinearSolver::ReducedAmg => LinearMethod::ReducedAmg {
                structure: model.structure_dofs(),
            },
            LinearSolver::CanonicalLu => LinearMethod::Canonical(CanonicalSettings {
                dofs: model.disc.canonical_dofs(),
                reuse_factorization: scene.file.solver.reuse_factorization,
            }),
            LinearSolver::DistributedLu => LinearMethod::DistributedLu {
                reuse_factorization: scene.file.solver.reuse_factorization,
            },
        }
    }

    /// The modes of the current stage's start state ([`super::modal`]), if it asked for them.
    pub fn modes(&self) -> Option<&super::modal::Modes> {
        self.modes.as_ref()
    }

    /// The rank-local indexing.
    pub fn discretization(&self) -> &Discretization {
        &self.model.disc
    }

    /// Seconds this rank has spent in its element loops so far ([`Model`]'s load-balance
    /// measure; rank-local, not collective).
    pub fn element_seconds(&self) -> f64 {
        self.model.element_seconds
    }

    /// Counts of open and slipping interface points in the committed state (collective).
    pub fn interface_counts(&self) -> InterfaceCounts {
        self.model.interface_counts()
    }

    /// One converged step of the current stage along `path` (the caller advances until
    /// [`StepControl::done`]): a failed step is cut back at most `max_cutbacks` times in a
    /// row and grown back after two successes. Collective.
    pub fn advance(
        &mut self,
        path: &mut StepControl,
        max_cutbacks: u32,
        report: &mut SolveReport,
    ) -> Result<(), SolveError> {
        let monitor = self.scene.file.solver.monitor && self.comm.rank() == 0;
        let kind = self.step_kind();
        path.advance(max_cutbacks, monitor, kind, report, |t0, t1, report| {
            self.solve_step(t0, t1, report)
        })
    }

    /// The motion of node `node` (mesh index) at the committed state of a dynamic stage, at its
    /// time `t` (s): `[t, u (3), a (3), a_g (3)]` with u relative to the base and to the stage's
    /// start and a the absolute acceleration, a_g the ground's (a row of
    /// [`SolveReport::crest`]). Zeros for a stage without rates. Collective.
    pub fn node_motion(&self, node: usize, t: f64) -> Result<[f64; 10], SolveError> {
        let mut row = [0.0; 10];
        let rates = self.integrator.rates()?;
        if let (Some(i), Some(r)) = (self.owned_index(node), &rates) {
            let u = self
                .model
                .u_committed
                .read(|s| [s[3 * i], s[3 * i + 1], s[3 * i + 2]])?;
            for c in 0..3 {
                row[1 + c] = u[c] - self.u_stage_start[3 * i + c];
                row[4 + c] = r.acceleration[3 * i + c] + r.ground[c];
                row[7 + c] = r.ground[c];
            }
        }
        // one rank holds the node: the sums add zeros to its values, exactly
        let mut out = [t; 10];
        for (o, v) in out.iter_mut().zip(row).skip(1) {
            *o = crate::parallel::sum_f64(self.comm, v);
        }
        Ok(out)
    }

    /// The displacement (m) of node `node` (mesh index) at the start of the current stage,
    /// relative to the base. Collective.
    pub fn node_stage_start(&self, node: usize) -> [f64; 3] {
        let local = self.owned_index(node).map_or([0.0; 3], |i| {
            std::array::from_fn(|c| self.u_stage_start[3 * i + c])
        });
        // one rank holds the node: the sums add zeros to its values, exactly
        local.map(|v| crate::parallel::sum_f64(self.comm, v))
    }

    /// The index among this rank's owned nodes of node `node` (mesh index), if it owns it.
    fn owned_index(&self, node: usize) -> Option<usize> {
        self.model
            .disc
            .owned_nodes
            .iter()
            .position(|&n| n as usize == node)
    }

    /// Whether the current stage steps in load (static) or in time (dynamic).
    fn step_kind(&self) -> StepKind {
        match self.scene.stages[self.stage].dynamic {
            Some(_) => StepKind::Time,
            None => StepKind::Load,
        }
    }

    /// Solves the step from the converged stage time `t0` to `t1` to equilibrium (loads and
    /// prescribed displacements at the integrator's load factor of `t1`) and commits the
    /// states. On failure the problem is back at its committed state. Collective.
    pub fn solve_step(&mut self, t0: f64, t1: f64, report: &mut SolveReport) -> Result<(), SolveError> {
        self.keep_jacobian_for(t1 - t0)?;
        self.integrator.begin_step(t0, t1);
        let lambda = self.integrator.load_factor(t1);
        let r = self.newton(lambda, self.step_kind().at(t1), report);
        if r.is_err() {
            self.model.revert()?;
            return r;
        }
        self.integrator.accept(&self.model.u)?;
        r
    }

    /// Newton on SNES for the step at load factor `lambda` ([`newton`]) from the integrator's
    /// predicted start; `at` names the step's end for the monitor. A predicted start that a
    /// material update cannot take (a GP interface closed beyond its void-ratio bound,
    /// [`crate::material::interface_gp`], or too many substeps), or whose residual is of the
    /// order of the forces themselves ([`newton::PREDICTION_REJECTED_AT`]), is dropped, and Newton starts
    /// again from the last converged state before the step is cut back
    /// ([`SolveReport::predictions_dropped`]). Whether the guess moved is one comparison and
    /// one reduction per step, none per iteration.
    fn newton(&mut self, lambda: f64, at: String, report: &mut SolveReport) -> Result<(), SolveError> {
        let mut guess = self.committed_copy()?;
        self.integrator.predict(&mut guess)?;
        let moved = guess.read(|g| self.model.u_committed.read(|u| g != u))??;
        let predicted = crate::parallel::any_true(self.comm, moved);
        match self.newton_from(lambda, at.clone(), (guess, predicted), report) {
            Err(SolveError::AtStart(m)) if predicted => {
                self.model.revert()?;
                report.predictions_dropped += 1;
                if self.scene.file.solver.monitor && self.comm.rank() == 0 {
                    eprintln!("predicted start of the step to {at} dropped: {m}");
                }
                let guess = self.committed_copy()?;
                self.newton_from(lambda, at, (guess, false), report)
            }
            r => r,
        }
    }

    /// In a dynamic stage of a linear scene, whose Jacobian K + shift_v·C + shift_a·M changes
    /// only with Δt: has it built again when `dt` is not the Δt of the kept one (a cut-back).
    fn keep_jacobian_for(&mut self, dt: f64) -> Result<(), SolveError> {
        if !self.kept_jacobian() {
            return Ok(());
        }
        match self.kept_jacobian_dt {
            Some(kept) if (kept - dt).abs() <= 1e-9 * dt.abs() => {}
            Some(_) => {
                self.snes
                    .as_mut()
                    .expect("the nonlinear solver is in place between steps")
                    .rebuild_jacobian()?;
                self.kept_jacobian_dt = Some(dt);
            }
            None => self.kept_jacobian_dt = Some(dt),
        }
        Ok(())
    }

    /// Whether the current stage keeps its Jacobian: a dynamic stage of a linear scene
    /// ([`super::model::Model::is_linear`]).
    pub(super) fn kept_jacobian(&self) -> bool {
        self.scene.stages[self.stage].dynamic.is_some() && self.model.is_linear()
    }

    /// The external and placement forces of the current stage at load factor `lambda`: those
    /// of the last step when it had the same factor (a stage's loads and placed blocks do not
    /// change within it), else assembled. Collective.
    pub(super) fn external_force(&mut self, lambda: f64) -> Result<Vector, SolveError> {
        let key = lambda.to_bits();
        if !matches!(&self.f_ext_kept, Some((k, _)) if *k == key) {
            let mut f = self.model.u.duplicate()?;
            let terms = &self.scene.stages[self.stage].terms;
            self.loads.external_force(&self.model, terms, lambda, &mut f)?;
            add_placement_force(&self.model, &mut f)?;
            self.f_ext_kept = Some((key, f));
        }
        let (_, kept) = self.f_ext_kept.as_ref().expect("kept just above");
        let mut f_ext = kept.duplicate()?;
        f_ext.copy_from(kept)?;
        Ok(f_ext)
    }

    /// A copy of the committed displacement (owned DOFs).
    fn committed_copy(&self) -> Result<Vector, SolveError> {
        let mut u = self.model.u_committed.duplicate()?;
        u.copy_from(&self.model.u_committed)?;
        Ok(u)
    }

    /// The Newton tolerance of the current stage: a dynamic stage's own `newton_tol`, else
    /// the scene's `solver.newton_tol`.
    fn newton_tol(&self) -> f64 {
        self.scene.stages[self.stage]
            .dynamic
            .as_ref()
            .and_then(|d| d.newton_tol)
            .unwrap_or(self.scene.file.solver.newton_tol)
    }

    /// Newton on SNES for the step at load factor `lambda` from the initial guess `guess`,
    /// `predicted` when it is the integrator's prediction.
    fn newton_from(
        &mut self,
        lambda: f64,
        at: String,
        (guess, predicted): (Vector, bool),
        report: &mut SolveReport,
    ) -> Result<(), SolveError> {
        let f_ext = self.external_force(lambda)?;
        let target = StepTarget {
            f_ext,
            targets: self.constraints.targets(self.model.disc.dof_lo, lambda),
            rows: self.constraints.rows(),
            at,
            predicted,
            tolerance: self.newton_tol(),
        };
        let mut snes = self
            .snes
            .take()
            .expect("the nonlinear solver is in place between steps");
        let solved = newton::solve(
            &mut self.model,
            &mut snes,
            self.integrator.as_ref(),
            (target, guess),
            report,
        );
        self.snes = Some(snes);
        solved
    }
}
