//! The distributed run against the serial one, on the falling deposit of
//! `xper_domain::fixtures::deposit_world` (240 disks in a box, 1 ms steps).
//!
//! The measure of agreement: the largest distance between a body's position in the two runs.
//! Gauss-Seidel stops at the tolerance, not at the solution, so two serial runs that differ only
//! in the order of the contacts in the sweep (the reversed body numbering) already differ; a
//! distributed run must stay within a small multiple of that serial spread.

use xper_bodies::BodySet;
use xper_domain::fixtures::deposit_world;
use xper_domain::{run_on_threads, DistributedParams, DistributedStepper, RankLoad};
use xper_math::Real;
use xper_nscd::{MoreauJean, World};
use xper_solver::ConvergenceNorm;

const TOLERANCE: Real = 1e-4;

fn start() -> World {
    with_tolerance(TOLERANCE)
}

fn with_tolerance(tolerance: Real) -> World {
    let mut world = deposit_world();
    world.params.nlgs.tolerance = tolerance;
    world.params.nlgs.norm = ConvergenceNorm::Quad;
    world
}

fn serial(mut world: World, steps: u64) -> World {
    let mut stepper = MoreauJean::new();
    for _ in 0..steps {
        stepper.step(&mut world).unwrap();
    }
    world
}

/// The run of `world` on `ranks` thread processes for `steps` steps: the gathered world and
/// each rank's load.
fn distributed(world: &World, ranks: usize, steps: u64, every: u64) -> (World, Vec<RankLoad>) {
    let out = run_on_threads(ranks, |comm| {
        let params = DistributedParams {
            rebalance_every: every,
            ..Default::default()
        };
        let mut stepper = DistributedStepper::new(comm, world.clone(), params);
        for _ in 0..steps {
            stepper.step().unwrap();
        }
        (stepper.gather(), stepper.load())
    });
    let loads = out.iter().map(|o| o.1).collect();
    let world = out.into_iter().find_map(|o| o.0).unwrap();
    (world, loads)
}

fn distance(a: &BodySet, b: &BodySet) -> Real {
    (0..a.len())
        .map(|k| (a.position[k] - b.position[k]).norm())
        .fold(0.0, Real::max)
}

/// The same world with the disks numbered in reverse (walls first as before): the serial
/// sweep then visits the contacts in another order.
fn reversed(world: &World) -> (World, Vec<usize>) {
    let n = world.bodies.len();
    let order: Vec<usize> = (0..3).chain((3..n).rev()).collect();
    let mut set = BodySet::new();
    for &b in &order {
        set.insert(xper_bodies::Body {
            shape: world.bodies.shape[b].clone(),
            position: world.bodies.position[b],
            rotation: world.bodies.rotation[b],
            velocity: world.bodies.velocity[b],
            angular_velocity: world.bodies.angular_velocity[b],
            mass: world.bodies.mass[b],
            inertia: world.bodies.inertia[b],
            group: world.bodies.group[b],
            drives: drives_of(&world.bodies, b),
        });
    }
    let mut out = World::new(set, world.laws.clone(), world.params.clone());
    out.energy = world.energy;
    (out, order)
}

fn drives_of(set: &BodySet, b: usize) -> [xper_bodies::Drive; 3] {
    set.driven
        .iter()
        .find(|(h, _)| h.index() == b)
        .map(|(_, d)| d.clone())
        .unwrap_or([
            xper_bodies::Drive::Free,
            xper_bodies::Drive::Free,
            xper_bodies::Drive::Free,
        ])
}

const STEPS: u64 = 120;

#[test]
fn one_process_is_the_serial_run_bit_for_bit() {
    let plain = start();
    let mut accelerated = plain.clone();
    accelerated.params.nlgs.acceleration = xper_solver::Acceleration::ANDERSON;
    for world in [plain, accelerated] {
        let reference = serial(world.clone(), STEPS);
        let (one, loads) = distributed(&world, 1, STEPS, 50);
        assert_eq!(one.bodies.position, reference.bodies.position);
        assert_eq!(one.bodies.velocity, reference.bodies.velocity);
        assert_eq!(loads[0].shadows, 0);
        assert!((one.energy.dissipated - reference.energy.dissipated).abs() <= 1e-12);
    }
}

