//! Periodic cells of rigid bodies (`xper_nscd::cell`), each against an exact answer or an
//! independent simulation: a body crossing a side, a lattice in a cell against the same
//! lattice tiled into a larger free block, the energy budget of a sheared cell, the wrap of a
//! Lees-Edwards cell, and a cell under an imposed pressure against the granular stress.

use xper_bodies::{Body, BodySet, TimeFunction};
use xper_geometry::Lattice;
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, SplitMix64, Tensor, Vector};
use xper_nscd::micro::{measure, VolumeSource};
use xper_nscd::{CellLoad, MoreauJean, PeriodicCell, StepParams, World};
use xper_solver::NlgsParams;

fn laws(friction: Real, restitution: Real) -> LawTable {
    let mut laws = LawTable::new(1);
    laws.set(
        0,
        0,
        InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
            friction,
            restitution,
        }),
    );
    laws
}

fn params(dt: Real) -> StepParams {
    StepParams {
        dt,
        theta: 0.5,
        gravity: Vector::zeros(),
        alert_distance: 1e-3,
        detection: Default::default(),
        nlgs: NlgsParams {
            tolerance: 1e-10,
            max_iterations: 20_000,
            ..Default::default()
        },
        solver: Default::default(),
        projection_tolerance: None,
    }
}

fn lattice(lx: Real, ly: Real) -> Lattice {
    Lattice {
        origin: Vector::zeros(),
        edges: Tensor::new(lx, 0.0, 0.0, ly),
        periodic: [true, true],
        relabels: 0,
    }
}

fn at_rest() -> [[CellLoad; 2]; 2] {
    Default::default()
}

#[test]
fn a_disk_leaving_a_side_re_enters_with_the_same_velocity() {
    let mut bodies = BodySet::new();
    let v = Vector::new(1.3, -0.7);
    bodies.insert(Body::disk(0.05, 1000.0, Vector::new(0.9, 0.2)).with_velocity(v));
    let cell = PeriodicCell::new(lattice(1.0, 0.5), at_rest(), 1.0, 1);
    let mut world = World::new(bodies, laws(0.3, 0.0), params(1e-3)).with_cell(cell);
    let mut stepper = MoreauJean::new();
    let mut crossed = [false; 2];
    for step in 1..=400 {
        stepper.step(&mut world).unwrap();
        let t = step as Real * 1e-3;
        let free = Vector::new(0.9, 0.2) + v * t;
        let expected = Vector::new(free.x.rem_euclid(1.0), free.y.rem_euclid(0.5));
        let p = world.bodies.position[0];
        assert!(
            (p - expected).norm() < 1e-12,
            "step {step}: {p:?} vs {expected:?}"
        );
        assert_eq!(world.bodies.velocity[0], v, "step {step}");
        crossed[0] |= free.x >= 1.0;
        crossed[1] |= free.y < 0.0;
    }
    assert_eq!(crossed, [true, true]);
    let wraps = world.cell.as_ref().unwrap().wraps[0];
    assert_eq!(wraps, [1, -1]);
    assert!(world.energy_error().abs() < 1e-12);
}

#[test]
fn a_cell_periodic_along_x_only_wraps_along_x_only() {
    let mut bodies = BodySet::new();
    let v = Vector::new(2.0, 0.5);
    bodies.insert(Body::disk(0.05, 1000.0, Vector::new(0.5, 0.4)).with_velocity(v));
    let mut lattice = lattice(1.0, 0.5);
    lattice.periodic = [true, false];
    let cell = PeriodicCell::new(lattice, at_rest(), 1.0, 1);
    let mut world = World::new(bodies, laws(0.3, 0.0), params(1e-3)).with_cell(cell);
    let mut stepper = MoreauJean::new();
    for _ in 0..300 {
        stepper.step(&mut world).unwrap();
    }
    // At 0.3 s: x = 0.5 + 0.6 wrapped to 0.1; y = 0.55, past the top, not wrapped.
    let p = world.bodies.position[0];
    assert!((p - Vector::new(0.1, 0.55)).norm() < 1e-12, "{p:?}");
    assert_eq!(world.cell.as_ref().unwrap().wraps[0], [1, 0]);
}

