//! The bodies of a 3D scene: spheres, convex polyhedra and planar walls.

use super::drive;
use xper_bodies::{Body, BodySet, ConvexPolyhedron, Shape};
use xper_math::{AngMatrix, AngVector, Real, Rotation, Vector};
use xper_scene::{Scene3, ShapeDesc3};

/// The scenes this build runs: 3D rigid scenes.
pub type RigidScene = Scene3;

/// The 3D rigid scene among the kinds a scene file may hold.
pub(super) fn rigid_scene(any: xper_scene::AnyScene) -> Option<Scene3> {
    match any {
        xper_scene::AnyScene::Rigid3(scene) => Some(scene),
        _ => None,
    }
}

/// The body set of `scene` and the size of its smallest body that is not a wall (m).
///
/// A polyhedron's vertices are relative to its centroid in the scene; their hull is taken
/// again here, and its centroid (zero up to rounding) added to the body's position.
pub(super) fn bodies(scene: &Scene3) -> (BodySet, Real) {
    let mut bodies = BodySet::new();
    let mut smallest = Real::INFINITY;
    for b in &scene.bodies {
        let rotation = Rotation::from_scaled_axis(Vector::from(b.orientation));
        let mut position = Vector::from(b.position);
        let shape = match &b.shape {
            ShapeDesc3::Sphere { radius } => Shape::Sphere { radius: *radius },
            ShapeDesc3::Polyhedron { vertices } => {
                let points: Vec<Vector> = vertices.iter().map(|v| Vector::from(*v)).collect();
                let (hull, centroid) = ConvexPolyhedron::hull(&points)
                    .expect("the scene reader took the hull of these vertices");
                position += rotation * centroid;
                Shape::Polyhedron(Box::new(hull))
            }
            ShapeDesc3::Plane { half_extents } => Shape::Plane {
                half_extents: *half_extents,
            },
        };
        if !shape.is_wall() {
            smallest = smallest.min(shape.size());
        }
        // The scene's tensor is row-major; it is symmetric.
        let inertia = AngMatrix::from_fn(|r, c| b.inertia[r][c]);
        bodies.insert(Body {
            shape,
            position,
            rotation,
            velocity: Vector::from(b.velocity),
            angular_velocity: AngVector::from(b.angular_velocity),
            mass: b.mass,
            inertia,
            group: b.group as u16,
            drives: std::array::from_fn(|k| drive(&b.drives[k])),
        });
    }
    (bodies, smallest)
}

/// The scene's `[[events]]`.
pub(super) fn events(scene: &Scene3) -> &[xper_scene::EventDesc] {
    &scene.events
}

/// The scene's periodic cell (`[cell]`), if any.
pub(super) fn cell(scene: &Scene3) -> Option<&xper_scene::CellDesc<3>> {
    scene.cell.as_ref()
}
