//! The global (velocity-impulse) form of a frictional contact problem and its reduction
//! to the local form.
//!
//! ```text
//! M v = H r + f,    u = H^T v + w,    (u_a, r_a) Signorini + Coulomb with mu_a
//! ```
//!
//! Eliminating `v = M^-1 (H r + f)` gives the local problem `u = W r + q` with
//! `W = H^T M^-1 H` and `q = H^T M^-1 f + w` (FCLib's convention, Acary et al. 2014).
//! The reduction factorises `M` once with faer: block by block when `M` is block diagonal
//! (rigid bodies), otherwise with faer's sparse Cholesky when `M` is symmetric positive
//! definite and its sparse LU otherwise, then solves for the columns of `H`.
//!
//! `W` is kept sparse: entry `(i, j)` is stored when the supports of column `i` of `H`
//! and of `M^-1 H e_j` meet, with no threshold dropping, so block-diagonal mass matrices
//! (rigid bodies) give the same sparsity as the contact graph.

mod factor;

use factor::MassSolver;
use xper_solver::{CsrMatrix, FrictionProblem, ProblemError};

/// A global frictional contact problem `M v = H r + f`, `u = H^T v + w`.
#[derive(Clone, Debug, PartialEq)]
pub struct GlobalFrictionProblem {
    /// Local dimension: 2 or 3.
    pub dim: usize,
    /// The mass (or iteration) matrix, `n x n`, stored in full (the readers complete
    /// matrices stored as one triangle of a symmetric matrix).
    pub m: CsrMatrix,
    /// The transpose of the contact Jacobian, `n x dim nc`: `u = H^T v + w`.
    pub h: CsrMatrix,
    /// The free-flight term, length `n`.
    pub f: Vec<f64>,
    /// The constant local velocity, length `dim nc`.
    pub w: Vec<f64>,
    /// Friction coefficient per contact, length `nc`.
    pub mu: Vec<f64>,
}

/// Which factorisation of `M` the reduction used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Factorization {
    /// No factorisation: the problem has no contact.
    None,
    /// Sparse Cholesky `L L^T` (M symmetric positive definite).
    Cholesky,
    /// Sparse LU with partial pivoting (M non-symmetric, or Cholesky failed).
    Lu,
    /// `M` is block diagonal (its graph has small connected components, as for rigid
    /// bodies): each block was factorised densely (Cholesky, or LU when that fails).
    BlockDiagonal {
        /// Number of blocks.
        blocks: usize,
        /// Size of the largest block.
        largest: usize,
        /// Whether some block needed LU.
        lu: bool,
    },
}

/// The result of [`GlobalFrictionProblem::reduce`].
#[derive(Clone, Debug, PartialEq)]
pub struct Reduction {
    /// The local problem `u = W r + q`.
    pub problem: FrictionProblem,
    /// How `M` was factorised.
    pub factorization: Factorization,
}

fn err(msg: impl Into<String>) -> ProblemError {
    ProblemError(msg.into())
}

impl GlobalFrictionProblem {
    /// Checks sizes and values (all finite, `mu >= 0`) and builds the problem.
    pub fn new(
        dim: usize,
        m: CsrMatrix,
        h: CsrMatrix,
        f: Vec<f64>,
        w: Vec<f64>,
        mu: Vec<f64>,
    ) -> Result<Self, ProblemError> {
        let p = GlobalFrictionProblem {
            dim,
            m,
            h,
            f,
            w,
            mu,
        };
        p.validate()?;
        Ok(p)
    }

