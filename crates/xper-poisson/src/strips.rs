//! The grid cut into horizontal strips, one per process, and one multigrid level of a strip.
//!
//! Strip `s` holds the global rows `starts[s]..starts[s + 1]` and every column. A level keeps
//! one ghost layer around its cells (padded arrays of `(nx + 2) x (rows + 2)` entries); the
//! ghost rows towards another strip (or across a periodic bottom/top) are filled by
//! [`RowLinks::exchange_rows`], the ghost columns of periodic left/right sides by a local copy.
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
    /// Every strip's `values` concatenated in strip order, on every strip.
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
    /// largest power of two `2^k` that divides `nx` and `ny`, leaves every strip at least one
    /// block of `2^k` rows, and is not beyond what brings the grid down to
    /// [`GATHERED_CELLS`]: the strips then coarsen `k` times without cutting a coarse cell.
    pub fn balanced(nx: usize, ny: usize, strips: usize) -> Result<Self, String> {
        if strips == 0 || ny < strips {
            return Err(format!(
                "{ny} rows cannot be shared among {strips} strips (at least one row each)"
            ));
        }
        let mut unit = 1;
        while nx.is_multiple_of(2 * unit)
            && ny.is_multiple_of(2 * unit)
            && ny / (2 * unit) >= strips
            && (nx / unit) * (ny / unit) > GATHERED_CELLS
        {
            unit *= 2;
        }
        let blocks = ny / unit;
        let starts = (0..=strips).map(|s| unit * (blocks * s / strips)).collect();
        Ok(StripLayout { starts })
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

/// One level of one strip: the correction `u`, the rhs `f` and the residual `r`.
pub(crate) struct StripLevel {
    pub nx: usize,
    pub rows: usize,
    /// Global index of local row 0.
    pub first_row: usize,
    pub hx: f64,
    pub hy: f64,
    pub u: Vec<f64>,
    pub f: Vec<f64>,
    pub r: Vec<f64>,
    inverse_diagonal: Vec<f64>,
    diagonal: Vec<f64>,
    /// Whether the bottom and top ghost rows come from another strip (or this one, periodic).
    linked: [bool; 2],
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
        let padded = (nx + 2) * (rows.len() + 2);
        let mut diagonal = Vec::with_capacity(nx * rows.len());
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
            for i in 0..nx {
                let s_west = if i == 0 { fold(boundary.left) } else { 0.0 };
                let s_east = if i + 1 == nx {
                    fold(boundary.right)
                } else {
                    0.0
                };
                diagonal.push(-cx * (2.0 - s_west - s_east) - cy * (2.0 - s_south - s_north));
            }
        }
        StripLevel {
            nx,
            rows: rows.len(),
            first_row: rows.start,
            hx,
            hy,
            u: vec![0.0; padded],
            f: vec![0.0; padded],
            r: vec![0.0; padded],
            inverse_diagonal: diagonal.iter().map(|d| 1.0 / d).collect(),
            diagonal,
            linked,
            boundary,
        }
    }

    #[inline]
    pub fn width(&self) -> usize {
        self.nx + 2
    }

    /// Padded index of local cell `(i, j)`, `i, j >= -1`.
    #[inline]
    pub fn index(&self, i: isize, j: isize) -> usize {
        (i + 1) as usize + self.width() * (j + 1) as usize
    }

    pub fn cells(&self) -> usize {
        self.nx * self.rows
    }

    /// Fills the ghosts of `u`: periodic columns copied, the linked rows exchanged (whole
    /// padded rows, so corners follow), the other sides' ghosts zero, or, with `reflect`, the
    /// boundary rule (`+-` the interior, for the bilinear prolongation).
    pub fn fill_ghosts(&mut self, links: &mut dyn RowLinks, reflect: bool) {
        let (nx, w) = (self.nx, self.width());
        let periodic_x = self.boundary.left == SideCondition::Periodic;
        let rule = |c: SideCondition| if reflect { fold(c) } else { 0.0 };
        let (s_left, s_right) = (rule(self.boundary.left), rule(self.boundary.right));
        for j in 0..self.rows as isize {
            let row = self.index(-1, j);
            let u = &mut self.u[row..row + w];
            if periodic_x {
                u[0] = u[nx];
                u[nx + 1] = u[1];
            } else {
                u[0] = s_left * u[1];
                u[nx + 1] = s_right * u[nx];
            }
        }
        let (low, high) = (self.index(-1, 0), self.index(-1, self.rows as isize - 1));
        let received = links.exchange_rows(
            self.linked[0].then(|| &self.u[low..low + w]),
            self.linked[1].then(|| &self.u[high..high + w]),
        );
        let [from_below, from_above] = received;
        let (below, above) = (self.index(-1, -1), self.index(-1, self.rows as isize));
        let sides = [
            (from_below, below, low, self.boundary.bottom),
            (from_above, above, high, self.boundary.top),
        ];
        for (received, ghost, inside, condition) in sides {
            match received {
                Some(row) => self.u[ghost..ghost + w].copy_from_slice(&row),
                None => {
                    let s = rule(condition);
                    for k in 0..w {
                        self.u[ghost + k] = s * self.u[inside + k];
                    }
                }
            }
        }
    }

    /// One red-black SOR sweep: the cells of colour 0 (`i + j` even, global `j`) then those of
    /// colour 1, the ghosts refreshed before each half.
    pub fn sweep(&mut self, omega: f64, links: &mut dyn RowLinks) {
        for colour in 0..2 {
            self.fill_ghosts(links, false);
            self.relax(colour, omega);
        }
    }

    fn relax(&mut self, colour: usize, omega: f64) {
        let (nx, w) = (self.nx, self.width());
        let (cx, cy) = (1.0 / (self.hx * self.hx), 1.0 / (self.hy * self.hy));
        for j in 0..self.rows {
            // The row with its two ghosts, and the rows below and above, as separate slices.
            let start = self.index(-1, j as isize);
            let (before, after) = self.u.split_at_mut(start);
            let (here, rest) = after.split_at_mut(nx + 2);
            let below = &before[start - w..start - w + nx + 2];
            let above = &rest[w - nx - 2..w];
            let f = &self.f[start + 1..start + 1 + nx];
            let inverse = &self.inverse_diagonal[nx * j..nx * (j + 1)];
            let first = (colour + self.first_row + j) % 2;
            for i in (first..nx).step_by(2) {
                let neighbours = cx * (here[i] + here[i + 2]) + cy * (below[i + 1] + above[i + 1]);
                let target = (f[i] - neighbours) * inverse[i];
                here[i + 1] += omega * (target - here[i + 1]);
            }
        }
    }

    /// `r = f - Lap u` on every cell (ghosts refreshed first); returns `sum r^2`.
    pub fn residual(&mut self, links: &mut dyn RowLinks) -> f64 {
        self.fill_ghosts(links, false);
        let (nx, w) = (self.nx, self.width());
        let (cx, cy) = (1.0 / (self.hx * self.hx), 1.0 / (self.hy * self.hy));
        let mut squares = 0.0;
        for j in 0..self.rows {
            let start = self.index(-1, j as isize);
            let u = &self.u;
            let (below, here, above) = (
                &u[start - w + 1..start - w + 1 + nx],
                &u[start..start + nx + 2],
                &u[start + w + 1..start + w + 1 + nx],
            );
            let f = &self.f[start + 1..start + 1 + nx];
            let r = &mut self.r[start + 1..start + 1 + nx];
            let diagonal = &self.diagonal[nx * j..nx * (j + 1)];
            for i in 0..nx {
                let lap = cx * (here[i] + here[i + 2])
                    + cy * (below[i] + above[i])
                    + diagonal[i] * here[i + 1];
                let value = f[i] - lap;
                r[i] = value;
                squares += value * value;
            }
        }
        squares
    }

    /// The coarse rhs: the average of `r` over the four fine cells of each coarse cell.
    pub fn restrict(&self, coarse: &mut StripLevel) {
        for jc in 0..coarse.rows {
            for ic in 0..coarse.nx {
                let k = self.index(2 * ic as isize, 2 * jc as isize);
                let w = self.width();
                let sum = self.r[k] + self.r[k + 1] + self.r[k + w] + self.r[k + w + 1];
                let kc = coarse.index(ic as isize, jc as isize);
                coarse.f[kc] = 0.25 * sum;
            }
        }
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
            for (i, u) in row.iter_mut().enumerate() {
                let ic = i / 2 + 1;
                let side = if i % 2 == 0 { ic - 1 } else { ic + 1 };
                *u += 0.5625 * near[ic] + 0.1875 * (near[side] + far[ic]) + 0.0625 * far[side];
            }
        }
    }
}
