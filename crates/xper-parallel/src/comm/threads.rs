//! Ranks as threads of one process, linked by one channel per ordered pair of ranks: the
//! distributed algorithms run and are tested without MPI.

use crate::comm::{CommStats, Communicator};
use std::cell::Cell;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::time::Instant;

/// One rank of a group of threads (see [`run_on_threads`]).
pub struct ThreadCommunicator {
    rank: usize,
    size: usize,
    /// `to[r]` sends to rank `r`.
    to: Vec<Sender<Vec<f64>>>,
    /// `from[r]` receives from rank `r`.
    from: Vec<Receiver<Vec<f64>>>,
    stats: Cell<CommStats>,
}

/// Runs `task` on `size` threads, one rank each, and returns their results by rank.
///
/// A panic on one rank is propagated (after the others finish or also panic); a rank waiting
/// for a message from a rank that panicked gets a closed channel and panics in turn, so the
/// group cannot hang.
pub fn run_on_threads<T, F>(size: usize, task: F) -> Vec<T>
where
    T: Send,
    F: Fn(&ThreadCommunicator) -> T + Sync,
{
    assert!(size > 0, "a group needs at least one rank");
    let mut senders: Vec<Vec<Option<Sender<Vec<f64>>>>> = (0..size)
        .map(|_| (0..size).map(|_| None).collect())
        .collect();
    let mut receivers: Vec<Vec<Option<Receiver<Vec<f64>>>>> = (0..size)
        .map(|_| (0..size).map(|_| None).collect())
        .collect();
    for (src, row) in senders.iter_mut().enumerate() {
        for (dst, slot) in row.iter_mut().enumerate() {
            let (tx, rx) = channel();
            *slot = Some(tx);
            receivers[dst][src] = Some(rx);
        }
    }
    let comms: Vec<ThreadCommunicator> = senders
        .into_iter()
        .zip(receivers)
        .enumerate()
        .map(|(rank, (to, from))| ThreadCommunicator {
            rank,
            size,
            to: to.into_iter().map(Option::unwrap).collect(),
            from: from.into_iter().map(Option::unwrap).collect(),
            stats: Cell::new(CommStats::default()),
        })
        .collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = comms
            .into_iter()
            .map(|comm| {
                let task = &task;
                scope.spawn(move || task(&comm))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    })
}

impl ThreadCommunicator {
    fn send(&self, dst: usize, data: Vec<f64>) {
        let mut s = self.stats.get();
        s.messages += 1;
        s.bytes += (data.len() * std::mem::size_of::<f64>()) as u64;
        self.stats.set(s);
        self.to[dst]
            .send(data)
            .unwrap_or_else(|_| panic!("rank {}: rank {dst} has stopped", self.rank));
    }

    fn receive(&self, src: usize) -> Vec<f64> {
        self.from[src]
            .recv()
            .unwrap_or_else(|_| panic!("rank {}: rank {src} has stopped", self.rank))
    }

    fn timed<T>(&self, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        let mut s = self.stats.get();
        s.time += start.elapsed();
        self.stats.set(s);
        out
    }
}

impl Communicator for ThreadCommunicator {
    fn abort(&self, message: &str, _code: i32) -> ! {
        panic!("rank {}: {message}", self.rank())
    }
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.size
    }

    fn all_to_all(&self, sends: &[Vec<f64>]) -> Vec<Vec<f64>> {
        assert_eq!(
            sends.len(),
            self.size,
            "all_to_all needs one vector per rank"
        );
        self.timed(|| {
            for (dst, data) in sends.iter().enumerate() {
                if dst != self.rank {
                    self.send(dst, data.clone());
                }
            }
            (0..self.size)
                .map(|src| {
                    if src == self.rank {
                        sends[src].clone()
                    } else {
                        self.receive(src)
                    }
                })
                .collect()
        })
    }

    fn exchange_overlapped(
        &self,
        sends: &[(usize, Vec<f64>)],
        sources: &[usize],
        work: &mut dyn FnMut(),
    ) -> Vec<Vec<f64>> {
        self.timed(|| {
            for (dst, data) in sends {
                self.send(*dst, data.clone());
            }
        });
        work();
        self.timed(|| sources.iter().map(|&src| self.receive(src)).collect())
    }

    fn stats(&self) -> CommStats {
        self.stats.get()
    }
}
