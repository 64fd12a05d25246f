//! The solvers of assembled problems against each other, against hand solutions and against
//! an independent check of the Signorini-Coulomb conditions.

use proptest::prelude::*;
use xper_solver::{
    nlgs, solve, ContactOperator, ConvergenceNorm, CsrMatrix, DenseProblem, FrictionProblem,
    NlgsParams, SolveError, SolveReport, SolverKind, SolverParams,
};

/// A tiny deterministic generator (splitmix64) for the random problems.
struct Rng(xper_math::SplitMix64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0.next_f64()
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// `W = H^T M^-1 H` from a random `H` (`dofs x dim n`) and a random diagonal SPD `M`:
/// rank-deficient when `dofs < dim n`, as for rigid bodies with many contacts.
/// `q = H^T v` for a random free velocity `v`, as in time stepping without gaps: then `v = 0`
/// is admissible and a solution exists (a random `q` off the range of `H^T` may make a
/// rank-deficient problem infeasible).
fn random_problem(
    rng: &mut Rng,
    dim: usize,
    n: usize,
    dofs: usize,
    mu_max: f64,
) -> FrictionProblem {
    let m = dim * n;
    let h: Vec<f64> = (0..dofs * m).map(|_| rng.range(-1.0, 1.0)).collect();
    let minv: Vec<f64> = (0..dofs).map(|_| rng.range(0.5, 2.0)).collect();
    let mut w = vec![0.0; m * m];
    for i in 0..m {
        for j in 0..m {
            w[i * m + j] = (0..dofs)
                .map(|k| h[k * m + i] * minv[k] * h[k * m + j])
                .sum();
        }
    }
    let v: Vec<f64> = (0..dofs).map(|_| rng.range(-1.0, 1.0)).collect();
    let q: Vec<f64> = (0..m)
        .map(|i| (0..dofs).map(|k| h[k * m + i] * v[k]).sum())
        .collect();
    let mu: Vec<f64> = (0..n).map(|_| rng.range(0.1, mu_max)).collect();
    FrictionProblem::new(dim, CsrMatrix::from_dense_row_major(m, m, &w), q, mu).unwrap()
}

/// Independent check of the Signorini-Coulomb conditions (not through the natural map):
/// `r_N >= 0`, `u_N >= 0`, `r_N u_N = 0`, `|r_T| <= mu r_N`, and when sliding
/// (`|u_T| > 0` and `r_N > 0`) `r_T = -mu r_N u_T / |u_T|`; stick (`|r_T| < mu r_N`)
/// requires `u_T = 0`. `tol` is absolute on quantities of the problem's scale.
fn check_coulomb(dim: usize, r: &[f64], u: &[f64], mu: &[f64], tol: f64) -> Result<(), String> {
    for (a, &mu) in mu.iter().enumerate() {
        let (ra, ua) = (&r[dim * a..dim * (a + 1)], &u[dim * a..dim * (a + 1)]);
        let rt = ra[1..].iter().map(|x| x * x).sum::<f64>().sqrt();
        let ut = ua[1..].iter().map(|x| x * x).sum::<f64>().sqrt();
        let fail = |what: &str| Err(format!("contact {a}: {what}: r = {ra:?}, u = {ua:?}"));
        if ra[0] < -tol || ua[0] < -tol {
            return fail("negative normal impulse or velocity");
        }
        if (ra[0] * ua[0]).abs() > tol * (1.0 + ra[0].abs() + ua[0].abs()) {
            return fail("normal complementarity");
        }
        if rt > mu * ra[0] + tol {
            return fail("outside the friction cone");
        }
        if rt < mu * ra[0] - tol && ut > tol {
            return fail("sticking impulse with a sliding velocity");
        }
        if ut > tol && ra[0] > tol {
            for k in 1..dim {
                if (ra[k] + mu * ra[0] * ua[k] / ut).abs() > tol * (1.0 + ra[0]) {
                    return fail("friction not opposite to sliding");
                }
            }
        }
    }
    Ok(())
}

fn params(kind: SolverKind, tol: f64) -> SolverParams {
    let mut p = SolverParams::with_kind(kind);
    p.tolerance = tol;
    if kind == SolverKind::Nlgs {
        p.max_iterations = 200_000;
    }
    p
}

fn run(p: &FrictionProblem, kind: SolverKind, tol: f64) -> SolveReport {
    let rep = solve(p, &params(kind, tol), None).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
    assert!(rep.converged, "{kind:?} did not converge: {:?}", rep.error);
    assert!(rep.error.relative_max < 1e-8, "{kind:?}: {:?}", rep.error);
    rep
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn norm(a: &[f64]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Relative agreement of two solutions.
fn agree(a: &[f64], b: &[f64], tol: f64) -> bool {
    dist(a, b) <= tol * norm(a).max(norm(b)).max(1.0)
}

#[test]
fn small_2d_problems_nsgs_newton_lemke_agree() {
    let mut rng = Rng(xper_math::SplitMix64::new(11));
    let mut checked = 0;
    for case in 0..40 {
        let n = 1 + case % 5;
        // Full rank (dofs = 2n + 2) in even cases, rank-deficient (dofs = n + 1) in odd ones.
        let full_rank = case % 2 == 0;
        let dofs = if full_rank { 2 * n + 2 } else { n + 1 };
        let p = random_problem(&mut rng, 2, n, dofs, 0.6);
        // Tight tolerance (1e-12) so that the comparison below measures disagreement between
        // solutions, not solver accuracy; Lemke's pivoting is exact up to rounding.
        let lemke = run(&p, SolverKind::Lemke, 1e-12);
        let newton_kind = if full_rank {
            SolverKind::Newton
        } else {
            SolverKind::ProximalNewton
        };
        let reports = [
            run(&p, SolverKind::Nlgs, 1e-12),
            run(&p, newton_kind, 1e-12),
            run(&p, SolverKind::ProximalNewton, 1e-12),
        ];
        check_coulomb(2, &lemke.r, &lemke.u, &p.mu, 1e-9).unwrap();
        for rep in &reports {
            check_coulomb(2, &rep.r, &rep.u, &p.mu, 1e-8)
                .unwrap_or_else(|e| panic!("case {case} {}: {e}", rep.solver));
            // Velocities: 1e-7 relative. Impulses only when W has full rank: with more
            // contact unknowns than degrees of freedom, r is not unique (W has a kernel),
            // while u = W r + q generally is.
            assert!(
                agree(&rep.u, &lemke.u, 1e-7),
                "case {case} {}: u {:?} vs Lemke {:?}",
                rep.solver,
                rep.u,
                lemke.u
            );
            if full_rank {
                assert!(
                    agree(&rep.r, &lemke.r, 1e-7),
                    "case {case} {}: r {:?} vs Lemke {:?}",
                    rep.solver,
                    rep.r,
                    lemke.r
                );
            }
        }
        checked += 1;
    }
    assert_eq!(checked, 40);
}

#[test]
fn random_3d_problems_nsgs_and_newton_agree() {
    let mut rng = Rng(xper_math::SplitMix64::new(5));
    for case in 0..30 {
        let n = 1 + case % 6;
        let full_rank = case % 3 != 0;
        let dofs = if full_rank { 3 * n + 3 } else { 2 * n };
        let p = random_problem(&mut rng, 3, n, dofs, 0.8);
        let nsgs = run(&p, SolverKind::Nlgs, 1e-12);
        let newton = run(
            &p,
            if full_rank {
                SolverKind::Newton
            } else {
                SolverKind::ProximalNewton
            },
            1e-12,
        );
        for rep in [&nsgs, &newton] {
            check_coulomb(3, &rep.r, &rep.u, &p.mu, 1e-8)
                .unwrap_or_else(|e| panic!("case {case} {}: {e}", rep.solver));
        }
        // Same tolerances and reasons as in 2D.
        assert!(agree(&nsgs.u, &newton.u, 1e-7), "case {case}: u differ");
        if full_rank {
            assert!(agree(&nsgs.r, &newton.r, 1e-7), "case {case}: r differ");
        }
    }
}

#[test]
fn nlgs_on_dense_problem_agrees_with_nsgs() {
    let mut rng = Rng(xper_math::SplitMix64::new(3));
    for case in 0..10 {
        let n = 2 + case % 4;
        let p = random_problem(&mut rng, 2, n, 2 * n + 1, 0.5);
        let m = 2 * n;
        let dense: Vec<f64> = (0..m * m).map(|k| p.w.get(k / m, k % m)).collect();
        let mut op = DenseProblem::new(dense, p.q.clone(), p.mu.clone());
        let mut impulses = vec![[0.0; 2]; n];
        let nlgs_params = NlgsParams {
            tolerance: 1e-12,
            max_iterations: 200_000,
            check_every: 1,
            relaxation: 1.0,
            norm: ConvergenceNorm::NaturalMap,
            ..Default::default()
        };
        let info = nlgs(
            &mut op,
            &p.mu.clone(),
            &vec![0.0; n],
            &mut impulses,
            &nlgs_params,
        )
        .unwrap();
        assert!(info.converged, "case {case}: {info:?}");
        let r_nlgs: Vec<f64> = impulses.iter().flatten().copied().collect();
        let rep = run(&p, SolverKind::Nlgs, 1e-12);
        // Same contact order and the same exact local solve: the two iterations coincide, up
        // to the rounding of the velocity updates (incremental in nlgs, from rows in nsgs).
        assert!(
            agree(&r_nlgs, &rep.r, 1e-8),
            "case {case}: {r_nlgs:?} vs {:?}",
            rep.r
        );
    }
}

#[test]
fn one_contact_3d_stick_slide_take_off() {
    let w = CsrMatrix::from_dense_row_major(3, 3, &[2., 0., 0., 0., 1., 0., 0., 0., 1.]);
    // (q, mu, exact r): with W = diag(2, 1, 1)
    let cases = [
        // take-off: q_N > 0, r = 0
        ([1.0, 0.3, -0.2], 0.5, [0.0, 0.0, 0.0]),
        // stick: r = -W^-1 q = (1, -0.1, -0.05), |r_T| = 0.112 < 0.5 r_N
        ([-2.0, 0.1, 0.05], 0.5, [1.0, -0.1, -0.05]),
        // slide: u_N = 0 gives r_N = 1; r_T = -mu r_N (3, 4) / 5; u_T = (2.7, 3.6) // q_T
        ([-2.0, 3.0, 4.0], 0.5, [1.0, -0.3, -0.4]),
    ];
    for (q, mu, exact) in cases {
        let p = FrictionProblem::new(3, w.clone(), q.to_vec(), vec![mu]).unwrap();
        for kind in [
            SolverKind::Nlgs,
            SolverKind::Newton,
            SolverKind::ProximalNewton,
        ] {
            let rep = run(&p, kind, 1e-12);
            assert!(dist(&rep.r, &exact) < 1e-10, "{kind:?} {q:?}: {:?}", rep.r);
            check_coulomb(3, &rep.r, &rep.u, &p.mu, 1e-12).unwrap();
        }
    }
}

#[test]
fn bad_problems_are_errors_not_panics() {
    let w0 = CsrMatrix::from_dense_row_major(2, 2, &[0.0, 0.0, 0.0, 1.0]);
    let zero_wnn = FrictionProblem::new(2, w0, vec![-1.0, 0.0], vec![0.3]).unwrap();
    let w = CsrMatrix::from_dense_row_major(2, 2, &[1.0, 0.0, 0.0, 1.0]);
    // Fields are public: a NaN can bypass FrictionProblem::new.
    let nan_q = FrictionProblem {
        dim: 2,
        w: w.clone(),
        q: vec![f64::NAN, 0.0],
        mu: vec![0.3],
    };
    let bad_size = FrictionProblem {
        dim: 2,
        w: w.clone(),
        q: vec![1.0, 0.0, 0.0],
        mu: vec![0.3],
    };
    for kind in [
        SolverKind::Nlgs,
        SolverKind::Newton,
        SolverKind::ProximalNewton,
        SolverKind::Lemke,
    ] {
        let prm = SolverParams::with_kind(kind);
        for p in [&zero_wnn, &nan_q, &bad_size] {
            assert!(solve(p, &prm, None).is_err(), "{kind:?} accepted {p:?}");
        }
        let good = FrictionProblem::new(2, w.clone(), vec![-1.0, 0.0], vec![0.3]).unwrap();
        let bad_warm = solve(&good, &prm, Some(&[f64::NAN, 0.0]));
        if kind != SolverKind::Lemke {
            assert!(matches!(bad_warm, Err(SolveError::InvalidData { .. })));
            assert!(solve(&good, &prm, Some(&[1.0])).is_err());
        }
        let mut bad_tol = prm;
        bad_tol.tolerance = -1.0;
        assert!(solve(&good, &bad_tol, None).is_err());
    }
    let p3 = FrictionProblem::new(
        3,
        CsrMatrix::from_dense_row_major(3, 3, &[1., 0., 0., 0., 1., 0., 0., 0., 1.]),
        vec![-1.0, 0.0, 0.0],
        vec![0.3],
    )
    .unwrap();
    let lemke3 = solve(&p3, &SolverParams::with_kind(SolverKind::Lemke), None);
    assert!(matches!(lemke3, Err(SolveError::Unsupported(_))));
}

#[test]
fn empty_problem_is_solved() {
    let p = FrictionProblem::new(
        3,
        CsrMatrix::from_triplets(0, 0, &[]).unwrap(),
        vec![],
        vec![],
    )
    .unwrap();
    for kind in [
        SolverKind::Nlgs,
        SolverKind::Newton,
        SolverKind::ProximalNewton,
    ] {
        let rep = solve(&p, &SolverParams::with_kind(kind), None).unwrap();
        assert!(rep.converged && rep.r.is_empty());
    }
}

#[test]
fn warm_start_at_the_solution_stops_at_once() {
    let mut rng = Rng(xper_math::SplitMix64::new(21));
    let p = random_problem(&mut rng, 3, 4, 15, 0.5);
    let first = run(&p, SolverKind::Newton, 1e-12);
    for kind in [
        SolverKind::Nlgs,
        SolverKind::Newton,
        SolverKind::ProximalNewton,
    ] {
        let rep = solve(&p, &params(kind, 1e-10), Some(&first.r)).unwrap();
        assert!(
            rep.converged && rep.iterations <= 2,
            "{kind:?}: {}",
            rep.iterations
        );
    }
}

#[test]
fn shuffled_nsgs_is_deterministic_and_converges() {
    let mut rng = Rng(xper_math::SplitMix64::new(8));
    let p = random_problem(&mut rng, 3, 6, 12, 0.7);
    let mut prm = params(SolverKind::Nlgs, 1e-10);
    prm.nsgs.shuffle_seed = Some(99);
    let a = solve(&p, &prm, None).unwrap();
    let b = solve(&p, &prm, None).unwrap();
    assert!(a.converged);
    assert_eq!(a.r, b.r);
    prm.nsgs.relaxation = 1.3;
    assert!(solve(&p, &prm, None).unwrap().converged);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Any finite problem (W not even positive) gives a report or an error, never a panic.
    #[test]
    fn solve_never_panics(
        dim in 2usize..=3,
        n in 1usize..=4,
        seed in any::<u64>(),
        kind in 0usize..4,
        positive_diagonal in prop::bool::weighted(0.9),
        scale in prop_oneof![Just(1e-300), Just(1e-12), Just(1.0), Just(1e8), Just(1e300)],
    ) {
        let mut rng = Rng(xper_math::SplitMix64::new(seed));
        let m = dim * n;
        let mut w: Vec<f64> = (0..m * m).map(|_| scale * rng.range(-2.0, 2.0)).collect();
        if positive_diagonal {
            // Most runs pass the W_NN > 0 check and exercise the iterations.
            for i in 0..m {
                w[i * m + i] = w[i * m + i].abs() + scale * 1e-3;
            }
        }
        let q: Vec<f64> = (0..m).map(|_| rng.range(-3.0, 3.0)).collect();
        let mu: Vec<f64> = (0..n).map(|_| rng.range(0.0, 2.0)).collect();
        let p = FrictionProblem::new(dim, CsrMatrix::from_dense_row_major(m, m, &w), q, mu).unwrap();
        let kind = [SolverKind::Nlgs, SolverKind::Newton, SolverKind::ProximalNewton, SolverKind::Lemke][kind];
        let mut prm = SolverParams::with_kind(kind);
        prm.max_iterations = if kind == SolverKind::Lemke { 0 } else { 30 };
        if let Ok(rep) = solve(&p, &prm, None) {
            prop_assert_eq!(rep.r.len(), m);
            prop_assert!(!rep.converged || rep.error.relative_max < prm.tolerance);
        }
    }
}

/// A sweep done in two parts (`sweep_part_accumulating` over `0..k`, then `k..n`, as a
/// domain decomposition does around its exchange) gives the bits of the whole sweep, its
/// LMGC90 sums included, for every cut `k`, plain and over-relaxed.
#[test]
fn a_sweep_in_two_parts_is_the_whole_sweep() {
    for relaxation in [1.0, 0.7] {
        sweep_in_two_parts_with(relaxation);
    }
}

fn sweep_in_two_parts_with(relaxation: f64) {
    use xper_solver::{NlgsSweeper, NormAccumulator};
    let mut rng = Rng(xper_math::SplitMix64::new(17));
    let n = 6;
    let p = random_problem(&mut rng, 2, n, 2 * n + 1, 0.5);
    let m = 2 * n;
    let dense: Vec<f64> = (0..m * m).map(|k| p.w.get(k / m, k % m)).collect();
    let params = NlgsParams {
        relaxation,
        ..NlgsParams::default()
    };
    let state = |cut: Option<usize>| {
        let mut op = DenseProblem::new(dense.clone(), p.q.clone(), p.mu.clone());
        let mut impulses = vec![[0.0; 2]; n];
        let shift = vec![0.0; n];
        let sweeper =
            NlgsSweeper::new(&mut op, &p.mu, &shift, &[], &mut impulses, &params).unwrap();
        let mut acc = NormAccumulator::default();
        for _ in 0..3 {
            acc = NormAccumulator::default();
            match cut {
                None => sweeper.sweep_accumulating(&mut op, &mut impulses, Some(&mut acc)),
                Some(k) => {
                    sweeper.sweep_part_accumulating(&mut op, &mut impulses, 0..k, Some(&mut acc));
                    sweeper.sweep_part_accumulating(&mut op, &mut impulses, k..n, Some(&mut acc));
                }
            }
        }
        let bits: Vec<u64> = (impulses.iter().flatten())
            .chain(&op.local_velocity(n - 1))
            .map(|v| v.to_bits())
            .collect();
        (bits, acc.to_sums())
    };
    let whole = state(None);
    for k in 0..=n {
        assert_eq!(state(Some(k)), whole, "cut at {k}, relaxation {relaxation}");
    }
}

/// The operator NLGS in the 3D contact frame (the sweep, Anderson mixing, LMGC90's norms and
/// the natural-map test are written once for both frames) against the assembled problem's
/// generalized Newton method, an independent algorithm: on full-rank random problems the
/// solution is unique for these friction coefficients, so both must find it.
#[test]
fn nlgs_in_the_3d_frame_agrees_with_newton() {
    use xper_solver::{Acceleration, Frame3};
    let mut rng = Rng(xper_math::SplitMix64::new(23));
    for case in 0..12 {
        let n = 1 + case % 5;
        let p = random_problem(&mut rng, 3, n, 3 * n + 3, 0.8);
        let m = 3 * n;
        let dense: Vec<f64> = (0..m * m).map(|k| p.w.get(k / m, k % m)).collect();
        let newton = run(&p, SolverKind::Newton, 1e-12);
        for acceleration in [Acceleration::None, Acceleration::ANDERSON] {
            let mut op = DenseProblem::<Frame3>::in_frame(dense.clone(), p.q.clone(), p.mu.clone());
            let mut impulses = vec![[0.0; 3]; n];
            let params = NlgsParams {
                tolerance: 1e-12,
                max_iterations: 200_000,
                check_every: 1,
                norm: ConvergenceNorm::NaturalMap,
                acceleration,
                ..Default::default()
            };
            let info = nlgs(&mut op, &p.mu, &vec![0.0; n], &mut impulses, &params).unwrap();
            assert!(info.converged, "case {case} {acceleration:?}: {info:?}");
            let r: Vec<f64> = impulses.iter().flatten().copied().collect();
            let u: Vec<f64> = op.velocity_for(&impulses).into_iter().flatten().collect();
            // The incremental state of the operator is the velocity of the impulses.
            let u_state: Vec<f64> = (0..n).flat_map(|a| op.local_velocity(a)).collect();
            assert!(agree(&u, &u_state, 1e-12), "case {case}: state drifted");
            check_coulomb(3, &r, &u, &p.mu, 1e-8)
                .unwrap_or_else(|e| panic!("case {case} {acceleration:?}: {e}"));
            assert!(
                agree(&r, &newton.r, 1e-7),
                "case {case}: r {r:?} vs {:?}",
                newton.r
            );
            assert!(agree(&u, &newton.u, 1e-7), "case {case}: u differ");
        }
    }
}

/// LMGC90's norms in the 3D frame: with the Quad norm at a tight tolerance the solve stops
/// only near the solution (natural-map error small), and a warm start at the solution
/// stops at the first check.
#[test]
fn lmgc90_norms_in_the_3d_frame() {
    use xper_solver::Frame3;
    let mut rng = Rng(xper_math::SplitMix64::new(29));
    let n = 8;
    let p = random_problem(&mut rng, 3, n, 3 * n + 3, 0.5);
    let m = 3 * n;
    let dense: Vec<f64> = (0..m * m).map(|k| p.w.get(k / m, k % m)).collect();
    let mut op = DenseProblem::<Frame3>::in_frame(dense.clone(), p.q.clone(), p.mu.clone());
    let mut impulses = vec![[0.0; 3]; n];
    let params = NlgsParams {
        tolerance: 1e-9,
        max_iterations: 100_000,
        ..Default::default()
    };
    let shift = vec![0.0; n];
    let info = nlgs(&mut op, &p.mu, &shift, &mut impulses, &params).unwrap();
    assert!(info.converged && info.iterations > 10, "{info:?}");
    let u = op.velocity_for(&impulses);
    let error = xper_solver::natural_map_error_of::<Frame3>(&u, &impulses, &p.mu);
    let scale = norm(&impulses.iter().flatten().copied().collect::<Vec<_>>());
    assert!(
        error < 1e-6 * scale,
        "natural-map error {error:e}, |r| {scale:e}"
    );
    let mut again = DenseProblem::<Frame3>::in_frame(dense, p.q.clone(), p.mu.clone());
    let info = nlgs(&mut again, &p.mu, &shift, &mut impulses, &params).unwrap();
    assert!(info.converged && info.iterations == 10, "{info:?}");
}

/// Adhesive contacts have no 3D local solve yet: asking for one is an error, not a panic.
#[test]
fn adhesive_contacts_in_3d_are_refused() {
    use xper_solver::{nlgs_with_cohesion, CohesiveTerm, Frame3};
    let mut op = DenseProblem::<Frame3>::in_frame(
        vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        vec![-1.0, 0.0, 0.0],
        vec![0.3],
    );
    let term = CohesiveTerm {
        stiffness: [1.0, 1.0],
        offset: [0.0, 0.0],
    };
    let result = nlgs_with_cohesion(
        &mut op,
        &[0.3],
        &[0.0],
        &[term],
        &mut [[0.0; 3]],
        &NlgsParams::default(),
    );
    match result {
        Err(SolveError::InvalidData { contact: 0, what }) => assert!(what.contains("2D"), "{what}"),
        other => panic!("{other:?}"),
    }
}
