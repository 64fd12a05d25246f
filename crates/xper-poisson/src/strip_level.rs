//! One multigrid level of one strip: the correction `u`, the rhs `f` and the residual `r` of the
//! rows `first_row..first_row + rows` of an `nx x ny` level, with one ghost column on each side
//! and `ghosts` ghost rows below and above (padded arrays of `(nx + 2) x (rows + 2 ghosts)`).
//!
//! The 5-point operator is written with the boundary rules of the Neumann and Dirichlet sides
//! folded into a per-cell diagonal (Trottenberg et al., "Multigrid", section 5.6): with the
//! ghost beyond such a side held at zero,
//!
//! ```text
//! (Lap u)_ij = cx (u_W + u_E) + cy (u_S + u_N) + D_ij u_ij,
//! D_ij = -cx (2 - s_W - s_E) - cy (2 - s_S - s_N),
//! ```
//!
//! with `cx = 1 / hx^2`, `cy = 1 / hy^2`, and `s = 1` (Neumann: ghost = interior), `-1`
//! (Dirichlet: ghost = -interior) on a folded side, `0` elsewhere. Red-black relaxation with
//! this diagonal relaxes boundary cells exactly, as the serial [`crate::Multigrid`] does.
//!
//! **Deep ghost rows.** The ghost rows towards another strip (or across a periodic bottom and
//! top) are filled by [`RowExchange::exchange_rows_overlapped`], `2 s + 1` rows of `u` and
//! `2 s` of `f` at once before `s` sweeps. The strip then relaxes its neighbours' edge rows
//! itself, one row fewer per half-sweep, so the `s` sweeps and the residual after them need
//! no other exchange: a V(2, 1) cycle exchanges twice per level (before the pre- and before the
//! post-smoothing) instead of once per sweep, once for the residual and once for the
//! prolongation. The last post-smoothing sweep leaves the ghost row next to the cells current,
//! which is what the finer level's prolongation reads. Every value a strip computes in its
//! ghost rows is the one its neighbour computes in its own rows, bit for bit, so the result is
//! that of sweeps over the whole grid. (The deep ghost zones of Williams et al., "Optimization
//! of geometric multigrid for emerging multi- and manycore processors", SC 2012, section V;
//! the redundant computation of Douglas et al., ETNA 10, 2000.)
//!
//! **Overlap.** The exchange runs while the strip relaxes the cells that do not need the
//! rows on their way (half-sweep `h` of the rows at least `h` from a linked edge,
//! [`RowExchange::exchange_rows_overlapped`]); the rows near the edges and the ghost rows are
//! relaxed once they arrive. A process slightly behind its neighbour then delays it only when
//! the lag exceeds that inner work, instead of at every exchange.
//!
//! Every strip makes the same calls in the same order: whether an exchange is needed is
//! decided from the counts of current ghost rows, which evolve alike on every strip.

mod smoothing;

use crate::strips::RowExchange;
use crate::{Boundary, MultigridParams, PoissonSide};

/// The ghost rows of a level for `params`: `2 s + 1` for the larger smoothing count `s`.
pub fn ghost_rows(params: &MultigridParams) -> usize {
    2 * params.pre_smoothing.max(params.post_smoothing) as usize + 1
}

/// The folded diagonal `D` of one row's cells: the cells `1..nx - 1`, the first and the last.
#[derive(Clone, Copy, Debug)]
struct RowDiagonal {
    interior: f64,
    first: f64,
    last: f64,
}

fn fold(condition: PoissonSide) -> f64 {
    match condition {
        PoissonSide::Neumann => 1.0,
        PoissonSide::Dirichlet => -1.0,
        PoissonSide::Periodic => 0.0,
    }
}

/// Which array of a level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Field {
    /// The correction `u`.
    Solution,
    /// The rhs `f`.
    Rhs,
    /// The residual `r`.
    Residual,
}

/// How rows written into a level meet what it holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Combine {
    /// They replace it.
    Replace,
    /// They are added to it.
    Add,
}

