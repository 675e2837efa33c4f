//! The quake's clock: every dynamic stage of a scene on one time axis. The first dynamic stage
//! starts at t = 0; each later one starts where the dynamic stage before it ended (static
//! stages between them take no time on this clock). The crest and probe histories, the quake
//! fields read back from the results and the quake's figures all use it, so a scene whose
//! earthquake is split into stages (a main shock and a quiet tail, or a main shock and an
//! aftershock) gets one history over all of them.

use crate::scene::dynamic::DynamicStage;
use crate::scene::{Scene, Stage};

/// The dynamic stages of a scene with their start on the quake's clock.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct QuakeClock {
    /// (stage index, start on the clock in s), in schedule order.
    stages: Vec<(usize, f64)>,
}

impl QuakeClock {
    /// The clock of `scene`'s dynamic stages.
    pub fn new(scene: &Scene) -> Self {
        let mut start = 0.0;
        let mut stages = Vec::new();
        for (k, s) in scene.stages.iter().enumerate() {
            if let Some(d) = &s.dynamic {
                stages.push((k, start));
                start += d.duration;
            }
        }
        QuakeClock { stages }
    }

    /// Whether the scene has a dynamic stage.
    pub fn is_empty(&self) -> bool {
        self.stages.is_empty()
    }

    /// The index of the first dynamic stage.
    pub fn first(&self) -> Option<usize> {
        self.stages.first().map(|&(k, _)| k)
    }

    /// The start on the clock (s) of stage `k`; `None` for a static stage.
    pub fn start(&self, k: usize) -> Option<f64> {
        self.stages.iter().find(|&&(j, _)| j == k).map(|&(_, t)| t)
    }

    /// The dynamic stages with their start on the clock.
    pub fn stages<'s>(
        &'s self,
        scene: &'s Scene,
    ) -> impl Iterator<Item = (usize, &'s Stage, &'s DynamicStage, f64)> + 's {
        self.stages.iter().map(move |&(k, t0)| {
            let s = &scene.stages[k];
            (k, s, s.dynamic.as_ref().expect("a dynamic stage"), t0)
        })
    }

    /// The names of the dynamic stages, joined by ", " (for notes and sampling lines).
    pub fn names(&self, scene: &Scene) -> String {
        let names: Vec<&str> = self.stages(scene).map(|(_, s, _, _)| s.name.as_str()).collect();
        names.join(", ")
    }

    /// The peak ground acceleration (m/s², x, y, z) over the records of every dynamic stage,
    /// at the records' samples.
    pub fn peak_ground_acceleration(&self, scene: &Scene) -> [f64; 3] {
        let mut peak = [0.0f64; 3];
        for (_, _, d, _) in self.stages(scene) {
            let n = (d.duration / d.record.dt()).round() as usize;
            for i in 0..=n {
                let a = d.ground_acceleration(i as f64 * d.record.dt());
                for c in 0..3 {
                    peak[c] = peak[c].max(a[c].abs());
                }
            }
        }
        peak
    }
}
