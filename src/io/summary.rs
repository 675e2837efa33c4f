//! The machine-readable run summary (JSON, written by rank 0), a phase timer and peak-memory
//! measurement.
//!
//! ```json
//! {
//!   "cfrd_version": "0.1.0", "scene": "dam_3d", "ranks": 2,
//!   "nodes": 1030301, "elements": 1000000, "dofs": 3090903,
//!   "phase_seconds": { "read": 1.2, "partition": 3.4, "setup": 0.8,
//!                      "assembly": 20.1, "solve": 55.0, "output": 2.2 },
//!   "total_seconds": 83.0,
//!   "ksp_iterations": 412, "newton_iterations": 37, "steps": 10,
//!   "peak_memory_bytes": 2147483648, "peak_memory_bytes_per_rank": [2147483648, 2013265920]
//! }
//! ```
//!
//! Phase times are wall-clock seconds, the maximum over ranks of each rank's accumulated time in
//! that phase. Peak memory is each rank's `VmHWM` (peak resident set size) from
//! `/proc/self/status`, in bytes; `peak_memory_bytes` is the maximum over ranks (0 where the
//! kernel does not provide it).

use std::path::Path;
use std::time::{Duration, Instant};

pub use crate::solver::StageSeconds;
use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, CommunicatorCollectives};
use serde::{Deserialize, Serialize};

use super::error::{write_atomic, IoError};

/// The phases timed in a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Reading the scene and the mesh.
    Read,
    /// Partitioning (METIS) and distributing the mesh.
    Partition,
    /// DOF numbering, matrix preallocation, material state allocation.
    Setup,
    /// Element loops: internal forces and tangent matrices.
    Assembly,
    /// Linear solves (KSP).
    Solve,
    /// Results and checkpoint output.
    Output,
}

impl Phase {
    /// All phases in reporting order.
    pub const ALL: [Phase; 6] = [
        Phase::Read,
        Phase::Partition,
        Phase::Setup,
        Phase::Assembly,
        Phase::Solve,
        Phase::Output,
    ];

    fn slot(self) -> usize {
        self as usize
    }
}

/// Wall-clock seconds per phase.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhaseSeconds {
    /// Reading the scene and the mesh.
    pub read: f64,
    /// Partitioning and distribution.
    pub partition: f64,
    /// Setup (DOFs, preallocation, states).
    pub setup: f64,
    /// Assembly of forces and tangents.
    pub assembly: f64,
    /// Linear solves.
    pub solve: f64,
    /// Output.
    pub output: f64,
}

impl PhaseSeconds {
    fn as_array(&self) -> [f64; 6] {
        [
            self.read,
            self.partition,
            self.setup,
            self.assembly,
            self.solve,
            self.output,
        ]
    }

    fn from_array(a: [f64; 6]) -> Self {
        PhaseSeconds {
            read: a[0],
            partition: a[1],
            setup: a[2],
            assembly: a[3],
            solve: a[4],
            output: a[5],
        }
    }

    /// The maximum over the ranks of each phase. Collective.
    pub fn max_over_ranks(&self, comm: &SimpleCommunicator) -> Self {
        let mine = self.as_array();
        let mut max = [0.0; 6];
        comm.all_reduce_into(&mine[..], &mut max[..], mpi::collective::SystemOperation::max());
        Self::from_array(max)
    }

    /// Sum of all phases.
    pub fn total(&self) -> f64 {
        self.as_array().iter().sum()
    }
}

/// Accumulates wall-clock time per phase; one phase runs at a time.
#[derive(Debug, Clone, Default)]
pub struct PhaseTimer {
    totals: [Duration; 6],
    running: Option<(Phase, Instant)>,
}

impl PhaseTimer {
    /// A timer with all phases at zero.
    pub fn new() -> Self {
        Self::default()
    }

    /// Starts timing `phase`, stopping the running phase first.
    pub fn start(&mut self, phase: Phase) {
        self.stop();
        self.running = Some((phase, Instant::now()));
    }

    /// Stops the running phase, if any, and adds its time.
    pub fn stop(&mut self) {
        if let Some((phase, since)) = self.running.take() {
            self.totals[phase.slot()] += since.elapsed();
        }
    }

