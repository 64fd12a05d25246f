//! LMGC90's check pass (`CheckPass::Lmgc90`) against an independent computation of its norms
//! (BRIEF.md section 2, written out here from `W`, `q` and the impulses), and against the
//! stricter check on the sweep's own updates.

use xper_solver::{
    nlgs, solve_one_contact, CheckPass, ContactOperator, ConvergenceNorm, DenseProblem, NlgsParams,
    NlgsSweeper, NormAccumulator,
};

/// A column of `n` unit masses on the floor, with a sideways push so that some contacts
/// slide: contact 0 joins the floor and mass 0, contact k masses k - 1 and k.
fn column(n: usize) -> DenseProblem {
    let gh = 9.81 * 1e-3;
    let m = 2 * n;
    let mut w = vec![0.0; m * m];
    for k in 0..n {
        let (rn, rt) = (2 * k, 2 * k + 1);
        w[rn * m + rn] = if k == 0 { 1.0 } else { 2.0 };
        w[rt * m + rt] = if k == 0 { 1.5 } else { 3.0 };
        if k + 1 < n {
            let (next_n, next_t) = (2 * (k + 1), 2 * (k + 1) + 1);
            w[rn * m + next_n] = -1.0;
            w[next_n * m + rn] = -1.0;
            w[rt * m + next_t] = -1.0;
            w[next_t * m + rt] = -1.0;
        }
    }
    let mut q = vec![0.0; m];
    q[0] = -gh;
    q[1] = 0.5 * gh;
    DenseProblem::new(w, q, vec![0.3; n])
}

/// LMGC90's three "Quad" norms of the state `r`, written out: every contact solved on the same
/// state `U = W r + q`.
fn independent_norms(p: &DenseProblem, r: &[[f64; 2]], tol: f64) -> [f64; 3] {
    let n = r.len();
    let u = p.velocity_for(r);
    let (mut dv2, mut dv2r2, mut wrr, mut wrwr, mut dvor, mut active) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for a in 0..n {
        let w = p.diagonal_block(a);
        let wr = [
            w[0] * r[a][0] + w[1] * r[a][1],
            w[2] * r[a][0] + w[3] * r[a][1],
        ];
        let r_new = solve_one_contact(&w, [u[a][0] - wr[0], u[a][1] - wr[1]], p.mu[a]);
        let wr_new = [
            w[0] * r_new[0] + w[1] * r_new[1],
            w[2] * r_new[0] + w[3] * r_new[1],
        ];
        let du = [wr[0] - wr_new[0], wr[1] - wr_new[1]];
        let rm = [(r[a][0] + r_new[0]) / 2.0, (r[a][1] + r_new[1]) / 2.0];
        if rm == [0.0, 0.0] {
            continue;
        }
        let du2 = du[0] * du[0] + du[1] * du[1];
        dv2 += du2;
        dv2r2 += du2 * (rm[0] * rm[0] + rm[1] * rm[1]);
        wrr +=
            (r[a][0] * wr[0] + r[a][1] * wr[1] + r_new[0] * wr_new[0] + r_new[1] * wr_new[1]) / 2.0;
        wrwr +=
            (wr[0] * wr[0] + wr[1] * wr[1] + wr_new[0] * wr_new[0] + wr_new[1] * wr_new[1]) / 2.0;
        dvor += rm[0] * du[0] + rm[1] * du[1];
        active += 1.0;
    }
    let quad_wr = (wrwr / active).sqrt();
    [
        (dv2 / active).sqrt() / (quad_wr * tol),
        (dv2r2 / active).sqrt() / (wrr / active * tol),
        dvor / (wrr * tol),
    ]
}

#[test]
fn the_check_pass_gives_the_norms_of_every_contact_solved_on_the_same_state() {
    let n = 12;
    let mut p = column(n);
    // A state away from the solution: half of the column's weight, some tangential impulse.
    let mut r: Vec<[f64; 2]> = (0..n)
        .map(|k| [0.5 * (n - k) as f64 * 9.81e-3, 0.02 * 9.81e-3])
        .collect();
    let (mu, shift) = (p.mu.clone(), vec![0.0; n]);
    let params = NlgsParams::default();
    let sweeper = NlgsSweeper::new(&mut p, &mu, &shift, &[], &mut r, &params).unwrap();
    let before: Vec<[f64; 2]> = (0..n).map(|a| p.local_velocity(a)).collect();
    let r_before = r.clone();
    let mut acc = NormAccumulator::default();
    sweeper.check_pass(&p, &r, 0..n, &mut acc);
    let got = acc.norms(params.tolerance);
    let expected = independent_norms(&p, &r, params.tolerance);
    for (name, g, e) in [
        ("QuadDV", got.quad_dv, expected[0]),
        ("QuadDVR", got.quad_dvr, expected[1]),
        ("MeanDVoR", got.mean_dvor, expected[2]),
    ] {
        assert!(
            (g - e).abs() <= 1e-12 * e.abs().max(1.0),
            "{name}: {g} vs {e}"
        );
    }
    assert!(
        got.quad_dv > 1.0,
        "the state is far from converged: {got:?}"
    );
    // Nothing was applied.
    assert_eq!(r, r_before);
    let after: Vec<[f64; 2]> = (0..n).map(|a| p.local_velocity(a)).collect();
    assert_eq!(after, before);
}

fn solve(n: usize, check: CheckPass) -> (u32, f64) {
    let mut p = column(n);
    let params = NlgsParams {
        max_iterations: 100_000,
        norm: ConvergenceNorm::Quad,
        check,
        ..Default::default()
    };
    let (mu, mut r) = (p.mu.clone(), vec![[0.0; 2]; n]);
    let info = nlgs(&mut p, &mu, &vec![0.0; n], &mut r, &params).unwrap();
    assert!(info.converged, "{check:?}: {info:?}");
    // The independent norms of the returned state, one check pass later, for the record.
    let norms = independent_norms(&p, &r, params.tolerance);
    (info.iterations, norms[0])
}

#[test]
fn lmgc90s_check_stops_before_the_strict_one_on_a_column() {
    for n in [10, 30] {
        let (lmgc, _) = solve(n, CheckPass::Lmgc90);
        let (strict, strict_state) = solve(n, CheckPass::Strict);
        eprintln!("n = {n}: {lmgc} sweeps with LMGC90's check, {strict} with the strict one");
        assert!(
            lmgc < strict,
            "n = {n}: {lmgc} sweeps (LMGC90's check), {strict} (strict)"
        );
        // The strict check's answer also passes LMGC90's test.
        assert!(strict_state < 1.0, "n = {n}: QuadDV {strict_state}");
    }
}
