//! The solver: the hierarchy built once, the cycles, the stopping test.

use crate::coarse::CoarseSolver;
use crate::level::{Level, RowSink};
use crate::transfer::Transfer;
use crate::{
    operator, Boundary, CycleType, GridShape, MultigridError, MultigridInfo, MultigridParams,
    PoissonSide, SetupError,
};

/// Largest coarsest grid the dense factorisation accepts (128 MiB of factor).
const MAX_COARSEST_CELLS: usize = 4096;

/// A geometric multigrid solver for `Lap phi = rhs` on one grid and boundary.
///
/// The level hierarchy, its workspaces and the coarsest factorisation are built by
/// [`Multigrid::new`]; [`Multigrid::solve`] allocates nothing.
pub struct Multigrid {
    shape: GridShape,
    boundary: Boundary,
    params: MultigridParams,
    singular: bool,
    levels: Vec<Level>,
    transfers: Vec<Transfer>,
    coarse: CoarseSolver,
}

/// The next coarser grid of `(n, h)` per axis, if any: an axis with at least 2 cells goes to
/// `ceil(n / 2)` cells unless its spacing exceeds `sqrt 2` times the smallest spacing of the
/// axes that can still be coarsened.
fn coarser(nx: usize, ny: usize, hx: f64, hy: f64, coarsest: usize) -> Option<[(usize, f64); 2]> {
    let can = [nx >= 2, ny >= 2];
    if nx * ny <= coarsest || !(can[0] || can[1]) {
        return None;
    }
    let h = [hx, hy];
    let smallest = (0..2)
        .filter(|&d| can[d])
        .map(|d| h[d])
        .fold(f64::INFINITY, f64::min);
    let mut out = [(nx, hx), (ny, hy)];
    for (d, (n, hd)) in out.iter_mut().enumerate() {
        if can[d] && h[d] <= std::f64::consts::SQRT_2 * smallest * (1.0 + 1e-12) {
            let m = (*n).div_ceil(2);
            *hd *= *n as f64 / m as f64;
            *n = m;
        }
    }
    Some(out)
}

fn sum_squares(r: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let chunks = r.chunks_exact(4);
    let tail: f64 = chunks.remainder().iter().map(|v| v * v).sum();
    for c in chunks {
        for (a, v) in acc.iter_mut().zip(c) {
            *a += v * v;
        }
    }
    acc.iter().sum::<f64>() + tail
}

pub(crate) fn validate(
    shape: &GridShape,
    boundary: &Boundary,
    p: &MultigridParams,
) -> Result<(), SetupError> {
    if shape.nx == 0 || shape.ny == 0 || shape.nx.checked_mul(shape.ny).is_none() {
        return Err(SetupError::NoCells {
            nx: shape.nx,
            ny: shape.ny,
        });
    }
    let good = |h: f64| h > 0.0 && h.is_finite() && (1.0 / (h * h)).is_finite();
    if !good(shape.hx) || !good(shape.hy) {
        return Err(SetupError::BadSpacing {
            hx: shape.hx,
            hy: shape.hy,
        });
    }
    for axis in 0..2 {
        let [a, b] = boundary.axis(axis);
        if (a == PoissonSide::Periodic) != (b == PoissonSide::Periodic) {
            return Err(SetupError::OneSidedPeriodic { axis });
        }
    }
    let bad = |name, value: f64| Err(SetupError::BadParameter { name, value });
    if !(p.relative_tolerance >= 0.0 && p.relative_tolerance.is_finite()) {
        return bad("relative_tolerance", p.relative_tolerance);
    }
    if !(p.omega > 0.0 && p.omega < 2.0) {
        return bad("omega", p.omega);
    }
    if p.pre_smoothing + p.post_smoothing == 0 {
        return bad("pre_smoothing + post_smoothing", 0.0);
    }
    if p.coarsest_cells > MAX_COARSEST_CELLS {
        return bad("coarsest_cells", p.coarsest_cells as f64);
    }
    Ok(())
}

