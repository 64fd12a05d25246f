//! How a solver sees the Delassus operator `W`.

use std::marker::PhantomData;

use crate::frame::{dot, is_zero, ContactFrame, Frame2};

/// A 2x2 block of `W` in the contact frame, row-major: `[W_nn, W_nt, W_tn, W_tt]`.
pub type Block2 = [f64; 4];

/// Product of a block with a local vector.
#[inline(always)]
pub fn block_mul(w: &Block2, r: [f64; 2]) -> [f64; 2] {
    [w[0] * r[0] + w[1] * r[1], w[2] * r[0] + w[3] * r[1]]
}

/// The diagonal-block type of an operator's frame.
pub type BlockOf<O> = <<O as ContactOperator>::Frame as ContactFrame>::Block;
/// The local-vector type of an operator's frame.
pub type VectorOf<O> = <<O as ContactOperator>::Frame as ContactFrame>::Vector;

/// The Delassus operator of a problem together with the state it updates.
///
/// Implementations keep `U = W R + q` consistent with every impulse applied so far.
pub trait ContactOperator {
    /// The contact frame (2 or 3 components per contact).
    type Frame: ContactFrame;
    /// Number of contacts.
    fn contact_count(&self) -> usize;
    /// The diagonal block `W_aa`.
    fn diagonal_block(&self, a: usize) -> BlockOf<Self>;
    /// The current local velocity `U_a` (without the normal shift).
    fn local_velocity(&self, a: usize) -> VectorOf<Self>;
    /// Adds `delta` to the impulse of contact `a` and updates the state.
    fn apply_impulse(&mut self, a: usize, delta: VectorOf<Self>);
    /// One Gauss-Seidel update of contact `a`: `solve(W_aa, U_a)` gives the impulse increment,
    /// which is applied (unless zero) and returned with `W_aa`. The same as
    /// [`Self::diagonal_block`], [`Self::local_velocity`] and [`Self::apply_impulse`] in turn;
    /// an operator overrides it to read the contact's data once for all three.
    #[inline(always)]
    fn update_contact(
        &mut self,
        a: usize,
        solve: impl FnOnce(&BlockOf<Self>, VectorOf<Self>) -> VectorOf<Self>,
    ) -> (BlockOf<Self>, VectorOf<Self>) {
        let w = self.diagonal_block(a);
        let delta = solve(&w, self.local_velocity(a));
        if !is_zero(&delta) {
            self.apply_impulse(a, delta);
        }
        (w, delta)
    }
}

/// A problem with an explicit dense `W` in frame `F` (for tests, small problems and file
/// readers); `d` below is `F::SIZE`.
#[derive(Clone, Debug, PartialEq)]
pub struct DenseProblem<F: ContactFrame = Frame2> {
    /// `W`, size `dn x dn`, row-major.
    pub w: Vec<f64>,
    /// `q`, size `dn`.
    pub q: Vec<f64>,
    /// Friction coefficient per contact.
    pub mu: Vec<f64>,
    /// Current `U = W R + q`.
    velocity: Vec<f64>,
    frame: PhantomData<F>,
}

impl DenseProblem {
    /// A 2D problem `U = W R + q` with zero impulses.
    ///
    /// # Panics
    /// If the sizes disagree (a programming error, not bad data).
    pub fn new(w: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> Self {
        Self::in_frame(w, q, mu)
    }
}

impl<F: ContactFrame> DenseProblem<F> {
    /// A problem `U = W R + q` in frame `F` with zero impulses.
    ///
    /// # Panics
    /// If the sizes disagree (a programming error, not bad data).
    pub fn in_frame(w: Vec<f64>, q: Vec<f64>, mu: Vec<f64>) -> Self {
        let (n, d) = (mu.len(), F::SIZE);
        assert!(
            q.len() == d * n && w.len() == d * d * n * n,
            "DenseProblem: inconsistent sizes"
        );
        DenseProblem {
            velocity: q.clone(),
            w,
            q,
            mu,
            frame: PhantomData,
        }
    }

    /// Resets the state to zero impulses.
    pub fn reset(&mut self) {
        self.velocity.clone_from(&self.q);
    }

    /// `W R + q` for arbitrary impulses (independent of the incremental state).
    pub fn velocity_for(&self, impulses: &[F::Vector]) -> Vec<F::Vector> {
        let (d, n) = (F::SIZE, self.mu.len());
        let m = d * n;
        (0..n)
            .map(|a| {
                let mut u = F::Vector::default();
                u.as_mut().copy_from_slice(&self.q[d * a..d * a + d]);
                for (b, r) in impulses.iter().enumerate() {
                    for (k, uk) in u.as_mut().iter_mut().enumerate() {
                        let row = (d * a + k) * m;
                        *uk += dot(&self.w[row + d * b..row + d * b + d], r.as_ref());
                    }
                }
                u
            })
            .collect()
    }
}

impl<F: ContactFrame> ContactOperator for DenseProblem<F> {
    type Frame = F;
    fn contact_count(&self) -> usize {
        self.mu.len()
    }
    fn diagonal_block(&self, a: usize) -> F::Block {
        let (d, m) = (F::SIZE, F::SIZE * self.mu.len());
        let mut block = F::Block::default();
        for (k, row) in block.as_mut().chunks_exact_mut(d).enumerate() {
            let start = (d * a + k) * m + d * a;
            row.copy_from_slice(&self.w[start..start + d]);
        }
        block
    }
    fn local_velocity(&self, a: usize) -> F::Vector {
        let d = F::SIZE;
        let mut u = F::Vector::default();
        u.as_mut().copy_from_slice(&self.velocity[d * a..d * a + d]);
        u
    }
    fn apply_impulse(&mut self, a: usize, delta: F::Vector) {
        let (d, m) = (F::SIZE, F::SIZE * self.mu.len());
        for i in 0..m {
            let start = i * m + d * a;
            self.velocity[i] += dot(&self.w[start..start + d], delta.as_ref());
        }
    }
}
