//! The reduction of global problems to `W = H^T M^-1 H`, `q = H^T M^-1 f + w`, checked
//! against a dense computation on hand-made problems, through each factorisation path.

mod common;

use common::{dense_reduction, max_diff, norm};
use xper_fclib::{CsrMatrix, Factorization, GlobalFrictionProblem};

/// Deterministic pseudo-random numbers in [-1, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

fn matrix(n: usize, m: usize, entries: &[(usize, usize, f64)]) -> CsrMatrix {
    CsrMatrix::from_triplets(n, m, entries).unwrap()
}

/// `n x n` tridiagonal: `diag[i]`, `upper` above, `lower` below.
fn tridiagonal(n: usize, diag: impl Fn(usize) -> f64, upper: f64, lower: f64) -> CsrMatrix {
    let mut e = Vec::new();
    for i in 0..n {
        e.push((i, i, diag(i)));
        if i + 1 < n {
            e.push((i, i + 1, upper));
            e.push((i + 1, i, lower));
        }
    }
    matrix(n, n, &e)
}

/// A problem with mass matrix `m`, a random `H` with `k` columns (about 3 entries each),
/// random `f`, `w`, `mu`.
fn problem(dim: usize, m: CsrMatrix, nc: usize, seed: u64) -> GlobalFrictionProblem {
    let (n, k) = (m.nrows, dim * nc);
    let mut rng = Lcg(seed);
    let mut e = Vec::new();
    for j in 0..k {
        for _ in 0..3 {
            let i = ((rng.next() + 1.0) * 0.5 * n as f64) as usize % n;
            e.push((i, j, rng.next()));
        }
    }
    let h = matrix(n, k, &e);
    let f = (0..n).map(|_| rng.next()).collect();
    let w = (0..k).map(|_| rng.next()).collect();
    let mu = (0..nc).map(|_| 0.5 * (rng.next() + 1.0)).collect();
    GlobalFrictionProblem::new(dim, m, h, f, w, mu).unwrap()
}

/// Reduces `p`, compares with the dense reduction, returns the factorisation used.
fn check_against_dense(p: &GlobalFrictionProblem) -> Factorization {
    let red = p.reduce().unwrap();
    let (wd, qd) = dense_reduction(&p.m, &p.h, &p.f, &p.w);
    let scale = wd.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let dw = max_diff(&red.problem.w, &wd);
    assert!(dw <= 1e-12 * scale, "W differs by {dw:e} (scale {scale:e})");
    let dq: f64 = red
        .problem
        .q
        .iter()
        .zip(&qd)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(dq <= 1e-12 * norm(&qd), "q differs by {dq:e}");
    assert_eq!(red.problem.mu, p.mu);
    assert_eq!(red.problem.dim, p.dim);
    red.factorization
}

#[test]
fn sign_convention_m_v_equals_h_r_plus_f() {
    // M = 2 I, H = I: v = (r + f) / 2, u = v + w, so W = I / 2 and q = f / 2 + w.
    let m = matrix(2, 2, &[(0, 0, 2.0), (1, 1, 2.0)]);
    let h = matrix(2, 2, &[(0, 0, 1.0), (1, 1, 1.0)]);
    let p = GlobalFrictionProblem::new(2, m, h, vec![2.0, 4.0], vec![1.0, 1.0], vec![0.3]).unwrap();
    let l = p.to_local().unwrap();
    assert_eq!(l.w, matrix(2, 2, &[(0, 0, 0.5), (1, 1, 0.5)]));
    assert_eq!(l.q, vec![2.0, 3.0]);
    assert_eq!(l.mu, vec![0.3]);
}

#[test]
fn small_coupled_mass_is_one_dense_cholesky_block() {
    let m = matrix(
        5,
        5,
        &[
            (0, 0, 4.0),
            (0, 1, 1.0),
            (0, 4, 0.5),
            (1, 0, 1.0),
            (1, 1, 3.0),
            (1, 2, 0.2),
            (2, 1, 0.2),
            (2, 2, 2.0),
            (2, 3, 0.1),
            (3, 2, 0.1),
            (3, 3, 5.0),
            (3, 4, 1.0),
            (4, 0, 0.5),
            (4, 3, 1.0),
            (4, 4, 6.0),
        ],
    );
    let p = problem(2, m, 2, 1);
    let kind = check_against_dense(&p);
    assert_eq!(
        kind,
        Factorization::BlockDiagonal {
            blocks: 1,
            largest: 5,
            lu: false
        }
    );
}

#[test]
fn rigid_bodies_give_blocks_and_the_contact_graph_sparsity() {
    // Three 2D bodies (x, y, rotation), the first with a coupled 3 x 3 block.
    let mut e = vec![
        (0, 0, 2.0),
        (0, 1, 0.1),
        (0, 2, 0.3),
        (1, 0, 0.1),
        (1, 1, 2.0),
        (2, 0, 0.3),
        (2, 2, 0.5),
    ];
    for b in 1..3 {
        for d in 0..3 {
            e.push((3 * b + d, 3 * b + d, 1.0 + b as f64 + 0.1 * d as f64));
        }
    }
    let m = matrix(9, 9, &e);
    // Contact 0 between bodies 0 and 1, contact 1 on body 2 only.
    let mut h = Vec::new();
    for (c, bodies) in [(0usize, vec![0usize, 1]), (1, vec![2])] {
        for (s, &b) in bodies.iter().enumerate() {
            let sign = if s == 0 { 1.0 } else { -1.0 };
            h.push((3 * b, 2 * c, sign * 0.6));
            h.push((3 * b + 1, 2 * c, sign * 0.8));
            h.push((3 * b + 1, 2 * c + 1, sign * 0.6));
            h.push((3 * b + 2, 2 * c + 1, 0.25));
        }
    }
    let h = matrix(9, 4, &h);
    let p =
        GlobalFrictionProblem::new(2, m, h, vec![0.5; 9], vec![0.0; 4], vec![0.2, 0.4]).unwrap();
    let kind = check_against_dense(&p);
    assert_eq!(
        kind,
        Factorization::BlockDiagonal {
            blocks: 7,
            largest: 3,
            lu: false
        }
    );
    let w = p.to_local().unwrap().w;
    // The two contacts share no body: no coupling stored, and each 2 x 2 block is full.
    assert_eq!(w.nnz(), 8);
    for (i, j) in [(0, 2), (0, 3), (1, 2), (3, 1)] {
        assert_eq!(w.get(i, j), 0.0);
    }
}

