//! An exact reference for small 2D problems: the linear complementarity form of 2D Coulomb
//! friction solved by Lemke's complementary pivoting.
//!
//! In 2D the friction cone is the polyhedral cone spanned by two directions, so the problem
//! is exactly an LCP (Klarbring 1986; Stewart, Trinkle, IJNME 39, 1996; Anitescu, Potra,
//! Nonlinear Dynamics 14, 1997). With `r_T = b+ - b-` and a slack `lambda` (the sliding speed)
//! per contact, the unknowns `z_a = (r_N, b+, b-, lambda) >= 0` satisfy `w = M z + c >= 0`,
//! `z . w = 0` with
//!
//! ```text
//! w_N      = u_N                       ⊥ r_N
//! w_+      = lambda + u_T              ⊥ b+
//! w_-      = lambda - u_T              ⊥ b-
//! w_lambda = mu r_N - b+ - b-          ⊥ lambda        (u = W r + q)
//! ```
//!
//! Sliding (`u_T != 0`) forces `lambda = |u_T| > 0`, so `b+ + b- = mu r_N` with only the
//! component opposing `u_T` non-zero; `lambda = 0` forces `u_T = 0` (stick). `z^T M z =
//! r.W r + mu r_N lambda >= 0` on `z >= 0`: `M` is copositive, and Lemke's method processes
//! such LCPs, ending either at a solution or on a secondary ray (reported as an error).
//!
//! Lemke's method (Lemke 1965; Cottle, Pang, Stone, "The Linear Complementarity Problem",
//! section 4.4) on the dense tableau `[B^-1 | B^-1 (-M) | B^-1 (-e) | B^-1 c]` with covering
//! vector `e = 1`; the ratio test breaks ties by the lexicographic rule on the rows of
//! `(B^-1 c, B^-1)` (which prevents cycling), preferring the artificial variable `z0` when it
//! is among the tied rows. The dense tableau costs `O((4n)^2)` memory, hence
//! [`LemkeParams::max_contacts`].

use crate::nlgs::SolveError;
use crate::problem::FrictionProblem;
use crate::solve::{check_params, check_problem, SolveReport, SolverKind, SolverParams};

/// Tuning of Lemke's method.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LemkeParams {
    /// A pivot candidate must exceed this times the largest magnitude of its column.
    pub pivot_tolerance: f64,
    /// Problems with more contacts are refused (the tableau is dense).
    pub max_contacts: usize,
}

impl Default for LemkeParams {
    fn default() -> Self {
        LemkeParams {
            pivot_tolerance: 1e-11,
            max_contacts: 400,
        }
    }
}

/// Solves a 2D `problem` by Lemke's method on its LCP form. `params.max_iterations` bounds
/// the pivots (0: `50 (4n + 1)`). Errors: 3D problems, too many contacts, ray termination,
/// pivot limit.
pub fn lemke(problem: &FrictionProblem, params: &SolverParams) -> Result<SolveReport, SolveError> {
    if problem.dim != 2 {
        return Err(SolveError::Unsupported(format!(
            "Lemke's method solves 2D problems (LCP form of the friction cone); got {}D",
            problem.dim
        )));
    }
    check_params(params)?;
    check_problem(problem)?;
    let n = problem.mu.len();
    if n > params.lemke.max_contacts {
        return Err(SolveError::Unsupported(format!(
            "{n} contacts: Lemke's dense tableau is limited to {}",
            params.lemke.max_contacts
        )));
    }
    let (m, mut c) = lcp_of(problem);
    // The LCP is homogeneous in c: solve with |c|_inf = 1 so that the pivoting tolerances
    // are relative, then scale z back.
    let c_scale = c.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    if c_scale > 0.0 {
        c.iter_mut().for_each(|x| *x /= c_scale);
    }
    let max_pivots = if params.max_iterations > 0 {
        params.max_iterations as usize
    } else {
        50 * (4 * n + 1)
    };
    let (z, pivots) = solve_lcp(&m, &c, params.lemke.pivot_tolerance, max_pivots)?;
    let mut r = vec![0.0; 2 * n];
    for a in 0..n {
        r[2 * a] = c_scale * z[4 * a];
        r[2 * a + 1] = c_scale * (z[4 * a + 1] - z[4 * a + 2]);
    }
    Ok(SolveReport::new(
        SolverKind::Lemke,
        problem,
        params,
        pivots as u32,
        0,
        r,
    ))
}

