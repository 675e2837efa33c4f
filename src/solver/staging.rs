//! Stages: placing blocks, holding the nodes not yet placed, ending a stage, and the state a
//! checkpoint saves and restores between (or within) stages.

use super::error::SolveError;
use super::integrator::newmark::GroundMotion;
use super::integrator::{Newmark, NewmarkParameters, QuasiStatic, Rayleigh, TimeIntegrator};
use super::problem::Problem;
use super::solid::Vector24;
use super::state::{ProblemState, StageProgress};
use super::step_control::StepControl;
use crate::scene::dynamic::Anchors;
use crate::scene::schema::{LineSearch, PlacedNodes, Predictor};

impl Problem<'_> {
    /// Starts stage `k` of the scene: places its blocks (strain-free: their states start from
    /// the initial state and their strains count from the current displacement), fixes, at
    /// their current displacement, the nodes that no placed element touches yet, and runs the
    /// stage's modal analysis, if any ([`super::modal`]). Collective.
    pub fn begin_stage(&mut self, k: usize) -> Result<(), SolveError> {
        self.stage = k;
        self.f_ext_kept = None;
        for (i, &n) in self.model.disc.owned_nodes.iter().enumerate() {
            self.node_was_active[i] = self.model.node_active[n as usize];
        }
        self.model.place(&self.scene.stages[k].activate)?;
        self.u_stage_start = self.model.u.read(|s| s.to_vec())?;
        self.fix_for_stage()?;
        self.modes = match self.scene.stages[k].modal {
            Some(request) => Some(self.modal_analysis(request)?),
            None => None,
        };
        self.integrator = self.integrator_for_stage()?;
        self.start_states = match self.scene.stages[k].dynamic {
            Some(_) => Some(self.model.encode_states()?),
            None => None,
        };
        Ok(())
    }

    /// The time integrator of the current stage: quasi-static, or Newmark at rest at the
    /// committed state with the mass (and K₀ for Rayleigh damping) built now, only for a
    /// dynamic stage. Collective.
    fn integrator_for_stage(&mut self) -> Result<Box<dyn TimeIntegrator>, SolveError> {
        let scene = self.scene;
        let Some(d) = &scene.stages[self.stage].dynamic else {
            return Ok(match scene.file.solver.predictor {
                Predictor::Extrapolate => Box::new(QuasiStatic::extrapolating()),
                Predictor::None => Box::new(QuasiStatic::default()),
            });
        };
        let mass = self.model.assemble_mass(d.lumped)?;
        let damping = match d.damping {
            Some(r) => {
                let [f1, f2] = self.anchor_frequencies(r.anchors)?;
                Rayleigh::from_frequencies(r.ratio, f1, f2)
            }
            None => Rayleigh::default(),
        };
        let k0 = match damping.stiffness != 0.0 {
            true => Some(self.model.initial_stiffness()?),
            false => None,
        };
        let params = match d.alpha != 0.0 {
            true => NewmarkParameters::hht(d.alpha),
            false => NewmarkParameters {
                beta: d.newmark.beta,
                gamma: d.newmark.gamma,
                alpha: 0.0,
            },
        };
        let stage = d.clone();
        let ground: GroundMotion = Box::new(move |t| stage.ground_acceleration(t));
        let order = self.model.disc.canonical_dofs();
        let u = &self.model.u_committed;
        let newmark = Newmark::new(params, damping, (mass, k0), ground, u, &order)?;
        Ok(match d.predictor {
            Predictor::Extrapolate => Box::new(newmark.extrapolating()),
            Predictor::None => Box::new(newmark),
        })
    }

    /// The two frequencies (Hz) of Rayleigh damping: given, or those of two modes of the
    /// stage's modal analysis (which the scene's validation makes run for such a stage).
    fn anchor_frequencies(&self, anchors: Anchors) -> Result<[f64; 2], SolveError> {
        match anchors {
            Anchors::Frequencies(f) => Ok(f),
            Anchors::Modes(m) => {
                let f = |i: u32| {
                    self.modes
                        .as_ref()
                        .and_then(|modes| modes.frequencies_hz.get(i as usize - 1).copied())
                };
                match (f(m[0]), f(m[1])) {
                    (Some(f1), Some(f2)) if f2 > f1 => Ok([f1, f2]),
                    _ => Err(SolveError::Collective(format!(
                        "Rayleigh damping on modes {m:?}: no such pair of distinct modal frequencies"
                    ))),
                }
            }
        }
    }

    /// Continues the stage in progress of a step checkpoint, once the problem's state is
    /// restored from it (the checkpoint reader in `io` calls this): the fixed DOFs and their
    /// start values from the stored start of the stage, and a fresh preconditioner, as the
    /// uninterrupted run has after writing that checkpoint. Collective.
    pub fn resume_stage(&mut self, progress: &StageProgress) -> Result<(), SolveError> {
        self.node_was_active.clone_from(&progress.node_was_active);
        self.u_stage_start.clone_from(&progress.u_stage_start);
        self.fix_for_stage()?;
        match &progress.start_states {
            Some(start) => self.at_start_states(start, Self::stage_operators)?,
            // a checkpoint without the stage's start states: the modes and K₀ of the restored
            // state, which differ from the start state's for a softened model
            None => self.stage_operators()?,
        }
        if let Some(rates) = &progress.rates {
            self.integrator.restore_rates(&self.model.u_committed, rates)?;
        }
        Ok(())
    }

    /// The modes (when the stage asks for them) and the time integrator of the current stage,
    /// at the model's present states. Collective.
    fn stage_operators(&mut self) -> Result<(), SolveError> {
        self.modes = match self.scene.stages[self.stage].modal {
            Some(request) => Some(self.modal_analysis(request)?),
            None => None,
        };
        self.integrator = self.integrator_for_stage()?;
        Ok(())
    }

    /// Runs `build` with the point states `start` (evaluated elements, encoded) in place of the
    /// committed ones, which are put back afterwards; keeps `start` (owned elements) for the
    /// next step checkpoints. Collective.
    fn at_start_states(
        &mut self,
        start: &[Vec<u8>],
        build: fn(&mut Self) -> Result<(), SolveError>,
    ) -> Result<(), SolveError> {
        let committed = self.model.blocks.clone();
        let decoded = crate::parallel::any_error(self.comm, self.model.decode_states(start))
            .map_err(|m| SolveError::Collective(format!("the stage's start states: {m}")));
        let built = decoded.and_then(|()| {
            self.start_states = Some(self.model.encode_states()?);
            build(self)
        });
        self.model.blocks = committed;
        built
    }

    /// A fresh preconditioner and predictor (after a step checkpoint: the steps that follow do
    /// not depend on the factors or the rate of the steps before it, so a restart from it
    /// repeats them exactly).
    /// Collective.
    pub fn fresh_preconditioner(&mut self) -> Result<(), SolveError> {
        self.integrator.forget();
        self.kept_jacobian_dt = None;
        self.snes
            .as_mut()
            .expect("the nonlinear solver is in place between steps")
            .reset()?;
        Ok(())
    }

    /// The fixed DOFs of the current stage ([`super::constraints::Constraints::for_stage`]),
    /// then a fresh preconditioner: the stage's solves do not depend on earlier stages, so a
    /// restart from the checkpoint of the previous stage repeats them exactly. Collective.
    fn fix_for_stage(&mut self) -> Result<(), SolveError> {
        self.constraints
            .for_stage(&self.model.disc, &self.model.node_active, &self.u_stage_start);
        let dynamic = &self.scene.stages[self.stage].dynamic;
        let (line_search, choice) = match dynamic {
            Some(d) => (d.line_search, d.linear_solver),
            None => (
                self.scene.file.solver.line_search,
                self.scene.file.solver.linear_solver,
            ),
        };
        let method = Self::linear_method(self.scene, &self.model, choice);
        // a linear scene's time steps keep one Jacobian: complete factors, made once
        let kept = self.kept_jacobian();
        let snes = self
            .snes
            .as_mut()
            .expect("the nonlinear solver is in place between steps");
        snes.set_time_stepping(dynamic.is_some() && !kept);
        snes.set_kept_jacobian(kept);
        snes.set_linear_method(method);
        snes.set_line_search(match line_search {
            LineSearch::Secant => crate::linalg::petsc::LineSearch::Secant,
            LineSearch::FullStepFirst => crate::linalg::petsc::LineSearch::FullStepFirst,
            LineSearch::ResidualSecant => crate::linalg::petsc::LineSearch::ResidualSecant,
        });
        self.fresh_preconditioner()
    }

    /// Ends the current stage: its loads become the starting loads of the next one, and the
    /// nodes it placed get the zero of their reported displacement: a static stage's current
    /// displacement (a new lift's surface starts level; settlement counts from its
    /// placement), a dynamic stage's displacement at its start, so that the motion of the
    /// quake is reported on the blocks it placed too.
    pub fn end_stage(&mut self) -> Result<(), SolveError> {
        self.f_ext_kept = None;
        self.loads
            .end_stage(&self.model, &self.scene.stages[self.stage].terms)?;
        let zero: Vec<f64> = match self.scene.stages[self.stage].dynamic {
            Some(_) => self.u_stage_start.clone(),
            None => self.model.u.read(|s| s.to_vec())?,
        };
        let staged = !self.scene.file.stages.is_empty();
        let reset = staged && self.scene.file.output.placed_nodes == PlacedNodes::EndOfStage;
        for (i, &n) in self.model.disc.owned_nodes.iter().enumerate() {
            if reset && self.model.node_active[n as usize] && !self.node_was_active[i] {
                self.node_offset[i] = [zero[3 * i], zero[3 * i + 1], zero[3 * i + 2]];
            }
        }
        Ok(())
    }

    /// The state a checkpoint stores, in this rank's owned order: with `within: None` at the
    /// end of the current stage (after [`Problem::end_stage`]), everything
    /// [`Problem::begin_stage`] of the next stage and the solve need; with `Some(path)` after a
    /// converged step inside the stage, also what [`Problem::resume_stage`] needs to continue
    /// the stage from `path`.
    pub fn save_state(&self, within: Option<StepControl>) -> Result<ProblemState, SolveError> {
        let model = &self.model;
        let rates = match within {
            Some(_) => self.integrator.rates()?,
            None => None,
        };
        let in_stage = within.map(|path| StageProgress {
            path,
            u_stage_start: self.u_stage_start.clone(),
            node_was_active: self.node_was_active.clone(),
            rates,
            start_states: self.start_states.clone(),
        });
        Ok(ProblemState {
            stages_done: if within.is_some() {
                self.stage
            } else {
                self.stage + 1
            },
            in_stage,
            active_block: model.active_block.clone(),
            node_active: model.node_active.clone(),
            u: model.u_committed.read(|s| s.to_vec())?,
            f_prev: self.loads.f_prev.read(|s| s.to_vec())?,
            node_offset: self.node_offset.clone(),
            elem_ref: model
                .elem_ref
                .iter()
                .zip(&model.disc.element_owned)
                .filter(|(_, &owned)| owned)
                .map(|(v, _)| std::array::from_fn(|k| v[k]))
                .collect(),
            element_states: model.encode_states()?,
        })
    }

    /// Restores a state saved by [`Problem::save_state`] (possibly under another partition:
    /// the caller maps it to this rank's owned nodes and evaluated elements,
    /// `Discretization::elements`). The next call is [`Problem::begin_stage`] of stage
    /// `state.stages_done`, or [`Problem::resume_stage`] for a state saved within that stage.
    /// Local; fails on wrong lengths or states that do not decode for the block's model
    /// (naming the element).
    pub fn restore_state(&mut self, state: &ProblemState) -> Result<(), String> {
        self.check_lengths(state)?;
        let first = usize::from(state.in_stage.is_none());
        if state.stages_done < first || state.stages_done > self.scene.stages.len() {
            return Err(format!(
                "{} completed stage(s), the scene has {}",
                state.stages_done,
                self.scene.stages.len()
            ));
        }
        self.model.decode_states(&state.element_states)?;
        self.stage = state.stages_done.saturating_sub(first);
        self.f_ext_kept = None;
        let model = &mut self.model;
        model.active_block.clone_from(&state.active_block);
        model.node_active.clone_from(&state.node_active);
        self.node_offset.clone_from(&state.node_offset);
        model.elem_ref = state
            .elem_ref
            .iter()
            .map(|r| Vector24::from_column_slice(r))
            .collect();
        let petsc = |e: crate::linalg::petsc::PetscError| e.to_string();
        model.u.write(|s| s.copy_from_slice(&state.u)).map_err(petsc)?;
        model.u_committed.copy_from(&model.u).map_err(petsc)?;
        self.loads
            .f_prev
            .write(|s| s.copy_from_slice(&state.f_prev))
            .map_err(petsc)?;
        Ok(())
    }

    /// Refuses a state whose tables do not fit this problem.
    fn check_lengths(&self, state: &ProblemState) -> Result<(), String> {
        let model = &self.model;
        let (nn, ne) = (model.disc.owned_nodes.len(), model.disc.elements.len());
        let lens = [
            (
                "active blocks",
                state.active_block.len(),
                model.active_block.len(),
            ),
            ("node flags", state.node_active.len(), model.node_active.len()),
            ("displacements", state.u.len(), 3 * nn),
            ("previous loads", state.f_prev.len(), 3 * nn),
            ("node offsets", state.node_offset.len(), nn),
            ("element references", state.elem_ref.len(), ne),
            ("element states", state.element_states.len(), ne),
        ];
        if let Some((what, got, want)) = lens.iter().find(|(_, got, want)| got != want) {
            return Err(format!("{what}: {got} values, this problem has {want}"));
        }
        if let Some(p) = &state.in_stage {
            let rates_fit = p
                .rates
                .as_ref()
                .is_none_or(|r| r.velocity.len() == 3 * nn && r.acceleration.len() == 3 * nn);
            if p.u_stage_start.len() != 3 * nn || p.node_was_active.len() != nn || !rates_fit {
                return Err("the stage's start values do not fit this problem".into());
            }
        }
        Ok(())
    }
}
