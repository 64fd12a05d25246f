//! The distributed pressure multigrid on many processes, measured where this machine can:
//! each process's compute. `P` thread processes solve one Poisson problem (open top, random
//! rhs, relative tolerance 1e-8) with the strip multigrid, each recording what its links
//! return and counting its messages; then each process's solve is replayed alone on one core
//! with the recorded rows and sums (the same computation, bit for bit, with no one to wait
//! for and its caches its own, as on a core of a cluster), timed best of 3. The serial
//! multigrid solves the same problem alone. Per V-cycle:
//!
//! ```text
//! T_P = max over processes of (compute)
//!     + (messages + collectives log2 P) alpha + (message bytes + collective bytes) / beta
//! efficiency = T_serial / (P T_P)
//! ```
//!
//! (messages, bytes and collectives each the largest count of any process; a reduction or
//! gather over `P` processes is `log2 P` deep) with `alpha` = 2 us and `beta` = 5 GB/s (an
//! InfiniBand cluster, as the rigid model of BENCHMARKS.md). The busiest process's compute is the critical path when every level is
//! balanced as the finest is; a process that waits at a level for a busier neighbour and is
//! itself the busiest elsewhere makes the real path longer, so this is a lower bound of the
//! compute part. (Timing the threads' CPU in the threaded run instead counts the caches
//! refilled at every switch between 48 threads on 2 cores: 2.6 times a process's share of the
//! serial cycle on 1024 x 1024 against 1.5 replayed.)
//!
//! `cargo run -p xper-domain --release --example pressure_model [-- NXxNY:P ...] [--json FILE]`

mod common;

use common::{arguments, write_json, ALPHA, BETA};
use std::time::Instant;
use xper_domain::halo::{strip_neighbours, StripComm};
use xper_domain::{run_on_threads, Communicator};
use xper_poisson::{
    Boundary, GridShape, Multigrid, MultigridParams, RowExchange, RowLinks, StripLayout,
    StripMultigrid,
};

const ROUNDS: usize = 3;

/// What a call to the links returned, in call order.
#[derive(Clone)]
enum Event {
    Rows([Option<Vec<f64>>; 2]),
    Messages(Vec<Vec<f64>>),
    Values(Vec<f64>),
}

/// The strip links, recording what every call returns and counting what this process sends:
/// point-to-point messages and their bytes, collectives and the bytes they return.
struct Recording<'c, C: Communicator> {
    links: StripComm<'c, C>,
    events: Vec<Event>,
    messages: usize,
    bytes: usize,
    collectives: usize,
    collective_bytes: usize,
}

impl<C: Communicator> Recording<'_, C> {
    fn count(&mut self, sent: impl IntoIterator<Item = usize>) {
        for values in sent {
            self.messages += 1;
            self.bytes += 8 * values;
        }
    }
}

impl<C: Communicator> RowExchange for Recording<'_, C> {
    fn exchange_rows_overlapped(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        let neighbours = self.links.neighbours;
        self.exchange_rows_among(neighbours, to_below, to_above, work)
    }
}

impl<C: Communicator> RowLinks for Recording<'_, C> {
    fn exchange_rows_among(
        &mut self,
        neighbours: [Option<usize>; 2],
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        let rows = (self.links).exchange_rows_among(neighbours, to_below, to_above, work);
        let me = self.links.comm.rank();
        self.count(sent_rows(neighbours, me, to_below, to_above));
        self.events.push(Event::Rows(rows.clone()));
        rows
    }
    fn send_receive(&mut self, sends: Vec<(usize, Vec<f64>)>, sources: &[usize]) -> Vec<Vec<f64>> {
        self.count(sends.iter().map(|(_, values)| values.len()));
        let messages = self.links.send_receive(sends, sources);
        self.events.push(Event::Messages(messages.clone()));
        messages
    }
    fn sum(&mut self, values: &mut [f64]) {
        self.links.sum(values);
        self.collectives += 1;
        self.collective_bytes += 8 * values.len();
        self.events.push(Event::Values(values.to_vec()));
    }
    fn gather(&mut self, values: &[f64]) -> Vec<f64> {
        let whole = self.links.gather(values);
        self.collectives += 1;
        self.collective_bytes += 8 * whole.len();
        self.events.push(Event::Values(whole.clone()));
        whole
    }
}

/// The lengths of the rows a row exchange sends to other processes.
fn sent_rows(
    neighbours: [Option<usize>; 2],
    me: usize,
    to_below: Option<&[f64]>,
    to_above: Option<&[f64]>,
) -> Vec<usize> {
    let sends = [(neighbours[0], to_below), (neighbours[1], to_above)];
    let lengths = sends.iter().filter_map(|(n, rows)| match (n, rows) {
        (Some(n), Some(rows)) if *n != me => Some(rows.len()),
        _ => None,
    });
    if neighbours[0].is_some() && neighbours[0] == neighbours[1] && neighbours[0] != Some(me) {
        vec![lengths.sum()]
    } else {
        lengths.collect()
    }
}

