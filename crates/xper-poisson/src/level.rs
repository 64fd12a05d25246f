//! One grid of the hierarchy: padded arrays with one ghost layer, the ghost filling, the
//! red-black smoother and the residual.
//!
//! Cell `(i, j)`, `i` in `0..nx`, `j` in `0..ny`, is entry `(i + 1) + (nx + 2) (j + 1)` of a
//! padded array. The Neumann and Dirichlet rules are folded into the stencil coefficients of
//! the boundary cells (a Neumann face has coefficient 0; a Dirichlet face, ghost `-phi`, has
//! coefficient `2 / h^2` against a zero ghost), so those ghosts stay zero and the smoother
//! relaxes boundary cells exactly. Periodic ghosts are copies of the opposite cells, written by
//! [`Level::fill_ghosts_x`] and [`Level::fill_ghosts_y`] only: a distributed version exchanges
//! halos there instead.

use crate::{Boundary, PoissonSide};

/// Stencil coefficients of one row: `cx` between interior neighbours along x, `west` and
/// `east` of the first and last cell, `south` and `north` of every cell of the row.
#[derive(Clone, Copy)]
struct RowStencil {
    cx: f64,
    west: f64,
    east: f64,
    south: f64,
    north: f64,
}

impl RowStencil {
    /// The sum of the coefficients of cell `i` of a row of `n` cells (the negated diagonal).
    #[inline]
    fn diagonal(&self, n: usize, i: usize) -> f64 {
        let w = if i == 0 { self.west } else { self.cx };
        let e = if i + 1 == n { self.east } else { self.cx };
        w + e + self.south + self.north
    }
}

/// The Gauss-Seidel value of end cell `i` (0 or `n - 1`) of a row: `dn`, `cur`, `up` the
/// padded rows `j - 1`, `j`, `j + 1`, `f` the padded rhs row.
#[inline]
fn end_value(
    k: &RowStencil,
    n: usize,
    i: usize,
    dn: &[f64],
    cur: &[f64],
    up: &[f64],
    f: &[f64],
) -> f64 {
    let w = if i == 0 { k.west } else { k.cx };
    let e = if i + 1 == n { k.east } else { k.cx };
    (w * cur[i] + e * cur[i + 2] + k.south * dn[i + 1] + k.north * up[i + 1] - f[i + 1])
        / k.diagonal(n, i)
}

/// Receives the residual of a row (row index, `nx` values).
pub(crate) type RowSink<'a> = &'a mut dyn FnMut(usize, &[f64]);

/// A level: sizes, coefficients, the padded solution `u` and right-hand side `f`, row buffers.
pub(crate) struct Level {
    pub nx: usize,
    pub ny: usize,
    pub hx: f64,
    pub hy: f64,
    periodic_x: bool,
    periodic_y: bool,
    cx: f64,
    cy: f64,
    /// Face coefficients of the four sides (`cx` or `cy` if periodic, 0 Neumann, twice for
    /// Dirichlet).
    sides: [f64; 4],
    /// The solution (or correction on coarse levels), padded.
    pub u: Vec<f64>,
    /// The right-hand side, padded.
    pub f: Vec<f64>,
    /// Row buffer, `nx` long: the coarse row of the restriction into this level.
    pub row: Vec<f64>,
    /// Residual row, `nx` long.
    res: Vec<f64>,
}

/// The coefficient of a boundary face of a direction with `n` cells and interior
/// coefficient `c`.
fn face_coefficient(condition: PoissonSide, c: f64, n: usize) -> f64 {
    match condition {
        PoissonSide::Neumann => 0.0,
        PoissonSide::Dirichlet => 2.0 * c,
        // With one cell the periodic neighbour is the cell itself: no coupling.
        PoissonSide::Periodic if n == 1 => 0.0,
        PoissonSide::Periodic => c,
    }
}

impl Level {
    pub fn new(nx: usize, ny: usize, hx: f64, hy: f64, boundary: &Boundary) -> Self {
        let (cx, cy) = (1.0 / (hx * hx), 1.0 / (hy * hy));
        let size = (nx + 2) * (ny + 2);
        Level {
            nx,
            ny,
            hx,
            hy,
            periodic_x: boundary.left == PoissonSide::Periodic,
            periodic_y: boundary.bottom == PoissonSide::Periodic,
            cx,
            cy,
            sides: [
                face_coefficient(boundary.left, cx, nx),
                face_coefficient(boundary.right, cx, nx),
                face_coefficient(boundary.bottom, cy, ny),
                face_coefficient(boundary.top, cy, ny),
            ],
            u: vec![0.0; size],
            f: vec![0.0; size],
            row: vec![0.0; nx],
            res: vec![0.0; nx],
        }
    }

