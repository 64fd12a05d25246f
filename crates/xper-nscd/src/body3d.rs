//! The 3D parts of the rigid-body operator: a body's working state (velocity
//! `(v, w)` in the world frame, inverse mass with the world inverse inertia), the local
//! velocity of a contact row, the impulses it exerts, and the update of a body's
//! configuration with its gyroscopic term.
//!
//! # The rotation update
//!
//! The contact problem of a step is posed on the angular velocity `w` (world frame) with the
//! world inverse inertia at the beginning of the step, `I_w(q_i)^-1 = R_i I^-1 R_i^T`, so the
//! step gives the angular momentum `L_i+1 = I_w(q_i) w_i+1` (torques and contact impulses
//! included). The orientation then follows the free rotor `dq/dt = w(q) q` with the world
//! angular momentum `L_theta = I_w(q_i) ((1 - theta) w_i + theta w_i+1)` held constant, by the
//! symmetric splitting of T. Dullweber, B. Leimkuhler and R. McLachlan, "Symplectic splitting
//! methods for rigid body molecular dynamics", J. Chem. Phys. 107, 5840 (1997): the exact
//! flows of `L_k^2 / (2 I_k)` about the principal axes in the order 1, 2, 3, 2, 1 for
//! `h/2, h/2, h, h/2, h/2`. Finally `w_i+1 = I_w(q_i+1)^-1 L_i+1`: angular momentum is what a
//! step carries over, so a torque-free body keeps `L` to round-off, and the splitting, being
//! symplectic, symmetric and of order 2, keeps its energy within `O(h^2)` with no drift
//! (backward error analysis: E. Hairer, C. Lubich, G. Wanner, "Geometric Numerical
//! Integration", 2nd ed., Springer 2006, sections VII.5 and IX.8).
//!
//! Bodies whose inertia is isotropic (spheres, cubes, regular solids) or which have an imposed
//! rotation have no gyroscopic term to integrate (or none the drive leaves free): their
//! orientation turns by the exact exponential `q_i+1 = exp(h w_theta) q_i`,
//! `w_theta = (1 - theta) w_i + theta w_i+1`, and `w_i+1` is the solver's. A limitation: with
//! some rotations imposed and others free, the free ones get `(I_FF)^-1` of their torques and
//! miss the coupling `-(I_FF)^-1 I_Fk dw_k` when an imposed rate `w_k` changes in time and the
//! world inertia couples the axes.

use xper_bodies::{isotropic_inertia, BodySet, InverseMass};
use xper_geometry::ContactRow;
use xper_math::{integrate_rotation, AngMatrix, AngVector, Real, Rotation, Vector, DIM, DOFS};

/// A local impulse or velocity `(normal, tangent 1, tangent 2)`.
pub type Local = [Real; DIM];

/// Working state of one body: generalised velocity and inverse mass.
#[derive(Clone, Copy, Debug, Default)]
pub struct SolverBody {
    /// Generalised velocity (vx, vy, vz, wx, wy, wz), world frame.
    pub velocity: [Real; DOFS],
    /// Inverse mass (0 where imposed or infinite) and world inverse inertia.
    pub inv_mass: InverseMass,
}

fn split(v: &[Real; DOFS]) -> (Vector, AngVector) {
    (
        Vector::new(v[0], v[1], v[2]),
        AngVector::new(v[3], v[4], v[5]),
    )
}

impl SolverBody {
    /// Whether impulses move degree of freedom `d` (its row of the inverse mass is not 0).
    #[inline(always)]
    pub fn is_free(&self, d: usize) -> bool {
        if d < DIM {
            self.inv_mass.linear[d] != 0.0
        } else {
            self.inv_mass.angular.row(d - DIM).iter().any(|&w| w != 0.0)
        }
    }

    /// Whether impulses move the body at all.
    #[inline]
    pub fn is_movable(&self) -> bool {
        self.inv_mass.linear.iter().any(|&w| w != 0.0)
            || self.inv_mass.angular.iter().any(|&w| w != 0.0)
    }

    /// `v += h g` on the free translations.
    #[inline(always)]
    pub fn add_gravity(&mut self, h: Real, g: &Vector) {
        for k in 0..DIM {
            self.velocity[k] += h * g[k] * (self.inv_mass.linear[k] > 0.0) as u8 as Real;
        }
    }

    /// `v += h M^-1 f` for a generalised force `f` (force, then torque).
    #[inline]
    pub fn add_force(&mut self, h: Real, f: &[Real; DOFS]) {
        for ((v, m), f) in self.velocity.iter_mut().zip(self.inv_mass.linear).zip(f) {
            *v += h * m * f;
        }
        let dw = self.inv_mass.angular * AngVector::new(f[3], f[4], f[5]) * h;
        for k in 0..DIM {
            self.velocity[DIM + k] += dw[k];
        }
    }

