//! The 3D parts of the body set: inverse masses (with the world inverse inertia tensor),
//! generalised velocities, kinetic energy and the bodies of 3D scenes (spheres, polyhedra,
//! planar walls).

use super::{Body, BodySet};
use crate::{ConvexPolyhedron, Drive, Shape};
use xper_math::{AngMatrix, AngVector, Real, Rotation, Vector, DOFS};

/// Inverse mass of a body: per translational degree of freedom (x, y, z; 1/kg) and the
/// inverse inertia tensor in the world frame (1/(kg m^2)), zero on imposed components.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InverseMass {
    /// `1 / m` per axis, 0 where the velocity is imposed or the mass infinite.
    pub linear: [Real; 3],
    /// The inverse of the world inertia restricted to the free rotation axes (zero rows and
    /// columns on the imposed ones).
    pub angular: AngMatrix,
}

/// The scalar `i` of an inertia tensor equal to `i Id` to round-off (`max|I - I_00 Id| <=
/// 1e-12 I_00`: a cube's or a regular solid's tensor from the face integrals differs from a
/// multiple of the identity by a few ulps), `None` for an anisotropic, infinite or zero one.
/// Such a tensor is the same in every frame, so `R I R^T = I` needs no rotation.
#[inline]
pub fn isotropic_inertia(i: &AngMatrix) -> Option<Real> {
    let d = i[(0, 0)];
    if !(d.is_finite() && d > 0.0) {
        return None;
    }
    let tolerance = 1e-12 * d;
    let mut off = 0.0f64;
    for k in 0..3 {
        for l in 0..3 {
            let x = if k == l { i[(k, l)] - d } else { i[(k, l)] };
            off = off.max(x.abs());
        }
    }
    (off <= tolerance).then_some(d)
}

impl BodySet {
    /// Inverse mass of body `b` (see [`InverseMass`]): with the rotations about the world
    /// axes in `F` free and the others imposed, the angular part is `(I_FF)^-1` on `F` (the
    /// inverse of the free block of the world inertia `R I R^T`) and zero elsewhere, so that
    /// contact impulses cannot change an imposed component.
    pub fn inv_mass(&self, b: usize) -> InverseMass {
        let free = |k: usize| self.imposed[b] & 1 << k == 0;
        let m = self.mass[b];
        let inv_m = if m.is_finite() && m > 0.0 {
            1.0 / m
        } else {
            0.0
        };
        let linear = [0, 1, 2].map(|k| if free(k) { inv_m } else { 0.0 });
        let body = self.inertia[b];
        if self.imposed[b] >> 3 == 0 {
            if let Some(i) = isotropic_inertia(&body) {
                let angular = AngMatrix::from_diagonal_element(1.0 / i);
                return InverseMass { linear, angular };
            }
        }
        let finite = body.iter().all(|x| x.is_finite()) && body.trace() > 0.0;
        let mut angular = AngMatrix::zeros();
        if finite {
            let r = self.rotation[b].to_rotation_matrix();
            let world = r.matrix() * body * r.matrix().transpose();
            // The free block, with the identity on the imposed axes, inverted: block diagonal,
            // so its free block is (I_FF)^-1; the imposed block is then zeroed.
            let mut m = world;
            for k in 0..3 {
                if !free(3 + k) {
                    for l in 0..3 {
                        m[(k, l)] = 0.0;
                        m[(l, k)] = 0.0;
                    }
                    m[(k, k)] = 1.0;
                }
            }
            if let Some(inv) = m.try_inverse() {
                angular = inv;
                for k in (0..3).filter(|&k| !free(3 + k)) {
                    for l in 0..3 {
                        angular[(k, l)] = 0.0;
                        angular[(l, k)] = 0.0;
                    }
                }
            }
        }
        InverseMass { linear, angular }
    }

    /// Whether contacts can move body `b`: some degree of freedom is free and of finite,
    /// positive mass (some [`BodySet::inv_mass`] is not 0), without computing the inverse.
    #[inline]
    pub fn is_movable(&self, b: usize) -> bool {
        let free = |k: usize| self.imposed[b] & 1 << k == 0;
        let (m, inertia) = (self.mass[b], &self.inertia[b]);
        let finite = m.is_finite() && m > 0.0;
        let turns = inertia.iter().all(|x| x.is_finite()) && inertia.trace() > 0.0;
        (free(0) || free(1) || free(2)) && finite || (free(3) || free(4) || free(5)) && turns
    }

    /// Generalised velocity `(vx, vy, vz, wx, wy, wz)` of a body.
    #[inline(always)]
    pub fn generalized_velocity(&self, b: usize) -> [Real; DOFS] {
        let (v, w) = (self.velocity[b], self.angular_velocity[b]);
        [v.x, v.y, v.z, w.x, w.y, w.z]
    }

    /// Sets the generalised velocity of a body.
    #[inline(always)]
    pub fn set_generalized_velocity(&mut self, b: usize, v: [Real; DOFS]) {
        self.velocity[b] = Vector::new(v[0], v[1], v[2]);
        self.angular_velocity[b] = AngVector::new(v[3], v[4], v[5]);
    }

