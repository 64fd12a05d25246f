//! The smoothing of a strip level: red-black sweeps as a wavefront over the rows, with the
//! exchange of the ghost rows overlapped by the rows that do not need them (see the parent
//! module's documentation).

use super::StripLevel;
use crate::strips::RowExchange;

impl StripLevel {
    /// `sweeps` red-black SOR sweeps (all cells of colour 0, `i + j` even with global `j`, then
    /// those of colour 1), in groups of at most [`StripLevel::sweeps_per_exchange`], each
    /// after one exchange of the ghost rows it needs; the ghost row next to the cells is
    /// current after. The result is that of sweeps over the whole grid.
    ///
    /// With `residual`, also writes `r` on the cells (each row as soon as its neighbours are
    /// final; with no sweep, after one exchange) and returns `sum r^2` over the strip; else
    /// returns 0. With `coarse` as well, each pair of residual rows is restricted into it as
    /// soon as written, while in cache.
    pub fn smooth(
        &mut self,
        links: &mut dyn RowExchange,
        omega: f64,
        sweeps: usize,
        residual: bool,
        mut coarse: Option<&mut StripLevel>,
    ) -> f64 {
        if sweeps == 0 {
            if !residual {
                return 0.0;
            }
            let squares = self.residual(links);
            if let Some(coarse) = coarse {
                self.restrict(coarse);
            }
            return squares;
        }
        let group = self.sweeps_per_exchange();
        let (mut left, mut squares) = (sweeps, 0.0);
        while left > 0 {
            let now = left.min(group);
            left -= now;
            let last = left == 0;
            let into = if last { coarse.take() } else { None };
            squares = self.smooth_group(links, omega, now, residual && last, into);
        }
        squares
    }

    /// `sweeps` sweeps after one exchange, `1 <= sweeps <= (ghosts - 1) / 2`, after which the
    /// ghost rows `d + 1 - 2 sweeps` deep are current, `d` the depth the ghost rows allow the
    /// first half-sweep ([`StripLevel::relaxable_depth`]).
    ///
    /// The rows the sweeps need (`2 sweeps + 1` of `u` and `2 sweeps` of `f`, those not
    /// current already) are exchanged in one message per neighbour, and the exchange overlaps
    /// the work that does not need them: half-sweep `h` (from 1) of the cells at least `h`
    /// rows from a linked edge, as a wavefront (half-sweep `h` on row `t - h + 1` at step `t`).
    /// Once the rows are in, half-sweep `h` is completed on the rows near the edges and on the
    /// neighbours' rows `d - h + 1` deep. A process a little behind its neighbour thus delays
    /// it only when the lag exceeds that inner work.
    fn smooth_group(
        &mut self,
        links: &mut dyn RowExchange,
        omega: f64,
        sweeps: usize,
        residual: bool,
        mut coarse: Option<&mut StripLevel>,
    ) -> f64 {
        debug_assert!(sweeps >= 1 && 2 * sweeps < self.ghosts + 1);
        let rows = self.rows as isize;
        let halves = 2 * sweeps;
        self.fill_ghost_columns(false, 0..rows);
        self.zero_boundary_ghost_rows();
        let u_depth = if self.u_current > halves {
            0
        } else {
            halves + 1
        };
        let f_depth = if self.f_current >= halves { 0 } else { halves };
        let linked = self.linked;
        // The rows of half-sweep `h` before the exchange (at least `h` from a linked edge)
        // and, with the ghost rows `d` deep current, after it.
        let range = move |h: usize, depth: Option<isize>| {
            let reach = depth.map_or(-(h as isize), |d| d - h as isize + 1);
            let low = if linked[0] { -reach } else { 0 };
            let high = if linked[1] {
                rows - 1 + reach
            } else {
                rows - 1
            };
            (low, high)
        };
        let inner: Vec<(isize, isize)> = (1..=halves).map(|h| range(h, None)).collect();
        // The residual rows the inner work can finish: their neighbours relaxed by every
        // half-sweep; with a restriction, whole pairs of rows.
        let (last_low, last_high) = inner[halves - 1];
        let mut low = if linked[0] { (last_low + 1).max(0) } else { 0 };
        let mut high = if linked[1] {
            (last_high - 1).min(rows - 1)
        } else {
            rows - 1
        };
        if coarse.is_some() {
            low += low.rem_euclid(2);
            high -= (high + 1).rem_euclid(2);
        }
        let mut squares = 0.0;
        let rows_done = residual.then_some((low, high));
        if u_depth == 0 && f_depth == 0 {
            // Every row needed is current (the solve's opening exchange sent them).
            squares += self.wavefront(omega, &inner, rows_done, &mut coarse);
        } else {
            let [to_below, to_above] = self.messages(u_depth, f_depth);
            let received = links.exchange_rows_overlapped(
                to_below.as_deref(),
                to_above.as_deref(),
                &mut || squares += self.wavefront(omega, &inner, rows_done, &mut coarse),
            );
            self.store(received, u_depth, f_depth);
        }
        let depth = self.relaxable_depth();
        debug_assert!(
            !linked.contains(&true) || depth >= halves as isize - 1 + residual as isize,
            "{sweeps} sweeps with {} ghost rows of u and {} of f current",
            self.u_current,
            self.f_current
        );
        for (k, &(inner_low, inner_high)) in inner.iter().enumerate() {
            let (full_low, full_high) = range(k + 1, Some(depth));
            let colour = k % 2;
            if inner_low > inner_high {
                (full_low..=full_high).for_each(|j| self.relax_row(j, colour, omega));
            } else {
                (full_low..inner_low).for_each(|j| self.relax_row(j, colour, omega));
                (inner_high + 1..=full_high).for_each(|j| self.relax_row(j, colour, omega));
            }
        }
        if residual {
            let rest = if low > high {
                [0..rows, 0..0]
            } else {
                [0..low, high + 1..rows]
            };
            for j in rest.into_iter().flatten() {
                squares += self.residual_and_restriction(j, coarse.as_deref_mut());
            }
        }
        if let Some(coarse) = coarse {
            coarse.rhs_changed();
        }
        self.u_current = (depth + 1 - halves as isize).max(0) as usize;
        squares
    }

