//! A fluid scene's parameters, grid and initial state.

use crate::rigid::build::world_from_scene;
use xper_fluid::{
    CoupledState, FluidBoundary, FluidParams, FluidState, InflowProfile, MacGrid, SideCondition,
    SolidIndicator,
};
use xper_math::{Real, Vector};
use xper_scene::{FluidDesc, FluidSideDesc, Scene};

/// The fluid parameters of a scene.
pub fn fluid_params(desc: &FluidDesc, dt: Real) -> FluidParams {
    let side = |s: FluidSideDesc| match s {
        FluidSideDesc::NoSlip => SideCondition::NoSlip,
        FluidSideDesc::MovingWall { velocity } => SideCondition::MovingWall { velocity },
        FluidSideDesc::Periodic => SideCondition::Periodic,
        FluidSideDesc::Outflow => SideCondition::Outflow,
        FluidSideDesc::Inflow { parabolic, speed } => SideCondition::Inflow {
            profile: if parabolic {
                InflowProfile::Parabolic { max_speed: speed }
            } else {
                InflowProfile::Uniform { speed }
            },
        },
    };
    let [left, right, bottom, top] = desc.boundary.map(side);
    FluidParams {
        body_force: Vector::new(desc.body_force[0], desc.body_force[1]),
        cfl: desc.cfl,
        viscous_safety: desc.viscous_safety,
        dt_max: dt,
        upwinding: desc.upwinding,
        indicator: if desc.sharp_indicator {
            SolidIndicator::Sharp
        } else {
            SolidIndicator::Smoothed
        },
        pressure_tolerance: desc.pressure_tolerance,
        pressure_max_cycles: desc.pressure_max_cycles,
        time_scheme: desc.time_scheme,
        lubrication: desc.lubrication,
        forcing: desc.forcing,
        ..FluidParams::new(
            desc.density,
            desc.viscosity,
            FluidBoundary {
                left,
                right,
                bottom,
                top,
            },
        )
    }
}

/// The grid of a scene's fluid.
pub fn fluid_grid(desc: &FluidDesc) -> MacGrid {
    let h = desc.cell_size;
    let n = |d: usize| ((desc.upper[d] - desc.lower[d]) / h).round() as usize;
    MacGrid {
        nx: n(0),
        ny: n(1),
        h,
        origin: Vector::new(desc.lower[0], desc.lower[1]),
    }
}

/// The state of a fluid scene at time 0.
pub fn coupled_state(scene: &Scene, desc: &FluidDesc, params: &FluidParams) -> CoupledState {
    CoupledState {
        fluid: FluidState::at_rest(fluid_grid(desc), &params.boundary),
        world: world_from_scene(scene),
    }
}
