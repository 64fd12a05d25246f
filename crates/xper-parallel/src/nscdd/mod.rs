//! Non-smooth contact domain decomposition (NSCDD): Gauss-Seidel inside each process, the
//! interface bodies glued by averaging after every sweep.
//!
//! Each process owns a subset of the contacts and holds copies of their bodies, the shared
//! ones with their inverse masses multiplied by their number of copies
//! ([`InterfaceMap::multiplicity`]). One iteration is
//!
//! ```text
//! 1. a Gauss-Seidel sweep over the local contacts (xper_solver::NlgsSweeper), updating the
//!    local copies of the bodies;
//! 2. for every shared body, v <- (1/m) sum over its m copies of v_copy (an exchange with the
//!    neighbour processes only); global components every process holds (the free strain
//!    rates of a periodic cell, their mass split among all P processes) likewise take the
//!    average of their P copies (an all-gather).
//! ```
//!
//! The sweep visits the contacts touching a shared body first and sweeps the others while
//! step 2's messages travel (they touch no shared body), so the exchange's latency hides
//! behind the inner contacts' work.
//!
//! After step 2 each copy holds `v_free + M^-1 sum_a H_a R_a` over all contacts of all
//! processes: the fixed point is the solution of the undivided problem. Every `check_every`
//! sweeps convergence is judged on all contacts, as the serial solver judges it: LMGC90's
//! norms from the sums of the check sweep's updates (added over processes, maxima taken as
//! maxima), or the natural-map error scaled by `max(|q|, |U|, |R|)` (all-reduce). With Anderson
//! acceleration, every `period` sweeps each process mixes its own contacts' impulses with the
//! coefficients of the sums over all processes (one all-reduce of `2 depth + 1` numbers), then
//! the copies are glued again. On one process the iterates and the decision are those of
//! [`xper_solver::nlgs`], bit for bit.
//! Visseq et al., Comput. Mech. 49 (2012) 709; Renouf, Dubois and Alart, J. Comput. Appl.
//! Math. 168 (2004) 375.

pub mod interface;

use crate::comm::Communicator;
use crate::nscdd::interface::InterfaceMap;
use xper_solver::{
    dot, sweep_until_converged, BlockOf, CohesiveTerm, ContactFrame, ContactOperator, NlgsParams,
    NlgsSweeper, NormAccumulator, SolveError, SolveInfo, SweepExchange, VectorOf,
};

