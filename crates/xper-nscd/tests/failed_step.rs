//! A step lends the world's contact rows and impulses to its solver; a step that fails must
//! give them back whole, so that the world can still be written out or stepped on.

use xper_bodies::{Body, BodySet};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{MoreauJean, StepError, StepParams, VelocitySolver, World};
use xper_solver::{NlgsParams, SolveError};

/// A column of three disks on a floor, settled for a few steps so that every contact carries
/// an impulse.
fn settled_column() -> World {
    let r = 0.01;
    let mut set = BodySet::new();
    set.insert(Body::wall(Vector::new(-0.1, 0.0), Vector::new(0.1, 0.0)));
    for k in 0..3 {
        let y = r + 2.0 * r * k as Real + 1e-5 * k as Real;
        set.insert(Body::disk(r, 1000.0, Vector::new(1e-4 * k as Real, y)));
    }
    let mut laws = LawTable::new(1);
    let law = SignoriniCoulomb {
        friction: 0.4,
        restitution: 0.0,
    };
    laws.set(0, 0, InteractionLaw::SignoriniCoulomb(law));
    let params = StepParams {
        dt: 1e-3,
        theta: 0.5,
        gravity: Vector::new(0.0, -9.81),
        alert_distance: 1e-3,
        detection: Default::default(),
        nlgs: NlgsParams {
            tolerance: 1e-10,
            max_iterations: 10_000,
            ..Default::default()
        },
        solver: VelocitySolver::Nlgs,
        projection_tolerance: None,
    };
    let mut world = World::new(set, laws, params);
    let mut stepper = MoreauJean::new();
    for _ in 0..20 {
        stepper.step(&mut world).unwrap();
    }
    world
}

#[test]
fn a_failed_step_gives_the_contact_rows_and_impulses_back() {
    let before = settled_column();
    let n = before.contacts.len();
    assert!(n >= 3, "{n} contacts");
    assert!(before.contacts.impulses.iter().all(|r| r[0] > 0.0));

    // The solver refuses its parameters after detection and assembly have run.
    let mut failed = before.clone();
    failed.params.nlgs.relaxation = 3.0;
    let mut stepper = MoreauJean::new();
    let error = stepper.step(&mut failed).unwrap_err();
    assert!(matches!(
        error,
        StepError::Solver(SolveError::InvalidParams(_))
    ));
    let set = &failed.contacts;
    assert_eq!(
        [
            set.rows.len(),
            set.keys.len(),
            set.gaps.len(),
            set.impulses.len()
        ],
        [n; 4]
    );
    assert_eq!(set.impulses, before.contacts.impulses, "warm start kept");
    assert_eq!(set.keys, before.contacts.keys);

    // Stepped on with valid parameters, it follows the world that never failed bit for bit.
    failed.params.nlgs.relaxation = 1.0;
    stepper.step(&mut failed).unwrap();
    let mut reference = before.clone();
    MoreauJean::new().step(&mut reference).unwrap();
    assert_eq!(failed.bodies.position, reference.bodies.position);
    assert_eq!(failed.contacts.impulses, reference.contacts.impulses);
}
