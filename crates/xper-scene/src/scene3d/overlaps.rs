//! The overlap check of a 3D scene: bodies that overlap another body, or lie partly behind a
//! wall, at the start by more than `1e-9 + 1e-6 x` the smaller size (m) are errors, at most
//! [`MAX_OVERLAP_REPORTS`] listed.
//!
//! Spheres against spheres and walls are checked in closed form. Pairs with a polyhedron go
//! through the engine's narrow phase (`xper_geometry3d::collide` at alert distance 0: the
//! deepest contact point's gap), so that the check sees the contacts the first step will see;
//! candidates are the pairs whose bounding spheres (bounding boxes for walls) meet.

use std::collections::HashMap;

use crate::read::Ctx;
use crate::shared::Built3;
use crate::types3d::ShapeDesc3;
use crate::MAX_OVERLAP_REPORTS;
use xper_bodies3d::{ConvexPolyhedron, Shape};
use xper_math3d::{Rotation, Vector};

/// Overlapping pairs `(a, b, depth)` found so far (at most [`MAX_OVERLAP_REPORTS`]) and how
/// many there are in all.
#[derive(Default)]
struct Found {
    pairs: Vec<(usize, usize, f64)>,
    total: usize,
}

impl Found {
    /// Records bodies `a` and `b` overlapping by `depth` (m) when it exceeds the tolerance for
    /// the smaller size `size` (m).
    fn record(&mut self, a: usize, b: usize, depth: f64, size: f64) {
        if depth > 1e-9 + 1e-6 * size {
            self.total += 1;
            if self.pairs.len() < MAX_OVERLAP_REPORTS {
                self.pairs.push((a.min(b), a.max(b), depth));
            }
        }
    }
}

/// A placed body of the scene: index, engine shape, position, orientation, reach (m).
struct Placed {
    index: usize,
    shape: Shape,
    position: Vector,
    rotation: Rotation,
    /// Radius of a ball about `position` holding the body; walls, whose candidates are found
    /// by bounding boxes, have none (infinite).
    reach: f64,
}

/// Reports the overlaps of the bodies `built` (see the module documentation).
pub(super) fn overlaps(ctx: &mut Ctx, built: &Built3) {
    let mut found = Found::default();
    spheres(built, &mut found);
    polyhedra(built, &mut found);
    crate::overlap::report(ctx, &built.origins, found.pairs, found.total);
}

/// The walls of the scene, placed.
fn walls(built: &Built3) -> Vec<Placed> {
    (built.bodies.iter().enumerate())
        .filter_map(|(w, b)| match b.shape {
            ShapeDesc3::Plane { half_extents } => Some(Placed {
                index: w,
                shape: Shape::Plane { half_extents },
                position: Vector::from(b.position),
                rotation: Rotation::from_scaled_axis(Vector::from(b.orientation)),
                reach: f64::INFINITY,
            }),
            _ => None,
        })
        .collect()
}

/// Spheres against spheres (on a grid of cells of the largest diameter) and against walls.
fn spheres(built: &Built3, found: &mut Found) {
    let spheres: Vec<(usize, Vector, f64)> = (built.bodies.iter().enumerate())
        .filter_map(|(k, b)| match b.shape {
            ShapeDesc3::Sphere { radius } => Some((k, Vector::from(b.position), radius)),
            _ => None,
        })
        .collect();
    let Some(rmax) = spheres.iter().map(|s| s.2).reduce(f64::max) else {
        return;
    };
    let cell = 2.0 * rmax;
    let key = |x: &Vector| -> [i64; 3] { std::array::from_fn(|k| (x[k] / cell).floor() as i64) };
    let walls = walls(built);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (s, (_, x, _)) in spheres.iter().enumerate() {
        grid.entry(key(x)).or_default().push(s);
    }
    for (s, &(b, x, r)) in spheres.iter().enumerate() {
        let c = key(&x);
        for d in 0..27 {
            let offset = [d % 3, d / 3 % 3, d / 9].map(|v| v as i64 - 1);
            let at = std::array::from_fn(|k| c[k].saturating_add(offset[k]));
            for &o in grid.get(&at).into_iter().flatten().filter(|&&o| o > s) {
                let (a, y, q) = spheres[o];
                found.record(a, b, r + q - (x - y).norm(), 2.0 * r.min(q));
            }
        }
        for w in &walls {
            let [hx, hy] = match w.shape {
                Shape::Plane { half_extents } => half_extents,
                _ => continue,
            };
            let local = w.rotation.inverse_transform_vector(&(x - w.position));
            let within = local.x.abs() <= hx && local.y.abs() <= hy;
            if within && local.z > -r {
                found.record(w.index, b, r - local.z, 2.0 * r);
            }
        }
    }
}