    /// Runs `f` timed as `phase` and returns its result; the previously running phase resumes
    /// afterwards.
    pub fn time<R>(&mut self, phase: Phase, f: impl FnOnce() -> R) -> R {
        let previous = self.running.map(|(p, _)| p);
        self.start(phase);
        let out = f();
        self.stop();
        if let Some(p) = previous {
            self.start(p);
        }
        out
    }

    /// Adds a measured duration to `phase`.
    pub fn add(&mut self, phase: Phase, d: Duration) {
        self.totals[phase.slot()] += d;
    }

    /// Accumulated time of `phase` (including the running part if it is running).
    pub fn elapsed(&self, phase: Phase) -> Duration {
        let running = match self.running {
            Some((p, since)) if p == phase => since.elapsed(),
            _ => Duration::ZERO,
        };
        self.totals[phase.slot()] + running
    }

    /// This rank's seconds per phase.
    pub fn seconds(&self) -> PhaseSeconds {
        PhaseSeconds::from_array(Phase::ALL.map(|p| self.elapsed(p).as_secs_f64()))
    }
}

/// The run summary.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSummary {
    /// Version of cfrd that ran.
    pub cfrd_version: String,
    /// Scene name.
    pub scene: String,
    /// Number of MPI ranks.
    pub ranks: u32,
    /// Number of mesh nodes.
    pub nodes: u64,
    /// Number of volume elements.
    pub elements: u64,
    /// Number of equations (free DOFs).
    pub dofs: u64,
    /// Wall-clock seconds per phase (max over ranks).
    pub phase_seconds: PhaseSeconds,
    /// Total wall-clock seconds of the run.
    pub total_seconds: f64,
    /// Total linear-solver (KSP) iterations.
    pub ksp_iterations: u64,
    /// Total Newton iterations.
    pub newton_iterations: u64,
    /// Residual evaluations (material integrations of the whole model): the Newton iterations,
    /// step starts and line-search trial points.
    #[serde(default)]
    pub residual_evaluations: u64,
    /// Element loops (integrations of every placed element): a linear scene's time steps
    /// start from the forces kept at the committed state and integrate once per step.
    #[serde(default)]
    pub element_loops: u64,
    /// Number of load or time steps completed.
    pub steps: u64,
    /// Step cut-backs (failed steps retried with a smaller increment).
    #[serde(default)]
    pub cutbacks: u64,
    /// Predicted starts of steps dropped because a material update failed there; Newton then
    /// started from the last converged state (`solver.predictor: extrapolate`).
    #[serde(default)]
    pub predictions_dropped: u64,
    /// Newton iterations of each completed step.
    #[serde(default)]
    pub newton_per_step: Vec<u32>,
    /// Numeric factorizations of the direct solvers (`canonical_lu`, `distributed_lu`) or of
    /// the reduced multigrid's structure (`reduced_amg`).
    #[serde(default)]
    pub factorizations: u64,
    /// Set-ups of the reduced multigrid's multigrid (`reduced_amg`), kept across Jacobians.
    #[serde(default)]
    pub multigrid_builds: u64,
    /// Interface and joint points of placed elements at the end of the run.
    #[serde(default)]
    pub interface_points: u64,
    /// Of those, points that are open.
    #[serde(default)]
    pub interface_open: u64,
    /// Of those, points slipping (on the plastic branch in their last update).
    #[serde(default)]
    pub interface_slipping: u64,
    /// For a run restarted from a checkpoint (`--restart`): the stages completed before the
    /// restart (the run began with the next one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restarted_after_stage: Option<u64>,
    /// For a restart given `--accept-changed`: the input files that changed since the
    /// checkpoint and that the run went on with (`key: path`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub accepted_changed_inputs: Vec<String>,
    /// For a run ended early with `--stop-after-stage K`: K, the last stage run (the schedule
    /// is not finished; continue with `--restart <out>/checkpoint.h5`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stopped_after_stage: Option<u64>,
    /// Wall-clock seconds spent writing checkpoints (max over ranks).
    #[serde(default)]
    pub checkpoint_seconds: f64,
    /// Wall-clock seconds of each completed stage, from its start to its results written
    /// (checkpoint not included; rank 0's clock). A restarted run lists the stages of the runs
    /// before it too (they are carried in the checkpoint), so a run in parts has them all.
    #[serde(default)]
    pub stage_seconds: Vec<StageSeconds>,
    /// The modal analysis of the run, if a stage asked for one (spec seismic §4 items 4, 9).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modal: Option<ModalSummary>,
    /// Seconds each rank spent in its element loops (material updates and element matrices,
    /// without the waits of the collective assembly) in this run: the spread is the load
    /// imbalance of the assembly, which the partition balances by element counts.
    #[serde(default)]
    pub element_seconds_per_rank: Vec<f64>,
    /// The most matrix rows each rank's direct solver held at once in this run (of its
    /// factors, or of its overlapping Schwarz subdomains in a dynamic stage; the whole
    /// system, `dofs`, for the canonical solver's gathered copy); 0 with the Krylov solvers.
    #[serde(default)]
    pub solver_rows_held_per_rank: Vec<u64>,
    /// Peak resident memory (bytes), maximum over ranks.
    pub peak_memory_bytes: u64,
    /// Peak resident memory (bytes) of each rank.
    pub peak_memory_bytes_per_rank: Vec<u64>,
}

