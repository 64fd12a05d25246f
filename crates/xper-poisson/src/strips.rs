//! The grid cut into horizontal strips, one per process, and one multigrid level of a strip.
//!
//! Strip `s` holds the global rows `starts[s]..starts[s + 1]` and every column. A level keeps
//! one ghost column on each side and two ghost rows below and above its cells (padded arrays
//! of `(nx + 2) x (rows + 4)` entries); the ghost rows towards another strip (or across a
//! periodic bottom/top) are filled by [`RowLinks::exchange_rows`], the ghost columns of
//! periodic left/right sides by a local copy.
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

use crate::{Boundary, SideCondition};

/// What a strip needs from the processes holding the other strips.
///
/// Strip `s`'s neighbour below is `s - 1` (the last strip for `s = 0` when the bottom and top
/// are periodic) and its neighbour above `s + 1` (the first strip for the last one when
/// periodic). Every strip makes the same calls in the same order.
pub trait RowLinks {
    /// Sends `to_below` to the strip below and `to_above` to the strip above (`None` where
    /// this side is the domain's boundary) and returns what they sent here: `[from_below,
    /// from_above]`, the row the strip below sent up and the row the strip above sent down.
    fn exchange_rows(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
    ) -> [Option<Vec<f64>>; 2];
    /// Replaces each value by its sum over the strips (the same bits on every strip).
    fn sum(&mut self, values: &mut [f64]);
    /// Every strip's `values` concatenated in strip order, on every strip. Every strip passes
    /// the same number of values (so one fixed-size collective can carry them).
    fn gather(&mut self, values: &[f64]) -> Vec<f64>;
}

/// The links of a grid held whole by one process: periodic sides link the strip to itself.
#[derive(Clone, Copy, Debug, Default)]
pub struct OneStrip;

impl RowLinks for OneStrip {
    fn exchange_rows(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
    ) -> [Option<Vec<f64>>; 2] {
        [to_above.map(<[f64]>::to_vec), to_below.map(<[f64]>::to_vec)]
    }
    fn sum(&mut self, _values: &mut [f64]) {}
    fn gather(&mut self, values: &[f64]) -> Vec<f64> {
        values.to_vec()
    }
}

/// The rows of each strip: strip `s` holds `starts[s]..starts[s + 1]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StripLayout {
    /// `strips + 1` increasing row boundaries from 0 to `ny`.
    pub starts: Vec<usize>,
}

/// Coarse grids at most this large are gathered and solved whole on every strip.
pub const GATHERED_CELLS: usize = 1024;

impl StripLayout {
    /// `strips` strips of nearly equal height over an `nx x ny` grid, cut at multiples of the
    /// largest power of two `2^k` that divides `nx` and `ny`, leaves every strip at least
    /// [`MIN_STRIP_ROWS`] blocks of `2^k` rows, and is not beyond what brings the grid down to
    /// [`GATHERED_CELLS`]: the strips then coarsen `k` times without cutting a coarse cell.
    pub fn balanced(nx: usize, ny: usize, strips: usize) -> Result<Self, String> {
        let unit = Self::unit_rows(nx, ny, strips)?;
        let blocks = ny / unit;
        let starts = (0..=strips).map(|s| unit * (blocks * s / strips)).collect();
        Ok(StripLayout { starts })
    }

    /// `strips` strips over an `nx x ny` grid cut where [`StripLayout::balanced`] may cut, so
    /// that the strips carry nearly equal sums of `row_weight` (one non-negative weight per
    /// row: the work of the row), each keeping at least [`MIN_STRIP_ROWS`] blocks. Each cut is
    /// the block boundary nearest to its share of the total weight, so the shares are equal
    /// to within half a block's weight. Weights all zero give the balanced strips.
    pub fn weighted(
        nx: usize,
        ny: usize,
        strips: usize,
        row_weight: &[f64],
    ) -> Result<Self, String> {
        if row_weight.len() != ny || !row_weight.iter().all(|w| *w >= 0.0 && w.is_finite()) {
            return Err(format!(
                "{} row weights for {ny} rows, or a weight negative or not finite",
                row_weight.len()
            ));
        }
        let unit = Self::unit_rows(nx, ny, strips)?;
        let blocks = ny / unit;
        // before[b]: the weight of blocks 0..b.
        let mut before = vec![0.0; blocks + 1];
        for b in 0..blocks {
            before[b + 1] = before[b] + row_weight[b * unit..(b + 1) * unit].iter().sum::<f64>();
        }
        let total = before[blocks];
        if total == 0.0 {
            return Self::balanced(nx, ny, strips);
        }
        let mut starts = vec![0; strips + 1];
        let mut cut = 0;
        for (s, start) in starts.iter_mut().enumerate().take(strips).skip(1) {
            let share = total * s as f64 / strips as f64;
            let mut b = before.partition_point(|&w| w < share).min(blocks);
            if b > 0 && share - before[b - 1] < before[b] - share {
                b -= 1;
            }
            let lowest = cut + MIN_STRIP_ROWS;
            let highest = blocks - (strips - s) * MIN_STRIP_ROWS;
            cut = b.clamp(lowest, highest);
            *start = unit * cut;
        }
        starts[strips] = ny;
        Ok(StripLayout { starts })
    }

