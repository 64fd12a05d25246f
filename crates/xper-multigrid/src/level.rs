//! One grid of the multigrid hierarchy: padded arrays (one ghost layer), boundary ghosts,
//! red-black Gauss-Seidel, residual, and the cell-centred transfers.
//!
//! Entry `(i, j)`, `i` in `0..nx`, `j` in `0..ny`, is at `(i + 1) + (nx + 2) (j + 1)`. Ghost
//! values carry the homogeneous boundary conditions: `ghost = interior` (Neumann), `ghost =
//! -interior` (Dirichlet on the face), `ghost = opposite interior` (periodic); filling them in
//! one function is also where a distributed version exchanges halos instead.

use crate::{Boundary, SideCondition};

/// A level: sizes, stencil coefficients and its three arrays.
pub(crate) struct Level {
    pub nx: usize,
    pub ny: usize,
    /// `1 / hx^2`, `1 / hy^2`.
    pub ax: f64,
    pub ay: f64,
    pub phi: Vec<f64>,
    pub rhs: Vec<f64>,
    pub res: Vec<f64>,
}

impl Level {
    pub fn new(nx: usize, ny: usize, hx: f64, hy: f64) -> Self {
        let n = (nx + 2) * (ny + 2);
        Level {
            nx,
            ny,
            ax: 1.0 / (hx * hx),
            ay: 1.0 / (hy * hy),
            phi: vec![0.0; n],
            rhs: vec![0.0; n],
            res: vec![0.0; n],
        }
    }

    #[inline]
    pub fn width(&self) -> usize {
        self.nx + 2
    }

    #[inline]
    pub fn at(&self, i: usize, j: usize) -> usize {
        (i + 1) + (self.nx + 2) * (j + 1)
    }

    pub fn cells(&self) -> usize {
        self.nx * self.ny
    }

    /// Fills the ghost layer of `v` from its interior.
    pub fn fill_ghosts(&self, boundary: &Boundary, v: &mut [f64]) {
        let (nx, ny, w) = (self.nx, self.ny, self.width());
        let ghost = |c: SideCondition, inside: f64, opposite: f64| match c {
            SideCondition::Neumann => inside,
            SideCondition::Dirichlet => -inside,
            SideCondition::Periodic => opposite,
        };
        for j in 1..=ny {
            let row = w * j;
            v[row] = ghost(boundary.left, v[row + 1], v[row + nx]);
            v[row + nx + 1] = ghost(boundary.right, v[row + nx], v[row + 1]);
        }
        // Over the ghost columns too, so corners hold the values the two conditions imply.
        for i in 0..=nx + 1 {
            v[i] = ghost(boundary.bottom, v[i + w], v[i + w * ny]);
            v[i + w * (ny + 1)] = ghost(boundary.top, v[i + w * ny], v[i + w]);
        }
    }

    /// One red-black Gauss-Seidel sweep on `phi` (both colours).
    pub fn smooth(&mut self, boundary: &Boundary) {
        let (nx, ny, w) = (self.nx, self.ny, self.width());
        let (ax, ay) = (self.ax, self.ay);
        let inv_diag = 1.0 / (2.0 * (ax + ay));
        for colour in 0..2 {
            let mut phi = std::mem::take(&mut self.phi);
            self.fill_ghosts(boundary, &mut phi);
            for j in 1..=ny {
                let start = 1 + (j + colour) % 2;
                let row = w * j;
                let rhs = &self.rhs[row..row + w];
                let (below, rest) = phi[row - w..row + 2 * w].split_at_mut(w);
                let (centre, above) = rest.split_at_mut(w);
                let mut i = start;
                while i <= nx {
                    centre[i] = (ax * (centre[i - 1] + centre[i + 1]) + ay * (below[i] + above[i])
                        - rhs[i])
                        * inv_diag;
                    i += 2;
                }
            }
            self.phi = phi;
        }
    }

    /// `res = rhs - A phi` (ghosts of `phi` filled first); returns `||res||_2^2`.
    pub fn residual(&mut self, boundary: &Boundary) -> f64 {
        let mut phi = std::mem::take(&mut self.phi);
        self.fill_ghosts(boundary, &mut phi);
        let (nx, ny, w) = (self.nx, self.ny, self.width());
        let (ax, ay) = (self.ax, self.ay);
        let diag = 2.0 * (ax + ay);
        let mut sum = 0.0;
        for j in 1..=ny {
            let row = w * j;
            for k in row + 1..=row + nx {
                let a =
                    ax * (phi[k - 1] + phi[k + 1]) + ay * (phi[k - w] + phi[k + w]) - diag * phi[k];
                let r = self.rhs[k] - a;
                self.res[k] = r;
                sum += r * r;
            }
        }
        self.phi = phi;
        sum
    }

    /// The coarse right-hand side: the mean of the four fine residuals of each coarse cell.
    pub fn restrict_into(&self, coarse: &mut Level) {
        let (w, cw) = (self.width(), coarse.width());
        for jc in 0..coarse.ny {
            for ic in 0..coarse.nx {
                let k = (2 * ic + 1) + w * (2 * jc + 1);
                let r = &self.res;
                coarse.rhs[(ic + 1) + cw * (jc + 1)] =
                    0.25 * (r[k] + r[k + 1] + r[k + w] + r[k + w + 1]);
            }
        }
    }

    /// Adds the bilinear interpolation of the coarse correction (ghosts filled) to `phi`.
    pub fn prolong_add(&mut self, coarse: &mut Level, boundary: &Boundary) {
        let mut e = std::mem::take(&mut coarse.phi);
        coarse.fill_ghosts(boundary, &mut e);
        let cw = coarse.width();
        let (cnx, cny) = (coarse.nx, coarse.ny);
        let w = self.width();
        for jc in 0..cny {
            for ic in 0..cnx {
                let k = (ic + 1) + cw * (jc + 1);
                let c = e[k];
                let (west, east, south, north) = (e[k - 1], e[k + 1], e[k - cw], e[k + cw]);
                let (sw, se, nw, ne) = (e[k - cw - 1], e[k - cw + 1], e[k + cw - 1], e[k + cw + 1]);
                let f = (2 * ic + 1) + w * (2 * jc + 1);
                self.phi[f] += 0.0625 * (9.0 * c + 3.0 * (west + south) + sw);
                self.phi[f + 1] += 0.0625 * (9.0 * c + 3.0 * (east + south) + se);
                self.phi[f + w] += 0.0625 * (9.0 * c + 3.0 * (west + north) + nw);
                self.phi[f + w + 1] += 0.0625 * (9.0 * c + 3.0 * (east + north) + ne);
            }
        }
        coarse.phi = e;
    }
}
