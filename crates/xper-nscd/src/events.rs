//! Events of a run: changes of drives, friction coefficients and the periodic cell's controls
//! at given times, the stages of a staged test (a sample compacted without friction, then
//! sheared with it; a wall held by a pressure, then moved at a strain rate; a cell compacted
//! under an isotropic stress, then strained along one axis), applied at the beginning of the
//! first step that starts at or after their time, as Basilisk's events are in its time loop.

use crate::cell::CellLoad;
use crate::World;
use serde::{Deserialize, Serialize};
use xper_bodies::Drive;
use xper_laws::InteractionLaw;
use xper_math::Real;

/// What an event changes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Change {
    /// Degree of freedom `dof` of body `body` is driven by `drive` from now on.
    Drive {
        /// The body (index in the body set).
        body: u32,
        /// The degree of freedom (translations, then rotations).
        dof: usize,
        /// Its new drive.
        drive: Drive,
    },
    /// The friction coefficient of the law between two groups.
    Friction {
        /// The two groups.
        groups: [u16; 2],
        /// Coulomb's coefficient, >= 0.
        friction: Real,
    },
    /// The control of component `L_kl` of the periodic cell's velocity gradient (`k <= l`).
    /// The gradient itself carries on: a component put under stress starts from its current
    /// rate, one given a rate takes it at the next step.
    Cell {
        /// `[k, l]`.
        component: [usize; 2],
        /// Its new control.
        load: CellLoad,
    },
}

/// Changes made at a time (s).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// When (s): applied before the first step whose beginning is at or after it.
    pub time: Real,
    /// What changes.
    pub changes: Vec<Change>,
}

/// A run's events in time order and how many have been applied.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Events {
    /// The events, by increasing time.
    pub list: Vec<Event>,
    /// Events applied so far (the first ones of `list`).
    pub applied: usize,
}

impl World {
    /// Applies the events due at the beginning of the step starting at `t_begin` (those at or
    /// before `t_begin + dt / 2`, so that round-off in the time never delays one by a step).
    pub fn apply_due_events(&mut self, t_begin: Real) {
        let due = t_begin + 0.5 * self.params.dt;
        while let Some(event) = self.events.list.get(self.events.applied) {
            if event.time > due {
                break;
            }
            for change in event.changes.clone() {
                match change {
                    Change::Drive { body, dof, drive } => {
                        self.bodies.set_drive(body as usize, dof, drive)
                    }
                    Change::Friction { groups, friction } => {
                        let [a, b] = groups;
                        if let Some(k) = self.laws.between(a, b) {
                            let InteractionLaw::SignoriniCoulomb(law) = self.laws.law_mut(k);
                            law.friction = friction;
                        }
                    }
                    Change::Cell { component, load } => {
                        if let Some(cell) = &mut self.cell {
                            cell.loads[component[0]][component[1]] = load;
                        }
                    }
                }
            }
            self.events.applied += 1;
        }
    }
}

#[cfg(all(test, feature = "dim2"))]
mod tests {
    use super::*;
    use crate::{MoreauJean, StepParams};
    use xper_bodies::{Body, BodySet, TimeFunction};
    use xper_laws::{LawTable, SignoriniCoulomb};
    use xper_math::Vector;

    #[test]
    fn events_apply_at_the_first_step_beginning_at_their_time() {
        let mut bodies = BodySet::new();
        bodies.insert(Body::disk(0.1, 1000.0, Vector::zeros()));
        let mut laws = LawTable::new(1);
        let law = SignoriniCoulomb {
            friction: 0.0,
            restitution: 0.0,
        };
        laws.set(0, 0, InteractionLaw::SignoriniCoulomb(law));
        let params = StepParams::for_tests(0.01);
        let mut world = World::new(bodies, laws, params);
        world.events.list = vec![Event {
            // Three steps of 0.01 s end at 0.030000000000000002: round-off must not delay it.
            time: 0.03,
            changes: vec![
                Change::Drive {
                    body: 0,
                    dof: 0,
                    drive: Drive::Velocity(TimeFunction::Constant(2.0)),
                },
                Change::Friction {
                    groups: [0, 0],
                    friction: 0.5,
                },
            ],
        }];
        let mut stepper = MoreauJean::new();
        for _ in 0..3 {
            stepper.step(&mut world).unwrap();
        }
        assert_eq!(world.bodies.position[0].x, 0.0);
        assert_eq!(world.events.applied, 0);
        stepper.step(&mut world).unwrap();
        assert_eq!(world.events.applied, 1);
        // Step 4 imposes 2 m/s: q += h ((1 - theta) 0 + theta 2) = 0.01 m; step 5 moves 0.02 m.
        assert!((world.bodies.position[0].x - 0.01).abs() < 1e-15);
        assert_eq!(
            world.contact_law([0, 0]).map(|l| match l {
                InteractionLaw::SignoriniCoulomb(l) => l.friction,
            }),
            Some(0.5)
        );
        stepper.step(&mut world).unwrap();
        assert!((world.bodies.position[0].x - 0.03).abs() < 1e-15);
        // Applied once: a checkpointed world keeps the count.
        let again = World::from_bytes(&world.to_bytes()).unwrap();
        assert_eq!(again.events.applied, 1);
    }
}
