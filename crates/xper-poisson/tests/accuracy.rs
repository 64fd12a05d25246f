//! The solver's answer against independent ones: the continuous solution (second-order
//! discretisation error) and a dense direct solve of the same discrete problem.

use std::f64::consts::PI;
use xper_poisson::{Boundary, GridShape, Multigrid, MultigridParams, PoissonSide};

use PoissonSide::{Dirichlet as D, Neumann as N, Periodic as P};

fn unit_square(n: usize) -> GridShape {
    GridShape {
        nx: n,
        ny: n,
        hx: 1.0 / n as f64,
        hy: 1.0 / n as f64,
    }
}

fn tight() -> MultigridParams {
    MultigridParams {
        relative_tolerance: 1e-10,
        ..MultigridParams::default()
    }
}

/// Max-norm error of the discrete solution against `exact` (shifted to zero mean over the cell
/// centres when the problem is singular, as the solver's answer is).
fn error(
    n: usize,
    boundary: Boundary,
    exact: impl Fn(f64, f64) -> f64,
    lap: impl Fn(f64, f64) -> f64,
) -> f64 {
    let shape = unit_square(n);
    let mut mg = Multigrid::new(shape, boundary, tight()).expect("a valid grid");
    let centre = |k: usize| ((k % n) as f64 + 0.5) / n as f64;
    let row = |k: usize| ((k / n) as f64 + 0.5) / n as f64;
    let rhs: Vec<f64> = (0..n * n).map(|k| lap(centre(k), row(k))).collect();
    let mut want: Vec<f64> = (0..n * n).map(|k| exact(centre(k), row(k))).collect();
    if boundary.is_singular() {
        let mean = want.iter().sum::<f64>() / want.len() as f64;
        want.iter_mut().for_each(|w| *w -= mean);
    }
    let mut phi = vec![0.0; n * n];
    let info = mg.solve(&rhs, &mut phi).expect("converges");
    assert!(info.relative_residual <= 1e-10);
    phi.iter()
        .zip(&want)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// Observed orders between grids 32, 64 and 128 must lie in 1.8..2.2: the 5-point stencil and
/// the ghost rules are second order, and 1e-10 solves leave the algebraic error negligible
/// (errors are ~1e-4..1e-5). A first-order boundary treatment would give about 1.
fn assert_second_order(
    boundary: Boundary,
    exact: impl Fn(f64, f64) -> f64 + Copy,
    lap: impl Fn(f64, f64) -> f64 + Copy,
) {
    let errors: Vec<f64> = [32, 64, 128]
        .iter()
        .map(|&n| error(n, boundary, exact, lap))
        .collect();
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!(
            (1.8..=2.2).contains(&order),
            "errors {errors:?}, order {order}"
        );
    }
}

#[test]
fn neumann_cosines_converge_at_second_order() {
    assert_second_order(
        Boundary::all(N),
        |x, y| (PI * x).cos() * (PI * y).cos(),
        |x, y| -2.0 * PI * PI * (PI * x).cos() * (PI * y).cos(),
    );
}

#[test]
fn dirichlet_sines_converge_at_second_order() {
    assert_second_order(
        Boundary::all(D),
        |x, y| (PI * x).sin() * (PI * y).sin(),
        |x, y| -2.0 * PI * PI * (PI * x).sin() * (PI * y).sin(),
    );
}

#[test]
fn periodic_sines_converge_at_second_order() {
    let k = 2.0 * PI;
    assert_second_order(
        Boundary::all(P),
        move |x, y| (k * x).sin() * (k * y).sin(),
        move |x, y| -2.0 * k * k * (k * x).sin() * (k * y).sin(),
    );
}

#[test]
fn mixed_outflow_converges_at_second_order() {
    // Neumann left, right and bottom, Dirichlet top: cos(pi x) cos(pi y / 2).
    let boundary = Boundary {
        top: D,
        ..Boundary::all(N)
    };
    assert_second_order(
        boundary,
        |x, y| (PI * x).cos() * (0.5 * PI * y).cos(),
        |x, y| -1.25 * PI * PI * (PI * x).cos() * (0.5 * PI * y).cos(),
    );
}

