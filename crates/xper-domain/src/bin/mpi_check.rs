//! `mpirun -np N xper-domain-mpi-check [--tolerance T] [--anderson] [--fail-on-rank R]
//! [--pressure]`: the distributed contact solve of the deposit fixture over MPI (with
//! `--anderson`, its sweeps Anderson-accelerated), compared on every rank with the undivided
//! plain solve. Prints one line per rank and exits 0 when every body's velocity is within
//! `SPREAD_MARGIN` times the spread of the solver (undivided solves with other sweep orders,
//! see `serial_spread`); 1 otherwise. With `--fail-on-rank R`, rank R panics before the
//! solve, which must end the whole job (the panic hook's MPI_Abort).
//! With `--pressure`, instead, the strip multigrid of a 512 x 64 grid (agglomerated on 4
//! processes: its 4-row strips of 128 x 16 re-cut into 2) against the same solve on one
//! strip: every rank's rows must be the same bits.

use xper_domain::fixtures::{
    deposit, serial_spread, serial_velocities, solver_params, SPREAD_MARGIN,
};
use xper_domain::MpiCommunicator;
use xper_domain::{distributed_nlgs, split_problem, Bisection, Communicator, InterfaceMap};

fn main() {
    let Some(comm) = MpiCommunicator::init() else {
        eprintln!("xper-domain-mpi-check: MPI was already initialised");
        std::process::exit(2);
    };
    let (mut tolerance, mut fail_on, mut anderson, mut pressure) = (1e-7, None, false, false);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--anderson" {
            anderson = true;
            continue;
        }
        if arg == "--pressure" {
            pressure = true;
            continue;
        }
        let value = args.next();
        let bad =
            |what: &str| -> ! { comm.abort(&format!("{arg} needs {what}, got {value:?}"), 2) };
        match arg.as_str() {
            "--tolerance" => {
                tolerance = value
                    .as_deref()
                    .and_then(|v| v.parse::<f64>().ok())
                    .filter(|t| t.is_finite() && *t > 0.0)
                    .unwrap_or_else(|| bad("a positive number"))
            }
            "--fail-on-rank" => {
                fail_on = Some(
                    value
                        .as_deref()
                        .and_then(|v| v.parse::<usize>().ok())
                        .unwrap_or_else(|| bad("a rank number")),
                )
            }
            _ => comm.abort(
                &format!(
                    "unknown argument {arg:?} (known: --tolerance T, --anderson, --fail-on-rank R, --pressure)"
                ),
                2,
            ),
        }
    }
    if pressure {
        if pressure_matches_one_strip(&comm) {
            return;
        }
        std::process::exit(1);
    }
    let (rank, size) = (comm.rank(), comm.size());
    let (world, problem) = deposit();
    let serial = serial_velocities(&problem, tolerance);
    let spread = serial_spread(&problem, tolerance, &serial);
    if fail_on == Some(rank) {
        panic!("failure injected on rank {rank} (--fail-on-rank)");
    }
    let owners = Bisection::new(&world.bodies.position, size).assign(&world.bodies.position);
    let local = split_problem(&problem, &owners, rank as u32);
    let interface = InterfaceMap::build(
        &comm,
        &local.global_ids,
        &local.owners,
        &local.shared(),
        None,
    );
    let mut op = local.operator(&interface);
    let mut impulses = local.problem.impulses.clone();
    let start = std::time::Instant::now();
    let info = distributed_nlgs(
        &comm,
        &mut op,
        &interface,
        &local.problem.mu,
        &local.problem.shift,
        &[],
        &mut impulses,
        &xper_solver::NlgsParams {
            acceleration: if anderson {
                xper_solver::Acceleration::ANDERSON
            } else {
                xper_solver::Acceleration::None
            },
            ..solver_params(tolerance)
        },
    )
    .unwrap_or_else(|e| comm.abort(&format!("distributed solve: {e}"), 1));
    let solve_seconds = start.elapsed().as_secs_f64();
    let worst = local
        .global_ids
        .iter()
        .zip(&op.bodies)
        .flat_map(|(&id, b)| {
            let s = serial[id as usize];
            [(b.velocity[0] - s[0]).abs(), (b.velocity[1] - s[1]).abs()]
        })
        .fold(0.0, f64::max);
    let stats = comm.stats();
    let ok = info.converged && worst <= SPREAD_MARGIN * spread;
    println!(
        "rank {rank} of {size}: {} contacts, {} shared bodies, {} sweeps, converged {}, \
         largest velocity difference {worst:.2e} (serial spread {spread:.2e}), \
         solve {solve_seconds:.3} s ({:.2} us per sweep), {} messages, {} bytes, \
         {:.3} s communicating: {}",
        local.problem.rows.len(),
        interface.shared_count(),
        info.iterations,
        info.converged,
        1e6 * solve_seconds / info.iterations.max(1) as f64,
        stats.messages,
        stats.bytes,
        stats.time.as_secs_f64(),
        if ok { "ok" } else { "MISMATCH" }
    );
    let mut failures = [if ok { 0.0 } else { 1.0 }];
    comm.all_reduce_sum(&mut failures);
    if failures[0] > 0.0 {
        std::process::exit(1);
    }
}

/// The `--pressure` check: whether every rank's rows of four V(2,1) cycles over MPI are the
/// bits of the one-strip solve (the same answer on every rank).
fn pressure_matches_one_strip(comm: &MpiCommunicator) -> bool {
    use xper_poisson::{Boundary, GridShape, MultigridParams, OneStrip, StripLayout};
    let (rank, size) = (comm.rank(), comm.size());
    let (nx, ny) = (512, 64);
    let shape = GridShape::square_cells(nx, ny, 1.0);
    let boundary = Boundary::open_top();
    let params = MultigridParams {
        relative_tolerance: 1e-30,
        max_cycles: 4,
        ..MultigridParams::default()
    };
    let rhs = xper_poisson::random::random_values(nx * ny, 7);
    let solve = |layout: StripLayout, strip: usize, links: &mut dyn xper_poisson::RowLinks| {
        let rows = layout.rows(strip);
        let mut solver = xper_poisson::StripMultigrid::new(shape, boundary, params, layout, strip)
            .unwrap_or_else(|e| comm.abort(&format!("strip multigrid: {e}"), 1));
        let mut phi = vec![0.0; nx * rows.len()];
        let _ = solver.solve(links, &rhs[nx * rows.start..nx * rows.end], &mut phi);
        (phi, solver.gathered_cells(), rows)
    };
    let (whole, _, _) = solve(StripLayout::balanced(nx, ny, 1).unwrap(), 0, &mut OneStrip);
    let layout = StripLayout::balanced(nx, ny, size)
        .unwrap_or_else(|e| comm.abort(&format!("strips: {e}"), 2));
    let mut links = xper_domain::halo::StripComm {
        comm,
        neighbours: xper_domain::halo::strip_neighbours(rank, size, false),
    };
    let (mine, gathered, rows) = solve(layout, rank, &mut links);
    let differing = (mine.iter().zip(&whole[nx * rows.start..nx * rows.end]))
        .filter(|(a, b)| a.to_bits() != b.to_bits())
        .count();
    let ok = differing == 0;
    println!(
        "rank {rank} of {size}: pressure rows {rows:?}, gathered grid {gathered} cells, \
         {differing} values differ from one strip: {}",
        if ok { "ok" } else { "MISMATCH" }
    );
    let mut failures = [if ok { 0.0 } else { 1.0 }];
    comm.all_reduce_sum(&mut failures);
    failures[0] == 0.0
}
