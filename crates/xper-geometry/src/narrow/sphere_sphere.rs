//! Sphere against sphere.

use super::{round_point, Manifold};
use xper_math::{Real, Vector};

/// Contact between sphere `a` (centre `ca`, radius `ra`) and sphere `b`; normal from `a` to
/// `b`, gap the distance between the surfaces along the line of centres.
pub fn collide_spheres(ca: &Vector, ra: Real, cb: &Vector, rb: Real, alert: Real) -> Manifold {
    round_point(ca, ra, cb, rb, alert).map_or(Manifold::EMPTY, Manifold::one)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gap_normal_and_midpoint() {
        let (ca, cb) = (Vector::new(0.0, 0.0, 0.0), Vector::new(1.0, 2.0, 2.0));
        let m = collide_spheres(&ca, 1.0, &cb, 1.5, 1.0);
        let p = m.points[0];
        assert_eq!(m.len, 1);
        assert!((p.gap - 0.5).abs() < 1e-15);
        assert!((p.normal - Vector::new(1.0, 2.0, 2.0) / 3.0).norm() < 1e-15);
        // Midway between the surface points at distances 1 and 3 - 1.5 from ca.
        assert!((p.point - p.normal * 1.25).norm() < 1e-15);
        assert_eq!(collide_spheres(&ca, 1.0, &cb, 1.5, 0.49).len, 0);
    }
}
