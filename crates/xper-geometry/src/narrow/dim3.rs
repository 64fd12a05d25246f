//! The 3D narrow phase: which pair function handles which pair of shapes.

use super::{
    collide_polyhedra, collide_polyhedron_plane, collide_sphere_plane, collide_sphere_polyhedron,
    collide_spheres, Manifold, MANIFOLD_POINTS,
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

/// At most [`MANIFOLD_POINTS`] of `count` contact candidates (point `point(k)`, gap `gap(k)`)
/// on a face of normal `n`, spanning the largest area: all when few enough; else the deepest,
/// the farthest from it in the face's plane, and the farthest on each side of the line
/// through those two.
pub(super) fn reduce(
    count: usize,
    point: impl Fn(usize) -> Vector,
    gap: impl Fn(usize) -> Real,
    n: &Vector,
) -> Vec<usize> {
    if count <= MANIFOLD_POINTS {
        return (0..count).collect();
    }
    let deepest = (0..count)
        .min_by(|&a, &b| gap(a).total_cmp(&gap(b)))
        .unwrap_or(0);
    // Offsets from the deepest point, in the face's plane.
    let offset = |k: usize| {
        let d = point(k) - point(deepest);
        d - n * n.dot(&d)
    };
    let far = (0..count)
        .max_by(|&a, &b| {
            offset(a)
                .norm_squared()
                .total_cmp(&offset(b).norm_squared())
        })
        .unwrap_or(0);
    let side = |k: usize| offset(far).cross(&offset(k)).dot(n);
    let mut keep = vec![deepest, far];
    let left = (0..count).max_by(|&a, &b| side(a).total_cmp(&side(b)));
    let right = (0..count).min_by(|&a, &b| side(a).total_cmp(&side(b)));
    for k in [left, right].into_iter().flatten() {
        if !keep.contains(&k) {
            keep.push(k);
        }
    }
    keep
}

/// Whether `x`, on the plane of a convex face of `count` vertices (`vertex(k)`,
/// counter-clockwise about its outward normal `n`), lies inside the face (borders included).
pub(super) fn inside_face(
    count: usize,
    vertex: impl Fn(usize) -> Vector,
    n: &Vector,
    x: &Vector,
) -> bool {
    (0..count).all(|k| {
        let a = vertex(k);
        (vertex((k + 1) % count) - a).cross(&(x - a)).dot(n) >= 0.0
    })
}