/// Work of one cycle, in finest-grid sweeps.
struct Work {
    fine_cells: f64,
    units: f64,
}

impl Work {
    fn add(&mut self, level: &Level, passes: f64) {
        self.units += passes * level.cells() as f64 / self.fine_cells;
    }
}

/// One cycle of type `kind` on `levels[0]` (its `u` the initial guess, `f` the rhs). With
/// `norm`, the squared residual norm after the cycle is written there.
fn cycle(
    levels: &mut [Level],
    transfers: &mut [Transfer],
    coarse: &mut CoarseSolver,
    p: &MultigridParams,
    kind: CycleType,
    work: &mut Work,
    norm: Option<&mut f64>,
) {
    let Some(((fine, rest), (transfer, lower))) =
        levels.split_first_mut().zip(transfers.split_first_mut())
    else {
        let level = &mut levels[0];
        coarse.solve(level);
        let n = coarse.cells() as f64;
        work.units += 2.0 * n * n / (8.0 * work.fine_cells);
        if let Some(norm) = norm {
            *norm = 0.0;
            level.residual(&mut |_, r| *norm += sum_squares(r));
            work.add(level, 1.0);
        }
        return;
    };
    {
        let next = &mut rest[0];
        next.u.fill(0.0);
        next.f.fill(0.0);
        let mut restrict = |j: usize, r: &[f64]| transfer.restrict_row(j, r, next);
        for k in 0..p.pre_smoothing {
            let last = k + 1 == p.pre_smoothing;
            fine.sweep(p.omega, last.then_some(&mut restrict as RowSink));
        }
        if p.pre_smoothing == 0 {
            fine.residual(&mut restrict);
        }
        work.add(fine, p.pre_smoothing as f64 + 1.5);
    }
    match kind {
        CycleType::V => cycle(rest, lower, coarse, p, CycleType::V, work, None),
        CycleType::W => {
            cycle(rest, lower, coarse, p, CycleType::W, work, None);
            cycle(rest, lower, coarse, p, CycleType::W, work, None);
        }
        CycleType::F => {
            cycle(rest, lower, coarse, p, CycleType::F, work, None);
            cycle(rest, lower, coarse, p, CycleType::V, work, None);
        }
    }
    transfer.prolong(&rest[0], fine);
    work.add(fine, 0.5 + p.post_smoothing as f64);
    let want_norm = norm.is_some();
    let mut sum = 0.0;
    let mut accumulate = |_: usize, r: &[f64]| sum += sum_squares(r);
    for k in 0..p.post_smoothing {
        let last = want_norm && k + 1 == p.post_smoothing;
        fine.sweep(p.omega, last.then_some(&mut accumulate as RowSink));
    }
    if want_norm && p.post_smoothing == 0 {
        fine.residual(&mut accumulate);
    }
    if let Some(norm) = norm {
        *norm = sum;
        work.add(fine, 1.0);
    }
}

impl Multigrid {
    /// Builds the hierarchy for `shape` and `boundary`, factorises the coarsest operator.
    pub fn new(
        shape: GridShape,
        boundary: Boundary,
        params: MultigridParams,
    ) -> Result<Self, SetupError> {
        validate(&shape, &boundary, &params)?;
        let mut levels = vec![Level::new(
            shape.nx, shape.ny, shape.hx, shape.hy, &boundary,
        )];
        loop {
            let l = levels.last().expect("the finest level");
            let Some([(nx, hx), (ny, hy)]) = coarser(l.nx, l.ny, l.hx, l.hy, params.coarsest_cells)
            else {
                break;
            };
            levels.push(Level::new(nx, ny, hx, hy, &boundary));
        }
        let transfers = levels
            .windows(2)
            .map(|w| Transfer::new(&w[0], &w[1], boundary.axis(0), boundary.axis(1)))
            .collect();
        let singular = boundary.is_singular();
        let coarse = CoarseSolver::new(levels.last_mut().expect("the coarsest level"), singular)?;
        Ok(Multigrid {
            shape,
            boundary,
            params,
            singular,
            levels,
            transfers,
            coarse,
        })
    }