/// The natural frequencies of a modal analysis (K₀·φ = ω²·M·φ, spec seismic §4 items 4, 9);
/// the mode shapes are in `modes.h5`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModalSummary {
    /// The stage at whose start the modes were computed.
    pub stage: String,
    /// f = ω/(2π) (Hz), ascending.
    pub frequencies_hz: Vec<f64>,
    /// T = 1/f (s), descending.
    pub periods_s: Vec<f64>,
    /// Wall-clock seconds of the analysis (assembly of K₀ and M, eigensolve; max over ranks).
    pub seconds: f64,
}

impl RunSummary {
    /// A summary with the version filled in and the rank count of `comm`.
    pub fn new(comm: &SimpleCommunicator, scene: &str) -> Self {
        RunSummary {
            cfrd_version: env!("CARGO_PKG_VERSION").to_string(),
            scene: scene.to_string(),
            ranks: comm.size() as u32,
            ..Self::default()
        }
    }

    /// Fills `peak_memory_bytes` and `peak_memory_bytes_per_rank` from every rank's `VmHWM`.
    /// Collective.
    pub fn gather_peak_memory(&mut self, comm: &SimpleCommunicator) {
        let per_rank = gather_peak_memory(comm);
        self.peak_memory_bytes = per_rank.iter().copied().max().unwrap_or(0);
        self.peak_memory_bytes_per_rank = per_rank;
    }

    /// Fills `element_seconds_per_rank` from every rank's `seconds`. Collective.
    pub fn gather_element_seconds(&mut self, comm: &SimpleCommunicator, seconds: f64) {
        let mut all = vec![0.0f64; comm.size() as usize];
        comm.all_gather_into(&seconds, &mut all[..]);
        self.element_seconds_per_rank = all;
    }

    /// Fills `solver_rows_held_per_rank` from every rank's `rows`. Collective.
    pub fn gather_solver_rows(&mut self, comm: &SimpleCommunicator, rows: u64) {
        let mut all = vec![0u64; comm.size() as usize];
        comm.all_gather_into(&rows, &mut all[..]);
        self.solver_rows_held_per_rank = all;
    }

    /// Pretty JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }

    /// Writes the JSON to `path` through a temporary file renamed into place. Call on rank 0.
    pub fn write_json(&self, path: &Path) -> Result<(), IoError> {
        write_atomic(path, (self.to_json() + "\n").as_bytes())
    }
}

/// Parses the `VmHWM:` line (in kB) of a `/proc/<pid>/status` text into bytes.
pub fn parse_vm_hwm(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut words = line["VmHWM:".len()..].split_whitespace();
    let value: u64 = words.next()?.parse().ok()?;
    match words.next() {
        Some("kB") | None => Some(value * 1024),
        Some(_) => None,
    }
}

/// This process's peak resident set size in bytes (`VmHWM`), if the kernel reports it.
pub fn peak_memory_bytes() -> Option<u64> {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| parse_vm_hwm(&s))
}

