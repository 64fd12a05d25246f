//! Assembled frictional contact problems (the "local" form of Siconos and FCLib),
//! in 2D or 3D, and the error measure every solver is judged by.
//!
//! ```text
//! u = W r + q,   for each contact a: (u_a, r_a) satisfy Signorini + Coulomb with mu_a
//! ```
//!
//! Unknowns per contact are ordered `[normal, tangent]` (2D) or `[normal, t1, t2]` (3D).
//! The error is the natural-map residual with De Saxcé's shift
//! (Acary, Bremond, Huber, 2018):
//! `e_a = r_a - P_K(r_a - u_a - mu_a |u_T,a| e_n)`, `error = |e| / scale`.

/// A sparse matrix in compressed sparse row form (column indices sorted within a row,
/// no duplicates).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CsrMatrix {
    /// Number of rows.
    pub nrows: usize,
    /// Number of columns.
    pub ncols: usize,
    /// Row pointers, length `nrows + 1`.
    pub row_ptr: Vec<usize>,
    /// Column index of each stored value.
    pub col_idx: Vec<usize>,
    /// Stored values.
    pub values: Vec<f64>,
}

/// Why a problem or matrix cannot be built from the data given.
#[derive(Clone, Debug, PartialEq)]
pub struct ProblemError(pub String);

impl std::fmt::Display for ProblemError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ProblemError {}

impl CsrMatrix {
    /// Builds a matrix from `(row, column, value)` entries; duplicates are summed.
    pub fn from_triplets(
        nrows: usize,
        ncols: usize,
        entries: &[(usize, usize, f64)],
    ) -> Result<Self, ProblemError> {
        let mut counts = vec![0usize; nrows + 1];
        for (k, &(i, j, _)) in entries.iter().enumerate() {
            if i >= nrows || j >= ncols {
                return Err(ProblemError(format!(
                    "entry {k}: ({i}, {j}) outside a {nrows} x {ncols} matrix"
                )));
            }
            counts[i + 1] += 1;
        }
        for i in 0..nrows {
            counts[i + 1] += counts[i];
        }
        let mut next = counts.clone();
        let mut cols = vec![0usize; entries.len()];
        let mut vals = vec![0.0; entries.len()];
        for &(i, j, v) in entries {
            cols[next[i]] = j;
            vals[next[i]] = v;
            next[i] += 1;
        }
        let mut row_ptr = Vec::with_capacity(nrows + 1);
        let mut col_idx = Vec::with_capacity(entries.len());
        let mut values = Vec::with_capacity(entries.len());
        row_ptr.push(0);
        let mut order: Vec<usize> = Vec::new();
        for i in 0..nrows {
            order.clear();
            order.extend(counts[i]..counts[i + 1]);
            order.sort_by_key(|&k| cols[k]);
            for &k in &order {
                if col_idx.len() > row_ptr[i] && *col_idx.last().unwrap() == cols[k] {
                    *values.last_mut().unwrap() += vals[k];
                } else {
                    col_idx.push(cols[k]);
                    values.push(vals[k]);
                }
            }
            row_ptr.push(col_idx.len());
        }
        Ok(CsrMatrix {
            nrows,
            ncols,
            row_ptr,
            col_idx,
            values,
        })
    }

    /// A matrix from its compressed rows, checked: `row_ptr` has `nrows + 1` non-decreasing
    /// entries from 0 to the number of values, column indices are below `ncols` and strictly
    /// increasing within each row, values are finite. The error says which of these fails.
    pub fn from_parts(
        nrows: usize,
        ncols: usize,
        row_ptr: Vec<usize>,
        col_idx: Vec<usize>,
        values: Vec<f64>,
    ) -> Result<Self, ProblemError> {
        let bad = |why: String| Err(ProblemError(why));
        if row_ptr.len() != nrows + 1 || row_ptr[0] != 0 {
            return bad(format!(
                "row pointers: {} entries starting at {:?}; {nrows} rows need {} starting at 0",
                row_ptr.len(),
                row_ptr.first(),
                nrows + 1
            ));
        }
        if row_ptr.windows(2).any(|w| w[0] > w[1]) || row_ptr[nrows] != values.len() {
            return bad(
                "row pointers must not decrease and must end at the number of values".into(),
            );
        }
        if col_idx.len() != values.len() {
            return bad(format!(
                "{} column indices for {} values",
                col_idx.len(),
                values.len()
            ));
        }
        for (i, w) in row_ptr.windows(2).enumerate() {
            let row = &col_idx[w[0]..w[1]];
            if let Some(&c) = row.iter().find(|&&c| c >= ncols) {
                return bad(format!("row {i}: column {c} outside {ncols} columns"));
            }
            if row.windows(2).any(|p| p[0] >= p[1]) {
                return bad(format!("row {i}: column indices not strictly increasing"));
            }
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return bad(format!("value {v} is not finite"));
        }
        Ok(CsrMatrix {
            nrows,
            ncols,
            row_ptr,
            col_idx,
            values,
        })
    }

