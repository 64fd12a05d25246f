//! The example scenes under /scenes parse, and the box10k benchmark check values.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use xper_scene::{
    load_scene, Acceleration, CheckPass, ConvergenceNorm, Detection, Drive, ShapeDesc, SplitMix64,
    TimeFunction, VelocitySolverKind,
};

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name)
        .join("scene.toml")
}

fn radius(shape: &ShapeDesc) -> f64 {
    match shape {
        ShapeDesc::Disk { radius } => *radius,
        other => panic!("expected a disk, got {other:?}"),
    }
}

#[test]
fn splitmix_reference_values() {
    // Reference outputs of SplitMix64 for seed 0 (Vigna's reference implementation).
    let mut g = SplitMix64::new(0);
    assert_eq!(g.next_u64(), 0xE220A8397B1DCDAF);
    assert_eq!(g.next_u64(), 0x6E789E6AA1B965F4);
    let mut g = SplitMix64::new(7);
    for _ in 0..1000 {
        let u = g.next_f64();
        assert!((0.0..1.0).contains(&u));
    }
}

/// box10k_anderson is box10k (bodies, laws, step, tolerance and convergence test) with the
/// sweeps accelerated, and nothing else.
#[test]
fn box10k_anderson_is_box10k_with_acceleration() {
    let plain = load_scene(&scene_path("box10k")).unwrap_or_else(|e| panic!("{e}"));
    let fast = load_scene(&scene_path("box10k_anderson")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(plain.solver.acceleration, Acceleration::None);
    assert_eq!(
        fast.solver.acceleration,
        Acceleration::Anderson {
            depth: 3,
            period: 3
        }
    );
    let mut same = fast.clone();
    same.name = plain.name.clone();
    same.solver.acceleration = Acceleration::None;
    assert_eq!(same, plain);
}

/// The study scenes of issue 39 are box10k with one solver line changed, and nothing else.
#[test]
fn box10k_variants_differ_from_box10k_in_one_line() {
    let plain = load_scene(&scene_path("box10k")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(plain.solver.check, CheckPass::Lmgc90);
    assert!(plain.solver.position_projection);
    let strict = load_scene(&scene_path("box10k_strict_check")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(strict.solver.check, CheckPass::Strict);
    let mut same = strict.clone();
    same.name = plain.name.clone();
    same.solver.check = CheckPass::Lmgc90;
    assert_eq!(same, plain);
    let free = load_scene(&scene_path("box10k_no_projection")).unwrap_or_else(|e| panic!("{e}"));
    assert!(!free.solver.position_projection);
    let mut same = free.clone();
    same.name = plain.name.clone();
    same.solver.position_projection = true;
    assert_eq!(same, plain);
    let lmgc90 = load_scene(&scene_path("box10k_as_lmgc90")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(plain.detection, Detection::Begin);
    assert_eq!(lmgc90.detection, Detection::Predicted);
    let mut same = lmgc90.clone();
    same.name = free.name.clone();
    same.detection = Detection::Begin;
    assert_eq!(same, free);
}

#[test]
fn box10k_check_values() {
    let s = load_scene(&scene_path("box10k")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.name, "box10k");
    assert_eq!(s.bodies.len(), 10_000 + 4);
    let r0 = radius(&s.bodies[0].shape);
    let r1 = radius(&s.bodies[1].shape);
    assert_eq!(format!("{r0:.6e}"), "1.133080e-3");
    assert_eq!(format!("{r1:.6e}"), "1.204817e-3");
    let sum: f64 = s.bodies[..10_000].iter().map(|b| radius(&b.shape)).sum();
    assert_eq!(format!("{sum:.7}"), "15.0326785");
    // Lattice positions: disk k = 100 j + i.
    let p = 4.1e-3;
    let b = &s.bodies[100 * 3 + 7];
    assert_eq!(
        b.position,
        [
            p / 2.0 + 7.0 * p + p / 2.0,
            p / 2.0 + 3.0 * p * 3f64.sqrt() / 2.0
        ]
    );
    let m = 2600.0 * PI * r0 * r0;
    assert!((s.bodies[0].mass - m).abs() <= 1e-15 * m);
    assert!((s.bodies[0].inertia - m * r0 * r0 / 2.0).abs() <= 1e-15 * m * r0 * r0);
    assert_eq!(s.groups, vec!["grains".to_string(), "walls".to_string()]);
    assert_eq!(s.laws.len(), 2);
    assert_eq!((s.laws[0].groups, s.laws[0].friction), ([0, 0], 0.3));
    assert_eq!((s.laws[1].groups, s.laws[1].friction), ([0, 1], 0.5));
    assert_eq!(
        (s.dt, s.steps, s.theta, s.alert_distance),
        (2e-4, 1500, 0.5, 2e-4)
    );
    assert_eq!(s.solver.tolerance, 1.666e-4);
    assert_eq!(s.solver.norm, ConvergenceNorm::Quad);
    assert_eq!(
        (
            s.solver.max_iterations,
            s.solver.check_every,
            s.solver.relaxation
        ),
        (1000, 10, 1.0)
    );
    // The four walls: bottom, right, top, left, closing the box.
    let walls = &s.bodies[10_000..];
    let expected = [
        ([0.41205 / 2.0, 0.0], 0.0, 0.41205),
        ([0.41205, 0.18], PI / 2.0, 0.36),
        ([0.41205 / 2.0, 0.36], PI, 0.41205),
        ([0.0, 0.18], -PI / 2.0, 0.36),
    ];
    for (w, (pos, angle, len)) in walls.iter().zip(expected) {
        assert_eq!(w.group, 1);
        assert_eq!(w.mass, f64::INFINITY);
        assert!((w.position[0] - pos[0]).abs() < 1e-15 && (w.position[1] - pos[1]).abs() < 1e-15);
        assert!((w.angle - angle).abs() < 1e-12, "{} vs {angle}", w.angle);
        assert_eq!(
            w.shape,
            ShapeDesc::Segment {
                half_length: len / 2.0
            }
        );
        assert_eq!(w.drives[0], Drive::Velocity(TimeFunction::Constant(0.0)));
    }
}

#[test]
fn drop_scene() {
    let s = load_scene(&scene_path("drop")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((s.dt, s.steps), (1e-3, 1000));
    assert_eq!(s.bodies.len(), 2);
    let d = &s.bodies[0];
    assert_eq!(d.shape, ShapeDesc::Disk { radius: 0.05 });
    assert_eq!(d.position, [0.0, 0.55]);
    assert!((d.mass - 1000.0 * PI * 0.0025).abs() < 1e-12);
    assert_eq!(d.drives, [Drive::Free, Drive::Free, Drive::Free]);
    assert_eq!(s.laws[0].restitution, 0.0);
    assert_eq!(s.bodies[1].shape, ShapeDesc::Segment { half_length: 0.5 });
}

/// Also the "100x100 lattice validates quickly" run (the overlap grid): no timing assertion.
#[test]
fn box100k_scene() {
    let t = std::time::Instant::now();
    let s = load_scene(&scene_path("box100k")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.bodies.len(), 316 * 316 + 4);
    eprintln!("box100k parsed and validated in {:?}", t.elapsed());
}

#[test]
fn newton_deposit_scene() {
    let s = load_scene(&scene_path("newton_deposit")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.bodies.len(), 200 + 4);
    assert_eq!(s.solver.kind, VelocitySolverKind::Newton);
    assert_eq!((s.solver.tolerance, s.solver.max_iterations), (1e-8, 50));
    assert_eq!(s.output.dump_problems, vec![400]);
    assert!(s.laws.iter().all(|l| l.friction == 0.0));
    assert_eq!((s.dt, s.steps), (2e-4, 600));
}

#[test]
fn missing_file_is_an_error_with_line_0() {
    let e = load_scene(Path::new("/nonexistent/scene.toml")).unwrap_err();
    assert_eq!(e.0.len(), 1);
    assert_eq!((e.0[0].line, e.0[0].column), (0, 0));
}