/// The serial run of `world` and the distance between it and the serial run with the disks
/// numbered in reverse.
fn serial_and_spread(world: &World, steps: u64) -> (World, Real) {
    let reference = serial(world.clone(), steps);
    let (flipped, order) = reversed(world);
    let flipped = serial(flipped, steps);
    let mut unflipped = reference.bodies.clone();
    for (k, &b) in order.iter().enumerate() {
        unflipped.position[b] = flipped.bodies.position[k];
    }
    let spread = distance(&reference.bodies, &unflipped);
    assert!(
        spread > 0.0 && spread < 1e-3,
        "serial spread {spread:.3e} m"
    );
    (reference, spread)
}

/// The distance to the serial run is of the order of the serial spread and shrinks with the
/// tolerance as the spread does: the runs converge to the same trajectory. Re-partitioning only
/// at the start, so that bodies falling across a horizontal cut migrate.
#[test]
fn two_and_four_processes_agree_with_the_serial_run_within_its_spread() {
    let mut previous: Option<Vec<Real>> = None;
    for tolerance in [1e-4, 1e-6] {
        let world = with_tolerance(tolerance);
        let (reference, spread) = serial_and_spread(&world, STEPS);
        let mut distances = Vec::new();
        for ranks in [2, 4] {
            let (run, loads) = distributed(&world, ranks, STEPS, 1000);
            let d = distance(&run.bodies, &reference.bodies);
            let migrated: u64 = loads.iter().map(|l| l.migrated_in).sum();
            let owned: usize = loads.iter().map(|l| l.bodies).sum();
            eprintln!(
                "tolerance {tolerance:e}, {ranks} ranks: {d:.3e} m from serial (serial spread \
                 {spread:.3e} m), {migrated} migrations, loads {loads:?}"
            );
            assert_eq!(owned, 240, "every disk owned once");
            if ranks == 4 {
                assert!(migrated > 0, "bodies migrated between ranks");
            }
            assert!(
                d <= 10.0 * spread,
                "{ranks} ranks: {d:.3e} m vs spread {spread:.3e} m"
            );
            let dissipated = run.energy.dissipated / reference.energy.dissipated;
            assert!(
                (dissipated - 1.0).abs() < 1e-3,
                "dissipation ratio {dissipated}"
            );
            distances.push(d);
        }
        if let Some(before) = previous.take() {
            for (d, b) in distances.iter().zip(&before) {
                assert!(
                    *d < b / 10.0,
                    "tolerance / 100 but distance {b:.3e} -> {d:.3e} m"
                );
            }
        }
        previous = Some(distances);
    }
}

#[test]
fn resume_on_the_same_count_is_exact_and_on_another_within_the_spread() {
    let world = start();
    let (whole, _) = distributed(&world, 2, STEPS, 30);
    let (middle, _) = distributed(&world, 2, 60, 30);
    let (same, _) = distributed(&middle, 2, STEPS - 60, 30);
    assert_eq!(same.bodies.position, whole.bodies.position);
    let (other, _) = distributed(&middle, 3, STEPS - 60, 30);
    let (_, spread) = serial_and_spread(&world, STEPS);
    let d = distance(&other.bodies, &whole.bodies);
    eprintln!("resumed on 3 processes: {d:.3e} m from the run on 2 (serial spread {spread:.3e} m)");
    assert!(d <= 10.0 * spread, "{d:.3e} m vs spread {spread:.3e} m");
}

#[test]
fn runs_repeat_bit_for_bit() {
    let world = start();
    let (a, _) = distributed(&world, 3, 40, 10);
    let (b, _) = distributed(&world, 3, 40, 10);
    assert_eq!(a.bodies.position, b.bodies.position);
    assert_eq!(a.contacts, b.contacts);
}

