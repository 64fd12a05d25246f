//! One Moreau-Jean step as a sequence of named stages: detect, assemble, free velocity,
//! select, solve (NLGS, or an `xper_solver` solver on the assembled problem), energy,
//! end gaps, update, project.

use crate::assemble::assemble_problem;
use crate::contact_solve::reborrow;
pub use crate::contact_solve::ContactSolve;
use crate::dimension::{advance, imposed_velocity_work, Local};
use crate::operator::{ContactRow, RigidContactOperator, RigidProblem};
pub use crate::report::{energy_blown_up, StageTimes, StepError, StepReport};
use crate::select::{contact_owner_body, normal_shift, predicted_gap};
use crate::world::{Detection, VelocitySolver, World};
use std::time::Instant;
use xper_bodies::{Configuration, Ownership};
use xper_geometry::Detector;
use xper_laws::InteractionLaw;
use xper_math::buffer::{renew, renew_for};
use xper_math::{Real, DIM, DOFS};
use xper_solver::{nlgs, solve, ContactOperator, FrictionProblem, ProblemError, SolveError};

mod periodic;
mod project;

/// A problem the assembly refused (inconsistent sizes: a bug, never the user's data).
fn problem_error(e: ProblemError) -> StepError {
    StepError::Solver(SolveError::SizeMismatch { what: e.0 })
}

/// The Moreau-Jean stepper with its buffers.
///
/// After a step that completes it holds the detector's candidate list, the solver's bodies and
/// the external forces. During a step it borrows the world's contact rows (and impulses, when
/// every contact is active) for its operator, and gives them back when the step ends, failed
/// or not; the friction coefficients and shifts are taken, in room for the step's contacts
/// exactly, when a step assembles its problem and released when it ends, so that they never
/// coexist with a list build's arrays.
#[derive(Default)]
pub struct MoreauJean {
    capture: bool,
    captured: Option<FrictionProblem>,
    detector: Detector,
    op: RigidContactOperator,
    /// The rows of every contact while `op.rows` holds only the active ones; empty (and
    /// `op.rows` holds every row) when every contact is active, the usual case with e = 0.
    all_rows: Vec<ContactRow>,
    active_is_subset: bool,
    /// The indices of the active contacts when they are a subset; empty when every contact
    /// is active (see [`MoreauJean::active_contact`]).
    active: Vec<u32>,
    mu: Vec<Real>,
    shift: Vec<Real>,
    impulses: Vec<Local>,
    /// Forces applied to the bodies during each step besides gravity and drives (e.g. the
    /// fluid's), one generalised force per body; empty when there are none.
    external_forces: Vec<[Real; DOFS]>,
    /// The length of the step being taken (s): `world.params.dt` for [`MoreauJean::step`],
    /// the caller's for [`MoreauJean::step_by`]; set by [`MoreauJean::prepare`].
    h: Real,
    /// The bodies' configuration at the beginning of the step while they stand in the
    /// predicted one for the detection ([`Detection::Predicted`]); kept between steps.
    begin: Configuration,
    /// In a periodic cell, the image of each contact's second body (from the detection).
    images: Vec<xper_geometry::Image>,
    /// In a periodic cell, every contact's image shift while the operator holds the active
    /// ones' (see `all_rows`).
    all_spans: Vec<xper_math::Vector>,
    /// The same for the rows' offsets of the imposed flow.
    all_offsets: Vec<crate::dimension::Local>,
}

impl MoreauJean {
    /// A stepper with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the generalised forces (N/m and N m/m per body, translations then rotation) that
    /// act on the bodies during the following steps, besides gravity and imposed drives: e.g.
    /// the hydrodynamic forces of a fluid. Their work enters the energy budget as external
    /// work. An empty slice removes them; otherwise there must be one entry per body.
    pub fn set_external_forces(&mut self, forces: &[[Real; DOFS]]) {
        self.external_forces.clear();
        self.external_forces.extend_from_slice(forces);
    }

