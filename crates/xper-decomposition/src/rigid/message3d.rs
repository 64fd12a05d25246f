//! What the processes of a 3D run exchange: a body's state and a contact, as numbers.

use xper_bodies::BodySet;
use xper_geometry::{Contact, ContactKey, ContactRow};
use xper_math::{AngVector, Rotation, Vector};

/// Numbers per body state: id, position, orientation (quaternion `i, j, k, w`), velocity,
/// angular velocity.
pub(super) const STATE: usize = 14;
/// Numbers per contact: bodies, feature, normal, first tangent, lever arms, gap, impulse.
pub(super) const CONTACT: usize = 19;

pub(super) fn write_state(out: &mut Vec<f64>, bodies: &BodySet, b: u32) {
    let k = b as usize;
    out.push(b as f64);
    out.extend_from_slice(bodies.position[k].as_slice());
    out.extend_from_slice(bodies.rotation[k].coords.as_slice());
    out.extend_from_slice(bodies.velocity[k].as_slice());
    out.extend_from_slice(bodies.angular_velocity[k].as_slice());
}

pub(super) fn set_state(bodies: &mut BodySet, s: &[f64]) -> u32 {
    let b = s[0] as usize;
    bodies.position[b] = Vector::from_column_slice(&s[1..4]);
    // The quaternion as it was sent, bit for bit (already unit).
    let q = nalgebra::Quaternion::new(s[7], s[4], s[5], s[6]);
    bodies.rotation[b] = Rotation::new_unchecked(q);
    bodies.velocity[b] = Vector::from_column_slice(&s[8..11]);
    bodies.angular_velocity[b] = AngVector::from_column_slice(&s[11..14]);
    b as u32
}

/// A contact as [`CONTACT`] numbers: bodies, feature, normal, first tangent, lever arms, gap,
/// impulse (the Delassus block is the step's, recomputed by each).
pub(super) fn write_contact(out: &mut Vec<f64>, c: &Contact) {
    let r = &c.row;
    out.extend_from_slice(&[r.bodies[0] as f64, r.bodies[1] as f64]);
    out.push(c.key.feature as f64);
    out.extend_from_slice(&r.normal);
    out.extend_from_slice(&r.tangent);
    out.extend_from_slice(&r.arms[0]);
    out.extend_from_slice(&r.arms[1]);
    out.push(c.gap);
    out.extend_from_slice(&c.impulse);
}

pub(super) fn read_contact(m: &[f64]) -> Contact {
    let three = |k: usize| [m[k], m[k + 1], m[k + 2]];
    Contact {
        row: ContactRow {
            bodies: [m[0] as u32, m[1] as u32],
            normal: three(3),
            tangent: three(6),
            arms: [three(9), three(12)],
            block: [0.0; 6],
        },
        key: ContactKey {
            feature: m[2] as u32,
        },
        gap: m[15],
        impulse: three(16),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use xper_bodies::Body;

    /// A state and a contact read back are the ones written, bit for bit.
    #[test]
    fn messages_round_trip() {
        let mut bodies = BodySet::new();
        let ball = Body::sphere(0.1, 1000.0, Vector::new(0.1, -0.2, 0.3))
            .with_rotation(Rotation::from_scaled_axis(Vector::new(0.3, 0.2, -0.1)))
            .with_velocity(Vector::new(1.0, 2.0, 3.0));
        bodies.insert(ball.clone());
        bodies.insert(ball);
        bodies.angular_velocity[0] = AngVector::new(-1.0, 0.5, 0.25);
        let mut out = Vec::new();
        write_state(&mut out, &bodies, 0);
        assert_eq!(out.len(), STATE);
        let mut copy = bodies.clone();
        copy.position[0] = Vector::zeros();
        copy.rotation[0] = Rotation::identity();
        assert_eq!(set_state(&mut copy, &out), 0);
        assert_eq!(copy, bodies);
        let point = Vector::new(0.1, 0.2, 0.3);
        let normal = Vector::new(0.0, 0.6, 0.8);
        let row = ContactRow::new([0, 1], &point, &normal, &Vector::zeros(), &Vector::x());
        let c = Contact {
            row,
            key: ContactKey { feature: 7 },
            gap: -1e-5,
            impulse: [1.0, -2.0, 0.5],
        };
        let mut out = Vec::new();
        write_contact(&mut out, &c);
        assert_eq!(out.len(), CONTACT);
        assert_eq!(read_contact(&out), c);
    }
}
