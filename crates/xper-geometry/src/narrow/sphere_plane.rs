//! Sphere against a planar wall: a rectangle (or, with infinite half-extents, the boundary of a
//! half-space) touched on its front face, edges and corners.

use super::{ContactPoint, Manifold};
use xper_math::{Real, Rotation, Vector};

/// Contact between a wall (centre `cw`, orientation `q`, outward normal `q e_z`, half-extents
/// `half` along `q e_x`, `q e_y`) and a sphere; normal from the wall to the sphere. A centre
/// above the rectangle touches the face (normal `q e_z`, gap its height minus the radius, also
/// when negative, unless the sphere lies wholly behind the plane by more than `alert`);
/// beside it, the nearest point of the rectangle's border; behind the plane and beside the
/// rectangle, nothing.
pub fn collide_sphere_plane(
    cs: &Vector,
    radius: Real,
    cw: &Vector,
    q: Rotation,
    half: [Real; 2],
    alert: Real,
) -> Manifold {
    let local = q.inverse() * (cs - cw);
    let clamped = Vector::new(
        local.x.clamp(-half[0], half[0]),
        local.y.clamp(-half[1], half[1]),
        0.0,
    );
    let beside = clamped.x != local.x || clamped.y != local.y;
    let (normal_local, dist, feature) = if !beside {
        // Entirely behind the wall by more than `alert`: no contact (the boxes do not meet).
        if local.z + radius < -alert {
            return Manifold::EMPTY;
        }
        (Vector::z(), local.z, 0)
    } else {
        if local.z < 0.0 {
            return Manifold::EMPTY;
        }
        let d = local - clamped;
        let dist = d.norm();
        (d / dist, dist, 1)
    };
    let gap = dist - radius;
    if gap > alert {
        return Manifold::EMPTY;
    }
    let normal = q * normal_local;
    // The wall's surface point: the nearest point of the border, or the centre's projection.
    let surface = if beside {
        cw + q * clamped
    } else {
        cs - normal * dist
    };
    Manifold::one(ContactPoint {
        point: surface + normal * (gap / 2.0),
        normal,
        gap,
        feature,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use xper_math::SplitMix64;

    /// Against the distance to the rectangle found by sampling it on a fine grid (an
    /// independent computation): the gap within the grid's resolution, never above it.
    #[test]
    fn gap_matches_the_sampled_distance_to_the_rectangle() {
        let mut rng = SplitMix64::new(5);
        let q = Rotation::from_scaled_axis(Vector::new(0.3, -0.5, 0.2));
        let (cw, half) = (Vector::new(1.0, 2.0, 3.0), [1.0, 0.5]);
        let samples = 400;
        let mut checked = 0;
        for _ in 0..200 {
            let local = Vector::new(
                3.0 * rng.next_f64() - 1.5,
                2.0 * rng.next_f64() - 1.0,
                1.5 * rng.next_f64() - 0.2,
            );
            let cs = cw + q * local;
            let m = collide_sphere_plane(&cs, 0.3, &cw, q, half, 10.0);
            let wholly_behind = local.z + 0.3 < -10.0;
            if wholly_behind
                || local.z < 0.0 && (local.x.abs() > half[0] || local.y.abs() > half[1])
            {
                assert_eq!(m.len, 0);
                continue;
            }
            let mut best = Real::INFINITY;
            for i in 0..=samples {
                for j in 0..=samples {
                    let s = Vector::new(
                        half[0] * (2.0 * i as Real / samples as Real - 1.0),
                        half[1] * (2.0 * j as Real / samples as Real - 1.0),
                        0.0,
                    );
                    best = best.min((local - s).norm());
                }
            }
            let p = m.points[0];
            let expected = if local.z < 0.0 { local.z } else { best } - 0.3;
            let resolution = 2.0 * half[0] / samples as Real;
            assert!(
                p.gap <= expected + 1e-12 && p.gap >= expected - resolution,
                "{local:?}"
            );
            // The point lies midway between the surfaces along the normal.
            let on_sphere = cs - p.normal * 0.3;
            assert!((p.point - (on_sphere - p.normal * (p.gap / 2.0))).norm() < 1e-12);
            checked += 1;
        }
        assert!(checked > 100);
    }
}
