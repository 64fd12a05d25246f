//! A rigid-body run over several processes: [`DistributedStepper`].
//!
//! Each step is a sequence of named stages, every one collective:
//!
//! ```text
//! 1. partition: every `rebalance_every` steps space is cut again by recursive coordinate
//!    bisection (equal work: a movable body weighs 1 and each contact it owns
//!    `contact_weight` more; cuts along gravity preferred, `partition::across_gravity`), found
//!    by reductions over the owned bodies' positions without
//!    gathering them, and the bodies in another region go to its owner;
//!    in between, a body whose centre left its owner's region migrates to the region's owner.
//!    Contacts follow the body that owns them, carrying their impulses (the warm start);
//! 2. shadows: each owner sends the state of its bodies to every process whose region lies
//!    within the halo `2 r_max + alert` (a contact partner of one of that process's bodies
//!    cannot be farther; with detection on the predicted configuration, plus twice the
//!    largest displacement to it);
//!
//! Between re-partitions every message of stages 1 to 3 goes to the partition's neighbours only
//! (the regions within the halo of this one, [`Bisection::neighbours`]): a body migrates to a
//! neighbour unless it crossed a whole region in one step, which stage 4 detects for the next
//! step's migration to fall back to an all-to-all. The number of messages per step and
//! process is then bounded by the number of neighbours, not of processes.
//! 3. local step: the process's bodies (owned, shadow copies, and the immovable ones that every
//!    process holds) in increasing global id, so that contacts are detected with the same body
//!    order, normal and feature as in a serial run (the set is kept between steps and only its
//!    states refreshed while it holds the same bodies: `local_bodies`);
//!    `MoreauJean::step_with` keeps the contacts this process owns and solves them with the
//!    others' ([`SharedNlgs`]);
//! 4. totals: contacts, energies and the budget check are summed over processes.
//! ```
//!
//! The bodies' descriptions (shape, masses, group, drives) are held by every process; their
//! state is authoritative only at the owner. [`DistributedStepper::gather`] rebuilds the whole
//! world on rank 0 for outputs and checkpoints, which are therefore those of a serial run, and a
//! checkpoint written with any number of processes resumes with any other.

use crate::comm::{exchange_by_rank, Communicator};
use crate::partition::{across_gravity, in_box, Bisection};
use crate::rigid::local_bodies;
use crate::rigid::message::{read_contact, set_state, write_contact, write_state, CONTACT, STATE};
use crate::rigid::shared_solve::SharedNlgs;
use xper_bodies::{BodySet, Ownership};
use xper_geometry::{Contact, ContactSet};
use xper_math::{Real, Vector};
use xper_nscd::{
    contact_owner_body, Detection, EnergyBudget, MoreauJean, StepError, StepReport, World,
};
pub use xper_parallel::RankLoad;

/// Tuning of a distributed run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistributedParams {
    /// Steps between re-partitions of space (bodies migrate at every step in between).
    pub rebalance_every: u64,
    /// The work of a contact over a step in units of a body's (detection, integration,
    /// messages): each contact a body owns adds this to the body's weight of 1 in the
    /// partition. A contact costs its updates (tens to hundreds of sweeps of 12 to 50 ns on
    /// box10k and box3d10k) where a body costs a few hundred ns, hence 10 by default; an
    /// integer, so that the weights sum exactly in any order and the cuts do not depend on
    /// how bodies are spread over processes. 0 balances the numbers of bodies.
    pub contact_weight: u32,
}

impl Default for DistributedParams {
    fn default() -> Self {
        DistributedParams {
            rebalance_every: 50,
            contact_weight: 10,
        }
    }
}

/// A rigid-body world stepped by `comm.size()` processes (see the module documentation).
pub struct DistributedStepper<'c, C: Communicator + ?Sized> {
    comm: &'c C,
    params: DistributedParams,
    /// Every body's description; states are current for the bodies held here.
    all: World,
    movable: Vec<bool>,
    immovable: Vec<u32>,
    driven_of: Vec<u32>,
    owned: Vec<u32>,
    carried: Vec<Contact>,
    partition: Bisection,
    /// This process's region of the partition, `[lo, hi)`.
    region: (Vector, Vector),
    partitioned_at: u64,
    halo: Real,
    /// The halo of this step's shadows and neighbours: `halo`, widened by the bodies' motion to
    /// the configuration contacts are detected on ([`Self::widen_halo`]).
    step_halo: Real,
    /// The ranks whose regions lie within `step_halo` of this one (symmetric).
    neighbours: Vec<usize>,
    /// Whether a body owned somewhere is now in a region that is not its owner's neighbour
    /// (found by stage 4): the next migration then goes to every process.
    far_migration: bool,
    local: World,
    /// The bodies of `local`: `(global id, ownership)` in increasing id.
    held: Vec<(u32, Ownership)>,
    local_of: Vec<u32>,
    stepper: MoreauJean,
    load: RankLoad,
}

