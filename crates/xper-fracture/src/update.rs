//! Stage `interfaces` of a step: new displacement jumps, intensities (once per step, as in
//! BRIEF.md section 3) and the interface energies.

use crate::cell::{tensor_weights, CellState, MacroDrive, SHEAR_WEIGHT};
use crate::interface::cohesive;
use crate::model::{FractureEnergy, FractureModel};
use crate::operator::ElementContactOperator;
use crate::step::{stored_energy, FractureStepper, LoadReading};
use xper_solver::ContactSolve;

/// Updates the interface points of `m` from the solved step in `stepper`.
pub(crate) fn interfaces(stepper: &FractureStepper, m: &mut FractureModel) {
    let (h, th) = (m.spec.dt, m.spec.theta);
    let points = stepper.points();
    let (mut damage, mut contact) = (0.0, 0.0);
    for (i, interface) in m.interfaces.iter_mut().enumerate() {
        let law = m.laws[interface.law as usize];
        let area = 0.5 * interface.length * m.spec.thickness;
        for (k, p) in interface.points.iter_mut().enumerate() {
            let w = &points[2 * i + k];
            let (u0, u1, r) = (w.u_begin, stepper.end_velocity(&w.row), w.impulse);
            let weighted = [
                (1.0 - th) * u0[0] + th * u1[0],
                (1.0 - th) * u0[1] + th * u1[1],
            ];
            let adhesive = [
                -(w.offset[0] + w.stiffness[0] * u1[0]),
                -(w.offset[1] + w.stiffness[1] * u1[1]),
            ];
            let rc = [r[0] - adhesive[0], r[1] - adhesive[1]];
            contact -= rc[0] * weighted[0] + rc[1] * weighted[1];
            p.jump = [p.jump[0] + h * weighted[0], p.jump[1] + h * weighted[1]];
            p.impulse = r;
            p.adhesive_impulse = adhesive;
            if let Some(z) = cohesive(&law) {
                if p.intensity > 0.0 {
                    let (beta, max_jump) = z.update_intensity(p.max_jump, p.jump);
                    damage += area * z.damage_dissipation_per_area(p.jump, p.intensity, beta);
                    p.intensity = beta;
                    p.max_jump = max_jump;
                }
            }
        }
    }
    m.energy.cohesive_dissipated += damage;
    m.energy.contact_dissipated += contact;
    m.energy.cohesive_stored = stored_energy(m);
}

/// This model's share of the macroscopic measures of a periodic cell over a step.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CellSums {
    /// `sum V_e sigma_e` over the owned elements (N m).
    volume: [f64; 3],
    /// `sum tensor_weights(p, T)` over the periodic points (N s m).
    boundary: [f64; 3],
    /// Work of the macroscopic loading (J).
    work: f64,
    /// `V` (m^3) and `h` (s) of the cell, to turn the sums into stresses.
    scale: [f64; 2],
}

/// Stage `cell`: the macroscopic strain at the end of the step, the work of the loading
/// (added to the external work), and this model's share of the stress measures.
pub(crate) fn cell(stepper: &FractureStepper, m: &mut FractureModel) -> Option<CellSums> {
    let p = m.spec.periodic.as_ref()?;
    let (h, th) = (m.spec.dt, m.spec.theta);
    let t_end = m.time + h;
    let volume = p.cell.area() * m.spec.thickness;
    let (begin, end) = stepper.cell_rates();
    let weighted: [f64; 3] = std::array::from_fn(|k| (1.0 - th) * begin[k] + th * end[k]);
    let mut sums = CellSums {
        scale: [volume, h],
        ..Default::default()
    };
    for (i, interface) in m.interfaces.iter().enumerate() {
        if interface.period == [0.0; 2] {
            continue;
        }
        for k in 0..2 {
            let w = &stepper.points()[2 * i + k];
            let force = ElementContactOperator::global_impulse(&w.row, w.impulse);
            let t = tensor_weights(force, interface.period);
            for c in 0..3 {
                sums.boundary[c] += t[c];
                if !p.is_free(c) {
                    sums.work += t[c] * weighted[c];
                }
            }
        }
    }
    for (e, el) in m.elements.iter().enumerate() {
        if m.is_shadow(e) {
            continue;
        }
        let sigma = el.state.in_plane_stress();
        for c in 0..3 {
            sums.volume[c] += el.triangle.volume() * sigma[c];
        }
    }
    let state = m.cell.as_mut()?;
    for (k, drive) in p.drives.iter().enumerate() {
        match drive {
            MacroDrive::Strain(f) => state.strain[k] = f.eval(t_end),
            MacroDrive::Stress(f) => {
                let increment = h * weighted[k];
                if !m.cell_copy {
                    sums.work += SHEAR_WEIGHT[k] * volume * f.eval(m.time + th * h) * increment;
                }
                state.strain[k] += increment;
            }
        }
        state.rate[k] = end[k];
    }
    m.energy.external_work += sums.work;
    Some(sums)
}

