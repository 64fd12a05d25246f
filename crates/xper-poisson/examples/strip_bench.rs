//! The strip multigrid held whole by one process against the serial multigrid on the same
//! problems: time per solve (best of 5, one run, so the ratio is meaningful), cycles, and the
//! row exchanges and sums a distributed run would make per solve.
//! `cargo run -p xper-poisson --release --example strip_bench [-- NXxNY ...]`.

use std::time::Instant;
use xper_poisson::{
    Boundary, CountingLinks, GridShape, Multigrid, MultigridParams, PoissonSide, StripLayout,
    StripMultigrid,
};

/// A random rhs with its mean removed (a solvable Neumann problem).
fn random_rhs(n: usize) -> Vec<f64> {
    let mut values = xper_poisson::random::random_values(n, 11);
    let mean = values.iter().sum::<f64>() / n as f64;
    values.iter_mut().for_each(|v| *v -= mean);
    values
}

fn best_of<F: FnMut()>(runs: usize, mut f: F) -> f64 {
    (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let mut grids: Vec<(usize, usize)> = std::env::args()
        .skip(1)
        .filter_map(|a| {
            let (x, y) = a.split_once('x')?;
            Some((x.parse().ok()?, y.parse().ok()?))
        })
        .collect();
    if grids.is_empty() {
        grids = vec![(64, 640), (160, 640), (512, 512)];
    }
    println!(
        "{:>11} {:<9} {:>6} {:>6} {:>10} {:>10} {:>6} {:>9} {:>5}",
        "grid",
        "boundary",
        "cycles",
        "strip",
        "serial (s)",
        "strip (s)",
        "ratio",
        "exchanges",
        "sums"
    );
    for (nx, ny) in grids {
        for (name, boundary) in [
            ("neumann", Boundary::all(PoissonSide::Neumann)),
            ("open top", Boundary::open_top()),
        ] {
            let shape = GridShape::square_cells(nx, ny, 1.0);
            let params = MultigridParams {
                relative_tolerance: 1e-8,
                ..MultigridParams::default()
            };
            let rhs = random_rhs(nx * ny);
            let mut phi = vec![0.0; nx * ny];
            let mut serial = Multigrid::new(shape, boundary, params).expect("serial solver");
            let mut serial_cycles = 0;
            let serial_time = best_of(5, || {
                phi.fill(0.0);
                serial_cycles = serial.solve(&rhs, &mut phi).expect("serial solve").cycles;
            });
            let layout = StripLayout::balanced(nx, ny, 1).expect("layout");
            let mut strip =
                StripMultigrid::new(shape, boundary, params, layout, 0).expect("strip solver");
            let mut counting = CountingLinks::default();
            let mut strip_cycles = 0;
            let strip_time = best_of(5, || {
                phi.fill(0.0);
                counting = CountingLinks::default();
                strip_cycles = strip
                    .solve(&mut counting, &rhs, &mut phi)
                    .expect("strip solve")
                    .cycles;
            });
            println!(
                "{:>5}x{:<5} {:<9} {:>6} {:>6} {:>10.5} {:>10.5} {:>6.2} {:>9} {:>5}",
                nx,
                ny,
                name,
                serial_cycles,
                strip_cycles,
                serial_time,
                strip_time,
                strip_time / serial_time,
                counting.exchanges,
                counting.sums + counting.gathers
            );
        }
    }
}
