//! Periodic cells that break: a single cohesive line across the cell follows the
//! bar-and-crack curve and dissipates `w` per unit crack length; a crack leaving one side
//! re-enters from the opposite one.

use super::runs::{converged, run, transit, E, NU};
use super::setup::*;
use super::{case, tensor, Case};
use xper_bodies::TimeFunction;
use xper_fracture::{InterfaceLaw, InterfaceRule, MacroDrive};
use xper_mesh::{Mesh, Region};

/// The rules of a cell whose regions `weak_pair` meet through `weak` and every other pair of
/// `pairs` through `stiff`.
fn rules(
    pairs: [[u32; 2]; 6],
    weak_pair: [u32; 2],
    weak: InterfaceLaw,
    stiff: InterfaceLaw,
) -> Vec<InterfaceRule> {
    (pairs.map(|regions| InterfaceRule {
        regions,
        law: if regions == weak_pair { weak } else { stiff },
    }))
    .to_vec()
}

/// One cohesive line across the cell: an 8 x 4 grid (1 mm x 0.5 mm, E = 100 GPa, nu = 0.3)
/// whose first and last columns are regions of their own, so that the only interfaces between
/// them are those across the periodic side x = 0 = L (C = 10 E / h, R_max = 30 MPa,
/// w = 10 J/m^2); every other interface is stiff (1e3 E / h) and does not break. E_xx is
/// ramped to 5.5e-4 over 103 wave transits in 8250 steps (E_yy = E_xy = 0). The macroscopic
/// curve is that of a bar and one cohesive crack, `E L = Sigma L / E' + delta(Sigma)`
/// (BRIEF.md section 10), `E'` the cell's C11 without the weak line and `delta` the law's
/// opening at traction Sigma. L < 2 E' w / R^2: no snap-back. The errors are those of the
/// damage update once per step (first order in the strain increment: the peak's excess, the
/// largest departure from the curve and the excess dissipation halve when the steps double).
pub fn single_line() -> Result<Vec<Case>, String> {
    const S: &str = "periodic cell with one cohesive line across its side, slow E_xx";
    let (nx, ny, length, height) = (8, 4, 1e-3, 0.5e-3);
    let h = length / nx as f64;
    let stiff = stiff_zone(1e3 * E / h);
    let (r, w) = (30e6, 10.0);
    let weak = weak_zone(10.0 * E / h, r, w);
    let (final_strain, duration, steps) = (5.5e-4, 103.0 * transit(length), 8250);
    let drives = [
        MacroDrive::Strain(TimeFunction::Table(vec![
            (0.0, 0.0),
            (duration, final_strain),
        ])),
        MacroDrive::Strain(TimeFunction::Constant(0.0)),
        MacroDrive::Strain(TimeFunction::Constant(0.0)),
    ];
    let build = |weak_law| {
        let mut mesh = grid(nx, ny, length, height, |_| false)?;
        for t in 0..mesh.triangles.len() {
            let cx = mesh.triangles[t]
                .iter()
                .map(|&n| mesh.nodes[n as usize][0])
                .sum::<f64>()
                / 3.0;
            mesh.triangle_region[t] = if cx < h {
                0
            } else if cx > length - h {
                2
            } else {
                1
            };
        }
        mesh.regions.push(Region {
            name: "last".into(),
            tag: 3,
        });
        let pairs = [[0, 0], [1, 1], [2, 2], [0, 1], [1, 2], [0, 2]];
        let laws = rules(
            pairs,
            [0, 2],
            InterfaceLaw::Cohesive(weak_law),
            InterfaceLaw::Cohesive(stiff),
        );
        cell_model_with(
            mesh,
            vec![elastic(E, NU); 3],
            laws,
            drives.clone(),
            duration / steps as f64,
        )
    };
    let bulk = tensor(S, &build(stiff)?)?.tensor[0][0];
    let mut m = build(weak)?;
    let (mut peak, mut worst, mut softening) = (0.0f64, 0.0f64, 0);
    let result = run(S, &mut m, steps, |m| {
        let cell = m.cell.unwrap_or_default();
        // The force across the line is the boundary stress; the bulk's mean strain is the
        // volume-average stress over E'.
        let traction = cell.stress_boundary[0];
        peak = peak.max(traction);
        let opening = cell.strain[0] * length - cell.stress_volume[0] * length / bulk;
        if opening > weak.d0() && opening < weak.dc() {
            let law = weak.stiffness(weak.intensity(opening))[0] * opening;
            worst = worst.max((traction - law).abs());
            softening += 1;
        }
    })?;
    let cell = m.cell.unwrap_or_default();
    let crack_area = height * m.spec.thickness;
    let dissipated = m.energy.cohesive_dissipated;
    let e = m.energy;
    let held =
        e.kinetic + e.elastic + e.cohesive_stored + e.cohesive_dissipated + e.contact_dissipated
            - e.initial;
    Ok(vec![
        case(
            format!("{S}: peak stress = strength"),
            format!("the law's strength R_max = {r:.1e} Pa; error relative"),
            format!("peak Sigma_xx {peak:.6e} Pa (boundary forces)"),
            (peak - r).abs() / r,
            1e-2,
        ),
        case(
            format!("{S}: softening on the bar-and-crack curve"),
            "E_xx L = Sigma L / E' + delta(Sigma), delta the law's opening (BRIEF.md sections 3 \
             and 10), on the softening branch; error max |Sigma - law(opening)| / R_max"
                .into(),
            format!("largest departure {worst:.3e} Pa over {softening} steps on the branch"),
            if softening > 500 { worst / r } else { f64::NAN },
            1e-2,
        ),
        case(
            format!("{S}: dissipated energy = w per unit crack length"),
            format!(
                "w H t = {:.4e} J (the line broken through); error relative",
                w * crack_area
            ),
            format!(
                "{dissipated:.6e} J, {} interfaces broken of {ny}",
                m.broken_interfaces()
            ),
            if m.broken_interfaces() == ny {
                (dissipated - w * crack_area).abs() / (w * crack_area)
            } else {
                f64::NAN
            },
            1e-3,
        ),
        case(
            format!("{S}: nothing carried across the broken line"),
            "Sigma_xx = 0 once the line is broken; error |Sigma_xx| / R_max".into(),
            format!("Sigma_xx {:.3e} Pa", cell.stress_boundary[0]),
            cell.stress_boundary[0].abs() / r,
            1e-9,
        ),
        case(
            format!("{S}: energy under damage"),
            "work of the macroscopic strain = kinetic + elastic + stored + dissipated energies; \
             error relative"
                .into(),
            format!("{held:.6e} J against the work {:.6e} J", cell.work),
            (held - cell.work).abs() / cell.work,
            1e-2,
        ),
        converged(S, &result),
    ])
}

