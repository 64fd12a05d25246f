//! The contact frame a contact problem is written in: two components `(N, T)` in 2D, three
//! `(N, T1, T2)` in 3D, normal first.
//!
//! The operator NLGS ([`crate::nlgs`]), its domain-decomposition variant, Anderson mixing and
//! LMGC90's norms are written once over a [`ContactFrame`]; each frame supplies the few
//! operations that differ: the product of a diagonal block with a local vector, the exact
//! one-contact solve and the projection on the Coulomb cone
//!
//! ```text
//! K_mu = { r : |r_T| <= mu r_N }        (r_T a scalar in 2D, a 2-vector in 3D)
//! ```
//!
//! [`Frame2`] keeps the closed-form 2D solve of M. Jean (CMAME 177, 1999) and its arithmetic
//! operation for operation, so 2D results do not depend on this abstraction; [`Frame3`] uses
//! the Alart-Curnier local solve with its fallbacks ([`crate::alart_curnier`]).

use std::fmt::Debug;
use std::ops::{Index, IndexMut};

use crate::alart_curnier::{inverse3, local_residual3, solve_contact_3d_inverse, LocalParams};
use crate::cohesive::{CohesiveTerm, PreparedCohesiveContact};
use crate::local::{solve_one_contact_factored, LocalFactors};
use crate::operator::{block_mul, Block2};

/// Operations on the local vectors and diagonal blocks of one contact frame (see the module
/// documentation).
pub trait ContactFrame: Copy + Debug + Default + Send + Sync + 'static {
    /// Components per contact: 2 or 3.
    const SIZE: usize;
    /// A local velocity or impulse, normal component first.
    type Vector: Copy
        + Debug
        + Default
        + PartialEq
        + Send
        + Sync
        + AsRef<[f64]>
        + AsMut<[f64]>
        + Index<usize, Output = f64>
        + IndexMut<usize>
        + 'static;
    /// A diagonal block `W_aa` of the Delassus operator, `SIZE x SIZE`, row-major.
    type Block: Copy + Debug + Default + PartialEq + Send + Sync + AsRef<[f64]> + AsMut<[f64]>;
    /// What the local solve computes once per block (see [`ContactFrame::factors`]).
    type Factors: Copy + Debug + Default + Send + Sync;
    /// A contact with an adhesive term, prepared once per solve.
    type Cohesive: Copy + Debug + Default + Send + Sync;
    /// A local vector rounded to single precision (Anderson mixing's history).
    type Stored: Copy + Debug + Default + Send + Sync;

    /// `v` rounded to single precision.
    fn to_stored(v: Self::Vector) -> Self::Stored;
    /// A stored vector back in double precision (exact).
    fn from_stored(v: Self::Stored) -> Self::Vector;

    /// `a . b`, summed from the first component on.
    fn dot(a: &Self::Vector, b: &Self::Vector) -> f64;
    /// `a - b`.
    fn sub(a: Self::Vector, b: Self::Vector) -> Self::Vector;
    /// `W r`.
    fn block_mul(w: &Self::Block, r: Self::Vector) -> Self::Vector;
    /// `W + eps I`.
    fn add_to_diagonal(w: &Self::Block, eps: f64) -> Self::Block;
    /// What [`ContactFrame::solve`] needs of `w` besides `w` itself.
    fn factors(w: &Self::Block) -> Self::Factors;
    /// The impulse `r` of the one-contact problem `u = u_free + w r`, `(u + 0, r)` satisfying
    /// Signorini-Coulomb with `mu`; `warm` is the contact's current impulse, a starting point
    /// for an iterative local solve. `factors` are `Self::factors(w)`.
    fn solve(
        w: &Self::Block,
        factors: &Self::Factors,
        u_free: Self::Vector,
        mu: f64,
        warm: Self::Vector,
    ) -> Self::Vector;
    /// The Euclidean projection of `r` on the cone `K_mu`.
    fn project_on_cone(r: Self::Vector, mu: f64) -> Self::Vector;
    /// `|r - P_K(r - u - mu |u_T| e_N)|^2`, the square of one contact's natural-map error.
    fn natural_map_error2(u: Self::Vector, r: Self::Vector, mu: f64) -> f64;
    /// The proximal weight of a singular block, 0 for a regular one (see
    /// [`crate::NlgsSweeper`]).
    fn proximal_weight(w: &Self::Block) -> f64;
    /// Prepares the local solve of an adhesive contact; an error where the frame has none.
    fn prepare_cohesive(w: &Self::Block, term: &CohesiveTerm) -> Result<Self::Cohesive, String>;
    /// The total impulse of a prepared adhesive contact for `u_free` and `mu`.
    fn solve_cohesive(c: &Self::Cohesive, u_free: Self::Vector, mu: f64) -> Self::Vector;
}

