//! Stage `interfaces` of a step: new displacement jumps, intensities (once per step, as in
//! BRIEF.md section 3) and the interface energies.

use crate::interface::cohesive;
use crate::model::FractureModel;
use crate::step::{stored_energy, FractureStepper};

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
