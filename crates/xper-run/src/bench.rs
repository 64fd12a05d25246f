//! The figures of one benchmark run of a rigid scene (`xper bench`), in 2D or 3D: what its
//! JSON file holds and BENCHMARKS.md gathers.

use serde::{Deserialize, Serialize};

/// Figures of one benchmark run.
#[derive(Serialize, Deserialize)]
pub struct BenchResult {
    pub scene: String,
    /// Space dimension of the scene (absent from results written before 3D scenes: 2).
    #[serde(default)]
    pub dimension: Option<u8>,
    pub bodies: usize,
    pub steps: u64,
    pub machine: String,
    pub median_step_ms: f64,
    pub median_settled_step_ms: f64,
    pub median_sweeps: f64,
    pub median_settled_sweeps: f64,
    pub median_contacts: f64,
    pub median_settled_contacts: f64,
    pub median_ns_per_contact_update: f64,
    pub median_detect_ms: f64,
    pub median_detect_ns_per_body: f64,
    /// Mean detection time per step and body (ns), builds of the candidate list included
    /// (absent from results of versions before the candidate list).
    #[serde(default)]
    pub mean_detect_ns_per_body: Option<f64>,
    /// Steps whose detection rebuilt the candidate list (ran the broad phase).
    #[serde(default)]
    pub candidate_list_builds: Option<u64>,
    pub non_converged_steps: usize,
    pub peak_memory_bytes: u64,
    pub peak_memory_bytes_per_body: f64,
    /// Largest heap held at once over the run, counted by the allocator (the run's data
    /// without the executable, its libraries or memory the C allocator keeps); absent from
    /// results of earlier versions.
    #[serde(default)]
    pub peak_heap_bytes: Option<u64>,
    pub overlap_median_m: f64,
    pub overlap_p99_m: f64,
    pub overlap_max_m: f64,
    pub overlapping_contacts: usize,
    pub wall_time_s: f64,
}
