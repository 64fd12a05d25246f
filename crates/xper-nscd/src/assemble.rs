//! The velocity problem of a step as an explicit [`FrictionProblem`] (local form).
//!
//! With `G_a^b` the `DOFS x DIM` map from the local impulse `(R_N, R_T)` of contact `a` to the
//! generalised impulse (force, torque) it exerts on body `b` (see
//! [`RigidContactOperator::generalized_impulses`]; `-` on the first body, `+` on the second),
//!
//! ```text
//! W_ab = sum over the bodies c shared by a and b of (G_a^c)^T M_c^-1 G_b^c
//! q_a  = U_a(v_free) + (s_a, 0)
//! ```
//!
//! `M_c^-1` is the body's inverse mass (2D: diagonal per degree of freedom; 3D: with the world
//! inverse inertia): a dof with inverse mass 0 (infinite mass or imposed velocity)
//! contributes nothing, so walls do not couple the contacts they carry. `q_a` is the local velocity of the operator in its state
//! of zero impulses (the free velocities), with the normal shift `s_a` of
//! [`crate::normal_shift`] added to its normal component, so that the problem is
//! `u = W r + q`, Signorini-Coulomb on `(u, r)`: exactly what NLGS solves on the operator.

use crate::dimension::inverse_mass_product;
use crate::operator::{ContactRow, RigidContactOperator};
use xper_math::{Real, DIM, DOFS};
use xper_solver::{ContactOperator, CsrMatrix, FrictionProblem, ProblemError};

/// `G` of a contact on each of its bodies, column by column: the generalised impulse of a
/// unit local impulse along each axis of the contact frame.
type LocalMap = [[Real; DOFS]; DIM];

/// The maps `(G_i, G_j)` of a row, read off [`RigidContactOperator::generalized_impulses`]
/// with unit impulses along the normal and the tangents.
fn maps(row: &ContactRow) -> (LocalMap, LocalMap) {
    let columns: [_; DIM] = std::array::from_fn(|k| {
        let unit = std::array::from_fn(|l| if l == k { 1.0 } else { 0.0 });
        RigidContactOperator::generalized_impulses(row, unit)
    });
    (columns.map(|(gi, _)| gi), columns.map(|(_, gj)| gj))
}

/// Assembles the problem of the contacts of `op` (its rows, in order) with friction
/// coefficients `mu` and normal shifts `normal_shift`.
///
/// `op` must be in its state of zero impulses: its body velocities are the free velocities.
/// `W` is exactly symmetric (each entry is summed in the same order as its transpose) and
/// its sparsity pattern holds every pair of contacts sharing a body with a non-zero inverse
/// mass, diagonal blocks included. The values are not checked for finiteness here
/// ([`xper_solver::solve`] and the FCLib writers check them); sizes and body indices are.
pub fn assemble_problem(
    op: &RigidContactOperator,
    mu: &[Real],
    normal_shift: &[Real],
) -> Result<FrictionProblem, ProblemError> {
    let n = op.rows.len();
    if mu.len() != n || normal_shift.len() != n {
        return Err(ProblemError(format!(
            "{n} contact rows, {} friction coefficients, {} normal shifts",
            mu.len(),
            normal_shift.len()
        )));
    }
    let nb = op.bodies.len();
    if let Some((a, row)) = op
        .rows
        .iter()
        .enumerate()
        .find(|(_, row)| row.bodies.iter().any(|&b| b as usize >= nb))
    {
        return Err(ProblemError(format!(
            "contact {a} refers to bodies {:?}; the operator has {nb} bodies",
            row.bodies
        )));
    }
    let mobile = |b: usize| op.bodies[b].is_movable();

    // Contacts incident to each mobile body (counting sort, contacts in increasing order).
    let mut start = vec![0usize; nb + 1];
    for row in &op.rows {
        for &b in &row.bodies {
            if mobile(b as usize) {
                start[b as usize + 1] += 1;
            }
        }
    }
    for b in 0..nb {
        start[b + 1] += start[b];
    }
    let mut incident: Vec<(usize, LocalMap)> = vec![(0, [[0.0; DOFS]; DIM]); start[nb]];
    let mut fill = start.clone();
    for (a, row) in op.rows.iter().enumerate() {
        let (gi, gj) = maps(row);
        for (b, g) in [(row.bodies[0] as usize, gi), (row.bodies[1] as usize, gj)] {
            if mobile(b) {
                incident[fill[b]] = (a, g);
                fill[b] += 1;
            }
        }
    }

    // One DIM x DIM block per ordered pair of contacts on a body.
    let blocks: usize = (0..nb).map(|b| (start[b + 1] - start[b]).pow(2)).sum();
    let mut entries: Vec<(usize, usize, f64)> = Vec::with_capacity(DIM * DIM * blocks);
    for b in 0..nb {
        let m = &op.bodies[b].inv_mass;
        let on_b = &incident[start[b]..start[b + 1]];
        for (a, ga) in on_b {
            for (c, gc) in on_b {
                for (k, gak) in ga.iter().enumerate() {
                    for (l, gcl) in gc.iter().enumerate() {
                        // The same bits for (a, k, c, l) and (c, l, a, k): W is symmetric.
                        let v = inverse_mass_product(m, gak, gcl);
                        entries.push((DIM * a + k, DIM * c + l, v));
                    }
                }
            }
        }
    }
    let w = CsrMatrix::from_triplets(DIM * n, DIM * n, &entries)?;
    let mut q = Vec::with_capacity(DIM * n);
    for (a, s) in normal_shift.iter().enumerate() {
        let mut u = op.local_velocity(a);
        u[0] += s;
        q.extend_from_slice(&u);
    }
    Ok(FrictionProblem {
        dim: DIM,
        w,
        q,
        mu: mu.to_vec(),
    })
}
