//! Stage `interfaces` of a step: new displacement jumps, intensities (once per step, as in
//! BRIEF.md section 3) and the interface energies.

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

/// What a step reports of the whole model: this model's share summed over the processes
/// sharing it ([`ContactSolve::sum`], one reduction per step).
pub(crate) struct StepTotals {
    pub contacts: usize,
    pub broken_points: usize,
    pub broken_interfaces: usize,
    pub energy: FractureEnergy,
    pub loads: Vec<LoadReading>,
}

impl StepTotals {
    /// Sums the counts, the energy budget and the load sums (per load: force x, y,
    /// displacement x, y, degrees of freedom x, y) of `m`'s share, then averages the
    /// displacements.
    pub fn sum(
        m: &FractureModel,
        contacts: usize,
        load_sums: Vec<[f64; 6]>,
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
        let head = values.len();
        values.extend(load_sums.iter().flatten());
        solver.sum(&mut values);
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
        }
    }
}
