//! When a staged run writes at the end of a stage: publishing `results.h5` (a complete copy of
//! the file, [`crate::io::hdf5_out::ResultsFile::publish`]) and the checkpoint that follows it.
//!
//! The copy grows with every stage, so writing at every stage costs work quadratic in the
//! number of stages: on the fine seed mesh (95 stages, 1.6 GB of results) the copies took
//! 3.4–3.8 s each by stage 55 (0.9 GB), 79 s by stage 55 in all
//! ([`crate::performance`], "The fine run"). With stage checkpoints (`output.checkpoint:
//! stage`, the default of staged scenes) the writes at a stage's end are therefore paced: they
//! happen once the run has computed [`COMPUTE_PER_WRITE`] times as long as the last such
//! writes took, so that they cost at most 2.5 % of the run, and always after the last stage and
//! at `--stop-after-stage`. Small and medium meshes write at every stage or every few (their
//! writes take milliseconds to tenths of a second); a killed run recomputes at most the stages
//! since its last checkpoint, [`COMPUTE_PER_WRITE`] times as long as that checkpoint's writes
//! took (on the fine seed mesh, whose last copies take some 4 s, about 3 min).
//!
//! 39 rather than 19: on the fine hyperbolic run 19 left 102.0–104.6 s of output, 39 leaves
//! 76.4 s; it doubles the time a kill may cost ([`crate::performance`], "The fine run").

use crate::parallel::max_f64;
use mpi::topology::SimpleCommunicator;
use std::time::Instant;

/// Compute time between two stage-end writes, in multiples of the last writes' duration (39:
/// the writes take at most 1/40 of the run).
pub const COMPUTE_PER_WRITE: f64 = 39.0;

/// Whether a stage's end writes: always when `must` (the last stage, a stop), otherwise once
/// `computed` seconds since the last writes are at least [`COMPUTE_PER_WRITE`] times their
/// duration `last_write` (0 before the first writes, which therefore come at the first stage).
pub fn write_due(computed: f64, last_write: f64, must: bool) -> bool {
    must || computed >= COMPUTE_PER_WRITE * last_write
}

/// The clock of the stage-end writes of one run (module docs). Its decisions are collective:
/// every rank takes the largest time over the ranks, so all ranks decide alike.
pub struct StageEndWrites {
    /// End of the last writes (the run's start before them).
    since: Instant,
    /// Duration of the last writes, the largest over the ranks (s).
    last_write: f64,
}

impl StageEndWrites {
    /// A clock that starts now, with no writes yet.
    pub fn new() -> Self {
        StageEndWrites {
            since: Instant::now(),
            last_write: 0.0,
        }
    }

    /// Whether this stage's end writes ([`write_due`]). Collective.
    pub fn due(&self, world: &SimpleCommunicator, must: bool) -> bool {
        let computed = max_f64(world, self.since.elapsed().as_secs_f64());
        write_due(computed, self.last_write, must)
    }

    /// Records writes that began at `began` and have just ended. Collective.
    pub fn wrote(&mut self, world: &SimpleCommunicator, began: Instant) {
        self.last_write = max_f64(world, began.elapsed().as_secs_f64());
        self.since = Instant::now();
    }
}

impl Default for StageEndWrites {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_stage_always_writes() {
        assert!(write_due(0.0, 0.0, false));
    }

    #[test]
    fn writes_wait_for_thirty_nine_times_their_duration_of_computing() {
        // a 3.5 s publish of the fine mesh: the next after 136.5 s of computing, not before
        assert!(!write_due(66.5, 3.5, false));
        assert!(!write_due(136.4, 3.5, false));
        assert!(write_due(136.5, 3.5, false));
        // a medium mesh's 0.05 s: every stage of two seconds or more
        assert!(write_due(2.0, 0.05, false));
    }

    #[test]
    fn the_last_stage_and_a_stop_always_write() {
        assert!(write_due(0.0, 100.0, true));
    }

    #[test]
    fn the_writes_cost_at_most_a_fortieth_of_the_run() {
        // stages of 20 s whose writes grow by 0.1 s a stage (the fine mesh's copy grows so)
        let (mut computed, mut last, mut writing, mut total) = (0.0, 0.0, 0.0, 0.0);
        for k in 0..200 {
            computed += 20.0;
            total += 20.0;
            if write_due(computed, last, k == 199) {
                last = 0.1 * k as f64;
                writing += last;
                total += last;
                computed = 0.0;
            }
        }
        // every stage would have written 1,990 s in a run of 4,000 s of computing
        assert!(writing <= total / 40.0 + last, "{writing} s of {total} s");
    }
}