    pub fn cells(&self) -> usize {
        self.nx * self.ny
    }

    /// Row stride of the padded arrays.
    #[inline]
    pub fn stride(&self) -> usize {
        self.nx + 2
    }

    /// Padded index of the first cell of row `j`.
    #[inline]
    pub fn row_start(&self, j: usize) -> usize {
        1 + self.stride() * (j + 1)
    }

    fn stencil(&self, j: usize) -> RowStencil {
        let cx = if self.nx == 1 { 0.0 } else { self.cx };
        RowStencil {
            cx,
            west: self.sides[0],
            east: self.sides[1],
            south: if j == 0 { self.sides[2] } else { self.cy },
            north: if j + 1 == self.ny {
                self.sides[3]
            } else {
                self.cy
            },
        }
    }

    /// Periodic ghosts of row `j` of `u` (x direction).
    #[inline]
    pub fn fill_ghosts_x(&mut self, j: usize) {
        if self.periodic_x {
            let s = self.row_start(j);
            let n = self.nx;
            self.u[s - 1] = self.u[s + n - 1];
            self.u[s + n] = self.u[s];
        }
    }

    /// Periodic ghost row below row 0 of `u` (a copy of row `ny - 1`).
    #[inline]
    fn fill_ghost_row_below(&mut self) {
        if self.periodic_y {
            let w = self.stride();
            let top = w * self.ny;
            self.u.copy_within(top..top + w, 0);
        }
    }

    /// Periodic ghost row above row `ny - 1` of `u` (a copy of row 0).
    #[inline]
    fn fill_ghost_row_above(&mut self) {
        if self.periodic_y {
            let w = self.stride();
            self.u.copy_within(w..2 * w, w * (self.ny + 1));
        }
    }

    /// Periodic ghost rows of `u` (y direction).
    #[inline]
    pub fn fill_ghosts_y(&mut self) {
        self.fill_ghost_row_below();
        self.fill_ghost_row_above();
    }

    /// All ghosts of `u`.
    pub fn fill_ghosts(&mut self) {
        for j in 0..self.ny {
            self.fill_ghosts_x(j);
        }
        self.fill_ghosts_y();
    }

    /// The rows `j - 1`, `j` (mutable) and `j + 1` of `u` and row `j` of `f`, padded.
    #[inline]
    fn rows_mut(&mut self, j: usize) -> (&[f64], &mut [f64], &[f64], &[f64]) {
        let w = self.stride();
        let (below, rest) = self.u.split_at_mut(w * (j + 1));
        let (centre, above) = rest.split_at_mut(w);
        let f = &self.f[w * (j + 1)..w * (j + 2)];
        (&below[w * j..], centre, &above[..w], f)
    }

    /// Relaxes the cells of colour `colour` (`(i + j) % 2 == colour`) of row `j`.
    fn relax_row(&mut self, j: usize, colour: usize, omega: f64) {
        self.fill_ghosts_x(j);
        let n = self.nx;
        let k = self.stencil(j);
        let periodic_x = self.periodic_x;
        let (dn, cur, up, f) = self.rows_mut(j);
        let first = (colour + j) % 2;
        // The interior cells of the colour (1 <= i <= n - 2), in padded indices p = i + 1. A
        // direct stride-2 loop measured faster than computing the whole row contiguously and
        // writing back one cell in two (8.5e8 against 6.5e8 cells/s on 1024^2).
        let scale = omega / (2.0 * k.cx + k.south + k.north);
        let keep = 1.0 - omega;
        let (dn, cur, up, f) = (&dn[..n + 2], &mut cur[..n + 2], &up[..n + 2], &f[..n + 2]);
        let mut p = if first == 0 { 3 } else { 2 };
        while p < n {
            let sum = k.cx * (cur[p - 1] + cur[p + 1]) + k.south * dn[p] + k.north * up[p] - f[p];
            cur[p] = keep * cur[p] + scale * sum;
            p += 2;
        }
        // The end cells with their own stencils. With an odd periodic row, cells 0 and n - 1
        // are neighbours of the same colour: n - 1 is relaxed after 0, as sequential
        // Gauss-Seidel would.
        if first == 0 {
            cur[1] += omega * (end_value(&k, n, 0, dn, cur, up, f) - cur[1]);
        }
        if n > 1 && (n - 1) % 2 == first {
            if periodic_x {
                cur[n + 1] = cur[1];
            }
            cur[n] += omega * (end_value(&k, n, n - 1, dn, cur, up, f) - cur[n]);
        }
    }