    /// `v += h M^-1 f e_d` for a force (or a torque about a world axis) `f` on degree of
    /// freedom `d` alone.
    #[inline]
    pub fn add_dof_force(&mut self, d: usize, h: Real, f: Real) {
        if d < DIM {
            self.velocity[d] += h * self.inv_mass.linear[d] * f;
        } else {
            let dw = self.inv_mass.angular.column(d - DIM) * (h * f);
            for k in 0..DIM {
                self.velocity[DIM + k] += dw[k];
            }
        }
    }

    /// Multiplies the inverse mass by `factor`.
    #[inline]
    pub fn scale_inverse_mass(&mut self, factor: Real) {
        for w in &mut self.inv_mass.linear {
            *w *= factor;
        }
        self.inv_mass.angular *= factor;
    }

    #[inline(always)]
    fn push(&mut self, arm: &Vector, p: &Vector, sign: Real) {
        let dw = self.inv_mass.angular * arm.cross(p);
        for k in 0..DIM {
            self.velocity[k] += sign * self.inv_mass.linear[k] * p[k];
            self.velocity[DIM + k] += sign * dw[k];
        }
    }
}

/// `x^T M^-1 y`, the same bits for `(x, y)` and `(y, x)` (the angular part from the upper
/// triangle of the inverse inertia, each pair of terms summed symmetrically).
#[inline]
pub fn inverse_mass_product(m: &InverseMass, x: &[Real; DOFS], y: &[Real; DOFS]) -> Real {
    let a = &m.angular;
    let mut sum: Real = (0..DIM).map(|d| m.linear[d] * (x[d] * y[d])).sum();
    for k in 0..DIM {
        sum += a[(k, k)] * (x[DIM + k] * y[DIM + k]);
        for l in k + 1..DIM {
            sum += a[(k, l)] * (x[DIM + k] * y[DIM + l] + x[DIM + l] * y[DIM + k]);
        }
    }
    sum
}

/// The local velocity `F^T (v_j + w_j x r_j - v_i - w_i x r_i)` of `row`.
#[inline(always)]
pub fn relative_velocity(row: &ContactRow, vi: &[Real; DOFS], vj: &[Real; DOFS]) -> Local {
    let ((li, wi), (lj, wj)) = (split(vi), split(vj));
    let [ri, rj] = row.arms.map(Vector::from);
    let dv = lj + wj.cross(&rj) - li - wi.cross(&ri);
    row.frame().map(|a| a.dot(&dv))
}

/// A world vector `v` in the frame of `row`: its components on `(n, t1, t2)`.
#[inline(always)]
pub fn local_of(row: &ContactRow, v: &Vector) -> Local {
    row.frame().map(|a| a.dot(v))
}

/// Adds the local impulse `d` of `row` to the velocities of its two bodies (`-d` on the first).
#[inline(always)]
pub fn push_bodies(bodies: &mut [SolverBody], row: &ContactRow, d: Local) {
    let [n, t1, t2] = row.frame();
    let p = n * d[0] + t1 * d[1] + t2 * d[2];
    let [ri, rj] = row.arms.map(Vector::from);
    bodies[row.bodies[0] as usize].push(&ri, &p, -1.0);
    bodies[row.bodies[1] as usize].push(&rj, &p, 1.0);
}

/// Generalised impulses `(on body i, on body j)` (force, then torque about the body's
/// position) of a local impulse `r` at a row.
#[inline(always)]
pub fn generalized_impulses(row: &ContactRow, r: Local) -> ([Real; DOFS], [Real; DOFS]) {
    let [n, t1, t2] = row.frame();
    let p = n * r[0] + t1 * r[1] + t2 * r[2];
    let [ri, rj] = row.arms.map(Vector::from);
    let (ti, tj) = (ri.cross(&p), rj.cross(&p));
    (
        [-p.x, -p.y, -p.z, -ti.x, -ti.y, -ti.z],
        [p.x, p.y, p.z, tj.x, tj.y, tj.z],
    )
}

/// `g . v` over the translations of a generalised velocity (W/kg).
#[inline(always)]
pub fn gravity_power(g: &Vector, v: &[Real; DOFS]) -> Real {
    g.x * v[0] + g.y * v[1] + g.z * v[2]
}

/// The world inertia `R I R^T` of body `b`.
fn world_inertia(bodies: &BodySet, b: usize) -> AngMatrix {
    let r = bodies.rotation[b].to_rotation_matrix();
    r.matrix() * bodies.inertia[b] * r.matrix().transpose()
}

