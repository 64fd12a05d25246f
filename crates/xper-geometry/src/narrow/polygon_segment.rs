//! Convex polygon against a wall segment, through the polygon-polygon manifold with the
//! segment as a 2-gon.

use super::polygon_polygon::{collide_polygons, WorldPolygon};
use super::Manifold;
use xper_bodies::ConvexPolygon;
use xper_math::{rotate, Real, Vector};

/// Contact between a polygon placed at (`cp`, `angle_p`) and a segment (centre `cs`, rotation
/// `angle_s`, half-length `half`); normal from the polygon to the segment.
pub fn collide_polygon_segment(
    poly: &ConvexPolygon,
    cp: &Vector,
    angle_p: Real,
    cs: &Vector,
    angle_s: Real,
    half: Real,
    alert: Real,
) -> Manifold {
    let d = rotate(&Vector::new(half, 0.0), angle_s);
    let segment = WorldPolygon::from_segment(cs - d, cs + d);
    collide_polygons(
        &WorldPolygon::from_polygon(poly, cp, angle_p),
        &segment,
        alert,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_resting_on_incline_touches_at_two_corners() {
        let slope: Real = 0.3;
        let block = ConvexPolygon::new(vec![
            Vector::new(-0.5, -0.25),
            Vector::new(0.5, -0.25),
            Vector::new(0.5, 0.25),
            Vector::new(-0.5, 0.25),
        ]);
        let up = Vector::new(-slope.sin(), slope.cos());
        let centre = up * 0.25;
        let m =
            collide_polygon_segment(&block, &centre, slope, &Vector::zeros(), slope, 10.0, 1e-3);
        assert_eq!(m.len, 2);
        for p in m.as_slice() {
            assert!(p.gap.abs() < 1e-12, "{p:?}");
            assert!((p.normal + up).norm() < 1e-12);
        }
    }
}
