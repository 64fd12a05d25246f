//! Prints the multigrid figures of `xper_bench::poisson` for the acceptance grids:
//! `cargo run -p xper-bench --release --example poisson_bench [-- nx ny]`.

use xper_bench::poisson::{run_benchmark_with, BenchFigures};
use xper_poisson::{Boundary, CycleType, MultigridParams, PoissonSide};

fn families() -> [(&'static str, Boundary); 3] {
    [
        ("neumann", Boundary::all(PoissonSide::Neumann)),
        ("periodic", Boundary::all(PoissonSide::Periodic)),
        ("mixed", Boundary::open_top()),
    ]
}

fn print(name: &str, f: &BenchFigures) {
    println!(
        "{:>5} x {:<5} {:<9} {:>2} {:>5} {:>3} {:>7.4} {:>7.4} {:>6.2} {:>6.2} {:>9.3e} {:>9.4} {:>9.3e} {:>7.3}",
        f.cells[0],
        f.cells[1],
        name,
        f.levels,
        f.coarsest_cells,
        f.cycles,
        f.convergence_factor,
        f.asymptotic_factor,
        f.work_units_per_decade,
        f.timed_work_units_per_decade,
        f.smoother_cells_per_second,
        f.solve_seconds,
        f.solve_cells_per_second,
        f.setup_seconds,
    );
}

fn main() {
    // Arguments: grids as `NXxNY` (default: the acceptance grids) and parameters as
    // `pre=2 post=1 omega=1.15 cycle=V coarsest=64`.
    let mut grids = Vec::new();
    let mut params = MultigridParams::default();
    for arg in std::env::args().skip(1) {
        let number = |s: &str| s.parse::<f64>().expect("a number");
        match arg.split_once(['=', 'x']) {
            Some(("pre", v)) => params.pre_smoothing = number(v) as u32,
            Some(("post", v)) => params.post_smoothing = number(v) as u32,
            Some(("omega", v)) => params.omega = number(v),
            Some(("coarsest", v)) => params.coarsest_cells = number(v) as usize,
            Some(("cycle", v)) => {
                params.cycle = match v {
                    "W" => CycleType::W,
                    "F" => CycleType::F,
                    _ => CycleType::V,
                }
            }
            Some((nx, ny)) => grids.push((number(nx) as usize, number(ny) as usize)),
            None => panic!("unknown argument {arg}"),
        }
    }
    if grids.is_empty() {
        grids = vec![
            (512, 512),
            (1024, 1024),
            (64, 640),
            (82, 440),
            (80, 320),
            (100, 37),
        ];
    }
    println!("{params:?}");
    println!(
        "{:>13} {:<9} {:>2} {:>5} {:>3} {:>7} {:>7} {:>6} {:>6} {:>9} {:>9} {:>9} {:>7}",
        "grid",
        "boundary",
        "L",
        "Nc",
        "cyc",
        "factor",
        "asympt",
        "WU/dec",
        "tWU/d",
        "sweep c/s",
        "solve s",
        "solve c/s",
        "setup s"
    );
    for (nx, ny) in grids {
        for (name, boundary) in families() {
            print(name, &run_benchmark_with(nx, ny, boundary, params));
        }
    }
}