/// A contact operator whose bodies each carry a velocity of `DOFS` components: what the glue
/// of interface bodies averages. Rigid bodies (`vx, vy, w`) and element bodies (the six nodal
/// velocity components of a triangle) both are.
pub trait BodyVelocities: ContactOperator {
    /// Velocity components per body.
    const DOFS: usize;
    /// Number of bodies.
    fn body_count(&self) -> usize;
    /// Velocity of body `b`.
    fn body_velocity(&self, b: usize) -> &[f64];
    /// Velocity of body `b`, to overwrite.
    fn body_velocity_mut(&mut self, b: usize) -> &mut [f64];
    /// The two bodies of row `a`.
    fn row_bodies(&self, a: usize) -> [u32; 2];
    /// Reorders the rows: row `k` becomes the former row `order[k]` (a permutation).
    fn permute_rows(&mut self, order: &[u32]);
    /// The velocity components every process holds a copy of, whatever rows it owns (the
    /// free strain rates of a periodic cell, moved by the rows across the cell's sides): glued
    /// by averaging over all processes. None by default.
    fn global_velocity(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Overwrites the components of [`BodyVelocities::global_velocity`].
    fn set_global_velocity(&mut self, _velocity: &[f64]) {}
}

/// An operator whose bodies can carry a share of their mass, for the interface bodies of
/// [`solve_with_split_masses`]: inverse masses multiplied and put back, the Delassus blocks of
/// the rows they touch recomputed and put back.
pub trait SplitMasses: BodyVelocities {
    /// A body's inverse mass.
    type InverseMass: Copy;
    /// Inverse mass of body `b`.
    fn inverse_mass(&self, b: usize) -> Self::InverseMass;
    /// Sets the inverse mass of body `b`.
    fn set_inverse_mass(&mut self, b: usize, inverse_mass: Self::InverseMass);
    /// Multiplies the inverse mass of body `b` by `factor`.
    fn scale_inverse_mass(&mut self, b: usize, factor: f64);
    /// Sets the Delassus block of row `a`.
    fn set_block(&mut self, a: usize, block: BlockOf<Self>);
    /// Recomputes the Delassus block of row `a` from the current inverse masses.
    fn refresh_block(&mut self, a: usize);
    /// The inverse masses of the components of [`BodyVelocities::global_velocity`]
    /// (zeros, none by default).
    fn global_inverse_mass(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Sets the inverse masses of [`SplitMasses::global_inverse_mass`].
    fn set_global_inverse_mass(&mut self, _inverse_mass: &[f64]) {}
    /// Whether row `a` moves the global components.
    fn touches_global(&self, _a: usize) -> bool {
        false
    }
}

/// Solves the contacts of `op` (this process's rows, its bodies with split masses at their
/// free velocities, zero impulses applied) together with those of the other processes.
/// `cohesion` is empty or holds the adhesive term of each row, as for
/// [`xper_solver::nlgs_with_cohesion`]. `impulses` holds the warm start on entry and the
/// solution on exit. The outcome (sweeps, residual of `params.norm`, convergence, LMGC90
/// norms of all contacts) is the same on every rank.
///
/// A sweep visits the rows touching a shared body first, sends those bodies' velocities,
/// and sweeps the other rows while they travel (they touch no shared body, so the velocities
/// sent are the sweep's): the exchange's latency is hidden behind the inner rows' work. The
/// rows are reordered so for the solve and put back after it.
#[allow(clippy::too_many_arguments)]
pub fn distributed_nlgs<C: Communicator + ?Sized, O: BodyVelocities>(
    comm: &C,
    op: &mut O,
    interface: &InterfaceMap,
    mu: &[f64],
    normal_shift: &[f64],
    cohesion: &[CohesiveTerm],
    impulses: &mut [VectorOf<O>],
    params: &NlgsParams,
) -> Result<SolveInfo, SolveError> {
    if interface.multiplicity.len() != op.body_count() {
        return Err(SolveError::SizeMismatch {
            what: format!(
                "{} bodies, an interface of {}",
                op.body_count(),
                interface.multiplicity.len()
            ),
        });
    }
    let n = op.contact_count();
    xper_solver::check_contact_sizes(n, mu, normal_shift, cohesion, impulses)?;
    let on_interface = |a: usize| touches_shared(op, interface, a);
    let mut order: Vec<u32> = (0..n as u32)
        .filter(|&a| on_interface(a as usize))
        .collect();
    let interface_rows = order.len();
    order.extend((0..n as u32).filter(|&a| !on_interface(a as usize)));
    if order.iter().enumerate().all(|(k, &a)| k == a as usize) {
        let rows = RowData {
            mu,
            normal_shift,
            cohesion,
        };
        return solve_interface_first(comm, op, interface, rows, impulses, params, interface_rows);
    }
    let (mu_sorted, shift_sorted) = (permuted(mu, &order), permuted(normal_shift, &order));
    let cohesion_sorted = if cohesion.is_empty() {
        Vec::new()
    } else {
        permuted(cohesion, &order)
    };
    let mut sorted = permuted(impulses, &order);
    op.permute_rows(&order);
    let rows = RowData {
        mu: &mu_sorted,
        normal_shift: &shift_sorted,
        cohesion: &cohesion_sorted,
    };
    let info = solve_interface_first(
        comm,
        op,
        interface,
        rows,
        &mut sorted,
        params,
        interface_rows,
    );
    let mut inverse = vec![0u32; n];
    for (k, &a) in order.iter().enumerate() {
        inverse[a as usize] = k as u32;
        impulses[a as usize] = sorted[k];
    }
    op.permute_rows(&inverse);
    info.map_err(|e| match e {
        SolveError::InvalidData { contact, what } => SolveError::InvalidData {
            contact: order.get(contact).map_or(contact, |&a| a as usize),
            what,
        },
        other => other,
    })
}

/// Whether row `a` of `op` touches a body shared with other processes.
fn touches_shared<O: BodyVelocities>(op: &O, interface: &InterfaceMap, a: usize) -> bool {
    op.row_bodies(a).into_iter().any(|b| interface.is_shared(b))
}

/// `values` in the order `order` (entry `k` is `values[order[k]]`).
pub fn permuted<T: Copy>(values: &[T], order: &[u32]) -> Vec<T> {
    order.iter().map(|&a| values[a as usize]).collect()
}

/// The per-row data of a problem besides the operator.
#[derive(Clone, Copy)]
struct RowData<'a> {
    mu: &'a [f64],
    normal_shift: &'a [f64],
    cohesion: &'a [CohesiveTerm],
}

/// [`distributed_nlgs`] on rows whose first `interface_rows` are those touching a shared body.
fn solve_interface_first<C: Communicator + ?Sized, O: BodyVelocities>(
    comm: &C,
    op: &mut O,
    interface: &InterfaceMap,
    rows: RowData,
    impulses: &mut [VectorOf<O>],
    params: &NlgsParams,
    interface_rows: usize,
) -> Result<SolveInfo, SolveError> {
    let RowData {
        mu,
        normal_shift,
        cohesion,
    } = rows;
    let sweeper = NlgsSweeper::new(op, mu, normal_shift, cohesion, impulses, params)?;
    let mut totals = [sweeper.q_norm().powi(2), op.contact_count() as f64];
    comm.all_reduce_sum(&mut totals);
    let (q_norm, contacts) = (totals[0].sqrt(), totals[1]);
    let mut glue = Glue::new(interface, comm.rank(), O::DOFS);
    glue.apply(comm, op, interface);
    if contacts == 0.0 {
        return Ok(SolveInfo {
            converged: true,
            ..SolveInfo::default()
        });
    }
    let mut exchange = InterfaceExchange {
        comm,
        interface,
        glue,
        interface_rows,
        q_norm,
    };
    Ok(sweep_until_converged(
        &sweeper,
        op,
        impulses,
        params,
        &mut exchange,
    ))
}

/// The exchange of a sweep between processes: the rows touching shared bodies swept first,
/// the shared velocities glued while the inner rows are swept; norms and mixing sums reduced
/// over all processes.
struct InterfaceExchange<'a, C: ?Sized> {
    comm: &'a C,
    interface: &'a InterfaceMap,
    glue: Glue,
    /// The first rows, those touching a shared body.
    interface_rows: usize,
    /// `|q + shift|` over all processes.
    q_norm: f64,
}