/// The LCP `(M, c)` of a 2D problem, `M` dense row-major `4n x 4n`.
fn lcp_of(problem: &FrictionProblem) -> (Vec<f64>, Vec<f64>) {
    let n = problem.mu.len();
    let nn = 4 * n;
    let w = &problem.w;
    let mut m = vec![0.0; nn * nn];
    let mut c = vec![0.0; nn];
    for a in 0..n {
        for k in 0..2 {
            let i = 2 * a + k;
            for e in w.row_ptr[i]..w.row_ptr[i + 1] {
                let (j, v) = (w.col_idx[e], w.values[e]);
                let (b, l) = (j / 2, j % 2);
                // Contribution of r_j to u_i: r_N of contact b, or b+ - b- of contact b.
                let cols: &[(usize, f64)] = if l == 0 {
                    &[(4 * b, 1.0)]
                } else {
                    &[(4 * b + 1, 1.0), (4 * b + 2, -1.0)]
                };
                for &(col, s) in cols {
                    if k == 0 {
                        m[4 * a * nn + col] += s * v;
                    } else {
                        m[(4 * a + 1) * nn + col] += s * v;
                        m[(4 * a + 2) * nn + col] -= s * v;
                    }
                }
            }
        }
        c[4 * a] = problem.q[2 * a];
        c[4 * a + 1] = problem.q[2 * a + 1];
        c[4 * a + 2] = -problem.q[2 * a + 1];
        m[(4 * a + 1) * nn + 4 * a + 3] += 1.0;
        m[(4 * a + 2) * nn + 4 * a + 3] += 1.0;
        m[(4 * a + 3) * nn + 4 * a] = problem.mu[a];
        m[(4 * a + 3) * nn + 4 * a + 1] = -1.0;
        m[(4 * a + 3) * nn + 4 * a + 2] = -1.0;
    }
    (m, c)
}

/// Lemke's method for `w = M z + c`; returns `z` and the number of pivots.
///
/// The tableau is `B^-1 [I | -M | -e | c]` for `[I, -M, -e] (w, z, z0) = c`: columns
/// `w` (0..N, they hold `B^-1`), `z` (N..2N), the artificial `z0` (2N), the right-hand side
/// (2N+1), whose entries are the values of the basic variables.
fn solve_lcp(
    m: &[f64],
    c: &[f64],
    tol: f64,
    max_pivots: usize,
) -> Result<(Vec<f64>, usize), SolveError> {
    let nn = c.len();
    if c.iter().all(|&x| x >= 0.0) {
        return Ok((vec![0.0; nn], 0));
    }
    let width = 2 * nn + 2;
    let (art, rhs) = (2 * nn, 2 * nn + 1);
    let mut t = vec![0.0; nn * width];
    for i in 0..nn {
        let row = &mut t[i * width..(i + 1) * width];
        row[i] = 1.0;
        for j in 0..nn {
            row[nn + j] = -m[i * nn + j];
        }
        row[art] = -1.0;
        row[rhs] = c[i];
    }
    let mut basis: Vec<usize> = (0..nn).collect();
    // First pivot: z0 enters at the value -min c; among tied rows the last one leaves,
    // which leaves every row of (B^-1 c, B^-1) lexicographically positive.
    let cmin = c.iter().cloned().fold(f64::INFINITY, f64::min);
    let first = (0..nn).rev().find(|&i| c[i] == cmin).unwrap_or(0);
    pivot(&mut t, width, first, art);
    let mut leaving = basis[first];
    basis[first] = art;
    let mut pivots = 1;
    loop {
        let entering = if leaving < nn {
            leaving + nn
        } else {
            leaving - nn
        };
        let col_max = (0..nn).fold(0.0f64, |s, i| s.max(t[i * width + entering].abs()));
        let eps = tol * col_max;
        // Ratio test on the rows whose basic variable decreases when `entering` grows.
        let ratio = |i: usize| t[i * width + rhs] / t[i * width + entering];
        let mut rmin = f64::INFINITY;
        for i in 0..nn {
            if t[i * width + entering] > eps {
                rmin = rmin.min(ratio(i));
            }
        }
        if !rmin.is_finite() {
            return Err(SolveError::Breakdown(format!(
                "Lemke: ray termination after {pivots} pivots (no solution found)"
            )));
        }
        let tied = (0..nn).filter(|&i| {
            t[i * width + entering] > eps && ratio(i) <= rmin + 1e-12 * (1.0 + rmin.abs())
        });
        let row = match tied.clone().find(|&i| basis[i] == art) {
            Some(i) => i,
            None => tied
                .min_by(|&i, &j| lex_cmp(&t, width, nn, i, j, entering, rhs))
                .unwrap_or(0),
        };
        pivot(&mut t, width, row, entering);
        leaving = basis[row];
        basis[row] = entering;
        pivots += 1;
        if leaving == art {
            break;
        }
        if pivots >= max_pivots {
            return Err(SolveError::Breakdown(format!(
                "Lemke: no solution within {max_pivots} pivots"
            )));
        }
    }
    let mut z = vec![0.0; nn];
    for (i, &v) in basis.iter().enumerate() {
        if (nn..2 * nn).contains(&v) {
            z[v - nn] = t[i * width + rhs].max(0.0);
        }
    }
    Ok((z, pivots))
}

