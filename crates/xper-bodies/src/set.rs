//! The body set: every rigid body of a run, stored as a structure of arrays.

use crate::{Drive, Shape};
use serde::{Deserialize, Serialize};
use xper_math::{integrate_rotation, AngMatrix, AngVector, Real, Rotation, Vector, DOFS};

#[cfg(feature = "dim2")]
#[path = "set2d.rs"]
mod dimension;
#[cfg(feature = "dim3")]
#[path = "set3d.rs"]
mod dimension;
#[cfg(feature = "dim3")]
pub use dimension::isotropic_inertia;
pub use dimension::InverseMass;

/// Index of a body in its [`BodySet`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct BodyHandle(pub u32);

impl BodyHandle {
    /// The index as `usize`.
    #[inline(always)]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Which process owns a body in a domain-decomposed run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Ownership {
    /// Integrated by this process.
    #[default]
    Owned,
    /// A copy of a body owned by process `owner`, kept for contacts near a subdomain boundary.
    Shadow {
        /// Rank of the owning process.
        owner: u32,
    },
}

/// Everything needed to add one body to a [`BodySet`].
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Geometry.
    pub shape: Shape,
    /// Centre of mass (m).
    pub position: Vector,
    /// Orientation (2D: the angle, rad).
    pub rotation: Rotation,
    /// Velocity of the centre of mass (m/s).
    pub velocity: Vector,
    /// Angular velocity (rad/s).
    pub angular_velocity: AngVector,
    /// Mass (kg per m of thickness); `INFINITY` for walls.
    pub mass: Real,
    /// Moment of inertia about the centre of mass (kg m^2 per m); `INFINITY` for walls.
    pub inertia: AngMatrix,
    /// Index of the body's group in the law table.
    pub group: u16,
    /// Drives of the x, y and rotation degrees of freedom.
    pub drives: [Drive; DOFS],
}

/// Positions and angles of every body of a [`BodySet`], saved by
/// [`BodySet::advance_explicitly`].
#[derive(Clone, Debug, Default)]
pub struct Configuration {
    position: Vec<Vector>,
    rotation: Vec<Rotation>,
}

/// All bodies of a run. Field `k` of every array belongs to body `k`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BodySet {
    /// Centres of mass (m).
    pub position: Vec<Vector>,
    /// Orientations (2D: angles, rad).
    pub rotation: Vec<Rotation>,
    /// Velocities (m/s).
    pub velocity: Vec<Vector>,
    /// Angular velocities (rad/s).
    pub angular_velocity: Vec<AngVector>,
    /// Masses (kg per m).
    pub mass: Vec<Real>,
    /// Moments of inertia about the centre of mass, in the body's frame (kg m^2 per m).
    pub inertia: Vec<AngMatrix>,
    /// The degrees of freedom whose velocity is imposed, one bit each (x: 1, y: 2,
    /// rotation: 4); see [`BodySet::inv_mass`].
    pub imposed: Vec<u8>,
    /// Shapes.
    pub shape: Vec<Shape>,
    /// Group index of each body.
    pub group: Vec<u16>,
    /// Global identifier (stable across processes and restarts).
    pub id: Vec<u64>,
    /// Owner process of each body.
    pub ownership: Vec<Ownership>,
    /// Bodies with at least one driven degree of freedom, in body order, with their drives.
    pub driven: Vec<(BodyHandle, [Drive; DOFS])>,
}

impl BodySet {
    /// An empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of bodies.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Adds a body and returns its handle.
    pub fn insert(&mut self, body: Body) -> BodyHandle {
        let handle = BodyHandle(self.len() as u32);
        let imposed = (body.drives.iter().enumerate())
            .filter(|(_, d)| d.is_imposed_velocity())
            .fold(0u8, |bits, (k, _)| bits | 1 << k);
        self.position.push(body.position);
        self.rotation.push(body.rotation);
        self.velocity.push(body.velocity);
        self.angular_velocity.push(body.angular_velocity);
        self.mass.push(body.mass);
        self.inertia.push(body.inertia);
        self.imposed.push(imposed);
        self.shape.push(body.shape);
        self.group.push(body.group);
        self.id.push(handle.0 as u64);
        self.ownership.push(Ownership::Owned);
        if body.drives.iter().any(|d| *d != Drive::Free) {
            self.driven.push((handle, body.drives));
        }
        handle
    }

