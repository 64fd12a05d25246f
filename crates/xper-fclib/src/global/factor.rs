//! Solving `M x = b` for many sparse right-hand sides `b`.
//!
//! When the graph of `M` splits into small connected components (rigid bodies: one
//! 3 x 3 or 6 x 6 block per body), each block is factorised densely with faer (Cholesky,
//! or LU when that fails) and inverted once; a right-hand side then only touches the
//! blocks of its non-zero entries, so the whole reduction costs `O(nnz(H) b)` for blocks
//! of size `b`. Otherwise `M` is factorised as a whole with faer's sparse Cholesky (when
//! symmetric positive definite) or sparse LU, and the right-hand sides are solved densely
//! in batches.

use super::Factorization;
use faer::linalg::solvers::{DenseSolveCore, Solve};
use faer::sparse::linalg::solvers::{Llt, Lu};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use xper_solver::{CsrMatrix, ProblemError};

/// Largest connected component of `M` handled as a dense block.
const MAX_BLOCK: usize = 32;
/// Number of right-hand sides solved at once by the sparse factorisations.
const BATCH: usize = 64;
/// Relative residual above which `M` is declared singular (LU only).
const RESIDUAL_TOL: f64 = 1e-8;

fn err(msg: impl Into<String>) -> ProblemError {
    ProblemError(msg.into())
}

/// A factorised `M`.
pub(super) enum MassSolver {
    Llt(Llt<usize, f64>),
    Lu(Box<Lu<usize, f64>>),
    Blocks(Blocks),
}

/// Dense inverses of the diagonal blocks of a block-diagonal `M`.
pub(super) struct Blocks {
    /// Component of each unknown.
    comp: Vec<usize>,
    /// Position of each unknown in its component.
    pos: Vec<usize>,
    /// Unknowns of each component, ascending.
    members: Vec<Vec<usize>>,
    /// The inverse of the block of `M`, per component.
    inverses: Vec<Mat<f64>>,
    /// Whether some block needed LU.
    lu: bool,
}

impl MassSolver {
    /// Factorises `m` (square, finite).
    pub fn new(m: &CsrMatrix) -> Result<Self, ProblemError> {
        if let Some(blocks) = Blocks::new(m)? {
            return Ok(MassSolver::Blocks(blocks));
        }
        let triplets: Vec<Triplet<usize, usize, f64>> = (0..m.nrows)
            .flat_map(|i| {
                (m.row_ptr[i]..m.row_ptr[i + 1])
                    .map(move |p| Triplet::new(i, m.col_idx[p], m.values[p]))
            })
            .collect();
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(m.nrows, m.ncols, &triplets)
            .map_err(|e| err(format!("M cannot be stored by faer: {e:?}")))?;
        if is_symmetric(m) {
            if let Ok(llt) = a.sp_cholesky(Side::Lower) {
                return Ok(MassSolver::Llt(llt));
            }
        }
        a.sp_lu()
            .map(|lu| MassSolver::Lu(Box::new(lu)))
            .map_err(|e| err(format!("M is singular: sparse LU failed ({e:?})")))
    }

    /// How `M` was factorised.
    pub fn kind(&self) -> Factorization {
        match self {
            MassSolver::Llt(_) => Factorization::Cholesky,
            MassSolver::Lu(_) => Factorization::Lu,
            MassSolver::Blocks(b) => Factorization::BlockDiagonal {
                blocks: b.members.len(),
                largest: b.members.iter().map(Vec::len).max().unwrap_or(0),
                lu: b.lu,
            },
        }
    }

    /// Solves `M x_c = b_c` for `c` in `0..count`, where `rhs(c)` gives `b_c` as
    /// `(index, value)` pairs, and hands each solution to `out` as its non-zero entries.
    pub fn solve_all(
        &self,
        m: &CsrMatrix,
        count: usize,
        rhs: impl Fn(usize) -> Vec<(usize, f64)>,
        mut out: impl FnMut(usize, &[(usize, f64)]),
    ) -> Result<(), ProblemError> {
        let n = m.nrows;
        if let MassSolver::Blocks(b) = self {
            for c in 0..count {
                out(c, &b.solve(&rhs(c), c)?);
            }
            return Ok(());
        }
        let mut x = Vec::new();
        let mut dense_b = vec![0.0; n];
        for start in (0..count).step_by(BATCH) {
            let end = (start + BATCH).min(count);
            let mut mat = Mat::<f64>::zeros(n, end - start);
            for c in start..end {
                for (i, v) in rhs(c) {
                    mat[(i, c - start)] += v;
                }
            }
            let check = matches!(self, MassSolver::Lu(_)).then(|| mat.clone());
            match self {
                MassSolver::Llt(s) => s.solve_in_place(mat.as_mut()),
                MassSolver::Lu(s) => s.solve_in_place(mat.as_mut()),
                MassSolver::Blocks(_) => unreachable!("handled above"),
            }
            for c in start..end {
                let col: Vec<f64> = (0..n).map(|i| mat[(i, c - start)]).collect();
                if let Some(i) = col.iter().position(|v| !v.is_finite()) {
                    return Err(singular(c, &format!("non-finite entry at {i}")));
                }
                if let Some(b) = &check {
                    for (i, bi) in dense_b.iter_mut().enumerate() {
                        *bi = b[(i, c - start)];
                    }
                    check_residual(m, &col, &dense_b, c)?;
                }
                x.clear();
                x.extend(
                    col.iter()
                        .enumerate()
                        .filter(|(_, v)| **v != 0.0)
                        .map(|(i, v)| (i, *v)),
                );
                out(c, &x);
            }
        }
        Ok(())
    }
}

