//! Each process's share of a distributed run, as `summary.json` reports it.

use serde::{Deserialize, Serialize};
use xper_parallel::{CommStats, Communicator, RankLoad};

/// A process's share of a distributed run, in `summary.json`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RankSummary {
    /// Process rank.
    pub rank: usize,
    /// Movable bodies (fracture: elements) owned at the end.
    pub bodies: usize,
    /// Shadow copies held at the end.
    pub shadows: usize,
    /// Contacts (fracture: interface points) owned at the last step.
    pub contacts: usize,
    /// Bodies shared with other processes in the last solve.
    pub interface_bodies: usize,
    /// Bodies received by migration during the run.
    pub migrated_in: u64,
    /// Fluid cells held (runs with a fluid).
    pub cells: usize,
    /// Times the fluid's blocks of rows were cut again as the grains moved (runs with a
    /// fluid; the time it took is in the step times).
    pub recuts: u64,
    /// Messages sent from the first step on (the initial distribution is left out; the
    /// gathers of outputs are in).
    pub messages: u64,
    /// Bytes sent, counted as `messages`.
    pub bytes: u64,
    /// Seconds inside communication calls from the first step on, waiting included.
    pub communication_s: f64,
    /// Share of the run's wall time spent communicating.
    pub communication_share: f64,
}

/// Every process's `load` and communication since `setup` (the stats when the run was
/// distributed) over a run of `wall` seconds (collective).
pub fn rank_summaries(
    comm: &dyn Communicator,
    load: RankLoad,
    setup: &CommStats,
    wall: f64,
) -> Vec<RankSummary> {
    let stats = comm.stats().since(setup);
    let mine = [
        load.bodies as f64,
        load.shadows as f64,
        load.contacts as f64,
        load.interface_bodies as f64,
        load.migrated_in as f64,
        stats.messages as f64,
        stats.bytes as f64,
        stats.time.as_secs_f64(),
        load.cells as f64,
        load.recuts as f64,
    ];
    (comm.all_gather(&mine).iter().enumerate())
        .map(|(rank, v)| RankSummary {
            rank,
            bodies: v[0] as usize,
            shadows: v[1] as usize,
            contacts: v[2] as usize,
            interface_bodies: v[3] as usize,
            migrated_in: v[4] as u64,
            cells: v[8] as usize,
            recuts: v[9] as u64,
            messages: v[5] as u64,
            bytes: v[6] as u64,
            communication_s: v[7],
            communication_share: if wall > 0.0 { v[7] / wall } else { 0.0 },
        })
        .collect()
}
