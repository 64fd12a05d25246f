//! Reproducible random numbers (splitmix64): right-hand sides for tests and benchmarks, and
//! the random error of [`crate::Multigrid::asymptotic_factor`].

/// `n` reproducible uniform random numbers in `[-1, 1)` from `seed` (a right-hand side for
/// tests and benchmarks).
pub fn random_values(n: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..n).map(|_| random(&mut state)).collect()
}

/// A reproducible uniform random number in `[-1, 1)` (splitmix64).
pub fn random(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}
