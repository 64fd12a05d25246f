//! Worlds for the 3D tests: bodies, one law, tight NLGS.

// Each test binary uses a part of these helpers.
#![allow(dead_code)]

use xper_bodies::{Body, BodySet};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd3d::{Detection, StepParams, VelocitySolver, World};
use xper_solver::NlgsParams;

/// Gravity (m/s^2).
pub const G: Real = 9.81;

/// A world of `bodies` with one Signorini-Coulomb law, theta 1/2, NLGS to 1e-12.
pub fn world(
    bodies: BodySet,
    friction: Real,
    restitution: Real,
    gravity: Vector,
    h: Real,
) -> World {
    let mut laws = LawTable::new(1);
    let law = SignoriniCoulomb {
        friction,
        restitution,
    };
    laws.set(0, 0, InteractionLaw::SignoriniCoulomb(law));
    let params = StepParams {
        dt: h,
        theta: 0.5,
        gravity,
        alert_distance: 1e-3,
        detection: Detection::Begin,
        nlgs: NlgsParams {
            tolerance: 1e-13,
            max_iterations: 100_000,
            check_every: 1,
            ..Default::default()
        },
        solver: VelocitySolver::Nlgs,
        projection_tolerance: None,
    };
    World::new(bodies, laws, params)
}

/// The half-space `z <= 0` (outward normal +z).
pub fn floor() -> Body {
    Body::plane(Vector::zeros(), Vector::z(), [Real::INFINITY; 2])
}

/// A cube of half-edge `half` (m) and density 1000 kg/m^3 centred at `centre`.
pub fn cube(half: Real, centre: Vector) -> Body {
    cuboid(Vector::repeat(half), centre)
}

/// A box of half-extents `half` (m) along the axes and density 1000 kg/m^3 centred at
/// `centre`.
pub fn cuboid(half: Vector, centre: Vector) -> Body {
    let corners: Vec<Vector> = (0..8)
        .map(|k| {
            let s = |bit: usize| if k >> bit & 1 == 1 { 1.0 } else { -1.0 };
            centre + Vector::new(s(0) * half.x, s(1) * half.y, s(2) * half.z)
        })
        .collect();
    Body::polyhedron(&corners, 1000.0).expect("a box spans a volume")
}

/// Gravity of magnitude `G` on the incline of angle `theta` (rad) about the y axis: the
/// floor `z = 0` is the incline, x points down the slope.
pub fn tilted_gravity(theta: Real) -> Vector {
    Vector::new(G * theta.sin(), 0.0, -G * theta.cos())
}
