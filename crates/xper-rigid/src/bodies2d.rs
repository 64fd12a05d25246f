//! The bodies of a 2D scene: disks, convex polygons and wall segments.

use super::drive;
use xper_bodies::{Body, BodySet, ConvexPolygon, Shape};
use xper_math::{Real, Vector};
use xper_scene::{CellDesc, Scene, ShapeDesc};

/// The scenes this build runs: 2D rigid scenes.
pub type RigidScene = Scene;

/// The 2D rigid scene among the kinds a scene file may hold.
pub(super) fn rigid_scene(any: xper_scene::AnyScene) -> Option<Scene> {
    match any {
        xper_scene::AnyScene::Rigid(scene) if scene.fluid.is_none() => Some(scene),
        _ => None,
    }
}

/// The body set of `scene` and the size of its smallest body that is not a wall (m).
pub(super) fn bodies(scene: &Scene) -> (BodySet, Real) {
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
    (bodies, smallest)
}

/// The scene's periodic cell (`[cell]`), if any.
pub(super) fn cell(scene: &Scene) -> Option<&CellDesc<2>> {
    scene.cell.as_ref()
}

/// The scene's `[[events]]`.
pub(super) fn events(scene: &Scene) -> &[xper_scene::EventDesc] {
    &scene.events
}
