//! Disk against disk.

use super::{round_point, Manifold};
use xper_math::{Real, Vector};

/// Contact between disk `a` (centre `ca`, radius `ra`) and disk `b`; normal from `a` to `b`.
pub fn collide_disk_disk(ca: &Vector, ra: Real, cb: &Vector, rb: Real, alert: Real) -> Manifold {
    round_point(ca, ra, cb, rb, alert).map_or(Manifold::EMPTY, Manifold::one)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gap_normal_and_midpoint() {
        let m = collide_disk_disk(
            &Vector::new(0.0, 0.0),
            1.0,
            &Vector::new(3.0, 4.0),
            3.5,
            1.0,
        );
        assert_eq!(m.len, 1);
        let p = m.points[0];
        assert!((p.gap - 0.5).abs() < 1e-15);
        assert!((p.normal - Vector::new(0.6, 0.8)).norm() < 1e-15);
        assert!((p.point - Vector::new(0.6, 0.8) * 1.25).norm() < 1e-15);
        assert_eq!(
            collide_disk_disk(&Vector::zeros(), 1.0, &Vector::new(3.0, 4.0), 3.5, 0.4).len,
            0
        );
    }
}