fn singular(c: usize, what: &str) -> ProblemError {
    err(format!(
        "M is singular: solving for right-hand side {c} gives a {what}"
    ))
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// `|M x - b| <= tol (|M|_F |x| + |b|)`, else `M` is numerically singular.
fn check_residual(m: &CsrMatrix, x: &[f64], b: &[f64], c: usize) -> Result<(), ProblemError> {
    let mut r: Vec<f64> = b.iter().map(|v| -v).collect();
    m.mul_add(x, &mut r);
    if norm(&r) > RESIDUAL_TOL * (norm(&m.values) * norm(x) + norm(b)) {
        return Err(singular(c, &format!("residual of {:e}", norm(&r))));
    }
    Ok(())
}

/// Whether `|m_ij - m_ji| <= 1e-12 max |m|` for every stored entry.
fn is_symmetric(m: &CsrMatrix) -> bool {
    let scale = m.values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    (0..m.nrows).all(|i| {
        (m.row_ptr[i]..m.row_ptr[i + 1])
            .all(|p| (m.values[p] - m.get(m.col_idx[p], i)).abs() <= 1e-12 * scale)
    })
}

fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

impl Blocks {
    /// The block structure of `m`, if every connected component has at most
    /// `MAX_BLOCK` unknowns; `None` otherwise.
    fn new(m: &CsrMatrix) -> Result<Option<Self>, ProblemError> {
        let n = m.nrows;
        let mut parent: Vec<usize> = (0..n).collect();
        for i in 0..n {
            for &j in &m.col_idx[m.row_ptr[i]..m.row_ptr[i + 1]] {
                let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                parent[a.max(b)] = a.min(b);
            }
        }
        let mut comp = vec![usize::MAX; n];
        let mut pos = vec![0; n];
        let mut members: Vec<Vec<usize>> = Vec::new();
        for i in 0..n {
            let root = find(&mut parent, i);
            if comp[root] == usize::MAX {
                comp[root] = members.len();
                members.push(Vec::new());
            }
            let c = comp[root];
            comp[i] = c;
            pos[i] = members[c].len();
            members[c].push(i);
            if members[c].len() > MAX_BLOCK {
                return Ok(None);
            }
        }
        let mut inverses = Vec::with_capacity(members.len());
        let mut lu = false;
        for (c, idx) in members.iter().enumerate() {
            let block = Mat::from_fn(idx.len(), idx.len(), |a, b| m.get(idx[a], idx[b]));
            let symmetric = (0..idx.len()).all(|a| (0..a).all(|b| block[(a, b)] == block[(b, a)]));
            let llt = || block.as_ref().llt(Side::Lower).ok().filter(|_| symmetric);
            let inv = if idx.len() == 1 {
                // 1 / m exactly, rather than 1 / (sqrt(m) sqrt(m)).
                Mat::from_fn(1, 1, |_, _| 1.0 / block[(0, 0)])
            } else if let Some(llt) = llt() {
                llt.inverse()
            } else {
                lu = true;
                block.as_ref().partial_piv_lu().inverse()
            };
            // inv * block must be the identity.
            let prod = &inv * &block;
            let off = (0..idx.len())
                .flat_map(|a| (0..idx.len()).map(move |b| (a, b)))
                .map(|(a, b)| (prod[(a, b)] - if a == b { 1.0 } else { 0.0 }).abs())
                .fold(0.0f64, |acc, v| {
                    if v.is_nan() {
                        f64::INFINITY
                    } else {
                        acc.max(v)
                    }
                });
            if off > RESIDUAL_TOL.sqrt() {
                return Err(err(format!(
                    "M is singular: its diagonal block {c} (unknowns {}..={}) cannot be inverted",
                    idx[0],
                    idx[idx.len() - 1]
                )));
            }
            inverses.push(inv);
        }
        Ok(Some(Blocks {
            comp,
            pos,
            members,
            inverses,
            lu,
        }))
    }

    /// `M^-1 b` for a sparse `b`, as non-zero entries.
    fn solve(&self, b: &[(usize, f64)], c: usize) -> Result<Vec<(usize, f64)>, ProblemError> {
        let mut by_block: Vec<(usize, usize, f64)> = b
            .iter()
            .map(|&(i, v)| (self.comp[i], self.pos[i], v))
            .collect();
        by_block.sort_unstable_by_key(|&(k, p, _)| (k, p));
        let mut x = Vec::new();
        let mut local = Vec::new();
        for group in by_block.chunk_by(|a, b| a.0 == b.0) {
            let k = group[0].0;
            let (idx, inv) = (&self.members[k], &self.inverses[k]);
            local.clear();
            local.resize(idx.len(), 0.0);
            for &(_, p, v) in group {
                local[p] += v;
            }
            for (a, &row) in idx.iter().enumerate() {
                let v: f64 = (0..idx.len()).map(|b| inv[(a, b)] * local[b]).sum();
                if !v.is_finite() {
                    return Err(singular(c, &format!("non-finite entry at {row}")));
                }
                if v != 0.0 {
                    x.push((row, v));
                }
            }
        }
        Ok(x)
    }
}