impl<C: Communicator + ?Sized, O: BodyVelocities> SweepExchange<O> for InterfaceExchange<'_, C> {
    fn sweep(
        &mut self,
        sweeper: &NlgsSweeper<O::Frame>,
        op: &mut O,
        impulses: &mut [VectorOf<O>],
        mut acc: Option<&mut NormAccumulator>,
    ) {
        let n = impulses.len();
        let (edge, inner) = (0..self.interface_rows, self.interface_rows..n);
        sweeper.sweep_part_accumulating(op, impulses, edge, acc.as_deref_mut());
        self.glue
            .apply_overlapped(self.comm, op, self.interface, &mut |op: &mut O| {
                sweeper.sweep_part_accumulating(op, impulses, inner.clone(), acc.as_deref_mut())
            });
    }
    fn reduce_norms(&mut self, acc: &NormAccumulator) -> NormAccumulator {
        global_norms(self.comm, acc)
    }
    fn reduce_sums(&mut self, sums: &mut [f64]) {
        self.comm.all_reduce_sum(sums);
    }
    fn natural_map_error(
        &mut self,
        sweeper: &NlgsSweeper<O::Frame>,
        op: &O,
        impulses: &[VectorOf<O>],
    ) -> f64 {
        let (mu, shift) = (sweeper.mu(), sweeper.normal_shift());
        global_error(self.comm, op, mu, shift, impulses, self.q_norm)
    }
    /// The mixed impulses change the copies of shared bodies: glued again as after a sweep.
    fn after_mixing(&mut self, op: &mut O) {
        self.glue.apply(self.comm, op, self.interface);
    }
}

