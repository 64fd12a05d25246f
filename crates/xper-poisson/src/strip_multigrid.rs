//! Multigrid over strips held by several processes: the same equation as [`crate::Multigrid`]
//! (the 5-point Laplacian with Neumann, Dirichlet or periodic sides), each process holding the
//! rows of its strip ([`StripLayout`]).
//!
//! The strip levels coarsen by two in both directions while the strips stay whole numbers of
//! at least [`MIN_STRIP_ROWS`] coarse rows ([`StripLayout::balanced`] cuts them so); a level
//! exchanges deep ghost rows (`2 s + 1` for `s` sweeps, fewer on strips thinner than that,
//! whose sweeps are then exchanged for in groups) with each neighbouring strip
//! once before its pre-smoothing and once before its post-smoothing, overlapping each
//! exchange with the sweeps of its inner rows, and relaxes its
//! neighbours' edge rows itself (the private module `strip_level`); the residual is
//! restricted by four-cell averages within the last pre-smoothing sweep and the correction
//! prolongated bilinearly, as in the serial solver. A V(2,1) cycle thus exchanges rows twice
//! per strip level, and the residual that ends it is computed within its last sweep.
//! When the strips get too thin to coarsen while the grid is still large, the level is
//! agglomerated: its residual is re-cut into about half as many strips on about half the
//! processes, which go on while the others wait for their rows of the correction (the private
//! module `strip_hierarchy`).
//! The coarsest strip level (at most [`crate::strips::GATHERED_CELLS`] cells when the grid
//! halves that far) is gathered on every process holding one of its strips and
//! relaxed whole by one V-cycle of the serial [`crate::Multigrid`], so that, when the serial
//! solver coarsens the same way, a strip cycle is the serial solver's cycle to round-off (the
//! strip cycle is a V-cycle whatever [`MultigridParams::cycle`] says); every
//! process gets the same bits, so no broadcast is needed (the agglomeration of Trottenberg et
//! al., "Multigrid", section 6.3). Convergence is judged on the global residual norm (one sum
//! per cycle), so every process stops at the same cycle. A solve opens with one exchange (the
//! rows of the first pre-smoothing, which then needs none) and one sum (the mean, the rhs
//! norm and the first residual norm together).

use crate::strip_hierarchy::{move_rows, plan_levels, Below, LevelPlan, Strips};
use crate::strip_level::{ghost_rows, Combine, Field, StripLevel};
use crate::strips::{AgglomeratedLinks, RowExchange, RowLinks, StripLayout, MIN_STRIP_ROWS};
use crate::{
    Boundary, CycleType, GridShape, Multigrid, MultigridError, MultigridInfo, MultigridParams,
    SetupError,
};

/// A multigrid solver for the rows of one strip of the grid.
pub struct StripMultigrid {
    shape: GridShape,
    params: MultigridParams,
    singular: bool,
    /// Whether the bottom and top are periodic (the strips' links wrap around).
    periodic: bool,
    /// The levels of every process (the same on each).
    plans: Vec<LevelPlan>,
    /// The levels this process holds a strip of: a first part of the hierarchy, the whole of
    /// it unless an agglomeration leaves this process out.
    levels: Vec<StripLevel>,
    /// Per level of `levels` agglomerated below: this process's strip of the re-cut, at the
    /// level's resolution, if it holds one (the residual is restricted from it, the
    /// correction prolongated into it).
    stagings: Vec<Option<StripLevel>>,
    strip: usize,
    coarse: Multigrid,
    coarse_rhs: Vec<f64>,
    coarse_solution: Vec<f64>,
}

