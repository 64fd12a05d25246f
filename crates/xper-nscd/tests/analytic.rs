//! The exact answers of BRIEF.md section 7 for rigid bodies, each against its formula.

use xper_bodies::{Body, BodySet};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{MoreauJean, StepParams, World};
use xper_solver::{ConvergenceNorm, NlgsParams};

const G: Real = 9.81;

/// A tight solver: these tests compare with exact solutions, not with LMGC90's tolerance.
fn params(dt: Real, gravity: Vector) -> StepParams {
    StepParams {
        dt,
        theta: 0.5,
        gravity,
        alert_distance: 1e-3,
        nlgs: NlgsParams {
            tolerance: 1e-14,
            max_iterations: 20_000,
            check_every: 1,
            relaxation: 1.0,
            norm: ConvergenceNorm::NaturalMap,
        },
        projection_tolerance: Some(1e-9),
    }
}

fn world(bodies: Vec<Body>, friction: Real, restitution: Real, params: StepParams) -> World {
    let mut set = BodySet::new();
    for b in bodies {
        set.insert(b);
    }
    let mut laws = LawTable::new(1);
    laws.set(0, 0, InteractionLaw::SignoriniCoulomb(SignoriniCoulomb { friction, restitution }));
    World::new(set, laws, params)
}

fn rectangle(w: Real, h: Real) -> Vec<Vector> {
    vec![Vector::new(-w / 2.0, -h / 2.0), Vector::new(w / 2.0, -h / 2.0), Vector::new(w / 2.0, h / 2.0), Vector::new(-w / 2.0, h / 2.0)]
}

/// Distance travelled down an incline of angle `slope` by a block after `steps` steps.
fn slide_on_incline(slope: Real, mu: Real, steps: usize) -> (Real, Real, Real) {
    let (dir, up) = (Vector::new(slope.cos(), slope.sin()), Vector::new(-slope.sin(), slope.cos()));
    let h = 0.1;
    let block = Body::polygon(rectangle(0.4, h), 1000.0, up * (h / 2.0)).with_angle(slope);
    let wall = Body::wall(-dir * 5.0, dir * 5.0);
    let dt = 1e-3;
    let mut w = world(vec![block, wall], mu, 0.0, params(dt, Vector::new(0.0, -G)));
    let start = w.bodies.position[0];
    let mut stepper = MoreauJean::new();
    for _ in 0..steps {
        let r = stepper.step(&mut w).expect("step");
        if std::env::var("DBG").is_ok() { eprintln!("{} act {} it {} res {:e} conv {} ang {:e} proj {} ov {:e}", r.step, r.active, r.iterations, r.residual, r.converged, w.bodies.angle[0]-slope, r.projection_iterations, r.max_overlap); }
        assert!(r.converged, "solver did not converge: {r:?}");
    }
    let travelled = (w.bodies.position[0] - start).dot(&dir);
    let lift = (w.bodies.position[0] - start).dot(&up);
    (travelled, lift, w.bodies.angle[0] - slope)
}

#[test]
fn block_on_incline_sticks_when_tan_below_mu() {
    let (x, lift, rotation) = slide_on_incline(0.3, 0.4, 400);
    assert!(x.abs() < 1e-12 && lift.abs() < 1e-12 && rotation.abs() < 1e-12, "{x} {lift} {rotation}");
}

#[test]
fn block_on_incline_slides_with_coulomb_acceleration() {
    let (slope, mu, steps) = (0.5, 0.3, 400);
    let (x, lift, rotation) = slide_on_incline(slope, mu, steps);
    let t = steps as Real * 1e-3;
    let exact = -G * (slope.sin() - mu * slope.cos()) * t * t / 2.0;
    assert!((x - exact).abs() < 1e-12 * exact.abs().max(1.0), "x = {x}, exact {exact}");
    assert!(lift.abs() < 1e-12 && rotation.abs() < 1e-12, "{lift} {rotation}");
}

