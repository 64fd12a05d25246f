//! `mpirun -np N xper-domain-sync-ceiling --out DIR [--cells NX NY] [--sweeps K] [--steps S]`:
//! the parallel efficiency this machine allows a code that synchronises as often as the fluid
//! solver did before the pressure multigrid's deep ghost rows (112 exchanges per step by
//! default; `--sweeps` sets it) and has no imbalance and no other communication cost.
//!
//! The work is Jacobi sweeps of the 5-point Laplacian, `u_new[i,j] = (u[i-1,j] + u[i+1,j] +
//! u[i,j-1] + u[i,j+1]) / 4`, over a hierarchy of grids (each level halves both sizes of a
//! strip, as a multigrid cycle visits them; the serial run's levels are the strips' stacked),
//! the rows split into equal strips, one halo row exchanged with
//! each neighbour after every sweep. One step is `K` sweeps on every level. The processes run
//! `S` steps together; then process 0 runs the same `S` steps on the whole grid alone while the
//! others wait, as `xper run --compare-serial` does. The efficiency is
//! `T_serial / (N T_distributed)`: with equal strips and a few kilobytes per message, what it
//! loses below 1 is what the machine takes (processes descheduled, cores of unequal speed), the
//! ceiling of any code with this pattern of synchronisation. Written to `DIR/summary.json` in
//! the form of `xper run`'s summary, so `benches/scaling.sh` tabulates it beside the scenes.

use std::time::Instant;
use xper_domain::{Communicator, MpiCommunicator};

/// A strip of `rows` rows of `nx` cells, with one halo row below and one above.
struct Strip {
    nx: usize,
    rows: usize,
    u: Vec<f64>,
    scratch: Vec<f64>,
}

impl Strip {
    fn new(nx: usize, rows: usize, seed: usize) -> Self {
        let u = (0..nx * (rows + 2))
            .map(|k| ((k * 7919 + seed * 104_729) % 1000) as f64 * 1e-3)
            .collect();
        Strip {
            nx,
            rows,
            u,
            scratch: vec![0.0; nx * (rows + 2)],
        }
    }

    /// One Jacobi sweep over the strip's own rows (the halo rows are read, the side columns
    /// are held fixed).
    fn sweep(&mut self) {
        let nx = self.nx;
        for r in 1..=self.rows {
            let (below, row, above) = (
                &self.u[(r - 1) * nx..],
                &self.u[r * nx..],
                &self.u[(r + 1) * nx..],
            );
            let out = &mut self.scratch[r * nx..(r + 1) * nx];
            out[0] = row[0];
            out[nx - 1] = row[nx - 1];
            for i in 1..nx - 1 {
                out[i] = 0.25 * (row[i - 1] + row[i + 1] + below[i] + above[i]);
            }
        }
        let own = nx..(self.rows + 1) * nx;
        self.u[own.clone()].copy_from_slice(&self.scratch[own]);
    }

    /// Sends the first and last own rows to the neighbours below and above and stores theirs
    /// in the halo rows.
    fn exchange_halos(&mut self, comm: &dyn Communicator) {
        let (rank, size, nx) = (comm.rank(), comm.size(), self.nx);
        let mut sends = Vec::new();
        let mut sources = Vec::new();
        if rank > 0 {
            sends.push((rank - 1, self.u[nx..2 * nx].to_vec()));
            sources.push(rank - 1);
        }
        if rank + 1 < size {
            sends.push((
                rank + 1,
                self.u[self.rows * nx..(self.rows + 1) * nx].to_vec(),
            ));
            sources.push(rank + 1);
        }
        let received = comm.exchange(&sends, &sources);
        for (source, row) in sources.iter().zip(received) {
            let halo = if *source < rank { 0 } else { self.rows + 1 };
            self.u[halo * nx..(halo + 1) * nx].copy_from_slice(&row);
        }
    }
}

/// The sizes `(columns, rows)` of the levels of a strip of `rows` rows of `nx` columns: each
/// halves both, down to 8 of each.
fn level_sizes(nx: usize, rows: usize) -> Vec<(usize, usize)> {
    (0..)
        .map(|l| (nx >> l, rows >> l))
        .take_while(|&(x, r)| r >= 8 && x >= 8)
        .collect()
}

/// The grids of the strips' levels, each with `strips` times a strip's rows (1 for a strip,
/// the number of processes for the whole grid relaxed by one process), so that the serial run
/// does the same work as the strips together.
fn levels(sizes: &[(usize, usize)], strips: usize, seed: usize) -> Vec<Strip> {
    sizes
        .iter()
        .map(|&(x, r)| Strip::new(x, strips * r, seed))
        .collect()
}