#[test]
fn bodies_added_between_steps_join_the_cell() {
    let bodies = random_disks(30, 1.0, 0.04, 5);
    let cell = PeriodicCell::new(lattice(1.0, 1.0), at_rest(), 1.0, 30);
    let mut world = World::new(bodies, laws(0.3, 0.0), params(1e-3)).with_cell(cell);
    let mut stepper = MoreauJean::new();
    stepper.step(&mut world).unwrap();
    // Near a side, moving out of the cell: it meets the images and is wrapped.
    let v = Vector::new(-1.0, 0.0);
    world
        .bodies
        .insert(Body::disk(0.03, 1000.0, Vector::new(0.001, 0.5)).with_velocity(v));
    for _ in 0..10 {
        stepper.step(&mut world).unwrap();
    }
    let last = world.bodies.len() - 1;
    assert_eq!(world.cell.as_ref().unwrap().wraps[last], [-1, 0]);
    assert!(world.bodies.position[last].x > 0.9);
}

/// `n x n` disks on a square lattice of spacing `a` with random velocities, radius below
/// `a / 2`: they collide in pairs.
fn gas(n: usize, a: Real, seed: u64) -> Vec<(Vector, Vector)> {
    let mut rng = SplitMix64::new(seed);
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let p = Vector::new((i as Real + 0.5) * a, (j as Real + 0.5) * a);
            let v = Vector::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5);
            out.push((p, v));
        }
    }
    out
}

#[test]
fn a_lattice_in_a_cell_matches_the_inner_tile_of_a_larger_free_block() {
    let (n, a, r, dt) = (5usize, 0.1, 0.042, 2e-4);
    let tile = gas(n, a, 7);
    let l = n as Real * a;
    let mut bodies = BodySet::new();
    for (p, v) in &tile {
        bodies.insert(Body::disk(r, 1000.0, *p).with_velocity(*v));
    }
    let cell = PeriodicCell::new(lattice(l, l), at_rest(), 1.0, tile.len());
    let mut periodic = World::new(bodies, laws(0.4, 0.0), params(dt)).with_cell(cell);
    // The same tile repeated 5 x 5 times, without a cell: its middle tile sees periodic
    // surroundings until the free edges' influence arrives, two tiles later.
    let mut bodies = BodySet::new();
    let tiles = 5;
    for tj in 0..tiles {
        for ti in 0..tiles {
            let shift = Vector::new(ti as Real * l, tj as Real * l);
            for (p, v) in &tile {
                bodies.insert(Body::disk(r, 1000.0, p + shift).with_velocity(*v));
            }
        }
    }
    let mut block = World::new(bodies, laws(0.4, 0.0), params(dt));
    let middle = (tiles / 2) * tiles + tiles / 2;
    let (mut a_steps, mut b_steps) = (MoreauJean::new(), MoreauJean::new());
    let mut impacts = 0;
    for _ in 0..1000 {
        let ra = a_steps.step(&mut periodic).unwrap();
        b_steps.step(&mut block).unwrap();
        impacts += ra.active;
    }
    assert!(
        impacts > 200,
        "the disks collided only {impacts} contact-steps"
    );
    let cell = periodic.cell.as_ref().unwrap();
    let mut worst: Real = 0.0;
    for k in 0..tile.len() {
        let w = cell.wraps[k];
        let unwrapped = periodic.bodies.position[k] + Vector::new(w[0] as Real, w[1] as Real) * l;
        let inner = middle * tile.len() + k;
        let shift = Vector::new((tiles / 2) as Real * l, (tiles / 2) as Real * l);
        worst = worst.max((unwrapped + shift - block.bodies.position[inner]).norm());
        let dv = periodic.bodies.velocity[k] - block.bodies.velocity[inner];
        worst = worst.max(dv.norm() * dt);
    }
    assert!(
        worst < 1e-9,
        "the cell and the inner tile differ by {worst:e} m"
    );
}

