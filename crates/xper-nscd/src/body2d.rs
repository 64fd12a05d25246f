//! The 2D parts of the rigid-body operator: a body's working state (velocity `(vx, vy, w)`
//! and diagonal inverse mass), the local velocity of a contact row, the impulses it exerts,
//! and the update of a body's configuration.

use xper_bodies::{BodySet, InverseMass};
use xper_geometry::ContactRow;
use xper_math::{tangent, Real, Vector, DIM, DOFS};

/// A local impulse or velocity `(normal, tangent)`.
pub type Local = [Real; DIM];

/// Working state of one body: generalised velocity and inverse masses per degree of freedom.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(16))]
pub struct SolverBody {
    /// Generalised velocity (vx, vy, w).
    pub velocity: [Real; DOFS],
    /// Inverse mass per degree of freedom (0 where imposed or infinite).
    pub inv_mass: InverseMass,
}

impl SolverBody {
    /// Whether impulses move degree of freedom `d` (its inverse mass is not 0).
    #[inline(always)]
    pub fn is_free(&self, d: usize) -> bool {
        self.inv_mass[d] != 0.0
    }

    /// Whether impulses move the body at all.
    #[inline]
    pub fn is_movable(&self) -> bool {
        self.inv_mass.iter().any(|&w| w != 0.0)
    }

    /// `v += h g` on the free translations.
    #[inline(always)]
    pub fn add_gravity(&mut self, h: Real, g: &Vector) {
        self.velocity[0] += h * g.x * (self.inv_mass[0] > 0.0) as u8 as Real;
        self.velocity[1] += h * g.y * (self.inv_mass[1] > 0.0) as u8 as Real;
    }

    /// `v += h M^-1 f` for a generalised force `f`.
    #[inline]
    pub fn add_force(&mut self, h: Real, f: &[Real; DOFS]) {
        for ((v, m), f) in self.velocity.iter_mut().zip(self.inv_mass).zip(f) {
            *v += h * m * f;
        }
    }

    /// `v += h M^-1 f e_d` for a force `f` on degree of freedom `d` alone.
    #[inline]
    pub fn add_dof_force(&mut self, d: usize, h: Real, f: Real) {
        self.velocity[d] += h * self.inv_mass[d] * f;
    }

    /// Multiplies the inverse mass by `factor`.
    #[inline]
    pub fn scale_inverse_mass(&mut self, factor: Real) {
        for w in &mut self.inv_mass {
            *w *= factor;
        }
    }
}

/// `x^T M^-1 y`, the same bits for `(x, y)` and `(y, x)`.
#[inline]
pub fn inverse_mass_product(m: &InverseMass, x: &[Real; DOFS], y: &[Real; DOFS]) -> Real {
    (0..DOFS).map(|d| m[d] * (x[d] * y[d])).sum()
}

/// The local velocity `(U_N, U_T)` of `row` from the generalised velocities of its bodies.
#[inline(always)]
pub fn relative_velocity(row: &ContactRow, vi: &[Real; DOFS], vj: &[Real; DOFS]) -> Local {
    let [nx, ny] = row.normal;
    let (dx, dy) = (vj[0] - vi[0], vj[1] - vi[1]);
    let a = &row.arms;
    [
        nx * dx + ny * dy + vj[2] * a[2] - vi[2] * a[0],
        -ny * dx + nx * dy + vj[2] * a[3] - vi[2] * a[1],
    ]
}

/// A world vector `v` in the frame of `row`: `(v . n, v . t)`.
#[inline(always)]
pub fn local_of(row: &ContactRow, v: &Vector) -> Local {
    let [nx, ny] = row.normal;
    [nx * v.x + ny * v.y, -ny * v.x + nx * v.y]
}

/// Adds the local impulse `d` of `row` to the velocities of its two bodies (`-d` on the first).
#[inline(always)]
pub fn push_bodies(bodies: &mut [SolverBody], row: &ContactRow, d: Local) {
    let [nx, ny] = row.normal;
    let (px, py) = (nx * d[0] - ny * d[1], ny * d[0] + nx * d[1]);
    let a = row.arms;
    let bi = &mut bodies[row.bodies[0] as usize];
    bi.velocity[0] -= bi.inv_mass[0] * px;
    bi.velocity[1] -= bi.inv_mass[1] * py;
    bi.velocity[2] -= bi.inv_mass[2] * (a[0] * d[0] + a[1] * d[1]);
    let bj = &mut bodies[row.bodies[1] as usize];
    bj.velocity[0] += bj.inv_mass[0] * px;
    bj.velocity[1] += bj.inv_mass[1] * py;
    bj.velocity[2] += bj.inv_mass[2] * (a[2] * d[0] + a[3] * d[1]);
}

/// Generalised impulses `(on body i, on body j)` of a local impulse `r` at a row.
#[inline(always)]
pub fn generalized_impulses(row: &ContactRow, r: Local) -> ([Real; DOFS], [Real; DOFS]) {
    let n = Vector::new(row.normal[0], row.normal[1]);
    let p = n * r[0] + tangent(&n) * r[1];
    let a = &row.arms;
    (
        [-p.x, -p.y, -(a[0] * r[0] + a[1] * r[1])],
        [p.x, p.y, a[2] * r[0] + a[3] * r[1]],
    )
}

/// `g . v` over the translations of a generalised velocity (W/kg).
#[inline(always)]
pub fn gravity_power(g: &Vector, v: &[Real; DOFS]) -> Real {
    g.x * v[0] + g.y * v[1]
}

/// Work over a step of `h` of the reaction that holds degree of freedom `d` of body `b` at
/// its imposed velocity, from `v0` to `v1` (besides contacts): the change of its kinetic
/// energy less gravity's work; 0 for an infinite mass.
#[inline]
pub fn imposed_velocity_work(
    bodies: &BodySet,
    b: usize,
    d: usize,
    [v0, v1]: [&[Real; DOFS]; 2],
    h: Real,
    g: &Vector,
) -> Real {
    let masses = [bodies.mass[b], bodies.mass[b], bodies.inertia[b]];
    if !masses[d].is_finite() {
        return 0.0;
    }
    let mean = (v0[d] + v1[d]) / 2.0;
    let gravity = if d < 2 { g[d] } else { 0.0 };
    masses[d] * (v1[d] * v1[d] - v0[d] * v0[d]) / 2.0 - h * masses[d] * gravity * mean
}

/// Moves body `b` by the generalised displacement `dq`.
#[inline(always)]
pub fn displace(bodies: &mut BodySet, b: usize, dq: &[Real; DOFS]) {
    bodies.position[b].x += dq[0];
    bodies.position[b].y += dq[1];
    bodies.rotation[b] += dq[2];
}

/// The end of a step for body `b`: `q_i+1 = q_i + h ((1 - theta) v_i + theta v_i+1)` and
/// `v_i+1`, from the velocities `v0` (in the body set) and `v1` (the solver's).
#[inline]
pub fn advance(bodies: &mut BodySet, b: usize, v1: [Real; DOFS], h: Real, theta: Real) {
    let v0 = bodies.generalized_velocity(b);
    let dq: [Real; DOFS] = std::array::from_fn(|d| h * ((1.0 - theta) * v0[d] + theta * v1[d]));
    displace(bodies, b, &dq);
    bodies.set_generalized_velocity(b, v1);
}
