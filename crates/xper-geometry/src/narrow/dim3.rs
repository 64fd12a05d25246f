//! The 3D narrow phase: which pair function handles which pair of shapes.

use super::{
    collide_polyhedra, collide_polyhedron_plane, collide_sphere_plane, collide_sphere_polyhedron,
    collide_spheres, Manifold,
};
use xper_bodies::Shape;
use xper_math::{Real, Rotation, Vector};

/// Contact points between shape `a` placed at (`pa`, `qa`) and shape `b`, with normals from
/// `a` to `b`, keeping points whose gap is at most `alert`. Two walls never touch.
pub fn collide(
    a: &Shape,
    pa: &Vector,
    qa: Rotation,
    b: &Shape,
    pb: &Vector,
    qb: Rotation,
    alert: Real,
) -> Manifold {
    use Shape::*;
    match (a, b) {
        (Sphere { radius: ra }, Sphere { radius: rb }) => collide_spheres(pa, *ra, pb, *rb, alert),
        (Plane { half_extents }, Sphere { radius }) => {
            collide_sphere_plane(pb, *radius, pa, qa, *half_extents, alert)
        }
        (Sphere { radius }, Plane { half_extents }) => {
            collide_sphere_plane(pa, *radius, pb, qb, *half_extents, alert).flipped()
        }
        (Polyhedron(p), Sphere { radius }) => {
            collide_sphere_polyhedron(pb, *radius, p, pa, qa, alert)
        }
        (Sphere { radius }, Polyhedron(p)) => {
            collide_sphere_polyhedron(pa, *radius, p, pb, qb, alert).flipped()
        }
        (Plane { half_extents }, Polyhedron(p)) => {
            collide_polyhedron_plane(p, pb, qb, pa, qa, *half_extents, alert)
        }
        (Polyhedron(p), Plane { half_extents }) => {
            collide_polyhedron_plane(p, pa, qa, pb, qb, *half_extents, alert).flipped()
        }
        (Polyhedron(p), Polyhedron(r)) => collide_polyhedra(p, pa, qa, r, pb, qb, alert),
        (Plane { .. }, Plane { .. }) => Manifold::EMPTY,
    }
}