/// Disks at random in a cell `l x l`, without overlap.
fn random_disks(count: usize, l: Real, r: Real, seed: u64) -> BodySet {
    let mut rng = SplitMix64::new(seed);
    let mut placed: Vec<Vector> = Vec::new();
    let mut bodies = BodySet::new();
    while placed.len() < count {
        let p = Vector::new(rng.next_f64() * l, rng.next_f64() * l);
        let clear = placed.iter().all(|q| {
            let mut d = p - q;
            d.x -= l * (d.x / l).round();
            d.y -= l * (d.y / l).round();
            d.norm() > 2.2 * r
        });
        if clear {
            let v = Vector::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5);
            bodies.insert(Body::disk(r * (0.9 + 0.2 * rng.next_f64()), 1000.0, p).with_velocity(v));
            placed.push(p);
        }
    }
    bodies
}

#[test]
fn a_sheared_cell_balances_its_energy_and_reduces_its_edges() {
    let mut loads = at_rest();
    loads[0][1] = CellLoad::Rate(TimeFunction::Constant(2.0));
    let bodies = random_disks(60, 1.0, 0.04, 3);
    let cell = PeriodicCell::new(lattice(1.0, 1.0), loads, 1.0, 60);
    let mut world = World::new(bodies, laws(0.5, 0.0), params(1e-3)).with_cell(cell);
    // Relative speeds reach 3 m/s: pairs are found 3 steps ahead.
    world.params.alert_distance = 0.01;
    let mut stepper = MoreauJean::new();
    let mut deepest: Real = 0.0;
    for _ in 0..500 {
        deepest = deepest.max(stepper.step(&mut world).unwrap().max_overlap);
    }
    // The contacts with images move with the shear: solved without it, disks overlap by 3 cm.
    assert!(deepest < 1e-5, "overlap {deepest:e} m");
    let cell = world.cell.as_ref().unwrap();
    // Sheared by 2 x 0.5 = 1 edge: reduced once, the lean back to 0 (up to round-off).
    assert_eq!(cell.lattice.relabels, 1);
    assert!(
        cell.lattice.edges[(0, 1)].abs() < 1e-9,
        "{}",
        cell.lattice.edges
    );
    let budget = world.energy.dissipated.abs() + world.energy.external_work.abs();
    assert!(
        world.energy.external_work > 0.0,
        "the shear works on the disks"
    );
    assert!(
        world.energy_error().abs() < 1e-9 * budget.max(1e-12),
        "energy error {:e} of {budget:e}",
        world.energy_error()
    );
}

