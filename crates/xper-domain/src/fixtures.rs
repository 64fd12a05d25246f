//! A disk deposit and its velocity problem, shared by the tests and the MPI check binary: the
//! distributed solve is compared with the undivided one on it.

use xper_bodies::{Body, BodySet};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{MoreauJean, RigidContactOperator, RigidProblem, StepParams, World};
use xper_solver::{nlgs, ConvergenceNorm, NlgsParams};

/// SplitMix64 uniform numbers in [-1, 1).
struct Rng(u64);

impl Rng {
    /// The next number.
    fn next(&mut self) -> Real {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        2.0 * ((z >> 11) as Real * (1.0 / (1u64 << 53) as Real)) - 1.0
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
    let mut rng = Rng(7);
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
        nlgs: solver_params(1e-6),
        solver: xper_nscd::VelocitySolver::Nlgs,
        projection_tolerance: Some(1e-6),
    };
    World::new(set, laws, params)
}

/// The deposit of [`deposit_world`] after 250 steps (settled into contact) and the velocity
/// problem of its next step.
pub fn deposit() -> (World, RigidProblem) {
    let mut world = deposit_world();
    let mut stepper = MoreauJean::new();
    for _ in 0..250 {
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
    let mut op = RigidContactOperator {
        bodies: problem.bodies.clone(),
        rows: problem.rows.clone(),
    };
    let mut impulses = problem.impulses.clone();
    let info = nlgs(
        &mut op,
        &problem.mu,
        &problem.shift,
        &mut impulses,
        &solver_params(tolerance),
    )
    .unwrap();
    assert!(info.converged, "serial solve: {info:?}");
    op.bodies.iter().map(|b| b.velocity).collect()
}

/// The spread of the undivided solver itself on `problem`: the largest difference of a
/// translational velocity between `serial` (from [`serial_velocities`]) and a second solve of
/// the same problem with the contacts swept in reverse order. Two solutions within the
/// tolerance differ by this much, so a decomposition is judged against it.
pub fn serial_spread(problem: &RigidProblem, tolerance: Real, serial: &[[Real; 3]]) -> Real {
    let mut reversed = problem.clone();
    reversed.rows.reverse();
    reversed.mu.reverse();
    reversed.shift.reverse();
    reversed.impulses.reverse();
    serial_velocities(&reversed, tolerance)
        .iter()
        .zip(serial)
        .flat_map(|(a, b)| [(a[0] - b[0]).abs(), (a[1] - b[1]).abs()])
        .fold(0.0, Real::max)
}
