//! The pressure-correction projection (Chorin, Math. Comp. 22 (1968) 745; incremental form of
//! van Kan, SIAM J. Sci. Stat. Comput. 7 (1986) 870):
//!
//! ```text
//! lap(phi) = (rho / dt) div u*,     u = u* - (dt / rho) grad phi,     p <- p + phi
//! ```
//!
//! on the MAC grid, where `div` and `grad` are the staggered differences, so `div u` after the
//! correction equals `(dt / rho)` times the residual of the pressure solve: the velocity is as
//! divergence-free as the multigrid tolerance makes it.

use crate::blocks::BlockLinks;
use crate::boundary::FluidBoundary;
use crate::grid::MacGrid;
use xper_math::{Real, DIM};
use xper_poisson::{MultigridError, MultigridInfo};

/// Writes the divergence of every cell into `out` (row-major, unpadded) and returns the sum of
/// its squares.
pub fn divergence(grid: &MacGrid, u: &[Vec<Real>; DIM], out: &mut [Real]) -> Real {
    let (nx, inv_h) = (grid.nx, 1.0 / grid.h);
    let mut sum = 0.0;
    for j in 0..grid.ny {
        let r = grid.index(0, j as isize);
        let row = &mut out[nx * j..nx * (j + 1)];
        row.fill(0.0);
        for (d, ud) in u.iter().enumerate() {
            let sd = grid.stride(d);
            let (low, high) = (&ud[r..r + nx], &ud[r + sd..r + sd + nx]);
            for ((div, lo), hi) in row.iter_mut().zip(low).zip(high) {
                *div += hi - lo;
            }
        }
        for div in row.iter_mut() {
            *div *= inv_h;
            sum += *div * *div;
        }
    }
    sum
}

/// Workspaces of the projection.
pub struct Projection {
    rhs: Vec<Real>,
    correction: Vec<Real>,
}

/// Outcome of one projection.
#[derive(Clone, Copy, Debug)]
pub struct ProjectionInfo {
    /// The pressure solve.
    pub solve: MultigridInfo,
    /// This block's sums of the squared divergence before and after the correction (1/s^2;
    /// the grid's norms are the roots of their sums over the blocks, which the caller reduces
    /// together with its other sums).
    pub divergence_squares: [Real; 2],
}

impl Projection {
    /// Workspaces for `grid`.
    pub fn new(grid: &MacGrid) -> Self {
        Projection {
            rhs: vec![0.0; grid.num_cells()],
            correction: grid.zeros(),
        }
    }

    /// Projects `u` (boundary values already set) onto divergence-free fields, adds the
    /// pressure increment to `p` (padded). `phi` (unpadded) holds the previous increment on
    /// entry, the warm start, and the new one on exit. On a block of a split grid, `links`
    /// solves over the whole grid and completes the halos and norms.
    #[allow(clippy::too_many_arguments)]
    pub fn project(
        &mut self,
        links: &mut dyn BlockLinks,
        grid: &MacGrid,
        boundary: &FluidBoundary,
        dt: Real,
        density: Real,
        u: &mut [Vec<Real>; DIM],
        p: &mut [Real],
        phi: &mut [Real],
    ) -> Result<ProjectionInfo, MultigridError> {
        let mut squares = [divergence(grid, u, &mut self.rhs), 0.0];
        let scale = density / dt;
        for r in &mut self.rhs {
            *r *= scale;
        }
        let solve = links.solve_pressure(&self.rhs, phi)?;
        self.fill_correction(grid, boundary, phi);
        links.exchange_halo(grid, &mut [&mut self.correction]);
        let factor = dt / (density * grid.h);
        let c = &self.correction;
        for (d, ud) in u.iter_mut().enumerate() {
            let sd = grid.stride(d);
            for run in grid.face_rows(d, boundary.projected_faces(grid, d)) {
                let (here, back) = (&c[run.clone()], &c[run.start - sd..run.end - sd]);
                for ((v, c_here), c_back) in ud[run].iter_mut().zip(here).zip(back) {
                    *v -= factor * (c_here - c_back);
                }
            }
        }
        let nx = grid.nx;
        for j in 0..grid.ny {
            let r = grid.index(0, j as isize);
            for (pk, phik) in p[r..r + nx].iter_mut().zip(&phi[nx * j..nx * (j + 1)]) {
                *pk += phik;
            }
        }
        boundary.fill_velocity(grid, u);
        boundary.fill_pressure(grid, p);
        exchange_velocity_and_pressure(links, grid, u, p);
        squares[1] = divergence(grid, u, &mut self.rhs);
        Ok(ProjectionInfo {
            solve,
            divergence_squares: squares,
        })
    }

    /// Copies `phi` into the padded correction array with its boundary ghosts: periodic copies,
    /// `-phi` beyond a Dirichlet (outflow) side, `phi` beyond a Neumann side.
    fn fill_correction(&mut self, grid: &MacGrid, boundary: &FluidBoundary, phi: &[Real]) {
        let c = &mut self.correction;
        let nx = grid.nx;
        for j in 0..grid.ny {
            let r = grid.index(0, j as isize);
            c[r..r + nx].copy_from_slice(&phi[nx * j..nx * (j + 1)]);
        }
        for a in 0..DIM {
            let n = grid.cells(a) as isize;
            let m = grid.cells(1 - a) as isize;
            let [lo, hi] = boundary.sides(a);
            for k in 0..m {
                let at = |along: isize| {
                    if a == 0 {
                        grid.index(along, k)
                    } else {
                        grid.index(k, along)
                    }
                };
                let ghost = |c: &[Real], side, inside: isize, other: isize| match side {
                    crate::SideCondition::Periodic => c[at(other)],
                    crate::SideCondition::Outflow => -c[at(inside)],
                    _ => c[at(inside)],
                };
                c[at(-1)] = ghost(c, lo, 0, n - 1);
                c[at(n)] = ghost(c, hi, n - 1, 0);
            }
        }
    }
}

/// Completes the halos of the velocity components and the pressure (padded arrays).
pub fn exchange_velocity_and_pressure(
    links: &mut dyn BlockLinks,
    grid: &MacGrid,
    u: &mut [Vec<Real>; DIM],
    p: &mut [Real],
) {
    let [u0, u1] = u;
    links.exchange_halo(grid, &mut [u0.as_mut_slice(), u1.as_mut_slice(), p]);
}
