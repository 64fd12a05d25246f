//! The exact solve on the coarsest grid: a sparse Cholesky factorisation (faer) of `-A`,
//! which is symmetric positive definite once, for a singular problem (no Dirichlet side), the
//! first unknown is pinned to zero (the coarse correction is then defined up to a constant,
//! which the fine operator annihilates).

use crate::level::Level;
use crate::{Boundary, SetupError, SideCondition};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Llt;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use std::collections::BTreeMap;

pub(crate) struct CoarsestSolver {
    llt: Llt<usize, f64>,
    pinned: bool,
    work: Mat<f64>,
}

impl CoarsestSolver {
    pub fn new(level: &Level, boundary: &Boundary) -> Result<Self, SetupError> {
        let (nx, ny) = (level.nx, level.ny);
        let pinned = boundary.is_singular();
        let mut entries: BTreeMap<(usize, usize), f64> = BTreeMap::new();
        let cell = |i: usize, j: usize| i + nx * j;
        for j in 0..ny {
            for i in 0..nx {
                let row = cell(i, j);
                *entries.entry((row, row)).or_default() += 2.0 * (level.ax + level.ay);
                // The four neighbours: inside, wrapped (periodic), or a ghost folded into the
                // diagonal (Neumann: +phi, so -a; Dirichlet: -phi, so +a).
                let sides = [
                    (i > 0, level.ax, boundary.left, (i + nx - 1) % nx, j),
                    (i + 1 < nx, level.ax, boundary.right, (i + 1) % nx, j),
                    (j > 0, level.ay, boundary.bottom, i, (j + ny - 1) % ny),
                    (j + 1 < ny, level.ay, boundary.top, i, (j + 1) % ny),
                ];
                for (inside, a, condition, ni, nj) in sides {
                    if inside || condition == SideCondition::Periodic {
                        *entries.entry((row, cell(ni, nj))).or_default() -= a;
                    } else if condition == SideCondition::Neumann {
                        *entries.entry((row, row)).or_default() -= a;
                    } else {
                        *entries.entry((row, row)).or_default() += a;
                    }
                }
            }
        }
        let skip = pinned as usize;
        let n = nx * ny - skip;
        let triplets: Vec<Triplet<usize, usize, f64>> = entries
            .into_iter()
            .filter(|&((r, c), _)| r >= skip && c >= skip)
            .map(|((r, c), v)| Triplet::new(r - skip, c - skip, v))
            .collect();
        let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
            .map_err(|e| SetupError(format!("coarsest operator: {e:?}")))?;
        let llt = matrix.sp_cholesky(Side::Lower).map_err(|e| {
            SetupError(format!("coarsest operator is not positive definite: {e:?}"))
        })?;
        Ok(CoarsestSolver {
            llt,
            pinned,
            work: Mat::zeros(n, 1),
        })
    }

    /// Overwrites `level.phi` with the solution of `A phi = level.rhs`.
    pub fn solve(&mut self, level: &mut Level, _boundary: &Boundary) {
        let (nx, ny) = (level.nx, level.ny);
        let skip = self.pinned as usize;
        for j in 0..ny {
            for i in 0..nx {
                let c = i + nx * j;
                if c >= skip {
                    self.work[(c - skip, 0)] = -level.rhs[level.at(i, j)];
                }
            }
        }
        self.llt.solve_in_place(self.work.as_mut());
        for j in 0..ny {
            for i in 0..nx {
                let c = i + nx * j;
                let k = level.at(i, j);
                level.phi[k] = if c >= skip {
                    self.work[(c - skip, 0)]
                } else {
                    0.0
                };
            }
        }
    }
}