/// Lexicographic comparison of rows `i` and `j` of `(B^-1 c, B^-1)`, each divided by its
/// (positive) entry in column `col`.
fn lex_cmp(
    t: &[f64],
    width: usize,
    nn: usize,
    i: usize,
    j: usize,
    col: usize,
    rhs: usize,
) -> std::cmp::Ordering {
    let (di, dj) = (t[i * width + col], t[j * width + col]);
    for k in std::iter::once(rhs).chain(0..nn) {
        let (a, b) = (t[i * width + k] / di, t[j * width + k] / dj);
        if (a - b).abs() > 1e-12 * (1.0 + a.abs().max(b.abs())) {
            return a.total_cmp(&b);
        }
    }
    i.cmp(&j)
}

/// Gauss-Jordan pivot on `(row, col)`.
fn pivot(t: &mut [f64], width: usize, row: usize, col: usize) {
    let p = t[row * width + col];
    let (before, rest) = t.split_at_mut(row * width);
    let (prow, after) = rest.split_at_mut(width);
    for x in prow.iter_mut() {
        *x /= p;
    }
    prow[col] = 1.0;
    for other in before.chunks_mut(width).chain(after.chunks_mut(width)) {
        let f = other[col];
        if f != 0.0 {
            for (x, &y) in other.iter_mut().zip(prow.iter()) {
                *x -= f * y;
            }
            other[col] = 0.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_lcp(m: &[f64], c: &[f64], z: &[f64]) {
        let nn = c.len();
        for i in 0..nn {
            let w: f64 = c[i] + (0..nn).map(|j| m[i * nn + j] * z[j]).sum::<f64>();
            assert!(
                z[i] >= 0.0 && w >= -1e-10 && (z[i] * w).abs() < 1e-10,
                "{i}: z {} w {w}",
                z[i]
            );
        }
    }

    #[test]
    fn solves_positive_definite_lcps() {
        let mut s = 1u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for case in 0..200 {
            let nn = 1 + case % 7;
            let k = 1 + case % 3;
            let a: Vec<f64> = (0..k * nn).map(|_| rnd()).collect();
            let skew: Vec<f64> = (0..nn * nn).map(|_| rnd()).collect();
            let mut m = vec![0.0; nn * nn];
            for i in 0..nn {
                for j in 0..nn {
                    m[i * nn + j] = (0..k).map(|l| a[l * nn + i] * a[l * nn + j]).sum::<f64>()
                        + skew[i * nn + j]
                        - skew[j * nn + i]
                        + if i == j { 0.1 } else { 0.0 };
                }
            }
            let c: Vec<f64> = (0..nn).map(|_| rnd()).collect();
            // Positive definite (plus skew): Lemke must end at the unique solution.
            let (z, _) = solve_lcp(&m, &c, 1e-11, 1000).unwrap();
            check_lcp(&m, &c, &z);
        }
        // A feasible PSD LCP: M = I.
        let (z, _) = solve_lcp(&[1.0, 0.0, 0.0, 1.0], &[-1.0, 2.0], 1e-11, 100).unwrap();
        assert_eq!(z, vec![1.0, 0.0]);
    }
}