    /// Sets what drives degree of freedom `d` (translations then rotations) of body `b`,
    /// between steps: the imposed-velocity bits and the list of driven bodies (in body order)
    /// follow.
    pub fn set_drive(&mut self, b: usize, d: usize, drive: Drive) {
        let handle = BodyHandle(b as u32);
        let bit = 1u8 << d;
        match drive.is_imposed_velocity() {
            true => self.imposed[b] |= bit,
            false => self.imposed[b] &= !bit,
        }
        match self.driven.binary_search_by_key(&handle, |(h, _)| *h) {
            Ok(k) => {
                self.driven[k].1[d] = drive;
                if self.driven[k].1.iter().all(|x| *x == Drive::Free) {
                    self.driven.remove(k);
                }
            }
            Err(at) if drive != Drive::Free => {
                let mut drives: [Drive; DOFS] = Default::default();
                drives[d] = drive;
                self.driven.insert(at, (handle, drives));
            }
            Err(_) => {}
        }
    }

    /// Body `b` as the description [`BodySet::insert`] takes.
    pub fn body(&self, b: usize) -> Body {
        Body {
            shape: self.shape[b].clone(),
            position: self.position[b],
            rotation: self.rotation[b],
            velocity: self.velocity[b],
            angular_velocity: self.angular_velocity[b],
            mass: self.mass[b],
            inertia: self.inertia[b],
            group: self.group[b],
            drives: self.drives(b),
        }
    }

    /// What drives each degree of freedom of body `b`.
    pub fn drives(&self, b: usize) -> [Drive; DOFS] {
        let handle = BodyHandle(b as u32);
        match self.driven.binary_search_by_key(&handle, |(h, _)| *h) {
            Ok(k) => self.driven[k].1.clone(),
            Err(_) => Default::default(),
        }
    }

    /// Moves every body by `dt` times its velocity (`q += dt v`) after saving the configuration
    /// it had in `saved` (whose buffers are reused), for [`BodySet::restore_configuration`]:
    /// Moreau-Jean's detection configuration `q_TT = q_i + h (1 - theta) v_i` is
    /// `advance_explicitly(h * (1 - theta), saved)`.
    pub fn advance_explicitly(&mut self, dt: Real, saved: &mut Configuration) {
        saved.position.clone_from(&self.position);
        saved.rotation.clone_from(&self.rotation);
        for (q, v) in self.position.iter_mut().zip(&self.velocity) {
            *q += v * dt;
        }
        for (r, w) in self.rotation.iter_mut().zip(&self.angular_velocity) {
            *r = integrate_rotation(r, w, dt);
        }
    }

    /// Puts the bodies back, bit for bit, in the configuration [`BodySet::advance_explicitly`]
    /// saved.
    pub fn restore_configuration(&mut self, saved: &Configuration) {
        self.position.copy_from_slice(&saved.position);
        self.rotation.copy_from_slice(&saved.rotation);
    }

    /// Releases the room the arrays have beyond their bodies (a set filled by
    /// [`BodySet::insert`] grows by doubling, up to twice the room it needs).
    pub fn shrink_to_fit(&mut self) {
        self.position.shrink_to_fit();
        self.rotation.shrink_to_fit();
        self.velocity.shrink_to_fit();
        self.angular_velocity.shrink_to_fit();
        self.mass.shrink_to_fit();
        self.inertia.shrink_to_fit();
        self.imposed.shrink_to_fit();
        self.shape.shrink_to_fit();
        self.group.shrink_to_fit();
        self.id.shrink_to_fit();
        self.ownership.shrink_to_fit();
        self.driven.shrink_to_fit();
    }

