//! The dimension abstraction of xper.
//!
//! Every crate names spatial quantities through the aliases of this module and never through
//! a concrete `Vector2` or a literal `2`, in the manner of rapier's `math` module. One source
//! is built twice: the package `xper-math` (feature `dim2`) maps the names to 2D types, the
//! package `xper-math3d` (feature `dim3`, the same `src/`) to 3D types; a crate built for 3D
//! renames `xper-math3d` to `xper_math` in its manifest, so its source is the same too.
//!
//! Conventions (SI units throughout):
//! - a rigid body has `DOFS = DIM + ANGULAR_DIM` generalised velocity components, ordered
//!   translations first, then rotations;
//! - the cross product `cross(r, f)` of two vectors is the angular quantity (a scalar in 2D,
//!   a vector in 3D);
//! - a contact frame has `DIM` axes, the normal first (`n`, `t` in 2D; `n`, `t1`, `t2` in 3D,
//!   from `tangents` in 3D).

use serde::{Deserialize, Serialize};

pub mod buffer;
#[cfg(feature = "dim2")]
mod dim2;
#[cfg(feature = "dim3")]
mod dim3;
pub mod rng;

#[cfg(feature = "dim2")]
pub use dim2::*;
#[cfg(feature = "dim3")]
pub use dim3::*;
pub use rng::SplitMix64;

#[cfg(not(any(feature = "dim2", feature = "dim3")))]
compile_error!(
    "xper-math is built with feature `dim2` (package xper-math) or `dim3` (xper-math3d)"
);

/// Floating-point type of every physical quantity.
pub type Real = f64;
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