    /// The rows of the blocks strips are cut in: the largest power of two `2^k` dividing `nx`
    /// and `ny` that leaves every strip at least [`MIN_STRIP_ROWS`] blocks and does not coarsen
    /// beyond [`GATHERED_CELLS`].
    fn unit_rows(nx: usize, ny: usize, strips: usize) -> Result<usize, String> {
        if strips == 0 || ny < MIN_STRIP_ROWS * strips {
            return Err(format!(
                "{ny} rows cannot be shared among {strips} strips (at least {MIN_STRIP_ROWS} rows each)"
            ));
        }
        let mut unit = 1;
        while nx.is_multiple_of(2 * unit)
            && ny.is_multiple_of(2 * unit)
            && ny / (2 * unit) >= MIN_STRIP_ROWS * strips
            && (nx / unit) * (ny / unit) > GATHERED_CELLS
        {
            unit *= 2;
        }
        Ok(unit)
    }

    /// Number of strips.
    pub fn strips(&self) -> usize {
        self.starts.len() - 1
    }

    /// The global rows of strip `s`.
    pub fn rows(&self, s: usize) -> std::ops::Range<usize> {
        self.starts[s]..self.starts[s + 1]
    }
}

/// Ghost rows on each side of a strip level. Two let a strip, after one exchange, compute the
/// red half-sweep of its neighbours' edge rows itself, so a red-black sweep needs one exchange
/// instead of one per colour (the redundant-computation halo of Douglas et al., "Cache
/// optimization for structured and unstructured grid multigrid", ETNA 10, 2000).
const GHOST_ROWS: usize = 2;

/// Strips at least this many rows high on every level, so the two ghost rows of a strip come
/// from its neighbour alone.
pub const MIN_STRIP_ROWS: usize = GHOST_ROWS;

/// The folded diagonal `D` of one row's cells: the cells `1..nx - 1`, the first and the last.
#[derive(Clone, Copy, Debug)]
struct RowDiagonal {
    interior: f64,
    first: f64,
    last: f64,
}

/// One level of one strip: the correction `u`, the rhs `f` and the residual `r`, padded with
/// one ghost column on each side and [`GHOST_ROWS`] ghost rows below and above.
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
    /// The diagonal of local rows `-1..=rows` (entry `j + 1`). The ghost rows' are those of a
    /// row inside the grid in y: they are relaxed only when linked, and then their other
    /// neighbour lies in the same neighbouring strip.
    diagonals: Vec<RowDiagonal>,
    /// Whether the bottom and top ghost rows come from another strip (or this one, periodic).
    linked: [bool; 2],
    /// Whether the ghost rows next to the cells hold the neighbours' current `f` (needed to
    /// relax the ghost rows); cleared by [`StripLevel::rhs_changed`].
    rhs_ghosts_current: bool,
    periodic_x: bool,
    boundary: Boundary,
}

fn fold(condition: SideCondition) -> f64 {
    match condition {
        SideCondition::Neumann => 1.0,
        SideCondition::Dirichlet => -1.0,
        SideCondition::Periodic => 0.0,
    }
}