    /// Advances `world` by one time step of `world.params.dt`; the step's times are multiples
    /// of it (`t_i = i h`), exact over long runs.
    pub fn step(&mut self, world: &mut World) -> Result<StepReport, StepError> {
        let h = world.params.dt;
        let (t_begin, t_end) = (world.step as Real * h, (world.step + 1) as Real * h);
        self.step_between(world, [t_begin, t_end], h, None)
    }

    /// [`MoreauJean::step`] of a process's part of a distributed world: bodies marked
    /// [`Ownership::Shadow`] are copies of other processes' bodies, the contacts kept are those
    /// whose [`contact_owner_body`] is owned here, `solver` solves them together with the other
    /// processes', and the energies reported (kinetic, potential, dissipated, work) count only
    /// what this process owns, so that they add up over the processes. The energy check is the
    /// caller's, on the sums: `world.energy.scale` is left to the caller.
    pub fn step_with(
        &mut self,
        world: &mut World,
        solver: &mut dyn ContactSolve<RigidContactOperator>,
    ) -> Result<StepReport, StepError> {
        if let VelocitySolver::Assembled(_) = world.params.solver {
            return Err(StepError::Solver(SolveError::Unsupported(
                "a distributed step solves by NLGS only".into(),
            )));
        }
        let h = world.params.dt;
        let (t_begin, t_end) = (world.step as Real * h, (world.step + 1) as Real * h);
        self.step_between(world, [t_begin, t_end], h, Some(solver))
    }

    /// Advances `world` by a step of `h` from `world.time` (for time steps that change during
    /// a run, e.g. set by a fluid's stability limit); `world.params.dt` is left as it is (the
    /// caller's bound on the step, if any).
    pub fn step_by(&mut self, world: &mut World, h: Real) -> Result<StepReport, StepError> {
        let t_begin = world.time;
        self.step_between(world, [t_begin, t_begin + h], h, None)
    }

    /// One step of length `h` over `[t_begin, t_end]` (`t_end - t_begin` is `h` up to
    /// rounding: the bounds are computed so that long runs keep exact times).
    fn step_between(
        &mut self,
        world: &mut World,
        [t_begin, t_end]: [Real; 2],
        h: Real,
        shared: Option<&mut dyn ContactSolve<RigidContactOperator>>,
    ) -> Result<StepReport, StepError> {
        self.h = h;
        if world.cell.is_some() && (shared.is_some() || world.params.solver != VelocitySolver::Nlgs)
        {
            return Err(StepError::Solver(SolveError::Unsupported(
                "a periodic cell is solved by NLGS on one process only".into(),
            )));
        }
        world.apply_due_events(t_begin);
        let start = Instant::now();
        let mut report = StepReport {
            step: world.step + 1,
            ..Default::default()
        };
        let distributed = shared.is_some();
        self.prepare(world, &mut report, t_begin, t_end, distributed);
        let advanced = self.advance(world, &mut report, t_begin, t_end, shared);
        self.give_back(world);
        self.release_step_buffers();
        advanced?;

        world.step += 1;
        world.time = t_end;
        report.time = t_end;
        report.kinetic = world.kinetic_energy();
        report.potential = world.potential_energy();
        report.dissipated = world.energy.dissipated;
        report.external_work = world.energy.external_work;
        report.projection_work = world.energy.projection_work;
        report.energy_error = world.energy_error();
        let e = &mut world.energy;
        e.scale = e
            .scale
            .max((report.kinetic + report.potential - e.initial).abs())
            .max(e.external_work.abs());
        report.times.total = start.elapsed().as_secs_f64();
        let scale = e.scale + e.dissipated + report.kinetic.min(e.initial.abs());
        if !distributed && energy_blown_up(report.energy_error, scale) {
            return Err(StepError::EnergyBlowUp {
                error: report.energy_error,
                scale,
            });
        }
        Ok(report)
    }