impl<'c, C: Communicator + ?Sized> DistributedStepper<'c, C> {
    /// Distributes `world` (the same on every process: read from the scene or a checkpoint).
    pub fn new(comm: &'c C, world: World, params: DistributedParams) -> Self {
        let n = world.bodies.len();
        let movable: Vec<bool> = (0..n).map(|b| world.bodies.is_movable(b)).collect();
        let mut driven_of = vec![u32::MAX; n];
        for (k, (handle, _)) in world.bodies.driven.iter().enumerate() {
            driven_of[handle.index()] = k as u32;
        }
        let r_max = (0..n)
            .filter(|&b| movable[b])
            .map(|b| world.bodies.shape[b].size())
            .fold(0.0, Real::max);
        let halo = 2.0 * r_max + world.params.alert_distance;
        let mut local = world.clone();
        local.bodies = BodySet::new();
        local.contacts.clear();
        let mut me = DistributedStepper {
            comm,
            params,
            immovable: (0..n as u32).filter(|&b| !movable[b as usize]).collect(),
            movable,
            driven_of,
            owned: Vec::new(),
            carried: world.contacts.iter().collect(),
            partition: Bisection::new(&[], 1),
            region: (Vector::zeros(), Vector::zeros()),
            partitioned_at: world.step,
            halo,
            step_halo: halo,
            neighbours: Vec::new(),
            far_migration: false,
            local_of: vec![u32::MAX; n],
            all: world,
            local,
            held: Vec::new(),
            stepper: MoreauJean::new(),
            load: RankLoad::default(),
        };
        me.partition_space(false);
        me
    }

    /// The run's time, step and global energy budget (bodies current only where held).
    pub fn world(&self) -> &World {
        &self.all
    }

    /// This process's load.
    pub fn load(&self) -> RankLoad {
        self.load
    }

    /// One step of the whole world; the report holds the totals over processes (contacts,
    /// energies) and the shared solver's figures.
    pub fn step(&mut self) -> Result<StepReport, StepError> {
        let start = std::time::Instant::now();
        let step = self.all.step;
        if step.is_multiple_of(self.params.rebalance_every.max(1)) && step != self.partitioned_at {
            self.partition_space(true);
        } else {
            self.migrate(!self.far_migration);
        }
        self.widen_halo();
        let shadows = self.exchange_shadows();
        self.build_local(&shadows);
        let mut solver = SharedNlgs::new(self.comm);
        solver.ids = self.local.bodies.id.clone();
        solver.neighbours = Some(self.neighbours.clone());
        let me = self.comm.rank() as u32;
        solver.owners = (self.local.bodies.ownership.iter())
            .map(|o| match o {
                Ownership::Owned => me,
                Ownership::Shadow { owner } => *owner,
            })
            .collect();
        solver.movable = (self.local.bodies.id.iter())
            .map(|&g| self.movable[g as usize])
            .collect();
        self.local.energy = EnergyBudget {
            scale: Real::INFINITY,
            ..Default::default()
        };
        let stepped = self.stepper.step_with(&mut self.local, &mut solver);
        if stepped.is_err() {
            // The contacts as they were, so that a gather still finds them.
            self.carry_local_contacts();
        }
        let mut report = stepped?;
        self.load.interface_bodies = solver.shared_bodies;
        self.load.contacts = self.local.contacts.len();
        self.store_local();
        self.totals(&mut report)?;
        report.times.total = start.elapsed().as_secs_f64();
        Ok(report)
    }

