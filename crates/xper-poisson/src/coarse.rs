//! The exact solve on the coarsest level: a dense Cholesky factorisation of `M = -A`, computed
//! once.
//!
//! `-A` is symmetric positive definite when a side is Dirichlet. Otherwise its kernel is the
//! constants and `M = -A + c 1 1^T` (with `c` the largest diagonal entry over the number of
//! unknowns, so that the added eigenvalue is of the order of the others): for a compatible
//! right-hand side `b` (zero sum), `1^T M x = c n 1^T x = 1^T b = 0`, so `x` is the zero-mean
//! solution of `-A x = b`.

use crate::level::Level;
use crate::SetupError;

pub(crate) struct CoarseSolver {
    n: usize,
    /// Lower Cholesky factor, row-major `n x n`.
    factor: Vec<f64>,
    /// Right-hand side and solution.
    x: Vec<f64>,
}

impl CoarseSolver {
    /// Factorises the operator of `level` (whose `u` and `f` are left zero).
    pub fn new(level: &mut Level, singular: bool) -> Result<Self, SetupError> {
        let (nx, n) = (level.nx, level.cells());
        let mut m = vec![0.0; n * n];
        level.u.fill(0.0);
        level.f.fill(0.0);
        // Column k of -A is the residual f - A u of u = e_k, f = 0 (with the smoother's own
        // stencil, so that the coarse problem is exactly the level's).
        for k in 0..n {
            let at = level.row_start(k / nx) + k % nx;
            level.u[at] = 1.0;
            level.residual(&mut |j, r| {
                for (i, &v) in r.iter().enumerate() {
                    m[(i + nx * j) * n + k] = v;
                }
            });
            level.u.fill(0.0);
        }
        if singular {
            let largest = (0..n).map(|k| m[k * n + k]).fold(0.0, f64::max);
            // A single cell without coupling has A = 0: any positive c does.
            let c = if largest > 0.0 {
                largest / n as f64
            } else {
                1.0
            };
            m.iter_mut().for_each(|v| *v += c);
        }
        for k in 0..n {
            for j in 0..k {
                let dot: f64 = (0..j).map(|p| m[k * n + p] * m[j * n + p]).sum();
                m[k * n + j] = (m[k * n + j] - dot) / m[j * n + j];
            }
            let dot: f64 = (0..k).map(|p| m[k * n + p] * m[k * n + p]).sum();
            let pivot = m[k * n + k] - dot;
            if pivot <= 0.0 || !pivot.is_finite() {
                return Err(SetupError::CoarseFactorisation { cells: n });
            }
            m[k * n + k] = pivot.sqrt();
            m[k * n + k + 1..(k + 1) * n].fill(0.0);
        }
        Ok(CoarseSolver {
            n,
            factor: m,
            x: vec![0.0; n],
        })
    }

    /// Number of unknowns.
    pub fn cells(&self) -> usize {
        self.n
    }

    /// Overwrites `level.u` with the solution of `A u = level.f`.
    pub fn solve(&mut self, level: &mut Level) {
        let (n, nx) = (self.n, level.nx);
        let l = &self.factor;
        for j in 0..level.ny {
            let start = level.row_start(j);
            for (x, &f) in self.x[nx * j..nx * (j + 1)]
                .iter_mut()
                .zip(&level.f[start..])
            {
                *x = -f;
            }
        }
        let x = &mut self.x;
        for k in 0..n {
            let dot: f64 = l[k * n..k * n + k]
                .iter()
                .zip(&x[..k])
                .map(|(a, b)| a * b)
                .sum();
            x[k] = (x[k] - dot) / l[k * n + k];
        }
        // L^T x = y by columns of L^T (rows of L, contiguous).
        for k in (0..n).rev() {
            x[k] /= l[k * n + k];
            let xk = x[k];
            for (xp, &lkp) in x[..k].iter_mut().zip(&l[k * n..k * n + k]) {
                *xp -= lkp * xk;
            }
        }
        for j in 0..level.ny {
            let start = level.row_start(j);
            level.u[start..start + nx].copy_from_slice(&x[nx * j..nx * (j + 1)]);
        }
    }
}
