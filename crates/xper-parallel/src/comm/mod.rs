//! What the distributed algorithms need from a group of processes.

#[cfg(feature = "mpi")]
pub mod mpi;
pub mod threads;

use std::time::Duration;

/// Traffic and time spent communicating, per process.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CommStats {
    /// Messages sent.
    pub messages: u64,
    /// Bytes sent.
    pub bytes: u64,
    /// Wall time inside communication calls, waiting included.
    pub time: Duration,
}

impl CommStats {
    /// The traffic and time since `earlier` (the stats of the same process then).
    pub fn since(&self, earlier: &CommStats) -> CommStats {
        CommStats {
            messages: self.messages - earlier.messages,
            bytes: self.bytes - earlier.bytes,
            time: self.time.saturating_sub(earlier.time),
        }
    }
}

/// A group of `size` processes, this one being `rank`.
///
/// Every collective call (`all_to_all`, `all_reduce_*`, `all_gather`) must be made by all
/// ranks in the same order; an `exchange` by the ranks it links (each sending to and
/// receiving from the others in matching order). Reductions are computed in rank order on
/// every rank, so every rank gets bit-identical results and a run is reproducible for a given
/// number of processes.
pub trait Communicator {
    /// This process, `0..size`.
    fn rank(&self) -> usize;
    /// Number of processes.
    fn size(&self) -> usize;
    /// Sends `sends[r]` to each rank `r` (empty vectors allowed, `sends[rank]` is kept) and
    /// returns what each rank sent here, indexed by rank.
    fn all_to_all(&self, sends: &[Vec<f64>]) -> Vec<Vec<f64>>;
    /// Neighbour exchange: sends each `(rank, data)` of `sends`, runs `work` exactly once (it
    /// must not need what arrives) after the sends are posted and before the receives wait,
    /// so a neighbour's small lag is absorbed by it (a message above the transport's eager
    /// size may still move only once received: MPI makes no progress without a call), and
    /// receives one message from each rank of `sources`, returned in the order of `sources`.
    /// `work`'s time is not counted as communication.
    fn exchange_overlapped(
        &self,
        sends: &[(usize, Vec<f64>)],
        sources: &[usize],
        work: &mut dyn FnMut(),
    ) -> Vec<Vec<f64>>;
    /// [`Communicator::exchange_overlapped`] with nothing to overlap.
    fn exchange(&self, sends: &[(usize, Vec<f64>)], sources: &[usize]) -> Vec<Vec<f64>> {
        self.exchange_overlapped(sends, sources, &mut || {})
    }
    /// Replaces each value by its sum over the ranks.
    fn all_reduce_sum(&self, values: &mut [f64]) {
        self.all_reduce_sum_max(values, &mut []);
    }
    /// Replaces each value by its maximum over the ranks.
    fn all_reduce_max(&self, values: &mut [f64]) {
        self.all_reduce_sum_max(&mut [], values);
    }
    /// [`Communicator::all_reduce_sum`] of `sums` and [`Communicator::all_reduce_max`] of
    /// `maxima` from one gather.
    fn all_reduce_sum_max(&self, sums: &mut [f64], maxima: &mut [f64]) {
        let mut values = Vec::with_capacity(sums.len() + maxima.len());
        values.extend_from_slice(sums);
        values.extend_from_slice(maxima);
        let gathered = self.all_gather(&values);
        for (k, v) in sums.iter_mut().enumerate() {
            *v = gathered.iter().map(|g| g[k]).sum();
        }
        let n = sums.len();
        for (k, v) in maxima.iter_mut().enumerate() {
            *v = gathered
                .iter()
                .map(|g| g[n + k])
                .fold(f64::NEG_INFINITY, f64::max);
        }
    }
    /// Every rank's `values` (all of the same length), indexed by rank.
    fn all_gather(&self, values: &[f64]) -> Vec<Vec<f64>> {
        let sends = vec![values.to_vec(); self.size()];
        self.all_to_all(&sends)
    }
    /// Traffic and time so far.
    fn stats(&self) -> CommStats;
    /// Ends every process of the group at once with exit code `code`, after printing
    /// `message`: for a failure one process meets alone, when the others would wait for it.
    fn abort(&self, message: &str, code: i32) -> ! {
        eprintln!("xper: rank {}: {message}", self.rank());
        std::process::exit(code)
    }
}

/// [`Communicator::all_to_all`] when `among` is `None`; else the same exchange restricted to
/// the ranks of `among` (a symmetric relation: each of them calls it with this rank among its
/// own), `sends[r]` empty for every other rank `r`. Returns what each rank sent here, indexed
/// by rank (empty for ranks outside `among`, `sends[rank]` kept). Latency then grows with the
/// number of neighbours instead of the number of processes.
pub fn exchange_by_rank<C: Communicator + ?Sized>(
    comm: &C,
    mut sends: Vec<Vec<f64>>,
    among: Option<&[usize]>,
) -> Vec<Vec<f64>> {
    let Some(among) = among else {
        return comm.all_to_all(&sends);
    };
    let me = comm.rank();
    debug_assert!((0..comm.size()).all(|r| r == me || among.contains(&r) || sends[r].is_empty()));
    let outgoing: Vec<(usize, Vec<f64>)> = (among.iter())
        .map(|&r| (r, std::mem::take(&mut sends[r])))
        .collect();
    let mut received = vec![Vec::new(); comm.size()];
    for (&r, message) in among.iter().zip(comm.exchange(&outgoing, among)) {
        received[r] = message;
    }
    received[me] = std::mem::take(&mut sends[me]);
    received
}

/// The group of one process: every collective returns its input.
#[derive(Clone, Copy, Debug, Default)]
pub struct SingleProcess;

impl Communicator for SingleProcess {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn all_to_all(&self, sends: &[Vec<f64>]) -> Vec<Vec<f64>> {
        sends.to_vec()
    }
    fn exchange_overlapped(
        &self,
        sends: &[(usize, Vec<f64>)],
        sources: &[usize],
        work: &mut dyn FnMut(),
    ) -> Vec<Vec<f64>> {
        work();
        sources
            .iter()
            .map(|&s| {
                sends
                    .iter()
                    .find(|(r, _)| *r == s)
                    .map(|(_, d)| d.clone())
                    .unwrap_or_default()
            })
            .collect()
    }
    fn stats(&self) -> CommStats {
        CommStats::default()
    }
}
