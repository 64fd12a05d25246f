//! Grains in the fluid: one coupled step advances the fluid with the grains held at their
//! state, then moves the grains by one Moreau-Jean step of the same length under their
//! hydrodynamic forces (BRIEF.md section 4; explicit coupling as in Uhlmann 2005 and Kempe
//! and Froehlich 2012, with contacts by NSCD):
//!
//! 1. **time step**: the fluid's stability limit for the current velocities (grains included),
//!    capped by the scene's `dt`;
//! 2. **fluid**: predictor, forcing towards the grains' rigid velocities, projection
//!    ([`FluidSolver::step`]), giving `F_p` and `T_p` for every immersed disk;
//! 3. **lubrication** (optional, [`crate::lubrication`]): the squeeze force the grid misses
//!    between grains (and with the domain's walls) closer than about a cell, added to `F_p`;
//! 4. **grains**: `m_p dU/dt = F_p + (m_p - rho_f A_p) g`, `I_p dw/dt = T_p` with contacts
//!    (grain-grain, grain-wall) by [`MoreauJean::step_by`]; gravity acts through the world's
//!    `m_p g`, so the coupling adds `F_p - rho_f A_p g`.
//!
//! Immersed bodies are the world's disks (moving or fixed, e.g. an obstacle); walls only carry
//! contacts, the fluid's walls being the sides of its domain.

use crate::lubrication::{LubricatedGrain, LubricatedWall};
use crate::{
    BlockLinks, FluidBoundary, FluidError, FluidParams, FluidSolver, FluidState, FluidStepReport,
    ImmersedDisk, MacGrid, SideCondition,
};
use serde::{Deserialize, Serialize};
use xper_bodies::Shape;
use xper_math::{Real, Vector, DIM, DOFS};
use xper_nscd::{MoreauJean, StepError, StepReport, World};

/// Everything that evolves in a run with a fluid; serialisable for checkpoints.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CoupledState {
    /// The fluid.
    pub fluid: FluidState,
    /// The grains, walls and contacts.
    pub world: World,
}

/// What one coupled step did.
#[derive(Clone, Debug, Default)]
pub struct CoupledReport {
    /// The fluid step (with the force on each immersed disk, in [`CoupledStepper::immersed`]
    /// order).
    pub fluid: FluidStepReport,
    /// The grains' step.
    pub grains: StepReport,
}

/// A coupled step that failed.
#[derive(Debug)]
pub enum CoupledError {
    /// The fluid step failed.
    Fluid(FluidError),
    /// The grains' step failed.
    Grains(StepError),
    /// A grain's footprint (radius plus one cell) reached a periodic side: grains are not
    /// wrapped across periodic sides (nor their contacts and forcing), so the run stops rather
    /// than continue with a cut forcing.
    GrainAtPeriodicSide {
        /// Body index.
        body: usize,
        /// Its centre (m).
        centre: [Real; 2],
        /// Step at which it left.
        step: u64,
    },
}

impl std::fmt::Display for CoupledError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CoupledError::Fluid(e) => write!(f, "fluid: {e}"),
            CoupledError::Grains(e) => write!(f, "grains: {e}"),
            CoupledError::GrainAtPeriodicSide { body, centre, step } => write!(
                f,
                "grain (body {body}) reached a periodic side of the fluid domain at step \
                 {step}, centre ({:.6e}, {:.6e}) m: grains are not wrapped across periodic \
                 sides yet; keep them one radius plus one cell away, or use walls",
                centre[0], centre[1]
            ),
        }
    }
}

impl std::error::Error for CoupledError {}

/// The coupled stepper: the fluid solver, the contact stepper, and the immersed bodies.
pub struct CoupledStepper {
    fluid: FluidSolver,
    /// The whole grid (a block's stepper holds one block of it).
    domain: MacGrid,
    grains: MoreauJean,
    immersed: Vec<usize>,
    disks: Vec<ImmersedDisk>,
    forces: Vec<[Real; DOFS]>,
    /// The walls of the whole domain (no-slip or moving sides), for the lubrication correction.
    walls: Vec<LubricatedWall>,
    /// Workspaces of the lubrication correction.
    lubricated: Vec<LubricatedGrain>,
    lubrication_forces: Vec<Vector>,
    /// The whole grid's largest fluid speed (m/s) after the last step, with the step count of
    /// the fluid state it was measured on: the next step's time step needs no reduction.
    fluid_speed: Option<(u64, Real)>,
}

impl CoupledStepper {
    /// A stepper for `state` (the disks of `state.world` are immersed). Each step's length is
    /// chosen by [`FluidSolver::stable_dt_for`], at most `params.dt_max`, and handed to the
    /// grains' step ([`MoreauJean::step_by`]); `world.params.dt` is not used.
    pub fn new(params: &FluidParams, state: &CoupledState) -> Result<Self, FluidError> {
        let fluid = FluidSolver::new(state.fluid.grid, params)?;
        Ok(Self::with_solver(
            fluid,
            state.fluid.grid,
            &params.boundary,
            state,
        ))
    }

