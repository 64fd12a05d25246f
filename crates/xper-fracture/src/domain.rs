//! The element operator in a domain decomposition ([`xper_parallel::nscdd`]): each triangle
//! carries its six nodal velocity components, and the free strain rates of a periodic cell
//! are held by every process.

use crate::operator::ElementContactOperator;
use crate::Mat6;
use xper_parallel::{permuted, BodyVelocities, SplitMasses};
use xper_solver::Block2;

impl SplitMasses for ElementContactOperator {
    type InverseMass = Mat6;
    fn inverse_mass(&self, b: usize) -> Mat6 {
        self.bodies[b].inv_mass
    }
    fn set_inverse_mass(&mut self, b: usize, inverse_mass: Mat6) {
        self.bodies[b].inv_mass = inverse_mass;
    }
    fn scale_inverse_mass(&mut self, b: usize, factor: f64) {
        for x in self.bodies[b].inv_mass.iter_mut().flatten() {
            *x *= factor;
        }
    }
    fn set_block(&mut self, a: usize, block: Block2) {
        self.rows[a].block = block;
    }
    fn refresh_block(&mut self, a: usize) {
        let row = self.rows[a];
        self.rows[a].block = self
            .row(row.elements, row.nodes, row.normal, row.period)
            .block;
    }
    fn global_inverse_mass(&self) -> Vec<f64> {
        self.cell.inv_mass.to_vec()
    }
    fn set_global_inverse_mass(&mut self, inverse_mass: &[f64]) {
        self.cell.inv_mass.copy_from_slice(inverse_mass);
    }
    fn touches_global(&self, a: usize) -> bool {
        self.rows[a].period != [0.0; 2]
    }
}

impl BodyVelocities for ElementContactOperator {
    const DOFS: usize = 6;
    fn body_count(&self) -> usize {
        self.bodies.len()
    }
    fn body_velocity(&self, b: usize) -> &[f64] {
        &self.bodies[b].velocity
    }
    fn body_velocity_mut(&mut self, b: usize) -> &mut [f64] {
        &mut self.bodies[b].velocity
    }
    fn row_bodies(&self, a: usize) -> [u32; 2] {
        self.rows[a].elements
    }
    fn permute_rows(&mut self, order: &[u32]) {
        self.rows = permuted(&self.rows, order);
    }
    /// The rates of the cell's free strain components (those with a mass).
    fn global_velocity(&self) -> Vec<f64> {
        let cell = &self.cell;
        (0..3)
            .filter(|&k| cell.inv_mass[k] != 0.0)
            .map(|k| cell.rate[k])
            .collect()
    }
    fn set_global_velocity(&mut self, velocity: &[f64]) {
        let cell = &mut self.cell;
        let free = cell.inv_mass.map(|w| w != 0.0);
        for (k, &v) in (0..3).filter(|&k| free[k]).zip(velocity) {
            cell.rate[k] = v;
        }
    }
}