#[test]
fn disk_dropped_with_zero_restitution_does_not_rebound() {
    let (r, height) = (0.05, 0.5);
    let disk = Body::disk(r, 1000.0, Vector::new(0.0, r + height));
    let floor = Body::wall(Vector::new(-1.0, 0.0), Vector::new(1.0, 0.0));
    let mut w = world(vec![disk, floor], 0.3, 0.0, params(1e-3, Vector::new(0.0, -G)));
    let m = w.bodies.mass[0];
    let e0 = w.kinetic_energy() + w.potential_energy();
    let mut stepper = MoreauJean::new();
    let mut landed = false;
    for _ in 0..1000 {
        stepper.step(&mut w).expect("step");
        let vy = w.bodies.velocity[0].y;
        if landed {
            assert!(vy.abs() < 1e-12, "rebound: vy = {vy}");
        }
        landed |= w.bodies.position[0].y - r < 1e-3 && vy.abs() < 1e-12;
    }
    assert!(landed);
    let lost = e0 - (w.kinetic_energy() + w.potential_energy());
    let exact = m * G * height;
    assert!((lost - exact).abs() < 1e-7 * exact, "lost {lost}, m g H = {exact}");
    let balance = w.energy_error();
    assert!(balance.abs() < 1e-9 * exact, "energy balance error {balance}");
}

fn cradle(gap: Real) -> [Real; 3] {
    let (r, v0) = (0.1, 1.0);
    let bodies = (0..3)
        .map(|k| {
            let b = Body::disk(r, 1000.0, Vector::new(k as Real * (2.0 * r + gap), 0.0));
            if k == 0 { b.with_velocity(Vector::new(v0, 0.0)) } else { b }
        })
        .collect();
    let mut w = world(bodies, 0.0, 1.0, params(1e-3, Vector::zeros()));
    let mut stepper = MoreauJean::new();
    for _ in 0..200 {
        stepper.step(&mut w).expect("step");
    }
    [0, 1, 2].map(|k| w.bodies.velocity[k].x / v0)
}

#[test]
fn newtons_cradle_simultaneous_impact() {
    let v = cradle(0.0);
    for (got, want) in v.iter().zip([-1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0]) {
        assert!((got - want).abs() < 1e-10, "{v:?}");
    }
}

#[test]
fn newtons_cradle_with_small_gaps_transmits_velocity() {
    let v = cradle(1e-4);
    for (got, want) in v.iter().zip([0.0, 0.0, 1.0]) {
        assert!((got - want).abs() < 1e-10, "{v:?}");
    }
}

#[test]
fn column_of_disks_carries_the_weight_above() {
    let (r, n) = (0.01, 10);
    let mut bodies: Vec<Body> = (0..n).map(|k| Body::disk(r, 2000.0, Vector::new(0.0, r + 2.0 * r * k as Real))).collect();
    bodies.push(Body::wall(Vector::new(-1.0, 0.0), Vector::new(1.0, 0.0)));
    let dt = 1e-3;
    let mut w = world(bodies, 0.3, 0.0, params(dt, Vector::new(0.0, -G)));
    let m = w.bodies.mass[0];
    let mut stepper = MoreauJean::new();
    for _ in 0..20 {
        let r = stepper.step(&mut w).expect("step");
        if std::env::var("DBG").is_ok() { eprintln!("{r:?}"); }
    }
    // The contact below disk j (from the bottom) carries the disks j..n-1 above it included.
    for c in &w.contacts.contacts {
        let [a, b] = c.bodies;
        let below = if b as usize == n { a as usize } else { b as usize };
        let k_from_top = n - below;
        let force = c.impulse[0] / dt;
        let exact = k_from_top as Real * m * G;
        assert!((force - exact).abs() < 1e-9 * exact, "disk {below}: force {force}, k m g = {exact}");
        assert!(c.impulse[1].abs() < 1e-12);
    }
    assert_eq!(w.contacts.len(), n);
}