impl StripMultigrid {
    /// The solver of strip `strip` of `layout` over `shape` with `boundary`.
    pub fn new(
        shape: GridShape,
        boundary: Boundary,
        params: MultigridParams,
        layout: StripLayout,
        strip: usize,
    ) -> Result<Self, SetupError> {
        crate::multigrid::validate(&shape, &boundary, &params)?;
        if layout.starts.first() != Some(&0)
            || layout.starts.last() != Some(&shape.ny)
            || layout
                .starts
                .windows(2)
                .any(|w| w[0] + MIN_STRIP_ROWS > w[1])
            || strip >= layout.strips()
        {
            return Err(SetupError::BadStrips {
                starts: layout.starts.clone(),
                ny: shape.ny,
                strip,
                min_rows: MIN_STRIP_ROWS,
            });
        }
        let plans = plan_levels(shape, &layout);
        let mut levels = Vec::new();
        let mut stagings = Vec::new();
        for plan in &plans {
            let Some(at) = plan.strips.strip_of(strip) else {
                break;
            };
            levels.push(Self::level(
                plan,
                &plan.strips,
                at,
                boundary,
                ghost_rows(&params),
            ));
            stagings.push(match &plan.below {
                Below::Agglomerated(cut) => {
                    (cut.strip_of(strip)).map(|t| Self::level(plan, cut, t, boundary, 1))
                }
                Below::Coarser | Below::Gathered => None,
            });
        }
        let bottom = plans.last().expect("at least one level").shape;
        // One V-cycle of the serial solver on the gathered grid, as the serial cycle would
        // continue below this level: the strip cycle is then the serial iteration, and every
        // process does no more coarse work than the serial solver. (Solving the gathered grid
        // to 1e-3 took several cycles on every process, about 7 % of a process's time on
        // two_grains_sedimentation, for the same number of outer cycles.)
        let coarse_params = MultigridParams {
            relative_tolerance: 0.0,
            max_cycles: 1,
            cycle: CycleType::V,
            ..params
        };
        Ok(StripMultigrid {
            shape,
            params,
            singular: boundary.is_singular(),
            periodic: boundary.bottom == crate::PoissonSide::Periodic,
            plans,
            levels,
            stagings,
            strip,
            coarse: Multigrid::new(bottom, boundary, coarse_params)?,
            coarse_rhs: vec![0.0; bottom.cells()],
            coarse_solution: vec![0.0; bottom.cells()],
        })
    }

    /// Strip `at` of `strips` on the grid of `plan`, with `ghosts` ghost rows or fewer where
    /// the strips are thinner (the sweeps are then exchanged for in smaller groups); the same
    /// on every strip of the level.
    fn level(
        plan: &LevelPlan,
        strips: &Strips,
        at: usize,
        boundary: Boundary,
        ghosts: usize,
    ) -> StripLevel {
        let GridShape { nx, ny, hx, hy } = plan.shape;
        let ghosts = ghosts.min(strips.thinnest());
        StripLevel::new(nx, ny, strips.rows(at), [hx, hy], boundary, ghosts)
    }

    /// Number of strip levels this process holds a strip of, the coarsest (the one gathered
    /// whole) included when it holds one of its strips.
    pub fn strip_levels(&self) -> usize {
        self.levels.len()
    }

    /// Cells of the coarse grid that this process gathers and relaxes whole in each cycle
    /// (0 when an agglomeration leaves it out before): work repeated by every process that
    /// holds a strip of it, not divided. Strips stop coarsening once one is thinner than
    /// `2 MIN_STRIP_ROWS` rows; the levels are then agglomerated on fewer processes until
    /// the grid has at most [`crate::strips::GATHERED_CELLS`] cells or does not halve.
    pub fn gathered_cells(&self) -> usize {
        let bottom = &self.plans.last().expect("at least one level").strips;
        if bottom.strip_of(self.strip).is_some() {
            self.coarse_rhs.len()
        } else {
            0
        }
    }

    /// The rows of this strip.
    pub fn rows(&self) -> std::ops::Range<usize> {
        self.plans[0].strips.rows(self.strip)
    }