/// One level of one strip (see the module documentation).
pub(crate) struct StripLevel {
    pub nx: usize,
    pub rows: usize,
    /// Global index of local row 0.
    pub first_row: usize,
    cx: f64,
    cy: f64,
    pub u: Vec<f64>,
    pub f: Vec<f64>,
    pub r: Vec<f64>,
    ghosts: usize,
    /// The diagonal of local rows `-ghosts..rows + ghosts` (entry `j + ghosts`). The ghost
    /// rows' are those of a row inside the grid in y: they are relaxed only when linked, and
    /// then they and their neighbours lie in the neighbouring strip, at least `ghosts` high.
    diagonals: Vec<RowDiagonal>,
    /// Whether the bottom and top ghost rows come from another strip (or this one, periodic).
    linked: [bool; 2],
    /// How many ghost rows of `u` next to the cells, on the linked sides, hold the values the
    /// neighbours hold.
    u_current: usize,
    /// The same for `f`.
    f_current: usize,
    periodic_x: bool,
    boundary: Boundary,
}

impl StripLevel {
    pub fn new(
        nx: usize,
        ny: usize,
        rows: std::ops::Range<usize>,
        spacing: [f64; 2],
        boundary: Boundary,
        ghosts: usize,
    ) -> Self {
        let [hx, hy] = spacing;
        let (cx, cy) = (1.0 / (hx * hx), 1.0 / (hy * hy));
        let periodic_y = boundary.bottom == PoissonSide::Periodic;
        let linked = [rows.start > 0 || periodic_y, rows.end < ny || periodic_y];
        let padded = (nx + 2) * (rows.len() + 2 * ghosts);
        let (s_west, s_east) = (fold(boundary.left), fold(boundary.right));
        let diagonal = |s_south: f64, s_north: f64| {
            let y = -cy * (2.0 - s_south - s_north);
            let first = if nx == 1 { s_west + s_east } else { s_west };
            RowDiagonal {
                interior: y - 2.0 * cx,
                first: y - cx * (2.0 - first),
                last: y - cx * (2.0 - s_east),
            }
        };
        let mut diagonals = vec![diagonal(0.0, 0.0); ghosts];
        for j in rows.clone() {
            let s_south = if j == 0 && !linked[0] {
                fold(boundary.bottom)
            } else {
                0.0
            };
            let s_north = if j + 1 == ny && !linked[1] {
                fold(boundary.top)
            } else {
                0.0
            };
            diagonals.push(diagonal(s_south, s_north));
        }
        diagonals.extend(std::iter::repeat_n(diagonal(0.0, 0.0), ghosts));
        StripLevel {
            nx,
            rows: rows.len(),
            first_row: rows.start,
            cx,
            cy,
            u: vec![0.0; padded],
            f: vec![0.0; padded],
            r: vec![0.0; padded],
            ghosts,
            diagonals,
            linked,
            u_current: 0,
            f_current: 0,
            periodic_x: boundary.left == PoissonSide::Periodic,
            boundary,
        }
    }

    #[inline]
    pub fn width(&self) -> usize {
        self.nx + 2
    }

    /// Padded index of local cell `(i, j)`, `i >= -1`, `j >= -ghosts`.
    #[inline]
    pub fn index(&self, i: isize, j: isize) -> usize {
        (i + 1) as usize + self.width() * (j + self.ghosts as isize) as usize
    }

    pub fn cells(&self) -> usize {
        self.nx * self.rows
    }

    /// The most sweeps one exchange of the ghost rows allows (at least 1).
    pub fn sweeps_per_exchange(&self) -> usize {
        (self.ghosts.saturating_sub(1) / 2).max(1)
    }

    /// The padded array of `field`.
    fn field(&self, field: Field) -> &[f64] {
        match field {
            Field::Solution => &self.u,
            Field::Rhs => &self.f,
            Field::Residual => &self.r,
        }
    }

    /// The padded array of `field`, to write.
    fn field_mut(&mut self, field: Field) -> &mut [f64] {
        match field {
            Field::Solution => &mut self.u,
            Field::Rhs => &mut self.f,
            Field::Residual => &mut self.r,
        }
    }

