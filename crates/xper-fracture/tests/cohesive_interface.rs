//! One cohesive interface between two squares of stiff elastic elements, opened quasi-
//! statically in mode I and in mode II by imposed velocities on the far edge (the near edge
//! fixed): the traction follows the law (BRIEF.md section 3), the energy dissipated at full
//! separation is w x length, unloading follows the damaged secant, and a broken interface is
//! a unilateral contact with Coulomb friction.
//!
//! Units: m, s, Pa, J. The bulk (E = 1e12 Pa) and the bonding interfaces inside each square
//! (C = 1e12 Pa/m) are 100 times stiffer than the tested interface (C = 1e10 Pa/m), so the
//! tested jump is the imposed displacement to about 2 %, and the traction is measured by the
//! reaction on the far edge.

mod common;

use common::*;
use xper_bodies::{Drive, TimeFunction};
use xper_fracture::{FractureModel, FractureStepper, InterfaceLaw, InterfaceRule};
use xper_laws::cohesive::CohesiveZone;

const C: f64 = 1e10;
const STRENGTH: f64 = 1e6;
const W: f64 = 500.0;

fn tested(friction: f64) -> CohesiveZone {
    zone(C, W, STRENGTH, friction)
}

/// Two unit squares (regions 0 and 1); the tested interface is the edge x = 1. The far edge
/// (x = 2) follows the velocity tables `vx`, `vy` (m/s); the near edge (x = 0) is fixed.
fn specimen(friction: f64, vx: TimeFunction, vy: TimeFunction, dt: f64) -> FractureModel {
    let mesh = grid(2, 1, 1.0, 1.0, |i| i as u32);
    let bond = InterfaceLaw::Cohesive(zone(1e12, 1e20, 1e12, 0.0));
    let rules = vec![
        InterfaceRule {
            regions: [0, 0],
            law: bond,
        },
        InterfaceRule {
            regions: [1, 1],
            law: bond,
        },
        InterfaceRule {
            regions: [0, 1],
            law: InterfaceLaw::Cohesive(tested(friction)),
        },
    ];
    let stiff = elastic(1e12, 0.2, 100.0);
    let mut spec = spec(vec![stiff, stiff], rules, dt, 1.0);
    spec.nlgs.tolerance = 1e-7;
    spec.loads = vec![
        load(&mesh, "left", [velocity(0.0), velocity(0.0)]),
        load(&mesh, "right", [Drive::Velocity(vx), Drive::Velocity(vy)]),
    ];
    FractureModel::new(mesh, spec).unwrap()
}

/// The tested interface.
fn tested_interface(m: &FractureModel) -> usize {
    m.interfaces
        .iter()
        .position(|i| {
            m.mesh.triangle_region[i.elements[0] as usize]
                != m.mesh.triangle_region[i.elements[1] as usize]
        })
        .unwrap()
}

/// Runs `steps` steps and returns per step (mean jump [N, T], far-edge force [x, y], beta
/// before the step).
fn run(m: &mut FractureModel, steps: usize) -> Vec<([f64; 2], [f64; 2], f64)> {
    let k = tested_interface(m);
    let mut stepper = FractureStepper::new();
    let mut out = Vec::new();
    for _ in 0..steps {
        let beta = m.interfaces[k].points[0].intensity;
        let r = stepper.step(m).unwrap();
        assert!(
            r.converged,
            "step {} did not converge ({})",
            r.step, r.residual
        );
        let p = &m.interfaces[k].points;
        let jump = [
            0.5 * (p[0].jump[0] + p[1].jump[0]),
            0.5 * (p[0].jump[1] + p[1].jump[1]),
        ];
        out.push((jump, r.loads[1].force, beta));
    }
    out
}