/// Work over a step of `h` of the reaction that holds degree of freedom `d` of body `b` at
/// its imposed velocity, from `v0` to `v1` (besides contacts): for a translation the change
/// of its kinetic energy less gravity's work, for a rotation about a world axis `k` the
/// reaction's angular impulse `(I_w (w_1 - w_0))_k` times the mean rate; 0 for an infinite
/// mass.
#[inline]
pub fn imposed_velocity_work(
    bodies: &BodySet,
    b: usize,
    d: usize,
    [v0, v1]: [&[Real; DOFS]; 2],
    h: Real,
    g: &Vector,
) -> Real {
    let mean = (v0[d] + v1[d]) / 2.0;
    if d < DIM {
        let m = bodies.mass[b];
        if !m.is_finite() {
            return 0.0;
        }
        return m * (v1[d] * v1[d] - v0[d] * v0[d]) / 2.0 - h * m * g[d] * mean;
    }
    if !bodies.inertia[b].iter().all(|x| x.is_finite()) {
        return 0.0;
    }
    let (w0, w1) = (split(v0).1, split(v1).1);
    (world_inertia(bodies, b) * (w1 - w0))[d - DIM] * mean
}

/// Moves body `b` by the generalised displacement `dq` (translation, then rotation vector).
#[inline(always)]
pub fn displace(bodies: &mut BodySet, b: usize, dq: &[Real; DOFS]) {
    let (dx, turn) = split(dq);
    bodies.position[b] += dx;
    bodies.rotation[b] = integrate_rotation(&bodies.rotation[b], &turn, 1.0);
}

/// Principal moments and axes of a body-frame inertia: `I = P diag(moments) P^T`, `P` a
/// rotation (the identity for a diagonal `I`).
fn principal(inertia: &AngMatrix) -> (Vector, Rotation) {
    let off = [inertia[(0, 1)], inertia[(0, 2)], inertia[(1, 2)]];
    if off.iter().all(|&x| x == 0.0) {
        return (inertia.diagonal(), Rotation::identity());
    }
    let eigen = nalgebra::SymmetricEigen::new(*inertia);
    let mut axes = eigen.eigenvectors;
    if axes.determinant() < 0.0 {
        axes.column_mut(2).neg_mut();
    }
    let rotation = nalgebra::Rotation3::from_matrix_unchecked(axes);
    (eigen.eigenvalues, Rotation::from_rotation_matrix(&rotation))
}

/// The free rotor's orientation after `h` from `q` with world angular momentum `l`, by the
/// splitting of the module documentation; `inertia` in the body frame.
fn free_rotor(q: &Rotation, inertia: &AngMatrix, l: &AngVector, h: Real) -> Rotation {
    let (moments, axes) = principal(inertia);
    let mut p = q * axes;
    for (k, tau) in [
        (0, h / 2.0),
        (1, h / 2.0),
        (2, h),
        (1, h / 2.0),
        (0, h / 2.0),
    ] {
        let body_l = p.inverse_transform_vector(l);
        let mut turn = AngVector::zeros();
        turn[k] = tau * body_l[k] / moments[k];
        p *= Rotation::from_scaled_axis(turn);
    }
    Rotation::new_normalize((p * axes.inverse()).into_inner())
}

/// Whether body `b` has a gyroscopic term to integrate: a finite, anisotropic inertia and no
/// imposed rotation.
fn has_gyroscopic_term(bodies: &BodySet, b: usize) -> bool {
    let i = &bodies.inertia[b];
    let rotation_imposed = bodies.imposed[b] >> DIM != 0;
    if rotation_imposed || !i.iter().all(|x| x.is_finite()) || i.trace() <= 0.0 {
        return false;
    }
    isotropic_inertia(i).is_none()
}

/// The end of a step for body `b` from the velocities `v0` (in the body set) and `v1` (the
/// solver's): positions by the theta-method, the orientation and the angular velocity as the
/// module documentation says.
#[inline]
pub fn advance(bodies: &mut BodySet, b: usize, v1: [Real; DOFS], h: Real, theta: Real) {
    let v0 = bodies.generalized_velocity(b);
    let ((l0, w0), (l1, w1)) = (split(&v0), split(&v1));
    bodies.position[b] += (l0 * (1.0 - theta) + l1 * theta) * h;
    let w_theta = w0 * (1.0 - theta) + w1 * theta;
    if !has_gyroscopic_term(bodies, b) {
        bodies.rotation[b] = integrate_rotation(&bodies.rotation[b], &w_theta, h);
        bodies.set_generalized_velocity(b, v1);
        return;
    }
    let inertia_begin = world_inertia(bodies, b);
    let momentum = inertia_begin * w1;
    let q = free_rotor(
        &bodies.rotation[b],
        &bodies.inertia[b],
        &(inertia_begin * w_theta),
        h,
    );
    bodies.rotation[b] = q;
    let body_momentum = q.inverse_transform_vector(&momentum);
    let body_w = bodies.inertia[b]
        .cholesky()
        .map_or(AngVector::zeros(), |c| c.solve(&body_momentum));
    let w = q * body_w;
    bodies.velocity[b] = l1;
    bodies.angular_velocity[b] = w;
}
