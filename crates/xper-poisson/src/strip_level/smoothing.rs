//! The smoothing of a strip level: red-black sweeps as a wavefront over the rows, with the
//! exchange of the ghost rows overlapped by the rows that do not need them (see the parent
//! module's documentation).

use super::StripLevel;
use crate::strips::RowLinks;

impl StripLevel {
    /// `sweeps` red-black SOR sweeps (all cells of colour 0, `i + j` even with global `j`, then
    /// those of colour 1), `1 <= sweeps <= (ghosts - 1) / 2`, after which the ghost rows
    /// `d + 1 - 2 sweeps` deep are current, `d` the depth of the first half-sweep below. The
    /// result is that of sweeps over the whole grid.
    ///
    /// When the ghost rows are not current for them (`2 sweeps + 1` rows of `u` and
    /// `2 sweeps` of `f`), those rows are exchanged in one message per neighbour, and the
    /// exchange overlaps the work that does not need it: half-sweep `h` (from 1) of the cells
    /// at least `h` rows from a linked edge, as a wavefront (half-sweep `h` on row `t - h + 1`
    /// at step `t`). Once the rows are in, half-sweep `h` is completed on the rows near the
    /// edges and on the neighbours' rows `d - h + 1` deep, `d` the depth the ghost rows allow
    /// ([`StripLevel::relaxable_depth`]). A process a little behind its neighbour thus delays
    /// it only when the lag exceeds that inner work.
    ///
    /// With `residual`, also writes `r` on the cells (each row as soon as its neighbours are
    /// final) and returns `sum r^2` over the strip; else returns 0. With `coarse` as well, each
    /// pair of residual rows is restricted into it as soon as written, while in cache.
    pub fn smooth(
        &mut self,
        links: &mut dyn RowLinks,
        omega: f64,
        sweeps: usize,
        residual: bool,
        mut coarse: Option<&mut StripLevel>,
    ) -> f64 {
        debug_assert!(sweeps >= 1 && 2 * sweeps < self.ghosts + 1);
        let rows = self.rows as isize;
        let halves = 2 * sweeps;
        let (need_u, need_f) = (2 * sweeps + 1, 2 * sweeps);
        self.fill_ghost_columns(false, 0..rows);
        self.zero_boundary_ghost_rows();
        let u_depth = if self.u_current >= need_u { 0 } else { need_u };
        let f_depth = if self.f_current >= need_f { 0 } else { need_f };
        let exchanging = u_depth + f_depth > 0;
        // Rows of half-sweep `h` (index h - 1): with the ghosts `depth` deep current, or with
        // no ghost row at all (`depth` None).
        let linked = self.linked;
        let range = move |h: usize, depth: Option<isize>| {
            let reach = match depth {
                Some(d) => d - h as isize + 1,
                None => -(h as isize),
            };
            let low = if linked[0] { -reach } else { 0 };
            let high = if linked[1] {
                rows - 1 + reach
            } else {
                rows - 1
            };
            (low, high)
        };
        let depth_now = (!exchanging).then(|| self.relaxable_depth());
        let first: Vec<(isize, isize)> = (1..=halves).map(|h| range(h, depth_now)).collect();
        // The residual rows the first phase can finish: their neighbours relaxed by every
        // half-sweep; with a restriction, whole pairs of rows.
        let (last_low, last_high) = first[halves - 1];
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
        let residual_rows = (low, high);
        let mut squares = 0.0;
        let [to_below, to_above] = if exchanging {
            self.messages(u_depth, f_depth)
        } else {
            [None, None]
        };
        let mut phase = |level: &mut Self| {
            squares += level.wavefront(
                omega,
                &first,
                residual.then_some(residual_rows),
                &mut coarse,
            )
        };
        if exchanging {
            let received = links.exchange_rows_overlapped(
                to_below.as_deref(),
                to_above.as_deref(),
                &mut || phase(self),
            );
            self.store(received, u_depth, f_depth);
        } else {
            phase(self);
        }
        let depth = self.relaxable_depth();
        debug_assert!(
            !linked.contains(&true) || depth >= halves as isize - 1 + residual as isize,
            "{sweeps} sweeps with {} ghost rows of u and {} of f current",
            self.u_current,
            self.f_current
        );
        if exchanging {
            for (k, &(inner_low, inner_high)) in first.iter().enumerate() {
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