    /// Builds a matrix from dense row-major values, keeping the non-zero ones.
    pub fn from_dense_row_major(nrows: usize, ncols: usize, values: &[f64]) -> Self {
        assert_eq!(values.len(), nrows * ncols, "from_dense_row_major: size");
        let entries: Vec<(usize, usize, f64)> = (0..nrows)
            .flat_map(|i| (0..ncols).map(move |j| (i, j)))
            .filter_map(|(i, j)| {
                let v = values[i * ncols + j];
                (v != 0.0).then_some((i, j, v))
            })
            .collect();
        Self::from_triplets(nrows, ncols, &entries).expect("indices in range by construction")
    }

    /// Number of stored values.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// The entry `(i, j)`, zero when not stored.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (lo, hi) = (self.row_ptr[i], self.row_ptr[i + 1]);
        match self.col_idx[lo..hi].binary_search(&j) {
            Ok(k) => self.values[lo + k],
            Err(_) => 0.0,
        }
    }

    /// `y += A x`.
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        assert!(
            x.len() == self.ncols && y.len() == self.nrows,
            "mul_add: size"
        );
        for (i, yi) in y.iter_mut().enumerate() {
            let (lo, hi) = (self.row_ptr[i], self.row_ptr[i + 1]);
            *yi += self.col_idx[lo..hi]
                .iter()
                .zip(&self.values[lo..hi])
                .map(|(&j, &v)| v * x[j])
                .sum::<f64>();
        }
    }

    /// The transpose.
    pub fn transpose(&self) -> CsrMatrix {
        let entries: Vec<(usize, usize, f64)> = (0..self.nrows)
            .flat_map(|i| {
                (self.row_ptr[i]..self.row_ptr[i + 1])
                    .map(move |k| (self.col_idx[k], i, self.values[k]))
            })
            .collect();
        Self::from_triplets(self.ncols, self.nrows, &entries).expect("transpose in range")
    }

    /// All stored values finite.
    pub fn is_finite(&self) -> bool {
        self.values.iter().all(|v| v.is_finite())
    }
}

/// An assembled frictional contact problem `u = W r + q` with friction coefficients `mu`.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionProblem {
    /// Local dimension: 2 (normal, tangent) or 3 (normal, t1, t2).
    pub dim: usize,
    /// The Delassus operator, `dim n x dim n`.
    pub w: CsrMatrix,
    /// The free local velocity, length `dim n`.
    pub q: Vec<f64>,
    /// Friction coefficient per contact, length `n`.
    pub mu: Vec<f64>,
}

impl FrictionProblem {
    /// Checks the sizes and values and builds the problem.
    pub fn new(dim: usize, w: CsrMatrix, q: Vec<f64>, mu: Vec<f64>) -> Result<Self, ProblemError> {
        if dim != 2 && dim != 3 {
            return Err(ProblemError(format!("dimension {dim} is not 2 or 3")));
        }
        let m = dim * mu.len();
        if w.nrows != m || w.ncols != m || q.len() != m {
            return Err(ProblemError(format!(
                "{} contacts in {dim}D need W {m} x {m} and q of length {m}; got W {} x {} and q of length {}",
                mu.len(),
                w.nrows,
                w.ncols,
                q.len()
            )));
        }
        if let Some(k) = q.iter().position(|v| !v.is_finite()) {
            return Err(ProblemError(format!("q[{k}] = {} is not finite", q[k])));
        }
        if let Some(a) = mu.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(ProblemError(format!(
                "mu[{a}] = {} is not a finite non-negative number",
                mu[a]
            )));
        }
        if !w.is_finite() {
            return Err(ProblemError("W holds a non-finite value".into()));
        }
        Ok(FrictionProblem { dim, w, q, mu })
    }

    /// Number of contacts.
    pub fn contact_count(&self) -> usize {
        self.mu.len()
    }

    /// `u = W r + q`.
    pub fn velocity(&self, r: &[f64]) -> Vec<f64> {
        let mut u = self.q.clone();
        self.w.mul_add(r, &mut u);
        u
    }

    /// The error of `r` by the shared measure.
    pub fn error(&self, r: &[f64]) -> ProblemErrorMeasure {
        let u = self.velocity(r);
        error_measure(self.dim, &self.q, &u, r, &self.mu)
    }
}

/// The natural-map error of a solution under both published scalings.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ProblemErrorMeasure {
    /// `sqrt(sum |e_a|^2)`.
    pub absolute: f64,
    /// Divided by `|q|` (Acary, Bremond, Huber 2018); `absolute` when `|q| = 0`.
    pub relative_q: f64,
    /// Divided by `max(|q|, |r|, |u|)` (Siconos since 2020); `absolute` when all are zero.
    pub relative_max: f64,
}