    /// Solves `Lap phi = rhs` over the whole grid, `rhs` and `phi` holding this strip's cells
    /// row-major (`nx` by its rows); `phi` is the initial guess. The conventions (mean removal
    /// of singular problems, stopping test, errors) are those of [`Multigrid::solve`].
    pub fn solve(
        &mut self,
        links: &mut dyn RowLinks,
        rhs: &[f64],
        phi: &mut [f64],
    ) -> Result<MultigridInfo, MultigridError> {
        let nx = self.shape.nx;
        let expected = nx * self.rows().len();
        for got in [rhs.len(), phi.len()] {
            if got != expected {
                return Err(MultigridError::SizeMismatch { expected, got });
            }
        }
        let fine = &mut self.levels[0];
        for j in 0..fine.rows {
            let k = fine.index(0, j as isize);
            fine.f[k..k + nx].copy_from_slice(&rhs[nx * j..nx * (j + 1)]);
            fine.u[k..k + nx].copy_from_slice(&phi[nx * j..nx * (j + 1)]);
        }
        fine.rhs_changed();
        fine.solution_changed();
        // One exchange and one sum open the solve: with `m` the removed mean (singular
        // problems) and `r = f - Lap u` the residual before its removal,
        // `|f - m|^2 = sum f^2 - N m^2` and `|r - m|^2 = sum r^2 - 2 m sum r + N m^2`.
        let mut sums = fine.open_solve(links, self.params.pre_smoothing as usize);
        links.sum(&mut sums);
        let cells = self.shape.cells() as f64;
        let removed_mean = if self.singular { sums[0] / cells } else { 0.0 };
        fine.remove_mean(removed_mean);
        let shift = cells * removed_mean * removed_mean;
        let (mut rhs_squares, mut residual_squares) = (
            sums[1] - shift,
            sums[3] - 2.0 * removed_mean * sums[2] + shift,
        );
        if shift > 1e-6 * sums[1] {
            // The mean is not negligible: the differences would lose digits; sum again.
            let mut exact = fine.residual_sums();
            links.sum(&mut exact);
            [rhs_squares, residual_squares] = [exact[1], exact[3]];
        }
        // A root that keeps NaN (a difference of sums may round below zero).
        let root = |x: f64| if x < 0.0 { 0.0 } else { x.sqrt() };
        let rhs_norm = root(rhs_squares);
        let mut info = MultigridInfo {
            removed_mean,
            ..MultigridInfo::default()
        };
        if rhs_norm == 0.0 {
            phi.fill(0.0);
            return Ok(info);
        }
        let initial = root(residual_squares);
        if !initial.is_finite() {
            return Err(MultigridError::NonFinite { cycle: 0 });
        }
        let target = self.params.relative_tolerance * rhs_norm;
        let mut norm = initial;
        let mut cycles = 0;
        let mut work = 1.0;
        while norm > target && cycles < self.params.max_cycles {
            let (cycle_work, fused) = self.cycle(0, links);
            work += cycle_work + 1.0;
            let mut squares = [match fused {
                Some(squares) => squares,
                None => self.levels[0].residual(links),
            }];
            links.sum(&mut squares);
            norm = squares[0].sqrt();
            cycles += 1;
            if !norm.is_finite() {
                return Err(MultigridError::NonFinite { cycle: cycles });
            }
        }
        let fine = &self.levels[0];
        let mut mean = [0.0];
        if self.singular {
            for j in 0..fine.rows {
                let k = fine.index(0, j as isize);
                mean[0] += fine.u[k..k + nx].iter().sum::<f64>();
            }
            links.sum(&mut mean);
            mean[0] /= self.shape.cells() as f64;
        }
        for j in 0..fine.rows {
            let k = fine.index(0, j as isize);
            for (p, u) in phi[nx * j..nx * (j + 1)].iter_mut().zip(&fine.u[k..k + nx]) {
                *p = u - mean[0];
            }
        }
        info.cycles = cycles;
        info.initial_residual = initial;
        info.relative_residual = norm / rhs_norm;
        info.convergence_factor = if cycles == 0 {
            0.0
        } else {
            (norm / initial).powf(1.0 / cycles as f64)
        };
        info.work_units = work;
        if norm > target {
            Err(MultigridError::NotConverged { info })
        } else {
            Ok(info)
        }
    }