/// Runs `steps` steps of `sweeps` sweeps per level; exchanges halos when `comm` is given.
fn run(grids: &mut [Strip], steps: usize, sweeps: usize, comm: Option<&dyn Communicator>) -> f64 {
    let start = Instant::now();
    for _ in 0..steps {
        for grid in grids.iter_mut() {
            for _ in 0..sweeps {
                grid.sweep();
                if let Some(comm) = comm {
                    grid.exchange_halos(comm);
                }
            }
        }
    }
    start.elapsed().as_secs_f64()
}

fn main() {
    let Some(comm) = MpiCommunicator::init() else {
        eprintln!("xper-domain-sync-ceiling: MPI was already initialised");
        std::process::exit(2);
    };
    let (mut nx, mut ny, mut sweeps, mut steps, mut out) = (512, 1024, 16, 200, None);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut number = |what: &str| -> usize {
            args.next()
                .and_then(|v| v.parse::<usize>().ok())
                .filter(|v| *v > 0)
                .unwrap_or_else(|| comm.abort(&format!("{arg} needs {what}"), 2))
        };
        match arg.as_str() {
            "--cells" => (nx, ny) = (number("two positive counts"), number("two positive counts")),
            "--sweeps" => sweeps = number("a positive count"),
            "--steps" => steps = number("a positive count"),
            "--out" => out = args.next(),
            _ => comm.abort(
                &format!("unknown argument {arg:?} (known: --out DIR, --cells NX NY, --sweeps K, --steps S)"),
                2,
            ),
        }
    }
    let Some(out) = out else {
        comm.abort("--out DIR is required", 2)
    };
    let (rank, size) = (comm.rank(), comm.size());
    if ny % size != 0 || ny / size < 8 || nx < 8 {
        comm.abort(
            &format!("{nx} x {ny} cells do not split into {size} strips of at least 8 x 8"),
            2,
        );
    }
    let sizes = level_sizes(nx, ny / size);
    let mut grids = levels(&sizes, 1, rank);
    let mut barrier = [0.0];
    comm.all_reduce_sum(&mut barrier);
    let before = comm.stats();
    let distributed = run(&mut grids, steps, sweeps, Some(&comm));
    let mut wall = [distributed];
    comm.all_reduce_max(&mut wall);
    let traffic = comm.stats().since(&before);
    let serial = if rank == 0 {
        let mut whole = levels(&sizes, size, 0);
        run(&mut whole, steps, sweeps, None)
    } else {
        0.0
    };
    let mut serial_wall = [serial];
    comm.all_reduce_sum(&mut serial_wall);
    let per_rank = comm.all_gather(&[
        traffic.messages as f64,
        traffic.bytes as f64,
        traffic.time.as_secs_f64(),
    ]);
    if rank != 0 {
        return;
    }
    let (t1, tn) = (serial_wall[0], wall[0]);
    let ranks: Vec<String> = per_rank
        .iter()
        .map(|r| {
            format!(
                "{{\"messages\": {}, \"bytes\": {}, \"communication_share\": {:.4}}}",
                r[0],
                r[1],
                r[2] / tn
            )
        })
        .collect();
    let summary = format!(
        "{{\n \"scene\": \"sync_ceiling\",\n \"cells\": [{nx}, {ny}],\n \"sweeps_per_level\": {sweeps},\n \
         \"levels\": {},\n \"processes\": {size},\n \"steps\": {steps},\n \"wall_time_s\": {tn},\n \
         \"serial_comparison\": {{\"serial_wall_time_s\": {t1}, \"distributed_wall_time_s\": {tn}, \
         \"speed_up\": {}, \"efficiency\": {}}},\n \"ranks\": [{}]\n}}\n",
        grids.len(),
        t1 / tn,
        t1 / (size as f64 * tn),
        ranks.join(", ")
    );
    let dir = std::path::Path::new(&out);
    let written = std::fs::create_dir_all(dir).and_then(|_| {
        let tmp = dir.join("summary.json.tmp");
        std::fs::write(&tmp, &summary)?;
        std::fs::rename(&tmp, dir.join("summary.json"))
    });
    if let Err(e) = written {
        comm.abort(&format!("cannot write {}/summary.json: {e}", out), 1);
    }
    println!(
        "sync ceiling: {size} processes, {steps} steps, serial {t1:.2} s, distributed {tn:.2} s, efficiency {:.3}",
        t1 / (size as f64 * tn)
    );
}