    /// The cells of the global rows `rows` (within this strip) of `field`, row after row.
    pub fn copy_rows(&self, field: Field, rows: std::ops::Range<usize>) -> Vec<f64> {
        let values = self.field(field);
        let mut cells = Vec::with_capacity(self.nx * rows.len());
        for global in rows {
            let k = self.index(0, (global - self.first_row) as isize);
            cells.extend_from_slice(&values[k..k + self.nx]);
        }
        cells
    }

    /// Writes `cells` (whole rows, the first of them global row `first`, within this strip)
    /// into `field` as `combine` says.
    pub fn write_rows(&mut self, field: Field, first: usize, cells: &[f64], combine: Combine) {
        let nx = self.nx;
        let start = self.index(0, (first - self.first_row) as isize);
        let width = self.width();
        let values = self.field_mut(field);
        for (j, row) in cells.chunks_exact(nx).enumerate() {
            let k = start + j * width;
            let target = &mut values[k..k + nx];
            if combine == Combine::Add {
                target.iter_mut().zip(row).for_each(|(v, c)| *v += c);
            } else {
                target.copy_from_slice(row);
            }
        }
    }

    /// Records that `f` changed in the cells (its ghost rows are stale).
    pub fn rhs_changed(&mut self) {
        self.f_current = 0;
    }

    /// Records that `u` changed in the cells (its ghost rows are stale).
    pub fn solution_changed(&mut self) {
        self.u_current = 0;
    }

    /// Sets `u` to zero everywhere, ghosts included: they are then current on every strip.
    pub fn zero_solution(&mut self) {
        self.u.fill(0.0);
        self.u_current = self.ghosts;
    }

    /// Ghost columns of `u` on local rows `rows`: copies across periodic sides, else zero or,
    /// with `reflect`, the boundary rule (`+-` the interior, for the bilinear prolongation).
    fn fill_ghost_columns(&mut self, reflect: bool, rows: std::ops::Range<isize>) {
        let (nx, w) = (self.nx, self.width());
        let rule = |c: PoissonSide| if reflect { fold(c) } else { 0.0 };
        let (s_left, s_right) = (rule(self.boundary.left), rule(self.boundary.right));
        for j in rows {
            let row = self.index(-1, j);
            let u = &mut self.u[row..row + w];
            if self.periodic_x {
                u[0] = u[nx];
                u[nx + 1] = u[1];
            } else {
                u[0] = s_left * u[1];
                u[nx + 1] = s_right * u[nx];
            }
        }
    }

    /// The messages to the neighbouring strips, `[to_below, to_above]` (`None` where the
    /// side is the domain's boundary): `u_depth` edge rows of `u`, then `f_depth` of `f`, whole
    /// padded rows so the corners follow.
    fn messages(&self, u_depth: usize, f_depth: usize) -> [Option<Vec<f64>>; 2] {
        let (w, rows) = (self.width(), self.rows as isize);
        [0, 1].map(|side| {
            self.linked[side].then(|| {
                let mut values = Vec::with_capacity((u_depth + f_depth) * w);
                for (depth, field) in [(u_depth, &self.u), (f_depth, &self.f)] {
                    let first = if side == 0 { 0 } else { rows - depth as isize };
                    let start = self.index(-1, first);
                    values.extend_from_slice(&field[start..start + depth * w]);
                }
                values
            })
        })
    }

