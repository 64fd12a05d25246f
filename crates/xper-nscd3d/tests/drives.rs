//! Driven degrees of freedom in 3D against exact answers: a conveyor plane dragging a cube by
//! friction, and a torque on a free sphere.

mod common;

use common::*;
use xper_bodies::{Body, BodySet, Drive, TimeFunction};
use xper_math::{Real, Vector};
use xper_nscd3d::MoreauJean;

const H: Real = 1e-3;

/// A cube at rest on a floor moving along x at `V`: friction accelerates it at `mu g` (exactly
/// `v_i = mu g t_i` with the theta-method) until it reaches `V`, then it is carried at `V`.
#[test]
fn a_conveyor_plane_drags_a_cube_up_to_its_speed() {
    let (mu, v) = (0.4, 0.5);
    let mut set = BodySet::new();
    let mut belt = floor().with_velocity(Vector::new(v, 0.0, 0.0));
    belt.drives[0] = Drive::Velocity(TimeFunction::Constant(v));
    set.insert(belt);
    set.insert(cube(0.05, Vector::new(0.0, 0.0, 0.05)));
    let mut w = world(set, mu, 0.0, Vector::new(0.0, 0.0, -G), H);
    let mut stepper = MoreauJean::new();
    let catch_up = v / (mu * G);
    for step in 1..=300 {
        stepper.step(&mut w).unwrap();
        let t = step as Real * H;
        let expected = (mu * G * t).min(v);
        let got = w.bodies.velocity[1].x;
        // The step that reaches V sticks within it; every other step is exact.
        if (t - catch_up).abs() > H {
            assert!(
                (got - expected).abs() < 1e-9,
                "t = {t}: {got} vs {expected}"
            );
        }
    }
    assert!(
        (w.bodies.position[0].x - v * 0.3).abs() < 1e-12,
        "the belt moved at V"
    );
    assert!(w.bodies.angular_velocity[1].norm() < 1e-9);
}

/// A constant torque `T` about z on a free sphere (no gravity): `w = T t / I`, and the energy
/// budget counts the torque's work.
#[test]
fn a_torque_spins_a_free_sphere() {
    let torque = 0.02;
    let mut set = BodySet::new();
    let mut ball = Body::sphere(0.1, 1000.0, Vector::zeros());
    ball.drives[5] = Drive::Force(TimeFunction::Constant(torque));
    let inertia = ball.inertia[(2, 2)];
    set.insert(ball);
    let mut w = world(set, 0.3, 0.0, Vector::zeros(), H);
    let mut stepper = MoreauJean::new();
    for _ in 0..200 {
        stepper.step(&mut w).unwrap();
    }
    let t = 200.0 * H;
    let spin = w.bodies.angular_velocity[0];
    assert!(
        (spin.z - torque * t / inertia).abs() < 1e-12 * spin.z,
        "{spin:?}"
    );
    assert!(spin.x == 0.0 && spin.y == 0.0);
    let angle = w.bodies.rotation[0].angle();
    assert!(
        (angle - torque * t * t / (2.0 * inertia)).abs() < 1e-9,
        "{angle}"
    );
    assert!(w.energy_error().abs() < 1e-12 * w.kinetic_energy());
}