/// Every pair with a polyhedron, by the narrow phase; candidates by bounding spheres.
fn polyhedra(built: &Built3, found: &mut Found) {
    let solids: Vec<Placed> = (built.bodies.iter().enumerate())
        .filter_map(|(k, b)| {
            let shape = match &b.shape {
                ShapeDesc3::Sphere { radius } => Shape::Sphere { radius: *radius },
                ShapeDesc3::Polyhedron { vertices } => {
                    let points: Vec<Vector> = vertices.iter().map(|&v| Vector::from(v)).collect();
                    // The scene's vertices are already a hull about its centroid.
                    Shape::Polyhedron(Box::new(ConvexPolyhedron::hull(&points).ok()?.0))
                }
                ShapeDesc3::Plane { .. } => return None,
            };
            let reach = match &shape {
                Shape::Sphere { radius } => *radius,
                Shape::Polyhedron(p) => p.bounding_radius,
                Shape::Plane { .. } => return None,
            };
            Some(Placed {
                index: k,
                shape,
                position: Vector::from(b.position),
                rotation: Rotation::from_scaled_axis(Vector::from(b.orientation)),
                reach,
            })
        })
        .collect();
    let is_polyhedron = |p: &Placed| matches!(p.shape, Shape::Polyhedron(_));
    if !solids.iter().any(is_polyhedron) {
        return;
    }
    let rmax = solids.iter().map(|s| s.reach).fold(0.0, f64::max);
    let cell = 2.0 * rmax;
    let key = |x: &Vector| -> [i64; 3] { std::array::from_fn(|k| (x[k] / cell).floor() as i64) };
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (s, p) in solids.iter().enumerate() {
        grid.entry(key(&p.position)).or_default().push(s);
    }
    let depth = |a: &Placed, b: &Placed| -> f64 {
        let m = xper_geometry3d::collide(
            &a.shape,
            &a.position,
            a.rotation,
            &b.shape,
            &b.position,
            b.rotation,
            0.0,
        );
        -(m.as_slice().iter().map(|p| p.gap).fold(0.0, f64::min))
    };
    let walls = walls(built);
    for (s, p) in solids.iter().enumerate().filter(|(_, p)| is_polyhedron(p)) {
        let c = key(&p.position);
        for d in 0..27 {
            let offset = [d % 3, d / 3 % 3, d / 9].map(|v| v as i64 - 1);
            let at = std::array::from_fn(|k| c[k].saturating_add(offset[k]));
            for &o in grid.get(&at).into_iter().flatten() {
                let other = &solids[o];
                // Each pair once: a polyhedron with a sphere, or with a later polyhedron.
                if o == s || is_polyhedron(other) && o < s {
                    continue;
                }
                if (p.position - other.position).norm() > p.reach + other.reach {
                    continue;
                }
                let size = 2.0 * p.reach.min(other.reach);
                found.record(p.index, other.index, depth(p, other), size);
            }
        }
        let bounds = p.shape.aabb(&p.position, p.rotation);
        for w in &walls {
            if w.shape.aabb(&w.position, w.rotation).intersects(&bounds) {
                found.record(w.index, p.index, depth(p, w), 2.0 * p.reach);
            }
        }
    }
}