    /// Stage 1 at a re-partition: space cut again from the owned bodies' positions by
    /// reductions only ([`Bisection::distributed`]), the bodies that fall in another region
    /// sent to its owner with the contacts they own (to any process). At the start (`spread`
    /// false) every process has the whole world and keeps the bodies of its region.
    fn partition_space(&mut self, spread: bool) {
        let me = self.comm.rank() as u32;
        let bodies = &self.all.bodies;
        // The cuts depend on the points alone, not on which process holds them: at the start
        // rank 0 offers them all, so a run resumed from a checkpoint is cut as the
        // uninterrupted run was at that step.
        let offered: Vec<u32> = if spread {
            self.owned.clone()
        } else if me == 0 {
            (0..self.movable.len() as u32)
                .filter(|&b| self.movable[b as usize])
                .collect()
        } else {
            Vec::new()
        };
        // The contacts held here are those the offered bodies own (at the start, every
        // process holds all of them and rank 0 offers every body).
        let mut owned_contacts = vec![0u32; self.movable.len()];
        for c in &self.carried {
            let [i, j] = c.row.bodies;
            owned_contacts[contact_owner_body(bodies, i as _, j as _)] += 1;
        }
        let weight = Real::from(self.params.contact_weight);
        let points: Vec<Vector> = offered
            .iter()
            .map(|&b| bodies.position[b as usize])
            .collect();
        let weights: Vec<Real> = (offered.iter())
            .map(|&b| 1.0 + weight * Real::from(owned_contacts[b as usize]))
            .collect();
        let parts = self.comm.size();
        let stretch = across_gravity(&self.all.params.gravity);
        self.partition = Bisection::distributed(self.comm, &points, &weights, &stretch, parts);
        self.partitioned_at = self.all.step;
        self.region = self.partition.regions()[me as usize];
        self.neighbours = neighbours_within(&self.partition, me, self.step_halo);
        if spread {
            self.migrate(false);
            return;
        }
        let partition = &self.partition;
        self.owned = (0..self.movable.len() as u32)
            .filter(|&b| self.movable[b as usize])
            .filter(|&b| partition.part_of(&bodies.position[b as usize]) == me)
            .collect();
        let mut owned = vec![false; self.movable.len()];
        for &b in &self.owned {
            owned[b as usize] = true;
        }
        self.carried.retain(|c| {
            owned[contact_owner_body(bodies, c.row.bodies[0] as _, c.row.bodies[1] as _)]
        });
    }

    /// Stage 1: bodies whose centre left this region go to its owner, with the contacts they
    /// own; to the neighbours only when `near` (no body crossed a whole region), else to every
    /// process.
    fn migrate(&mut self, near: bool) {
        let (me, size) = (self.comm.rank() as u32, self.comm.size());
        let mut leaving = vec![Vec::new(); size];
        let partition = &self.partition;
        let bodies = &self.all.bodies;
        let region = self.region;
        self.owned.retain(|&b| {
            let x = &bodies.position[b as usize];
            let p = if in_box(x, &region, 0.0) {
                me
            } else {
                partition.part_of(x)
            };
            if p != me {
                leaving[p as usize].push(b);
            }
            p == me
        });
        let sends: Vec<Vec<f64>> = leaving.iter().map(|ids| self.states_of(ids)).collect();
        let among = near.then_some(self.neighbours.as_slice());
        for message in exchange_by_rank(self.comm, sends, among) {
            let arrived = self.read_states(&message);
            self.load.migrated_in += arrived.len() as u64;
            self.owned.extend(arrived);
        }
        self.owned.sort_unstable();
        let carried = std::mem::take(&mut self.carried);
        self.send_contacts(carried, near);
    }

    /// Sends each contact to the process owning its owner body (by the current partition),
    /// to the neighbours only when `near` (no body went farther); keeps those of this process.
    fn send_contacts(&mut self, contacts: Vec<Contact>, near: bool) {
        let mut sends = vec![Vec::new(); self.comm.size()];
        for c in &contacts {
            let [i, j] = c.row.bodies;
            let b = contact_owner_body(&self.all.bodies, i as _, j as _);
            let p = self.partition.part_of(&self.all.bodies.position[b]);
            write_contact(&mut sends[p as usize], c);
        }
        let among = near.then_some(self.neighbours.as_slice());
        self.carried = exchange_by_rank(self.comm, sends, among)
            .iter()
            .flat_map(|m| m.chunks_exact(CONTACT).map(read_contact))
            .collect();
    }

