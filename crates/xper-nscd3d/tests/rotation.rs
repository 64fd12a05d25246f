//! The rotation update of a torque-free asymmetric body (`body3d.rs`: angular momentum carried
//! over, orientation by the splitting of Dullweber, Leimkuhler and McLachlan 1997), against
//! what that scheme promises and an independent integration of Euler's equations.

mod common;

use common::*;
use xper_bodies::BodySet;
use xper_math::{AngMatrix, AngVector, Real, Rotation, Vector};
use xper_nscd3d::{MoreauJean, World};

/// A free box of half-extents (0.3, 0.2, 0.1) m (three distinct moments), turned away from
/// the axes, spinning at (1, 2, 3) rad/s; no gravity, no other body. `tilted`: the same box
/// given by its turned corners, so that its tensor in its own frame is not diagonal (the
/// rotation update then finds the principal axes itself).
fn spinning_box(h: Real, tilted: bool) -> World {
    let mut set = BodySet::new();
    let turn = Rotation::from_scaled_axis(Vector::new(0.4, -0.7, 0.2));
    let body = if tilted {
        let corners: Vec<Vector> = (0..8)
            .map(|k| {
                let s = |bit: usize, e: Real| if k >> bit & 1 == 1 { e } else { -e };
                turn * Vector::new(s(0, 0.3), s(1, 0.2), s(2, 0.1))
            })
            .collect();
        xper_bodies::Body::polyhedron(&corners, 1000.0).unwrap()
    } else {
        cuboid(Vector::new(0.3, 0.2, 0.1), Vector::zeros()).with_rotation(turn)
    };
    set.insert(body);
    set.angular_velocity[0] = AngVector::new(1.0, 2.0, 3.0);
    world(set, 0.0, 0.0, Vector::zeros(), h)
}

fn world_inertia(w: &World) -> AngMatrix {
    let r = w.bodies.rotation[0].to_rotation_matrix();
    r.matrix() * w.bodies.inertia[0] * r.matrix().transpose()
}

/// Steps a spinning box for `t` seconds with step `h`; returns the largest relative change of
/// the angular momentum, the largest relative energy error over the first and second halves
/// of the run, and the final orientation.
fn spin(h: Real, t: Real, tilted: bool) -> (Real, [Real; 2], Rotation) {
    let mut w = spinning_box(h, tilted);
    let l0 = world_inertia(&w) * w.bodies.angular_velocity[0];
    let e0 = w.kinetic_energy();
    let steps = (t / h).round() as usize;
    let (mut dl, mut de) = (0.0 as Real, [0.0 as Real; 2]);
    let mut stepper = MoreauJean::new();
    for k in 0..steps {
        stepper.step(&mut w).unwrap();
        let l = world_inertia(&w) * w.bodies.angular_velocity[0];
        dl = dl.max((l - l0).norm() / l0.norm());
        let half = usize::from(2 * k >= steps);
        de[half] = de[half].max((w.kinetic_energy() - e0).abs() / e0);
    }
    (dl, de, w.bodies.rotation[0])
}

/// The orientation after `t` by classical Runge-Kutta on `dq/dt = (w/2) q` with the world
/// angular momentum `L` fixed and `w = R I^-1 R^T L`: an independent reference.
fn reference(t: Real, steps: usize, tilted: bool) -> Rotation {
    let w = spinning_box(1.0, tilted);
    let (inertia, mut q) = (w.bodies.inertia[0], w.bodies.rotation[0].into_inner());
    let l = world_inertia(&w) * w.bodies.angular_velocity[0];
    let inverse = inertia.try_inverse().unwrap();
    let rate = |q: &nalgebra::Quaternion<Real>| {
        let unit = Rotation::new_normalize(*q);
        let omega = unit * (inverse * unit.inverse_transform_vector(&l));
        nalgebra::Quaternion::from_imag(omega) * *q * 0.5
    };
    let dt = t / steps as Real;
    for _ in 0..steps {
        let k1 = rate(&q);
        let k2 = rate(&(q + k1 * (dt / 2.0)));
        let k3 = rate(&(q + k2 * (dt / 2.0)));
        let k4 = rate(&(q + k3 * dt));
        q += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (dt / 6.0);
    }
    Rotation::new_normalize(q)
}

/// Angular momentum is kept to round-off (a few ulps per step); the energy error is of order 2 in `h` (halving `h`
/// divides it by about 4) and does not drift (its largest value over the second half of a
/// long run is no larger than over the first half, up to the oscillation); the orientation
/// converges at order 2 to an independent Runge-Kutta integration of the free rotor.
#[test]
fn torque_free_asymmetric_body() {
    for tilted in [false, true] {
        torque_free(tilted);
    }
}

fn torque_free(tilted: bool) {
    let (t, coarse, fine) = (20.0, 1e-2, 5e-3);
    let (dl_c, de_c, q_c) = spin(coarse, t, tilted);
    let (dl_f, de_f, q_f) = spin(fine, t, tilted);
    // Round-off: a few ulps per step (the rotations of the splitting, the inertia products).
    let ulps = |dl: Real, h: Real| dl / (t / h * Real::EPSILON);
    assert!(
        ulps(dl_c, coarse) < 10.0 && ulps(dl_f, fine) < 10.0,
        "{dl_c:e} {dl_f:e}"
    );
    let (e_c, e_f) = (de_c[0].max(de_c[1]), de_f[0].max(de_f[1]));
    let order = (e_c / e_f).log2();
    assert!(
        (1.8..2.2).contains(&order),
        "energy errors {e_c:e} {e_f:e}: order {order}"
    );
    assert!(e_c < 1e-3, "{e_c:e}");
    for de in [de_c, de_f] {
        assert!(de[1] < 1.5 * de[0], "drift: {de:?}");
    }
    let exact = reference(t, 200_000, tilted);
    let (err_c, err_f) = (q_c.angle_to(&exact), q_f.angle_to(&exact));
    let order = (err_c / err_f).log2();
    assert!(
        (1.8..2.2).contains(&order),
        "orientation errors {err_c:e} {err_f:e}: order {order}"
    );
}
