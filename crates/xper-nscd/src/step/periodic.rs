//! The stages of a step that a periodic cell adds (see `crate::cell`): detection with the
//! images, the cell and its flow in the operator, their work, the bodies carried by the flow,
//! and the advance of the edges.

use super::MoreauJean;
use crate::dimension::local_of;
use crate::operator::CellCoupling;
use crate::world::World;
use xper_geometry::Periodic;
use xper_math::{Real, Tensor, Vector, DIM};

/// The acceleration `a = L v` a dynamic body other than a wall gets from moving relative to
/// the cell's flow (at the beginning of the step): the SLLOD equations of motion relative to a
/// homogeneous flow (D.J. Evans, G.P. Morriss, "Statistical mechanics of nonequilibrium
/// liquids", Academic Press 1990, ch. 6), under which a body's velocity in the world is
/// constant in free flight through a simple shear and the bodies' momentum relative to the
/// flow is conserved by contacts (it stays zero if it starts so). The `(dL/dt + L^2) (x - o)`
/// terms of the "p-SLLOD" variant, zero in a steady simple shear and of the order of the
/// squared strain rate otherwise, are left out: with them the momentum relative to the flow
/// would depend on the corner `o` the flow is anchored at. `None` for other bodies or
/// without a cell.
fn flow_acceleration(world: &World, b: usize) -> Option<Vector> {
    let cell = world.cell.as_ref()?;
    let bodies = &world.bodies;
    if bodies.shape[b].is_wall() || !bodies.is_dynamic(b) {
        return None;
    }
    Some(cell.gradient * bodies.velocity[b])
}

impl MoreauJean {
    /// Stage detect: the contacts of the configuration the bodies are in, with the images of
    /// the periodic cell if there is one.
    pub(super) fn detect_contacts(&mut self, world: &mut World) {
        if let Some(cell) = &mut world.cell {
            // Bodies added since the last step (e.g. from Python) have not been wrapped yet.
            cell.wraps.resize(world.bodies.len(), [0; DIM]);
        }
        let laws = &world.laws;
        let periodic = world.cell.as_ref().map(|cell| Periodic {
            lattice: &cell.lattice,
            wraps: &cell.wraps,
        });
        self.detector.detect_in(
            &world.bodies,
            periodic,
            world.params.alert_distance,
            |a, b| laws.between(a, b),
            &mut world.contacts,
            &mut self.images,
        );
    }

    /// Puts the periodic cell, if any, in the operator for the step from `t_begin` to
    /// `t_end`, before the blocks are filled: each row's span `d`, `L` at the beginning, and
    /// its free value `L_free` (the imposed components at `t_end`, the others pushed by the
    /// imposed stress and the edges' momentum: `- h V S_theta / I - h L^2`); and the flow's
    /// inertial term in the bodies' free velocities, `- h L v` (see [`flow_acceleration`]).
    pub(super) fn load_cell(&mut self, world: &World, t_begin: Real, t_end: Real) {
        self.all_spans = Vec::new();
        self.all_offsets = Vec::new();
        let Some(cell) = &world.cell else {
            self.op.cell = None;
            return;
        };
        let (lattice, bodies) = (&cell.lattice, &world.bodies);
        let in_flow = |b: usize| {
            let x = bodies.position[b] - lattice.origin;
            (!bodies.shape[b].is_wall()).then_some(x)
        };
        let spans: Vec<Vector> = (self.op.rows.iter().zip(&self.images))
            .map(|(row, n)| {
                let [i, j] = row.bodies.map(|b| b as usize);
                let mut d = Vector::zeros();
                if let Some(xj) = in_flow(j) {
                    d += xj + lattice.shift(n);
                }
                if let Some(xi) = in_flow(i) {
                    d -= xi;
                }
                d
            })
            .collect();
        let (h, theta) = (self.h, world.params.theta);
        let inv_inertia = cell.inverse_inertia();
        let stress = cell.step_stress(t_begin, t_end, theta);
        let pushed = cell.gradient
            - inv_inertia.component_mul(&stress) * (h * cell.volume())
            - cell.gradient * cell.gradient * h;
        let imposed = cell.imposed_gradient(t_end);
        let gradient = Tensor::from_fn(|k, l| {
            if inv_inertia[(k, l)] != 0.0 {
                pushed[(k, l)]
            } else {
                imposed[(k, l)]
            }
        });
        for (b, body) in self.op.bodies.iter_mut().enumerate() {
            if let Some(a) = flow_acceleration(world, b) {
                for k in 0..DIM {
                    if body.is_free(k) {
                        body.velocity[k] -= h * a[k];
                    }
                }
            }
        }
        let free = inv_inertia.iter().any(|&w| w != 0.0);
        let offsets = if free {
            Vec::new()
        } else {
            (self.op.rows.iter().zip(&spans))
                .map(|(row, d)| local_of(row, &(imposed * d)))
                .collect()
        };
        self.op.cell = Some(CellCoupling {
            spans,
            offsets,
            gradient,
            begin: cell.gradient,
            inv_inertia,
            free,
        });
    }