    /// The processes holding the strips below and above this one on level `l`, when the
    /// level's strips are not every process's (`None`: the links' own neighbours).
    fn neighbours(&self, l: usize) -> Option<[Option<usize>; 2]> {
        let strips = &self.plans[l].strips;
        if strips.ranks.len() == self.plans[0].strips.ranks.len() {
            return None;
        }
        let at = strips
            .strip_of(self.strip)
            .expect("a level this process holds");
        Some(strips.neighbours(at, self.periodic))
    }

    /// One V-cycle from level `l` (its `u` the guess, `f` the rhs); returns its work in
    /// finest-grid sweeps of this strip and, on the finest level when it is not the gathered
    /// one, this strip's `sum r^2` after the cycle (computed within the last sweep).
    fn cycle(&mut self, l: usize, links: &mut dyn RowLinks) -> (f64, Option<f64>) {
        let scale = self.levels[l].cells() as f64 / self.levels[0].cells() as f64;
        match self.plans[l].below {
            Below::Agglomerated(_) => return self.agglomerated_cycle(l, links),
            Below::Gathered => {
                self.solve_gathered(links, l > 0);
                return (scale, None);
            }
            Below::Coarser => {}
        }
        let p = self.params;
        let neighbours = self.neighbours(l);
        let (upper, lower) = self.levels.split_at_mut(l + 1);
        let (fine, coarse) = (&mut upper[l], &mut lower[0]);
        coarse.zero_solution();
        with_links(neighbours, links, |links| {
            fine.smooth(links, p.omega, p.pre_smoothing as usize, true, Some(coarse))
        });
        let mut work = scale * (p.pre_smoothing as f64 + 1.5);
        work += self.cycle(l + 1, links).0;
        let (upper, lower) = self.levels.split_at_mut(l + 1);
        let (fine, coarse) = (&mut upper[l], &mut lower[0]);
        let sum = with_links(neighbours, links, |links| {
            fine.prolong(coarse, links);
            fine.smooth(links, p.omega, p.post_smoothing as usize, l == 0, None)
        });
        let squares = (l == 0).then_some(sum);
        (work + scale * (0.5 + p.post_smoothing as f64), squares)
    }

    /// [`StripMultigrid::cycle`] on a level agglomerated below: pre-smoothing with the
    /// residual on every cell, the residual re-cut onto the processes of the next stage, which
    /// restrict it, cycle below and prolongate the correction into the re-cut strips, the
    /// correction's rows sent back, post-smoothing.
    fn agglomerated_cycle(&mut self, l: usize, links: &mut dyn RowLinks) -> (f64, Option<f64>) {
        let p = self.params;
        let me = self.strip;
        let scale = self.levels[l].cells() as f64 / self.levels[0].cells() as f64;
        let mut work = scale * (p.pre_smoothing as f64 + 1.0);
        let neighbours = self.neighbours(l);
        let fine = &mut self.levels[l];
        with_links(neighbours, links, |links| {
            fine.smooth(links, p.omega, p.pre_smoothing as usize, true, None)
        });
        // Taken out while the levels below cycle (they do not use it).
        let mut staging = self.stagings[l].take();
        let (strips, cut) = self.plans[l].agglomeration();
        let (source, target) = (Some(&*fine), staging.as_mut());
        let (field, combine) = (Field::Residual, Combine::Replace);
        move_rows(links, me, strips, source, cut, target, field, combine);
        if let Some(staging) = staging.as_mut() {
            let coarse = &mut self.levels[l + 1];
            staging.restrict(coarse);
            coarse.zero_solution();
            work += scale * 0.5 + self.cycle(l + 1, links).0;
            let coarse_neighbours = self.neighbours(l + 1);
            let coarse = &mut self.levels[l + 1];
            staging.zero_solution();
            with_links(coarse_neighbours, links, |links| {
                staging.prolong(coarse, links)
            });
        }
        let fine = &mut self.levels[l];
        let (strips, cut) = self.plans[l].agglomeration();
        let (source, target) = (staging.as_ref(), Some(&mut *fine));
        let (field, combine) = (Field::Solution, Combine::Add);
        move_rows(links, me, cut, source, strips, target, field, combine);
        fine.solution_changed();
        let sum = with_links(neighbours, links, |links| {
            fine.smooth(links, p.omega, p.post_smoothing as usize, l == 0, None)
        });
        self.stagings[l] = staging;
        let squares = (l == 0).then_some(sum);
        (work + scale * (0.5 + p.post_smoothing as f64), squares)
    }