    /// The checks of [`Self::new`], for a problem whose public fields were set directly.
    pub fn validate(&self) -> Result<(), ProblemError> {
        let (dim, m, h) = (self.dim, &self.m, &self.h);
        if dim != 2 && dim != 3 {
            return Err(err(format!("dimension {dim} is not 2 or 3")));
        }
        let n = self.f.len();
        let k = dim * self.mu.len();
        if m.nrows != n || m.ncols != n {
            return Err(err(format!(
                "f has {n} entries so M must be {n} x {n}; it is {} x {}",
                m.nrows, m.ncols
            )));
        }
        if h.nrows != n || h.ncols != k || self.w.len() != k {
            return Err(err(format!(
                "{} contacts in {dim}D over {n} unknowns need H {n} x {k} and w of length {k}; got H {} x {} and w of length {}",
                self.mu.len(), h.nrows, h.ncols, self.w.len()
            )));
        }
        for a in [m, h] {
            let shape_ok = a.row_ptr.len() == a.nrows + 1
                && a.row_ptr.first() == Some(&0)
                && a.row_ptr.windows(2).all(|p| p[0] <= p[1])
                && a.row_ptr.last() == Some(&a.values.len())
                && a.col_idx.len() == a.values.len()
                && a.col_idx.iter().all(|&j| j < a.ncols);
            if !shape_ok {
                return Err(err("M or H is not a consistent CSR matrix"));
            }
        }
        for (name, v) in [("f", &self.f), ("w", &self.w)] {
            if let Some(i) = v.iter().position(|x| !x.is_finite()) {
                return Err(err(format!("{name}[{i}] = {} is not finite", v[i])));
            }
        }
        if let Some(a) = self.mu.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(err(format!(
                "mu[{a}] = {} is not a finite non-negative number",
                self.mu[a]
            )));
        }
        if !m.is_finite() || !h.is_finite() {
            return Err(err("M or H holds a non-finite value"));
        }
        Ok(())
    }

    /// Number of contacts.
    pub fn contact_count(&self) -> usize {
        self.mu.len()
    }

    /// Number of global unknowns (rows of `M`).
    pub fn dof_count(&self) -> usize {
        self.f.len()
    }

    /// The local problem `W = H^T M^-1 H`, `q = H^T M^-1 f + w`.
    pub fn to_local(&self) -> Result<FrictionProblem, ProblemError> {
        self.reduce().map(|r| r.problem)
    }

    /// As [`Self::to_local`], also telling which factorisation was used. Fails when `M`
    /// is singular: a non-finite solution, a diagonal block whose computed inverse is
    /// not one, or (sparse LU only; Cholesky succeeding proves `M` positive definite) a
    /// residual `|M x - b|` above `1e-8 (|M|_F |x| + |b|)`.
    pub fn reduce(&self) -> Result<Reduction, ProblemError> {
        self.validate()?;
        let k = self.h.ncols;
        if k == 0 {
            let w = CsrMatrix::from_triplets(0, 0, &[]).expect("empty");
            let problem = FrictionProblem::new(self.dim, w, Vec::new(), Vec::new())?;
            return Ok(Reduction {
                problem,
                factorization: Factorization::None,
            });
        }
        let solver = MassSolver::new(&self.m)?;
        let ht = self.h.transpose(); // row j of H^T = column j of H
        let mut entries = Vec::new();
        let mut q = vec![0.0; k];
        let mut acc = vec![0.0; k];
        let mut mark = vec![usize::MAX; k];
        let mut touched = Vec::new();
        // Right-hand sides 0..k are the columns of H; right-hand side k is f.
        let rhs = |c: usize| -> Vec<(usize, f64)> {
            if c < k {
                (ht.row_ptr[c]..ht.row_ptr[c + 1])
                    .map(|p| (ht.col_idx[p], ht.values[p]))
                    .collect()
            } else {
                self.f
                    .iter()
                    .copied()
                    .enumerate()
                    .filter(|(_, v)| *v != 0.0)
                    .collect()
            }
        };
        solver.solve_all(&self.m, k + 1, rhs, |c, x| {
            // Column c of H^T x: only the rows of H where x is non-zero contribute.
            touched.clear();
            for &(row, xv) in x {
                for p in self.h.row_ptr[row]..self.h.row_ptr[row + 1] {
                    let i = self.h.col_idx[p];
                    if mark[i] != c {
                        mark[i] = c;
                        acc[i] = 0.0;
                        touched.push(i);
                    }
                    acc[i] += self.h.values[p] * xv;
                }
            }
            for &i in &touched {
                if c < k {
                    entries.push((i, c, acc[i]));
                } else {
                    q[i] = acc[i];
                }
            }
        })?;
        for (qi, wi) in q.iter_mut().zip(&self.w) {
            *qi += wi;
        }
        let w = CsrMatrix::from_triplets(k, k, &entries)?;
        let problem = FrictionProblem::new(self.dim, w, q, self.mu.clone())?;
        Ok(Reduction {
            problem,
            factorization: solver.kind(),
        })
    }
}
