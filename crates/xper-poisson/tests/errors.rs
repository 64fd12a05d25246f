//! Bad input gives the right error variant, never a panic.

use xper_poisson::{
    Boundary, GridShape, Multigrid, MultigridError, MultigridParams, PoissonSide, SetupError,
};

use PoissonSide::{Dirichlet as D, Neumann as N, Periodic as P};

fn shape(nx: usize, ny: usize) -> GridShape {
    GridShape {
        nx,
        ny,
        hx: 0.1,
        hy: 0.1,
    }
}

fn build(
    shape: GridShape,
    boundary: Boundary,
    params: MultigridParams,
) -> Result<Multigrid, SetupError> {
    Multigrid::new(shape, boundary, params)
}

#[test]
fn setup_errors() {
    let ok = MultigridParams::default();
    let all_n = Boundary::all(N);
    assert_eq!(
        build(shape(0, 5), all_n, ok).err(),
        Some(SetupError::NoCells { nx: 0, ny: 5 })
    );
    assert_eq!(
        build(shape(5, 0), all_n, ok).err(),
        Some(SetupError::NoCells { nx: 5, ny: 0 })
    );
    assert_eq!(
        build(shape(usize::MAX, 3), all_n, ok).err(),
        Some(SetupError::NoCells {
            nx: usize::MAX,
            ny: 3
        })
    );
    for (hx, hy) in [
        (0.0, 1.0),
        (1.0, -1.0),
        (f64::NAN, 1.0),
        (1.0, f64::INFINITY),
        (1e-300, 1.0),
    ] {
        let s = GridShape {
            nx: 4,
            ny: 4,
            hx,
            hy,
        };
        assert!(
            matches!(build(s, all_n, ok), Err(SetupError::BadSpacing { .. })),
            "{hx} {hy}"
        );
    }
    let one_sided_x = Boundary { left: P, ..all_n };
    assert_eq!(
        build(shape(8, 8), one_sided_x, ok).err(),
        Some(SetupError::OneSidedPeriodic { axis: 0 })
    );
    let one_sided_y = Boundary {
        left: D,
        right: D,
        bottom: N,
        top: P,
    };
    assert_eq!(
        build(shape(8, 8), one_sided_y, ok).err(),
        Some(SetupError::OneSidedPeriodic { axis: 1 })
    );
    let bad = [
        MultigridParams { omega: 2.0, ..ok },
        MultigridParams { omega: 0.0, ..ok },
        MultigridParams {
            relative_tolerance: -1.0,
            ..ok
        },
        MultigridParams {
            relative_tolerance: f64::NAN,
            ..ok
        },
        MultigridParams {
            pre_smoothing: 0,
            post_smoothing: 0,
            ..ok
        },
        MultigridParams {
            coarsest_cells: 5000,
            ..ok
        },
    ];
    for params in bad {
        assert!(
            matches!(
                build(shape(8, 8), all_n, params),
                Err(SetupError::BadParameter { .. })
            ),
            "{params:?}"
        );
    }
    // Every message is readable.
    let e = build(shape(8, 8), one_sided_x, ok).err().expect("an error");
    assert!(e.to_string().contains("periodic on one side"));
}

#[test]
fn size_mismatch() {
    let mut mg = build(shape(6, 4), Boundary::all(D), MultigridParams::default()).expect("valid");
    let mut phi = vec![0.0; 24];
    let mut short = vec![0.0; 23];
    assert_eq!(
        mg.solve(&[1.0; 25], &mut phi),
        Err(MultigridError::SizeMismatch {
            expected: 24,
            got: 25
        })
    );
    assert_eq!(
        mg.solve(&[1.0; 24], &mut short),
        Err(MultigridError::SizeMismatch {
            expected: 24,
            got: 23
        })
    );
    // The rejected call left the solver usable.
    assert!(mg.solve(&[1.0; 24], &mut phi).is_ok());
}

#[test]
fn non_finite_input_and_non_convergence() {
    let mut mg = build(shape(16, 16), Boundary::all(D), MultigridParams::default()).expect("valid");
    let mut rhs = vec![1.0; 256];
    rhs[17] = f64::NAN;
    let mut phi = vec![0.0; 256];
    assert_eq!(
        mg.solve(&rhs, &mut phi),
        Err(MultigridError::NonFinite { cycle: 0 })
    );
    assert!(phi.iter().all(|&p| p == 0.0), "phi untouched");
    let mut bad_guess = vec![0.0; 256];
    bad_guess[3] = f64::INFINITY;
    assert_eq!(
        mg.solve(&[1.0; 256], &mut bad_guess),
        Err(MultigridError::NonFinite { cycle: 0 })
    );
    // One cycle cannot reach 1e-14: NotConverged carries the state and phi the iterate.
    let params = MultigridParams {
        max_cycles: 1,
        relative_tolerance: 1e-14,
        ..MultigridParams::default()
    };
    let mut mg = build(shape(64, 64), Boundary::all(N), params).expect("valid");
    let rhs: Vec<f64> = (0..4096).map(|k| ((k * 37) % 11) as f64 - 5.0).collect();
    let mut phi = vec![0.0; 4096];
    match mg.solve(&rhs, &mut phi) {
        Err(MultigridError::NotConverged { info }) => {
            assert_eq!(info.cycles, 1);
            assert!(
                info.relative_residual > 1e-14 && info.relative_residual < 0.2,
                "{info:?}"
            );
            assert!(phi.iter().any(|&p| p != 0.0));
            assert!(MultigridError::NotConverged { info }
                .to_string()
                .contains("did not converge"));
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}
