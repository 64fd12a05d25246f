//! The strip multigrid against the serial one, its exchange counts and its layouts.

use super::*;
use crate::strips::OneStrip;
use crate::PoissonSide::{Dirichlet, Neumann, Periodic};

use crate::random::random_values as random_rhs;
use crate::strips::CountingLinks;

/// One strip holding the whole grid solves the same discrete problem as the serial
/// multigrid: both at a relative residual of 1e-12 agree to 1e-8 of the solution's size
/// (the operator's condition number, about 1e4 on these grids, times the residuals).
#[test]
fn one_strip_agrees_with_the_serial_multigrid_for_every_kind_of_side() {
    let boundaries = [
        Boundary::all(Neumann),
        Boundary::all(Periodic),
        Boundary::open_top(),
        Boundary {
            left: Periodic,
            right: Periodic,
            bottom: Dirichlet,
            top: Neumann,
        },
    ];
    for (b, boundary) in boundaries.into_iter().enumerate() {
        for (nx, ny) in [(64, 128), (48, 40), (30, 18)] {
            let shape = GridShape::square_cells(nx, ny, 1.0);
            let params = MultigridParams {
                relative_tolerance: 1e-12,
                ..MultigridParams::default()
            };
            let rhs = random_rhs(nx * ny, 7 + b as u64);
            let mut serial = Multigrid::new(shape, boundary, params).unwrap();
            let mut expected = vec![0.0; nx * ny];
            serial.solve(&rhs, &mut expected).unwrap();
            let layout = StripLayout::balanced(nx, ny, 1).unwrap();
            let mut strips = StripMultigrid::new(shape, boundary, params, layout, 0).unwrap();
            let mut phi = vec![0.0; nx * ny];
            let info = strips.solve(&mut OneStrip, &rhs, &mut phi).unwrap();
            let size = expected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let difference = phi
                .iter()
                .zip(&expected)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                difference <= 1e-8 * size,
                "{boundary:?} {nx}x{ny}: difference {difference:e} of {size:e}"
            );
            assert!(
                info.convergence_factor < 0.2,
                "{boundary:?} {nx}x{ny}: factor {} in {} cycles",
                info.convergence_factor,
                info.cycles
            );
        }
    }
}

/// With deep ghost rows a cycle exchanges twice per strip level above the gathered one
/// (before the pre- and the post-smoothing), whatever the number of sweeps; the solve's
/// opening exchange serves its first residual and the first pre-smoothing. One sum opens
/// the solve, one ends each cycle and one takes the solution's mean (singular problem);
/// an rhs far from zero mean costs one more, for norms that do not cancel. The norms and
/// cycles are the serial solver's. Periodic sides, so every exchange carries rows.
#[test]
fn a_cycle_exchanges_rows_twice_per_strip_level() {
    let (nx, ny) = (64, 256);
    let shape = GridShape::square_cells(nx, ny, 1.0);
    for (pre, post, offset) in [(2, 1, 0.0), (1, 1, 0.0), (3, 2, 0.0), (2, 1, 1e4)] {
        let params = MultigridParams {
            relative_tolerance: 1e-10,
            pre_smoothing: pre,
            post_smoothing: post,
            ..MultigridParams::default()
        };
        let layout = StripLayout::balanced(nx, ny, 1).unwrap();
        let boundary = Boundary::all(Periodic);
        let mut strips = StripMultigrid::new(shape, boundary, params, layout, 0).unwrap();
        // A consistent rhs (zero mean), as a projection gives, then `offset` added.
        let mut rhs = random_rhs(nx * ny, 5);
        let mean = rhs.iter().sum::<f64>() / rhs.len() as f64;
        rhs.iter_mut().for_each(|r| *r += offset - mean);
        let mut phi = vec![0.0; nx * ny];
        let mut links = CountingLinks::default();
        let info = strips.solve(&mut links, &rhs, &mut phi).unwrap();
        let levels = strips.strip_levels();
        assert!(levels >= 3, "{levels} strip levels");
        assert_eq!(
            links.exchanges,
            info.cycles as usize * 2 * (levels - 1),
            "V({pre},{post}): {} cycles over {levels} strip levels",
            info.cycles
        );
        let recount = (offset != 0.0) as usize;
        assert_eq!(
            links.sums,
            2 + recount + info.cycles as usize,
            "V({pre},{post})"
        );
        let mut expected = vec![0.0; nx * ny];
        let serial = Multigrid::new(shape, boundary, params)
            .unwrap()
            .solve(&rhs, &mut expected)
            .unwrap();
        assert_eq!(
            info.cycles, serial.cycles,
            "V({pre},{post}) offset {offset}"
        );
        let initial = (info.initial_residual / serial.initial_residual - 1.0).abs();
        assert!(
            initial < 1e-12,
            "V({pre},{post}) offset {offset}: {initial:e}"
        );
        let size = expected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let difference = phi
            .iter()
            .zip(&expected)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(difference <= 1e-6 * size, "V({pre},{post}): {difference:e}");
    }
}

