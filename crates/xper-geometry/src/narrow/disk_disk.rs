//! Disk against disk.

use super::{ContactPoint, Manifold};
use xper_math::{Real, Vector};

/// Contact between disk `a` (centre `ca`, radius `ra`) and disk `b`; normal from `a` to `b`.
pub fn collide_disk_disk(ca: &Vector, ra: Real, cb: &Vector, rb: Real, alert: Real) -> Manifold {
    disk_disk_point(ca, ra, cb, rb, alert).map_or(Manifold::EMPTY, Manifold::one)
}

/// The contact point of [`collide_disk_disk`], `None` beyond the alert distance.
#[inline(always)]
pub fn disk_disk_point(
    ca: &Vector,
    ra: Real,
    cb: &Vector,
    rb: Real,
    alert: Real,
) -> Option<ContactPoint> {
    let d = cb - ca;
    let dist2 = d.norm_squared();
    let reach = ra + rb + alert;
    if dist2 > reach * reach {
        return None;
    }
    let dist = dist2.sqrt();
    let normal = if dist > 0.0 {
        d / dist
    } else {
        Vector::new(1.0, 0.0)
    };
    let gap = dist - ra - rb;
    Some(ContactPoint {
        point: ca + normal * (ra + gap / 2.0),
        normal,
        gap,
        feature: 0,
    })
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