#[test]
fn mode_one_follows_the_law_and_dissipates_w_times_length() {
    let z = tested(0.0);
    let (steps, dt) = (4000, 2.5e-4);
    let opening = 1.3 * z.dc();
    let v = opening / (steps as f64 * dt);
    let mut m = specimen(
        0.0,
        TimeFunction::Constant(v),
        TimeFunction::Constant(0.0),
        dt,
    );
    let history = run(&mut m, steps);
    let mut peak: f64 = 0.0;
    for (jump, force, beta) in &history {
        // Traction on the interface (Pa, positive in tension) against the law with the
        // intensity frozen over the step.
        let traction = force[0] / 1.0;
        let law = beta * C * jump[0];
        assert!(
            (traction - law).abs() < 2e-3 * STRENGTH,
            "x {} traction {traction} law {law}",
            jump[0]
        );
        peak = peak.max(traction);
    }
    assert!((peak - STRENGTH).abs() < 5e-3 * STRENGTH, "peak {peak}");
    let k = tested_interface(&m);
    assert!(m.interfaces[k].points.iter().all(|p| p.intensity == 0.0));
    let dissipated = m.energy.cohesive_dissipated;
    assert!(
        (dissipated - W).abs() < 1e-3 * W,
        "dissipated {dissipated} J, expected {W} J"
    );
}

#[test]
fn mode_two_follows_the_law_and_dissipates_w_times_length() {
    let z = tested(0.0);
    let (steps, dt) = (4000, 2.5e-4);
    let v = 1.3 * z.dc() / (steps as f64 * dt);
    let mut m = specimen(
        0.0,
        TimeFunction::Constant(0.0),
        TimeFunction::Constant(v),
        dt,
    );
    let history = run(&mut m, steps);
    for (jump, force, beta) in &history {
        let law = beta * C * jump[1];
        // The interface's tangent is (0, 1) in the frame of the left element: the traction
        // on the right square is -force_y per unit length.
        assert!(
            (force[1].abs() - law.abs()).abs() < 2e-3 * STRENGTH,
            "{jump:?} {force:?} {law}"
        );
    }
    let dissipated = m.energy.cohesive_dissipated;
    assert!(
        (dissipated - W).abs() < 1e-3 * W,
        "dissipated {dissipated} J, expected {W} J"
    );
}

#[test]
fn unloading_follows_the_damaged_secant() {
    let z = tested(0.0);
    let dt = 2.5e-4;
    let x1 = 0.5 * (z.d0() + z.dc());
    let t1 = 1000.0 * dt;
    let v = x1 / t1;
    // Open to x1, close back to x1 / 2, reopen to x1.
    let vx = TimeFunction::Table(vec![
        (0.0, v),
        (t1, v),
        (t1 + 1e-9, -v),
        (1.5 * t1, -v),
        (1.5 * t1 + 1e-9, v),
    ]);
    let mut m = specimen(0.0, vx, TimeFunction::Constant(0.0), dt);
    let history = run(&mut m, 2000);
    let beta1 = history[1005].2;
    assert!(beta1 > 0.0 && beta1 < 1.0, "beta at x1 {beta1}");
    for (jump, force, beta) in &history[1005..1990] {
        assert_eq!(*beta, beta1, "no damage while below the largest jump");
        let secant = beta1 * C * jump[0];
        assert!(
            (force[0] - secant).abs() < 2e-3 * STRENGTH,
            "{jump:?} {force:?} {secant}"
        );
    }
}

#[test]
fn a_broken_interface_is_a_frictional_contact() {
    let mu = 0.4;
    let z = tested(mu);
    let dt = 2.5e-4;
    // Open beyond dc in 1000 steps, close back by 1.01 times as much (the far edge then presses
    // on the near one through the broken interface), then slide along y.
    let t1 = 1000.0 * dt;
    let v = 1.2 * z.dc() / t1;
    let vx = TimeFunction::Table(vec![
        (0.0, v),
        (t1, v),
        (t1 + 1e-9, -v),
        (2.01 * t1, -v),
        (2.01 * t1 + 1e-9, 0.0),
    ]);
    let vy = TimeFunction::Table(vec![(0.0, 0.0), (2.1 * t1, 0.0), (2.1 * t1 + 1e-9, v)]);
    let mut m = specimen(mu, vx, vy, dt);
    let history = run(&mut m, 3000);
    let k = tested_interface(&m);
    assert!(m.interfaces[k].points.iter().all(|p| p.intensity == 0.0));
    for (jump, force, _) in &history[2020..] {
        assert!(jump[0] > -1e-3 * z.dc(), "interpenetration {jump:?}");
        assert!(force[0] < 0.0, "the far edge must push: {force:?}");
    }
    for (jump, force, _) in &history[2400..] {
        let ratio = force[1].abs() / force[0].abs();
        assert!(
            (ratio - mu).abs() < 1e-6,
            "sliding: |F_T| / |F_N| = {ratio}, {jump:?}"
        );
    }
}
