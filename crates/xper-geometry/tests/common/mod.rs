//! Random scenes for the detection tests: disks, triangles and walls.

use xper_bodies::{Body, BodySet, ConvexPolygon, Drive, Shape};
use xper_math::{Real, Vector};

/// A body of `shape` at `(x, y)` turned by `angle`; walls have infinite mass.
pub fn body(shape: Shape, x: Real, y: Real, angle: Real) -> Body {
    let fixed = matches!(shape, Shape::Segment { .. });
    Body {
        shape,
        position: Vector::new(x, y),
        rotation: angle,
        velocity: Vector::zeros(),
        angular_velocity: 0.0,
        mass: if fixed { Real::INFINITY } else { 1.0 },
        inertia: if fixed { Real::INFINITY } else { 1.0 },
        group: 0,
        drives: [Drive::Free, Drive::Free, Drive::Free],
    }
}

/// One body per `(kind, x, y, size, angle)`: kind modulo 3 picks a disk of radius `size`, a
/// triangle of that size or a wall of half-length `8 size`.
pub fn scene(specs: &[(u8, Real, Real, Real, Real)]) -> BodySet {
    let mut set = BodySet::new();
    for &(kind, x, y, size, angle) in specs {
        let shape = match kind % 3 {
            0 => Shape::Disk { radius: size },
            1 => Shape::Polygon(Box::new(ConvexPolygon::new(vec![
                Vector::new(-size, -size / 2.0),
                Vector::new(size, -size / 2.0),
                Vector::new(0.0, size),
            ]))),
            _ => Shape::Segment {
                half_length: size * 8.0,
            },
        };
        set.insert(body(shape, x, y, angle));
    }
    set
}