/// Links that return what a [`Recording`] of the same process recorded: the process's
/// computation alone, as on a core of its own with no one to wait for.
struct Replay {
    events: std::vec::IntoIter<Event>,
}

impl Replay {
    fn next(&mut self) -> Event {
        self.events
            .next()
            .expect("the replay makes the recorded calls")
    }
    fn rows(&mut self) -> [Option<Vec<f64>>; 2] {
        match self.next() {
            Event::Rows(rows) => rows,
            _ => panic!("the replay makes the recorded calls"),
        }
    }
    fn values(&mut self) -> Vec<f64> {
        match self.next() {
            Event::Values(values) => values,
            _ => panic!("the replay makes the recorded calls"),
        }
    }
}

impl RowExchange for Replay {
    fn exchange_rows_overlapped(
        &mut self,
        _to_below: Option<&[f64]>,
        _to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        work();
        self.rows()
    }
}

impl RowLinks for Replay {
    fn exchange_rows_among(
        &mut self,
        _neighbours: [Option<usize>; 2],
        _to_below: Option<&[f64]>,
        _to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        work();
        self.rows()
    }
    fn send_receive(
        &mut self,
        _sends: Vec<(usize, Vec<f64>)>,
        _sources: &[usize],
    ) -> Vec<Vec<f64>> {
        match self.next() {
            Event::Messages(messages) => messages,
            _ => panic!("the replay makes the recorded calls"),
        }
    }
    fn sum(&mut self, values: &mut [f64]) {
        values.copy_from_slice(&self.values());
    }
    fn gather(&mut self, _values: &[f64]) -> Vec<f64> {
        self.values()
    }
}

/// What one process did in the recorded solve.
struct Process {
    events: Vec<Event>,
    messages: usize,
    bytes: usize,
    collectives: usize,
    collective_bytes: usize,
    cycles: u32,
    gathered: usize,
    levels: usize,
}

