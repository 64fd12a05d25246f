//! The strip multigrid held whole by one process against the serial multigrid on the same
//! problems: time per solve (best of 5, one run, so the ratio is meaningful), cycles, and the
//! row exchanges and sums a distributed run would make per solve.
//! `cargo run -p xper-poisson --release --example strip_bench [-- NXxNY ...]`.

use std::time::Instant;
use xper_poisson::{
    Boundary, GridShape, Multigrid, MultigridParams, OneStrip, RowLinks, SideCondition,
    StripLayout, StripMultigrid,
};

/// [`OneStrip`] counting the calls a distributed run would turn into messages.
#[derive(Default)]
struct Counting {
    exchanges: usize,
    sums: usize,
    gathers: usize,
}

impl RowLinks for Counting {
    fn exchange_rows(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
    ) -> [Option<Vec<f64>>; 2] {
        self.exchanges += 1;
        OneStrip.exchange_rows(to_below, to_above)
    }
    fn sum(&mut self, values: &mut [f64]) {
        self.sums += 1;
        OneStrip.sum(values)
    }
    fn gather(&mut self, values: &[f64]) -> Vec<f64> {
        self.gathers += 1;
        OneStrip.gather(values)
    }
}

fn random_rhs(n: usize) -> Vec<f64> {
    let mut state = 11u64;
    let mut values: Vec<f64> = (0..n)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
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
    let walls_open_top = Boundary {
        top: SideCondition::Dirichlet,
        ..Boundary::all(SideCondition::Neumann)
    };
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
            ("neumann", Boundary::all(SideCondition::Neumann)),
            ("open top", walls_open_top),
        ] {
            let shape = GridShape {
                nx,
                ny,
                hx: 1.0 / nx as f64,
                hy: 1.0 / nx as f64,
            };
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
            let mut counting = Counting::default();
            let mut strip_cycles = 0;
            let strip_time = best_of(5, || {
                phi.fill(0.0);
                counting = Counting::default();
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