    /// Stages solve, energy, end gaps, update and project, on the problem
    /// [`Self::prepare`] left.
    fn advance(
        &mut self,
        world: &mut World,
        report: &mut StepReport,
        t_begin: Real,
        t_end: Real,
        mut shared: Option<&mut dyn ContactSolve<RigidContactOperator>>,
    ) -> Result<(), StepError> {
        // Stage: solve.
        let t_solve = Instant::now();
        self.solve(world, report, reborrow(&mut shared))?;
        report.times.solve = t_solve.elapsed().as_secs_f64();

        // Stage: energy exchanged at contacts, with the same H at both ends of the step.
        let mut dissipated = 0.0;
        let mut imposed_work = 0.0;
        for k in 0..self.impulses.len() {
            let (r, row) = (self.impulses[k], &self.op.rows[k]);
            let u0 = self.op.local_velocity_at(k, &world.bodies);
            let u1 = self.op.local_velocity(k);
            let mut power = r[0] * (u0[0] + u1[0]) / 2.0;
            for k in 1..DIM {
                power += r[k] * (u0[k] + u1[k]) / 2.0;
            }
            dissipated -= power;
            let (gi, gj) = RigidContactOperator::generalized_impulses(row, r);
            for (b, g) in [(row.bodies[0] as usize, gi), (row.bodies[1] as usize, gj)] {
                let (body, v0) = (&self.op.bodies[b], world.bodies.generalized_velocity(b));
                for (d, &gd) in g.iter().enumerate() {
                    if !body.is_free(d) {
                        imposed_work += gd * (v0[d] + body.velocity[d]) / 2.0;
                    }
                }
            }
        }
        world.energy.dissipated += dissipated;
        world.energy.external_work += self.driven_work(world, t_begin, t_end) - imposed_work;
        world.energy.external_work += self.cell_work(world, t_begin, t_end);

        // Stage: linearised gaps at the end of the step, while the bodies still hold the
        // velocities at its beginning; the shifts are done with.
        self.shift = Vec::new();
        let deepest = self.end_gaps(world);

        // Stage: update velocities and positions (and, in a periodic cell, the flow's share
        // and the cell's edges); keep impulses for the warm start.
        self.carry_by_flow(world);
        self.update(world)?;
        self.finish_cell(world);
        if self.active_is_subset {
            let impulses = &mut world.contacts.impulses;
            impulses.fill([0.0; DIM]);
            for (&a, &r) in self.active.iter().zip(&self.impulses) {
                impulses[a as usize] = r;
            }
        } else {
            world.contacts.impulses = std::mem::take(&mut self.impulses);
        }

        // Stage: project positions out of overlaps.
        let t_project = Instant::now();
        (report.projection_iterations, report.max_overlap) =
            self.project(world, deepest, reborrow(&mut shared))?;
        report.times.project = t_project.elapsed().as_secs_f64();
        world.wrap_into_cell();
        Ok(())
    }

    /// Returns the rows lent to the operator by [`Self::prepare`] to the world's contacts, and
    /// their impulses when a failed step kept them (zero when it lost them).
    fn give_back(&mut self, world: &mut World) {
        let n = world.contacts.len();
        world.contacts.rows = if self.op.rows.len() == n {
            std::mem::take(&mut self.op.rows)
        } else {
            std::mem::take(&mut self.all_rows)
        };
        if world.contacts.impulses.len() != n {
            world.contacts.impulses = if self.impulses.len() == n {
                std::mem::take(&mut self.impulses)
            } else {
                vec![[0.0; DIM]; n]
            };
        }
    }

    /// Frees what only a step's problem needs (see [`MoreauJean`]). The solver's bodies are
    /// kept: their count does not change from step to step, the detection's own buffers fit
    /// beside them below the solve's peak, and a block of 48 bytes per body mapped afresh
    /// every step cost box1m (a million disks) 20 ms per step in page faults.
    fn release_step_buffers(&mut self) {
        self.op.rows = Vec::new();
        self.all_rows = Vec::new();
        self.active = Vec::new();
        self.mu = Vec::new();
        self.shift = Vec::new();
        self.impulses = Vec::new();
        self.op.cell = None;
        self.all_spans = Vec::new();
        self.all_offsets = Vec::new();
    }

    /// What the contact detector has done so far (calls, candidate-list builds, skin).
    pub fn detector_stats(&self) -> xper_geometry::DetectorStats {
        self.detector.stats()
    }

