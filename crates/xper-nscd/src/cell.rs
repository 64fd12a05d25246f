//! Periodic cells for rigid bodies: bodies leaving the cell through a side re-enter through
//! the opposite one, contacts with the images of bodies across the sides are solved like the
//! others, and the cell deforms homogeneously with a velocity gradient `L` whose components are
//! imposed (a strain rate) or follow an imposed stress.
//!
//! ```text
//! cell           o + H s, s in [0, 1)^DIM; images of body j at x_j + H n
//! flow           a body's velocity in the world is L (x - o) + v, v the body's own
//! contact        U = G^T v + F^T (L d),  d = x_j + H n - x_i   (walls: their term left out)
//! motion         v_free = v_i + h (M^-1 F - L v_i)        (SLLOD, see `step/periodic.rs`)
//!                x_i+1 = x_i + h (v_theta + L_theta (x_i - o))
//! edges          H_i+1 = H_i + h L_theta H_i
//! stress control I_kl (L_kl,i+1 - L_kl,i) = sum_c p_c,k d_c,l - h V S_kl - h I_kl (L_i L_i)_kl
//!                I_kl = m |H e_l|^2, S the imposed stress (Pa, compression positive)
//! wrap           s_k >= 1 or < 0 on a periodic axis: x -= H n, v unchanged
//! ```
//!
//! With `H` upper triangular (the lower components of `L` are zero), a simple shear `L_xy`
//! is a Lees-Edwards cell (A.W. Lees, S.F. Edwards, "The computer study of transport processes
//! under extreme conditions", J. Phys. C 5:1921, 1972): when the shear of an edge exceeds half
//! the edge it leans on, the edge is reduced by that edge, which relabels the images without
//! moving them. A component under stress is a degree of freedom of inertia `I_kl` pushed by
//! every contact (through its span `d`) and by the imposed stress (M. Parrinello, A. Rahman,
//! J. Appl. Phys. 52:7182, 1981); `sum_c p_c (x) d_c` is `h V sigma` (sigma the granular stress of
//! `crate::micro`, compression positive, Love-Weber), so the cell comes to rest where the
//! granular stress equals the imposed one. The cell's momentum is that of its edges, `m dH/dt
//! = m L H`: from `m d2H/dt2 = F`, `dL/dt = F H^-1 / m - L^2`, whose `L^2` term (explicit,
//! from the beginning of the step) keeps the energy `m |dH/dt|^2 / 2` consistent while the
//! edges, and with them the inertia, change. It is solved implicitly with the contacts (see
//! `crate::CellCoupling`). Bodies other than walls follow the flow: a cell that deforms
//! carries them homogeneously, and their velocities (in outputs too) are relative to the
//! flow; walls keep velocities in the world and are not carried.

use crate::World;
use serde::{Deserialize, Serialize};
use xper_bodies::TimeFunction;
use xper_geometry::{Image, Lattice};
use xper_math::{Real, Tensor, DIM};

/// How a component `L_kl` of the cell's velocity gradient is controlled.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum CellLoad {
    /// `L_kl(t)` imposed (1/s): a strain rate (`k = l`) or a shear rate (`k < l`).
    Rate(TimeFunction),
    /// The stress `S_kl(t)` imposed on the cell (Pa, compression positive); `L_kl` follows.
    Stress(TimeFunction),
}

impl Default for CellLoad {
    fn default() -> Self {
        CellLoad::Rate(TimeFunction::Constant(0.0))
    }
}

/// A periodic cell: its lattice, the control of each component of its velocity gradient, and
/// its state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeriodicCell {
    /// Origin, edges and periodic axes.
    pub lattice: Lattice,
    /// The control of `L_kl`, row `k`, column `l`; the components below the diagonal are
    /// `Rate(0)` (the edges stay upper triangular).
    pub loads: [[CellLoad; DIM]; DIM],
    /// The velocity gradient `L` at the end of the last step (1/s).
    pub gradient: Tensor,
    /// The cell's mass `m` (kg per m in 2D): a component under stress has the inertia
    /// `m |H e_l|^2`, that of a wall of mass `m` moving at `L_kl |H e_l|`.
    pub mass: Real,
    /// Per body, the sum of the images it was moved back by (see
    /// [`xper_geometry::Periodic::wraps`]).
    pub wraps: Vec<Image>,
}

