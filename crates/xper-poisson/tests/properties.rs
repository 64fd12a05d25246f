//! Random small grids, boundaries, spacings, parameters and right-hand sides: the solve
//! converges and its residual, recomputed independently with `residual_norm`, is below the
//! tolerance.

use proptest::prelude::*;
use xper_poisson::{Boundary, CycleType, GridShape, Multigrid, MultigridParams, PoissonSide};

fn axis() -> impl Strategy<Value = [PoissonSide; 2]> {
    use PoissonSide::{Dirichlet as D, Neumann as N, Periodic as P};
    prop_oneof![
        Just([P, P]),
        Just([N, N]),
        Just([N, D]),
        Just([D, N]),
        Just([D, D])
    ]
}

fn cycle() -> impl Strategy<Value = CycleType> {
    prop_oneof![Just(CycleType::V), Just(CycleType::W), Just(CycleType::F)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn residual_after_solve_is_below_tolerance(
        nx in 1usize..40,
        ny in 1usize..40,
        hx in 0.02f64..0.05,
        ratio in 0.5f64..2.0,
        [left, right] in axis(),
        [bottom, top] in axis(),
        cycle in cycle(),
        coarsest_cells in prop_oneof![Just(1usize), Just(4), Just(64)],
        seed in any::<u64>(),
        offset in -2.0f64..2.0,
    ) {
        let shape = GridShape { nx, ny, hx, hy: hx * ratio };
        let boundary = Boundary { left, right, bottom, top };
        // 1e-9 inside the solver; the independent check allows 1e-8 for the roundoff of the
        // two residual evaluations (relative 1e-13 on these grids).
        let params = MultigridParams {
            relative_tolerance: 1e-9,
            max_cycles: 40,
            cycle,
            coarsest_cells,
            ..MultigridParams::default()
        };
        let mut mg = Multigrid::new(shape, boundary, params).expect("valid");
        let mut state = seed;
        let rhs: Vec<f64> = (0..nx * ny)
            .map(|_| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5 + offset
            })
            .collect();
        let mut phi = vec![0.0; nx * ny];
        let info = mg.solve(&rhs, &mut phi);
        prop_assert!(info.is_ok(), "{:?} levels {}", info, mg.levels());
        let info = info.expect("checked");
        let mean = if boundary.is_singular() { rhs.iter().sum::<f64>() / rhs.len() as f64 } else { 0.0 };
        prop_assert!((info.removed_mean - mean).abs() <= 1e-12 * (1.0 + mean.abs()));
        let compatible: Vec<f64> = rhs.iter().map(|r| r - mean).collect();
        let norm = compatible.iter().map(|r| r * r).sum::<f64>().sqrt();
        let residual = mg.residual_norm(&compatible, &phi);
        prop_assert!(residual <= 1e-8 * norm, "residual {residual:e}, rhs {norm:e}, {info:?}");
        if boundary.is_singular() {
            let phi_mean = phi.iter().sum::<f64>() / phi.len() as f64;
            let size = phi.iter().map(|p| p.abs()).fold(0.0, f64::max);
            prop_assert!(phi_mean.abs() <= 1e-12 * size.max(1e-300), "mean {phi_mean:e}");
        }
    }
}