    /// Asks the next [`MoreauJean::step`] to keep a copy of its velocity problem, assembled
    /// before solving, for [`MoreauJean::take_problem`] (e.g. to write it to a file).
    pub fn capture_next_problem(&mut self) {
        self.capture = true;
    }

    /// The problem captured by the last step after [`MoreauJean::capture_next_problem`]
    /// (also when the solve then failed), if any.
    pub fn take_problem(&mut self) -> Option<FrictionProblem> {
        self.captured.take()
    }

    /// The velocity problem the next step of `world` would solve (same detection, free
    /// velocities, selection and shifts), without changing `world`; the stepper's buffers are
    /// rebuilt by the next step, which is unaffected.
    pub fn next_problem(&mut self, world: &World) -> Result<FrictionProblem, StepError> {
        self.prepare_next(world);
        assemble_problem(&self.op, &self.mu, &self.shift).map_err(problem_error)
    }

    /// The next step's velocity problem of `world` in factorised form (bodies at their free
    /// velocities, active rows), without changing `world`, as [`MoreauJean::next_problem`].
    pub fn next_rigid_problem(&mut self, world: &World) -> RigidProblem {
        self.prepare_next(world);
        RigidProblem {
            bodies: self.op.bodies.clone(),
            rows: self.op.rows.clone(),
            mu: self.mu.clone(),
            shift: self.shift.clone(),
            impulses: self.impulses.clone(),
        }
    }

    /// [`MoreauJean::prepare`] for the next step of a copy of `world`.
    fn prepare_next(&mut self, world: &World) {
        let mut world = world.clone();
        let mut report = StepReport::default();
        let h = world.params.dt;
        let (t_begin, t_end) = (world.step as Real * h, (world.step + 1) as Real * h);
        self.h = h;
        self.prepare(&mut world, &mut report, t_begin, t_end, false);
    }

    /// Stages detect, assemble, free velocity and select: leaves the operator in its state of
    /// zero impulses at the free velocities, with the active rows, `mu`, shifts and warm start.
    /// With `owned_only`, the contacts other processes own are dropped after detection.
    fn prepare(
        &mut self,
        world: &mut World,
        report: &mut StepReport,
        t_begin: Real,
        t_end: Real,
        owned_only: bool,
    ) {
        let start = Instant::now();
        let (h, theta) = (self.h, world.params.theta);

        // Stage: detect, on the configuration at the beginning of the step or on the one the
        // explicit part of the motion reaches (the bodies are put back exactly afterwards).
        let detection = world.params.detection;
        if detection == Detection::Predicted {
            (world.bodies).advance_explicitly(h * (1.0 - theta), &mut self.begin);
        }
        self.detect_contacts(world);
        if detection == Detection::Predicted {
            world.bodies.restore_configuration(&self.begin);
        }
        if owned_only {
            let bodies = &world.bodies;
            world.contacts.retain(|c| {
                let [i, j] = c.row.bodies;
                let b = contact_owner_body(bodies, i as usize, j as usize);
                bodies.ownership[b] == Ownership::Owned
            });
        }
        report.contacts = world.contacts.len();
        report.times.detect = start.elapsed().as_secs_f64();

        // Stage: assemble: the contacts' rows (normals and lever arms, from the detection) are
        // lent to the operator for the step, which fills their Delassus blocks. The velocities
        // at the beginning of the step stay in the bodies until the update; the local ones,
        // U_i = H^T v_i, are computed from them where needed (not stored).
        let bodies = &world.bodies;
        self.op
            .load_bodies(bodies, |b| bodies.generalized_velocity(b));
        self.op.rows = std::mem::take(&mut world.contacts.rows);
        self.load_cell(world, t_begin, t_end);
        self.op.refresh_blocks();

        // Stage: free velocity.
        self.free_velocity(world, t_begin, t_end);

        // Stage: select the active contacts (predicted gap closed) and their law data.
        let n = world.contacts.len();
        self.active = Vec::new();
        renew_for(&mut self.mu, n);
        renew_for(&mut self.shift, n);
        let closed = world.params.projection_tolerance.unwrap_or(0.0);
        let mut subset = false;
        for (a, &gap) in world.contacts.gaps.iter().enumerate() {
            let un = self.op.local_velocity_at(a, &world.bodies)[0];
            // A contact whose groups no longer interact (a changed scene) is left out.
            let law = world.contact_law(self.op.rows[a].bodies);
            let Some((law, shift)) = law.and_then(|InteractionLaw::SignoriniCoulomb(law)| {
                let g_tt = predicted_gap(detection, gap, un, h, theta);
                let shift = normal_shift(g_tt, un, h, law.restitution, closed)?;
                Some((law, shift))
            }) else {
                if !subset {
                    // The first contact left out: the active ones so far are all before it.
                    subset = true;
                    renew_for(&mut self.active, n - 1);
                    self.active.extend(0..a as u32);
                }
                continue;
            };
            if subset {
                self.active.push(a as u32);
            }
            self.mu.push(law.friction);
            self.shift.push(shift);
        }
        // Rows and warm start of the active contacts: the contacts' own when all are active
        // (no copy).
        self.active_is_subset = subset;
        self.all_rows = Vec::new();
        if self.active_is_subset {
            std::mem::swap(&mut self.op.rows, &mut self.all_rows);
            let all = &self.all_rows;
            renew(
                &mut self.op.rows,
                self.active.iter().map(|&a| all[a as usize]),
            );
            let impulses = &world.contacts.impulses;
            renew(
                &mut self.impulses,
                self.active.iter().map(|&a| impulses[a as usize]),
            );
        } else {
            self.impulses = std::mem::take(&mut world.contacts.impulses);
        }
        self.select_spans();
        report.active = self.impulses.len();
    }