#[test]
fn a_disk_crossing_the_top_of_a_lees_edwards_cell_takes_the_velocity_of_the_image() {
    let mut loads = at_rest();
    let rate = 0.8;
    loads[0][1] = CellLoad::Rate(TimeFunction::Constant(rate));
    let mut bodies = BodySet::new();
    let v = Vector::new(0.0, 1.0);
    bodies.insert(Body::disk(0.02, 1000.0, Vector::new(0.3, 0.45)).with_velocity(v));
    let cell = PeriodicCell::new(lattice(1.0, 0.5), loads, 1.0, 1);
    let mut world = World::new(bodies, laws(0.0, 0.0), params(1e-3)).with_cell(cell);
    let mut stepper = MoreauJean::new();
    for _ in 0..100 {
        stepper.step(&mut world).unwrap();
    }
    // Crossed the top once, moved down by the top edge H e_y = (lean, 0.5). Its velocity in
    // the world, v + L (x - o) with x unwrapped, stays the initial (rate 0.45, 1): relative to
    // the flow it is v - t L v = (-rate t, 1).
    let cell = world.cell.as_ref().unwrap();
    assert_eq!(cell.wraps[0], [0, 1]);
    let t = 0.1;
    let u = world.bodies.velocity[0];
    assert!((u - Vector::new(-rate * t, 1.0)).norm() < 1e-12, "{u:?}");
    let p = world.bodies.position[0];
    let world_x = 0.3 + rate * 0.45 * t;
    let lean = cell.lattice.edges[(0, 1)];
    assert!((lean - rate * 0.5 * t).abs() < 1e-12, "lean {lean}");
    // The flow carries a body by h L (x_i - o), from the beginning of each step: first order
    // in the time step, `h rate v_y t / 2` behind here.
    let lag = 1e-3 * rate * 1.0 * t / 2.0;
    assert!(
        (p.x - (world_x - lean) + lag).abs() < 1e-9,
        "{p:?} vs {world_x} - {lean}"
    );
    assert!((p.y - (0.45 + t - 0.5)).abs() < 1e-12, "{p:?}");
    assert!(
        world.energy_error().abs() < 1e-12,
        "{}",
        world.energy_error()
    );
}

#[test]
fn a_cell_under_pressure_compacts_until_the_granular_stress_equals_it() {
    let pressure = 1000.0;
    let mut loads = at_rest();
    loads[0][0] = CellLoad::Stress(TimeFunction::Constant(pressure));
    loads[1][1] = CellLoad::Stress(TimeFunction::Constant(pressure));
    let mut bodies = random_disks(100, 1.0, 0.035, 11);
    // Without a mean velocity: the packing would otherwise keep translating.
    let mass: Real = bodies.mass.iter().sum();
    let momentum: Vector = (0..bodies.len())
        .map(|b| bodies.velocity[b] * bodies.mass[b])
        .sum();
    for v in &mut bodies.velocity {
        *v -= momentum / mass;
    }
    let cell = PeriodicCell::new(lattice(1.0, 1.0), loads, mass, 100);
    let mut world = World::new(bodies, laws(0.3, 0.0), params(2e-4)).with_cell(cell);
    world.params.nlgs.tolerance = 1e-6;
    let initial = world.kinetic_energy();
    let mut stepper = MoreauJean::new();
    let mut held = Vec::new();
    for step in 0..8000 {
        stepper.step(&mut world).unwrap();
        if step >= 7000 && step % 50 == 0 {
            let m = measure(&world, VolumeSource::Cell).unwrap();
            held.push((m.stress, m.solid_fraction));
        }
    }
    for (stress, phi) in held {
        for s in [stress[(0, 0)], stress[(1, 1)]] {
            assert!(
                (s - pressure).abs() < 0.01 * pressure,
                "sigma {stress} Pa against {pressure} Pa"
            );
        }
        assert!(phi > 0.75, "solid fraction {phi}");
    }
    // Nearly at rest: the compaction dissipated 99 % of the initial kinetic energy (31 J);
    // what is left are rattlers and the slow rearrangements of a packing under a fixed load.
    assert!(
        world.kinetic_energy() < 0.01 * initial,
        "{} J left of {initial} J",
        world.kinetic_energy()
    );
    // The imposed stress's work went into dissipation, to within the first-order error of
    // the cell's explicit `L^2` term (5e-5 of it, measured; without the term, 40 %).
    let work = world.energy.external_work;
    assert!(
        world.energy_error().abs() < 2e-4 * work,
        "energy error {:e} J of {work:e} J of work",
        world.energy_error()
    );
    let momentum: Vector = (0..world.bodies.len())
        .map(|b| world.bodies.velocity[b] * world.bodies.mass[b])
        .sum();
    assert!(
        momentum.norm() < 1e-9,
        "momentum relative to the flow {momentum:?}"
    );
}
