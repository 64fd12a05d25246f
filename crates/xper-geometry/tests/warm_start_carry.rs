//! Impulses carried from one detection to the next: the same contact (bodies and feature)
//! gets its previous impulse back, a new contact starts from zero, and a contact that left
//! the alert distance is forgotten.

use xper_bodies::{Body, BodySet, Drive, Shape};
use xper_geometry::{ContactSet, Detector};
use xper_math::{Real, Vector};

fn disk(x: Real, y: Real, radius: Real) -> Body {
    Body {
        shape: Shape::Disk { radius },
        position: Vector::new(x, y),
        rotation: 0.0,
        velocity: Vector::zeros(),
        angular_velocity: 0.0,
        mass: 1.0,
        inertia: 1.0,
        group: 0,
        drives: [Drive::Free, Drive::Free, Drive::Free],
    }
}

#[test]
fn impulses_follow_their_contacts_between_detections() {
    // A row of touching unit disks; every neighbour pair is a contact.
    let mut bodies = BodySet::new();
    for k in 0..6 {
        bodies.insert(disk(2.0 * k as Real, 0.0, 1.0));
    }
    let mut detector = Detector::new();
    let mut contacts = ContactSet::default();
    detector.detect(&bodies, 0.01, |_, _| Some(0), &mut contacts);
    assert_eq!(contacts.len(), 5);
    // Distinct impulses, one left at zero.
    for (k, r) in contacts.impulses.iter_mut().enumerate() {
        *r = if k == 2 {
            [0.0, 0.0]
        } else {
            [1.0 + k as Real, -0.5 * k as Real]
        };
    }
    let expected: Vec<([u32; 2], [Real; 2])> =
        contacts.iter().map(|c| (c.row.bodies, c.impulse)).collect();
    // Move the last disk away (its contact leaves) and add a new touching disk.
    bodies.position[5].x += 1.0;
    bodies.insert(disk(0.0, 2.0, 1.0));
    detector.detect(&bodies, 0.01, |_, _| Some(0), &mut contacts);
    for c in contacts.iter() {
        let bodies = c.row.bodies;
        let before = expected.iter().find(|(b, _)| *b == bodies);
        match before {
            Some((_, impulse)) => assert_eq!(c.impulse, *impulse, "{bodies:?}"),
            None => assert_eq!(c.impulse, [0.0, 0.0], "new contact {bodies:?}"),
        }
    }
    assert!(contacts.rows.iter().all(|r| r.bodies != [4, 5]));
    assert!(contacts.rows.iter().any(|r| r.bodies == [0, 6]));
    assert_eq!(contacts.len(), 5);
}