/// [`distributed_nlgs`] on `op` with the masses of its interface bodies split among their
/// copies ([`InterfaceMap::multiplicity`]): only those bodies' masses change, hence only the
/// blocks of their rows, which are saved, split, and put back after the solve (copied, not
/// recomputed, so they keep their bits).
#[allow(clippy::too_many_arguments)]
pub fn solve_with_split_masses<C: Communicator + ?Sized, O: SplitMasses>(
    comm: &C,
    op: &mut O,
    interface: &InterfaceMap,
    mu: &[f64],
    normal_shift: &[f64],
    cohesion: &[CohesiveTerm],
    impulses: &mut [VectorOf<O>],
    params: &NlgsParams,
) -> Result<SolveInfo, SolveError> {
    let multiplicity = &interface.multiplicity;
    let bodies: Vec<usize> = (0..op.body_count())
        .filter(|&b| interface.is_shared(b as u32))
        .collect();
    let global = op.global_inverse_mass();
    let split_global = comm.size() > 1 && global.iter().any(|&w| w != 0.0);
    let rows: Vec<usize> = (0..op.contact_count())
        .filter(|&a| touches_shared(op, interface, a) || (split_global && op.touches_global(a)))
        .collect();
    let masses: Vec<_> = bodies.iter().map(|&b| op.inverse_mass(b)).collect();
    let blocks: Vec<_> = rows.iter().map(|&a| op.diagonal_block(a)).collect();
    for &b in &bodies {
        op.scale_inverse_mass(b, f64::from(multiplicity[b]));
    }
    if split_global {
        let processes = comm.size() as f64;
        op.set_global_inverse_mass(&global.iter().map(|w| w * processes).collect::<Vec<_>>());
    }
    for &a in &rows {
        op.refresh_block(a);
    }
    let info = distributed_nlgs(
        comm,
        op,
        interface,
        mu,
        normal_shift,
        cohesion,
        impulses,
        params,
    );
    for (&b, m) in bodies.iter().zip(masses) {
        op.set_inverse_mass(b, m);
    }
    op.set_global_inverse_mass(&global);
    for (&a, block) in rows.iter().zip(blocks) {
        op.set_block(a, block);
    }
    info
}

/// The accumulator of the check sweep over all processes (one gather: sums added and maxima
/// taken in rank order).
fn global_norms<C: Communicator + ?Sized>(comm: &C, acc: &NormAccumulator) -> NormAccumulator {
    if comm.size() == 1 {
        return *acc;
    }
    let (sums, maxima) = acc.to_sums();
    let mine: Vec<f64> = sums.iter().chain(&maxima).copied().collect();
    let (mut sums, mut maxima) = ([0.0; 6], [0.0; 2]);
    for theirs in comm.all_gather(&mine) {
        for k in 0..6 {
            sums[k] += theirs[k];
        }
        for k in 0..2 {
            maxima[k] = f64::max(maxima[k], theirs[6 + k]);
        }
    }
    NormAccumulator::from_sums(sums, maxima)
}

/// Step 2, prepared once per solve: the copies of every shared body take the average of their
/// velocities, summed in rank order so that every copy gets the same bits.
struct Glue {
    /// Local indices of the shared bodies.
    shared: Vec<u32>,
    /// For each neighbour of the interface, the slots in `shared` of its list.
    slots: Vec<Vec<u32>>,
    /// Neighbours of lower rank than this process: this copy is added after them.
    below: usize,
    sources: Vec<usize>,
    /// `DOFS` components per shared body.
    sums: Vec<f64>,
}

impl Glue {
    fn new(interface: &InterfaceMap, rank: usize, dofs: usize) -> Self {
        let shared: Vec<u32> = (0..interface.multiplicity.len() as u32)
            .filter(|&b| interface.is_shared(b))
            .collect();
        let mut slot_of = vec![u32::MAX; interface.multiplicity.len()];
        for (slot, &b) in shared.iter().enumerate() {
            slot_of[b as usize] = slot as u32;
        }
        Glue {
            slots: interface
                .neighbours
                .iter()
                .map(|(_, list)| list.iter().map(|&b| slot_of[b as usize]).collect())
                .collect(),
            below: interface
                .neighbours
                .iter()
                .filter(|(r, _)| *r < rank)
                .count(),
            sources: interface.neighbours.iter().map(|(r, _)| *r).collect(),
            sums: vec![0.0; dofs * shared.len()],
            shared,
        }
    }

    fn apply<C: Communicator + ?Sized, O: BodyVelocities>(
        &mut self,
        comm: &C,
        op: &mut O,
        interface: &InterfaceMap,
    ) {
        self.apply_overlapped(comm, op, interface, &mut |_: &mut O| {});
    }

