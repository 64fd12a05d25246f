//! Validation cases of grains in the fluid (fluid + NSCD coupling), as [`Case`]s:
//!
//! - [`resting_grain`]: a heavy disk resting on the floor of a closed box of fluid stays at
//!   rest: contact (Signorini, BRIEF.md section 2) and fluid forcing agree;
//! - [`settling_convergence`]: the velocity of a disk settling in a channel, at a fixed time,
//!   on three grids; its observed order of convergence.

use crate::Case;
use xper_bodies::{Body, BodySet};
use xper_fluid::{CoupledState, CoupledStepper, FluidBoundary, FluidParams, FluidState, MacGrid};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{StepParams, VelocitySolver, World};
use xper_solver::{ConvergenceNorm, NlgsParams};

/// Fluid density (kg/m^3) of the grain cases.
const RHO_F: Real = 1000.0;
/// Gravity (m/s^2).
const G: Real = 9.81;

/// A closed box `width x height` (m) of fluid of viscosity `mu` (Pa s) with one disk of
/// diameter `d` (m) and density `ratio x RHO_F` at `centre`, walls on the floor and the sides
/// (Signorini-Coulomb, mu = 0.5), `cells_per_diameter` cells across the disk.
fn grain_in_box(
    d: Real,
    ratio: Real,
    mu: Real,
    size: [Real; 2],
    centre: Vector,
    cells_per_diameter: usize,
) -> Result<(FluidParams, CoupledState), String> {
    let mut bodies = BodySet::new();
    bodies.insert(Body::disk(0.5 * d, ratio * RHO_F, centre).in_group(0));
    let [w, h] = size;
    for (a, b) in [
        ((0.0, 0.0), (w, 0.0)),
        ((0.0, h), (0.0, 0.0)),
        ((w, 0.0), (w, h)),
    ] {
        bodies.insert(Body::wall(Vector::new(a.0, a.1), Vector::new(b.0, b.1)).in_group(1));
    }
    let mut laws = LawTable::new(2);
    laws.set(
        0,
        1,
        InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
            friction: 0.5,
            restitution: 0.0,
        }),
    );
    let params = StepParams {
        dt: 1e-3,
        theta: 0.5,
        gravity: Vector::new(0.0, -G),
        alert_distance: 0.1 * d,
        detection: Default::default(),
        nlgs: NlgsParams {
            tolerance: 1e-10,
            max_iterations: 1000,
            check_every: 1,
            relaxation: 1.0,
            norm: ConvergenceNorm::NaturalMap,
            ..Default::default()
        },
        solver: VelocitySolver::Nlgs,
        projection_tolerance: Some(1e-4 * d),
    };
    let cell = d / cells_per_diameter as Real;
    let n = |length: Real| (length / cell).round() as usize;
    let grid = MacGrid {
        nx: n(w),
        ny: n(h),
        h: cell,
        origin: Vector::zeros(),
    };
    let fluid = FluidParams::new(RHO_F, mu, FluidBoundary::closed_box());
    let state = CoupledState {
        fluid: FluidState::at_rest(grid, &fluid.boundary),
        world: World::new(bodies, laws, params),
    };
    Ok((fluid, state))
}

/// Runs to `end` (s); returns the largest speed of the grain and its final centre and velocity.
fn run(
    fluid: &FluidParams,
    state: &mut CoupledState,
    end: Real,
) -> Result<(Real, Vector, Vector), String> {
    let mut stepper = CoupledStepper::new(fluid, state).map_err(|e| e.to_string())?;
    let mut fastest: Real = 0.0;
    while state.world.time < end * (1.0 - 1e-12) {
        stepper.step(fluid, state).map_err(|e| e.to_string())?;
        fastest = fastest.max(state.world.bodies.velocity[0].norm());
    }
    Ok((
        fastest,
        state.world.bodies.position[0],
        state.world.bodies.velocity[0],
    ))
}

/// A disk of d = 2 mm, density 1.5 rho_f, resting on the floor of an 8d x 4d box of water
/// (mu = 1e-3 Pa s) for 0.05 s at 16 cells per diameter: its largest speed relative to the free
/// fall speed `g t` it would reach without the floor, tolerance 1e-4.
pub fn resting_grain() -> Result<Case, String> {
    let d = 2e-3;
    let (fluid, mut state) = grain_in_box(
        d,
        1.5,
        1e-3,
        [8.0 * d, 4.0 * d],
        Vector::new(4.0 * d, 0.5 * d),
        16,
    )?;
    let end = 0.05;
    let (fastest, centre, _) = run(&fluid, &mut state, end)?;
    let ratio = fastest / (G * end);
    Ok(Case {
        name: "a grain resting on the floor of a box of fluid stays at rest (16 cells per diameter, 0.05 s)".into(),
        reference: "velocity 0 (contact and fluid in equilibrium)".into(),
        measured: format!(
            "largest speed {fastest:.2e} m/s = {ratio:.2e} g t; centre moved by {:.2e} d",
            (centre - Vector::new(4.0 * d, 0.5 * d)).norm() / d
        ),
        error: ratio,
        tolerance: 1e-4,
    })
}

/// Settling velocity at `t = 0.1` s of a disk (d = 2 mm, density 1.5 rho_f) released at rest at
/// mid-width, 12 d high, in an 8d x 16d box of fluid with mu = 1e-2 Pa s (nu = 1e-5 m^2/s), on
/// `cells`, `2 cells` and `4 cells` per diameter; observed order from the three. The error is
/// the relative change between the two finest grids (tolerance 5 %).
pub fn settling_convergence(cells: usize) -> Result<Case, String> {
    let d = 2e-3;
    let mut velocities = Vec::new();
    for k in 0..3 {
        let cpd = cells << k;
        let (fluid, mut state) = grain_in_box(
            d,
            1.5,
            1e-2,
            [8.0 * d, 16.0 * d],
            Vector::new(4.0 * d, 12.0 * d),
            cpd,
        )?;
        let (_, _, velocity) = run(&fluid, &mut state, 0.1)?;
        velocities.push(velocity.y);
    }
    let (a, b) = (
        (velocities[0] - velocities[1]).abs(),
        (velocities[1] - velocities[2]).abs(),
    );
    let order = (a / b).log2();
    Ok(Case {
        name: format!(
            "settling velocity of one grain at t = 0.1 s, {cells}, {}, {} cells per diameter",
            2 * cells,
            4 * cells
        ),
        reference: "converges under refinement (observed order reported)".into(),
        measured: format!(
            "v = {:.5}, {:.5}, {:.5} m/s; order {order:.2}",
            velocities[0], velocities[1], velocities[2]
        ),
        error: b / velocities[2].abs(),
        tolerance: 0.05,
    })
}
