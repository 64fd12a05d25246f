//! A disk deposit and its velocity problem, shared by the tests and the MPI check binary: the
//! distributed solve is compared with the undivided one on it; and grains in a fluid box.

use xper_bodies::{Body, BodySet};
use xper_fluid::{CoupledState, FluidBoundary, FluidParams, FluidState, MacGrid};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{MoreauJean, RigidContactOperator, RigidProblem, StepParams, World};
use xper_solver::{nlgs, ConvergenceNorm, NlgsParams};

/// SplitMix64 uniform numbers in [-1, 1).
struct Rng(xper_math::SplitMix64);

impl Rng {
    /// The next number.
    fn next(&mut self) -> Real {
        2.0 * self.0.next_f64() - 1.0
    }
}

/// NLGS to a scaled natural-map error of `tolerance`, checked every 5 sweeps.
pub fn solver_params(tolerance: Real) -> NlgsParams {
    NlgsParams {
        tolerance,
        max_iterations: 200_000,
        check_every: 5,
        relaxation: 1.0,
        norm: ConvergenceNorm::NaturalMap,
        ..Default::default()
    }
}

/// 240 disks (radius 1 cm +- 10 %, 1000 kg/m^3, random velocities up to 0.1 m/s) on a lattice in
/// a 0.4 m wide box under gravity, friction 0.3, time step 1 ms: they fall and pile up.
pub fn deposit_world() -> World {
    let width = 0.4;
    let mut set = BodySet::new();
    set.insert(Body::wall(Vector::new(0.0, 0.0), Vector::new(width, 0.0)));
    set.insert(Body::wall(Vector::new(0.0, 1.0), Vector::new(0.0, 0.0)));
    set.insert(Body::wall(Vector::new(width, 0.0), Vector::new(width, 1.0)));
    let mut rng = Rng(xper_math::SplitMix64::new(7));
    for k in 0..240 {
        let (i, j) = (k % 16, k / 16);
        let centre = Vector::new(0.0125 + 0.025 * i as Real, 0.0125 + 0.026 * j as Real);
        set.insert(
            Body::disk(0.01 * (1.0 + 0.1 * rng.next()), 1000.0, centre)
                .with_velocity(Vector::new(0.1 * rng.next(), 0.1 * rng.next())),
        );
    }
    let mut laws = LawTable::new(1);
    laws.set(
        0,
        0,
        InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
            friction: 0.3,
            restitution: 0.0,
        }),
    );
    let params = StepParams {
        dt: 1e-3,
        theta: 0.5,
        gravity: Vector::new(0.0, -9.81),
        alert_distance: 1e-3,
        detection: Default::default(),
        nlgs: solver_params(1e-6),
        solver: xper_nscd::VelocitySolver::Nlgs,
        projection_tolerance: Some(1e-6),
    };
    World::new(set, laws, params)
}

/// The deposit of [`deposit_world`] after 243 steps (settled into contact) and the velocity
/// problem of its next step, which the undivided NLGS solves to 1e-7 in about 2,000 sweeps
/// (the problems of some neighbouring steps make it cycle above that tolerance).
pub fn deposit() -> (World, RigidProblem) {
    let mut world = deposit_world();
    let mut stepper = MoreauJean::new();
    for _ in 0..243 {
        stepper.step(&mut world).unwrap();
    }
    let problem = stepper.next_rigid_problem(&world);
    (world, problem)
}

/// Velocities after the undivided NLGS solve.
///
/// # Panics
/// If the solve does not converge (the fixture is built so that it does).
pub fn serial_velocities(problem: &RigidProblem, tolerance: Real) -> Vec<[Real; 3]> {
    solve_velocities(problem, tolerance)
        .unwrap_or_else(|| panic!("serial solve of the fixture did not converge"))
}

/// Velocities after the undivided NLGS solve, `None` when it does not converge.
fn solve_velocities(problem: &RigidProblem, tolerance: Real) -> Option<Vec<[Real; 3]>> {
    let mut op = RigidContactOperator {
        bodies: problem.bodies.clone(),
        rows: problem.rows.clone(),
        cell: None,
    };
    let mut impulses = problem.impulses.clone();
    let info = nlgs(
        &mut op,
        &problem.mu,
        &problem.shift,
        &mut impulses,
        &solver_params(tolerance),
    )
    .ok()?;
    info.converged
        .then(|| op.bodies.iter().map(|b| b.velocity).collect())
}

