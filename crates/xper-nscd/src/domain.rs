//! The rigid-body operator in a domain decomposition ([`xper_parallel::nscdd`]): each body
//! carries its velocity `(vx, vy, w)` and a diagonal inverse mass.

use crate::operator::RigidContactOperator;
use xper_parallel::{permuted, BodyVelocities, SplitMasses};
use xper_solver::Block2;

impl BodyVelocities for RigidContactOperator {
    const DOFS: usize = 3;
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
        self.rows[a].bodies
    }
    fn permute_rows(&mut self, order: &[u32]) {
        self.rows = permuted(&self.rows, order);
    }
}

impl SplitMasses for RigidContactOperator {
    type InverseMass = [f64; 3];
    fn inverse_mass(&self, b: usize) -> [f64; 3] {
        self.bodies[b].inv_mass
    }
    fn set_inverse_mass(&mut self, b: usize, inverse_mass: [f64; 3]) {
        self.bodies[b].inv_mass = inverse_mass;
    }
    fn scale_inverse_mass(&mut self, b: usize, factor: f64) {
        for w in &mut self.bodies[b].inv_mass {
            *w *= factor;
        }
    }
    fn set_block(&mut self, a: usize, block: Block2) {
        self.rows[a].set_full_block(block);
    }
    fn refresh_block(&mut self, a: usize) {
        let bodies = &self.bodies;
        self.rows[a].refresh_block(|b| bodies[b].inv_mass);
    }
}
