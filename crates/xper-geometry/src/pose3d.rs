//! The 3D pose of a body at a candidate-list build (see `detector.rs`): position and unit
//! quaternion in single precision, with the bound on what their rounding hides.
//!
//! A point at distance at most `reach` from the body's position moves by at most
//! `reach theta` under a rotation of angle `theta` (`2 reach sin(theta / 2)`), and the angle
//! between two orientations obeys the triangle inequality (it is the geodesic distance on the
//! rotations), so the angle from the stored orientation plus the angle between the stored and
//! the true one at the build bounds the turn since the build.

use crate::narrow::{round_point, ContactPoint};
use nalgebra::Quaternion;
use xper_bodies::Shape;
use xper_math::{Real, Rotation, Vector};

/// A body's orientation at the build: its quaternion `[w, i, j, k]` in single precision.
pub(crate) type Orientation = [f32; 4];

/// A body's pose when the candidate list was built, in single precision.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BuildPose {
    pub position: [f32; 3],
    pub orientation: Orientation,
    /// The reach, rounded up.
    pub reach: f32,
}

/// The pose of `(p, q)` with `reach`, and the most its rounding can hide of the displacement
/// bound: `|p' - p| + reach' angle(q', q)`.
pub(crate) fn rounded(p: &Vector, q: Rotation, reach: Real) -> (BuildPose, Real) {
    let mut reach32 = reach as f32;
    if (reach32 as Real) < reach {
        reach32 = reach32.next_up();
    }
    let c = q.quaternion();
    let pose = BuildPose {
        position: [p.x as f32, p.y as f32, p.z as f32],
        orientation: [c.w as f32, c.i as f32, c.j as f32, c.k as f32],
        reach: reach32,
    };
    let back = Vector::new(
        pose.position[0] as Real,
        pose.position[1] as Real,
        pose.position[2] as Real,
    );
    let hidden = (back - p).norm() + reach32 as Real * turned(q, &pose.orientation);
    (pose, hidden)
}

/// A bound on the angle of the rotation from the orientation `built` to `q` (rad): the angle
/// of `q^-1 b`, `2 atan2(|v|, |w|)` (which does not need `b` normalised), plus a margin for
/// the rounding of this computation.
#[inline]
pub(crate) fn turned(q: Rotation, built: &Orientation) -> Real {
    let [w, i, j, k] = built.map(|x| x as Real);
    let relative = q.quaternion().conjugate() * Quaternion::new(w, i, j, k);
    2.0 * relative.imag().norm().atan2(relative.w.abs()) + 32.0 * Real::EPSILON
}

/// The largest distance from a body's position to its shape: 0 for a sphere; for a plane,
/// the half-diagonal of its rectangle, and 0 for an unbounded one (a half-space's boundary,
/// whose rotation the candidate list does not follow: such a wall must not turn).
pub(crate) fn reach(shape: &Shape) -> Real {
    match shape {
        Shape::Sphere { .. } => 0.0,
        Shape::Polyhedron(p) => p.bounding_radius,
        Shape::Plane {
            half_extents: [a, b],
        } => {
            let r = a.hypot(*b);
            if r.is_finite() {
                r
            } else {
                0.0
            }
        }
    }
}

/// The contact of two spheres without the general dispatch: `Some` of the point (or of
/// `None` beyond `alert`) for two spheres, `None` for other shapes.
#[inline(always)]
pub(crate) fn round_pair(
    a: &Shape,
    b: &Shape,
    pa: &Vector,
    pb: &Vector,
    alert: Real,
) -> Option<Option<ContactPoint>> {
    match (a, b) {
        (Shape::Sphere { radius: ra }, Shape::Sphere { radius: rb }) => {
            Some(round_point(pa, *ra, pb, *rb, alert))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use xper_math::SplitMix64;

    /// What the stored pose lets a body see of its own displacement never falls short of the
    /// true one by more than the bound `rounded` reports: for random poses, a point at the
    /// reach moved by the true rotation since the build is within `|dp| + reach turned`.
    #[test]
    fn a_single_precision_pose_hides_no_more_than_its_rounding_bound() {
        let mut rng = SplitMix64::new(17);
        for _ in 0..10_000 {
            let mut r = || 2.0 * rng.next_f64() - 1.0;
            let scale = 10f64.powi((r() * 6.0) as i32);
            let p = Vector::new(r(), r(), r()) * scale;
            let q = Rotation::from_scaled_axis(Vector::new(r(), r(), r()) * 3.0);
            let reach = r().abs() + 0.01;
            let (pose, hidden) = rounded(&p, q, reach);
            assert!(pose.reach as Real >= reach);
            assert!(hidden <= 1e-6 * (p.norm() + reach + 1.0), "{hidden}");
            // Later: moved by dp and turned by a small rotation dq.
            let dp = Vector::new(r(), r(), r()) * 1e-3;
            let dq = Rotation::from_scaled_axis(Vector::new(r(), r(), r()) * 1e-3);
            let later = dq * q;
            let stored = Vector::new(
                pose.position[0] as Real,
                pose.position[1] as Real,
                pose.position[2] as Real,
            );
            let bound =
                (p + dp - stored).norm() + pose.reach as Real * turned(later, &pose.orientation);
            // The true largest displacement of a point at the reach.
            let arm = Vector::new(r(), r(), r()).normalize() * reach;
            let moved = (p + dp + later * (q.inverse() * arm)) - (p + arm);
            assert!(
                moved.norm() <= bound + hidden + 1e-12,
                "{} > {}",
                moved.norm(),
                bound + hidden
            );
        }
    }

    /// The angle between orientations is that of the rotation between them, whatever the
    /// quaternions' signs.
    #[test]
    fn turned_is_the_rotation_angle() {
        let q = Rotation::from_scaled_axis(Vector::new(0.3, -0.2, 0.9));
        let later = Rotation::from_scaled_axis(Vector::new(0.0, 0.0, 0.25)) * q;
        let c = q.quaternion();
        for sign in [1.0f32, -1.0] {
            let built = [c.w as f32, c.i as f32, c.j as f32, c.k as f32].map(|x| sign * x);
            assert!((turned(later, &built) - 0.25).abs() < 1e-6);
        }
    }
}