    /// Corrects the coarsest strip level by a whole solve: its residual gathered from every
    /// strip of it, the serial multigrid run on each of their processes, each adding its rows.
    /// With `zero_guess` (a coarse level, its `u` zero on entry) the residual is the rhs
    /// itself.
    fn solve_gathered(&mut self, links: &mut dyn RowLinks, zero_guess: bool) {
        let neighbours = self.neighbours(self.levels.len() - 1);
        let level = self.levels.last_mut().expect("at least one level");
        let nx = level.nx;
        if !zero_guess {
            with_links(neighbours, links, |links| level.residual(links));
        }
        let field = if zero_guess {
            Field::Rhs
        } else {
            Field::Residual
        };
        let own = level.first_row..level.first_row + level.rows;
        let mut cells = level.copy_rows(field, own.clone());
        self.coarse_rhs[nx * own.start..nx * own.end].copy_from_slice(&cells);
        let bottom = &self.plans.last().expect("at least one level").strips;
        let starts = &bottom.starts;
        if bottom.ranks.len() == self.plans[0].strips.ranks.len() {
            // Every process holds a strip: one collective, every strip sending as many rows
            // as the highest one (zeros after its own).
            let highest = starts.windows(2).map(|w| w[1] - w[0]).max().unwrap_or(0);
            cells.resize(highest * nx, 0.0);
            let whole = links.gather(&cells);
            for (s, rows) in starts.windows(2).enumerate() {
                let count = nx * (rows[1] - rows[0]);
                let from = s * highest * nx;
                self.coarse_rhs[nx * rows[0]..nx * rows[1]]
                    .copy_from_slice(&whole[from..from + count]);
            }
        } else {
            // Some processes: each sends its rows to the others.
            let others: Vec<usize> = (bottom.ranks.iter())
                .copied()
                .filter(|&r| r != self.strip)
                .collect();
            let sends = others.iter().map(|&r| (r, cells.clone())).collect();
            let received = if others.is_empty() {
                Vec::new()
            } else {
                links.send_receive(sends, &others)
            };
            let held = bottom.ranks.iter().zip(starts.windows(2));
            for (rows, values) in (held.filter(|(&r, _)| r != self.strip))
                .map(|(_, rows)| rows)
                .zip(received)
            {
                assert_eq!(values.len(), nx * (rows[1] - rows[0]), "gathered rows");
                self.coarse_rhs[nx * rows[0]..nx * rows[1]].copy_from_slice(&values);
            }
        }
        self.coarse_solution.fill(0.0);
        // The one cycle ends short of the zero tolerance and returns its iterate, a valid
        // correction; the outer cycles judge the convergence.
        let _ = self
            .coarse
            .solve(&self.coarse_rhs, &mut self.coarse_solution);
        let ny = *starts.last().expect("row cuts");
        level.add_whole_correction(&self.coarse_solution, ny, zero_guess);
    }
}

/// Runs `f` with `links`, or with the links of an agglomerated level's strips `neighbours`.
fn with_links<R>(
    neighbours: Option<[Option<usize>; 2]>,
    links: &mut dyn RowLinks,
    f: impl FnOnce(&mut dyn RowExchange) -> R,
) -> R {
    match neighbours {
        None => f(links),
        Some(neighbours) => f(&mut AgglomeratedLinks { links, neighbours }),
    }
}

#[cfg(test)]
mod tests;
