//! Convex polyhedron against a planar wall: the vertices over the rectangle within the alert
//! distance, at most four kept.

use super::dim3::reduce;
use super::{ContactPoint, Manifold};
use xper_bodies::ConvexPolyhedron;
use xper_math::{Real, Rotation, Vector};

/// Contact between a wall (centre `cw`, orientation `qw`, outward normal `qw e_z`,
/// half-extents `half`) and a polyhedron (centroid `cp`, orientation `qp`); normal from the
/// wall to the polyhedron, one point per vertex over the rectangle within `alert` of its
/// plane (`feature` the vertex). A face lying on the wall gives its corners: four for a box,
/// each carrying its share of the load. More than four candidates (a face of many vertices)
/// are reduced to four spanning the largest area: the deepest, the farthest from it, then
/// the two farthest on either side of the line through those two.
///
/// Edges crossing the rectangle's border are not tested: walls are meant larger than the
/// bodies on them. A body entirely behind the wall (by more than `alert`) touches nothing.
pub fn collide_polyhedron_plane(
    poly: &ConvexPolyhedron,
    cp: &Vector,
    qp: Rotation,
    cw: &Vector,
    qw: Rotation,
    half: [Real; 2],
    alert: Real,
) -> Manifold {
    let to_wall = qw.inverse();
    let centre = to_wall * (cp - cw);
    if centre.z - poly.bounding_radius > alert {
        return Manifold::EMPTY;
    }
    let normal = qw * Vector::z();
    let mut candidates: Vec<(Vector, Real, u32)> = Vec::new();
    for (k, v) in poly.vertices.iter().enumerate() {
        let local = centre + to_wall * (qp * v);
        if local.z <= alert && local.x.abs() <= half[0] && local.y.abs() <= half[1] {
            candidates.push((local, local.z, k as u32));
        }
    }
    // A body entirely behind the wall, farther than the alert distance, does not touch it:
    // its box and the wall's do not meet, so the broad phase would not pair them either.
    let highest = (poly.vertices.iter())
        .map(|v| (centre + to_wall * (qp * v)).z)
        .fold(Real::NEG_INFINITY, Real::max);
    if highest < -alert {
        return Manifold::EMPTY;
    }
    let keep = reduce(
        candidates.len(),
        |k| candidates[k].0,
        |k| candidates[k].1,
        &Vector::z(),
    );
    let mut m = Manifold::EMPTY;
    for &k in &keep {
        let (local, gap, feature) = candidates[k];
        let on_wall = cw + qw * Vector::new(local.x, local.y, 0.0);
        m.push(ContactPoint {
            point: on_wall + normal * (gap / 2.0),
            normal,
            gap,
            feature,
        });
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A box resting face-down gives its four bottom corners, each at the same gap; tilted
    /// about an edge, the two corners of that edge; on its corner, one.
    #[test]
    fn a_box_on_a_plane() {
        let half = Vector::new(0.2, 0.1, 0.05);
        let cube = ConvexPolyhedron::cuboid(half);
        let (cw, qw) = (Vector::zeros(), Rotation::identity());
        let cp = Vector::new(0.3, -0.2, 0.05 + 1e-4);
        let m = collide_polyhedron_plane(&cube, &cp, Rotation::identity(), &cw, qw, [1.0; 2], 1e-3);
        assert_eq!(m.len, 4);
        for p in m.as_slice() {
            assert!((p.gap - 1e-4).abs() < 1e-15);
            assert!((p.normal - Vector::z()).norm() < 1e-15);
        }
        let sum: Vector = m.as_slice().iter().map(|p| p.point).sum();
        assert!((sum / 4.0 - Vector::new(0.3, -0.2, 5e-5)).norm() < 1e-14);
        let about_edge = Rotation::from_scaled_axis(Vector::new(0.0, 0.1, 0.0));
        let m = collide_polyhedron_plane(
            &cube,
            &(cp + Vector::z()),
            about_edge,
            &cw,
            qw,
            [1.0; 2],
            1.0,
        );
        let lowest = m
            .as_slice()
            .iter()
            .map(|p| p.gap)
            .fold(Real::INFINITY, Real::min);
        let count = m
            .as_slice()
            .iter()
            .filter(|p| p.gap < lowest + 1e-12)
            .count();
        assert_eq!(count, 2, "{m:?}");
        let corner = Rotation::from_scaled_axis(Vector::new(0.3, 0.2, 0.0));
        let m = collide_polyhedron_plane(
            &cube,
            &(cp + Vector::z() * 0.05),
            corner,
            &cw,
            qw,
            [1.0; 2],
            0.0,
        );
        assert_eq!(m.len, 1);
    }

    /// A prism whose bottom face has eight corners keeps four of them, spanning the face.
    #[test]
    fn many_coplanar_vertices_are_reduced_to_four() {
        let points: Vec<Vector> = (0..8)
            .flat_map(|k| {
                let a = k as Real * std::f64::consts::FRAC_PI_4;
                [
                    Vector::new(a.cos(), a.sin(), 0.0),
                    Vector::new(a.cos(), a.sin(), 1.0),
                ]
            })
            .collect();
        let (prism, centroid) = ConvexPolyhedron::hull(&points).unwrap();
        let m = collide_polyhedron_plane(
            &prism,
            &centroid,
            Rotation::identity(),
            &Vector::zeros(),
            Rotation::identity(),
            [10.0; 2],
            0.1,
        );
        assert_eq!(m.len, 4);
        let area = |a: Vector, b: Vector, c: Vector| (b - a).cross(&(c - a)).norm() / 2.0;
        let p: Vec<Vector> = m.as_slice().iter().map(|p| p.point).collect();
        // The quadrilateral's area: that of the square inscribed in the unit octagon, 2.
        let quad = area(p[0], p[1], p[2]) + area(p[0], p[1], p[3]);
        assert!((quad - 2.0).abs() < 1e-9, "{quad}");
    }
}
