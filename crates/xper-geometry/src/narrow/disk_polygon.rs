//! Disk against a convex polygon.

use super::{ContactPoint, Manifold};
use xper_bodies::ConvexPolygon;
use xper_math::{rotate, Real, Vector};

/// Contact between a polygon placed at (`cp`, `angle`) and a disk; normal from the polygon to
/// the disk. The closest boundary point is found over all edges (exact for any convex polygon).
pub fn collide_disk_polygon(
    cd: &Vector,
    radius: Real,
    poly: &ConvexPolygon,
    cp: &Vector,
    angle: Real,
    alert: Real,
) -> Manifold {
    let local = rotate(&(cd - cp), -angle);
    let n = poly.vertices.len();
    let (mut best_sep, mut best_face) = (Real::NEG_INFINITY, 0);
    for k in 0..n {
        let s = poly.normals[k].dot(&(local - poly.vertices[k]));
        if s > best_sep {
            best_sep = s;
            best_face = k;
        }
    }
    if best_sep > radius + alert {
        return Manifold::EMPTY;
    }
    let (closest, normal_local, dist, feature) = if best_sep <= 0.0 {
        let nrm = poly.normals[best_face];
        (local - nrm * best_sep, nrm, best_sep, best_face as u32)
    } else {
        let mut best = (Vector::zeros(), Real::INFINITY, 0u32);
        for k in 0..n {
            let (a, b) = (poly.vertices[k], poly.vertices[(k + 1) % n]);
            let e = b - a;
            let t = ((local - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
            let p = a + e * t;
            let d = (local - p).norm();
            if d < best.1 {
                best = (p, d, k as u32);
            }
        }
        let nrm = if best.1 > 0.0 {
            (local - best.0) / best.1
        } else {
            poly.normals[best.2 as usize]
        };
        (best.0, nrm, best.1, best.2)
    };
    let gap = dist - radius;
    if gap > alert {
        return Manifold::EMPTY;
    }
    let normal = rotate(&normal_local, angle);
    let point = cp + rotate(&closest, angle) + normal * (gap / 2.0);
    Manifold::one(ContactPoint {
        point,
        normal,
        gap,
        feature,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square() -> ConvexPolygon {
        ConvexPolygon::new(vec![
            Vector::new(-0.5, -0.5),
            Vector::new(0.5, -0.5),
            Vector::new(0.5, 0.5),
            Vector::new(-0.5, 0.5),
        ])
    }

    #[test]
    fn face_corner_and_inside() {
        let sq = unit_square();
        let m = collide_disk_polygon(&Vector::new(0.1, 1.0), 0.4, &sq, &Vector::zeros(), 0.0, 1.0);
        assert!((m.points[0].gap - 0.1).abs() < 1e-15);
        let m = collide_disk_polygon(&Vector::new(1.5, 1.5), 0.1, &sq, &Vector::zeros(), 0.0, 2.0);
        assert!((m.points[0].gap - (2f64.sqrt() - 0.1)).abs() < 1e-15);
        let m = collide_disk_polygon(&Vector::new(0.4, 0.0), 0.2, &sq, &Vector::zeros(), 0.0, 0.0);
        assert!((m.points[0].gap + 0.3).abs() < 1e-15);
        assert!((m.points[0].normal - Vector::new(1.0, 0.0)).norm() < 1e-15);
        // Rotated by 90 degrees, the same square.
        let m = collide_disk_polygon(
            &Vector::new(0.1, 1.0),
            0.4,
            &sq,
            &Vector::zeros(),
            std::f64::consts::FRAC_PI_2,
            1.0,
        );
        assert!((m.points[0].gap - 0.1).abs() < 1e-12);
    }
}
