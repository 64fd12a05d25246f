//! The 2D parts of the body set: inverse masses, generalised velocities, kinetic energy and
//! the bodies of 2D scenes (disks, polygons, wall segments).

use super::{Body, BodySet};
use crate::{Drive, Shape};
use xper_math::{Real, Vector, DOFS};

/// Inverse mass per degree of freedom (x, y, rotation).
pub type InverseMass = [Real; DOFS];

impl BodySet {
    /// Inverse mass per degree of freedom (x, y, rotation) of body `b`: `1 / m`, `1 / m`,
    /// `1 / I`, with 0 where the velocity is imposed or the mass infinite, so contact impulses
    /// cannot change it. Computed, not stored (24 bytes per body less; the solver keeps its
    /// own copy during a step).
    #[inline]
    pub fn inv_mass(&self, b: usize) -> InverseMass {
        let inv = |m: Real, k: usize| {
            if self.imposed[b] & 1 << k == 0 && m.is_finite() && m > 0.0 {
                1.0 / m
            } else {
                0.0
            }
        };
        [
            inv(self.mass[b], 0),
            inv(self.mass[b], 1),
            inv(self.inertia[b], 2),
        ]
    }

    /// Whether contacts can move body `b`: some degree of freedom is free and of finite,
    /// positive mass (some [`BodySet::inv_mass`] is not 0), without a division.
    #[inline]
    pub fn is_movable(&self, b: usize) -> bool {
        let finite = |m: Real| m.is_finite() && m > 0.0;
        let free = |k: usize| self.imposed[b] & 1 << k == 0;
        (free(0) || free(1)) && finite(self.mass[b]) || free(2) && finite(self.inertia[b])
    }

    /// Generalised velocity (vx, vy, w) of a body.
    #[inline(always)]
    pub fn generalized_velocity(&self, b: usize) -> [Real; DOFS] {
        [
            self.velocity[b].x,
            self.velocity[b].y,
            self.angular_velocity[b],
        ]
    }

    /// Sets the generalised velocity of a body.
    #[inline(always)]
    pub fn set_generalized_velocity(&mut self, b: usize, v: [Real; DOFS]) {
        self.velocity[b] = Vector::new(v[0], v[1]);
        self.angular_velocity[b] = v[2];
    }

    /// `I w^2 / 2` of body `b` (J per m).
    #[inline(always)]
    pub(super) fn rotational_energy(&self, b: usize) -> Real {
        0.5 * self.inertia[b] * self.angular_velocity[b].powi(2)
    }
}

impl Body {
    /// A free disk of `radius` (m) and `density` (kg/m^3) centred at `position`, at rest.
    pub fn disk(radius: Real, density: Real, position: Vector) -> Self {
        let shape = Shape::Disk { radius };
        let (mass, inertia) = shape.mass_properties(density);
        Self::free(shape, mass, inertia, position)
    }

    /// A free convex polygon with body-frame `vertices` (counter-clockwise, centred on their
    /// centroid) of `density` (kg/m^3), centroid at `position`.
    pub fn polygon(vertices: Vec<Vector>, density: Real, position: Vector) -> Self {
        let shape = Shape::Polygon(Box::new(crate::ConvexPolygon::new(vertices)));
        let (mass, inertia) = shape.mass_properties(density);
        Self::free(shape, mass, inertia, position)
    }

    /// A fixed wall segment from `a` to `b`.
    pub fn wall(a: Vector, b: Vector) -> Self {
        let d = b - a;
        let shape = Shape::Segment {
            half_length: d.norm() / 2.0,
        };
        let zero = || Drive::Velocity(crate::TimeFunction::Constant(0.0));
        Body {
            rotation: d.y.atan2(d.x),
            drives: [zero(), zero(), zero()],
            ..Self::free(shape, Real::INFINITY, Real::INFINITY, (a + b) / 2.0)
        }
    }

    fn free(shape: Shape, mass: Real, inertia: Real, position: Vector) -> Self {
        Body {
            shape,
            position,
            rotation: 0.0,
            velocity: Vector::zeros(),
            angular_velocity: 0.0,
            mass,
            inertia,
            group: 0,
            drives: [Drive::Free, Drive::Free, Drive::Free],
        }
    }
}