    /// A stepper for one block of a grid split among processes: `state.fluid` holds the
    /// block, `domain` is the whole grid and `params` carry the block's sides
    /// ([`crate::FluidBoundary::block`]), `whole` the whole domain's; every block holds all
    /// the grains. Stepped by [`CoupledStepper::step_with`].
    pub fn new_block(
        params: &FluidParams,
        state: &CoupledState,
        domain: MacGrid,
        whole: &FluidBoundary,
    ) -> Result<Self, FluidError> {
        let fluid = FluidSolver::new_block(state.fluid.grid, params)?;
        Ok(Self::with_solver(fluid, domain, whole, state))
    }

    fn with_solver(
        fluid: FluidSolver,
        domain: MacGrid,
        whole: &FluidBoundary,
        state: &CoupledState,
    ) -> Self {
        let mut walls = Vec::new();
        for axis in 0..DIM {
            let [low, high] = whole.sides(axis);
            let ends = [
                domain.origin[axis],
                domain.origin[axis] + domain.extent()[axis],
            ];
            for ((side, at), towards) in [low, high].into_iter().zip(ends).zip([1.0, -1.0]) {
                if matches!(
                    side,
                    SideCondition::NoSlip | SideCondition::MovingWall { .. }
                ) {
                    walls.push(LubricatedWall {
                        axis,
                        at,
                        side: towards,
                    });
                }
            }
        }
        let bodies = &state.world.bodies;
        let immersed = (0..bodies.len())
            .filter(|&b| matches!(bodies.shape[b], Shape::Disk { .. }))
            .collect();
        CoupledStepper {
            fluid,
            domain,
            grains: MoreauJean::new(),
            immersed,
            disks: Vec::new(),
            forces: Vec::new(),
            walls,
            lubricated: Vec::new(),
            lubrication_forces: Vec::new(),
            fluid_speed: None,
        }
    }

    /// Body indices of the immersed disks.
    pub fn immersed(&self) -> &[usize] {
        &self.immersed
    }

    /// One coupled step.
    pub fn step(
        &mut self,
        params: &FluidParams,
        state: &mut CoupledState,
    ) -> Result<CoupledReport, CoupledError> {
        self.step_by_stages(params, state, None)
    }

    /// Makes the next step measure the fluid's largest speed and exchange its halos afresh
    /// (after the caller changed the fluid of the state the last step left; see
    /// [`FluidSolver::fields_changed`]).
    pub fn fields_changed(&mut self) {
        self.fluid_speed = None;
        self.fluid.fields_changed();
    }

    /// One coupled step of a block of a split grid (see [`FluidSolver::step_with`]): the
    /// fluid's halos, sums and pressure solve go through `links`; the hydrodynamic forces are
    /// the whole grid's, so every block moves the grains identically. A step starts from what
    /// the last one left of the same state (its halos, its largest speed): a caller that
    /// changes the fluid between steps calls [`CoupledStepper::fields_changed`].
    pub fn step_with(
        &mut self,
        params: &FluidParams,
        state: &mut CoupledState,
        links: &mut dyn BlockLinks,
    ) -> Result<CoupledReport, CoupledError> {
        self.step_by_stages(params, state, Some(links))
    }

