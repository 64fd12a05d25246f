//! `--compare-serial`: the steps of a distributed run repeated on one process, for the
//! parallel efficiency and the largest difference of the two answers.

use crate::RunError;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// A distributed run against the same steps on one process (`--compare-serial`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SerialComparison {
    /// Steps compared.
    pub steps: u64,
    /// Wall time of the distributed run's steps (s), outputs excluded.
    pub distributed_wall_time_s: f64,
    /// Wall time of the same steps on one process (s).
    pub serial_wall_time_s: f64,
    /// `serial / distributed`.
    pub speed_up: f64,
    /// Speed-up divided by the number of processes.
    pub efficiency: f64,
    /// Largest distance between a body's positions at the end of the two runs (m); for a
    /// fracture scene, the largest difference of a nodal displacement component.
    pub max_position_difference_m: f64,
}

impl SerialComparison {
    /// `--compare-serial`: advances `start` on this process by `step` until `step_of` reaches
    /// `end_step`, timed, and compares the result by `difference` with a distributed run of
    /// `distributed.0` seconds on `distributed.1` processes.
    pub fn rerun<S, E: std::fmt::Display>(
        mut start: S,
        end_step: u64,
        step_of: impl Fn(&S) -> u64,
        mut step: impl FnMut(&mut S) -> Result<(), E>,
        difference: impl FnOnce(&S) -> f64,
        distributed: (f64, usize),
    ) -> Result<Self, RunError> {
        let steps = end_step - step_of(&start);
        let clock = Instant::now();
        while step_of(&start) < end_step {
            step(&mut start)
                .map_err(|e| RunError::Runtime(format!("--compare-serial: serial run: {e}")))?;
        }
        let serial = clock.elapsed().as_secs_f64();
        let (wall, processes) = distributed;
        Ok(Self::new(
            steps,
            wall,
            serial,
            processes,
            difference(&start),
        ))
    }

    /// The comparison of `steps` steps run in `distributed` seconds on `processes` processes
    /// and in `serial` seconds on one, ending `difference` apart.
    pub fn new(
        steps: u64,
        distributed: f64,
        serial: f64,
        processes: usize,
        difference: f64,
    ) -> Self {
        let speed_up = serial / distributed.max(1e-12);
        SerialComparison {
            steps,
            distributed_wall_time_s: distributed,
            serial_wall_time_s: serial,
            speed_up,
            efficiency: speed_up / processes as f64,
            max_position_difference_m: difference,
        }
    }
}