    /// Solves `Lap phi = rhs`; `phi` holds the initial guess (warm start) on entry and the
    /// solution on exit.
    ///
    /// Without a Dirichlet side the mean of `rhs` is removed first
    /// ([`MultigridInfo::removed_mean`]), residuals are those of the mean-free rhs, and the
    /// returned `phi` has zero mean. A zero (mean-free) rhs gives `phi = 0` without cycles.
    /// On [`MultigridError::NotConverged`] `phi` holds the last iterate; on
    /// [`MultigridError::NonFinite`] and [`MultigridError::SizeMismatch`] it is unchanged.
    pub fn solve(&mut self, rhs: &[f64], phi: &mut [f64]) -> Result<MultigridInfo, MultigridError> {
        let (nx, ny) = (self.shape.nx, self.shape.ny);
        let expected = nx * ny;
        for got in [rhs.len(), phi.len()] {
            if got != expected {
                return Err(MultigridError::SizeMismatch { expected, got });
            }
        }
        let removed_mean = if self.singular {
            rhs.iter().sum::<f64>() / expected as f64
        } else {
            0.0
        };
        let mut work = Work {
            fine_cells: expected as f64,
            units: 0.0,
        };
        let fine = &mut self.levels[0];
        let mut rhs_squares = 0.0;
        for j in 0..ny {
            let start = fine.row_start(j);
            let row = &rhs[nx * j..nx * (j + 1)];
            for (f, &r) in fine.f[start..start + nx].iter_mut().zip(row) {
                *f = r - removed_mean;
            }
            rhs_squares += sum_squares(&fine.f[start..start + nx]);
            fine.u[start..start + nx].copy_from_slice(&phi[nx * j..nx * (j + 1)]);
        }
        let rhs_norm = rhs_squares.sqrt();
        let mut info = MultigridInfo {
            removed_mean,
            ..MultigridInfo::default()
        };
        if rhs_norm == 0.0 {
            phi.fill(0.0);
            info.work_units = 0.5;
            return Ok(info);
        }
        let mut squares = 0.0;
        fine.residual(&mut |_, r| squares += sum_squares(r));
        work.units += 2.0;
        let initial = squares.sqrt();
        if !initial.is_finite() {
            return Err(MultigridError::NonFinite { cycle: 0 });
        }
        let target = self.params.relative_tolerance * rhs_norm;
        let mut residual = initial;
        let mut cycles = 0;
        while residual > target && cycles < self.params.max_cycles {
            cycle(
                &mut self.levels,
                &mut self.transfers,
                &mut self.coarse,
                &self.params,
                self.params.cycle,
                &mut work,
                Some(&mut squares),
            );
            cycles += 1;
            residual = squares.sqrt();
            if !residual.is_finite() {
                return Err(MultigridError::NonFinite { cycle: cycles });
            }
        }
        let fine = &self.levels[0];
        let mean = if self.singular {
            let mut sum = 0.0;
            for j in 0..ny {
                let start = fine.row_start(j);
                sum += fine.u[start..start + nx].iter().sum::<f64>();
            }
            work.units += 0.5;
            sum / expected as f64
        } else {
            0.0
        };
        for j in 0..ny {
            let start = fine.row_start(j);
            for (p, &u) in phi[nx * j..nx * (j + 1)]
                .iter_mut()
                .zip(&fine.u[start..start + nx])
            {
                *p = u - mean;
            }
        }
        work.units += 0.5;
        info.cycles = cycles;
        info.initial_residual = initial;
        info.relative_residual = residual / rhs_norm;
        info.convergence_factor = if cycles == 0 {
            0.0
        } else {
            (residual / initial).powf(1.0 / cycles as f64)
        };
        info.work_units = work.units;
        if residual > target {
            Err(MultigridError::NotConverged { info })
        } else {
            Ok(info)
        }
    }

