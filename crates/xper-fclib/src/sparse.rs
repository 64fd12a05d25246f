//! Checked conversions from the storage layouts found in files (CSR, CSC, triplet,
//! column-major dense) to [`CsrMatrix`]. Every index and pointer is checked before use;
//! the error is a reason in words, to which the caller adds the file and position.

use xper_solver::CsrMatrix;

#[cfg_attr(not(feature = "hdf5"), allow(dead_code))]
/// Converts a file integer to an index, rejecting negative values and values `>= bound`.
fn index(v: i64, bound: usize, what: &str, k: usize) -> Result<usize, String> {
    usize::try_from(v)
        .ok()
        .filter(|&u| u < bound)
        .ok_or_else(|| format!("{what}[{k}] = {v} is outside 0..{bound}"))
}

#[cfg_attr(not(feature = "hdf5"), allow(dead_code))]
/// A compressed matrix (CSR when `by_row`, CSC otherwise): `ptr` has one entry per row
/// (resp. column) plus one, `idx` holds column (resp. row) indices. `idx` and `val` may be
/// longer than the `ptr[last]` entries used (FCLib's `nzmax`); duplicates are summed.
pub(crate) fn from_compressed(
    nrows: usize,
    ncols: usize,
    ptr: &[i64],
    idx: &[i64],
    val: &[f64],
    by_row: bool,
) -> Result<CsrMatrix, String> {
    let (outer, inner, ptr_name) = if by_row {
        (nrows, ncols, "row pointer")
    } else {
        (ncols, nrows, "column pointer")
    };
    if ptr.len() != outer + 1 {
        return Err(format!(
            "{ptr_name} array has {} entries; {outer} + 1 expected",
            ptr.len()
        ));
    }
    if ptr[0] != 0 {
        return Err(format!("{ptr_name}[0] = {} is not 0", ptr[0]));
    }
    let nnz = usize::try_from(ptr[outer]).map_err(|_| format!("{ptr_name}[{outer}] < 0"))?;
    if nnz > idx.len() || nnz > val.len() {
        return Err(format!(
            "{ptr_name}[{outer}] = {nnz} stored values, but only {} indices and {} values are given",
            idx.len(),
            val.len()
        ));
    }
    let mut entries = Vec::with_capacity(nnz);
    for o in 0..outer {
        let (lo, hi) = (ptr[o], ptr[o + 1]);
        if hi < lo {
            return Err(format!(
                "{ptr_name}s decrease: [{o}] = {lo}, [{}] = {hi}",
                o + 1
            ));
        }
        // 0 <= lo <= hi <= nnz: ptr[0] = 0, the pointers do not decrease, ptr[outer] = nnz.
        if hi > ptr[outer] {
            return Err(format!(
                "{ptr_name}[{}] = {hi} exceeds the {nnz} stored values",
                o + 1
            ));
        }
        for k in lo as usize..hi as usize {
            let i = index(idx[k], inner, "index", k)?;
            let (r, c) = if by_row { (o, i) } else { (i, o) };
            entries.push((r, c, val[k]));
        }
    }
    CsrMatrix::from_triplets(nrows, ncols, &entries).map_err(|e| e.0)
}

#[cfg_attr(not(feature = "hdf5"), allow(dead_code))]
/// A triplet matrix: entry `k` is `(rows[k], cols[k], vals[k])`; duplicates are summed.
pub(crate) fn from_triplets(
    nrows: usize,
    ncols: usize,
    rows: &[i64],
    cols: &[i64],
    vals: &[f64],
) -> Result<CsrMatrix, String> {
    if rows.len() != cols.len() || rows.len() != vals.len() {
        return Err(format!(
            "triplet arrays of different lengths: {} rows, {} columns, {} values",
            rows.len(),
            cols.len(),
            vals.len()
        ));
    }
    let mut entries = Vec::with_capacity(rows.len());
    for k in 0..rows.len() {
        let i = index(rows[k], nrows, "row index", k)?;
        let j = index(cols[k], ncols, "column index", k)?;
        entries.push((i, j, vals[k]));
    }
    CsrMatrix::from_triplets(nrows, ncols, &entries).map_err(|e| e.0)
}

