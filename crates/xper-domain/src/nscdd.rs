//! Non-smooth contact domain decomposition (NSCDD): Gauss-Seidel inside each process, the
//! interface bodies glued by averaging after every sweep.
//!
//! Each process owns a subset of the contacts and holds copies of their bodies, the shared
//! ones with split masses ([`InterfaceMap::split_masses`]). One iteration is
//!
//! ```text
//! 1. a Gauss-Seidel sweep over the local contacts (xper_solver::NlgsSweeper), updating the
//!    local copies of the bodies;
//! 2. for every shared body, v <- (1/m) sum over its m copies of v_copy (an exchange with the
//!    neighbour processes only);
//! ```
//!
//! so after step 2 each copy holds `v_free + M^-1 sum_a H_a R_a` over all contacts of all
//! processes: the fixed point is the solution of the undivided problem. Every `check_every`
//! sweeps the natural-map error of all contacts, scaled as in the serial solver by
//! `max(|q|, |U|, |R|)`, is summed over processes (all-reduce) and compared with the tolerance.
//! Visseq et al., Comput. Mech. 49 (2012) 709; Renouf, Dubois and Alart, J. Comput. Appl.
//! Math. 168 (2004) 375.

use crate::communicator::Communicator;
use crate::interface::InterfaceMap;
use xper_nscd::RigidContactOperator;
use xper_solver::{natural_map_error, ContactOperator, NlgsParams, NlgsSweeper, SolveError};

/// Outcome of a distributed solve (identical on every rank).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DistributedSolveInfo {
    /// Sweeps performed (each followed by an interface exchange).
    pub iterations: u32,
    /// Scaled natural-map error of all contacts at the last check.
    pub residual: f64,
    /// Whether it went below the tolerance.
    pub converged: bool,
}

/// Solves the contacts of `op` (this process's rows, its bodies with split masses at their
/// free velocities, zero impulses applied) together with those of the other processes.
/// `impulses` holds the warm start on entry and the solution on exit. `params.tolerance` bounds
/// the scaled natural-map error (the `norm` field is not used: LMGC90's norms are per-process
/// sums of updates that the averaging step changes).
pub fn distributed_nlgs<C: Communicator + ?Sized>(
    comm: &C,
    op: &mut RigidContactOperator,
    interface: &InterfaceMap,
    mu: &[f64],
    normal_shift: &[f64],
    impulses: &mut [[f64; 2]],
    params: &NlgsParams,
) -> Result<DistributedSolveInfo, SolveError> {
    if interface.multiplicity.len() != op.bodies.len() {
        return Err(SolveError::SizeMismatch {
            what: format!(
                "{} bodies, an interface of {}",
                op.bodies.len(),
                interface.multiplicity.len()
            ),
        });
    }
    let sweeper = NlgsSweeper::new(op, mu, normal_shift, &[], impulses, params)?;
    let mut q_norm2 = [sweeper.q_norm().powi(2)];
    comm.all_reduce_sum(&mut q_norm2);
    let q_norm = q_norm2[0].sqrt();
    glue(comm, op, interface);
    let mut info = DistributedSolveInfo::default();
    for sweep in 1..=params.max_iterations {
        sweeper.sweep(op, impulses);
        glue(comm, op, interface);
        if sweep % params.check_every == 0 || sweep == params.max_iterations {
            info.iterations = sweep;
            info.residual = global_error(comm, op, mu, normal_shift, impulses, q_norm);
            if !info.residual.is_finite() {
                return Ok(info);
            }
            if info.residual < params.tolerance {
                info.converged = true;
                return Ok(info);
            }
        }
    }
    Ok(info)
}

/// Step 2: the copies of every shared body take the average of their velocities, summed in
/// rank order so that every copy gets the same bits.
fn glue<C: Communicator + ?Sized>(
    comm: &C,
    op: &mut RigidContactOperator,
    interface: &InterfaceMap,
) {
    if interface.neighbours.is_empty() {
        return;
    }
    let sends: Vec<(usize, Vec<f64>)> = interface
        .neighbours
        .iter()
        .map(|(rank, list)| {
            let data = list
                .iter()
                .flat_map(|&b| op.bodies[b as usize].velocity)
                .collect();
            (*rank, data)
        })
        .collect();
    let sources: Vec<usize> = interface.neighbours.iter().map(|(r, _)| *r).collect();
    let received = comm.exchange(&sends, &sources);
    let me = comm.rank();
    let own: Vec<[f64; 3]> = op.bodies.iter().map(|b| b.velocity).collect();
    let mut sum: Vec<Option<[f64; 3]>> = vec![None; op.bodies.len()];
    let mut add = |b: usize, v: [f64; 3]| {
        let s = sum[b].get_or_insert([0.0; 3]);
        for d in 0..3 {
            s[d] += v[d];
        }
    };
    let mut own_added = false;
    for ((rank, list), data) in interface.neighbours.iter().zip(&received) {
        if *rank > me && !own_added {
            add_own(&mut add, interface, &own);
            own_added = true;
        }
        for (k, &b) in list.iter().enumerate() {
            add(b as usize, [data[3 * k], data[3 * k + 1], data[3 * k + 2]]);
        }
    }
    if !own_added {
        add_own(&mut add, interface, &own);
    }
    for (b, s) in sum.iter().enumerate() {
        if let Some(s) = s {
            let m = interface.multiplicity[b] as f64;
            op.bodies[b].velocity = [s[0] / m, s[1] / m, s[2] / m];
        }
    }
}

fn add_own(add: &mut impl FnMut(usize, [f64; 3]), interface: &InterfaceMap, own: &[[f64; 3]]) {
    for (b, &m) in interface.multiplicity.iter().enumerate() {
        if m > 1 {
            add(b, own[b]);
        }
    }
}

/// The scaled natural-map error of the contacts of all processes.
fn global_error<C: Communicator + ?Sized>(
    comm: &C,
    op: &RigidContactOperator,
    mu: &[f64],
    normal_shift: &[f64],
    impulses: &[[f64; 2]],
    q_norm: f64,
) -> f64 {
    let mut sums = [0.0; 3];
    for a in 0..op.contact_count() {
        let u = op.local_velocity(a);
        let u = [u[0] + normal_shift[a], u[1]];
        let r = impulses[a];
        sums[0] += natural_map_error(&[u], &[r], &mu[a..a + 1]).powi(2);
        sums[1] += u[0] * u[0] + u[1] * u[1];
        sums[2] += r[0] * r[0] + r[1] * r[1];
    }
    comm.all_reduce_sum(&mut sums);
    let scale = q_norm.max(sums[1].sqrt()).max(sums[2].sqrt());
    sums[0].sqrt() / if scale > 0.0 { scale } else { 1.0 }
}
