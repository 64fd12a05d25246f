//! Conversion of a validated scene description into an engine [`World`].

use xper_bodies::{Body, BodySet, ConvexPolygon, Drive, Shape};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{StepParams, VelocitySolver, World};
use xper_scene::{Scene, ShapeDesc};
use xper_solver::{ConvergenceNorm, ErrorScaling, NlgsParams, SolverKind, SolverParams};

/// Overlap allowed before the position projection runs, relative to the smallest body size.
pub const PROJECTION_TOLERANCE_RELATIVE: Real = 1e-4;

fn drive(d: &xper_scene::Drive) -> Drive {
    match d {
        xper_scene::Drive::Free => Drive::Free,
        xper_scene::Drive::Velocity(f) => Drive::Velocity(f.clone()),
        xper_scene::Drive::Force(f) => Drive::Force(f.clone()),
    }
}

/// The velocity solver of a scene: NLGS, or an assembled-problem solver with the scene's
/// tolerance on the natural-map error under Siconos' scaling `max(|q|, |r|, |u|)`.
pub fn velocity_solver(settings: &xper_scene::SolverSettings) -> VelocitySolver {
    let kind = match settings.kind {
        xper_scene::VelocitySolverKind::Nlgs => return VelocitySolver::Nlgs,
        xper_scene::VelocitySolverKind::Newton => SolverKind::Newton,
        xper_scene::VelocitySolverKind::ProximalNewton => SolverKind::ProximalNewton,
    };
    VelocitySolver::Assembled(SolverParams {
        tolerance: settings.tolerance,
        max_iterations: settings.max_iterations,
        scaling: ErrorScaling::RelativeMax,
        ..SolverParams::with_kind(kind)
    })
}

/// Builds the world of a scene at time 0.
pub fn world_from_scene(scene: &Scene) -> World {
    let mut bodies = BodySet::new();
    let mut smallest = Real::INFINITY;
    for b in &scene.bodies {
        let shape = match &b.shape {
            ShapeDesc::Disk { radius } => Shape::Disk { radius: *radius },
            ShapeDesc::Polygon { vertices } => Shape::Polygon(Box::new(ConvexPolygon::new(
                vertices.iter().map(|v| Vector::new(v[0], v[1])).collect(),
            ))),
            ShapeDesc::Segment { half_length } => Shape::Segment {
                half_length: *half_length,
            },
        };
        if !matches!(shape, Shape::Segment { .. }) {
            smallest = smallest.min(shape.size());
        }
        bodies.insert(Body {
            shape,
            position: Vector::new(b.position[0], b.position[1]),
            rotation: b.angle,
            velocity: Vector::new(b.velocity[0], b.velocity[1]),
            angular_velocity: b.angular_velocity,
            mass: b.mass,
            inertia: b.inertia,
            group: b.group as u16,
            drives: [
                drive(&b.drives[0]),
                drive(&b.drives[1]),
                drive(&b.drives[2]),
            ],
        });
    }
    let mut laws = LawTable::new(scene.groups.len());
    for law in &scene.laws {
        laws.set(
            law.groups[0],
            law.groups[1],
            InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
                friction: law.friction,
                restitution: law.restitution,
            }),
        );
    }
    let s = &scene.solver;
    let params = StepParams {
        dt: scene.dt,
        theta: scene.theta,
        gravity: Vector::new(scene.gravity[0], scene.gravity[1]),
        alert_distance: scene.alert_distance,
        detection: scene.detection,
        nlgs: NlgsParams {
            tolerance: s.tolerance,
            max_iterations: s.max_iterations,
            check_every: s.check_every,
            relaxation: s.relaxation,
            norm: match s.norm {
                xper_scene::ConvergenceNorm::Quad => ConvergenceNorm::Quad,
                xper_scene::ConvergenceNorm::Maxm => ConvergenceNorm::Maxm,
                xper_scene::ConvergenceNorm::NaturalMap => ConvergenceNorm::NaturalMap,
            },
            acceleration: s.acceleration,
            check: s.check,
        },
        solver: velocity_solver(s),
        projection_tolerance: (s.position_projection && smallest.is_finite())
            .then_some(PROJECTION_TOLERANCE_RELATIVE * smallest),
    };
    World::new(bodies, laws, params)
}

/// Gives a world restored from a checkpoint the solver limits of its (possibly edited) scene:
/// tolerance, iteration limit and check interval are among the edits a resume may take
/// ([`crate::resume::COMPATIBLE`]).
pub fn take_solver_limits(world: &mut World, scene: &Scene) {
    let s = &scene.solver;
    world.params.nlgs.tolerance = s.tolerance;
    world.params.nlgs.max_iterations = s.max_iterations;
    world.params.nlgs.check_every = s.check_every;
    world.params.solver = velocity_solver(s);
}

/// Frees the scene's list of body descriptions once the world is built from it (nothing after
/// needs it): for a generated scene of a million disks it is as large as the world.
pub fn release_body_descriptions(scene: &mut Scene) {
    scene.bodies = Vec::new();
}
