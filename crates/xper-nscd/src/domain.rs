//! The rigid-body operator in a domain decomposition ([`xper_parallel::nscdd`]): each body
//! carries its generalised velocity and its inverse mass.

use crate::operator::RigidContactOperator;
use xper_bodies::InverseMass;
use xper_parallel::{permuted, BodyVelocities, SplitMasses};
use xper_solver::BlockOf;

impl BodyVelocities for RigidContactOperator {
    const DOFS: usize = xper_math::DOFS;
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
    type InverseMass = InverseMass;
    fn inverse_mass(&self, b: usize) -> InverseMass {
        self.bodies[b].inv_mass
    }
    fn set_inverse_mass(&mut self, b: usize, inverse_mass: InverseMass) {
        self.bodies[b].inv_mass = inverse_mass;
    }
    fn scale_inverse_mass(&mut self, b: usize, factor: f64) {
        self.bodies[b].scale_inverse_mass(factor);
    }
    fn set_block(&mut self, a: usize, block: BlockOf<Self>) {
        self.rows[a].set_full_block(block);
    }
    fn refresh_block(&mut self, a: usize) {
        let bodies = &self.bodies;
        self.rows[a].refresh_block(|b| bodies[b].inv_mass);
    }
}