    /// When the active contacts are a subset, keeps their image shifts in the operator and
    /// every contact's aside (as the rows are).
    pub(super) fn select_spans(&mut self) {
        if let (true, Some(cell)) = (self.active_is_subset, &mut self.op.cell) {
            self.all_spans = std::mem::take(&mut cell.spans);
            self.all_offsets = std::mem::take(&mut cell.offsets);
            let (spans, offsets) = (&self.all_spans, &self.all_offsets);
            cell.spans = self.active.iter().map(|&a| spans[a as usize]).collect();
            if !offsets.is_empty() {
                cell.offsets = self.active.iter().map(|&a| offsets[a as usize]).collect();
            }
        }
    }

    /// Exchanges the active rows' image shifts with every row's, as
    /// [`MoreauJean::exchange_rows`] does the rows.
    pub(super) fn exchange_spans(&mut self) {
        if let (true, Some(cell)) = (self.active_is_subset, &mut self.op.cell) {
            std::mem::swap(&mut cell.spans, &mut self.all_spans);
            std::mem::swap(&mut cell.offsets, &mut self.all_offsets);
        }
    }

    /// The work done over the step by the cell on the bodies (J per m), besides what the
    /// contacts dissipate: the imposed stress on the free components of `L`, `-h V S_theta :
    /// L_mean`; the imposed components through the rows, `-sum_c R_c . F_c^T (L_imposed,mean
    /// d_c)`; the flow's inertial term on the bodies, `-h m a . v_mean`. With the contacts'
    /// dissipation (computed on local velocities that include the flow) it balances the
    /// change of the bodies' and the cell's kinetic energy. Called before the update, while
    /// the bodies hold their state at the beginning of the step.
    pub(super) fn cell_work(&self, world: &World, t_begin: Real, t_end: Real) -> Real {
        let (Some(cell), Some(coupling)) = (&world.cell, &self.op.cell) else {
            return 0.0;
        };
        let (h, theta) = (self.h, world.params.theta);
        let mean = (coupling.begin + coupling.gradient) / 2.0;
        let stress = cell.step_stress(t_begin, t_end, theta);
        let free = Tensor::from_fn(|k, l| {
            if coupling.inv_inertia[(k, l)] != 0.0 {
                mean[(k, l)]
            } else {
                0.0
            }
        });
        let mut work = -h * cell.volume() * stress.component_mul(&free).sum();
        let imposed = mean - free;
        for ((row, d), r) in self.op.rows.iter().zip(&coupling.spans).zip(&self.impulses) {
            work -= row.world_impulse(*r).dot(&(imposed * d));
        }
        for (b, body) in self.op.bodies.iter().enumerate() {
            if let Some(a) = flow_acceleration(world, b) {
                let v0 = world.bodies.generalized_velocity(b);
                for k in (0..DIM).filter(|&k| body.is_free(k)) {
                    let v_mean = (v0[k] + body.velocity[k]) / 2.0;
                    work -= h * world.bodies.mass[b] * a[k] * v_mean;
                }
            }
        }
        work
    }

    /// Before the update: the bodies other than walls carried by the flow over the step,
    /// `x += h L_theta (x - o)`, with `L_theta` from the operator's `L` at both ends.
    pub(super) fn carry_by_flow(&self, world: &mut World) {
        let (Some(cell), Some(coupling)) = (&world.cell, &self.op.cell) else {
            return;
        };
        let theta = world.params.theta;
        let step = (coupling.begin * (1.0 - theta) + coupling.gradient * theta) * self.h;
        let origin = cell.lattice.origin;
        let bodies = &mut world.bodies;
        for b in 0..bodies.len() {
            if !bodies.shape[b].is_wall() {
                let x = bodies.position[b] - origin;
                bodies.position[b] += step * x;
            }
        }
    }

    /// After the update: the cell's gradient at the end of the step, its edges advanced with
    /// `L_theta`; the operator no longer holds it (the projection moves positions only).
    pub(super) fn finish_cell(&mut self, world: &mut World) {
        let coupling = self.op.cell.take();
        let (Some(cell), Some(coupling)) = (&mut world.cell, coupling) else {
            return;
        };
        let theta = world.params.theta;
        let mean = coupling.begin * (1.0 - theta) + coupling.gradient * theta;
        cell.gradient = coupling.gradient;
        cell.advance_edges(&mean, self.h);
    }
}