fn measure(nx: usize, ny: usize, processes: usize) -> Result<serde_json::Value, String> {
    let shape = GridShape::square_cells(nx, ny, 1.0);
    let boundary = Boundary::open_top();
    let params = MultigridParams {
        relative_tolerance: 1e-8,
        ..MultigridParams::default()
    };
    let rhs = xper_poisson::random::random_values(nx * ny, 5);
    let mut serial = Multigrid::new(shape, boundary, params).map_err(|e| e.to_string())?;
    let mut phi = vec![0.0; nx * ny];
    let mut serial_seconds = f64::INFINITY;
    let mut serial_cycles = 0;
    for _ in 0..ROUNDS {
        phi.fill(0.0);
        let start = Instant::now();
        let info = serial.solve(&rhs, &mut phi).map_err(|e| e.to_string())?;
        serial_seconds = serial_seconds.min(start.elapsed().as_secs_f64());
        serial_cycles = info.cycles;
    }
    let layout = StripLayout::balanced(nx, ny, processes)?;
    let solver_of = |strip: usize| {
        StripMultigrid::new(shape, boundary, params, layout.clone(), strip)
            .map_err(|e| e.to_string())
    };
    let local = |strip: usize| {
        let rows = layout.rows(strip);
        &rhs[nx * rows.start..nx * rows.end]
    };
    let recorded = run_on_threads(processes, |comm| -> Result<Process, String> {
        let strip = comm.rank();
        let mut solver = solver_of(strip)?;
        let mut links = Recording {
            links: StripComm {
                comm,
                neighbours: strip_neighbours(strip, processes, false),
            },
            events: Vec::new(),
            messages: 0,
            bytes: 0,
            collectives: 0,
            collective_bytes: 0,
        };
        let mut phi = vec![0.0; local(strip).len()];
        let info = solver
            .solve(&mut links, local(strip), &mut phi)
            .map_err(|e| e.to_string())?;
        Ok(Process {
            events: links.events,
            messages: links.messages,
            bytes: links.bytes,
            collectives: links.collectives,
            collective_bytes: links.collective_bytes,
            cycles: info.cycles,
            gathered: solver.gathered_cells(),
            levels: solver.strip_levels(),
        })
    });
    let recorded: Vec<Process> = recorded.into_iter().collect::<Result<_, _>>()?;
    // Each process's solve replayed alone, best of ROUNDS.
    let mut compute = Vec::with_capacity(processes);
    for (strip, process) in recorded.iter().enumerate() {
        let mut solver = solver_of(strip)?;
        let mut phi = vec![0.0; local(strip).len()];
        let mut best = f64::INFINITY;
        for _ in 0..ROUNDS {
            phi.fill(0.0);
            let mut replay = Replay {
                events: process.events.clone().into_iter(),
            };
            let start = Instant::now();
            solver
                .solve(&mut replay, local(strip), &mut phi)
                .map_err(|e| e.to_string())?;
            best = best.min(start.elapsed().as_secs_f64());
        }
        compute.push(best);
    }
    let cycles = recorded[0].cycles as f64;
    let busiest = compute.iter().fold(0.0, |m: f64, &c| m.max(c)) / cycles;
    let mean = compute.iter().sum::<f64>() / (processes as f64 * cycles);
    // Per cycle, each the largest of any process; a collective costs log2(P) latencies.
    let most = |of: &dyn Fn(&Process) -> usize| {
        (recorded.iter().map(of)).max().unwrap_or(0) as f64 / cycles
    };
    let messages = most(&|p| p.messages);
    let bytes = most(&|p| p.bytes);
    let collectives = most(&|p| p.collectives);
    let collective_bytes = most(&|p| p.collective_bytes);
    let depth = (processes as f64).log2().ceil();
    let gathered = (recorded.iter().map(|p| p.gathered)).max().unwrap_or(0);
    let holding = (recorded.iter().filter(|p| p.gathered > 0)).count();
    let deepest = (recorded.iter().map(|p| p.levels)).max().unwrap_or(0);
    let serial_cycle = serial_seconds / serial_cycles as f64;
    let communication =
        (messages + collectives * depth) * ALPHA + (bytes + collective_bytes) / BETA;
    let efficiency = serial_cycle / (processes as f64 * (busiest + communication));
    println!(
        "{:>5}x{:<5} {:>5} {:>6} {:>6} {:>11.3} {:>12.3} {:>10.3} {:>13.3} {:>9.0} {:>11.1} {:>10.3} {:>9} {:>7} {:>6} {:>10.2}",
        nx,
        ny,
        processes,
        serial_cycles,
        cycles,
        1e3 * serial_cycle,
        1e3 * serial_cycle / processes as f64,
        1e3 * mean,
        1e3 * busiest,
        messages,
        collectives,
        1e3 * communication,
        gathered,
        holding,
        deepest,
        efficiency
    );
    Ok(serde_json::json!({
        "grid": [nx, ny],
        "processes": processes,
        "serial_cycles": serial_cycles,
        "strip_cycles": cycles,
        "serial_ms_per_cycle": 1e3 * serial_cycle,
        "mean_process_compute_ms_per_cycle": 1e3 * mean,
        "busiest_process_compute_ms_per_cycle": 1e3 * busiest,
        "messages_per_cycle_most": messages,
        "message_bytes_per_cycle_most": bytes,
        "collectives_per_cycle": collectives,
        "collective_bytes_per_cycle": collective_bytes,
        "modelled_communication_ms_per_cycle": 1e3 * communication,
        "gathered_cells": gathered,
        "processes_relaxing_gathered_grid": holding,
        "strip_levels": deepest,
        "alpha_s": ALPHA,
        "beta_bytes_per_s": BETA,
        "modelled_efficiency": efficiency,
    }))
}

fn main() {
    let (arguments, json) = arguments("pressure_model");
    let mut cases = Vec::new();
    for arg in arguments {
        let parsed = arg.split_once(':').and_then(|(grid, p)| {
            let (x, y) = grid.split_once('x')?;
            Some((x.parse().ok()?, y.parse().ok()?, p.parse().ok()?))
        });
        match parsed {
            Some(case) => cases.push(case),
            None => {
                eprintln!("pressure_model: {arg:?} is not NXxNY:P (e.g. 1024x1024:48)");
                std::process::exit(2)
            }
        }
    }
    if cases.is_empty() {
        cases = vec![(1024, 1024, 48), (2048, 2048, 48), (4096, 4096, 48)];
    }
    println!(
        "{:>11} {:>5} {:>6} {:>6} {:>11} {:>12} {:>10} {:>13} {:>9} {:>11} {:>10} {:>9} {:>7} {:>6} {:>10}",
        "grid",
        "P",
        "cycles",
        "strip",
        "serial (ms)",
        "serial / P",
        "mean (ms)",
        "busiest (ms)",
        "messages",
        "collectives",
        "comm (ms)",
        "gathered",
        "holding",
        "levels",
        "efficiency"
    );
    let mut figures = Vec::new();
    for (nx, ny, p) in cases {
        match measure(nx, ny, p) {
            Ok(value) => figures.push(value),
            Err(e) => {
                eprintln!("pressure_model: {nx}x{ny} on {p}: {e}");
                std::process::exit(1)
            }
        }
    }
    if let Some(path) = json {
        write_json("pressure_model", &path, &figures);
    }
}
