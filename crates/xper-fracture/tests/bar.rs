//! Dynamic tests on bars of exploded elements (m, s, Pa, J):
//! - a bar pulled apart slowly breaks when the traction reaches the strength `R_max`, and the
//!   energy budget (kinetic + elastic + cohesive stored + dissipated = work of the loads)
//!   balances over the run;
//! - a longitudinal wave runs through an exploded bar at `sqrt(E_eff / rho)`, where the
//!   interfaces add their compliance to the bulk's: for the grid's squares of side d split by
//!   one diagonal and `C_N = C_T = C`, the average-strain theorem (uniform stress sigma,
//!   jumps `sigma n / C`) gives `1 / E_eff = 1 / E + (1 + 1 / sqrt 2) / (C d)` in tension
//!   (in compression the contact part keeps the normal jumps at zero).

mod common;

use common::*;
use xper_bodies::TimeFunction;
use xper_fracture::{FractureModel, FractureStepper, InterfaceLaw};

#[test]
fn a_bar_pulled_apart_breaks_at_the_strength_and_balances_its_energy() {
    let (strength, height) = (1e6, 0.2);
    let mesh = grid(10, 2, 0.1, 0.1, |_| 0);
    let law = InterfaceLaw::Cohesive(zone(1e12, 10.0, strength, 0.0));
    let mut spec = spec(
        vec![elastic(1e10, 0.2, 1000.0)],
        everywhere(1, law),
        1e-5,
        0.5,
    );
    spec.nlgs.tolerance = 1e-8;
    // Velocities ramped over 1 ms to 0.01 m/s at both ends, in opposite directions.
    let ramp = |v: f64| TimeFunction::Table(vec![(0.0, 0.0), (1e-3, v)]);
    spec.loads = vec![
        load(
            &mesh,
            "left",
            [
                xper_bodies::Drive::Velocity(ramp(-0.01)),
                xper_bodies::Drive::Free,
            ],
        ),
        load(
            &mesh,
            "right",
            [
                xper_bodies::Drive::Velocity(ramp(0.01)),
                xper_bodies::Drive::Free,
            ],
        ),
    ];
    let mut model = FractureModel::new(mesh, spec).unwrap();
    let mut stepper = FractureStepper::new();
    let (mut peak, mut max_work): (f64, f64) = (0.0, 0.0);
    let mut after_break = Vec::new();
    let mut worst_error: f64 = 0.0;
    for _ in 0..1500 {
        let r = stepper.step(&mut model).unwrap();
        assert!(r.converged, "step {}", r.step);
        peak = peak.max(r.loads[1].force[0]);
        if r.step > 1000 {
            after_break.push(r.loads[1].force[0]);
        }
        max_work = max_work.max(model.energy.external_work.abs());
        worst_error = worst_error.max(model.energy.error().abs());
    }
    let expected = strength * height;
    assert!(
        (peak - expected).abs() < 0.03 * expected,
        "peak force {peak} N, strength x section {expected} N"
    );
    assert!(
        model.broken_points() >= 6,
        "{} broken points",
        model.broken_points()
    );
    // After the break each half vibrates freely: the force on the pulled end averages to 0.
    let mean_after = after_break.iter().sum::<f64>() / after_break.len() as f64;
    assert!(
        mean_after.abs() < 0.03 * expected,
        "mean force after the break {mean_after} N"
    );
    assert!(
        model.energy.cohesive_dissipated >= 10.0 * height,
        "dissipated {} J, at least w x section = {} J",
        model.energy.cohesive_dissipated,
        10.0 * height
    );
    let e = &model.energy;
    assert!(e.cohesive_dissipated > 0.0 && e.external_work > 0.0);
    assert!(
        worst_error < 1e-4 * max_work,
        "energy error {worst_error} J against a work of {max_work} J ({e:?})"
    );
}

#[test]
fn waves_run_at_the_speed_of_the_bulk_plus_interface_compliance() {
    let (young, rho, d) = (1e10, 1000.0, 0.01);
    let c = 1.7e12;
    let e_eff = 1.0 / (1.0 / young + (1.0 + 0.5f64.sqrt()) / (c * d));
    let speed = (e_eff / rho).sqrt();
    let mesh = grid(200, 1, d, d, |_| 0);
    let law = InterfaceLaw::Cohesive(zone(c, 1e20, 1e12, 0.0));
    let dt = 0.1 * d / speed;
    let mut spec = spec(vec![elastic(young, 0.0, rho)], everywhere(1, law), dt, 0.5);
    spec.nlgs.tolerance = 1e-8;
    let v0 = 1e-3;
    // A tensile wave: in compression the contact part keeps the interfaces closed, and only
    // the tangential compliance remains.
    spec.loads = vec![load(&mesh, "left", [velocity(-v0), velocity(0.0)])];
    let probes = [0.6, 1.2];
    let nodes: Vec<Vec<u32>> = probes
        .iter()
        .map(|&x| {
            (0..mesh.nodes.len() as u32)
                .filter(|&n| (mesh.nodes[n as usize][0] - x).abs() < 1e-9)
                .collect()
        })
        .collect();
    let mut model = FractureModel::new(mesh, spec).unwrap();
    let mut stepper = FractureStepper::new();
    let mut arrival = [f64::NAN; 2];
    let steps = (1.6 / speed / dt) as usize;
    for _ in 0..steps {
        stepper.step(&mut model).unwrap();
        for (k, probe) in nodes.iter().enumerate() {
            if arrival[k].is_nan() && -mean_vx(&model, probe) > 0.5 * v0 {
                arrival[k] = model.time;
            }
        }
    }
    let measured = (probes[1] - probes[0]) / (arrival[1] - arrival[0]);
    let bulk = (young / rho).sqrt();
    assert!(
        (measured - speed).abs() < 0.02 * speed,
        "front speed {measured} m/s, expected {speed} m/s (bulk alone {bulk} m/s)"
    );
}

/// Mean x velocity of the copies of `nodes`.
fn mean_vx(m: &FractureModel, nodes: &[u32]) -> f64 {
    let (mut sum, mut count) = (0.0, 0);
    for el in &m.elements {
        for (j, n) in el.mesh_nodes.iter().enumerate() {
            if nodes.contains(n) {
                sum += el.velocity[2 * j];
                count += 1;
            }
        }
    }
    sum / count as f64
}