/// What a step reports of the whole model: this model's share summed over the processes
/// sharing it ([`ContactSolve::sum`], one reduction per step).
pub(crate) struct StepTotals {
    pub contacts: usize,
    pub broken_points: usize,
    pub damaged_points: usize,
    pub cohesive_points: usize,
    pub broken_interfaces: usize,
    pub energy: FractureEnergy,
    pub loads: Vec<LoadReading>,
    cell: Option<CellSums>,
}

impl StepTotals {
    /// Sums the counts, the energy budget and the load sums (per load: force x, y,
    /// displacement x, y, degrees of freedom x, y) of `m`'s share, then averages the
    /// displacements.
    pub fn sum(
        m: &FractureModel,
        contacts: usize,
        load_sums: Vec<[f64; 6]>,
        mut cell: Option<CellSums>,
        solver: &mut dyn ContactSolve<ElementContactOperator>,
    ) -> Self {
        let e = m.energy;
        let mut values = vec![
            contacts as f64,
            m.broken_points() as f64,
            m.broken_interfaces() as f64,
            e.kinetic,
            e.elastic,
            e.plastic,
            e.cohesive_stored,
            e.cohesive_dissipated,
            e.contact_dissipated,
            e.external_work,
            e.initial,
        ];
        if let Some(c) = &cell {
            values.extend(c.volume.iter().chain(&c.boundary));
            values.extend([
                c.work,
                m.damaged_points() as f64,
                m.cohesive_points() as f64,
            ]);
        }
        let head = values.len();
        values.extend(load_sums.iter().flatten());
        solver.sum(&mut values);
        let (mut damaged_points, mut cohesive_points) = (0, 0);
        if let Some(c) = &mut cell {
            damaged_points = values[head - 2] as usize;
            cohesive_points = values[head - 1] as usize;
            let s = &values[head - 9..head - 2];
            c.volume.copy_from_slice(&s[..3]);
            c.boundary.copy_from_slice(&s[3..6]);
            c.work = s[6];
        }
        let loads = values[head..]
            .chunks_exact(6)
            .map(|s| LoadReading {
                force: [s[0], s[1]],
                displacement: std::array::from_fn(|d| {
                    if s[4 + d] > 0.0 {
                        s[2 + d] / s[4 + d]
                    } else {
                        s[2 + d]
                    }
                }),
            })
            .collect();
        StepTotals {
            contacts: values[0] as usize,
            broken_points: values[1] as usize,
            damaged_points,
            cohesive_points,
            broken_interfaces: values[2] as usize,
            energy: FractureEnergy {
                kinetic: values[3],
                elastic: values[4],
                plastic: values[5],
                cohesive_stored: values[6],
                cohesive_dissipated: values[7],
                contact_dissipated: values[8],
                external_work: values[9],
                initial: values[10],
            },
            loads,
            cell,
        }
    }

    /// Writes the whole cell's stresses and the step's work of the loading into `state`.
    pub fn apply_to(&self, state: &mut CellState) {
        let Some(c) = &self.cell else {
            return;
        };
        let [volume, h] = c.scale;
        state.stress_volume = c.volume.map(|v| v / volume);
        state.stress_boundary = [
            c.boundary[0] / (volume * h),
            c.boundary[1] / (volume * h),
            0.5 * c.boundary[2] / (volume * h),
        ];
        state.work += c.work;
    }
}
