//! The 3D mapping: vectors of three components, angular quantities vectors, orientations unit
//! quaternions.

use crate::Real;

/// Number of space dimensions.
pub const DIM: usize = 3;
/// Number of rotational degrees of freedom of a rigid body (1 in 2D, 3 in 3D).
pub const ANGULAR_DIM: usize = 3;
/// Number of generalised velocity components of a rigid body.
pub const DOFS: usize = DIM + ANGULAR_DIM;
/// A spatial vector (position, velocity, force).
pub type Vector = nalgebra::Vector3<Real>;
/// An angular quantity (rotation vector, angular velocity, torque): a vector in 3D.
pub type AngVector = nalgebra::Vector3<Real>;
/// Generalised velocity or force of a rigid body: translations then rotations.
pub type Generalized = [Real; DOFS];
/// The orientation of a body: a unit quaternion.
pub type Rotation = nalgebra::UnitQuaternion<Real>;
/// A second-order tensor (inertia in the body's or the world's frame), kg m^2.
pub type AngMatrix = nalgebra::Matrix3<Real>;

/// `r x f`.
#[inline(always)]
pub fn cross(r: &Vector, f: &Vector) -> AngVector {
    r.cross(f)
}

/// Linear velocity `w x r` of a point at offset `r` on a body spinning at `w`.
#[inline(always)]
pub fn spin_velocity(w: AngVector, r: &Vector) -> Vector {
    w.cross(r)
}

/// The two tangents `(t1, t2)` completing the unit normal `n` to a right-handed orthonormal
/// contact frame `(n, t1, t2)` (`n x t1 = t2`), continuous except across `n_z = 0^-`.
///
/// The branch-free construction of T. Duff, J. Burgess, P. Christensen, C. Hery, A. Kensler,
/// M. Liani and R. Villemin, "Building an Orthonormal Basis, Revisited", J. Computer
/// Graphics Techniques 6(1), 2017 (J. R. Frisvad's 2012 basis with its singularity at
/// `n = -e_z` removed by the sign of `n_z`).
#[inline]
pub fn tangents(n: &Vector) -> [Vector; 2] {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t1 = Vector::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let t2 = Vector::new(b, sign + n.y * n.y * a, -n.y);
    [t1, t2]
}

/// Rotates `v` by `q`.
#[inline(always)]
pub fn rotate(v: &Vector, q: Rotation) -> Vector {
    q * v
}

/// The orientation after turning at the constant angular velocity `w` (world frame, rad/s)
/// for `h` seconds from `q`: `exp(h w) q` by the exact exponential map of the rotation vector
/// `h w`, renormalised so that round-off does not accumulate over many steps.
#[inline]
pub fn integrate_rotation(q: &Rotation, w: &AngVector, h: Real) -> Rotation {
    let turned = Rotation::from_scaled_axis(w * h) * q;
    Rotation::new_normalize(turned.into_inner())
}

/// The inverse inertia in the world frame, `R I^-1 R^T`, of a body with inverse inertia
/// `inv_body` in its own frame and orientation `q` (1/(kg m^2)).
#[inline]
pub fn world_inverse_inertia(q: &Rotation, inv_body: &AngMatrix) -> AngMatrix {
    let r = q.to_rotation_matrix();
    r.matrix() * inv_body * r.matrix().transpose()
}

/// Numbers that give an orientation in [`rotation_coords`]: a unit quaternion's.
pub const ROTATION_COORDS: usize = 4;

/// An orientation as numbers: the unit quaternion `[w, x, y, z]` (scalar first).
pub fn rotation_coords(q: &Rotation) -> [Real; ROTATION_COORDS] {
    [q.w, q.i, q.j, q.k]
}

/// An angular quantity's components `[x, y, z]`.
pub fn angular_coords(w: &AngVector) -> [Real; ANGULAR_DIM] {
    [w.x, w.y, w.z]
}

/// The angular quantity of the components [`angular_coords`] gives.
pub fn angular_from_coords(c: &[Real]) -> AngVector {
    AngVector::new(c[0], c[1], c[2])
}

/// The names of the axes (column names, messages).
pub const AXIS_NAMES: [&str; DIM] = ["x", "y", "z"];

/// A second-order tensor of the space (stress, fabric), `DIM x DIM`.
pub type Tensor = nalgebra::Matrix3<Real>;

/// Mean stress and deviator of a symmetric stress tensor from its principal values
/// (`s1 >= s2 >= s3`) in the convention of triaxial tests (e.g. E. Azema, F. Radjai,
/// "Stress-strain behavior and geometrical properties of packings of elongated particles",
/// Phys. Rev. E 81, 051304, 2010): `p = (s1 + s2 + s3) / 3`, `q = s1 - s3`.
pub fn stress_invariants(principal: [Real; DIM]) -> (Real, Real) {
    let [s1, s2, s3] = principal;
    ((s1 + s2 + s3) / 3.0, s1 - s3)
}

