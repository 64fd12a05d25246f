//! The last stages of a step: the linearised end gaps, and the projection of positions that
//! removes overlaps larger than the tolerance (a frictionless NLGS on positions with the end
//! gaps as shifts, Acary 2013), which leaves the velocities untouched.

use super::MoreauJean;
use crate::contact_solve::{reborrow, ContactSolve};
use crate::dimension::{displace, gravity_power};
use crate::operator::RigidContactOperator;
use crate::report::StepError;
use crate::world::{Detection, World};
use xper_bodies::Ownership;
use xper_math::buffer::refill;
use xper_math::{Real, DIM, DOFS};
use xper_solver::{nlgs, ContactOperator, NlgsParams};

impl MoreauJean {
    /// Exchanges the operator's rows (the active contacts') with every contact's rows when
    /// the active contacts are a subset; a second call restores them.
    pub(super) fn exchange_rows(&mut self) {
        if self.active_is_subset {
            std::mem::swap(&mut self.op.rows, &mut self.all_rows);
        }
        self.exchange_spans();
    }

    /// Replaces the gap of every contact by its linearised gap at the end of the step, and
    /// returns the largest overlap among them; called before [`Self::update`], while the
    /// bodies hold the velocities at the beginning of the step.
    pub(super) fn end_gaps(&mut self, world: &mut World) -> Real {
        let (h, theta, detection) = (self.h, world.params.theta, world.params.detection);
        self.exchange_rows();
        let mut deepest: Real = 0.0;
        for (a, gap) in world.contacts.gaps.iter_mut().enumerate() {
            let u_end = self.op.local_velocity(a)[0];
            let u_begin = self.op.local_velocity_at(a, &world.bodies)[0];
            // The gap plus the motion still to come: `predicted_gap` and `h theta u_end`, summed
            // in one expression for a detection on `q_i` (as before the option existed).
            *gap += match detection {
                Detection::Begin => h * ((1.0 - theta) * u_begin + theta * u_end),
                Detection::Predicted => h * theta * u_end,
            };
            deepest = deepest.max(-*gap);
        }
        self.exchange_rows();
        deepest
    }

    /// Removes overlaps larger than the projection tolerance, from the end gaps that
    /// [`Self::end_gaps`] left in the contacts and their largest overlap `deepest` on this
    /// process: returns the sweeps used and the largest overlap before projection.
    pub(super) fn project(
        &mut self,
        world: &mut World,
        mut deepest: Real,
        mut shared: Option<&mut dyn ContactSolve<RigidContactOperator>>,
    ) -> Result<(u32, Real), StepError> {
        if let Some(s) = reborrow(&mut shared) {
            deepest = s.max(deepest);
        }
        if !(world.params.projection_tolerance).is_some_and(|tolerance| deepest > tolerance) {
            return Ok((0, deepest));
        }
        self.exchange_rows();
        let n = self.op.rows.len();
        for body in &mut self.op.bodies {
            body.velocity = [0.0; DOFS];
        }
        refill(&mut self.mu, std::iter::repeat_n(0.0, n));
        refill(&mut self.impulses, std::iter::repeat_n([0.0; DIM], n));
        let params = NlgsParams {
            acceleration: xper_solver::Acceleration::None,
            ..world.params.nlgs
        };
        let (op, mu, shift) = (&mut self.op, &self.mu, &world.contacts.gaps);
        let info = match shared {
            Some(s) => s.solve(op, mu, shift, &[], &mut self.impulses, &params),
            None => nlgs(op, mu, shift, &mut self.impulses, &params),
        }
        .map_err(StepError::Solver)?;
        let bodies = &mut world.bodies;
        let gravity = world.params.gravity;
        for (b, body) in self.op.bodies.iter().enumerate() {
            if bodies.is_dynamic(b) && bodies.ownership[b] == Ownership::Owned {
                world.energy.projection_work -=
                    bodies.mass[b] * gravity_power(&gravity, &body.velocity);
            }
            displace(bodies, b, &body.velocity);
        }
        self.exchange_rows();
        Ok((info.iterations, deepest))
    }
}