impl StripLevel {
    pub fn new(
        nx: usize,
        ny: usize,
        rows: std::ops::Range<usize>,
        spacing: [f64; 2],
        boundary: Boundary,
    ) -> Self {
        let [hx, hy] = spacing;
        let (cx, cy) = (1.0 / (hx * hx), 1.0 / (hy * hy));
        let periodic_y = boundary.bottom == SideCondition::Periodic;
        let linked = [rows.start > 0 || periodic_y, rows.end < ny || periodic_y];
        let padded = (nx + 2) * (rows.len() + 2 * GHOST_ROWS);
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
        let mut diagonals = vec![diagonal(0.0, 0.0)];
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
        diagonals.push(diagonal(0.0, 0.0));
        StripLevel {
            nx,
            rows: rows.len(),
            first_row: rows.start,
            cx,
            cy,
            u: vec![0.0; padded],
            f: vec![0.0; padded],
            r: vec![0.0; padded],
            diagonals,
            linked,
            rhs_ghosts_current: false,
            periodic_x: boundary.left == SideCondition::Periodic,
            boundary,
        }
    }

    #[inline]
    pub fn width(&self) -> usize {
        self.nx + 2
    }

    /// Padded index of local cell `(i, j)`, `i >= -1`, `j >= -GHOST_ROWS`.
    #[inline]
    pub fn index(&self, i: isize, j: isize) -> usize {
        (i + 1) as usize + self.width() * (j + GHOST_ROWS as isize) as usize
    }

    pub fn cells(&self) -> usize {
        self.nx * self.rows
    }

