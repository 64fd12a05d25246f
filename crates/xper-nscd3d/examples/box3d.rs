//! `box3d10k` of ../shared/bench/box3d10k.md built directly on the 3D engine, stepped, and its
//! figures printed: a provisional measurement until the scene runs through `xper bench`.
//!
//! ```text
//! cargo run --release -p xper-nscd3d --example box3d -- [10k|100k] [steps]
//! ```
//!
//! Spheres on a lattice of `nx x nx x nz` (pitch 4.1 mm, odd layers shifted by half a pitch),
//! radii `1e-3 (1 + u)` m from SplitMix64 seed 12345, density 2600 kg/m^3, in a box of
//! half-spaces (x, y in [0, (nx + 1/2) p], z in [0, H]); mu = 0.3 between spheres, 0.5 with
//! the walls, e = 0, alert distance 2e-4 m, h = 2e-4 s, theta = 1/2, NLGS to 1.666e-4 in the
//! quadratic norm checked every 10 sweeps, at most 1000.

use std::time::Instant;
use xper_bodies::{Body, BodySet};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, SplitMix64, Vector};
use xper_nscd3d::{Detection, MoreauJean, StepParams, VelocitySolver, World};
use xper_solver::NlgsParams;

fn scene(nx: usize, nz: usize, height: Real) -> World {
    let p = 4.1e-3;
    let width = (nx as Real + 0.5) * p;
    let mut set = BodySet::new();
    let mut rng = SplitMix64::new(12345);
    for k in 0..nz {
        let shift = if k % 2 == 1 { p / 2.0 } else { 0.0 };
        for j in 0..nx {
            for i in 0..nx {
                let r = 1e-3 * (1.0 + rng.next_f64());
                let centre = Vector::new(
                    p / 2.0 + i as Real * p + shift,
                    p / 2.0 + j as Real * p + shift,
                    p / 2.0 + k as Real * p,
                );
                set.insert(Body::sphere(r, 2600.0, centre));
            }
        }
    }
    let wall = |centre: Vector, normal: Vector| {
        Body::plane(centre, normal, [Real::INFINITY; 2]).in_group(1)
    };
    set.insert(wall(Vector::zeros(), Vector::z()));
    set.insert(wall(Vector::new(0.0, 0.0, height), -Vector::z()));
    set.insert(wall(Vector::zeros(), Vector::x()));
    set.insert(wall(Vector::new(width, 0.0, 0.0), -Vector::x()));
    set.insert(wall(Vector::zeros(), Vector::y()));
    set.insert(wall(Vector::new(0.0, width, 0.0), -Vector::y()));
    let mut laws = LawTable::new(2);
    for (a, b, friction) in [(0, 0, 0.3), (0, 1, 0.5)] {
        let law = SignoriniCoulomb {
            friction,
            restitution: 0.0,
        };
        laws.set(a, b, InteractionLaw::SignoriniCoulomb(law));
    }
    let params = StepParams {
        dt: 2e-4,
        theta: 0.5,
        gravity: Vector::new(0.0, 0.0, -9.81),
        alert_distance: 2e-4,
        detection: Detection::Begin,
        nlgs: NlgsParams::default(),
        solver: VelocitySolver::Nlgs,
        projection_tolerance: None,
    };
    World::new(set, laws, params)
}

fn median(mut v: Vec<Real>) -> Real {
    v.sort_by(Real::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (nx, nz, height) = match args.get(1).map(String::as_str) {
        Some("100k") => (40, 63, 0.3),
        _ => (20, 25, 0.12),
    };
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1500);
    let built = Instant::now();
    let mut world = scene(nx, nz, height);
    let n = nx * nx * nz;
    eprintln!(
        "{n} spheres built in {:.2} s",
        built.elapsed().as_secs_f64()
    );
    let mut stepper = MoreauJean::new();
    let (mut wall, mut sweeps, mut contacts, mut update, mut detect) =
        (vec![], vec![], vec![], vec![], vec![]);
    let mut capped = 0;
    let start = Instant::now();
    for _ in 0..steps {
        let report = stepper.step(&mut world).expect("step");
        wall.push(report.times.total);
        sweeps.push(report.iterations as Real);
        contacts.push(report.contacts as Real);
        detect.push(report.times.detect);
        let updates = report.active as Real * report.iterations as Real;
        if updates > 0.0 {
            update.push(report.times.solve / updates * 1e9);
        }
        capped += usize::from(!report.converged);
        if report.step.is_multiple_of(50) {
            eprintln!(
                "step {}: {} contacts, {} sweeps, {:.1} ms",
                report.step,
                report.contacts,
                report.iterations,
                report.times.total * 1e3
            );
        }
    }
    let elapsed = start.elapsed().as_secs_f64();
    let mut overlaps: Vec<Real> = world.contacts.gaps.iter().map(|g| (-g).max(0.0)).collect();
    overlaps.sort_by(Real::total_cmp);
    let pick = |q: Real| overlaps[((overlaps.len() - 1) as Real * q) as usize];
    let last = wall.len().saturating_sub(200);
    let memory = xper_io::peak_memory_bytes().unwrap_or(0) as Real;
    println!(
        "{{\"spheres\": {n}, \"steps\": {steps}, \"wall_s\": {elapsed:.2}, \
         \"step_ms_median\": {:.3}, \"step_ms_median_last200\": {:.3}, \
         \"sweeps_median\": {}, \"capped_steps\": {capped}, \"contacts_median\": {}, \
         \"ns_per_contact_update_median\": {:.1}, \"detect_ms_median\": {:.3}, \
         \"detect_ns_per_body\": {:.0}, \"peak_bytes_per_sphere\": {:.0}, \
         \"overlap_um\": [{:.4}, {:.4}, {:.4}]}}",
        median(wall.clone()) * 1e3,
        median(wall[last..].to_vec()) * 1e3,
        median(sweeps),
        median(contacts),
        median(update),
        median(detect.clone()) * 1e3,
        median(detect) / n as Real * 1e9,
        memory / n as Real,
        pick(0.5) * 1e6,
        pick(0.99) * 1e6,
        pick(1.0) * 1e6,
    );
}