    /// [`Glue::apply`], running `work` on `op` between posting the sends and waiting for the
    /// neighbours' velocities; `work` must not change a shared body.
    fn apply_overlapped<C: Communicator + ?Sized, O: BodyVelocities>(
        &mut self,
        comm: &C,
        op: &mut O,
        interface: &InterfaceMap,
        work: &mut dyn FnMut(&mut O),
    ) {
        if self.shared.is_empty() {
            work(op);
        } else {
            self.average_shared(comm, op, interface, work);
        }
        average_global(comm, op);
    }

    /// The copies of the shared bodies averaged, `work` done while the messages travel.
    fn average_shared<C: Communicator + ?Sized, O: BodyVelocities>(
        &mut self,
        comm: &C,
        op: &mut O,
        interface: &InterfaceMap,
        work: &mut dyn FnMut(&mut O),
    ) {
        let dofs = O::DOFS;
        let sends: Vec<(usize, Vec<f64>)> = interface
            .neighbours
            .iter()
            .map(|(rank, list)| {
                let data = list
                    .iter()
                    .flat_map(|&b| op.body_velocity(b as usize).iter().copied())
                    .collect();
                (*rank, data)
            })
            .collect();
        let received = comm.exchange_overlapped(&sends, &self.sources, &mut || work(op));
        let Glue {
            shared,
            slots,
            below,
            sums,
            ..
        } = self;
        sums.fill(0.0);
        for (k, (slots, data)) in slots.iter().zip(&received).enumerate() {
            if k == *below {
                add_own(shared, sums, op);
            }
            for (&slot, v) in slots.iter().zip(data.chunks_exact(dofs)) {
                let sum = &mut sums[slot as usize * dofs..][..dofs];
                for d in 0..dofs {
                    sum[d] += v[d];
                }
            }
        }
        if *below == slots.len() {
            add_own(shared, sums, op);
        }
        for (&b, sum) in self.shared.iter().zip(self.sums.chunks_exact(dofs)) {
            let m = interface.multiplicity[b as usize] as f64;
            for (v, s) in op.body_velocity_mut(b as usize).iter_mut().zip(sum) {
                *v = s / m;
            }
        }
    }
}

/// The components every process holds ([`BodyVelocities::global_velocity`], with masses
/// split among all processes) take their average over all processes, summed in rank order.
/// Nothing on one process or without such components.
fn average_global<C: Communicator + ?Sized, O: BodyVelocities>(comm: &C, op: &mut O) {
    let mine = op.global_velocity();
    if comm.size() == 1 || mine.is_empty() {
        return;
    }
    let all = comm.all_gather(&mine);
    let processes = comm.size() as f64;
    let average: Vec<f64> = (0..mine.len())
        .map(|k| all.iter().map(|v| v[k]).sum::<f64>() / processes)
        .collect();
    op.set_global_velocity(&average);
}

/// Adds this process's copy of each shared body to its sum.
fn add_own<O: BodyVelocities>(shared: &[u32], sums: &mut [f64], op: &O) {
    for (&b, sum) in shared.iter().zip(sums.chunks_exact_mut(O::DOFS)) {
        for (s, v) in sum.iter_mut().zip(op.body_velocity(b as usize)) {
            *s += v;
        }
    }
}

/// The scaled natural-map error of the contacts of all processes.
fn global_error<C: Communicator + ?Sized, O: ContactOperator>(
    comm: &C,
    op: &O,
    mu: &[f64],
    normal_shift: &[f64],
    impulses: &[VectorOf<O>],
    q_norm: f64,
) -> f64 {
    let mut sums = [0.0; 3];
    for a in 0..op.contact_count() {
        let mut u = op.local_velocity(a);
        u[0] += normal_shift[a];
        let r = impulses[a];
        sums[0] += <O::Frame as ContactFrame>::natural_map_error2(u, r, mu[a]);
        sums[1] += dot(u.as_ref(), u.as_ref());
        sums[2] += dot(r.as_ref(), r.as_ref());
    }
    comm.all_reduce_sum(&mut sums);
    let scale = q_norm.max(sums[1].sqrt()).max(sums[2].sqrt());
    sums[0].sqrt() / if scale > 0.0 { scale } else { 1.0 }
}