/// A dense matrix stored column by column; exact zeros are not stored.
pub(crate) fn from_dense_col_major(nrows: usize, ncols: usize, vals: &[f64]) -> CsrMatrix {
    debug_assert_eq!(vals.len(), nrows * ncols);
    let mut entries = Vec::new();
    for (k, &v) in vals.iter().enumerate() {
        if v != 0.0 {
            entries.push((k % nrows, k / nrows, v));
        }
    }
    CsrMatrix::from_triplets(nrows, ncols, &entries).expect("indices in range by construction")
}

/// If the off-diagonal entries of the square matrix `a` all lie on one side of the
/// diagonal (and there is at least one), `a` is taken as the stored triangle of a
/// symmetric matrix (LMGC90 writes its mass matrices that way) and the full matrix is
/// returned; otherwise `a` itself.
pub(crate) fn complete_symmetric_triangle(a: CsrMatrix) -> CsrMatrix {
    if a.nrows != a.ncols {
        return a;
    }
    let (mut upper, mut lower) = (false, false);
    for i in 0..a.nrows {
        for &j in &a.col_idx[a.row_ptr[i]..a.row_ptr[i + 1]] {
            upper |= j > i;
            lower |= j < i;
        }
    }
    if upper == lower {
        return a;
    }
    let mut entries = Vec::with_capacity(2 * a.nnz());
    for i in 0..a.nrows {
        for p in a.row_ptr[i]..a.row_ptr[i + 1] {
            let (j, v) = (a.col_idx[p], a.values[p]);
            entries.push((i, j, v));
            if j != i {
                entries.push((j, i, v));
            }
        }
    }
    CsrMatrix::from_triplets(a.nrows, a.ncols, &entries).expect("same shape")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layouts_agree() {
        // [[1, 0, 2], [0, 3, 0]]
        let csr = from_compressed(2, 3, &[0, 2, 3], &[0, 2, 1], &[1., 2., 3.], true).unwrap();
        let csc = from_compressed(2, 3, &[0, 1, 2, 3], &[0, 1, 0], &[1., 3., 2.], false).unwrap();
        let tri = from_triplets(2, 3, &[1, 0, 0], &[1, 2, 0], &[3., 2., 1.]).unwrap();
        let dense = from_dense_col_major(2, 3, &[1., 0., 0., 3., 2., 0.]);
        assert_eq!(csr, csc);
        assert_eq!(csr, tri);
        assert_eq!(csr, dense);
        assert_eq!(csr.get(0, 2), 2.0);
    }

    #[test]
    fn bad_indices_and_pointers_are_errors() {
        assert!(from_compressed(2, 2, &[0, 1], &[0], &[1.], true).is_err());
        assert!(from_compressed(2, 2, &[1, 1, 1], &[0], &[1.], true).is_err());
        assert!(from_compressed(2, 2, &[0, 2, 1], &[0, 1], &[1., 1.], true).is_err());
        assert!(from_compressed(2, 2, &[0, 1, 3], &[0, 1], &[1., 1.], true).is_err());
        assert!(from_compressed(2, 2, &[0, 1, 2], &[0, 2], &[1., 1.], true).is_err());
        assert!(from_compressed(2, 2, &[0, 1, 2], &[0, -1], &[1., 1.], true).is_err());
        assert!(from_triplets(2, 2, &[0, 2], &[0, 0], &[1., 1.]).is_err());
        assert!(from_triplets(2, 2, &[0], &[0, 0], &[1.]).is_err());
        // nzmax longer than used is fine; duplicates are summed.
        let m = from_triplets(2, 2, &[1, 1], &[0, 0], &[1., 2.]).unwrap();
        assert_eq!(m.get(1, 0), 3.0);
        let m = from_compressed(2, 2, &[0, 1, 1], &[1, 9], &[4., 9.], true).unwrap();
        assert_eq!(m.nnz(), 1);
    }

    #[test]
    fn one_triangle_is_completed_and_full_matrices_are_kept() {
        let up = from_triplets(3, 3, &[0, 0, 1, 2], &[0, 2, 1, 2], &[4., 1., 5., 6.]).unwrap();
        let full = complete_symmetric_triangle(up);
        assert_eq!((full.get(2, 0), full.get(0, 2), full.nnz()), (1.0, 1.0, 5));
        assert_eq!(complete_symmetric_triangle(full.clone()), full);
        let diag = from_triplets(2, 2, &[0, 1], &[0, 1], &[1., 2.]).unwrap();
        assert_eq!(complete_symmetric_triangle(diag.clone()), diag);
    }
}
