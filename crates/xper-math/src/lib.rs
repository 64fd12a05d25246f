//! The dimension abstraction of xper.
//!
//! Every crate names spatial quantities through the aliases of this module and never through
//! a concrete `Vector2` or a literal `2`, in the manner of rapier's `math` module: the 2D build
//! maps them to 2D types; a 3D build maps the same names to 3D types (`Vector3`, a rotation
//! vector for angular quantities, a local contact frame of size 3) so that one source tree
//! serves both dimensions. Only the 2D mapping exists today.
//!
//! Conventions (SI units throughout):
//! - a rigid body has `DOFS = DIM + ANGULAR_DIM` generalised velocity components, ordered
//!   translations first, then rotations;
//! - the cross product `cross(r, f)` of two vectors is the angular quantity (a scalar in 2D);
//! - a contact frame has `DIM` axes, the normal first (`n`, `t` in 2D).

use serde::{Deserialize, Serialize};

pub mod buffer;
pub mod rng;

pub use rng::SplitMix64;

/// Floating-point type of every physical quantity.
pub type Real = f64;
/// Number of space dimensions.
pub const DIM: usize = 2;
/// Number of rotational degrees of freedom of a rigid body (1 in 2D, 3 in 3D).
pub const ANGULAR_DIM: usize = 1;
/// Number of generalised velocity components of a rigid body.
pub const DOFS: usize = DIM + ANGULAR_DIM;
/// A spatial vector (position, velocity, force).
pub type Vector = nalgebra::Vector2<Real>;
/// An angular quantity (angle increment, angular velocity, torque): a scalar in 2D.
pub type AngVector = Real;
/// Generalised velocity or force of a rigid body: translations then rotations.
pub type Generalized = [Real; DOFS];

/// The angular part of `r x f` (2D: the scalar `r_x f_y - r_y f_x`).
#[inline(always)]
pub fn cross(r: &Vector, f: &Vector) -> AngVector {
    r.x * f.y - r.y * f.x
}

/// Linear velocity `w x r` of a point at offset `r` on a body spinning at `w`.
#[inline(always)]
pub fn spin_velocity(w: AngVector, r: &Vector) -> Vector {
    Vector::new(-w * r.y, w * r.x)
}

/// The tangent of a contact frame with normal `n` (2D: `n` rotated by +90 degrees).
#[inline(always)]
pub fn tangent(n: &Vector) -> Vector {
    Vector::new(-n.y, n.x)
}

/// Rotates `v` by `angle` radians.
#[inline(always)]
pub fn rotate(v: &Vector, angle: AngVector) -> Vector {
    let (s, c) = angle.sin_cos();
    Vector::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vector,
    /// Upper corner.
    pub max: Vector,
}

impl Aabb {
    /// The box `[c - h, c + h]`.
    pub fn from_center(c: Vector, half: Vector) -> Self {
        Aabb {
            min: c - half,
            max: c + half,
        }
    }
    /// Grows the box by `margin` on every side.
    pub fn loosened(&self, margin: Real) -> Self {
        let m = Vector::repeat(margin);
        Aabb {
            min: self.min - m,
            max: self.max + m,
        }
    }
    /// Whether two boxes overlap (touching counts).
    ///
    /// The comparisons are all evaluated, without short-circuits: one branch at the caller
    /// instead of up to `2 DIM` poorly predicted ones (the broad phase's pair loops).
    #[inline(always)]
    pub fn intersects(&self, other: &Aabb) -> bool {
        (0..DIM).fold(true, |hit, k| {
            hit & (self.min[k] <= other.max[k]) & (other.min[k] <= self.max[k])
        })
    }
    /// Largest edge length.
    pub fn max_extent(&self) -> Real {
        (self.max - self.min).max()
    }
    /// Union of two boxes.
    pub fn merged(&self, other: &Aabb) -> Self {
        Aabb {
            min: self.min.inf(&other.min),
            max: self.max.sup(&other.max),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cross_and_spin_are_consistent() {
        let r = Vector::new(0.3, -1.2);
        let n = Vector::new(0.6, 0.8);
        let w = 2.5;
        // (w x r) . n == w (r x n)
        assert!((spin_velocity(w, &r).dot(&n) - w * cross(&r, &n)).abs() < 1e-14);
        let t = tangent(&n);
        assert!(n.dot(&t).abs() < 1e-15 && (cross(&n, &t) - 1.0).abs() < 1e-15);
        let v = rotate(&n, std::f64::consts::FRAC_PI_2);
        assert!((v - t).norm() < 1e-15);
    }
}
