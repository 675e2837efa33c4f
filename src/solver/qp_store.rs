//! Double-buffered integration-point storage (`spec/style.md` G.3).
//!
//! `trial[i]` is rebuilt from `committed[i]` at every Newton iterate with the total step
//! increment (spec §8.1), so a revert is free and a step cut-back is safe. [`QpStore::commit`]
//! swaps the buffers after a converged step.

use serde::{Deserialize, Serialize};

/// Committed and trial states of a set of integration points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QpStore<S> {
    /// States at the last converged step.
    pub committed: Vec<S>,
    /// States of the current iterate.
    pub trial: Vec<S>,
}

impl<S: Clone> QpStore<S> {
    /// `n` points, all starting at `init`.
    pub fn new(n: usize, init: S) -> Self {
        QpStore {
            committed: vec![init.clone(); n],
            trial: vec![init; n],
        }
    }

    /// Accepts the trial states (after convergence).
    pub fn commit(&mut self) {
        std::mem::swap(&mut self.committed, &mut self.trial);
        self.trial.clone_from(&self.committed);
    }

    /// Discards the trial states (after a failed step).
    pub fn revert(&mut self) {
        self.trial.clone_from(&self.committed);
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.committed.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.committed.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commit_and_revert() {
        let mut s = QpStore::new(2, 0.0f64);
        s.trial[0] = 1.0;
        s.revert();
        assert_eq!(s.trial, vec![0.0, 0.0]);
        s.trial[1] = 2.0;
        s.commit();
        assert_eq!(s.committed, vec![0.0, 2.0]);
        assert_eq!(s.trial, vec![0.0, 2.0]);
    }
}
