//! The 2D mapping: vectors of two components, angular quantities scalars.

use crate::Real;

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
/// The orientation of a body: its angle (rad).
pub type Rotation = Real;
/// A second-order tensor of angular quantities (inertia, kg m^2): a scalar in 2D.
pub type AngMatrix = Real;

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

/// The orientation after turning at the angular velocity `w` (rad/s) for `h` seconds from
/// `angle`: `angle + h w`, exact in 2D.
#[inline(always)]
pub fn integrate_rotation(angle: &Rotation, w: &AngVector, h: Real) -> Rotation {
    angle + h * w
}

/// The inverse inertia in the world frame: in 2D the body's own, whatever its angle.
#[inline(always)]
pub fn world_inverse_inertia(_angle: &Rotation, inv_body: &AngMatrix) -> AngMatrix {
    *inv_body
}

/// Numbers that give an orientation in [`rotation_coords`]: the angle.
pub const ROTATION_COORDS: usize = 1;

/// An orientation as numbers: `[angle]` (rad, counter-clockwise).
pub fn rotation_coords(angle: &Rotation) -> [Real; ROTATION_COORDS] {
    [*angle]
}

/// An angular quantity's components: `[w]`, about the axis out of the plane.
pub fn angular_coords(w: &AngVector) -> [Real; ANGULAR_DIM] {
    [*w]
}

/// The angular quantity of the components [`angular_coords`] gives.
pub fn angular_from_coords(c: &[Real]) -> AngVector {
    c[0]
}

/// The names of the axes (column names, messages).
pub const AXIS_NAMES: [&str; DIM] = ["x", "y"];

/// A second-order tensor of the space (stress, fabric), `DIM x DIM`.
pub type Tensor = nalgebra::Matrix2<Real>;

/// Mean stress and deviator of a symmetric stress tensor from its principal values
/// (`s1 >= s2`) in the 2D convention of granular mechanics (e.g. F. Radjai, F. Dubois,
/// "Discrete-element modeling of granular materials", Wiley 2011, ch. 8): `p = (s1 + s2) / 2`,
/// `q = (s1 - s2) / 2`, so that `q / p = sin(phi)` with `phi` the mobilised friction angle.
pub fn stress_invariants(principal: [Real; DIM]) -> (Real, Real) {
    let [s1, s2] = principal;
    ((s1 + s2) / 2.0, (s1 - s2) / 2.0)
}

/// Anisotropy of a fabric tensor of unit trace from its principal values (`f1 >= f2`):
/// `a = 2 (f1 - f2)`, the `a` of the contact-orientation density
/// `E(theta) = (1 + a cos 2(theta - theta_a)) / (2 pi)` (L. Rothenburg, R.J. Bathurst,
/// "Analytical study of induced anisotropy in idealized granular materials", Geotechnique 39,
/// 1989).
pub fn fabric_anisotropy(principal: [Real; DIM]) -> Real {
    2.0 * (principal[0] - principal[1])
}

/// Principal values of a symmetric tensor, largest first (closed form).
pub fn principal_values(t: &Tensor) -> [Real; DIM] {
    let mean = (t[(0, 0)] + t[(1, 1)]) / 2.0;
    let half_diff = (t[(0, 0)] - t[(1, 1)]) / 2.0;
    let radius = half_diff.hypot((t[(0, 1)] + t[(1, 0)]) / 2.0);
    [mean + radius, mean - radius]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn principal_values_and_invariants_of_a_rotated_tensor() {
        let (c, s) = (0.3f64.cos(), 0.3f64.sin());
        let r = Tensor::new(c, -s, s, c);
        let t = r * Tensor::new(3.0, 0.0, 0.0, 1.0) * r.transpose();
        let [s1, s2] = principal_values(&t);
        assert!((s1 - 3.0).abs() < 1e-14 && (s2 - 1.0).abs() < 1e-14);
        // q / p = sin(phi): 1 / 2 at 30 degrees.
        assert_eq!(stress_invariants([3.0, 1.0]), (2.0, 1.0));
        assert!((fabric_anisotropy([0.6, 0.4]) - 0.4).abs() < 1e-15);
    }

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
