//! What the processes of a 2D run exchange: a body's state and a contact, as numbers.

use xper_bodies::BodySet;
use xper_geometry::{Contact, ContactKey, ContactRow};
use xper_math::Vector;

/// Numbers per body state: id, position, angle, velocity, angular velocity.
pub(super) const STATE: usize = 7;
/// Numbers per contact: bodies, feature, normal, lever arms, gap, impulse.
pub(super) const CONTACT: usize = 12;

pub(super) fn write_state(out: &mut Vec<f64>, bodies: &BodySet, b: u32) {
    let k = b as usize;
    let (x, v) = (bodies.position[k], bodies.velocity[k]);
    out.extend_from_slice(&[
        b as f64,
        x.x,
        x.y,
        bodies.rotation[k],
        v.x,
        v.y,
        bodies.angular_velocity[k],
    ]);
}

pub(super) fn set_state(bodies: &mut BodySet, s: &[f64]) -> u32 {
    let b = s[0] as usize;
    bodies.position[b] = Vector::new(s[1], s[2]);
    bodies.rotation[b] = s[3];
    bodies.velocity[b] = Vector::new(s[4], s[5]);
    bodies.angular_velocity[b] = s[6];
    b as u32
}

/// A contact as [`CONTACT`] numbers: bodies, feature, normal, lever arms, gap, impulse
/// (the Delassus block is the step's, recomputed by each).
pub(super) fn write_contact(out: &mut Vec<f64>, c: &Contact) {
    let r = &c.row;
    out.extend_from_slice(&[r.bodies[0] as f64, r.bodies[1] as f64]);
    out.push(c.key.feature as f64);
    out.extend_from_slice(&r.normal);
    out.extend_from_slice(&r.arms);
    out.extend_from_slice(&[c.gap, c.impulse[0], c.impulse[1]]);
}

pub(super) fn read_contact(m: &[f64]) -> Contact {
    Contact {
        row: ContactRow {
            bodies: [m[0] as u32, m[1] as u32],
            normal: [m[3], m[4]],
            arms: [m[5], m[6], m[7], m[8]],
            block: [0.0; 3],
        },
        key: ContactKey {
            feature: m[2] as u32,
        },
        gap: m[9],
        impulse: [m[10], m[11]],
    }
}
