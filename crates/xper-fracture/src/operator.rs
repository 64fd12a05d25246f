//! The Delassus operator of element bodies in factorised form, `W = H^T M_eff^-1 H`.
//!
//! Each element keeps a working velocity (6 components) and the inverse of its effective
//! mass `M + h^2 theta^2 K` restricted to its free degrees of freedom. A contact point joins
//! one node of element a to one node of element b, so applying an impulse updates the two
//! velocities with two 6x2 products and a local velocity reads two nodes: O(1) per contact
//! update, as for rigid bodies (M. Jean, CMAME 177, 1999, section 6).

use xper_solver::{Block2, ContactOperator};

use crate::dense::Mat6;

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
}

impl ElementContactOperator {
    /// The row of a contact point, its block computed from the current inverse masses.
    pub fn row(&self, elements: [u32; 2], nodes: [u8; 2], normal: [f64; 2]) -> InterfaceRow {
        let (n, t) = (normal, [-normal[1], normal[0]]);
        let mut s = [0.0; 4];
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
            block: [quad(n, n), quad(n, t), quad(t, n), quad(t, t)],
        }
    }

    /// Local velocity `[U_N, U_T]` of a row for arbitrary element velocities.
    #[inline(always)]
    pub fn local_velocity_of(row: &InterfaceRow, va: &[f64; 6], vb: &[f64; 6]) -> [f64; 2] {
        let (ca, cb) = (2 * row.nodes[0] as usize, 2 * row.nodes[1] as usize);
        let d = [vb[cb] - va[ca], vb[cb + 1] - va[ca + 1]];
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
        Self::local_velocity_of(row, va, vb)
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
    }
}