    /// Ghost columns of every row of `u`: copies across periodic sides, else zero or, with
    /// `reflect`, the boundary rule (`+-` the interior, for the bilinear prolongation).
    fn fill_ghost_columns(&mut self, reflect: bool) {
        let (nx, w) = (self.nx, self.width());
        let rule = |c: SideCondition| if reflect { fold(c) } else { 0.0 };
        let (s_left, s_right) = (rule(self.boundary.left), rule(self.boundary.right));
        for j in 0..self.rows as isize {
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

    /// Fills `depth` ghost rows on each side of `u`: the linked ones exchanged with the
    /// neighbouring strips (whole padded rows, so corners follow), the others zero or, with
    /// `reflect` (depth 1), the boundary rule applied to the edge row. With `rhs`, the same
    /// messages also carry the edge row of `f` into the ghost row of `f` next to the cells.
    fn exchange_ghost_rows(
        &mut self,
        links: &mut dyn RowLinks,
        depth: usize,
        reflect: bool,
        rhs: bool,
    ) {
        let (w, rows) = (self.width(), self.rows as isize);
        let depth_rows = depth as isize;
        let (low, high) = (self.index(-1, 0), self.index(-1, rows - depth_rows));
        // With `rhs` the messages are built (rows of `u`, then the edge row of `f`); else the
        // rows of `u` go as they lie.
        let with_rhs = |start: usize, edge: isize| {
            let mut values = self.u[start..start + depth * w].to_vec();
            let edge = self.index(-1, edge);
            values.extend_from_slice(&self.f[edge..edge + w]);
            values
        };
        let built = [
            (rhs && self.linked[0]).then(|| with_rhs(low, 0)),
            (rhs && self.linked[1]).then(|| with_rhs(high, rows - 1)),
        ];
        let [to_below, to_above] = [(0, low), (1, high)].map(|(side, start)| {
            let rows_only = &self.u[start..start + depth * w];
            self.linked[side].then(|| built[side].as_deref().unwrap_or(rows_only))
        });
        let [from_below, from_above] = links.exchange_rows(to_below, to_above);
        let edges = [
            (
                from_below,
                self.index(-1, -depth_rows),
                self.index(-1, -1),
                0,
                self.boundary.bottom,
            ),
            (
                from_above,
                self.index(-1, rows),
                self.index(-1, rows),
                rows - 1,
                self.boundary.top,
            ),
        ];
        for (received, ghost, f_ghost, edge, condition) in edges {
            match received {
                Some(values) => {
                    let (u, f) = values.split_at(depth * w);
                    self.u[ghost..ghost + depth * w].copy_from_slice(u);
                    if rhs {
                        self.f[f_ghost..f_ghost + w].copy_from_slice(f);
                    }
                }
                None => {
                    let s = if reflect { fold(condition) } else { 0.0 };
                    let inside = self.index(-1, edge);
                    let near = if ghost < inside {
                        ghost + (depth - 1) * w
                    } else {
                        ghost
                    };
                    self.u[ghost..ghost + depth * w].fill(0.0);
                    for k in 0..w {
                        self.u[near + k] = s * self.u[inside + k];
                    }
                }
            }
        }
    }

    /// Records that `f` changed, so the next sweep also exchanges the edge rows of `f`.
    pub fn rhs_changed(&mut self) {
        self.rhs_ghosts_current = false;
    }

    /// Fills the ghost rows of `u` two deep for a sweep, and those of `f` next to the cells
    /// when `f` changed since the last sweep.
    fn exchange_for_sweep(&mut self, links: &mut dyn RowLinks) {
        let rhs = !self.rhs_ghosts_current;
        self.exchange_ghost_rows(links, GHOST_ROWS, false, rhs);
        self.rhs_ghosts_current = true;
    }

    /// Fills the ghosts of `u` next to the cells (one row or column deep).
    pub fn fill_ghosts(&mut self, links: &mut dyn RowLinks, reflect: bool) {
        self.fill_ghost_columns(reflect);
        self.exchange_ghost_rows(links, 1, reflect, false);
    }

    /// Relaxes the cells of `colour` (`i + j` even or odd, global `j`) of local row `j`, then
    /// refreshes the row's periodic ghost columns.
    #[inline]
    fn relax_row(&mut self, j: isize, colour: usize, omega: f64) {
        let (nx, w) = (self.nx, self.width());
        let (cx, cy) = (self.cx, self.cy);
        let diagonal = self.diagonals[(j + 1) as usize];
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
        let diagonal = self.diagonals[(j + 1) as usize];
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

    /// One red-black SOR sweep (all cells of colour 0, `i + j` even with global `j`, then
    /// those of colour 1) after one exchange of two rows with each neighbour: the strip first
    /// relaxes the red cells of its two linked ghost rows (their neighbours are all present),
    /// then pipelines red on row `s` with black on row `s - 1`. The result is that of a sweep
    /// over the whole grid.
    ///
    /// With `residual`, also writes `r` (the inner rows within the sweep, the edge rows after
    /// one more exchange of one row) and returns `sum r^2` over the strip; else returns 0.
    pub fn sweep(&mut self, omega: f64, links: &mut dyn RowLinks, residual: bool) -> f64 {
        let rows = self.rows as isize;
        self.fill_ghost_columns(false);
        self.exchange_for_sweep(links);
        if self.linked[0] {
            self.relax_row(-1, 0, omega);
        }
        if self.linked[1] {
            self.relax_row(rows, 0, omega);
        }
        let mut squares = 0.0;
        for s in 0..rows + 2 {
            if s < rows {
                self.relax_row(s, 0, omega);
            }
            if (1..=rows).contains(&s) {
                self.relax_row(s - 1, 1, omega);
            }
            if residual && (3..=rows).contains(&s) {
                squares += self.residual_row(s - 2);
            }
        }
        if residual {
            self.exchange_ghost_rows(links, 1, false, false);
            squares += self.residual_row(0);
            if rows > 1 {
                squares += self.residual_row(rows - 1);
            }
        }
        squares
    }

    /// `r = f - Lap u` on every cell (ghosts refreshed first); returns `sum r^2`.
    pub fn residual(&mut self, links: &mut dyn RowLinks) -> f64 {
        self.fill_ghosts(links, false);
        (0..self.rows as isize).map(|j| self.residual_row(j)).sum()
    }

    /// The coarse rhs: the average of `r` over the four fine cells of each coarse cell.
    pub fn restrict(&self, coarse: &mut StripLevel) {
        let w = self.width();
        for jc in 0..coarse.rows {
            let fine = self.index(0, 2 * jc as isize);
            let (low, high) = (&self.r[fine..fine + w], &self.r[fine + w..fine + 2 * w]);
            let kc = coarse.index(0, jc as isize);
            for (ic, f) in coarse.f[kc..kc + coarse.nx].iter_mut().enumerate() {
                let sum = low[2 * ic] + low[2 * ic + 1] + high[2 * ic] + high[2 * ic + 1];
                *f = 0.25 * sum;
            }
        }
        coarse.rhs_changed();
    }

    /// Adds the bilinear interpolation of the coarse correction (its ghosts reflected) to `u`:
    /// weights 9/16, 3/16, 3/16, 1/16 of the nearest coarse centres.
    pub fn prolong(&mut self, coarse: &mut StripLevel, links: &mut dyn RowLinks) {
        coarse.fill_ghosts(links, true);
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
    }
}