/// Regression for neighbour-only migration: a disk that crosses two whole regions in one step
/// lands in a region that is not a neighbour of its owner's; the step that follows must send
/// it there anyway (stage 4 finds it and the migration falls back to every process). Free
/// flight, no contact: the run must be the serial one bit for bit, no body lost.
#[test]
fn a_body_crossing_regions_in_one_step_migrates_to_a_process_that_is_not_a_neighbour() {
    use xper_bodies::Body;
    use xper_math::Vector;
    let mut world = deposit_world();
    let mut bodies = xper_bodies::BodySet::new();
    for k in 0..8 {
        bodies.insert(Body::disk(0.01, 1000.0, Vector::new(k as Real, 0.0)));
    }
    // 2.5 m per 1 ms step along the row, 1 m above it: from region 0 past regions 1 and 2.
    bodies.insert(
        Body::disk(0.01, 1000.0, Vector::new(0.2, 1.0)).with_velocity(Vector::new(2500.0, 0.0)),
    );
    world.bodies = bodies;
    world.contacts.clear();
    world.params.gravity = Vector::zeros();
    let steps = 3;
    let reference = serial(world.clone(), steps);
    let (four, loads) = distributed(&world, 4, steps, 50);
    assert_eq!(four.bodies.position, reference.bodies.position);
    let owned: usize = loads.iter().map(|l| l.bodies).sum();
    assert_eq!(owned, 9, "bodies owned after the run: {loads:?}");
    assert!(loads.iter().map(|l| l.migrated_in).sum::<u64>() >= 2);
}

/// With contacts detected on the predicted configuration `q + h (1 - theta) v`, the halo of
/// shadow bodies grows by the bodies' motion to it. Two disks (r = 1 cm, alert 1 mm, h = 1 ms)
/// 3 cm apart close at 59 m/s: their centres are farther apart than twice the plain halo
/// `2 r_max + alert` = 2.1 cm, so a cut between them leaves each out of the other's halo, yet
/// their predicted gap, 3 cm - 2.95 cm = 0.5 mm, is within the alert distance. The serial run
/// stops them without overlap; two processes must do the same (without the widening they
/// miss the contact, and the disks pass through each other as they do when detected on `q`).
#[test]
fn predicted_detection_finds_a_fast_pair_across_the_cut() {
    use xper_bodies::Body;
    use xper_math::Vector;
    use xper_nscd::Detection;
    let mut world = deposit_world();
    let mut bodies = BodySet::new();
    for x in [-1.0, -0.9] {
        bodies.insert(Body::disk(0.01, 1000.0, Vector::new(x, 0.0)));
    }
    let (gap, speed) = (0.03, 29.5);
    let centre = 0.01 + gap / 2.0;
    bodies.insert(
        Body::disk(0.01, 1000.0, Vector::new(-centre, 0.0)).with_velocity(Vector::new(speed, 0.0)),
    );
    bodies.insert(
        Body::disk(0.01, 1000.0, Vector::new(centre, 0.0)).with_velocity(Vector::new(-speed, 0.0)),
    );
    for x in [0.9, 1.0] {
        bodies.insert(Body::disk(0.01, 1000.0, Vector::new(x, 0.0)));
    }
    world.bodies = bodies;
    world.contacts.clear();
    world.params.gravity = Vector::zeros();
    world.params.nlgs.tolerance = 1e-12;
    // Signed along the row: negative once the disks overlap or have passed each other.
    let pair_gap = |w: &World| w.bodies.position[3].x - w.bodies.position[2].x - 0.02;
    let steps = 4;

    let mut begin = world.clone();
    begin.params.detection = Detection::Begin;
    let missed = serial(begin, steps);
    assert!(pair_gap(&missed) < -0.02, "gap {:e}", pair_gap(&missed));

    world.params.detection = Detection::Predicted;
    let reference = serial(world.clone(), steps);
    assert!(
        pair_gap(&reference).abs() < 1e-12,
        "gap {:e}",
        pair_gap(&reference)
    );
    let (two, loads) = distributed(&world, 2, steps, 50);
    assert_eq!(loads.iter().map(|l| l.bodies).sum::<usize>(), 6);
    assert!(
        loads.iter().all(|l| l.bodies == 3),
        "the cut between the two disks: {loads:?}"
    );
    let d = distance(&two.bodies, &reference.bodies);
    assert!(d < 1e-12, "{d:.3e} m from the serial run");
}