    fn step_by_stages(
        &mut self,
        params: &FluidParams,
        state: &mut CoupledState,
        mut links: Option<&mut dyn BlockLinks>,
    ) -> Result<CoupledReport, CoupledError> {
        // Stage: the immersed disks as the fluid sees them.
        let bodies = &state.world.bodies;
        self.disks.clear();
        let mut grain_speed: Real = 0.0;
        for &b in &self.immersed {
            let Shape::Disk { radius } = bodies.shape[b] else {
                unreachable!("immersed bodies are disks")
            };
            let disk = ImmersedDisk {
                centre: bodies.position[b],
                radius,
                velocity: bodies.velocity[b],
                angular_velocity: bodies.angular_velocity[b],
            };
            grain_speed =
                grain_speed.max(disk.velocity.amax() + (disk.angular_velocity * radius).abs());
            self.disks.push(disk);
        }

        // Stage: grains reaching a periodic side stop the run (their footprint would be cut).
        let grid = &self.domain;
        let (low, high) = (grid.origin, grid.origin + grid.extent());
        for (&b, disk) in self.immersed.iter().zip(&self.disks) {
            let reach = disk.radius + grid.h;
            let x = disk.centre;
            let outside = (0..DIM).any(|a| {
                params.boundary.is_periodic(a) && (x[a] - reach < low[a] || x[a] + reach > high[a])
            });
            if outside {
                return Err(CoupledError::GrainAtPeriodicSide {
                    body: b,
                    centre: [x.x, x.y],
                    step: state.world.step,
                });
            }
        }

        // Stage: time step, from the largest speed of the whole grid: the fluid's as the last
        // step reduced it when this is the state it left (every process holds every grain, so
        // their speed needs no reduction).
        let fluid_speed = match self.fluid_speed.take() {
            Some((step, speed)) if step == state.fluid.step => speed,
            _ => {
                let mut speed = [state.fluid.max_speed()];
                if let Some(links) = links.as_deref_mut() {
                    links.max(&mut speed);
                }
                speed[0]
            }
        };
        // At most `params.dt_max`, the scene's `dt`: the one bound on the step.
        let dt = self
            .fluid
            .stable_dt_for(params, fluid_speed.max(grain_speed));

        // Stage: fluid.
        let fluid = match links {
            Some(links) => self
                .fluid
                .step_with(params, &mut state.fluid, dt, &self.disks, links),
            None => self.fluid.step(params, &mut state.fluid, dt, &self.disks),
        }
        .map_err(CoupledError::Fluid)?;
        self.fluid_speed = Some((state.fluid.step, fluid.max_speed));

        // Stage: grains under hydrodynamic forces and buoyancy.
        let world = &mut state.world;
        let gravity = world.params.gravity;
        self.forces.clear();
        self.forces.resize(world.bodies.len(), [0.0; DOFS]);
        for ((&b, disk), f) in self.immersed.iter().zip(&self.disks).zip(&fluid.forces) {
            let buoyancy = -params.density * disk.area() * gravity;
            self.forces[b] = [f.force.x + buoyancy.x, f.force.y + buoyancy.y, f.torque];
        }
        if let Some(lubrication) = &params.lubrication {
            let bodies = &world.bodies;
            self.lubricated.clear();
            // Each grain's velocity at the end of the step under every force but lubrication
            // and contacts (hydrodynamic, buoyancy, weight) on its free degrees of freedom:
            // the correction resists it. A grain with an imposed translation counts as fixed.
            for (&b, disk) in self.immersed.iter().zip(&self.disks) {
                let inverse = bodies.inv_mass(b);
                let f = self.forces[b];
                let mut predicted = disk.velocity;
                for d in 0..DIM {
                    if inverse[d] > 0.0 {
                        predicted[d] += (f[d] / bodies.mass[b] + gravity[d]) * dt;
                    }
                }
                self.lubricated.push(LubricatedGrain {
                    centre: disk.centre,
                    radius: disk.radius,
                    velocity: predicted,
                    inverse_mass: inverse[..DIM]
                        .iter()
                        .copied()
                        .fold(Real::INFINITY, Real::min),
                });
            }
            self.lubrication_forces.clear();
            self.lubrication_forces
                .resize(self.immersed.len(), Vector::zeros());
            lubrication.add_forces(
                params.viscosity,
                self.domain.h,
                dt,
                &self.lubricated,
                &self.walls,
                &mut self.lubrication_forces,
            );
            for (&b, f) in self.immersed.iter().zip(&self.lubrication_forces) {
                self.forces[b][0] += f.x;
                self.forces[b][1] += f.y;
            }
        }
        self.grains.set_external_forces(&self.forces);
        let grains = self
            .grains
            .step_by(world, dt)
            .map_err(CoupledError::Grains)?;
        Ok(CoupledReport { fluid, grains })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FluidBoundary, MacGrid};
    use xper_bodies::{Body, BodySet};
    use xper_laws::LawTable;
    use xper_math::Vector;
    use xper_nscd::StepParams;

    #[test]
    fn a_grain_reaching_a_periodic_side_stops_the_run_with_its_position() {
        let mut bodies = BodySet::new();
        bodies.insert(
            Body::disk(0.05, 2000.0, Vector::new(0.9, 0.5)).with_velocity(Vector::new(1.0, 0.0)),
        );
        let world_params = StepParams {
            dt: 1e-3,
            theta: 0.5,
            gravity: Vector::zeros(),
            alert_distance: 1e-3,
            detection: Default::default(),
            nlgs: Default::default(),
            solver: xper_nscd::VelocitySolver::Nlgs,
            projection_tolerance: None,
        };
        let mut params = FluidParams::new(1000.0, 1.0, FluidBoundary::periodic());
        params.dt_max = 1e-3;
        let grid = MacGrid::square(32, 1.0);
        let mut state = CoupledState {
            fluid: FluidState::at_rest(grid, &params.boundary),
            world: World::new(bodies, LawTable::new(1), world_params),
        };
        let mut stepper = CoupledStepper::new(&params, &state).unwrap();
        let mut outcome = Ok(());
        for _ in 0..400 {
            if let Err(e) = stepper.step(&params, &mut state) {
                outcome = Err(e);
                break;
            }
        }
        match outcome {
            Err(CoupledError::GrainAtPeriodicSide { body, centre, .. }) => {
                // Stopped as soon as x + r + h passes 1, before the forcing is cut.
                assert_eq!(body, 0);
                let reach = 0.05 + 1.0 / 32.0;
                assert!(
                    centre[0] + reach > 1.0 && centre[0] + reach < 1.01,
                    "{centre:?}"
                );
            }
            other => panic!(
                "expected the grain to be reported, got {other:?} at {:?}, velocity {:?}",
                state.world.bodies.position[0], state.world.bodies.velocity[0]
            ),
        }
    }
}
