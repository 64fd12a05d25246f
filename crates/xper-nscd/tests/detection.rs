//! The configuration contacts are detected on ([`Detection`]), against the theta-method worked
//! out by hand for a disk falling onto a floor faster than the alert distance per step.
//!
//! Alert distance `a`, step `h`, theta 1/2, no gravity, the disk at gap `g_0 = 1.5 a` above the
//! floor moving down at `V = 2 a / h` (so a step's approach `h V = 2 a` exceeds `a`), e = 0:
//! - detection on `q_i`: the pair is `1.5 a > a` apart, so the first step misses it and the disk
//!   ends at `1.5 a - 2 a = -0.5 a`; the second step has the contact with
//!   `s = max(g_TT, 0) / h = 0`, which stops the disk (`v_2 = 0`), but the explicit half of the
//!   motion still moves it by `h v_1 / 2 = -a`: the overlap `1.5 a` stays for good;
//! - detection on `q_TT = q_i + h v_i / 2` (LMGC90's): `g_TT = 1.5 a - a = 0.5 a <= a`, so the
//!   contact is found at once with `s = 0.5 a / h`, `U_N,1 = -0.5 a / h`, and the gap becomes
//!   `1.5 a + h (-2 a / h - 0.5 a / h) / 2 = 0.25 a`; the second step has
//!   `g_TT = 0.25 a - 0.25 a = 0`, stops the disk and ends at gap 0, never overlapping.

use xper_bodies::{Body, BodySet};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{Detection, MoreauJean, StepParams, VelocitySolver, World};
use xper_solver::NlgsParams;

const R: Real = 0.01;
const ALERT: Real = 1e-3;
const H: Real = 1e-3;

fn falling_disk(detection: Detection) -> World {
    let mut set = BodySet::new();
    set.insert(Body::wall(Vector::new(-0.1, 0.0), Vector::new(0.1, 0.0)));
    set.insert(
        Body::disk(R, 1000.0, Vector::new(0.0, R + 1.5 * ALERT))
            .with_velocity(Vector::new(0.0, -2.0 * ALERT / H)),
    );
    let mut laws = LawTable::new(1);
    let law = SignoriniCoulomb {
        friction: 0.3,
        restitution: 0.0,
    };
    laws.set(0, 0, InteractionLaw::SignoriniCoulomb(law));
    let params = StepParams {
        dt: H,
        theta: 0.5,
        gravity: Vector::zeros(),
        alert_distance: ALERT,
        detection,
        nlgs: NlgsParams {
            tolerance: 1e-12,
            max_iterations: 100,
            ..Default::default()
        },
        solver: VelocitySolver::Nlgs,
        projection_tolerance: None,
    };
    World::new(set, laws, params)
}

/// Steps the falling disk and checks its gap to the floor after each step against `expected`
/// (in alert distances), to round-off.
fn assert_gaps(detection: Detection, expected: [Real; 5]) {
    let mut world = falling_disk(detection);
    let mut stepper = MoreauJean::new();
    for (k, e) in expected.into_iter().enumerate() {
        stepper.step(&mut world).unwrap();
        let (g, e) = (world.bodies.position[1].y - R, e * ALERT);
        assert!(
            (g - e).abs() < 1e-12,
            "{detection:?}, step {}: gap {g:e}, expected {e:e}",
            k + 1
        );
    }
}

#[test]
fn detection_on_the_begin_configuration_misses_the_pair_and_keeps_the_overlap() {
    assert_gaps(Detection::Begin, [-0.5, -1.5, -1.5, -1.5, -1.5]);
}

#[test]
fn detection_on_the_predicted_configuration_lands_the_disk_without_overlap() {
    assert_gaps(Detection::Predicted, [0.25, 0.0, 0.0, 0.0, 0.0]);
}

#[test]
fn the_predicted_detection_leaves_the_bodies_where_they_were() {
    let mut set = BodySet::new();
    for k in 0..50 {
        let x = k as Real * 0.1;
        let body = Body::disk(0.03, 1000.0, Vector::new(x, x.sin()))
            .with_velocity(Vector::new(x.cos(), 0.3 - x))
            .with_rotation(0.1 * x);
        set.insert(body);
    }
    for b in 0..set.len() {
        set.angular_velocity[b] = 1.0 / (b + 1) as Real;
    }
    let before = set.clone();
    let mut saved = xper_bodies::Configuration::default();
    set.advance_explicitly(1.7e-3, &mut saved);
    for b in 0..set.len() {
        let moved = before.position[b] + before.velocity[b] * 1.7e-3;
        assert_eq!(set.position[b], moved);
        assert_eq!(
            set.rotation[b],
            before.rotation[b] + before.angular_velocity[b] * 1.7e-3
        );
    }
    set.restore_configuration(&saved);
    assert_eq!(set, before, "positions and angles restored bit for bit");
}