impl PeriodicCell {
    /// A cell at rest with these loads; `wraps` are set for `bodies` bodies.
    pub fn new(lattice: Lattice, loads: [[CellLoad; DIM]; DIM], mass: Real, bodies: usize) -> Self {
        PeriodicCell {
            lattice,
            loads,
            gradient: Tensor::zeros(),
            mass,
            wraps: vec![[0; DIM]; bodies],
        }
    }

    /// The cell's volume (m^2 per m in 2D, m^3 in 3D).
    pub fn volume(&self) -> Real {
        self.lattice.edges.determinant().abs()
    }

    /// The imposed part of `L` at time `t`, zero where a stress is imposed.
    pub fn imposed_gradient(&self, t: Real) -> Tensor {
        Tensor::from_fn(|k, l| match &self.loads[k][l] {
            CellLoad::Rate(f) => f.eval(t),
            CellLoad::Stress(_) => 0.0,
        })
    }

    /// The imposed stress at time `t` on the components under stress, zero elsewhere (Pa).
    pub fn imposed_stress(&self, t: Real) -> Tensor {
        Tensor::from_fn(|k, l| match &self.loads[k][l] {
            CellLoad::Stress(f) => f.eval(t),
            CellLoad::Rate(_) => 0.0,
        })
    }

    /// The imposed stress over a step from `t_begin` to `t_end`, `(1 - theta) S(t_begin) +
    /// theta S(t_end)` (Pa).
    pub fn step_stress(&self, t_begin: Real, t_end: Real, theta: Real) -> Tensor {
        self.imposed_stress(t_begin) * (1.0 - theta) + self.imposed_stress(t_end) * theta
    }

    /// The inverse inertia of each component of `L`: `1 / (m |H e_l|^2)` under stress, 0
    /// where imposed.
    pub fn inverse_inertia(&self) -> Tensor {
        Tensor::from_fn(|k, l| match self.loads[k][l] {
            CellLoad::Stress(_) => 1.0 / (self.mass * self.lattice.edges.column(l).norm_squared()),
            CellLoad::Rate(_) => 0.0,
        })
    }

    /// The kinetic energy of the free components, `sum I_kl L_kl^2 / 2` (J per m).
    pub fn kinetic_energy(&self) -> Real {
        let inverse = self.inverse_inertia();
        (0..DIM * DIM)
            .filter(|&c| inverse[c] != 0.0)
            .map(|c| self.gradient[c] * self.gradient[c] / inverse[c] / 2.0)
            .sum()
    }

    /// Advances the edges over a step of `h` with the mean gradient `L_theta`, then reduces
    /// a leaning edge by the edges before it (a Lees-Edwards relabelling) when its component
    /// along one of them exceeds half of it.
    pub fn advance_edges(&mut self, mean_gradient: &Tensor, h: Real) {
        let edges = self.lattice.edges;
        self.lattice.edges = edges + mean_gradient * edges * h;
        for l in 1..DIM {
            for k in (0..l).rev() {
                if !self.lattice.periodic[k] {
                    continue;
                }
                let along = self.lattice.edges[(k, l)] / self.lattice.edges[(k, k)];
                let whole = along.round();
                if along.abs() > 0.5 && whole != 0.0 {
                    let base = self.lattice.edges.column(k).into_owned();
                    let mut column = self.lattice.edges.column_mut(l);
                    column -= base * whole;
                    self.lattice.relabels += 1;
                }
            }
        }
    }
}

impl World {
    /// Brings every body but walls back into the periodic cell, if any: a body whose reduced
    /// coordinate left `[0, 1)` along a periodic axis moves by `-H n` (it becomes the image
    /// that is inside), its velocity relative to the flow unchanged; the change of potential
    /// energy under gravity this causes is counted as work of the cell.
    pub fn wrap_into_cell(&mut self) {
        let Some(cell) = &mut self.cell else {
            return;
        };
        let Some(inverse) = cell.lattice.inverse() else {
            return;
        };
        cell.wraps.resize(self.bodies.len(), [0; DIM]);
        let g = self.params.gravity;
        for b in 0..self.bodies.len() {
            if self.bodies.shape[b].is_wall() {
                continue;
            }
            let n = cell.lattice.wrap_of(&inverse, &self.bodies.position[b]);
            if n.iter().all(|&x| x == 0) {
                continue;
            }
            let shift = cell.lattice.shift(&n);
            let m = self.bodies.mass[b];
            if m.is_finite() && self.bodies.is_dynamic(b) {
                self.energy.external_work += m * g.dot(&shift);
            }
            self.bodies.position[b] -= shift;
            for (w, k) in cell.wraps[b].iter_mut().zip(n) {
                *w += k;
            }
        }
    }
}