/// Anisotropy of a fabric tensor of unit trace from its principal values (`f1 >= f2 >= f3`):
/// `a = 5 (f1 - f3) / 2`, the `a` of an axisymmetric contact-orientation density
/// `E(n) = (1 + a (3 cos^2 theta - 1) / 2) / (4 pi)` (Azema and Radjai 2010, above).
pub fn fabric_anisotropy(principal: [Real; DIM]) -> Real {
    2.5 * (principal[0] - principal[2])
}

/// Principal values of a symmetric tensor, largest first.
pub fn principal_values(t: &Tensor) -> [Real; DIM] {
    let sym = (t + t.transpose()) / 2.0;
    let mut e: [Real; DIM] = sym.symmetric_eigenvalues().into();
    e.sort_by(|a, b| b.total_cmp(a));
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SplitMix64;

    fn random_unit(rng: &mut SplitMix64) -> Vector {
        loop {
            let v = Vector::new(
                2.0 * rng.next_f64() - 1.0,
                2.0 * rng.next_f64() - 1.0,
                2.0 * rng.next_f64() - 1.0,
            );
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }

    #[test]
    fn principal_values_and_invariants_of_a_rotated_tensor() {
        let q = Rotation::from_scaled_axis(Vector::new(0.3, -0.7, 0.2));
        let r = q.to_rotation_matrix();
        let t = r * Tensor::from_diagonal(&Vector::new(1.0, 3.0, 2.0)) * r.transpose();
        let [s1, s2, s3] = principal_values(&t);
        assert!((s1 - 3.0).abs() < 1e-12 && (s2 - 2.0).abs() < 1e-12 && (s3 - 1.0).abs() < 1e-12);
        assert_eq!(stress_invariants([3.0, 2.0, 1.0]), (2.0, 2.0));
        assert!((fabric_anisotropy([0.5, 0.3, 0.2]) - 0.75).abs() < 1e-15);
    }

    #[test]
    fn cross_and_spin_are_consistent() {
        let (r, n, w) = (
            Vector::new(0.3, -1.2, 0.7),
            Vector::new(0.6, 0.0, 0.8),
            Vector::new(2.5, -1.0, 0.4),
        );
        // (w x r) . n == w . (r x n)
        assert!((spin_velocity(w, &r).dot(&n) - w.dot(&cross(&r, &n))).abs() < 1e-14);
    }

    /// Orthonormal and right-handed for random normals and for the axes of both signs, the
    /// original construction's singular `-e_z` included.
    #[test]
    fn tangents_complete_a_right_handed_orthonormal_frame() {
        let mut rng = SplitMix64::new(3);
        let axes = [
            Vector::x(),
            Vector::y(),
            Vector::z(),
            -Vector::x(),
            -Vector::y(),
            -Vector::z(),
        ];
        let normals = axes
            .into_iter()
            .chain((0..10_000).map(|_| random_unit(&mut rng)));
        for n in normals {
            let [t1, t2] = tangents(&n);
            for (a, b, expected) in [
                (t1, t1, 1.0),
                (t2, t2, 1.0),
                (n, t1, 0.0),
                (n, t2, 0.0),
                (t1, t2, 0.0),
            ] {
                assert!((a.dot(&b) - expected).abs() < 1e-14, "{n:?}: {t1:?} {t2:?}");
            }
            assert!((n.cross(&t1) - t2).norm() < 1e-14, "{n:?}: left-handed");
        }
    }

    /// About a fixed axis the exponential map composes exactly: a million small steps land on
    /// the rotation by the total angle, and the quaternion stays a unit one.
    #[test]
    fn rotation_update_is_exact_about_a_fixed_axis_and_stays_unit() {
        let axis = Vector::new(1.0, 2.0, -2.0) / 3.0;
        let (w, h, steps) = (axis * 7.0, 1e-6, 1_000_000);
        let mut q = Rotation::identity();
        for _ in 0..steps {
            q = integrate_rotation(&q, &w, h);
        }
        let exact = Rotation::from_scaled_axis(w * (h * steps as f64));
        assert!(q.angle_to(&exact) < 1e-9, "{}", q.angle_to(&exact));
        assert!((q.into_inner().norm() - 1.0).abs() < 1e-15);
    }

    /// `R I^-1 R^T` is symmetric and inverts `R I R^T`.
    #[test]
    fn world_inverse_inertia_inverts_the_world_inertia() {
        let mut rng = SplitMix64::new(9);
        let body = AngMatrix::from_diagonal(&Vector::new(0.2, 0.5, 1.3));
        let inv = body.try_inverse().expect("positive diagonal");
        for _ in 0..100 {
            let q = Rotation::from_scaled_axis(random_unit(&mut rng) * 3.0 * rng.next_f64());
            let w_inv = world_inverse_inertia(&q, &inv);
            let r = q.to_rotation_matrix();
            let world = r.matrix() * body * r.matrix().transpose();
            assert!((w_inv * world - AngMatrix::identity()).norm() < 1e-13);
            assert!((w_inv - w_inv.transpose()).norm() < 1e-15);
        }
    }
}