/// The coarse grid a process relaxes whole: what the strips leave when they stop
/// coarsening (400 and 512 cells on 2 processes, as before agglomeration), and on 48
/// processes of a 1024 x 1024 grid, whose 20-row strips stop coarsening at 256 x 256
/// (65,536 cells, three times a process's share, before agglomeration), 1,024 cells on
/// the few processes the agglomeration leaves, none on the others; every process holds
/// the finest level, and those left out of an agglomeration fewer levels.
#[test]
fn agglomeration_keeps_the_gathered_grid_small() {
    for (nx, ny, strips, gathered, holding) in [
        (160, 640, 2, 400, 2),
        (512, 1024, 2, 512, 2),
        (1024, 1024, 48, 1024, 6),
    ] {
        let shape = GridShape {
            nx,
            ny,
            hx: 1.0,
            hy: 1.0,
        };
        let layout = StripLayout::balanced(nx, ny, strips).unwrap();
        let solvers: Vec<StripMultigrid> = (0..strips)
            .map(|s| {
                let params = MultigridParams::default();
                let boundary = Boundary::all(Neumann);
                StripMultigrid::new(shape, boundary, params, layout.clone(), s).unwrap()
            })
            .collect();
        let cells: Vec<usize> = solvers.iter().map(|s| s.gathered_cells()).collect();
        let relaxing = cells.iter().filter(|&&c| c > 0).count();
        assert_eq!(relaxing, holding, "{nx} x {ny} on {strips}: {cells:?}");
        assert!(cells.iter().all(|&c| c == 0 || c == gathered), "{cells:?}");
        let deepest = solvers.iter().map(|s| s.strip_levels()).max().unwrap();
        assert!(solvers.iter().all(|s| s.strip_levels() >= 1));
        assert_eq!(solvers[0].strip_levels(), deepest);
    }
}

#[test]
fn weighted_layouts_share_the_weight_at_the_same_cuts() {
    // Uniform weights: the balanced cuts where the shares fall on block boundaries.
    let uniform = vec![1.0; 640];
    for strips in [2, 4] {
        assert_eq!(
            StripLayout::weighted(64, 640, strips, &uniform).unwrap(),
            StripLayout::balanced(64, 640, strips).unwrap()
        );
    }
    // The top 160 rows three times heavier: rows 0..480 weigh 480, rows 480..640 too.
    let mut heavy = vec![1.0; 640];
    heavy[480..].iter_mut().for_each(|w| *w = 3.0);
    let layout = StripLayout::weighted(64, 640, 2, &heavy).unwrap();
    // Cuts are multiples of 8 rows here (80 blocks).
    assert_eq!(layout.starts, vec![0, 480, 640]);
    // All the weight in the top rows: every strip still keeps its minimum of blocks, three
    // blocks of 8 rows.
    let mut top = vec![0.0; 640];
    top[639] = 1.0;
    let layout = StripLayout::weighted(64, 640, 3, &top).unwrap();
    assert_eq!(layout.starts, vec![0, 592, 616, 640]);
    assert_eq!(
        StripLayout::weighted(64, 640, 3, &[0.0; 640]).unwrap(),
        StripLayout::balanced(64, 640, 3).unwrap()
    );
    assert!(StripLayout::weighted(64, 640, 2, &heavy[1..]).is_err());
    assert!(StripLayout::weighted(64, 640, 2, &[f64::NAN; 640]).is_err());
}

#[test]
fn balanced_layouts_cut_at_coarsenable_rows() {
    let layout = StripLayout::balanced(64, 640, 2).unwrap();
    assert_eq!(layout.starts, vec![0, 320, 640]);
    let layout = StripLayout::balanced(64, 640, 3).unwrap();
    assert_eq!(layout.starts, vec![0, 208, 424, 640]);
    assert!(StripLayout::balanced(8, 3, 4).is_err());
    let shape = GridShape {
        nx: 64,
        ny: 640,
        hx: 1.0,
        hy: 1.0,
    };
    let solver = StripMultigrid::new(
        shape,
        Boundary::all(Neumann),
        MultigridParams::default(),
        StripLayout::balanced(64, 640, 2).unwrap(),
        1,
    )
    .unwrap();
    assert_eq!(solver.rows(), 320..640);
    assert_eq!(solver.strip_levels(), 4);
    let bad = StripLayout {
        starts: vec![0, 700],
    };
    assert!(matches!(
        StripMultigrid::new(
            shape,
            Boundary::all(Neumann),
            MultigridParams::default(),
            bad,
            0
        ),
        Err(SetupError::BadStrips { .. })
    ));
}