/// The local vector type of a frame.
pub type LocalVector<F> = <F as ContactFrame>::Vector;

/// `sum_k a_k b_k`, summed from the first component on (the order the 2D code always used).
#[inline(always)]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = a[0] * b[0];
    for k in 1..a.len() {
        s += a[k] * b[k];
    }
    s
}

/// Whether every component is zero.
#[inline(always)]
pub fn is_zero<V: AsRef<[f64]>>(v: &V) -> bool {
    v.as_ref().iter().all(|&x| x == 0.0)
}

/// The 2D frame `(N, T)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Frame2;

impl ContactFrame for Frame2 {
    const SIZE: usize = 2;
    type Vector = [f64; 2];
    type Block = Block2;
    type Factors = LocalFactors;
    type Cohesive = PreparedCohesiveContact;
    type Stored = [f32; 2];

    #[inline(always)]
    fn to_stored(v: [f64; 2]) -> [f32; 2] {
        [v[0] as f32, v[1] as f32]
    }
    #[inline(always)]
    fn from_stored(v: [f32; 2]) -> [f64; 2] {
        [v[0] as f64, v[1] as f64]
    }
    #[inline(always)]
    fn dot(a: &[f64; 2], b: &[f64; 2]) -> f64 {
        a[0] * b[0] + a[1] * b[1]
    }
    #[inline(always)]
    fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        [a[0] - b[0], a[1] - b[1]]
    }

    #[inline(always)]
    fn block_mul(w: &Block2, r: [f64; 2]) -> [f64; 2] {
        block_mul(w, r)
    }
    #[inline(always)]
    fn add_to_diagonal(w: &Block2, eps: f64) -> Block2 {
        [w[0] + eps, w[1], w[2], w[3] + eps]
    }
    #[inline(always)]
    fn factors(w: &Block2) -> LocalFactors {
        LocalFactors::new(w)
    }
    #[inline(always)]
    fn solve(
        w: &Block2,
        factors: &LocalFactors,
        u_free: [f64; 2],
        mu: f64,
        _warm: [f64; 2],
    ) -> [f64; 2] {
        solve_one_contact_factored(w, factors, u_free, mu)
    }
    #[inline(always)]
    fn project_on_cone(r: [f64; 2], mu: f64) -> [f64; 2] {
        crate::error::project_on_cone(r, mu)
    }
    #[inline]
    fn natural_map_error2(u: [f64; 2], r: [f64; 2], mu: f64) -> f64 {
        let p = crate::error::project_on_cone([r[0] - u[0] - mu * u[1].abs(), r[1] - u[1]], mu);
        (r[0] - p[0]).powi(2) + (r[1] - p[1]).powi(2)
    }
    /// Singular when `det W <= 1e-9 (tr W)^2`; then a tenth of the trace.
    fn proximal_weight(w: &Block2) -> f64 {
        let trace = w[0] + w[3];
        let det = w[0] * w[3] - w[1] * w[2];
        if trace > 0.0 && det <= 1e-9 * trace * trace {
            0.1 * trace
        } else {
            0.0
        }
    }
    fn prepare_cohesive(
        w: &Block2,
        term: &CohesiveTerm,
    ) -> Result<PreparedCohesiveContact, String> {
        Ok(PreparedCohesiveContact::new(w, term))
    }
    #[inline(always)]
    fn solve_cohesive(c: &PreparedCohesiveContact, u_free: [f64; 2], mu: f64) -> [f64; 2] {
        c.solve(u_free, mu)
    }
}

/// The 3D frame `(N, T1, T2)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Frame3;

impl ContactFrame for Frame3 {
    const SIZE: usize = 3;
    type Vector = [f64; 3];
    type Block = [f64; 9];
    /// The inverse of the block (`None` when singular), for the sticking test.
    type Factors = Option<[f64; 9]>;
    type Cohesive = ();
    type Stored = [f32; 3];

