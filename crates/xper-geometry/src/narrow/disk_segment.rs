//! Disk against a wall segment (two-sided, rounded ends).

use super::{ContactPoint, Manifold};
use xper_math::{rotate, Real, Vector};

/// Contact between a segment (centre `cs`, rotation `angle`, half-length `half`) and a disk;
/// normal from the segment to the disk.
pub fn collide_disk_segment(
    cd: &Vector,
    radius: Real,
    cs: &Vector,
    angle: Real,
    half: Real,
    alert: Real,
) -> Manifold {
    let dir = rotate(&Vector::new(1.0, 0.0), angle);
    let s = (cd - cs).dot(&dir).clamp(-half, half);
    let closest = cs + dir * s;
    let d = cd - closest;
    let dist = d.norm();
    let gap = dist - radius;
    if gap > alert {
        return Manifold::EMPTY;
    }
    let normal = if dist > 0.0 {
        d / dist
    } else {
        Vector::new(-dir.y, dir.x)
    };
    Manifold::one(ContactPoint {
        point: closest + normal * (gap / 2.0),
        normal,
        gap,
        feature: 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disk_above_and_beyond_end() {
        let m = collide_disk_segment(&Vector::new(0.3, 1.1), 1.0, &Vector::zeros(), 0.0, 1.0, 0.2);
        assert!((m.points[0].gap - 0.1).abs() < 1e-15);
        assert!((m.points[0].normal - Vector::new(0.0, 1.0)).norm() < 1e-15);
        // Beyond the right end: distance to the end point.
        let m = collide_disk_segment(&Vector::new(1.6, 0.8), 0.5, &Vector::zeros(), 0.0, 1.0, 1.0);
        assert!((m.points[0].gap - 0.5).abs() < 1e-15);
    }
}