/// How far a decomposed solve may land from the undivided one, in units of
/// [`serial_spread`]: the decomposed solve is another iteration (Jacobi across subdomains), so
/// it reaches another point of the set of solutions within the tolerance, whose extent five
/// serial sweep orders only sample; a wrong exchange misses by the size of the velocities
/// themselves, orders of magnitude more.
pub const SPREAD_MARGIN: Real = 4.0;

/// The spread of the undivided solver itself on `problem`: the largest difference of a
/// translational velocity between `serial` (from [`serial_velocities`]) and solves of the
/// same problem with the contacts swept in other orders (reversed, odd after even, halves
/// swapped, two shuffles; an order whose solve does not converge is left out). Solutions
/// within the tolerance differ by this much, so a decomposition is judged against it.
///
/// # Panics
/// If no other order converges.
pub fn serial_spread(problem: &RigidProblem, tolerance: Real, serial: &[[Real; 3]]) -> Real {
    let n = problem.rows.len();
    let shuffled = |seed: u64| {
        let mut order: Vec<usize> = (0..n).collect();
        let mut rng = Rng(xper_math::SplitMix64::new(seed));
        for k in (1..n).rev() {
            let j = ((rng.next() + 1.0) / 2.0 * (k + 1) as Real) as usize;
            order.swap(k, j.min(k));
        }
        order
    };
    let orders: Vec<Vec<usize>> = vec![
        (0..n).rev().collect(),
        (0..n).step_by(2).chain((1..n).step_by(2)).collect(),
        (n / 2..n).chain(0..n / 2).collect(),
        shuffled(11),
        shuffled(12),
    ];
    let spreads: Vec<Real> = (orders.iter())
        .filter_map(|order| {
            let mut p = problem.clone();
            p.rows = order.iter().map(|&a| problem.rows[a]).collect();
            p.mu = order.iter().map(|&a| problem.mu[a]).collect();
            p.shift = order.iter().map(|&a| problem.shift[a]).collect();
            p.impulses = order.iter().map(|&a| problem.impulses[a]).collect();
            let velocities = solve_velocities(&p, tolerance)?;
            let diff = (velocities.iter().zip(serial))
                .flat_map(|(a, b)| [(a[0] - b[0]).abs(), (a[1] - b[1]).abs()])
                .fold(0.0, Real::max);
            Some(diff)
        })
        .collect();
    assert!(!spreads.is_empty(), "no other sweep order converges");
    spreads.into_iter().fold(0.0, Real::max)
}

/// Grains of 1200 kg/m^3, disks of the given `(radius, centre)` (m), at rest in water-like
/// fluid at rest (1000 kg/m^3, 4e-3 Pa s) filling the closed box `grid`, under gravity;
/// steps of at most 0.1 ms, the pressure solved to `pressure_tolerance`.
pub fn grains_in_a_box(
    grid: MacGrid,
    disks: &[(Real, Vector)],
    pressure_tolerance: Real,
) -> (FluidParams, CoupledState) {
    let mut params = FluidParams::new(1000.0, 4e-3, FluidBoundary::closed_box());
    params.dt_max = 1e-4;
    params.pressure_tolerance = pressure_tolerance;
    let mut bodies = BodySet::new();
    for &(radius, centre) in disks {
        bodies.insert(Body::disk(radius, 1200.0, centre));
    }
    let world_params = StepParams {
        dt: 1e-4,
        theta: 0.5,
        gravity: Vector::new(0.0, -9.81),
        alert_distance: 1e-5,
        detection: Default::default(),
        nlgs: Default::default(),
        solver: xper_nscd::VelocitySolver::Nlgs,
        projection_tolerance: None,
    };
    let state = CoupledState {
        fluid: FluidState::at_rest(grid, &params.boundary),
        world: World::new(bodies, LawTable::new(1), world_params),
    };
    (params, state)
}
