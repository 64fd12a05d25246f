//! Patch test of the exploded mesh: under a uniform uniaxial traction, every element carries
//! the same stress and every bonded cohesive interface opens by the jump its compliance
//! gives, `[u] = K^-1 (sigma n)` in the interface frame (C_N, C_T in Pa/m).
//!
//! The grid's interior nodes have their edges in opposite pairs, so the uniform stress state
//! is exactly compatible with the interface jumps; it is reached by backward Euler
//! (theta = 1) steps, which damp the dynamics, from rest under constant end forces.

mod common;

use common::*;
use xper_bodies::{Drive, TimeFunction};
use xper_fracture::{FractureModel, FractureStepper, InterfaceLaw};

#[test]
fn uniform_traction_gives_uniform_stress_and_the_compliance_jumps() {
    let (young, nu, c, sigma) = (1e4, 0.3, 1e5, 100.0);
    let mesh = grid(4, 3, 0.25, 0.25, |_| 0);
    let law = InterfaceLaw::Cohesive(zone(c, 1e20, 1e9, 0.0));
    let mut spec = spec(vec![elastic(young, nu, 1.0)], everywhere(1, law), 0.01, 1.0);
    let force = sigma * 0.75;
    spec.loads = vec![
        load(
            &mesh,
            "left",
            [Drive::Force(TimeFunction::Constant(-force)), Drive::Free],
        ),
        load(
            &mesh,
            "right",
            [Drive::Force(TimeFunction::Constant(force)), Drive::Free],
        ),
    ];
    let mut model = FractureModel::new(mesh, spec).unwrap();
    let mut stepper = FractureStepper::new();
    for _ in 0..200 {
        let r = stepper.step(&mut model).unwrap();
        assert!(r.converged, "step {} did not converge", r.step);
    }
    for (e, el) in model.elements.iter().enumerate() {
        let s = el.state.stress;
        assert!(
            (s[0] - sigma).abs() < 1e-6 * sigma
                && s[1].abs() < 1e-6 * sigma
                && s[3].abs() < 1e-6 * sigma,
            "element {e}: stress {s:?}"
        );
    }
    for i in &model.interfaces {
        let [nx, ny] = i.normal;
        // Traction sigma n in the (n, t) frame, t = (-n_y, n_x): (sigma n_x^2, -sigma n_x n_y).
        let expected = [sigma * nx * nx / c, -sigma * nx * ny / c];
        for p in &i.points {
            for d in 0..2 {
                assert!(
                    (p.jump[d] - expected[d]).abs() < 1e-6 * sigma / c,
                    "interface normal {:?}: jump {:?}, expected {expected:?}",
                    i.normal,
                    p.jump
                );
            }
        }
    }
}
