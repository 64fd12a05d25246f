//! Small dense linear algebra on the 6 degrees of freedom of a linear triangle.

/// A 6x6 matrix, row-major.
pub type Mat6 = [[f64; 6]; 6];

/// `a + s b`.
pub fn add_scaled(a: &Mat6, s: f64, b: &Mat6) -> Mat6 {
    let mut c = *a;
    for (ci, bi) in c.iter_mut().zip(b) {
        for (cij, bij) in ci.iter_mut().zip(bi) {
            *cij += s * bij;
        }
    }
    c
}

/// `m x`.
pub fn mul_vec(m: &Mat6, x: &[f64; 6]) -> [f64; 6] {
    let mut y = [0.0; 6];
    for (yi, mi) in y.iter_mut().zip(m) {
        *yi = mi.iter().zip(x).map(|(a, b)| a * b).sum();
    }
    y
}

/// The inverse of `m` restricted to the degrees of freedom where `free` holds, embedded in a
/// 6x6 matrix with zero rows and columns at the other ones, by Cholesky factorisation; `None`
/// when the restriction is not positive definite.
pub fn masked_spd_inverse(m: &Mat6, free: [bool; 6]) -> Option<Mat6> {
    let idx: Vec<usize> = (0..6).filter(|&i| free[i]).collect();
    let n = idx.len();
    let mut l = [[0.0; 6]; 6];
    for i in 0..n {
        for j in 0..=i {
            let mut s = m[idx[i]][idx[j]];
            for k in 0..j {
                s -= l[i][k] * l[j][k];
            }
            if i == j {
                if s <= 0.0 || !s.is_finite() {
                    return None;
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    let mut inv = [[0.0; 6]; 6];
    for col in 0..n {
        let mut y = [0.0; 6];
        for i in 0..n {
            let mut s = if i == col { 1.0 } else { 0.0 };
            for k in 0..i {
                s -= l[i][k] * y[k];
            }
            y[i] = s / l[i][i];
        }
        for i in (0..n).rev() {
            let mut s = y[i];
            for k in i + 1..n {
                s -= l[k][i] * y[k];
            }
            y[i] = s / l[i][i];
        }
        for i in 0..n {
            inv[idx[i]][idx[col]] = y[i];
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masked_inverse_inverts_the_free_block() {
        let mut m = [[0.0; 6]; 6];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = 1.0 / (1.0 + i as f64 + j as f64) + if i == j { 2.0 } else { 0.0 };
            }
        }
        let free = [true, false, true, true, false, true];
        let inv = masked_spd_inverse(&m, free).unwrap();
        for i in (0..6).filter(|&i| free[i]) {
            for j in (0..6).filter(|&j| free[j]) {
                let p: f64 = (0..6)
                    .filter(|&k| free[k])
                    .map(|k| m[i][k] * inv[k][j])
                    .sum();
                assert!((p - if i == j { 1.0 } else { 0.0 }).abs() < 1e-13);
            }
        }
        assert!(inv[1].iter().chain(inv[4].iter()).all(|&x| x == 0.0));
        assert!(masked_spd_inverse(&[[0.0; 6]; 6], [true; 6]).is_none());
    }
}
