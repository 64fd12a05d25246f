//! Anderson-accelerated NLGS against plain NLGS and the exact answer, on problems without
//! geometry.

use xper_solver::{
    natural_map_error, nlgs, Acceleration, ConvergenceNorm, DenseProblem, NlgsParams,
};

/// A column of `n` unit masses resting on the floor: contact 0 joins the floor and mass 0,
/// contact k masses k - 1 and k. `W` is the 1D Laplacian (normal part; the tangential part is
/// decoupled), the free velocities are those of one step of free fall `-g h` for every mass,
/// so the normal impulse below the k-th mass from the bottom is `(n - k) g h`: Gauss-Seidel
/// needs of the order of `n^2` sweeps to carry the weight of the top down to the floor.
fn column(n: usize, mu: f64) -> (DenseProblem, Vec<f64>) {
    let gh = 9.81 * 1e-3;
    let m = 2 * n;
    let mut w = vec![0.0; m * m];
    for k in 0..n {
        let (rn, rt) = (2 * k, 2 * k + 1);
        w[rn * m + rn] = if k == 0 { 1.0 } else { 2.0 };
        w[rt * m + rt] = 3.0;
        if k + 1 < n {
            let next = 2 * (k + 1);
            w[rn * m + next] = -1.0;
            w[next * m + rn] = -1.0;
        }
    }
    let mut q = vec![0.0; m];
    q[0] = -gh;
    let exact = (0..n).map(|k| (n - k) as f64 * gh).collect();
    (DenseProblem::new(w, q, vec![mu; n]), exact)
}

fn solve(n: usize, acceleration: Acceleration) -> (u32, Vec<[f64; 2]>, f64) {
    let (mut p, exact) = column(n, 0.3);
    let params = NlgsParams {
        tolerance: 1e-10,
        max_iterations: 200_000,
        check_every: 5,
        norm: ConvergenceNorm::NaturalMap,
        acceleration,
        ..Default::default()
    };
    let (mut r, mu) = (vec![[0.0; 2]; n], p.mu.clone());
    let info = nlgs(&mut p, &mu, &vec![0.0; n], &mut r, &params).unwrap();
    assert!(info.converged, "{acceleration:?}: {info:?}");
    let err = r
        .iter()
        .zip(&exact)
        .map(|(r, e)| ((r[0] - e) / e).abs() + r[1].abs())
        .fold(0.0, f64::max);
    (info.iterations, r, err)
}

#[test]
fn anderson_reaches_the_exact_column_forces_in_far_fewer_sweeps() {
    let n = 40;
    let (plain_sweeps, _, plain_err) = solve(n, Acceleration::None);
    let (aa_sweeps, r, aa_err) = solve(n, Acceleration::ANDERSON);
    // Natural-map error 1e-10 of max(|q|, |u|, |r|) (about 0.4): the impulses agree with the
    // exact ones to a few 1e-9 relative.
    assert!(plain_err < 1e-7, "plain NLGS error {plain_err:e}");
    assert!(aa_err < 1e-7, "Anderson error {aa_err:e}");
    // Plain Gauss-Seidel contracts by about 1 - pi^2 / (2 n^2) per sweep on this chain.
    assert!(
        aa_sweeps * 5 < plain_sweeps,
        "Anderson {aa_sweeps} sweeps against {plain_sweeps} plain"
    );
    // The answer is admissible: on the cones and complementary (natural map of the final
    // state).
    let (p, _) = column(n, 0.3);
    let u = p.velocity_for(&r);
    let u: Vec<[f64; 2]> = u.iter().map(|u| [u[0], u[1]]).collect();
    assert!(natural_map_error(&u, &r, &p.mu) < 1e-9);
}

#[test]
fn anderson_handles_contacts_that_open() {
    // The top half of the column is pulled up faster than it falls: the contact between the
    // halves opens, so the active set changes during the solve; the accelerated solve must
    // still end on the exact answer, that contact's impulse at zero.
    let n = 20;
    let (mut p, _) = column(n, 0.3);
    let gh = 9.81 * 1e-3;
    p.q[2 * (n / 2)] = 5.0 * gh;
    p.reset();
    for acceleration in [Acceleration::None, Acceleration::ANDERSON] {
        let params = NlgsParams {
            tolerance: 1e-10,
            max_iterations: 100_000,
            check_every: 5,
            norm: ConvergenceNorm::NaturalMap,
            acceleration,
            ..Default::default()
        };
        let mut q = p.clone();
        let mut r = vec![[0.0; 2]; n];
        let info = nlgs(&mut q, &p.mu.clone(), &vec![0.0; n], &mut r, &params).unwrap();
        assert!(info.converged, "{acceleration:?}: {info:?}");
        assert!(r.iter().all(|r| r[0] >= 0.0 && r[1].abs() <= 0.3 * r[0]));
        assert_eq!(
            r[n / 2],
            [0.0, 0.0],
            "{acceleration:?}: the pulled contact opens"
        );
        // Below the opening the column carries its lower half only.
        let expect = (n / 2) as f64 * gh;
        assert!(((r[0][0] - expect) / expect).abs() < 1e-7, "{:?}", r[0]);
    }
}

#[test]
fn invalid_anderson_parameters_are_refused() {
    let (mut p, _) = column(3, 0.3);
    for acceleration in [
        Acceleration::Anderson {
            depth: 0,
            period: 3,
        },
        Acceleration::Anderson {
            depth: 9,
            period: 3,
        },
        Acceleration::Anderson {
            depth: 3,
            period: 0,
        },
    ] {
        let params = NlgsParams {
            acceleration,
            ..Default::default()
        };
        let (mut r, mu) = (vec![[0.0; 2]; 3], p.mu.clone());
        let e = nlgs(&mut p, &mu, &[0.0; 3], &mut r, &params).unwrap_err();
        assert!(
            e.to_string().contains("depth in 1..=8 and period >= 1"),
            "{e}"
        );
    }
}
