//! Periodic cells stepped in time: slow loading gives the static answer of the effective
//! tensor, the jumps across the sides are those of the periodic fluctuation, the energy budget
//! holds, a single cohesive line follows the bar-and-crack curve, and a crack leaving one side
//! re-enters from the opposite one.

use super::setup::*;
use super::{case, tensor, Case};
use xper_bodies::TimeFunction;
use xper_fracture::{strain_times, FractureModel, FractureStepper, MacroDrive};
use xper_mesh::{periodic_cell, Circle, PeriodicCellSpec};

pub(super) const E: f64 = 100e9;
pub(super) const NU: f64 = 0.3;
/// Cell side (m).
const SIDE: f64 = 1e-3;
/// Final strain of the slow ramps.
const STRAIN: f64 = 1e-4;

/// Time for a plane-strain P-wave to cross a length `side` (m) of the elements (s).
pub(super) fn transit(side: f64) -> f64 {
    let (l, m) = lame(E, NU);
    side / ((l + 2.0 * m) / 7850.0).sqrt()
}

/// A ramp from 0 to `strain` over `duration` (s), then constant.
fn ramp(duration: f64, strain: f64) -> TimeFunction {
    TimeFunction::Table(vec![(0.0, 0.0), (duration, strain)])
}

/// A square cell of side `SIDE` with a circular inclusion crossing the left side, the
/// inclusion twice as stiff (nu = 0.25), interfaces `C_N h / E = 1e3`.
fn heterogeneous(drives: [MacroDrive; 3], dt: f64) -> Result<FractureModel, String> {
    let h = SIDE / 6.0;
    let spec = PeriodicCellSpec {
        width: SIDE,
        height: SIDE,
        circles: vec![Circle {
            center: [0.0, 0.5 * SIDE],
            radius: 0.25 * SIDE,
        }],
        rectangles: Vec::new(),
        random: None,
        element_size: h,
    };
    let mesh = periodic_cell(&spec).map_err(|e| e.to_string())?;
    let materials = [elastic(E, NU), elastic(2.0 * E, 0.25)];
    cell_model(mesh, materials, stiff_zone(1e3 * E / h), drives, dt)
}

/// What a run measured besides the model's final state.
#[derive(Default)]
pub(super) struct Run {
    /// The macroscopic work integrated independently from the volume stress,
    /// `sum V c_k Sigma_k dE_k` by the trapezoidal rule (J).
    pub work: f64,
    /// Steps whose NLGS did not converge.
    failed: usize,
    steps: usize,
}

/// Runs `steps` steps of `m`, calling `each` after every step.
pub(super) fn run(
    scenario: &str,
    m: &mut FractureModel,
    steps: usize,
    mut each: impl FnMut(&FractureModel),
) -> Result<Run, String> {
    let mut stepper = FractureStepper::new();
    let volume = m.spec.periodic.as_ref().map_or(0.0, |p| p.cell.area()) * m.spec.thickness;
    let mut out = Run::default();
    let mut previous = m.cell.ok_or(format!("{scenario}: not a periodic cell"))?;
    for _ in 0..steps {
        let report = (stepper.step(m)).map_err(|e| format!("{scenario}: step: {e}"))?;
        out.failed += usize::from(!report.converged);
        out.steps += 1;
        let now = m
            .cell
            .ok_or(format!("{scenario}: the cell state is gone"))?;
        for k in 0..3 {
            let mean = 0.5 * (previous.stress_volume[k] + now.stress_volume[k]);
            out.work += volume * [1.0, 1.0, 2.0][k] * mean * (now.strain[k] - previous.strain[k]);
        }
        previous = now;
        each(m);
    }
    Ok(out)
}

/// The case "NLGS converged at every step" (tolerance 1e-8).
pub(super) fn converged(scenario: &str, r: &Run) -> Case {
    case(
        format!("{scenario}: NLGS converged at every step"),
        "NLGS residual below 1e-8 at every step; error = the steps that did not converge".into(),
        format!("{} of {} steps converged", r.steps - r.failed, r.steps),
        r.failed as f64,
        0.0,
    )
}

/// The case "periodic fluctuation": the jump of every interface point equals the
/// displacement jump of its node copies minus `E T` across the sides, relative to
/// `E_xx SIDE`.
fn periodic_jumps(scenario: &str, m: &FractureModel) -> Case {
    let cell = m.cell.unwrap_or_default();
    let scale = STRAIN * SIDE;
    let mut worst = 0.0f64;
    for i in &m.interfaces {
        let [a, b] = i.elements.map(|e| &m.elements[e as usize]);
        let et = strain_times(&cell.strain, i.period);
        let [nx, ny] = i.normal;
        for (k, p) in i.points.iter().enumerate() {
            let [ca, cb] = i.local_nodes[k].map(|n| 2 * n as usize);
            let d = [
                b.displacement[cb] - a.displacement[ca] - et[0],
                b.displacement[cb + 1] - a.displacement[ca + 1] - et[1],
            ];
            let jump = [nx * d[0] + ny * d[1], -ny * d[0] + nx * d[1]];
            worst = worst.max((jump[0] - p.jump[0]).abs().max((jump[1] - p.jump[1]).abs()));
        }
    }
    case(
        format!("{scenario}: the fluctuation is periodic"),
        "every interface point's jump = its nodes' displacement jump - E T (T the period across \
         the sides, 0 inside); error max |difference| / (E_xx L)"
            .into(),
        format!("largest difference {worst:.3e} m"),
        worst / scale,
        1e-9,
    )
}

