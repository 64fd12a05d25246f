//! [`Communicator`] over MPI (Open MPI through rsmpi; cargo feature `mpi`).

use crate::comm::{CommStats, Communicator};
use mpi::request::WaitGuard;
use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator as _, CommunicatorCollectives, Destination, Source};
use std::cell::Cell;
use std::time::{Duration, Instant};

/// The processes of `MPI_COMM_WORLD`.
pub struct MpiCommunicator {
    world: SimpleCommunicator,
    stats: Cell<CommStats>,
    _universe: mpi::environment::Universe,
}

impl MpiCommunicator {
    /// Initialises MPI (once per process: `None` the second time) and installs a panic hook
    /// that prints the message and calls `MPI_Abort`, so that a failure on one rank ends the
    /// whole job instead of leaving the others waiting for it.
    pub fn init() -> Option<Self> {
        let universe = mpi::initialize()?;
        let world = universe.world();
        let rank = world.rank();
        let default_hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            eprintln!("xper: rank {rank} failed; aborting every rank");
            default_hook(info);
            SimpleCommunicator::world().abort(70);
        }));
        Some(MpiCommunicator {
            world,
            stats: Cell::new(CommStats::default()),
            _universe: universe,
        })
    }

    /// Whether an MPI launcher (`mpirun`, `mpiexec`, `srun`) started this process: Open MPI,
    /// PMIx and the PMI of MPICH and Slurm leave their variables in its environment. A plain
    /// start then runs on one process without initialising MPI, whose singleton start-up is
    /// slow and, with several such processes starting at once, sometimes fails.
    pub fn launched() -> bool {
        ["OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"]
            .iter()
            .any(|name| std::env::var_os(name).is_some())
    }

    fn count(&self, sends: &[(usize, &[f64])], start: Instant, working: Duration) {
        let mut s = self.stats.get();
        s.messages += sends.len() as u64;
        s.bytes += sends
            .iter()
            .map(|(_, d)| std::mem::size_of_val(*d) as u64)
            .sum::<u64>();
        s.time += start.elapsed().saturating_sub(working);
        self.stats.set(s);
    }

    /// Posts the sends, runs `work`, then receives from `sources` and waits for the sends.
    /// `work`'s time is left out of the communication time.
    fn send_receive(
        &self,
        sends: &[(usize, &[f64])],
        sources: &[usize],
        work: &mut dyn FnMut(),
    ) -> Vec<Vec<f64>> {
        let start = Instant::now();
        let mut working = Duration::ZERO;
        let received = mpi::request::scope(|scope| {
            let _guards: Vec<WaitGuard<[f64], _>> = sends
                .iter()
                .map(|(rank, data)| {
                    WaitGuard::from(
                        self.world
                            .process_at_rank(*rank as i32)
                            .immediate_send(scope, *data),
                    )
                })
                .collect();
            let work_start = Instant::now();
            work();
            working = work_start.elapsed();
            sources
                .iter()
                .map(|&s| self.world.process_at_rank(s as i32).receive_vec::<f64>().0)
                .collect()
        });
        self.count(sends, start, working);
        received
    }
}

impl Communicator for MpiCommunicator {
    fn abort(&self, message: &str, code: i32) -> ! {
        eprintln!("xper: rank {}: {message}", self.world.rank());
        self.world.abort(code)
    }
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn all_to_all(&self, sends: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let me = self.rank();
        let others: Vec<usize> = (0..self.size()).filter(|&r| r != me).collect();
        let outgoing: Vec<(usize, &[f64])> =
            others.iter().map(|&r| (r, sends[r].as_slice())).collect();
        let mut received = self
            .send_receive(&outgoing, &others, &mut || {})
            .into_iter();
        (0..self.size())
            .map(|r| {
                if r == me {
                    sends[r].clone()
                } else {
                    received.next().unwrap_or_default()
                }
            })
            .collect()
    }

    fn exchange_overlapped(
        &self,
        sends: &[(usize, Vec<f64>)],
        sources: &[usize],
        work: &mut dyn FnMut(),
    ) -> Vec<Vec<f64>> {
        let outgoing: Vec<(usize, &[f64])> =
            sends.iter().map(|(r, d)| (*r, d.as_slice())).collect();
        self.send_receive(&outgoing, sources, work)
    }

    /// One `MPI_Allgather` (a logarithmic-depth collective) instead of `size - 1` messages;
    /// the reductions built on it keep summing in rank order, so every rank gets the same bits.
    /// Counted as `ceil(log2 size)` messages carrying the `size - 1` other ranks' values.
    fn all_gather(&self, values: &[f64]) -> Vec<Vec<f64>> {
        let start = Instant::now();
        let size = self.size();
        let mut buffer = vec![0.0; values.len() * size];
        self.world.all_gather_into(values, &mut buffer[..]);
        let mut s = self.stats.get();
        s.messages += size.next_power_of_two().trailing_zeros() as u64;
        s.bytes += (std::mem::size_of_val(values) * (size - 1)) as u64;
        s.time += start.elapsed();
        self.stats.set(s);
        if values.is_empty() {
            return vec![Vec::new(); size];
        }
        buffer
            .chunks_exact(values.len())
            .map(<[f64]>::to_vec)
            .collect()
    }

    fn stats(&self) -> CommStats {
        self.stats.get()
    }
}