/// Dense Gaussian elimination (partial pivoting) on the operator assembled column by column
/// from `apply_laplacian`; a singular operator `A` is replaced by `A + 1 1^T`, whose solution for
/// a zero-mean rhs is the zero-mean solution of `A x = rhs`.
fn dense_solve(mg: &Multigrid, rhs: &[f64]) -> Vec<f64> {
    let n = rhs.len();
    let singular = mg.boundary().is_singular();
    let mut a = vec![vec![0.0; n + 1]; n];
    let mut e = vec![0.0; n];
    let mut column = vec![0.0; n];
    for c in 0..n {
        e.fill(0.0);
        e[c] = 1.0;
        mg.apply_laplacian(&e, &mut column);
        for r in 0..n {
            a[r][c] = column[r] + if singular { 1.0 } else { 0.0 };
        }
    }
    let mean = if singular {
        rhs.iter().sum::<f64>() / n as f64
    } else {
        0.0
    };
    for r in 0..n {
        a[r][n] = rhs[r] - mean;
    }
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))
            .expect("rows");
        a.swap(c, p);
        let (pivot_rows, rest) = a.split_at_mut(c + 1);
        let pivot = &pivot_rows[c];
        for row in rest {
            let m = row[c] / pivot[c];
            for (v, &q) in row[c..].iter_mut().zip(&pivot[c..]) {
                *v -= m * q;
            }
        }
    }
    let mut x = vec![0.0; n];
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| a[r][k] * x[k]).sum();
        x[r] = (a[r][n] - s) / a[r][r];
    }
    x
}

fn all_boundaries() -> Vec<Boundary> {
    let axis = [[P, P], [N, N], [N, D], [D, N], [D, D]];
    let mut out = Vec::new();
    for [left, right] in axis {
        for [bottom, top] in axis {
            out.push(Boundary {
                left,
                right,
                bottom,
                top,
            });
        }
    }
    out
}

/// Every boundary combination on 8 x 6 and 12 x 10 (even and odd coarse sizes), square and
/// stretched cells, through 1 (direct), 2 or more levels: the multigrid answer equals the dense
/// solve to 1e-9 relative. Both are solved to about 1e-13, so the difference is bounded by the
/// condition number (below 1e3 on these grids) times 1e-13.
#[test]
fn solution_equals_a_dense_direct_solve() {
    for (nx, ny) in [(8, 6), (12, 10)] {
        for (hx, hy) in [(0.1, 0.1), (0.1, 0.13)] {
            for boundary in all_boundaries() {
                for coarsest_cells in [1, 16, 200] {
                    let shape = GridShape { nx, ny, hx, hy };
                    let params = MultigridParams {
                        relative_tolerance: 1e-13,
                        coarsest_cells,
                        ..MultigridParams::default()
                    };
                    let mut mg = Multigrid::new(shape, boundary, params).expect("valid");
                    let rhs: Vec<f64> = (0..nx * ny)
                        .map(|k| ((k * 7919) % 23) as f64 - 11.0 + 0.3)
                        .collect();
                    let want = dense_solve(&mg, &rhs);
                    let mut phi = vec![0.0; nx * ny];
                    mg.solve(&rhs, &mut phi).expect("converges");
                    let diff = phi
                        .iter()
                        .zip(&want)
                        .map(|(a, b)| (a - b) * (a - b))
                        .sum::<f64>()
                        .sqrt();
                    let size = want.iter().map(|b| b * b).sum::<f64>().sqrt();
                    assert!(
                        diff <= 1e-9 * size,
                        "{nx}x{ny} h {hx},{hy} {boundary:?} coarsest {coarsest_cells} ({} levels): {diff:e} vs {size:e}",
                        mg.levels()
                    );
                }
            }
        }
    }
}

/// The operator of `apply_laplacian` on a 3 x 2 grid, entry by entry from the ghost rules.
#[test]
fn laplacian_follows_the_ghost_rules() {
    let shape = GridShape {
        nx: 3,
        ny: 2,
        hx: 1.0,
        hy: 0.5,
    };
    let boundary = Boundary {
        left: N,
        right: D,
        bottom: P,
        top: P,
    };
    let mg = Multigrid::new(shape, boundary, MultigridParams::default()).expect("valid");
    let phi = [1.0, 2.0, 4.0, 8.0, 16.0, 32.0];
    let mut out = [0.0; 6];
    mg.apply_laplacian(&phi, &mut out);
    // Cell (0, 0): west ghost = 1 (Neumann), east 2, south and north both (0, 1) = 8 (periodic).
    let c00 = (1.0 - 2.0 + 2.0) + 4.0 * (8.0 - 2.0 + 8.0);
    // Cell (2, 1): west 16, east ghost -32 (Dirichlet), south and north both (2, 0) = 4.
    let c21 = (16.0 - 64.0 - 32.0) + 4.0 * (4.0 - 64.0 + 4.0);
    assert_eq!(out[0], c00);
    assert_eq!(out[5], c21);
}