#[test]
fn large_spd_mass_uses_sparse_cholesky() {
    let m = tridiagonal(60, |i| 2.5 + 0.01 * i as f64, -1.0, -1.0);
    let p = problem(3, m, 5, 2);
    assert_eq!(check_against_dense(&p), Factorization::Cholesky);
    let w = p.to_local().unwrap().w;
    for i in 0..w.nrows {
        for j in 0..w.ncols {
            assert!((w.get(i, j) - w.get(j, i)).abs() <= 1e-14 * w.get(i, i).abs().max(1.0));
        }
    }
}

#[test]
fn non_symmetric_mass_uses_sparse_lu() {
    let m = tridiagonal(60, |_| 3.0, -1.0, -0.5);
    let p = problem(2, m, 7, 3);
    assert_eq!(check_against_dense(&p), Factorization::Lu);
}

#[test]
fn symmetric_indefinite_mass_falls_back_to_lu() {
    let m = tridiagonal(60, |i| if i % 2 == 0 { 3.0 } else { -3.0 }, 1.0, 1.0);
    let p = problem(3, m, 4, 4);
    assert_eq!(check_against_dense(&p), Factorization::Lu);
}

#[test]
fn singular_mass_is_an_error_not_garbage() {
    // Sparse path: a Neumann Laplacian (rows sum to zero).
    let n = 50;
    let m = tridiagonal(
        n,
        |i| if i == 0 || i == n - 1 { 1.0 } else { 2.0 },
        -1.0,
        -1.0,
    );
    let e = problem(2, m, 3, 5).to_local().unwrap_err();
    assert!(e.0.contains("singular"), "{e}");
    // Block path: a rank-one 2 x 2 block.
    let m = matrix(
        3,
        3,
        &[
            (0, 0, 1.0),
            (0, 1, 1.0),
            (1, 0, 1.0),
            (1, 1, 1.0),
            (2, 2, 1.0),
        ],
    );
    let e = problem(2, m, 1, 6).to_local().unwrap_err();
    assert!(e.0.contains("singular"), "{e}");
}

#[test]
fn no_contact_needs_no_factorisation() {
    let m = matrix(3, 3, &[(0, 0, 1.0), (1, 1, 1.0), (2, 2, 1.0)]);
    let p =
        GlobalFrictionProblem::new(3, m, matrix(3, 0, &[]), vec![1.0; 3], vec![], vec![]).unwrap();
    let r = p.reduce().unwrap();
    assert_eq!(r.factorization, Factorization::None);
    assert_eq!((r.problem.contact_count(), r.problem.w.nrows), (0, 0));
}

#[test]
fn new_rejects_inconsistent_data() {
    let eye = |n| matrix(n, n, &(0..n).map(|i| (i, i, 1.0)).collect::<Vec<_>>());
    let h = || matrix(3, 3, &[(0, 0, 1.0)]);
    let ok = GlobalFrictionProblem::new(3, eye(3), h(), vec![0.0; 3], vec![0.0; 3], vec![0.1]);
    assert!(ok.is_ok());
    let cases = [
        GlobalFrictionProblem::new(4, eye(3), h(), vec![0.0; 3], vec![0.0; 3], vec![0.1]),
        GlobalFrictionProblem::new(3, eye(2), h(), vec![0.0; 3], vec![0.0; 3], vec![0.1]),
        GlobalFrictionProblem::new(3, eye(3), h(), vec![0.0; 3], vec![0.0; 2], vec![0.1]),
        GlobalFrictionProblem::new(3, eye(3), h(), vec![0.0; 3], vec![0.0; 3], vec![0.1, 0.2]),
        GlobalFrictionProblem::new(
            3,
            eye(3),
            h(),
            vec![f64::NAN, 0.0, 0.0],
            vec![0.0; 3],
            vec![0.1],
        ),
        GlobalFrictionProblem::new(3, eye(3), h(), vec![0.0; 3], vec![0.0; 3], vec![-0.1]),
        GlobalFrictionProblem::new(3, eye(3), h(), vec![0.0; 3], vec![0.0; 3], vec![f64::NAN]),
        GlobalFrictionProblem::new(
            3,
            eye(3),
            matrix(3, 3, &[(0, 0, f64::INFINITY)]),
            vec![0.0; 3],
            vec![0.0; 3],
            vec![0.1],
        ),
    ];
    for (k, c) in cases.iter().enumerate() {
        assert!(c.is_err(), "case {k} accepted");
    }
    // Fields set directly are checked again before a reduction.
    let mut p = ok.unwrap();
    p.h.col_idx[0] = 7;
    assert!(p.to_local().unwrap_err().0.contains("consistent CSR"));
    p.h.col_idx[0] = 0;
    p.w.push(0.0);
    assert!(p.to_local().is_err());
}