    /// `||rhs - Lap phi||_2` with this solver's boundary conditions (`rhs` as given, without
    /// mean removal).
    ///
    /// # Panics
    /// If `rhs` or `phi` does not have `nx ny` entries.
    pub fn residual_norm(&self, rhs: &[f64], phi: &[f64]) -> f64 {
        let mut lap = vec![0.0; phi.len()];
        self.apply_laplacian(phi, &mut lap);
        assert_eq!(
            rhs.len(),
            lap.len(),
            "rhs has {} values, expected {}",
            rhs.len(),
            lap.len()
        );
        rhs.iter()
            .zip(&lap)
            .map(|(r, l)| (r - l) * (r - l))
            .sum::<f64>()
            .sqrt()
    }

    /// `out = Lap phi` with this solver's boundary conditions.
    ///
    /// # Panics
    /// If `phi` or `out` does not have `nx ny` entries.
    pub fn apply_laplacian(&self, phi: &[f64], out: &mut [f64]) {
        let n = self.shape.cells();
        assert!(
            phi.len() == n && out.len() == n,
            "apply_laplacian: expected {n} values, got {} and {}",
            phi.len(),
            out.len()
        );
        operator::apply(&self.shape, &self.boundary, phi, out);
    }

    /// Number of grids in the hierarchy (1: the finest grid is solved directly).
    pub fn levels(&self) -> usize {
        self.levels.len()
    }

    /// The grid of level `l` (0 the finest), `None` beyond the coarsest.
    pub fn level_shape(&self, l: usize) -> Option<GridShape> {
        self.levels.get(l).map(|level| GridShape {
            nx: level.nx,
            ny: level.ny,
            hx: level.hx,
            hy: level.hy,
        })
    }

    /// The finest grid.
    pub fn shape(&self) -> GridShape {
        self.shape
    }

    /// The boundary conditions.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }

    /// The parameters.
    pub fn params(&self) -> MultigridParams {
        self.params
    }

    /// The asymptotic convergence factor: the residual reduction of the last of `cycles`
    /// cycles on `Lap e = 0` from a random `e` (rescaled after each cycle), the error
    /// component that survives being the slowest one (benchmark support).
    pub fn asymptotic_factor(&mut self, cycles: u32, state: &mut u64) -> f64 {
        let fine_cells = self.shape.cells() as f64;
        let fine = &mut self.levels[0];
        fine.f.fill(0.0);
        for j in 0..fine.ny {
            let start = fine.row_start(j);
            for u in &mut fine.u[start..start + fine.nx] {
                *u = crate::random::random(state);
            }
        }
        let mut work = Work {
            fine_cells,
            units: 0.0,
        };
        let mut squares = 0.0;
        fine.residual(&mut |_, r| squares += sum_squares(r));
        let mut factor = 0.0;
        for _ in 0..cycles {
            let before = squares.sqrt();
            let p = self.params;
            cycle(
                &mut self.levels,
                &mut self.transfers,
                &mut self.coarse,
                &p,
                p.cycle,
                &mut work,
                Some(&mut squares),
            );
            factor = squares.sqrt() / before;
            // Rescale, and remove the mean (the kernel of singular problems) so that it does
            // not grow until the residual is roundoff.
            let fine = &mut self.levels[0];
            let mean = if self.singular {
                (0..fine.ny)
                    .map(|j| fine.u[fine.row_start(j)..][..fine.nx].iter().sum::<f64>())
                    .sum::<f64>()
                    / fine_cells
            } else {
                0.0
            };
            let scale = 1.0 / squares.sqrt();
            for j in 0..fine.ny {
                let start = fine.row_start(j);
                for u in &mut fine.u[start..start + fine.nx] {
                    *u = (*u - mean) * scale;
                }
            }
            squares = 1.0;
        }
        factor
    }

    /// Times `sweeps` red-black sweeps on the finest level (benchmark support; the level's
    /// arrays are overwritten).
    pub fn time_sweeps(&mut self, sweeps: u32) -> f64 {
        let fine = &mut self.levels[0];
        let start = std::time::Instant::now();
        for _ in 0..sweeps {
            fine.sweep(self.params.omega, None);
        }
        start.elapsed().as_secs_f64()
    }
}
