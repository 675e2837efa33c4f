//! The state of a problem that a checkpoint carries, in this rank's owned order; the I/O is
//! by the checkpoint reader and writer of the `io` room.

use super::integrator::Rates;
use super::step_control::StepControl;

/// A stage in progress in a step checkpoint: its step control and what
/// [`super::Problem::begin_stage`] computed at the stage's start (rank-local, owned order).
#[derive(Debug, Clone, PartialEq)]
pub struct StageProgress {
    /// The stepping reached.
    pub path: StepControl,
    /// Displacement of the owned DOFs at the start of the stage.
    pub u_stage_start: Vec<f64>,
    /// Per owned node: whether it was placed before the stage.
    pub node_was_active: Vec<bool>,
    /// Velocity and acceleration of a dynamic stage (`None` in a static stage).
    pub rates: Option<Rates>,
    /// Encoded point states at the start of a dynamic stage, from which K₀ of Rayleigh damping
    /// and the stage's modes are rebuilt (owned elements when saved, evaluated ones when read
    /// back; `None` in a static stage and in checkpoints written before they were stored).
    pub start_states: Option<Vec<Vec<u8>>>,
}

/// The state of the problem on one rank at the end of a stage or step, in this rank's owned
/// order (nodes of `Discretization::owned_nodes`; elements of `owned_elements` when saved, of
/// `Discretization::elements`, the evaluated ones, when read back).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ProblemState {
    /// Number of completed stages (the next stage, or the one in progress, has this index).
    pub stages_done: usize,
    /// For a step checkpoint: the stage in progress (index `stages_done`) and its stepping.
    pub in_stage: Option<StageProgress>,
    /// Whether each block is placed (all blocks).
    pub active_block: Vec<bool>,
    /// Whether each node belongs to a placed element (all nodes).
    pub node_active: Vec<bool>,
    /// Displacement, 3 values per owned node (m).
    pub u: Vec<f64>,
    /// External force of the last stage, 3 values per owned node (N).
    pub f_prev: Vec<f64>,
    /// Zero of the reported displacement of each owned node (m).
    pub node_offset: Vec<[f64; 3]>,
    /// Displacement of each owned element's nodes at its placement (m).
    pub elem_ref: Vec<[f64; 24]>,
    /// Encoded committed point states of each owned element ([`super::state_codec`]).
    pub element_states: Vec<Vec<u8>>,
}
