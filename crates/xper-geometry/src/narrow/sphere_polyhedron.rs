//! Sphere against a convex polyhedron.

use super::dim3::inside_face;
use super::{ContactPoint, Manifold};
use xper_bodies::ConvexPolyhedron;
use xper_math::{Real, Rotation, Vector};

/// Contact between a polyhedron (centroid `cp`, orientation `q`) and a sphere; normal from the
/// polyhedron to the sphere. With the centre outside, the nearest point of the polyhedron's
/// surface (on a face, an edge or a vertex; `feature` the face it was found on); inside, the
/// face the centre is nearest to, with a negative gap.
pub fn collide_sphere_polyhedron(
    cs: &Vector,
    radius: Real,
    poly: &ConvexPolyhedron,
    cp: &Vector,
    q: Rotation,
    alert: Real,
) -> Manifold {
    let c = q.inverse() * (cs - cp);
    if (c.norm() - poly.bounding_radius - radius) > alert {
        return Manifold::EMPTY;
    }
    // Signed distance of the centre to each face's plane; the largest decides inside/outside.
    let (mut deepest, mut deepest_face) = (Real::NEG_INFINITY, 0);
    let (mut nearest, mut nearest_dist, mut nearest_face) = (Vector::zeros(), Real::INFINITY, 0);
    for (f, (face, n)) in poly.faces.iter().zip(&poly.normals).enumerate() {
        let s = n.dot(&(c - poly.vertices[face[0] as usize]));
        if s > deepest {
            (deepest, deepest_face) = (s, f);
        }
        if s > 0.0 {
            let p = closest_on_face(poly, face, n, &c);
            let d = (c - p).norm();
            if d < nearest_dist {
                (nearest, nearest_dist, nearest_face) = (p, d, f);
            }
        }
    }
    let (normal_local, surface, dist, feature) = if deepest <= 0.0 {
        let n = poly.normals[deepest_face];
        (n, c - n * deepest, deepest, deepest_face)
    } else {
        (
            (c - nearest) / nearest_dist,
            nearest,
            nearest_dist,
            nearest_face,
        )
    };
    let gap = dist - radius;
    if gap > alert {
        return Manifold::EMPTY;
    }
    let normal = q * normal_local;
    Manifold::one(ContactPoint {
        point: cp + q * surface + normal * (gap / 2.0),
        normal,
        gap,
        feature: feature as u32,
    })
}

/// The point of a convex face (vertices counter-clockwise about its outward normal `n`)
/// nearest to `c`: the projection of `c` on the plane when inside the face, else the nearest
/// point of its edges.
fn closest_on_face(poly: &ConvexPolyhedron, face: &[u32], n: &Vector, c: &Vector) -> Vector {
    let v = |k: usize| poly.vertices[face[k % face.len()] as usize];
    let projected = c - n * n.dot(&(c - v(0)));
    if inside_face(face.len(), v, n, &projected) {
        return projected;
    }
    (0..face.len())
        .map(|k| {
            let (a, b) = (v(k), v(k + 1));
            let e = b - a;
            let t = ((c - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
            a + e * t
        })
        .min_by(|p, r| (c - p).norm_squared().total_cmp(&(c - r).norm_squared()))
        .unwrap_or(projected)
}

#[cfg(test)]
mod tests {
    use super::*;
    use xper_math::SplitMix64;

    /// Against the distance to the surface found by sampling its faces densely (triangles of
    /// each face's fan, an independent computation) for centres outside, and the depth below
    /// the nearest face for centres inside.
    #[test]
    fn gap_matches_the_sampled_distance_to_the_surface() {
        let mut rng = SplitMix64::new(11);
        let points: Vec<Vector> = (0..12)
            .map(|_| Vector::new(rng.next_f64(), rng.next_f64(), 0.6 * rng.next_f64()))
            .collect();
        let (poly, _) = ConvexPolyhedron::hull(&points).unwrap();
        let (cp, q) = (
            Vector::new(0.5, -1.0, 2.0),
            Rotation::from_scaled_axis(Vector::new(0.2, 0.9, -0.4)),
        );
        let n = 60;
        let mut surface = Vec::new();
        for face in &poly.faces {
            let a = poly.vertices[face[0] as usize];
            for w in face[1..].windows(2) {
                let (b, c) = (poly.vertices[w[0] as usize], poly.vertices[w[1] as usize]);
                for i in 0..=n {
                    for j in 0..=n - i {
                        let (s, t) = (i as Real / n as Real, j as Real / n as Real);
                        surface.push(a + (b - a) * s + (c - a) * t);
                    }
                }
            }
        }
        let (mut outside, mut inside) = (0, 0);
        for _ in 0..300 {
            let local = Vector::new(
                2.0 * rng.next_f64() - 0.5,
                2.0 * rng.next_f64() - 0.5,
                1.6 * rng.next_f64() - 0.5,
            );
            let m = collide_sphere_polyhedron(&(cp + q * local), 0.1, &poly, &cp, q, 10.0);
            assert_eq!(m.len, 1);
            let p = m.points[0];
            let is_inside = poly
                .faces
                .iter()
                .zip(&poly.normals)
                .all(|(f, nrm)| nrm.dot(&(local - poly.vertices[f[0] as usize])) <= 0.0);
            let sampled = surface
                .iter()
                .map(|s| (local - s).norm())
                .fold(Real::INFINITY, Real::min);
            if is_inside {
                inside += 1;
                // The depth is the distance to the nearest face plane: at most the sampled
                // distance to the surface.
                assert!(-(p.gap + 0.1) <= sampled + 1e-12, "{local:?}");
            } else {
                outside += 1;
                let resolution = 0.05;
                assert!(
                    p.gap + 0.1 <= sampled + 1e-12,
                    "{local:?}: {} vs {sampled}",
                    p.gap
                );
                assert!(p.gap + 0.1 >= sampled - resolution, "{local:?}");
            }
            // Midway between the two surfaces along the normal.
            let on_sphere = cp + q * local - p.normal * 0.1;
            assert!((p.point - (on_sphere - p.normal * (p.gap / 2.0))).norm() < 1e-12);
        }
        assert!(
            outside > 100 && inside > 5,
            "{outside} outside, {inside} inside"
        );
    }
}