/// A crack that crosses the sides: on a 6 x 6 grid (1 mm square, E = 100 GPa, nu = 0.3) whose
/// squares are all cut along the same diagonal, the diagonal edges of the squares `(i, j)`
/// with `j - i = 2 (mod 6)` form one straight line of slope 1 that leaves the cell through
/// the top and the right side and re-enters through the bottom and the left. Only those
/// interfaces can break (C = 10 E / h, R_max = 30 MPa, w = 10 J/m^2). Pulled by
/// E_xx = E_yy (ramped to 8e-4, 4000 steps), the whole line breaks, every piece of it, and the
/// cell then carries no normal stress across it: a crack that did not re-enter could not free
/// it. The pieces ring after the break (theta = 1/2 does not damp).
pub fn reentering_crack() -> Result<Vec<Case>, String> {
    const S: &str = "periodic cell, a crack line leaving through two sides";
    let (n, k, side) = (6usize, 2usize, 1e-3);
    let h = side / n as f64;
    let node = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let coordinate = |i: usize| {
        if i == n {
            side
        } else {
            side * i as f64 / n as f64
        }
    };
    let nodes: Vec<[f64; 2]> = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| (i, j)))
        .map(|(i, j)| [coordinate(i), coordinate(j)])
        .collect();
    let (mut triangles, mut regions) = (Vec::new(), Vec::new());
    for j in 0..n {
        for i in 0..n {
            let on_line = (j + n - i) % n == k;
            let [a, b, c, d] = [
                node(i, j),
                node(i + 1, j),
                node(i + 1, j + 1),
                node(i, j + 1),
            ];
            triangles.extend([[a, b, c], [a, c, d]]);
            regions.extend(if on_line { [1, 2] } else { [0, 0] });
        }
    }
    let names = ["bulk", "below", "above"].map(|name| Region {
        name: name.into(),
        tag: 1,
    });
    let mesh = Mesh::new(nodes, triangles, regions, names.to_vec()).map_err(|e| e.to_string())?;
    let (r, weak) = (30e6, weak_zone(10.0 * E / h, 30e6, 10.0));
    let pairs = [[0, 0], [1, 1], [2, 2], [0, 1], [0, 2], [1, 2]];
    let laws = rules(
        pairs,
        [1, 2],
        InterfaceLaw::Cohesive(weak),
        InterfaceLaw::Cohesive(stiff_zone(1e3 * E / h)),
    );
    let steps = 4000;
    let duration = 133.0 * side / 5800.0;
    let ramp = TimeFunction::Table(vec![(0.0, 0.0), (duration, 8e-4)]);
    let drives = [
        MacroDrive::Strain(ramp.clone()),
        MacroDrive::Strain(ramp),
        MacroDrive::Strain(TimeFunction::Constant(0.0)),
    ];
    let mut m = cell_model_with(
        mesh,
        vec![elastic(E, NU); 3],
        laws,
        drives,
        duration / steps as f64,
    )?;
    let weak_law = (m.laws.iter()).position(|l| *l == InterfaceLaw::Cohesive(weak));
    let weak_ones: Vec<usize> = (0..m.interfaces.len())
        .filter(|&i| Some(m.interfaces[i].law as usize) == weak_law)
        .collect();
    let (mut peak, mut tail) = (0.0f64, Vec::new());
    let normal_stress = |s: [f64; 3]| 0.5 * (s[0] + s[1]) - s[2];
    let result = run(S, &mut m, steps, |m| {
        let s = normal_stress(m.cell.unwrap_or_default().stress_boundary);
        peak = peak.max(s);
        if m.broken_interfaces() == n {
            tail.push(s);
        }
    })?;
    let broken = (weak_ones.iter())
        .filter(|&&i| m.is_broken(&m.interfaces[i]))
        .count();
    let mean = tail.iter().sum::<f64>() / tail.len().max(1) as f64;
    let largest = tail.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let long_enough = tail.len() > 1000 && peak > 0.9 * r;
    Ok(vec![
        case(
            format!("{S}: every piece of the line breaks"),
            format!(
                "the {n} diagonal interfaces of the line (it leaves through the top and the right \
                 side and re-enters through the bottom and the left) broken, nothing else; error \
                 = pieces missing or extra"
            ),
            format!(
                "{broken} of {} broken, {} broken in all",
                weak_ones.len(),
                m.broken_interfaces()
            ),
            (n as f64 - broken as f64).abs() + (m.broken_interfaces() as f64 - n as f64).abs(),
            0.0,
        ),
        case(
            format!("{S}: no normal stress across the broken line"),
            format!(
                "once the line is broken (more than 1000 steps before the end, the peak above \
                 0.9 R_max = {:.1e} Pa) the mean normal stress across it vanishes; error \
                 |mean| / peak",
                0.9 * r
            ),
            format!(
                "peak {peak:.4e} Pa, mean {mean:.3e} Pa over {} steps, ringing up to {largest:.3e} Pa",
                tail.len()
            ),
            if long_enough { mean.abs() / peak } else { f64::NAN },
            2e-3,
        ),
        case(
            format!("{S}: the pieces ring within 5 % of the peak"),
            "the largest normal stress after the break below 5 % of the peak; error \
             largest / peak"
                .into(),
            format!("{largest:.3e} Pa"),
            if long_enough { largest / peak } else { f64::NAN },
            5e-2,
        ),
        converged(S, &result),
    ])
}