    /// Stage solve: the velocity problem by the world's [`VelocitySolver`]; on return the
    /// operator's velocities are those of the impulses found.
    fn solve(
        &mut self,
        world: &World,
        report: &mut StepReport,
        shared: Option<&mut dyn ContactSolve<RigidContactOperator>>,
    ) -> Result<(), StepError> {
        let assembled = match world.params.solver {
            VelocitySolver::Assembled(params) => Some(params),
            VelocitySolver::Nlgs => None,
        };
        let problem = if self.capture || assembled.is_some() {
            let p = assemble_problem(&self.op, &self.mu, &self.shift).map_err(problem_error)?;
            if std::mem::take(&mut self.capture) {
                self.captured = Some(p.clone());
            }
            Some(p)
        } else {
            None
        };
        let (Some(params), Some(problem)) = (assembled, problem) else {
            let (op, mu, shift) = (&mut self.op, &self.mu, &self.shift);
            let info = match shared {
                Some(s) => s.solve(op, mu, shift, &[], &mut self.impulses, &world.params.nlgs),
                None => nlgs(op, mu, shift, &mut self.impulses, &world.params.nlgs),
            }
            .map_err(StepError::Solver)?;
            report.iterations = info.iterations;
            report.residual = info.residual;
            report.converged = info.converged;
            report.norms = info.norms;
            return Ok(());
        };
        if self.impulses.is_empty() {
            report.converged = true;
            return Ok(());
        }
        let warm: Vec<Real> = self.impulses.iter().flatten().copied().collect();
        let solved = solve(&problem, &params, Some(&warm)).map_err(StepError::Solver)?;
        for (a, r) in self.impulses.iter_mut().enumerate() {
            *r = std::array::from_fn(|k| solved.r[DIM * a + k]);
            self.op.apply_impulse(a, *r);
        }
        report.iterations = solved.iterations;
        report.residual = params.scaling.pick(&solved.error);
        report.converged = solved.converged;
        Ok(())
    }