    /// Stage 2, first: with contacts detected on the predicted configuration `q + h (1 - theta)
    /// v` ([`Detection::Predicted`]), two bodies whose centres are `2 r_max + alert` apart may
    /// come within the alert distance there: the halo grows by twice the largest displacement
    /// `h (1 - theta) max |v|` over all processes (the same on every process, so the
    /// neighbours stay symmetric), and the neighbours are found again when it changed.
    fn widen_halo(&mut self) {
        let p = &self.all.params;
        if p.detection == Detection::Begin {
            return;
        }
        let bodies = &self.all.bodies;
        let fastest = (self.owned.iter())
            .map(|&b| bodies.velocity[b as usize].norm())
            .fold(0.0, Real::max);
        let mut largest = [fastest];
        self.comm.all_reduce_max(&mut largest);
        let halo = self.halo + 2.0 * p.dt * (1.0 - p.theta) * largest[0];
        if halo != self.step_halo {
            self.step_halo = halo;
            self.neighbours = neighbours_within(&self.partition, self.comm.rank() as u32, halo);
        }
    }

    /// Stage 2: the states of the bodies of other processes within the halo of this region,
    /// with their owners.
    fn exchange_shadows(&mut self) -> Vec<(u32, u32)> {
        let (me, size) = (self.comm.rank(), self.comm.size());
        let mut sends = vec![Vec::new(); size];
        let mut near = Vec::new();
        // A body farther than the halo from every side of this region has no other process
        // near (the regions tile space): most bodies, found without walking the tree.
        for &b in &self.owned {
            let x = self.all.bodies.position[b as usize];
            if in_box(&x, &self.region, self.step_halo) {
                continue;
            }
            self.partition.parts_near(&x, self.step_halo, &mut near);
            for &p in near.iter().filter(|&&p| p as usize != me) {
                write_state(&mut sends[p as usize], &self.all.bodies, b);
            }
        }
        let received = exchange_by_rank(self.comm, sends, Some(&self.neighbours));
        let mut shadows = Vec::new();
        for (rank, message) in received.iter().enumerate() {
            for b in self.read_states(message) {
                shadows.push((b, rank as u32));
            }
        }
        shadows.sort_unstable();
        self.load.shadows = shadows.len();
        self.load.bodies = self.owned.len();
        shadows
    }

    /// Stage 3's world: immovable, owned and shadow bodies (`shadows` in increasing id) in
    /// increasing global id, and the carried contacts in local indices.
    fn build_local(&mut self, shadows: &[(u32, u32)]) {
        let wall_owner = if self.comm.rank() == 0 {
            Ownership::Owned
        } else {
            Ownership::Shadow { owner: 0 }
        };
        local_bodies::merge_held(
            &self.immovable,
            wall_owner,
            &self.owned,
            shadows,
            &mut self.held,
        );
        local_bodies::refresh(
            &self.all.bodies,
            &self.held,
            &self.driven_of,
            &mut self.local.bodies,
            &mut self.local_of,
        );
        let local_of = &self.local_of;
        // The carried contacts live in the local world during the step, in ascending order of
        // bodies as a detection expects them (those received from other processes come
        // rank by rank).
        let mut carried = std::mem::take(&mut self.carried);
        carried.retain_mut(|c| {
            c.row.bodies = c.row.bodies.map(|b| local_of[b as usize]);
            !c.row.bodies.contains(&u32::MAX)
        });
        carried.sort_by_key(|c| (c.row.bodies, c.key.feature));
        self.local.contacts = carried.into_iter().collect();
        self.local.step = self.all.step;
        self.local.time = self.all.time;
        self.local.params.dt = self.all.params.dt;
    }

    /// After the local step: the owned and immovable bodies' states, the owned contacts.
    fn store_local(&mut self) {
        let (local, all) = (&self.local.bodies, &mut self.all.bodies);
        for (k, &g) in local.id.iter().enumerate() {
            let b = g as usize;
            if local.ownership[k] == Ownership::Owned || !self.movable[b] {
                all.position[b] = local.position[k];
                all.rotation[b] = local.rotation[k];
                all.velocity[b] = local.velocity[k];
                all.angular_velocity[b] = local.angular_velocity[k];
            }
        }
        self.carry_local_contacts();
        self.all.step = self.local.step;
        self.all.time = self.local.time;
    }