    /// `w . (R I R^T w) / 2` of body `b` (J), with `I` its inertia in its own frame.
    #[inline]
    pub(super) fn rotational_energy(&self, b: usize) -> Real {
        // A body of finite mass may have an infinite inertia (a half-space wall with a mass,
        // its rotations imposed): its rotation is not counted, as the motion of a wall of
        // infinite mass is not.
        if !self.inertia[b].iter().all(|x| x.is_finite()) {
            return 0.0;
        }
        let body_w = self.rotation[b].inverse() * self.angular_velocity[b];
        0.5 * body_w.dot(&(self.inertia[b] * body_w))
    }
}

impl Body {
    /// A free sphere of `radius` (m) and `density` (kg/m^3) centred at `position`, at rest.
    pub fn sphere(radius: Real, density: Real, position: Vector) -> Self {
        let shape = Shape::Sphere { radius };
        let (mass, inertia) = shape.mass_properties(density);
        Self::free(shape, mass, inertia, position)
    }

    /// A free convex polyhedron, the hull of `points` (m, scene frame) of `density` (kg/m^3),
    /// placed with its centroid where the points put it; an error for points that do not
    /// span a volume.
    pub fn polyhedron(points: &[Vector], density: Real) -> Result<Self, String> {
        let (hull, centroid) = ConvexPolyhedron::hull(points)?;
        let shape = Shape::Polyhedron(Box::new(hull));
        let (mass, inertia) = shape.mass_properties(density);
        Ok(Self::free(shape, mass, inertia, centroid))
    }

    /// A fixed rectangular wall centred at `centre` with outward unit normal `normal` and
    /// half-extents `half_extents` (m) along two axes of its plane (`INFINITY` for a
    /// half-space's boundary).
    pub fn plane(centre: Vector, normal: Vector, half_extents: [Real; 2]) -> Self {
        let shape = Shape::Plane { half_extents };
        let rotation = Rotation::rotation_between(&Vector::z(), &normal).unwrap_or_else(|| {
            // normal = -z: a half turn about x.
            Rotation::from_scaled_axis(Vector::x() * std::f64::consts::PI)
        });
        let zero = || Drive::Velocity(crate::TimeFunction::Constant(0.0));
        let infinite = AngMatrix::from_diagonal_element(Real::INFINITY);
        Body {
            rotation,
            drives: std::array::from_fn(|_| zero()),
            ..Self::free(shape, Real::INFINITY, infinite, centre)
        }
    }

    fn free(shape: Shape, mass: Real, inertia: AngMatrix, position: Vector) -> Self {
        Body {
            shape,
            position,
            rotation: Rotation::identity(),
            velocity: Vector::zeros(),
            angular_velocity: AngVector::zeros(),
            mass,
            inertia,
            group: 0,
            drives: std::array::from_fn(|_| Drive::Free),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A free body's angular inverse mass inverts its world inertia; imposing the rotation
    /// about z leaves the inverse of the x-y block (checked against the 2x2 inverse), zero on z.
    #[test]
    fn inverse_inertia_in_the_world_frame() {
        let mut set = BodySet::new();
        let half = Vector::new(0.3, 0.2, 0.1);
        let shape = Shape::Polyhedron(Box::new(ConvexPolyhedron::cuboid(half)));
        let (mass, inertia) = shape.mass_properties(1000.0);
        let q = Rotation::from_scaled_axis(Vector::new(0.4, -0.2, 0.9));
        let body = Body::free(shape, mass, inertia, Vector::zeros()).with_rotation(q);
        let free = set.insert(body.clone());
        let mut held = body;
        held.drives[5] = Drive::Velocity(crate::TimeFunction::Constant(0.0));
        let held = set.insert(held);
        let r = q.to_rotation_matrix();
        let world = r.matrix() * inertia * r.matrix().transpose();
        let inv = set.inv_mass(free.index());
        assert!((inv.angular * world - AngMatrix::identity()).norm() < 1e-12);
        assert_eq!(inv.linear, [1.0 / mass; 3]);
        let inv = set.inv_mass(held.index());
        let block = world.fixed_view::<2, 2>(0, 0).into_owned();
        let expected = block.try_inverse().unwrap();
        assert!((inv.angular.fixed_view::<2, 2>(0, 0) - expected).norm() < 1e-10 * expected.norm());
        assert!(inv
            .angular
            .row(2)
            .iter()
            .chain(inv.angular.column(2).iter())
            .all(|&x| x == 0.0));
    }

    /// Walls and planes do not move; a sphere's kinetic energy is `m v^2 / 2 + I w^2 / 2`
    /// whatever its orientation.
    #[test]
    fn planes_are_fixed_and_energy_is_frame_independent() {
        let mut set = BodySet::new();
        let wall = set.insert(Body::plane(Vector::zeros(), -Vector::z(), [1.0, 1.0]));
        assert!(!set.is_movable(wall.index()));
        assert!((set.rotation[0] * Vector::z() + Vector::z()).norm() < 1e-15);
        let ball = Body::sphere(0.1, 1000.0, Vector::new(0.0, 0.0, 1.0))
            .with_rotation(Rotation::from_scaled_axis(Vector::new(1.0, 2.0, 3.0)))
            .with_velocity(Vector::new(1.0, 0.0, -2.0));
        let (m, i) = (ball.mass, ball.inertia[(0, 0)]);
        let b = set.insert(ball);
        set.angular_velocity[b.index()] = AngVector::new(0.0, 3.0, 4.0);
        let expected = 0.5 * m * 5.0 + 0.5 * i * 25.0;
        assert!((set.kinetic_energy() - expected).abs() < 1e-12 * expected);
    }
}