    /// `v_free = v_i + h M^-1 F_theta`; imposed velocities take their value at `t_end`.
    fn free_velocity(&mut self, world: &World, t_begin: Real, t_end: Real) {
        let (h, theta, g) = (self.h, world.params.theta, world.params.gravity);
        for (b, body) in self.op.bodies.iter_mut().enumerate() {
            if world.bodies.is_dynamic(b) {
                body.add_gravity(h, &g);
            }
        }
        for (body, force) in self.op.bodies.iter_mut().zip(&self.external_forces) {
            body.add_force(h, force);
        }
        for (handle, drives) in &world.bodies.driven {
            let b = handle.index();
            for (d, drive) in drives.iter().enumerate() {
                match drive {
                    xper_bodies::Drive::Free => {}
                    xper_bodies::Drive::Velocity(f) => {
                        self.op.bodies[b].velocity[d] = f.eval(t_end)
                    }
                    xper_bodies::Drive::Force(_) | xper_bodies::Drive::Pressure(_) => {
                        let force = imposed_force(drive, world, theta, t_begin, t_end);
                        self.op.bodies[b].add_dof_force(d, h, force);
                    }
                }
            }
        }
    }

    /// Work of imposed forces, and of imposed velocities on finite-mass bodies (the change of
    /// kinetic energy they cause beyond gravity), over the step.
    fn driven_work(&self, world: &World, t_begin: Real, t_end: Real) -> Real {
        let (h, theta, g) = (self.h, world.params.theta, world.params.gravity);
        let mut work = 0.0;
        let owned = |b: usize| world.bodies.ownership[b] == Ownership::Owned;
        for (handle, drives) in &world.bodies.driven {
            let b = handle.index();
            if !owned(b) {
                continue;
            }
            let (v0, v1) = (
                world.bodies.generalized_velocity(b),
                self.op.bodies[b].velocity,
            );
            for (d, drive) in drives.iter().enumerate() {
                match drive {
                    xper_bodies::Drive::Free => {}
                    xper_bodies::Drive::Force(_) | xper_bodies::Drive::Pressure(_) => {
                        let mean = (v0[d] + v1[d]) / 2.0;
                        work += h * imposed_force(drive, world, theta, t_begin, t_end) * mean;
                    }
                    xper_bodies::Drive::Velocity(_) => {
                        work += imposed_velocity_work(&world.bodies, b, d, [&v0, &v1], h, &g);
                    }
                }
            }
        }
        for (b, force) in self.external_forces.iter().enumerate() {
            if !owned(b) {
                continue;
            }
            let (v0, v1) = (
                world.bodies.generalized_velocity(b),
                self.op.bodies[b].velocity,
            );
            for d in 0..DOFS {
                if self.op.bodies[b].is_free(d) {
                    work += h * force[d] * (v0[d] + v1[d]) / 2.0;
                }
            }
        }
        work
    }

    /// `q_i+1 = q_i + h ((1 - theta) v_i + theta v_i+1)` and `v_i+1` (in 3D with the
    /// rotation update of the gyroscopic term, see `body3d.rs`).
    fn update(&mut self, world: &mut World) -> Result<(), StepError> {
        let (h, theta) = (self.h, world.params.theta);
        let bodies = &mut world.bodies;
        for b in 0..bodies.len() {
            let v1 = self.op.bodies[b].velocity;
            advance(bodies, b, v1, h, theta);
            if !(v1.iter().all(|x| x.is_finite())
                && bodies.position[b].iter().all(|x| x.is_finite()))
            {
                return Err(StepError::NonFinite { body: b });
            }
        }
        Ok(())
    }
}

/// The force of a force or pressure drive over a step, `(1 - theta) F(t_begin) + theta F(t_end)`;
/// a pressure's extent is measured on the positions at the beginning of the step.
fn imposed_force(
    drive: &xper_bodies::Drive,
    world: &World,
    theta: Real,
    t_begin: Real,
    t_end: Real,
) -> Real {
    let mean =
        |f: &xper_bodies::TimeFunction| (1.0 - theta) * f.eval(t_begin) + theta * f.eval(t_end);
    match drive {
        xper_bodies::Drive::Force(f) => mean(f),
        xper_bodies::Drive::Pressure(p) => p.force(mean(&p.pressure), &world.bodies.position),
        xper_bodies::Drive::Free | xper_bodies::Drive::Velocity(_) => 0.0,
    }
}