    /// Whether a body has a finite mass (walls do not).
    #[inline(always)]
    pub fn is_dynamic(&self, b: usize) -> bool {
        self.mass[b].is_finite()
    }

    /// The finite-mass bodies this process owns, whose energies it counts.
    fn owned_dynamic(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.len()).filter(|&b| self.is_dynamic(b) && self.ownership[b] == Ownership::Owned)
    }

    /// Kinetic energy of the finite-mass bodies (2D: J per m; 3D: J): `m |v|^2 / 2` plus the
    /// rotational part (2D: `I w^2 / 2`; 3D: `w . (R I R^T w) / 2`).
    pub fn kinetic_energy(&self) -> Real {
        self.owned_dynamic()
            .map(|b| {
                0.5 * self.mass[b] * self.velocity[b].norm_squared() + self.rotational_energy(b)
            })
            .sum()
    }

    /// Gravitational potential energy of the finite-mass bodies (J per m), zero at the origin.
    pub fn potential_energy(&self, gravity: &Vector) -> Real {
        self.owned_dynamic()
            .map(|b| -self.mass[b] * gravity.dot(&self.position[b]))
            .sum()
    }
}

impl Body {
    /// Sets the orientation (2D: the angle, rad).
    pub fn with_rotation(mut self, rotation: Rotation) -> Self {
        self.rotation = rotation;
        self
    }

    /// Sets the initial velocity (m/s).
    pub fn with_velocity(mut self, velocity: Vector) -> Self {
        self.velocity = velocity;
        self
    }

    /// Puts the body in a group of the law table.
    pub fn in_group(mut self, group: u16) -> Self {
        self.group = group;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TimeFunction;

    /// A round body of either dimension (a disk in 2D, a sphere in 3D).
    fn ball(position: Vector) -> Body {
        #[cfg(feature = "dim2")]
        return Body::disk(0.1, 1000.0, position);
        #[cfg(feature = "dim3")]
        return Body::sphere(0.1, 1000.0, position);
    }

    fn set_of(n: usize) -> BodySet {
        let mut set = BodySet::new();
        for k in 0..n {
            let mut body = ball(Vector::repeat(k as Real));
            if k == 2 {
                body.drives[0] = Drive::Velocity(TimeFunction::Constant(1.0));
            }
            set.insert(body);
        }
        set
    }

    #[test]
    fn set_drive_keeps_the_driven_list_in_order_and_the_imposed_bits() {
        let mut set = set_of(4);
        let speed = |v| Drive::Velocity(TimeFunction::Constant(v));
        set.set_drive(3, 1, Drive::Force(TimeFunction::Constant(2.0)));
        set.set_drive(0, 0, speed(-1.0));
        let order: Vec<u32> = set.driven.iter().map(|(h, _)| h.0).collect();
        assert_eq!(order, [0, 2, 3]);
        assert_eq!(set.imposed, [1, 0, 1, 0]);
        assert_eq!(set.drives(3)[1], Drive::Force(TimeFunction::Constant(2.0)));
        assert_eq!(set.drives(1), <[Drive; DOFS]>::default());
        // Freeing every degree of freedom of a body drops it from the list.
        set.set_drive(2, 0, Drive::Free);
        set.set_drive(3, 1, Drive::Free);
        let order: Vec<u32> = set.driven.iter().map(|(h, _)| h.0).collect();
        assert_eq!(order, [0]);
        assert_eq!(set.imposed, [1, 0, 0, 0]);
        // The same as a set built with those drives from the start.
        let mut fresh = BodySet::new();
        for k in 0..4 {
            let mut body = ball(Vector::repeat(k as Real));
            if k == 0 {
                body.drives[0] = speed(-1.0);
            }
            fresh.insert(body);
        }
        assert_eq!(set.driven, fresh.driven);
        assert_eq!(set.imposed, fresh.imposed);
        // A body read back and inserted again is the same body.
        let copy = set.body(0);
        let k = set.insert(copy.clone()).index();
        assert_eq!(set.body(k), copy);
    }
}