/// Every rank's peak memory (bytes, 0 where unknown), in rank order, on every rank. Collective.
pub fn gather_peak_memory(comm: &SimpleCommunicator) -> Vec<u64> {
    let mine = peak_memory_bytes().unwrap_or(0);
    let mut all = vec![0u64; comm.size() as usize];
    comm.all_gather_into(&mine, &mut all[..]);
    all
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vm_hwm_is_parsed_in_bytes() {
        let status = "Name:\tcfrd\nVmPeak:\t  300000 kB\nVmHWM:\t   12345 kB\nVmRSS:\t 100 kB\n";
        assert_eq!(parse_vm_hwm(status), Some(12345 * 1024));
        assert_eq!(parse_vm_hwm("Name: x\n"), None);
        assert_eq!(parse_vm_hwm("VmHWM: 12 MB\n"), None);
    }

    #[test]
    fn this_process_reports_a_plausible_peak() {
        if let Some(bytes) = peak_memory_bytes() {
            assert!(bytes > 100 * 1024, "peak RSS {bytes} B is implausibly small");
            assert!(bytes < 1 << 44, "peak RSS {bytes} B is implausibly large");
        }
    }

    #[test]
    fn timer_accumulates_per_phase_and_nests() {
        let mut t = PhaseTimer::new();
        t.start(Phase::Assembly);
        std::thread::sleep(Duration::from_millis(20));
        let x = t.time(Phase::Solve, || {
            std::thread::sleep(Duration::from_millis(30));
            7
        });
        assert_eq!(x, 7);
        std::thread::sleep(Duration::from_millis(10));
        t.stop();
        t.add(Phase::Output, Duration::from_millis(5));
        let s = t.seconds();
        assert!(s.assembly >= 0.030 && s.assembly < 0.5, "assembly {}", s.assembly);
        assert!(s.solve >= 0.030 && s.solve < 0.5, "solve {}", s.solve);
        assert!((s.output - 0.005).abs() < 1e-12);
        assert_eq!(s.read, 0.0);
        assert!((s.total() - (s.assembly + s.solve + s.output)).abs() < 1e-12);
    }

    #[test]
    fn summary_json_roundtrips_and_rejects_unknown_fields() {
        let s = RunSummary {
            cfrd_version: "0.1.0".into(),
            scene: "column".into(),
            ranks: 2,
            nodes: 10,
            elements: 4,
            dofs: 27,
            phase_seconds: PhaseSeconds {
                solve: 1.5,
                ..Default::default()
            },
            total_seconds: 2.0,
            ksp_iterations: 40,
            newton_iterations: 6,
            residual_evaluations: 9,
            element_loops: 8,
            element_seconds_per_rank: vec![0.5, 0.25],
            solver_rows_held_per_rank: vec![120, 96],
            steps: 3,
            cutbacks: 1,
            predictions_dropped: 1,
            newton_per_step: vec![2, 2, 2],
            factorizations: 5,
            multigrid_builds: 2,
            interface_points: 16,
            interface_open: 2,
            interface_slipping: 3,
            restarted_after_stage: Some(2),
            accepted_changed_inputs: vec!["stages[1].dynamic.record: record.csv".into()],
            stopped_after_stage: Some(3),
            checkpoint_seconds: 0.25,
            stage_seconds: vec![StageSeconds {
                stage: "fill_1".into(),
                seconds: 1.25,
                steps: 3,
                newton_iterations: 6,
                ksp_iterations: 30,
            }],
            modal: Some(ModalSummary {
                stage: "modes".into(),
                frequencies_hz: vec![1.0, 3.0],
                periods_s: vec![1.0, 1.0 / 3.0],
                seconds: 0.5,
            }),
            peak_memory_bytes: 2048,
            peak_memory_bytes_per_rank: vec![1024, 2048],
        };
        let text = s.to_json();
        let back: RunSummary = serde_json::from_str(&text).unwrap();
        assert_eq!(back, s);
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(value["phase_seconds"]["solve"], 1.5);
        assert_eq!(value["peak_memory_bytes_per_rank"][1], 2048);
        assert_eq!(value["stage_seconds"][0]["stage"], "fill_1");
        assert_eq!(value["stage_seconds"][0]["ksp_iterations"], 30);
        let bad = text.replacen("\"ranks\"", "\"rank_count\"", 1);
        assert!(serde_json::from_str::<RunSummary>(&bad).is_err());
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("summary.json");
        s.write_json(&path).unwrap();
        let read: RunSummary = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert_eq!(read, s);
    }
}