    /// Half-sweep `k + 1` on the rows `ranges[k]` (colour `k % 2`), as a wavefront: at step
    /// `t`, half-sweep `k + 1` on row `t - k`, then the residual of row `t - ranges.len()`
    /// when within `residual_rows`. Returns the residual's `sum r^2`.
    fn wavefront(
        &mut self,
        omega: f64,
        ranges: &[(isize, isize)],
        residual_rows: Option<(isize, isize)>,
        coarse: &mut Option<&mut StripLevel>,
    ) -> f64 {
        let halves = ranges.len() as isize;
        let start = ranges[0].0;
        let end = ranges
            .iter()
            .enumerate()
            .map(|(k, r)| r.1 + k as isize)
            .chain(residual_rows.map(|r| r.1 + halves))
            .max()
            .unwrap_or(start);
        let mut squares = 0.0;
        for t in start..=end {
            for (k, &(low, high)) in ranges.iter().enumerate() {
                let j = t - k as isize;
                if low <= j && j <= high {
                    self.relax_row(j, k % 2, omega);
                }
            }
            if let Some((low, high)) = residual_rows {
                let j = t - halves;
                if low <= j && j <= high {
                    squares += self.residual_and_restriction(j, coarse.as_deref_mut());
                }
            }
        }
        squares
    }

    /// [`StripLevel::residual_row`], then with `coarse` and an odd row `j`, the restriction of
    /// rows `j - 1` and `j` into it.
    #[inline]
    fn residual_and_restriction(&mut self, j: isize, coarse: Option<&mut StripLevel>) -> f64 {
        let squares = self.residual_row(j);
        if let Some(coarse) = coarse {
            if j % 2 == 1 {
                self.restrict_row_pair((j / 2) as usize, coarse);
            }
        }
        squares
    }
}
