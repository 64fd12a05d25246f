//! Rows exchanged between the horizontal strips of a grid, one strip per process (strip `s` on
//! rank `s`): the links of the distributed pressure multigrid ([`xper_poisson::RowLinks`]).

use crate::comm::Communicator;
use xper_poisson::{RowExchange, RowLinks};

/// The neighbours of strip `rank` among `size` strips: below and above, wrapping around when
/// the bottom and top are periodic.
pub fn strip_neighbours(rank: usize, size: usize, periodic: bool) -> [Option<usize>; 2] {
    let below = (rank > 0 || periodic).then(|| (rank + size - 1) % size);
    let above = (rank + 1 < size || periodic).then(|| (rank + 1) % size);
    [below, above]
}

/// Sends `to_below` and `to_above` to the neighbours `[below, above]` and returns `[from_below,
/// from_above]`: what the strip below sent up and what the strip above sent down. A strip that
/// is its own neighbour (one periodic strip) keeps its rows; two strips that are each other's
/// neighbour on both sides (two periodic strips) send both parts in one message.
pub fn exchange_with_neighbours<C: Communicator + ?Sized>(
    comm: &C,
    neighbours: [Option<usize>; 2],
    to_below: Option<Vec<f64>>,
    to_above: Option<Vec<f64>>,
) -> [Option<Vec<f64>>; 2] {
    exchange_with_neighbours_overlapped(comm, neighbours, to_below, to_above, &mut || {})
}

/// [`exchange_with_neighbours`], running `work` while the rows travel
/// ([`Communicator::exchange_overlapped`]).
pub fn exchange_with_neighbours_overlapped<C: Communicator + ?Sized>(
    comm: &C,
    neighbours: [Option<usize>; 2],
    to_below: Option<Vec<f64>>,
    to_above: Option<Vec<f64>>,
    work: &mut dyn FnMut(),
) -> [Option<Vec<f64>>; 2] {
    let me = comm.rank();
    match neighbours {
        [Some(below), Some(above)] if below == me && above == me => {
            work();
            [to_above, to_below]
        }
        [Some(below), Some(above)] if below == above => {
            let first = to_below.unwrap_or_default();
            let mut message = Vec::with_capacity(first.len() + 1);
            message.push(first.len() as f64);
            message.extend(first);
            message.extend(to_above.unwrap_or_default());
            let mut received = comm.exchange_overlapped(&[(below, message)], &[below], work);
            let mut message = received.pop().unwrap_or_default();
            let split = message
                .first()
                .map_or(0, |&n| n as usize + 1)
                .min(message.len());
            let from_below = message.split_off(split);
            message.remove(0);
            [Some(from_below), Some(message)]
        }
        [below, above] => {
            let mut sends = Vec::with_capacity(2);
            let mut sources = Vec::with_capacity(2);
            for (neighbour, data) in [(below, to_below), (above, to_above)] {
                if let Some(rank) = neighbour {
                    sends.push((rank, data.unwrap_or_default()));
                    sources.push(rank);
                }
            }
            let mut received = comm.exchange_overlapped(&sends, &sources, work).into_iter();
            [
                below.and_then(|_| received.next()),
                above.and_then(|_| received.next()),
            ]
        }
    }
}

/// The links of one strip over `comm`.
pub struct StripComm<'c, C: Communicator + ?Sized> {
    /// The processes.
    pub comm: &'c C,
    /// The strips below and above.
    pub neighbours: [Option<usize>; 2],
}

impl<C: Communicator + ?Sized> RowExchange for StripComm<'_, C> {
    fn exchange_rows_overlapped(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        self.exchange_rows_among(self.neighbours, to_below, to_above, work)
    }
}

impl<C: Communicator + ?Sized> RowLinks for StripComm<'_, C> {
    fn exchange_rows_among(
        &mut self,
        neighbours: [Option<usize>; 2],
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        exchange_with_neighbours_overlapped(
            self.comm,
            neighbours,
            to_below.map(<[f64]>::to_vec),
            to_above.map(<[f64]>::to_vec),
            work,
        )
    }

    fn send_receive(&mut self, sends: Vec<(usize, Vec<f64>)>, sources: &[usize]) -> Vec<Vec<f64>> {
        self.comm.exchange(&sends, sources)
    }

    fn sum(&mut self, values: &mut [f64]) {
        self.comm.all_reduce_sum(values);
    }

    fn gather(&mut self, values: &[f64]) -> Vec<f64> {
        self.comm.all_gather(values).concat()
    }
}