/// The case "energy budget": `|kinetic + elastic + stored + dissipated - initial - work|`
/// over the energy in play.
pub(super) fn energy_budget(scenario: &str, m: &FractureModel) -> Case {
    case(
        format!("{scenario}: energy balance"),
        "kinetic (the cell's free strains' included) + elastic + stored + dissipated - initial = \
         work of the macroscopic loading; error |balance| / energy in play"
            .into(),
        format!(
            "balance error {:.3e} J, in play {:.4e} J",
            m.energy.error(),
            m.energy.in_play()
        ),
        m.energy.error().abs() / m.energy.in_play(),
        1e-5,
    )
}

/// A uniaxial strain E_xx = 1e-4 ramped over 40 wave transits of the [`heterogeneous`] cell
/// (E_yy = E_xy = 0), 400 steps: the stress, both ways, is the static `C* E`; the work of the
/// loading is the independently integrated `V Sigma : dE`; the energy budget closes.
pub fn slow_strain() -> Result<Vec<Case>, String> {
    const S: &str = "periodic cell, slow uniaxial strain";
    let steps = 400;
    let duration = 40.0 * transit(SIDE);
    let drives = [
        MacroDrive::Strain(ramp(duration, STRAIN)),
        MacroDrive::Strain(TimeFunction::Constant(0.0)),
        MacroDrive::Strain(TimeFunction::Constant(0.0)),
    ];
    let mut m = heterogeneous(drives, 1.25 * duration / steps as f64)?;
    let c = tensor(S, &m)?.tensor;
    let r = run(S, &mut m, steps, |_| {})?;
    let cell = m.cell.unwrap_or_default();
    let scale = c[0][0] * STRAIN;
    let mut worst = 0.0f64;
    for (k, row) in c.iter().enumerate() {
        for got in [cell.stress_volume[k], cell.stress_boundary[k]] {
            worst = worst.max((got - row[0] * STRAIN).abs());
        }
    }
    Ok(vec![
        case(
            format!("{S}: stress = C* E"),
            format!(
                "the static answer of the effective tensor, C*_k1 E_xx (C*_11 E_xx = {:.4e} Pa), \
                 volume-average and boundary-force stresses; error max |difference| / (C*_11 E_xx)",
                scale
            ),
            format!(
                "Sigma_xx {:.4e} (volume) and {:.4e} (boundary) Pa",
                cell.stress_volume[0], cell.stress_boundary[0]
            ),
            worst / scale,
            1e-2,
        ),
        case(
            format!("{S}: work of the loading"),
            format!(
                "sum V Sigma : dE integrated from the volume stress (trapezoid) = {:.6e} J; \
                 error relative",
                r.work
            ),
            format!("{:.6e} J", cell.work),
            (cell.work - r.work).abs() / r.work,
            1e-2,
        ),
        energy_budget(S, &m),
        periodic_jumps(S, &m),
        converged(S, &r),
    ])
}

/// Uniaxial stress on the [`heterogeneous`] cell: E_xx ramped to 1e-4 over 40 wave transits,
/// Sigma_yy = Sigma_xy = 0 imposed, 600 steps. The free components settle where the static
/// tensor puts them (`C* [E_xx, E_yy, 2 E_xy] = [Sigma_xx, 0, 0]` solved for E_yy and
/// 2 E_xy), the stresses likewise; the energy budget, with the cell's own kinetic energy,
/// closes.
pub fn mixed_loading() -> Result<Vec<Case>, String> {
    const S: &str = "periodic cell, uniaxial stress (E_xx imposed, Sigma_yy = Sigma_xy = 0)";
    let steps = 600;
    let duration = 40.0 * transit(SIDE);
    let drives = [
        MacroDrive::Strain(ramp(duration, STRAIN)),
        MacroDrive::Stress(TimeFunction::Constant(0.0)),
        MacroDrive::Stress(TimeFunction::Constant(0.0)),
    ];
    let mut m = heterogeneous(drives, 1.5 * duration / steps as f64)?;
    let c = tensor(S, &m)?.tensor;
    let r = run(S, &mut m, steps, |_| {})?;
    let cell = m.cell.unwrap_or_default();
    let det = c[1][1] * c[2][2] - c[1][2] * c[2][1];
    let eyy = -(c[1][0] * c[2][2] - c[1][2] * c[2][0]) / det * STRAIN;
    let gxy = -(c[1][1] * c[2][0] - c[2][1] * c[1][0]) / det * STRAIN;
    let sxx = c[0][0] * STRAIN + c[0][1] * eyy + c[0][2] * gxy;
    let strain_error =
        ((cell.strain[1] - eyy).abs()).max((2.0 * cell.strain[2] - gxy).abs()) / STRAIN;
    let s = c[0][0] * STRAIN;
    let stress_error = ((cell.stress_volume[0] - sxx).abs())
        .max(cell.stress_boundary[1].abs())
        .max(cell.stress_boundary[2].abs())
        / s;
    Ok(vec![
        case(
            format!("{S}: free strains"),
            format!(
                "static: E_yy = {eyy:.5e}, 2 E_xy = {gxy:.3e} from C*; error max |difference| / E_xx"
            ),
            format!(
                "E_yy {:.5e}, 2 E_xy {:.3e}",
                cell.strain[1],
                2.0 * cell.strain[2]
            ),
            strain_error,
            2e-2,
        ),
        case(
            format!("{S}: stresses"),
            format!(
                "static: Sigma_xx = {sxx:.4e} Pa, Sigma_yy = Sigma_xy = 0; error max |difference| \
                 / (C*_11 E_xx)"
            ),
            format!(
                "Sigma_xx {:.4e}, Sigma_yy {:.2e}, Sigma_xy {:.2e} Pa",
                cell.stress_volume[0], cell.stress_boundary[1], cell.stress_boundary[2]
            ),
            stress_error,
            2e-2,
        ),
        energy_budget(S, &m),
        periodic_jumps(S, &m),
        converged(S, &r),
    ])
}
