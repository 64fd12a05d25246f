//! Validation cases of grains in the fluid (fluid + NSCD coupling), as [`Case`]s:
//!
//! - [`resting_grain`]: a heavy disk resting on the floor of a closed box of fluid stays at
//!   rest: contact (Signorini, BRIEF.md section 2) and fluid forcing agree;
//! - [`settling_convergence`]: the velocity of a disk settling in a channel, at a fixed time,
//!   on three grids; its observed order of convergence;
//! - [`settling_in_time`]: the same disk on one grid with three time steps, for each time
//!   scheme; the observed order in time of the coupled step;
//! - [`landing_with_lubrication`]: the same disk landing on the floor, with and without the
//!   lubrication correction, on several grids.

use crate::Case;
use xper_bodies::{Body, BodySet};
use xper_fluid::{
    CoupledState, CoupledStepper, FluidBoundary, FluidParams, FluidState, Forcing, Lubrication,
    MacGrid, TimeScheme,
};
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
    disks_in_box(d, ratio, mu, size, &[centre], cells_per_diameter, 0.5)
}

/// [`grain_in_box`] with a disk at each of `centres`, and Signorini-Coulomb contacts with
/// friction `friction` (no restitution) between the disks.
pub(super) fn disks_in_box(
    d: Real,
    ratio: Real,
    mu: Real,
    size: [Real; 2],
    centres: &[Vector],
    cells_per_diameter: usize,
    friction: Real,
) -> Result<(FluidParams, CoupledState), String> {
    let mut bodies = BodySet::new();
    for &centre in centres {
        bodies.insert(Body::disk(0.5 * d, ratio * RHO_F, centre).in_group(0));
    }
    let [w, h] = size;
    for (a, b) in [
        ((0.0, 0.0), (w, 0.0)),
        ((0.0, h), (0.0, 0.0)),
        ((w, 0.0), (w, h)),
    ] {
        bodies.insert(Body::wall(Vector::new(a.0, a.1), Vector::new(b.0, b.1)).in_group(1));
    }
    let mut laws = LawTable::new(2);
    let law = InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
        friction: 0.5,
        restitution: 0.0,
    });
    laws.set(0, 1, law);
    laws.set(
        0,
        0,
        InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
            friction,
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
pub(super) fn run(
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
    let mut velocities = Vec::new();
    for k in 0..3 {
        let (fluid, mut state) = settling_disk(cells << k)?;
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

/// Diameter (m) of the settling disk of [`settling_convergence`].
const SETTLING_D: Real = 2e-3;

/// The settling disk of [`settling_convergence`] (d = 2 mm, density 1.5 rho_f, mid-width, 12 d
/// above the floor of an 8d x 16d box, mu = 1e-2 Pa s) on `cells` per diameter.
fn settling_disk(cells: usize) -> Result<(FluidParams, CoupledState), String> {
    let d = SETTLING_D;
    grain_in_box(
        d,
        1.5,
        1e-2,
        [8.0 * d, 16.0 * d],
        Vector::new(4.0 * d, 12.0 * d),
        cells,
    )
}

/// The settling disk of [`settling_convergence`] on `cells` per diameter with the time step
/// fixed at `dt` (s, below every stability limit) under `scheme`: its velocity at 0.1 s (m/s).
fn settling_velocity(cells: usize, dt: Real, scheme: TimeScheme) -> Result<Real, String> {
    let (fluid, mut state) = settling_disk(cells)?;
    let fluid = FluidParams {
        dt_max: dt,
        time_scheme: scheme,
        pressure_tolerance: 1e-10,
        pressure_max_cycles: 200,
        ..fluid
    };
    let (_, _, velocity) = run(&fluid, &mut state, 0.1)?;
    Ok(velocity.y)
}

/// The order in time of the coupled step (fluid, forcing, grains) for each fluid time scheme:
/// the settling disk of [`settling_convergence`] on `cells` per diameter with steps `dt`,
/// `dt / 2`, `dt / 4` (`dt` = 0.8 of the explicit viscous limit), each against `dt / 32` with
/// the Runge-Kutta scheme on the same grid. The forcing uses the grain's velocity at the start
/// of the step and the grain moves once per step, so the coupled step is at most first order
/// whatever the fluid's scheme; and the smoothed forcing `u += alpha (u_s - u)`, applied once
/// per step, pulls a partly covered face closer to the grain's velocity the more steps there
/// are (its slip is about `(1 - alpha) / alpha dt N`), so the limit itself moves with the step
/// and the observed order is below 1 (0.64 with Euler, 0.81 with rk3 on 8 cells per
/// diameter). The case checks an order of at least 0.5 (the error divided by at least 2 over
/// two halvings) and reports the errors, whose size is what a scheme changes.
pub fn settling_in_time(cells: usize) -> Result<Vec<Case>, String> {
    let h = 2e-3 / cells as Real;
    let nu = 1e-2 / RHO_F;
    let dt = 0.8 * h * h / (4.0 * nu);
    let reference = settling_velocity(cells, dt / 32.0, TimeScheme::Rk3)?;
    let mut cases = Vec::new();
    for (scheme, name) in [
        (TimeScheme::Euler, "explicit Euler"),
        (TimeScheme::Rk3, "rk3"),
    ] {
        let mut errors = [0.0; 3];
        for (k, e) in errors.iter_mut().enumerate() {
            *e = (settling_velocity(cells, dt / (1 << k) as Real, scheme)? - reference).abs();
        }
        let order = (errors[0] / errors[2]).log2() / 2.0;
        cases.push(Case {
            name: format!(
                "settling velocity of one grain at t = 0.1 s, {cells} cells per diameter, steps \
                 {dt:.2e}, /2, /4 s, {name}: order in time of the coupled step"
            ),
            reference: format!(
                "at least 0.5 (at most 1 expected), against rk3 with steps of {:.2e} s (v = \
                 {reference:.6} m/s)",
                dt / 32.0
            ),
            measured: format!(
                "errors {:.2e}, {:.2e}, {:.2e} m/s ({:.2e} of v at the largest step); order \
                 {order:.2}",
                errors[0],
                errors[1],
                errors[2],
                errors[0] / reference.abs()
            ),
            error: (0.5 - order).max(0.0),
            tolerance: 0.0,
        });
    }
    Ok(cases)
}

/// Time (s) at which the disk of [`settling_convergence`], released 12 d above the floor of
/// its box, first comes within 0.01 d of the floor, on `cells` per diameter, with `forcing`
/// and with or without the lubrication correction.
fn landing_time(
    cells: usize,
    forcing: Forcing,
    lubrication: Option<Lubrication>,
) -> Result<Real, String> {
    let d = SETTLING_D;
    let (fluid, mut state) = settling_disk(cells)?;
    let fluid = FluidParams {
        lubrication,
        forcing,
        ..fluid
    };
    let mut stepper = CoupledStepper::new(&fluid, &state).map_err(|e| e.to_string())?;
    while state.world.time < 0.6 {
        stepper
            .step(&fluid, &mut state)
            .map_err(|e| e.to_string())?;
        if state.world.bodies.position[0].y - 0.5 * d < 0.01 * d {
            return Ok(state.world.time);
        }
    }
    Err(format!(
        "the disk did not come within 0.01 d of the floor by 0.6 s on {cells} cells per diameter"
    ))
}

/// The landing times of [`landing_with_lubrication`] on each of `cells` per diameter with
/// `forcing`: with the lubrication correction (range one cell), then without.
pub fn landing_times(cells: &[usize], forcing: Forcing) -> Result<(Vec<Real>, Vec<Real>), String> {
    let mut with = Vec::new();
    let mut without = Vec::new();
    for &c in cells {
        with.push(landing_time(c, forcing, Some(Lubrication::default()))?);
        without.push(landing_time(c, forcing, None)?);
    }
    Ok((with, without))
}

/// Times (s) as printed in the landing rows: four decimals, comma-separated.
pub fn times_list(t: &[Real]) -> String {
    t.iter()
        .map(|v| format!("{v:.4}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The relative change of a refinement series between its two finest grids (the last two).
pub fn last_change(t: &[Real]) -> Real {
    let n = t.len();
    (t[n - 1] - t[n - 2]).abs() / t[n - 1]
}

/// The landing of a settling disk on the floor, at the end of which the fluid film under it is
/// thinner than a cell: the time to a gap of 0.01 d on each of `cells` per diameter, with the
/// fraction forcing, with the lubrication correction (range one cell; `crate::fluid` cites the
/// model) and without. With it the time converges (the last two grids within 1 %); without,
/// the film drains as fast as the grid lets it and the time moves by several per cent per
/// refinement (reported). With the marker forcing it is the other way round
/// ([`landing_times`], VALIDATION.md), which is why the correction is not a default.
pub fn landing_with_lubrication(cells: &[usize]) -> Result<Case, String> {
    let (with, without) = landing_times(cells, Forcing::Fraction)?;
    let (list, change) = (times_list, last_change);
    Ok(Case {
        name: format!(
            "a settling disk landing on the floor: time to a gap of 0.01 d, {} cells per diameter, \
             fraction forcing, with the lubrication correction (range 1 cell)",
            cells
                .iter()
                .map(|c| c.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        reference: "converges: the two finest grids within 1 %".into(),
        measured: format!(
            "with: {} s (last change {:.2} %); without: {} s (last change {:.2} %)",
            list(&with),
            100.0 * change(&with),
            list(&without),
            100.0 * change(&without)
        ),
        error: change(&with),
        tolerance: 0.01,
    })
}