    /// Stores what the neighbours sent (their [`StripLevel::messages`]) in the ghost rows next
    /// to the cells, which are then current.
    fn store(&mut self, received: [Option<Vec<f64>>; 2], u_depth: usize, f_depth: usize) {
        let (w, rows) = (self.width(), self.rows as isize);
        for (side, values) in received.into_iter().enumerate() {
            let Some(values) = values else { continue };
            assert_eq!(
                values.len(),
                (u_depth + f_depth) * w,
                "strip rows from the neighbour {}: not the rows asked for",
                ["below", "above"][side]
            );
            let mut offset = 0;
            for (depth, of_u) in [(u_depth, true), (f_depth, false)] {
                let first = if side == 0 { -(depth as isize) } else { rows };
                let start = self.index(-1, first);
                let field = if of_u { &mut self.u } else { &mut self.f };
                field[start..start + depth * w]
                    .copy_from_slice(&values[offset..offset + depth * w]);
                offset += depth * w;
            }
        }
        if u_depth > 0 {
            self.u_current = u_depth;
        }
        if f_depth > 0 {
            self.f_current = f_depth;
        }
    }

    /// Zeroes the ghost row of `u` next to the cells on each side that is the domain's
    /// boundary (the folded diagonal holds the boundary rule).
    fn zero_boundary_ghost_rows(&mut self) {
        let (w, rows) = (self.width(), self.rows as isize);
        for (side, j) in [(0, -1), (1, rows)] {
            if !self.linked[side] {
                let start = self.index(-1, j);
                self.u[start..start + w].fill(0.0);
            }
        }
    }

    /// Exchanges `u_depth` edge rows of `u` and `f_depth` of `f` with the neighbours, which
    /// are then current in the ghost rows.
    fn exchange_ghost_rows(&mut self, links: &mut dyn RowExchange, u_depth: usize, f_depth: usize) {
        let [to_below, to_above] = self.messages(u_depth, f_depth);
        let received = links.exchange_rows(to_below.as_deref(), to_above.as_deref());
        self.zero_boundary_ghost_rows();
        self.store(received, u_depth, f_depth);
    }

    /// Makes the ghost row of `u` next to the cells current, by an exchange if it is not.
    fn refresh_next_ghost_row(&mut self, links: &mut dyn RowExchange) {
        if self.u_current == 0 {
            self.exchange_ghost_rows(links, 1, 0);
        }
    }

    /// How deep in the linked ghost rows the first red half-sweep can relax: it needs `u` one
    /// row deeper and `f` on the row.
    fn relaxable_depth(&self) -> isize {
        (self.u_current as isize - 1)
            .min(self.f_current as isize)
            .max(0)
    }

    /// Relaxes the cells of `colour` (`i + j` even or odd, global `j`) of local row `j`, then
    /// refreshes the row's periodic ghost columns.
    #[inline]
    fn relax_row(&mut self, j: isize, colour: usize, omega: f64) {
        let (nx, w) = (self.nx, self.width());
        let (cx, cy) = (self.cx, self.cy);
        let diagonal = self.diagonals[(j + self.ghosts as isize) as usize];
        let start = self.index(-1, j);
        let (before, after) = self.u.split_at_mut(start);
        let (here, rest) = after.split_at_mut(w);
        let below = &before[start - w..];
        let above = &rest[..w];
        let f = &self.f[start..start + w];
        let parity = (colour as isize + self.first_row as isize + j).rem_euclid(2) as usize;
        let keep = 1.0 - omega;
        let scale = omega / diagonal.interior;
        // The interior cells of the colour, padded index p = i + 1 for 1 <= i <= nx - 2.
        let mut p = 3 - parity;
        while p < nx {
            let neighbours = cx * (here[p - 1] + here[p + 1]) + cy * (below[p] + above[p]);
            here[p] = keep * here[p] + scale * (f[p] - neighbours);
            p += 2;
        }
        let ends = [
            (parity == 0, 1, diagonal.first),
            (nx > 1 && (nx - 1) % 2 == parity, nx, diagonal.last),
        ];
        for (relaxed, p, d) in ends {
            if relaxed {
                let neighbours = cx * (here[p - 1] + here[p + 1]) + cy * (below[p] + above[p]);
                here[p] = keep * here[p] + omega * (f[p] - neighbours) / d;
            }
        }
        if self.periodic_x {
            here[0] = here[nx];
            here[nx + 1] = here[1];
        }
    }

