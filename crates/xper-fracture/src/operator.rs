//! The Delassus operator of element bodies in factorised form, `W = H^T M_eff^-1 H`.
//!
//! Each element keeps a working velocity (6 components) and the inverse of its effective
//! mass `M + h^2 theta^2 K` restricted to its free degrees of freedom. A contact point joins
//! one node of element a to one node of element b, so applying an impulse updates the two
//! velocities with two 6x2 products and a local velocity reads two nodes: O(1) per contact
//! update, as for rigid bodies (M. Jean, CMAME 177, 1999, section 6).
//!
//! A row across the sides of a periodic cell (period `T != 0`) also reads the macroscopic
//! strain rate `E'` ([`crate::cell`]): `U = (v_b - v_a - E' T) . (n, t)`; an impulse on it
//! moves the free components of `E'` as it moves the two elements.

use xper_solver::{Block2, ContactOperator, Frame2};

use crate::cell::{drift_response, strain_times, tensor_weights};
use crate::dense::Mat6;

/// The macroscopic strain rate of a periodic cell as the solver sees it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CellWork {
    /// `[E'_xx, E'_yy, E'_xy]` (1/s).
    pub rate: [f64; 3],
    /// Inverse mass of each component (1/(kg m^2)); zero for an imposed strain.
    pub inv_mass: [f64; 3],
}

/// Working state of one element: velocity and inverse effective mass.
#[derive(Clone, Copy, Debug, Default)]
pub struct ElementWork {
    /// Nodal velocities (m/s).
    pub velocity: [f64; 6],
    /// `M_eff^-1` on the free degrees of freedom, zero rows and columns elsewhere (1/kg).
    pub inv_mass: Mat6,
}

/// One contact point: two element nodes, the frame and the diagonal Delassus block.
#[derive(Clone, Copy, Debug, Default)]
pub struct InterfaceRow {
    /// Elements `[a, b]`; the normal points from a to b.
    pub elements: [u32; 2],
    /// Local node in a and in b.
    pub nodes: [u8; 2],
    /// Unit normal; the tangent is `(-n_y, n_x)`.
    pub normal: [f64; 2],
    /// The period `X_b - X_a` (m) of a row across the sides of a periodic cell, zero inside.
    pub period: [f64; 2],
    /// `W_aa`.
    pub block: Block2,
}

/// Contact operator over element bodies.
#[derive(Clone, Debug, Default)]
pub struct ElementContactOperator {
    /// Working state per element.
    pub bodies: Vec<ElementWork>,
    /// One row per contact point.
    pub rows: Vec<InterfaceRow>,
    /// The macroscopic strain rate (zero without a periodic cell).
    pub cell: CellWork,
}

impl ElementContactOperator {
    /// The row of a contact point, its block computed from the current inverse masses (and
    /// those of the cell's free components when `period` is not zero).
    pub fn row(
        &self,
        elements: [u32; 2],
        nodes: [u8; 2],
        normal: [f64; 2],
        period: [f64; 2],
    ) -> InterfaceRow {
        let (n, t) = (normal, [-normal[1], normal[0]]);
        let mut s = if period == [0.0; 2] {
            [0.0; 4]
        } else {
            drift_response(&self.cell.inv_mass, period)
        };
        for (e, node) in elements.iter().zip(nodes) {
            let m = &self.bodies[*e as usize].inv_mass;
            let c = 2 * node as usize;
            s[0] += m[c][c];
            s[1] += m[c][c + 1];
            s[2] += m[c + 1][c];
            s[3] += m[c + 1][c + 1];
        }
        let quad = |x: [f64; 2], y: [f64; 2]| {
            x[0] * (s[0] * y[0] + s[1] * y[1]) + x[1] * (s[2] * y[0] + s[3] * y[1])
        };
        InterfaceRow {
            elements,
            nodes,
            normal,
            period,
            block: [quad(n, n), quad(n, t), quad(t, n), quad(t, t)],
        }
    }

    /// Local velocity `[U_N, U_T]` of a row for arbitrary element velocities and strain rate
    /// `rate` (1/s, Voigt order).
    #[inline(always)]
    pub fn local_velocity_of(
        row: &InterfaceRow,
        va: &[f64; 6],
        vb: &[f64; 6],
        rate: &[f64; 3],
    ) -> [f64; 2] {
        let (ca, cb) = (2 * row.nodes[0] as usize, 2 * row.nodes[1] as usize);
        let drift = strain_times(rate, row.period);
        let d = [
            vb[cb] - va[ca] - drift[0],
            vb[cb + 1] - va[ca + 1] - drift[1],
        ];
        let [nx, ny] = row.normal;
        [nx * d[0] + ny * d[1], -ny * d[0] + nx * d[1]]
    }

    /// The global vector `p = r_N n + r_T t` of a local impulse.
    #[inline(always)]
    pub fn global_impulse(row: &InterfaceRow, r: [f64; 2]) -> [f64; 2] {
        let [nx, ny] = row.normal;
        [nx * r[0] - ny * r[1], ny * r[0] + nx * r[1]]
    }
}

impl ContactOperator for ElementContactOperator {
    type Frame = Frame2;
    #[inline(always)]
    fn contact_count(&self) -> usize {
        self.rows.len()
    }

    #[inline(always)]
    fn diagonal_block(&self, a: usize) -> Block2 {
        self.rows[a].block
    }

    #[inline(always)]
    fn local_velocity(&self, a: usize) -> [f64; 2] {
        let row = &self.rows[a];
        let va = &self.bodies[row.elements[0] as usize].velocity;
        let vb = &self.bodies[row.elements[1] as usize].velocity;
        Self::local_velocity_of(row, va, vb, &self.cell.rate)
    }

    #[inline(always)]
    fn apply_impulse(&mut self, a: usize, d: [f64; 2]) {
        let row = self.rows[a];
        let p = Self::global_impulse(&row, d);
        for (k, sign) in [(0usize, -1.0), (1, 1.0)] {
            let body = &mut self.bodies[row.elements[k] as usize];
            let c = 2 * row.nodes[k] as usize;
            let (px, py) = (sign * p[0], sign * p[1]);
            // M_eff^-1 is symmetric: its columns c, c + 1 are its rows, contiguous in memory.
            let (col_x, col_y) = (body.inv_mass[c], body.inv_mass[c + 1]);
            for i in 0..6 {
                body.velocity[i] += col_x[i] * px + col_y[i] * py;
            }
        }
        if row.period != [0.0; 2] {
            let weights = tensor_weights(p, row.period);
            for k in 0..3 {
                self.cell.rate[k] -= self.cell.inv_mass[k] * weights[k];
            }
        }
    }
}
