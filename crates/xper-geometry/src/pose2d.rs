//! The 2D pose of a body at a candidate-list build (see `detector.rs`): position and angle in
//! single precision, with the bound on what their rounding hides.

use crate::narrow::{round_point, ContactPoint};
use xper_bodies::Shape;
use xper_math::{Real, Rotation, Vector};

/// A body's orientation at the build: its angle brought into `[-pi, pi]` (see [`wrapped`]),
/// so that its rounding stays small however long the body has turned (a rotating drum).
pub(crate) type Orientation = f32;

/// A body's pose when the candidate list was built, in single precision: the rounding is
/// bounded by the detector's `pose_rounding` and added to the displacement bounds, so no pair
/// within the alert distance is missed. A detector keeps the position of every body (8 bytes)
/// and the orientation and reach only of the bodies with a reach (not disks).
#[derive(Clone, Copy, Debug)]
pub(crate) struct BuildPose {
    pub position: [f32; 2],
    pub orientation: Orientation,
    /// The reach, rounded up.
    pub reach: f32,
}

/// The pose of `(p, angle)` with `reach`, and the most its rounding can hide of the
/// displacement bound `d_b`: `|p' - p| + reach' (|angle' - wrapped(angle)| + e)`, with `e`
/// the rounding of the wrap itself.
pub(crate) fn rounded(p: &Vector, angle: Rotation, reach: Real) -> (BuildPose, Real) {
    BuildPose::rounded(p.x, p.y, angle, reach)
}

/// A bound on the angle a body has turned since its orientation was `built`.
#[inline(always)]
pub(crate) fn turned(angle: Rotation, built: &Orientation) -> Real {
    wrapped(angle - *built as Real).abs() + wrap_error(angle)
}

/// The largest distance from a body's position to its shape, 0 for a disk (whose rotation
/// moves no point of it).
pub(crate) fn reach(shape: &Shape) -> Real {
    match shape {
        Shape::Disk { .. } => 0.0,
        Shape::Polygon(p) => p.bounding_radius,
        Shape::Segment { half_length } => *half_length,
    }
}

/// The contact of two disks without the general dispatch: `Some` of the point (or of `None`
/// beyond `alert`) for two disks, `None` for other shapes.
#[inline(always)]
pub(crate) fn round_pair(
    a: &Shape,
    b: &Shape,
    pa: &Vector,
    pb: &Vector,
    alert: Real,
) -> Option<Option<ContactPoint>> {
    match (a, b) {
        (Shape::Disk { radius: ra }, Shape::Disk { radius: rb }) => {
            Some(round_point(pa, *ra, pb, *rb, alert))
        }
        _ => None,
    }
}

impl BuildPose {
    fn rounded(x: Real, y: Real, angle: Real, reach: Real) -> (Self, Real) {
        let mut reach32 = reach as f32;
        if (reach32 as Real) < reach {
            reach32 = reach32.next_up();
        }
        let turned = wrapped(angle);
        let pose = BuildPose {
            position: [x as f32, y as f32],
            orientation: turned as f32,
            reach: reach32,
        };
        let (dx, dy) = (pose.position[0] as Real - x, pose.position[1] as Real - y);
        let angle_error = (pose.orientation as Real - turned).abs() + wrap_error(angle);
        let hidden = (dx * dx + dy * dy).sqrt() + reach32 as Real * angle_error;
        (pose, hidden)
    }
}

/// `angle` less the nearest multiple of 2 pi, in `[-pi, pi]`: the smallest rotation that
/// brings a shape from one orientation to another is `|wrapped(theta - theta_0)|`, whatever
/// whole turns lie between them.
#[inline]
fn wrapped(angle: Real) -> Real {
    use std::f64::consts::TAU;
    angle - TAU * (angle / TAU).round()
}

/// A bound on the rounding of [`wrapped`]`(angle)` (a few units in the last place of `angle`
/// and of 2 pi times the turns).
#[inline]
fn wrap_error(angle: Real) -> Real {
    8.0 * Real::EPSILON * (angle.abs() + 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_precision_pose_hides_no_more_than_its_rounding_bound() {
        let mut s = 3u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as Real / (1u64 << 53) as Real * 2.0 - 1.0
        };
        for _ in 0..10_000 {
            let scale = 10f64.powi((rnd() * 6.0) as i32);
            let (x, y, angle, reach) = (rnd() * scale, rnd() * scale, rnd() * 7.0, rnd().abs());
            let (pose, hidden) = BuildPose::rounded(x, y, angle, reach);
            assert!(pose.reach as Real >= reach, "reach rounded up");
            // The bound a body at the true pose gets from the stored one, and what it hides.
            let (dx, dy) = (x - pose.position[0] as Real, y - pose.position[1] as Real);
            let seen = (dx * dx + dy * dy).sqrt()
                + pose.reach as Real * wrapped(angle - pose.orientation as Real).abs();
            assert!(seen <= hidden * (1.0 + 1e-12), "{seen} > {hidden}");
            assert!(hidden <= 4.0 * f32::EPSILON as Real * (x.abs() + y.abs() + angle.abs() + 1.0));
        }
    }

    /// Regression: with the rotation stored as it is, a body that had turned for long (a
    /// drum of 0.5 m after 1000 turns, 6283 rad) hid 1.2e-4 m in its single-precision angle,
    /// as much as an alert distance, and its list was rebuilt at every step.
    #[test]
    fn a_long_turning_body_hides_no_more_than_one_that_never_turned() {
        let reach = 0.5;
        for turns in [0.0, 1.0, 1000.0, 1.0e5] {
            let angle = 0.3 + std::f64::consts::TAU * turns;
            let (pose, hidden) = BuildPose::rounded(0.1, 0.2, angle, reach);
            assert!(
                hidden <= 1e-7 * (1.0 + turns * 1e-8),
                "{turns} turns: {hidden} m"
            );
            // A further turn and a small rotation read as that small rotation.
            let later = angle + std::f64::consts::TAU + 1e-3;
            let turned = wrapped(later - pose.orientation as Real).abs();
            assert!((turned - 1e-3).abs() < 1e-6, "{turns} turns: {turned}");
        }
    }
}