    /// Writes `r = f - Lap u` on local row `j` (ghosts current); returns its `sum r^2`.
    #[inline]
    fn residual_row(&mut self, j: isize) -> f64 {
        let (nx, w) = (self.nx, self.width());
        let (cx, cy) = (self.cx, self.cy);
        let diagonal = self.diagonals[(j + self.ghosts as isize) as usize];
        let start = self.index(-1, j);
        let u = &self.u[start - w..start + 2 * w];
        let (below, here, above) = (&u[..w], &u[w..2 * w], &u[2 * w..]);
        let f = &self.f[start + 1..start + 1 + nx];
        let r = &mut self.r[start + 1..start + 1 + nx];
        let d = diagonal.interior;
        let (west, centre, east) = (&here[..nx], &here[1..nx + 1], &here[2..nx + 2]);
        let (south, north) = (&below[1..nx + 1], &above[1..nx + 1]);
        for i in 0..nx {
            let lap = cx * (west[i] + east[i]) + cy * (south[i] + north[i]) + d * centre[i];
            r[i] = f[i] - lap;
        }
        // The end cells' own diagonals (with one cell, `first` holds both sides' rules).
        r[0] -= (diagonal.first - d) * centre[0];
        if nx > 1 {
            r[nx - 1] -= (diagonal.last - d) * centre[nx - 1];
        }
        let mut partial = [0.0; 4];
        let chunks = r.chunks_exact(4);
        let tail: f64 = chunks.remainder().iter().map(|v| v * v).sum();
        for chunk in chunks {
            for (p, v) in partial.iter_mut().zip(chunk) {
                *p += v * v;
            }
        }
        partial.iter().sum::<f64>() + tail
    }

    /// `r = f - Lap u` on every cell (one ghost row exchanged first if needed); returns
    /// `sum r^2`.
    pub fn residual(&mut self, links: &mut dyn RowExchange) -> f64 {
        self.fill_ghost_columns(false, 0..self.rows as isize);
        self.refresh_next_ghost_row(links);
        (0..self.rows as isize).map(|j| self.residual_row(j)).sum()
    }

    /// The start of a solve (`u` the guess, `f` the rhs as given, both changed): exchanges
    /// the ghost rows that the residual and the first `sweeps` smoothing sweeps need, in the
    /// one message the sweeps would send (so they do not exchange again), writes
    /// `r = f - Lap u` and returns this strip's `[sum f, sum f^2, sum r, sum r^2]`, from which
    /// one sum over the strips gives the mean, the rhs norm and the residual norm.
    pub fn open_solve(&mut self, links: &mut dyn RowExchange, sweeps: usize) -> [f64; 4] {
        let halves = 2 * sweeps.min(self.sweeps_per_exchange());
        self.fill_ghost_columns(false, 0..self.rows as isize);
        self.exchange_ghost_rows(links, halves + 1, halves);
        self.residual_sums()
    }

    /// Subtracts `mean` from `f` everywhere, its current ghost rows included (every strip
    /// subtracts the same value, so they stay current).
    pub fn remove_mean(&mut self, mean: f64) {
        if mean != 0.0 {
            self.f.iter_mut().for_each(|f| *f -= mean);
        }
    }

    /// Writes `r = f - Lap u` (the ghost rows current) and returns this strip's
    /// `[sum f, sum f^2, sum r, sum r^2]`.
    pub fn residual_sums(&mut self) -> [f64; 4] {
        let mut sums = [0.0; 4];
        for j in 0..self.rows as isize {
            sums[3] += self.residual_row(j);
            let k = self.index(0, j);
            for (f, r) in self.f[k..k + self.nx].iter().zip(&self.r[k..k + self.nx]) {
                sums[0] += f;
                sums[1] += f * f;
                sums[2] += r;
            }
        }
        sums
    }

    /// The coarse rhs: the average of `r` over the four fine cells of each coarse cell.
    pub fn restrict(&self, coarse: &mut StripLevel) {
        for jc in 0..coarse.rows {
            self.restrict_row_pair(jc, coarse);
        }
        coarse.rhs_changed();
    }