    /// The local world's contacts into the carried ones, in global body ids; the local world
    /// holds none until the next step loads them back.
    fn carry_local_contacts(&mut self) {
        let id = &self.local.bodies.id;
        self.carried = (self.local.contacts.iter())
            .map(|mut c| {
                c.row.bodies = c.row.bodies.map(|b| id[b as usize] as u32);
                c
            })
            .collect();
        self.local.contacts = ContactSet::default();
    }

    /// Stage 4: totals over processes into `report` and the global energy budget, with the
    /// serial run's blow-up check; whether any body left for a region that is not a neighbour
    /// of its owner's.
    fn totals(&mut self, report: &mut StepReport) -> Result<(), StepError> {
        let me = self.comm.rank() as u32;
        let far = self.owned.iter().any(|&b| {
            let x = &self.all.bodies.position[b as usize];
            if in_box(x, &self.region, 0.0) {
                return false;
            }
            let p = self.partition.part_of(x);
            p != me && !self.neighbours.contains(&(p as usize))
        });
        let e = self.local.energy;
        let mut sums = [
            report.contacts as f64,
            report.active as f64,
            e.dissipated,
            e.external_work,
            e.projection_work,
            report.kinetic,
            report.potential,
        ];
        self.comm.all_reduce_sum(&mut sums);
        let mut maxima = [report.max_overlap, if far { 1.0 } else { 0.0 }];
        self.comm.all_reduce_max(&mut maxima);
        self.far_migration = maxima[1] > 0.0;
        let budget = &mut self.all.energy;
        budget.dissipated += sums[2];
        budget.external_work += sums[3];
        budget.projection_work += sums[4];
        report.contacts = sums[0] as usize;
        report.active = sums[1] as usize;
        report.max_overlap = maxima[0];
        report.kinetic = sums[5];
        report.potential = sums[6];
        report.dissipated = budget.dissipated;
        report.external_work = budget.external_work;
        report.projection_work = budget.projection_work;
        report.energy_error = report.kinetic + report.potential + budget.dissipated
            - budget.external_work
            - budget.projection_work
            - budget.initial;
        budget.scale = budget
            .scale
            .max((report.kinetic + report.potential - budget.initial).abs())
            .max(budget.external_work.abs());
        let scale = budget.scale + budget.dissipated + report.kinetic.min(budget.initial.abs());
        if xper_nscd::energy_blown_up(report.energy_error, scale) {
            return Err(StepError::EnergyBlowUp {
                error: report.energy_error,
                scale,
            });
        }
        Ok(())
    }

    /// The whole world on rank 0 (bodies, contacts in a canonical order, budget), `None`
    /// elsewhere; collective.
    pub fn gather(&self) -> Option<World> {
        let mut message = self.states_of(&self.owned);
        message.push(f64::NAN);
        for c in &self.carried {
            write_contact(&mut message, c);
        }
        let mut sends = vec![Vec::new(); self.comm.size()];
        sends[0] = message;
        let received = self.comm.all_to_all(&sends);
        if self.comm.rank() != 0 {
            return None;
        }
        let mut world = self.all.clone();
        let mut contacts = Vec::new();
        for m in &received {
            let split = m.iter().position(|x| x.is_nan()).unwrap_or(m.len());
            for s in m[..split].chunks_exact(STATE) {
                set_state(&mut world.bodies, s);
            }
            contacts.extend(
                m[(split + 1).min(m.len())..]
                    .chunks_exact(CONTACT)
                    .map(read_contact),
            );
        }
        contacts.sort_by_key(|c: &Contact| (c.row.bodies, c.key.feature));
        world.contacts = contacts.into_iter().collect();
        Some(world)
    }

    fn states_of(&self, ids: &[u32]) -> Vec<f64> {
        let mut out = Vec::with_capacity(ids.len() * STATE);
        for &b in ids {
            write_state(&mut out, &self.all.bodies, b);
        }
        out
    }

    /// Writes the states of `message` into the catalogue; returns their bodies.
    fn read_states(&mut self, message: &[f64]) -> Vec<u32> {
        (message.chunks_exact(STATE))
            .map(|s| set_state(&mut self.all.bodies, s))
            .collect()
    }
}

/// The ranks whose regions lie within `halo` of rank `me`'s region.
fn neighbours_within(partition: &Bisection, me: u32, halo: Real) -> Vec<usize> {
    (partition.neighbours(me, halo).into_iter())
        .map(|q| q as usize)
        .collect()
}
