//! How a solver sees the Delassus operator `W`.

/// A 2x2 block of `W` in the contact frame, row-major: `[W_nn, W_nt, W_tn, W_tt]`.
pub type Block2 = [f64; 4];

/// Product of a block with a local vector.
#[inline(always)]
pub fn block_mul(w: &Block2, r: [f64; 2]) -> [f64; 2] {
    [w[0] * r[0] + w[1] * r[1], w[2] * r[0] + w[3] * r[1]]
}

/// The Delassus operator of a problem together with the state it updates.
///
/// Implementations keep `U = W R + q` consistent with every impulse applied so far.
pub trait ContactOperator {
    /// Number of contacts.
    fn contact_count(&self) -> usize;
    /// The diagonal block `W_aa`.
    fn diagonal_block(&self, a: usize) -> Block2;
    /// The current local velocity `U_a` (without the normal shift).
    fn local_velocity(&self, a: usize) -> [f64; 2];
    /// Adds `delta` to the impulse of contact `a` and updates the state.
    fn apply_impulse(&mut self, a: usize, delta: [f64; 2]);
    /// One Gauss-Seidel update of contact `a`: `solve(W_aa, U_a)` gives the impulse increment,
    /// which is applied (unless zero) and returned with `W_aa`. The same as
    /// [`Self::diagonal_block`], [`Self::local_velocity`] and [`Self::apply_impulse`] in turn;
    /// an operator overrides it to read the contact's data once for all three.
    #[inline(always)]
    fn update_contact(
        &mut self,
        a: usize,
        solve: impl FnOnce(&Block2, [f64; 2]) -> [f64; 2],
    ) -> (Block2, [f64; 2]) {
        let w = self.diagonal_block(a);
        let delta = solve(&w, self.local_velocity(a));
        if delta[0] != 0.0 || delta[1] != 0.0 {
            self.apply_impulse(a, delta);
        }
        (w, delta)
    }
}

/// A 2D problem with an explicit dense `W` (for tests, small problems and file readers).
#[derive(Clone, Debug, PartialEq)]
pub struct DenseProblem {
    /// `W`, size `2n x 2n`, row-major.
    pub w: Vec<f64>,
    /// `q`, size `2n`.
    pub q: Vec<f64>,
    /// Friction coefficient per contact.
    pub mu: Vec<f64>,
    /// Current `U = W R + q`.
    velocity: Vec<f64>,
}

impl DenseProblem {
    /// A problem `U = W R + q` with zero impulses.
    ///
    /// # Panics
    /// If the sizes disagree (a programming error, not bad data).
    pub fn new(w: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> Self {
        let n = mu.len();
        assert!(
            q.len() == 2 * n && w.len() == 4 * n * n,
            "DenseProblem: inconsistent sizes"
        );
        DenseProblem {
            velocity: q.clone(),
            w,
            q,
            mu,
        }
    }

    /// Resets the state to zero impulses.
    pub fn reset(&mut self) {
        self.velocity.clone_from(&self.q);
    }

    /// `W R + q` for arbitrary impulses (independent of the incremental state).
    pub fn velocity_for(&self, impulses: &[[f64; 2]]) -> Vec<[f64; 2]> {
        let m = 2 * self.mu.len();
        (0..self.mu.len())
            .map(|a| {
                let mut u = [self.q[2 * a], self.q[2 * a + 1]];
                for (b, r) in impulses.iter().enumerate() {
                    for (k, uk) in u.iter_mut().enumerate() {
                        let row = (2 * a + k) * m;
                        *uk += self.w[row + 2 * b] * r[0] + self.w[row + 2 * b + 1] * r[1];
                    }
                }
                u
            })
            .collect()
    }
}

impl ContactOperator for DenseProblem {
    fn contact_count(&self) -> usize {
        self.mu.len()
    }
    fn diagonal_block(&self, a: usize) -> Block2 {
        let m = 2 * self.mu.len();
        let (r0, r1) = (2 * a * m, (2 * a + 1) * m);
        [
            self.w[r0 + 2 * a],
            self.w[r0 + 2 * a + 1],
            self.w[r1 + 2 * a],
            self.w[r1 + 2 * a + 1],
        ]
    }
    fn local_velocity(&self, a: usize) -> [f64; 2] {
        [self.velocity[2 * a], self.velocity[2 * a + 1]]
    }
    fn apply_impulse(&mut self, a: usize, delta: [f64; 2]) {
        let m = 2 * self.mu.len();
        for i in 0..m {
            self.velocity[i] +=
                self.w[i * m + 2 * a] * delta[0] + self.w[i * m + 2 * a + 1] * delta[1];
        }
    }
}
