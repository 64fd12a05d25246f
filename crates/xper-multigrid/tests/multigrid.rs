//! The multigrid solver against independent answers: a dense direct solve of the same
//! discrete problem, the continuous solution (second-order discretisation error), and its
//! textbook convergence factor.

use proptest::prelude::*;
use xper_multigrid::{Boundary, GridShape, Multigrid, MultigridParams, SideCondition, SolveError};

use SideCondition::{Dirichlet as D, Neumann as N, Periodic as P};

/// Dense Gaussian elimination on the operator assembled column by column from
/// `apply_laplacian` (with one unknown replaced by the zero-mean condition when singular).
fn dense_solve(mg: &Multigrid, rhs: &[f64], singular: bool) -> Vec<f64> {
    let n = rhs.len();
    let mut a = vec![vec![0.0; n + 1]; n];
    let mut e = vec![0.0; n];
    let mut col = vec![0.0; n];
    for c in 0..n {
        e.iter_mut().for_each(|v| *v = 0.0);
        e[c] = 1.0;
        mg.apply_laplacian(&e, &mut col);
        for r in 0..n {
            a[r][c] = col[r];
        }
    }
    let mean = rhs.iter().sum::<f64>() / n as f64;
    for r in 0..n {
        a[r][n] = if singular { rhs[r] - mean } else { rhs[r] };
    }
    if singular {
        a[n - 1] = vec![1.0; n + 1];
        a[n - 1][n] = 0.0;
    }
    for k in 0..n {
        let p = (k..n)
            .max_by(|&x, &y| a[x][k].abs().total_cmp(&a[y][k].abs()))
            .unwrap();
        a.swap(k, p);
        let pivot = a[k].clone();
        for row in a.iter_mut().skip(k + 1) {
            let f = row[k] / pivot[k];
            for (x, p) in row.iter_mut().zip(&pivot).skip(k) {
                *x -= f * p;
            }
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        x[k] = (a[k][n] - (k + 1..n).map(|c| a[k][c] * x[c]).sum::<f64>()) / a[k][k];
    }
    x
}

fn boundary(lr: SideCondition, bt: SideCondition) -> Boundary {
    Boundary {
        left: lr,
        right: lr,
        bottom: bt,
        top: bt,
    }
}

fn pseudo_random(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed | 1;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
}

#[test]
fn multigrid_equals_a_dense_solve_on_small_grids() {
    let mixed = Boundary {
        left: N,
        right: D,
        bottom: N,
        top: D,
    };
    for (nx, ny, hx, hy) in [(8, 6, 0.1, 0.1), (12, 10, 0.1, 0.07), (7, 5, 1.0, 2.0)] {
        for b in [
            boundary(N, N),
            boundary(D, D),
            boundary(P, P),
            boundary(P, N),
            boundary(D, P),
            mixed,
        ] {
            let shape = GridShape { nx, ny, hx, hy };
            let params = MultigridParams {
                relative_tolerance: 1e-12,
                ..Default::default()
            };
            let mut mg = Multigrid::new(shape, b, params).unwrap();
            let rhs = pseudo_random(nx * ny, (nx * 31 + ny) as u64);
            let mut phi = vec![0.0; nx * ny];
            mg.solve(&rhs, &mut phi).unwrap();
            let exact = dense_solve(&mg, &rhs, b.is_singular());
            let scale = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let shift = if b.is_singular() {
                exact.iter().sum::<f64>() / exact.len() as f64
            } else {
                0.0
            };
            let err = phi
                .iter()
                .zip(&exact)
                .fold(0.0f64, |m, (a, e)| m.max((a - (e - shift)).abs()));
            // 1e-12 relative residual and a condition number below ~1e3 on these grids.
            assert!(
                err <= 1e-9 * scale,
                "{nx}x{ny} {b:?}: error {err:e} (scale {scale:e})"
            );
        }
    }
}

/// Discretisation error of a manufactured solution on the unit square.
fn discretisation_error(
    n: usize,
    b: Boundary,
    exact: fn(f64, f64) -> f64,
    lap: fn(f64, f64) -> f64,
) -> f64 {
    let h = 1.0 / n as f64;
    let shape = GridShape {
        nx: n,
        ny: n,
        hx: h,
        hy: h,
    };
    let params = MultigridParams {
        relative_tolerance: 1e-11,
        ..Default::default()
    };
    let mut mg = Multigrid::new(shape, b, params).unwrap();
    let centre = |k: usize| (k as f64 + 0.5) * h;
    let rhs: Vec<f64> = (0..n * n)
        .map(|c| lap(centre(c % n), centre(c / n)))
        .collect();
    let mut phi = vec![0.0; n * n];
    mg.solve(&rhs, &mut phi).unwrap();
    let mut ex: Vec<f64> = (0..n * n)
        .map(|c| exact(centre(c % n), centre(c / n)))
        .collect();
    if b.is_singular() {
        let m = ex.iter().sum::<f64>() / ex.len() as f64;
        ex.iter_mut().for_each(|v| *v -= m);
    }
    phi.iter()
        .zip(&ex)
        .fold(0.0f64, |m, (a, e)| m.max((a - e).abs()))
}

#[test]
fn discretisation_error_is_second_order() {
    use std::f64::consts::PI;
    type Field = fn(f64, f64) -> f64;
    let cases: [(Boundary, Field, Field); 3] = [
        (
            boundary(N, N),
            |x, y| (PI * x).cos() * (PI * y).cos(),
            |x, y| -2.0 * PI * PI * (PI * x).cos() * (PI * y).cos(),
        ),
        (
            boundary(D, D),
            |x, y| (PI * x).sin() * (PI * y).sin(),
            |x, y| -2.0 * PI * PI * (PI * x).sin() * (PI * y).sin(),
        ),
        (
            boundary(P, P),
            |x, y| (2.0 * PI * x).sin() * (2.0 * PI * y).sin(),
            |x, y| -8.0 * PI * PI * (2.0 * PI * x).sin() * (2.0 * PI * y).sin(),
        ),
    ];
    for (b, exact, lap) in cases {
        let e: Vec<f64> = [32, 64, 128]
            .iter()
            .map(|&n| discretisation_error(n, b, exact, lap))
            .collect();
        for k in 0..2 {
            let order = (e[k] / e[k + 1]).log2();
            // The Dirichlet ghost (-interior) is a second-order boundary closure too.
            assert!(
                (1.8..=2.2).contains(&order),
                "{b:?}: errors {e:?}, order {order}"
            );
        }
    }
}

#[test]
fn convergence_factor_is_textbook() {
    for b in [
        boundary(N, N),
        boundary(P, P),
        Boundary {
            top: D,
            ..boundary(N, N)
        },
    ] {
        let figures = xper_multigrid::bench::run_benchmark(256, 256, b).unwrap();
        println!("{b:?}: {figures:?}");
        assert!(figures.convergence_factor <= 0.1, "{b:?}: {figures:?}");
    }
    // Elongated grids of the fluid scenes: 64 x 640 (sedimentation box), 82 x 440 and
    // 164 x 880 (Schaefer-Turek channel, coarsest 41 x 220 solved directly).
    for (nx, ny) in [(64, 640), (440, 82), (880, 164)] {
        let figures = xper_multigrid::bench::run_benchmark(nx, ny, boundary(N, N)).unwrap();
        println!("{nx}x{ny}: {figures:?}");
        assert!(figures.cycles <= 12, "{nx}x{ny}: {figures:?}");
    }
}

#[test]
fn bad_sizes_and_boundaries_are_errors() {
    let shape = GridShape {
        nx: 8,
        ny: 8,
        hx: 1.0,
        hy: 1.0,
    };
    let one_sided = Boundary {
        left: P,
        right: N,
        bottom: N,
        top: N,
    };
    assert!(Multigrid::new(shape, one_sided, Default::default()).is_err());
    assert!(Multigrid::new(
        GridShape { nx: 0, ..shape },
        boundary(N, N),
        Default::default()
    )
    .is_err());
    assert!(Multigrid::new(
        GridShape { hx: -1.0, ..shape },
        boundary(N, N),
        Default::default()
    )
    .is_err());
    let mut mg = Multigrid::new(shape, boundary(N, N), Default::default()).unwrap();
    let err = mg.solve(&[0.0; 63], &mut [0.0; 64]).unwrap_err();
    assert_eq!(
        err,
        SolveError::SizeMismatch {
            expected: 64,
            got: 63
        }
    );
    let info = mg.solve(&[1.0; 64], &mut [0.0; 64]).unwrap();
    assert!((info.removed_mean - 1.0).abs() < 1e-15, "{info:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]
    #[test]
    fn residual_below_tolerance(nx in 1usize..20, ny in 1usize..20, kind in 0usize..4, seed in 1u64..1000) {
        let b = [boundary(N, N), boundary(D, D), boundary(P, P), Boundary { left: D, ..boundary(N, N) }][kind];
        let shape = GridShape { nx, ny, hx: 0.1, hy: 0.13 };
        let mut mg = Multigrid::new(shape, b, Default::default()).unwrap();
        let mut rhs = pseudo_random(nx * ny, seed);
        if b.is_singular() {
            let m = rhs.iter().sum::<f64>() / rhs.len() as f64;
            rhs.iter_mut().for_each(|v| *v -= m);
        }
        let mut phi = vec![0.0; nx * ny];
        let info = mg.solve(&rhs, &mut phi).unwrap();
        let norm = rhs.iter().map(|v| v * v).sum::<f64>().sqrt();
        prop_assert!(mg.residual_norm(&rhs, &phi) <= 1e-8 * norm * 1.001 + 1e-14, "{:?}", info);
    }
}