    #[inline(always)]
    fn to_stored(v: [f64; 3]) -> [f32; 3] {
        [v[0] as f32, v[1] as f32, v[2] as f32]
    }
    #[inline(always)]
    fn from_stored(v: [f32; 3]) -> [f64; 3] {
        [v[0] as f64, v[1] as f64, v[2] as f64]
    }
    #[inline(always)]
    fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    #[inline(always)]
    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    #[inline(always)]
    fn block_mul(w: &[f64; 9], r: [f64; 3]) -> [f64; 3] {
        [
            w[0] * r[0] + w[1] * r[1] + w[2] * r[2],
            w[3] * r[0] + w[4] * r[1] + w[5] * r[2],
            w[6] * r[0] + w[7] * r[1] + w[8] * r[2],
        ]
    }
    #[inline(always)]
    fn add_to_diagonal(w: &[f64; 9], eps: f64) -> [f64; 9] {
        let mut m = *w;
        m[0] += eps;
        m[4] += eps;
        m[8] += eps;
        m
    }
    #[inline]
    fn factors(w: &[f64; 9]) -> Option<[f64; 9]> {
        inverse3(w)
    }
    /// Take-off and stick in closed form (the stick from the block's inverse), else
    /// Alart-Curnier's Newton from `warm`, with the slip-angle search and the projection as
    /// fallbacks ([`crate::alart_curnier`]).
    #[inline]
    fn solve(
        w: &[f64; 9],
        inverse: &Option<[f64; 9]>,
        u_free: [f64; 3],
        mu: f64,
        warm: [f64; 3],
    ) -> [f64; 3] {
        let mut r = warm;
        solve_contact_3d_inverse(w, inverse, u_free, mu, &mut r, &LocalParams::default());
        r
    }
    #[inline]
    fn project_on_cone(r: [f64; 3], mu: f64) -> [f64; 3] {
        let mut p = r;
        crate::problem::project_on_cone_nd(&mut p, mu);
        p
    }
    #[inline]
    fn natural_map_error2(u: [f64; 3], r: [f64; 3], mu: f64) -> f64 {
        local_residual3(&r, &u, mu).powi(2)
    }
    /// Singular when the smallest pivot of a Cholesky factorisation is below `1e-9 tr W`
    /// (rank-deficient blocks: bodies sharing imposed velocities); then a tenth of the trace.
    fn proximal_weight(w: &[f64; 9]) -> f64 {
        let trace = w[0] + w[4] + w[8];
        if trace <= 0.0 {
            return 0.0;
        }
        let tiny = 1e-9 * trace;
        let d0 = w[0];
        if d0 <= tiny {
            return 0.1 * trace;
        }
        let (l10, l20) = (w[3] / d0, w[6] / d0);
        let d1 = w[4] - l10 * w[1];
        if d1 <= tiny {
            return 0.1 * trace;
        }
        let l21 = (w[7] - l20 * w[1]) / d1;
        let d2 = w[8] - l20 * w[2] - l21 * l21 * d1;
        if d2 <= tiny {
            0.1 * trace
        } else {
            0.0
        }
    }
    fn prepare_cohesive(_w: &[f64; 9], _term: &CohesiveTerm) -> Result<(), String> {
        Err("adhesive (cohesive) contacts exist in 2D only".into())
    }
    fn solve_cohesive(_c: &(), u_free: [f64; 3], _mu: f64) -> [f64; 3] {
        // Unreachable: `prepare_cohesive` refuses every adhesive contact in 3D, so a solve
        // never marks one adhesive.
        u_free.map(|_| 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3D block with a positive determinant is regular; one of rank 1 or 2 is not.
    #[test]
    fn proximal_weight_3d_detects_rank_deficiency() {
        let regular = [2.0, 0.1, 0.0, 0.1, 1.0, 0.2, 0.0, 0.2, 3.0];
        assert_eq!(Frame3::proximal_weight(&regular), 0.0);
        // n n^T + t t^T with n, t independent: rank 2.
        let (n, t) = ([1.0, 0.5, 0.2], [0.0, 1.0, -1.0]);
        let mut rank2 = [0.0; 9];
        for i in 0..3 {
            for j in 0..3 {
                rank2[3 * i + j] = n[i] * n[j] + t[i] * t[j];
            }
        }
        let trace = rank2[0] + rank2[4] + rank2[8];
        assert_eq!(Frame3::proximal_weight(&rank2), 0.1 * trace);
    }

    /// The 3D cone projection keeps cone points, zeroes the polar cone, and is orthogonal.
    #[test]
    fn cone_projection_3d() {
        assert_eq!(
            Frame3::project_on_cone([1.0, 0.3, 0.1], 0.5),
            [1.0, 0.3, 0.1]
        );
        assert_eq!(Frame3::project_on_cone([-1.0, 0.1, 0.1], 0.5), [0.0; 3]);
        let x = [1.0, 2.0, -1.0];
        let p = Frame3::project_on_cone(x, 0.5);
        let pt = (p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((pt - 0.5 * p[0]).abs() < 1e-14, "{p:?} on the boundary");
        assert!(
            Frame3::dot(&Frame3::sub(x, p), &p).abs() < 1e-14,
            "{p:?} orthogonal"
        );
    }
}
