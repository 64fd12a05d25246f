//! Convex polygon against convex polygon: separating axes, then clipping of the incident
//! edge against the reference edge (the manifold construction of E. Catto's Box2D,
//! "Contact manifolds", GDC 2007), giving two points for face-to-face contact.

use super::{ContactPoint, Manifold};
use xper_bodies::ConvexPolygon;
use xper_math::{rotate, Real, Vector};

/// A convex polygon in world coordinates (a segment is the 2-gon `[a, b]` with normals `+n, -n`).
#[derive(Clone, Debug)]
pub struct WorldPolygon {
    /// Vertices, counter-clockwise.
    pub vertices: Vec<Vector>,
    /// Outward unit normal of edge `k` (vertex `k` to `k + 1`).
    pub normals: Vec<Vector>,
}

impl WorldPolygon {
    /// Places a body-frame polygon.
    pub fn from_polygon(p: &ConvexPolygon, position: &Vector, angle: Real) -> Self {
        WorldPolygon {
            vertices: p
                .vertices
                .iter()
                .map(|v| position + rotate(v, angle))
                .collect(),
            normals: p.normals.iter().map(|n| rotate(n, angle)).collect(),
        }
    }

    /// The 2-gon of a segment from `a` to `b`.
    pub fn from_segment(a: Vector, b: Vector) -> Self {
        let e = (b - a).normalize();
        let n = Vector::new(e.y, -e.x);
        WorldPolygon {
            vertices: vec![a, b],
            normals: vec![n, -n],
        }
    }

    fn len(&self) -> usize {
        self.vertices.len()
    }
}

/// Largest separation of `b` from the edges of `a`: (separation, edge of `a`).
fn max_separation(a: &WorldPolygon, b: &WorldPolygon) -> (Real, usize) {
    let mut best = (Real::NEG_INFINITY, 0);
    for k in 0..a.len() {
        let (n, v) = (a.normals[k], a.vertices[k]);
        let s = b
            .vertices
            .iter()
            .map(|w| n.dot(&(w - v)))
            .fold(Real::INFINITY, Real::min);
        if s > best.0 {
            best = (s, k);
        }
    }
    best
}

/// Contact points between polygons `a` and `b`, normal from `a` to `b`.
pub fn collide_polygons(a: &WorldPolygon, b: &WorldPolygon, alert: Real) -> Manifold {
    let (sep_a, edge_a) = max_separation(a, b);
    if sep_a > alert {
        return Manifold::EMPTY;
    }
    let (sep_b, edge_b) = max_separation(b, a);
    if sep_b > alert {
        return Manifold::EMPTY;
    }
    let scale = a
        .vertices
        .iter()
        .chain(&b.vertices)
        .map(|v| v.norm())
        .fold(1e-300, Real::max);
    let flip = sep_b > sep_a + 1e-9 * scale;
    let (reference, incident, ref_edge) = if flip { (b, a, edge_b) } else { (a, b, edge_a) };
    let n_ref = reference.normals[ref_edge];
    let inc_edge = (0..incident.len())
        .min_by(|&i, &j| {
            incident.normals[i]
                .dot(&n_ref)
                .total_cmp(&incident.normals[j].dot(&n_ref))
        })
        .unwrap_or(0);
    let (r1, r2) = (
        reference.vertices[ref_edge],
        reference.vertices[(ref_edge + 1) % reference.len()],
    );
    let tangent = (r2 - r1).normalize();
    let mut seg = [
        incident.vertices[inc_edge],
        incident.vertices[(inc_edge + 1) % incident.len()],
    ];
    // Clip against the side planes t >= t(r1) and t <= t(r2).
    for (dir, offset) in [(-tangent, -tangent.dot(&r1)), (tangent, tangent.dot(&r2))] {
        let d = [dir.dot(&seg[0]) - offset, dir.dot(&seg[1]) - offset];
        if d[0] > 0.0 && d[1] > 0.0 {
            return Manifold::EMPTY;
        }
        if d[0] > 0.0 || d[1] > 0.0 {
            let cut = seg[0] + (seg[1] - seg[0]) * (d[0] / (d[0] - d[1]));
            if d[0] > 0.0 {
                seg[0] = cut;
            } else {
                seg[1] = cut;
            }
        }
    }
    let mut m = Manifold::EMPTY;
    for (k, p) in seg.iter().enumerate() {
        let gap = n_ref.dot(&(p - r1));
        if gap <= alert {
            let normal = if flip { -n_ref } else { n_ref };
            let feature = ((flip as u32) << 31)
                | ((ref_edge as u32) << 16)
                | ((inc_edge as u32) << 1)
                | k as u32;
            m.push(ContactPoint {
                point: p - n_ref * (gap / 2.0),
                normal,
                gap,
                feature,
            });
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(c: Vector, h: Real) -> WorldPolygon {
        let p = ConvexPolygon::new(vec![
            Vector::new(-h, -h),
            Vector::new(h, -h),
            Vector::new(h, h),
            Vector::new(-h, h),
        ]);
        WorldPolygon::from_polygon(&p, &c, 0.0)
    }

    #[test]
    fn stacked_squares_give_two_points() {
        let m = collide_polygons(
            &square(Vector::zeros(), 1.0),
            &square(Vector::new(0.5, 2.1), 1.0),
            0.5,
        );
        assert_eq!(m.len, 2);
        for p in m.as_slice() {
            assert!((p.gap - 0.1).abs() < 1e-12);
            assert!((p.normal - Vector::new(0.0, 1.0)).norm() < 1e-15);
        }
        let xs: Vec<Real> = m.as_slice().iter().map(|p| p.point.x).collect();
        assert!(
            xs.iter().any(|x| (x + 0.5).abs() < 1e-12)
                && xs.iter().any(|x| (x - 1.0).abs() < 1e-12)
        );
        assert_eq!(
            collide_polygons(
                &square(Vector::zeros(), 1.0),
                &square(Vector::new(0.0, 2.6), 1.0),
                0.5
            )
            .len,
            0
        );
    }

    #[test]
    fn normal_points_from_first_to_second() {
        let m = collide_polygons(
            &square(Vector::new(0.0, 2.05), 1.0),
            &square(Vector::zeros(), 1.0),
            0.5,
        );
        assert_eq!(m.len, 2);
        assert!((m.points[0].normal - Vector::new(0.0, -1.0)).norm() < 1e-15);
        assert!((m.points[0].gap - 0.05).abs() < 1e-12);
    }
}