    /// Row `jc` of the coarse rhs from rows `2 jc` and `2 jc + 1` of `r`.
    #[inline]
    fn restrict_row_pair(&self, jc: usize, coarse: &mut StripLevel) {
        let w = self.width();
        let fine = self.index(0, 2 * jc as isize);
        let (low, high) = (&self.r[fine..fine + w], &self.r[fine + w..fine + 2 * w]);
        let kc = coarse.index(0, jc as isize);
        for (ic, f) in coarse.f[kc..kc + coarse.nx].iter_mut().enumerate() {
            let sum = low[2 * ic] + low[2 * ic + 1] + high[2 * ic] + high[2 * ic + 1];
            *f = 0.25 * sum;
        }
    }

    /// The ghosts of `u` next to the cells as the bilinear prolongation reads them: the
    /// linked rows current (exchanged if they are not), the rows beyond the domain's
    /// boundary and the ghost columns by the boundary rule (`+-` the interior).
    fn fill_ghosts_reflected(&mut self, links: &mut dyn RowExchange) {
        self.refresh_next_ghost_row(links);
        let (w, rows) = (self.width(), self.rows as isize);
        for (side, edge, ghost, condition) in [
            (0, 0, -1, self.boundary.bottom),
            (1, rows - 1, rows, self.boundary.top),
        ] {
            if !self.linked[side] {
                let (inside, outside) = (self.index(-1, edge), self.index(-1, ghost));
                let s = fold(condition);
                for k in 0..w {
                    self.u[outside + k] = s * self.u[inside + k];
                }
            }
        }
        self.fill_ghost_columns(true, -1..rows + 1);
    }

    /// Adds the bilinear interpolation of the coarse correction (its ghosts reflected) to `u`:
    /// weights 9/16, 3/16, 3/16, 1/16 of the nearest coarse centres.
    pub fn prolong(&mut self, coarse: &mut StripLevel, links: &mut dyn RowExchange) {
        coarse.fill_ghosts_reflected(links);
        let (nx, wc) = (self.nx, coarse.width());
        for j in 0..self.rows {
            // The coarse row of this fine row and the nearer of its neighbours.
            let centre = coarse.index(-1, (j / 2) as isize);
            let other = if j % 2 == 0 { centre - wc } else { centre + wc };
            let (near, far) = (&coarse.u[centre..centre + wc], &coarse.u[other..other + wc]);
            let start = self.index(0, j as isize);
            let row = &mut self.u[start..start + nx];
            for (ic, pair) in row.chunks_exact_mut(2).enumerate() {
                let (left, centre, right) = (ic, ic + 1, ic + 2);
                let common = 0.5625 * near[centre] + 0.1875 * far[centre];
                pair[0] += common + 0.1875 * near[left] + 0.0625 * far[left];
                pair[1] += common + 0.1875 * near[right] + 0.0625 * far[right];
            }
        }
        self.solution_changed();
    }

    /// Adds the rows of `whole` (a correction over the whole `nx x ny` level, the same on
    /// every strip) to the cells. With `zero_guess` (`u` was zero everywhere) the linked ghost
    /// rows next to the cells become the neighbours' rows of `whole`, current without an
    /// exchange.
    pub fn add_whole_correction(&mut self, whole: &[f64], ny: usize, zero_guess: bool) {
        let (nx, rows) = (self.nx, self.rows as isize);
        let first = self.first_row as isize;
        let add = |level: &mut Self, j: isize, global: isize| {
            let global = global.rem_euclid(ny as isize) as usize;
            let k = level.index(0, j);
            let from = nx * global;
            for (u, c) in level.u[k..k + nx].iter_mut().zip(&whole[from..from + nx]) {
                *u += c;
            }
        };
        for j in 0..rows {
            add(self, j, first + j);
        }
        if zero_guess {
            for (side, j) in [(0, -1), (1, rows)] {
                if self.linked[side] {
                    add(self, j, first + j);
                }
            }
            self.u_current = 1;
        } else {
            self.solution_changed();
        }
    }
}