    /// Writes `f - A u` of row `j` into the residual row (x ghosts of rows `j - 1..=j + 1`
    /// and y ghosts must be current).
    fn residual_row(&mut self, j: usize) {
        self.fill_ghosts_x(j);
        let n = self.nx;
        let k = self.stencil(j);
        let w = self.stride();
        let u = &self.u[w * j..w * (j + 3)];
        let (dn, cur, up) = (&u[..w], &u[w..2 * w], &u[2 * w..]);
        let f = &self.f[w * (j + 1)..w * (j + 2)];
        let r = &mut self.res[..n];
        let d = 2.0 * k.cx + k.south + k.north;
        {
            let (west, c, east) = (&cur[..n], &cur[1..n + 1], &cur[2..n + 2]);
            let (s, nn, ff) = (&dn[1..n + 1], &up[1..n + 1], &f[1..n + 1]);
            for i in 0..n {
                r[i] = ff[i]
                    - (k.cx * (west[i] + east[i]) + k.south * s[i] + k.north * nn[i] - d * c[i]);
            }
        }
        for i in [0, n - 1] {
            let we = if i == 0 { k.west } else { k.cx };
            let e = if i + 1 == n { k.east } else { k.cx };
            r[i] = f[i + 1]
                - (we * cur[i] + e * cur[i + 2] + k.south * dn[i + 1] + k.north * up[i + 1]
                    - k.diagonal(n, i) * cur[i + 1]);
        }
    }

    /// One red-black sweep, the red and black half-sweeps pipelined row by row. With `emit`,
    /// the residual of each row after the sweep is passed to it (rows in any order).
    pub fn sweep(&mut self, omega: f64, mut emit: Option<RowSink>) {
        let ny = self.ny;
        self.fill_ghosts_y();
        if !self.periodic_y {
            // Black on row j needs red on rows j - 1..=j + 1; the residual of row j needs black
            // on rows j - 1..=j + 1.
            for s in 0..ny + 2 {
                if s < ny {
                    self.relax_row(s, 0, omega);
                }
                if (1..=ny).contains(&s) {
                    self.relax_row(s - 1, 1, omega);
                }
                if s >= 2 {
                    if let Some(emit) = emit.as_mut() {
                        self.residual_row(s - 2);
                        emit(s - 2, &self.res);
                    }
                }
            }
            return;
        }
        // Periodic in y: rows 0 and ny - 1 are neighbours, so black on row 0 waits for red on
        // row ny - 1. The ghost rows are refreshed before rows ny - 1 and 0 are relaxed, which
        // for odd ny (same-colour neighbours across the seam) is sequential Gauss-Seidel.
        let interior = |j: usize, lo: usize| j >= lo && j + lo < ny;
        for s in 0..ny {
            if s + 1 == ny {
                self.fill_ghost_row_above();
            }
            self.relax_row(s, 0, omega);
            if s >= 2 && interior(s - 1, 1) {
                self.relax_row(s - 1, 1, omega);
                if s >= 3 && interior(s - 2, 2) {
                    if let Some(emit) = emit.as_mut() {
                        self.residual_row(s - 2);
                        emit(s - 2, &self.res);
                    }
                }
            }
        }
        self.fill_ghosts_y();
        if ny > 1 {
            self.relax_row(ny - 1, 1, omega);
            self.fill_ghost_row_below();
        }
        self.relax_row(0, 1, omega);
        if let Some(emit) = emit.as_mut() {
            self.fill_ghosts_y();
            for j in (0..ny).filter(|&j| !interior(j, 2)) {
                self.residual_row(j);
                emit(j, &self.res);
            }
        }
    }

    /// Passes the residual of every row to `emit`.
    pub fn residual(&mut self, emit: RowSink) {
        self.fill_ghosts();
        for j in 0..self.ny {
            self.residual_row(j);
            emit(j, &self.res);
        }
    }
}
