//! Helpers shared by the integration tests: where the shared problem files are, scratch
//! directories, and a dense reference solver.
#![allow(dead_code, clippy::needless_range_loop)]

use std::path::{Path, PathBuf};
use xper_fclib::CsrMatrix;

/// The shared test problems (`../../../shared/fclib` from this crate), or `None` with a
/// printed reason when they are not there.
pub fn shared_dir() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/fclib");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "skipped: the shared FCLib/Siconos problems are not at {}",
            dir.display()
        );
        None
    }
}

/// Sorted files of `sub` (a folder of the shared directory).
pub fn files(shared: &Path, sub: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(shared.join(sub))
        .unwrap_or_else(|e| panic!("{sub}: {e}"))
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

/// A scratch directory removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> Self {
        use std::sync::atomic::{AtomicUsize, Ordering};
        static N: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "xper-fclib-{tag}-{}-{}",
            std::process::id(),
            N.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Row-major dense copy of `a`.
pub fn dense(a: &CsrMatrix) -> Vec<Vec<f64>> {
    let mut d = vec![vec![0.0; a.ncols]; a.nrows];
    for (i, row) in d.iter_mut().enumerate() {
        for p in a.row_ptr[i]..a.row_ptr[i + 1] {
            row[a.col_idx[p]] += a.values[p];
        }
    }
    d
}

/// Solves `A X = B` densely by Gaussian elimination with partial pivoting.
pub fn dense_solve(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let n = a.len();
    let m = b.first().map_or(0, Vec::len);
    let mut a: Vec<Vec<f64>> = a.to_vec();
    let mut x: Vec<Vec<f64>> = b.to_vec();
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, piv);
        x.swap(col, piv);
        for i in 0..n {
            if i != col {
                let f = a[i][col] / a[col][col];
                if f != 0.0 {
                    for j in col..n {
                        a[i][j] -= f * a[col][j];
                    }
                    for j in 0..m {
                        x[i][j] -= f * x[col][j];
                    }
                }
            }
        }
    }
    for i in 0..n {
        for j in 0..m {
            x[i][j] /= a[i][i];
        }
    }
    x
}

/// Dense `W = H^T M^-1 H` and `q = H^T M^-1 f + w`.
pub fn dense_reduction(
    m: &CsrMatrix,
    h: &CsrMatrix,
    f: &[f64],
    w: &[f64],
) -> (Vec<Vec<f64>>, Vec<f64>) {
    let (n, k) = (h.nrows, h.ncols);
    let hd = dense(h);
    // Right-hand sides: the columns of H, then f.
    let b: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            let mut row = hd[i].clone();
            row.push(f[i]);
            row
        })
        .collect();
    let x = dense_solve(&dense(m), &b);
    let mut wd = vec![vec![0.0; k]; k];
    let mut q = w.to_vec();
    for i in 0..k {
        for j in 0..=k {
            let v: f64 = (0..n).map(|r| hd[r][i] * x[r][j]).sum();
            if j < k {
                wd[i][j] = v;
            } else {
                q[i] += v;
            }
        }
    }
    (wd, q)
}

/// Largest `|a_ij - b_ij|` over the dense `b` and the sparse `a` (same shape).
pub fn max_diff(a: &CsrMatrix, b: &[Vec<f64>]) -> f64 {
    let ad = dense(a);
    assert_eq!(
        (ad.len(), ad.first().map_or(0, Vec::len)),
        (b.len(), b.first().map_or(0, Vec::len))
    );
    ad.iter()
        .zip(b)
        .flat_map(|(r, s)| r.iter().zip(s).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max)
}

/// Euclidean norm.
pub fn norm(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() + 0.0).sqrt()
}
