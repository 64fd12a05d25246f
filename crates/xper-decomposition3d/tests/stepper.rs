//! The distributed 3D run against the serial one, as `xper-domain/tests/stepper.rs` does in 2D:
//! 150 spheres falling into a box of half-spaces, on thread processes.
//!
//! One process is the serial run bit for bit. With more, Gauss-Seidel visits the contacts in
//! another order and stops at the tolerance, not at the solution, so the runs differ by about
//! as much as two serial runs whose bodies are numbered differently (the serial spread); a
//! distributed run must stay within a small multiple of it.

use xper_bodies::{Body, BodySet};
use xper_decomposition3d::partition::Bisection;
use xper_decomposition3d::rigid::stepper::{DistributedParams, DistributedStepper, RankLoad};
use xper_decomposition3d::run_on_threads;
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, SplitMix64, Vector};
use xper_nscd::{Detection, MoreauJean, StepParams, VelocitySolver, World};
use xper_solver::NlgsParams;

const WALLS: usize = 5;
const STEPS: u64 = 150;

/// The sphere descriptions in `order` (indices into the lattice), after the walls.
fn deposit(order: &[usize]) -> World {
    let (r, p) = (0.01, 0.0215);
    let mut set = BodySet::new();
    let wall = |c: Vector, n: Vector| Body::plane(c, n, [Real::INFINITY; 2]).in_group(1);
    let width = 5.0 * p;
    set.insert(wall(Vector::zeros(), Vector::z()));
    set.insert(wall(Vector::zeros(), Vector::x()));
    set.insert(wall(Vector::new(width, 0.0, 0.0), -Vector::x()));
    set.insert(wall(Vector::zeros(), Vector::y()));
    set.insert(wall(Vector::new(0.0, width, 0.0), -Vector::y()));
    let mut rng = SplitMix64::new(9);
    let lattice: Vec<Body> = (0..150)
        .map(|n| {
            let (i, j, k) = (n % 5, n / 5 % 5, n / 25);
            let jitter = 1e-3 * (rng.next_f64() - 0.5);
            let c = Vector::new(
                p / 2.0 + i as Real * p + jitter,
                p / 2.0 + j as Real * p - jitter,
                p / 2.0 + k as Real * p * 1.2,
            );
            Body::sphere(r * (0.9 + 0.2 * rng.next_f64()), 2600.0, c)
        })
        .collect();
    for &n in order {
        set.insert(lattice[n].clone());
    }
    let mut laws = LawTable::new(2);
    for (a, b, friction) in [(0, 0, 0.3), (0, 1, 0.5)] {
        let law = SignoriniCoulomb {
            friction,
            restitution: 0.0,
        };
        laws.set(a, b, InteractionLaw::SignoriniCoulomb(law));
    }
    let params = StepParams {
        dt: 1e-3,
        theta: 0.5,
        gravity: Vector::new(0.0, 0.0, -9.81),
        alert_distance: 1e-3,
        detection: Detection::Begin,
        nlgs: NlgsParams {
            tolerance: 1e-5,
            ..Default::default()
        },
        solver: VelocitySolver::Nlgs,
        projection_tolerance: Some(1e-6),
    };
    World::new(set, laws, params)
}

fn serial(mut world: World) -> World {
    let mut stepper = MoreauJean::new();
    for _ in 0..STEPS {
        stepper.step(&mut world).unwrap();
    }
    world
}

fn distributed(world: &World, ranks: usize) -> (World, Vec<RankLoad>) {
    let out = run_on_threads(ranks, |comm| {
        let params = DistributedParams {
            rebalance_every: 50,
            ..Default::default()
        };
        let mut stepper = DistributedStepper::new(comm, world.clone(), params);
        for _ in 0..STEPS {
            stepper.step().unwrap();
        }
        (stepper.gather(), stepper.load())
    });
    let loads = out.iter().map(|o| o.1).collect();
    (out.into_iter().find_map(|o| o.0).unwrap(), loads)
}

fn distance(a: &BodySet, b: &BodySet) -> Real {
    (0..a.len())
        .map(|k| (a.position[k] - b.position[k]).norm())
        .fold(0.0, Real::max)
}

#[test]
fn distributed_runs_agree_with_the_serial_run() {
    let forward: Vec<usize> = (0..150).collect();
    let world = deposit(&forward);
    let reference = serial(world.clone());
    // The serial spread: the same spheres numbered in reverse.
    let backward: Vec<usize> = forward.iter().rev().copied().collect();
    let flipped = serial(deposit(&backward));
    let mut unflipped = reference.bodies.clone();
    for (k, &n) in backward.iter().enumerate() {
        unflipped.position[WALLS + n] = flipped.bodies.position[WALLS + k];
    }
    let spread = distance(&reference.bodies, &unflipped);
    assert!(spread > 0.0 && spread < 1e-3, "serial spread {spread:e} m");

    let (one, _) = distributed(&world, 1);
    assert_eq!(one.bodies.position, reference.bodies.position);
    assert_eq!(one.bodies.rotation, reference.bodies.rotation);
    // The contacts, but for the Delassus blocks a gather does not carry (each step refills them).
    assert_eq!(one.contacts.len(), reference.contacts.len());
    for (a, b) in one.contacts.iter().zip(reference.contacts.iter()) {
        let same = (
            a.row.bodies,
            a.row.normal,
            a.row.arms,
            a.key,
            a.gap,
            a.impulse,
        ) == (
            b.row.bodies,
            b.row.normal,
            b.row.arms,
            b.key,
            b.gap,
            b.impulse,
        );
        assert!(same, "{a:?} vs {b:?}");
    }
    for ranks in [2, 3] {
        let (run, loads) = distributed(&world, ranks);
        let owned: usize = loads.iter().map(|l| l.bodies).sum();
        assert_eq!(owned, 150, "every sphere owned once: {loads:?}");
        assert!(loads.iter().any(|l| l.shadows > 0), "{loads:?}");
        let d = distance(&run.bodies, &reference.bodies);
        eprintln!("{ranks} ranks: {d:.3e} m from serial (spread {spread:.3e} m), {loads:?}");
        assert!(
            d <= 10.0 * spread,
            "{ranks} ranks: {d:e} m vs spread {spread:e} m"
        );
        let dissipated = run.energy.dissipated / reference.energy.dissipated;
        assert!(
            (dissipated - 1.0).abs() < 1e-3,
            "dissipation ratio {dissipated}"
        );
    }
    // Space is cut along all three axes when there are enough parts.
    let points: Vec<Vector> = reference.bodies.position[WALLS..].to_vec();
    let cut = Bisection::new(&points, 8);
    assert_eq!(cut.regions().len(), 8);
}