/// Projection of the local vector `x` (`[n, t]` or `[n, t1, t2]`) on the Coulomb cone
/// `|t| <= mu n`, in place.
pub fn project_on_cone_nd(x: &mut [f64], mu: f64) {
    let n = x[0];
    let t_norm = x[1..].iter().map(|t| t * t).sum::<f64>().sqrt();
    if mu * t_norm <= -n {
        x.fill(0.0);
    } else if t_norm <= mu * n {
    } else {
        let np = (mu * t_norm + n) / (mu * mu + 1.0);
        x[0] = np;
        for t in &mut x[1..] {
            *t *= mu * np / t_norm;
        }
    }
}

/// The shared error measure of `r` with local velocities `u = W r + q`.
pub fn error_measure(
    dim: usize,
    q: &[f64],
    u: &[f64],
    r: &[f64],
    mu: &[f64],
) -> ProblemErrorMeasure {
    let mut sum = 0.0;
    let mut x = [0.0; 3];
    for (a, &mu_a) in mu.iter().enumerate() {
        let (ua, ra) = (&u[dim * a..dim * (a + 1)], &r[dim * a..dim * (a + 1)]);
        let ut_norm = ua[1..].iter().map(|t| t * t).sum::<f64>().sqrt();
        let x = &mut x[..dim];
        for k in 0..dim {
            x[k] = ra[k] - ua[k];
        }
        x[0] -= mu_a * ut_norm;
        project_on_cone_nd(x, mu_a);
        sum += (0..dim).map(|k| (ra[k] - x[k]).powi(2)).sum::<f64>();
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let absolute = sum.sqrt();
    let scaled = |s: f64| if s > 0.0 { absolute / s } else { absolute };
    ProblemErrorMeasure {
        absolute,
        relative_q: scaled(norm(q)),
        relative_max: scaled(norm(q).max(norm(r)).max(norm(u))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_are_checked_and_equal_the_triplets() {
        let entries = [(0, 0, 2.0), (0, 2, -1.0), (2, 1, 4.0)];
        let m = CsrMatrix::from_triplets(3, 3, &entries).unwrap();
        let parts =
            |p: Vec<usize>, c: Vec<usize>, v: Vec<f64>| CsrMatrix::from_parts(3, 3, p, c, v);
        let same = parts(m.row_ptr.clone(), m.col_idx.clone(), m.values.clone()).unwrap();
        assert_eq!(same, m);
        let why = |r: Result<CsrMatrix, ProblemError>| r.unwrap_err().0;
        assert!(why(parts(vec![0, 2, 2], vec![0, 2, 1], vec![1.0; 3])).contains("3 rows need 4"));
        assert!(
            why(parts(vec![0, 2, 1, 3], vec![0, 2, 1], vec![1.0; 3])).contains("must not decrease")
        );
        assert!(why(parts(vec![0, 2, 2, 3], vec![2, 0, 1], vec![1.0; 3]))
            .contains("row 0: column indices"));
        assert!(
            why(parts(vec![0, 2, 2, 3], vec![0, 3, 1], vec![1.0; 3])).contains("column 3 outside")
        );
        assert!(why(parts(
            vec![0, 2, 2, 3],
            vec![0, 2, 1],
            vec![1.0, f64::NAN, 1.0]
        ))
        .contains("not finite"));
    }

    #[test]
    fn triplets_sum_duplicates_and_sort() {
        let m =
            CsrMatrix::from_triplets(2, 3, &[(1, 2, 1.0), (0, 1, 2.0), (1, 0, 3.0), (1, 2, 4.0)])
                .unwrap();
        assert_eq!(m.row_ptr, vec![0, 1, 3]);
        assert_eq!(m.col_idx, vec![1, 0, 2]);
        assert_eq!(m.values, vec![2.0, 3.0, 5.0]);
        assert_eq!(m.transpose().get(2, 1), 5.0);
        let mut y = vec![0.0; 2];
        m.mul_add(&[1.0, 1.0, 1.0], &mut y);
        assert_eq!(y, vec![2.0, 8.0]);
        assert!(CsrMatrix::from_triplets(2, 2, &[(2, 0, 1.0)]).is_err());
    }

    #[test]
    fn error_is_zero_at_a_known_solution_and_positive_elsewhere() {
        // One 3D contact, W = I, q = (-1, 0.5, 0), mu = 0.2: sticking is impossible
        // (|q_t| / 1 > mu * 1); the solution slides: r_n = 1, r_t = -mu (1, 0).
        let w = CsrMatrix::from_dense_row_major(3, 3, &[1., 0., 0., 0., 1., 0., 0., 0., 1.]);
        let p = FrictionProblem::new(3, w, vec![-1.0, 0.5, 0.0], vec![0.2]).unwrap();
        let e = p.error(&[1.0, -0.2, 0.0]);
        assert!(e.absolute < 1e-15, "{e:?}");
        assert!(p.error(&[1.0, 0.0, 0.0]).absolute > 0.1);
        assert!(FrictionProblem::new(3, CsrMatrix::default(), vec![], vec![-1.0]).is_err());
    }
}
