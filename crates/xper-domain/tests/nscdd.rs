//! The distributed contact solve against the undivided one on a disk deposit: the same
//! velocities within the solver tolerance on 1 to 4 ranks (threads), the interface built
//! collectively against a direct count, copies glued bit-identically, runs reproducible.

use xper_domain::fixtures::{
    deposit, serial_spread, serial_velocities, solver_params, SPREAD_MARGIN,
};
use xper_domain::{
    distributed_nlgs, run_on_threads, split_problem, Bisection, Communicator, InterfaceMap,
};
use xper_math::Real;
use xper_nscd::RigidProblem;

/// For each rank: (global id, velocity) of every local body, the solve's outcome, the number of
/// shared bodies.
type RankResult = (Vec<(u64, [Real; 3])>, xper_solver::SolveInfo, usize);

fn distributed(problem: &RigidProblem, owners: &[u32], ranks: usize, tol: Real) -> Vec<RankResult> {
    distributed_with(problem, owners, ranks, &solver_params(tol))
}

fn distributed_with(
    problem: &RigidProblem,
    owners: &[u32],
    ranks: usize,
    params: &xper_solver::NlgsParams,
) -> Vec<RankResult> {
    run_on_threads(ranks, |comm| {
        let local = split_problem(problem, owners, comm.rank() as u32);
        let interface = InterfaceMap::build(
            comm,
            &local.global_ids,
            &local.owners,
            &local.shared(),
            None,
        );
        let mut op = local.operator(&interface);
        let mut impulses = local.problem.impulses.clone();
        let info = distributed_nlgs(
            comm,
            &mut op,
            &interface,
            &local.problem.mu,
            &local.problem.shift,
            &[],
            &mut impulses,
            params,
        )
        .unwrap();
        let velocities = local
            .global_ids
            .iter()
            .zip(&op.bodies)
            .map(|(&id, b)| (id, b.velocity))
            .collect();
        (velocities, info, interface.shared_count())
    })
}

#[test]
fn distributed_solve_matches_the_undivided_one_on_1_to_4_ranks() {
    let (world, problem) = deposit();
    assert!(problem.rows.len() > 300, "{} contacts", problem.rows.len());
    let tolerance = 1e-7;
    let serial = serial_velocities(&problem, tolerance);
    // The spread of the solver itself: the same problem with the contacts swept in reverse.
    let spread = serial_spread(&problem, tolerance, &serial);
    let scale = serial
        .iter()
        .flat_map(|v| v.iter().take(2))
        .fold(0.0, |m: Real, x| m.max(x.abs()));
    for ranks in 1..=4 {
        let owners = Bisection::new(&world.bodies.position, ranks).assign(&world.bodies.position);
        let results = distributed(&problem, &owners, ranks, tolerance);
        let mut worst: Real = 0.0;
        let mut copies = vec![Vec::new(); serial.len()];
        for (velocities, info, shared) in &results {
            assert!(info.converged, "{ranks} ranks: {info:?}");
            assert_eq!(*info, results[0].1, "every rank reports the same outcome");
            if ranks > 1 {
                assert!(*shared > 0, "{ranks} ranks: no interface");
            }
            for (id, v) in velocities {
                copies[*id as usize].push(*v);
                let s = serial[*id as usize];
                for d in 0..2 {
                    worst = worst.max((v[d] - s[d]).abs());
                }
            }
        }
        for (b, c) in copies.iter().enumerate() {
            assert!(
                c.windows(2).all(|w| w[0] == w[1]),
                "body {b}: copies differ {c:?}"
            );
        }
        // Any two solutions within the tolerance differ: the measure is the spread between
        // serial solves that only differ in the sweep order.
        assert!(
            worst <= SPREAD_MARGIN * spread,
            "{ranks} ranks: velocity difference {worst:e}, serial spread {spread:e}"
        );
        println!(
            "{ranks} ranks: {} sweeps, largest velocity difference {:.2e} (serial spread {:.2e}, \
             largest velocity {:.2e})",
            results[0].1.iterations, worst, spread, scale
        );
    }
}

/// Anderson mixing in the distributed solve (coefficients from sums over all ranks, copies
/// glued after mixing) lands as close to the undivided plain solve as the plain distributed
/// solve does, in fewer sweeps.
#[test]
fn accelerated_distributed_solve_matches_the_undivided_one_on_1_to_4_ranks() {
    let (world, problem) = deposit();
    let tolerance = 1e-7;
    let serial = serial_velocities(&problem, tolerance);
    let spread = serial_spread(&problem, tolerance, &serial);
    let accelerated = xper_solver::NlgsParams {
        acceleration: xper_solver::Acceleration::ANDERSON,
        ..solver_params(tolerance)
    };
    for ranks in 1..=4 {
        let owners = Bisection::new(&world.bodies.position, ranks).assign(&world.bodies.position);
        let plain = distributed(&problem, &owners, ranks, tolerance);
        let results = distributed_with(&problem, &owners, ranks, &accelerated);
        let mut worst: Real = 0.0;
        for (velocities, info, _) in &results {
            assert!(info.converged, "{ranks} ranks: {info:?}");
            assert_eq!(*info, results[0].1, "every rank reports the same outcome");
            for (id, v) in velocities {
                let s = serial[*id as usize];
                for d in 0..2 {
                    worst = worst.max((v[d] - s[d]).abs());
                }
            }
        }
        assert!(
            worst <= SPREAD_MARGIN * spread,
            "{ranks} ranks: velocity difference {worst:e}, serial spread {spread:e}"
        );
        let (sweeps, plain_sweeps) = (results[0].1.iterations, plain[0].1.iterations);
        println!(
            "{ranks} ranks, Anderson: {sweeps} sweeps (plain {plain_sweeps}), largest velocity \
             difference {worst:.2e} (serial spread {spread:.2e})"
        );
        assert!(
            sweeps < plain_sweeps,
            "{ranks} ranks: {sweeps} against {plain_sweeps}"
        );
    }
}

#[test]
fn interface_multiplicities_match_a_direct_count_and_runs_repeat_bit_for_bit() {
    let (world, problem) = deposit();
    let ranks = 3;
    let owners = Bisection::new(&world.bodies.position, ranks).assign(&world.bodies.position);
    let mut holders = vec![0u32; problem.bodies.len()];
    for r in 0..ranks {
        for id in split_problem(&problem, &owners, r as u32).global_ids {
            holders[id as usize] += 1;
        }
    }
    let maps = run_on_threads(ranks, |comm| {
        let local = split_problem(&problem, &owners, comm.rank() as u32);
        let map = InterfaceMap::build(
            comm,
            &local.global_ids,
            &local.owners,
            &local.shared(),
            None,
        );
        (local, map)
    });
    for (local, map) in &maps {
        for (b, &id) in local.global_ids.iter().enumerate() {
            let expected = if xper_domain::LocalProblem::movable(&local.problem.bodies[b]) {
                holders[id as usize]
            } else {
                1
            };
            assert_eq!(map.multiplicity[b], expected, "body {id}");
        }
    }
    let first = distributed(&problem, &owners, ranks, 1e-6);
    let second = distributed(&problem, &owners, ranks, 1e-6);
    assert_eq!(
        first.iter().map(|r| r.0.clone()).collect::<Vec<_>>(),
        second.iter().map(|r| r.0.clone()).collect::<Vec<_>>()
    );
}
