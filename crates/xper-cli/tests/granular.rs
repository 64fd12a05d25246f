//! The granular laboratory on `scenes/isotropic_compaction`: servo walls hold their pressure,
//! and the granular stress of the packing equals the wall forces over the wall lengths (two
//! independent measures of the same stress); `micro.csv` and `xper post` agree.

mod common;
use common::*;
use std::path::Path;
use xper_math::Real;
use xper_nscd::micro::{contact_force, measure, VolumeSource};
use xper_nscd::MoreauJean;
use xper_simulation::rigid::build::world_from_scene;

const SCENE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenes/isotropic_compaction"
);

/// Walls in the scene's order.
const BOTTOM: usize = 0;
const RIGHT: usize = 1;
const TOP: usize = 2;
const LEFT: usize = 3;
const PRESSURE: Real = 1e3;

fn relative(a: Real, b: Real) -> Real {
    (a - b).abs() / b.abs()
}

/// The shipped scene with friction 0.3 between grains: a frictional packing jams and comes
/// to rest (the frictionless one keeps rearranging, its stress fluctuating by a few percent).
fn frictional_scene() -> String {
    let text = std::fs::read_to_string(Path::new(SCENE).join("scene.toml")).unwrap();
    let frictionless = "friction = 0.0          # frictionless preparation";
    assert!(text.contains(frictionless));
    text.replace(frictionless, "friction = 0.3 #")
}

#[test]
fn servo_walls_hold_their_pressure_and_the_granular_stress_is_the_wall_stress() {
    let scene = xper_scene::parse_scene(&frictional_scene(), Path::new("scene.toml")).unwrap();
    let mut world = world_from_scene(&scene);
    let mut stepper = MoreauJean::new();
    for _ in 0..scene.steps {
        stepper.step(&mut world).unwrap();
    }
    let x = |b: usize| world.bodies.position[b];
    let (width, height) = (x(RIGHT).x - x(LEFT).x, x(TOP).y - x(BOTTOM).y);
    let f = |b| contact_force(&world, b);
    let m = measure(&world, VolumeSource::Walls).unwrap();
    // The stress each wall bears: the contacts push the top and right walls outwards (+y,
    // +x), the bottom and left ones outwards too (-y, -x).
    let walls = [
        f(TOP).y / width,
        f(RIGHT).x / height,
        -f(BOTTOM).y / width,
        -f(LEFT).x / height,
    ];
    let (sxx, syy) = (m.stress[(0, 0)], m.stress[(1, 1)]);
    eprintln!(
        "wall stresses (top, right, bottom, left) {walls:?} Pa; sigma_xx {sxx}, sigma_yy {syy} Pa"
    );
    // The servo walls hold their pressure within 1 % once the sample is at rest (after 0.3 s
    // the kinetic energy is ~1e-9 of the work done by the walls).
    assert!(relative(walls[0], PRESSURE) < 0.01, "{walls:?}");
    assert!(relative(walls[1], PRESSURE) < 0.01, "{walls:?}");
    // The granular stress from every contact's branch vector equals the fixed walls' forces
    // over their lengths: 1e-3 covers the solver's relative tolerance (1e-4) and the residual
    // inertia (here they agree to 2e-5).
    assert!(relative(syy, walls[2]) < 1e-3, "{syy} {walls:?}");
    assert!(relative(sxx, walls[3]) < 1e-3, "{sxx} {walls:?}");
    // Shear stresses: symmetric (moment balance of the grains).
    assert!((m.stress[(0, 1)] - m.stress[(1, 0)]).abs() < 1e-6 * sxx);
}

#[test]
fn micro_csv_rows_are_the_measures_of_the_frames_and_post_agrees() {
    let dir = temp_dir("granular_micro");
    let text = std::fs::read_to_string(Path::new(SCENE).join("scene.toml")).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, text.replace("steps = 6000 ", "steps = 300 ")).unwrap();
    let out = dir.join("out");
    assert_success(&run_scene(&path, &out, &["--quiet"]));
    let table = xper_io::SeriesTable::read_csv(&out.join("micro.csv")).unwrap();
    // A row per frame: steps 0, 100, 200, 300.
    assert_eq!(
        table.column("step").unwrap(),
        vec![0.0, 100.0, 200.0, 300.0]
    );
    let post = xper(&["post", out.to_str().unwrap()]);
    assert_success(&post);
    assert_post_matches_last_row(&out.join("post"), &table);
    let last = table.rows.last().unwrap();
    assert!(
        last[table
            .columns
            .iter()
            .position(|c| c == "solid_fraction")
            .unwrap()]
            > 0.5
    );
    let forces = std::fs::read_to_string(out.join("post/forces.csv")).unwrap();
    // The distribution integrates to 1 over bins of 0.1.
    let total: f64 = (forces.lines().skip(1))
        .map(|l| l.split(',').nth(1).unwrap().parse::<f64>().unwrap() * 0.1)
        .sum();
    assert!((total - 1.0).abs() < 1e-9, "{total}");
    assert!(out.join("post/force_chains.vtu").exists());
}

/// The rows of `micro.csv` as maps from column to value.
fn micro_rows(out: &Path) -> Vec<std::collections::HashMap<String, f64>> {
    let table = xper_io::SeriesTable::read_csv(&out.join("micro.csv")).unwrap();
    (table.rows.iter())
        .map(|r| {
            table
                .columns
                .iter()
                .cloned()
                .zip(r.iter().copied())
                .collect()
        })
        .collect()
}

#[test]
fn biaxial_small_compacts_isotropically_then_shears_with_friction() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/biaxial_small");
    let out = temp_dir("biaxial_small").join("out");
    assert_success(&run_scene(&scene, &out, &["--quiet"]));
    let rows = micro_rows(&out);
    let at = |step: f64| rows.iter().find(|r| r["step"] == step).unwrap();
    // End of the compaction (0.3 s, the event's time): isotropic, at the servo pressure.
    let start = at(3000.0);
    assert!(
        relative(start["stress_xx"], 1e4) < 0.01,
        "{}",
        start["stress_xx"]
    );
    assert!(
        relative(start["stress_yy"], 1e4) < 0.01,
        "{}",
        start["stress_yy"]
    );
    assert!(start["stress_ratio"] < 0.05);
    // From the event on the top wall moves at exactly 0.02 m/s (from the second row on: in
    // the event's step theta-method averages the old velocity and the imposed one).
    let after: Vec<_> = rows.iter().filter(|r| r["step"] > 3000.0).collect();
    for w in after.windows(2) {
        let moved = w[0]["extent_y"] - w[1]["extent_y"];
        let expected = 0.02 * (w[1]["time"] - w[0]["time"]);
        assert!((moved - expected).abs() < 1e-12, "{moved} {expected}");
    }
    // With friction 0.5 the sample resists shear (a frictionless one flows at q/p near 0.1)
    // and dilates, as a dense frictional packing does.
    let sheared: Vec<_> = (rows.iter())
        .filter(|r| start["extent_y"] - r["extent_y"] > 0.02 * start["extent_y"])
        .collect();
    let mean_ratio = sheared.iter().map(|r| r["stress_ratio"]).sum::<f64>() / sheared.len() as f64;
    assert!(mean_ratio > 0.25, "{mean_ratio}");
    let last = rows.last().unwrap();
    let dilation = (last["volume"] - start["volume"]) / start["volume"];
    assert!(dilation > 0.01, "{dilation}");
    // The confining wall: the granular stress across it stays at 10 kPa on average (within
    // 5 %: 400 grains sheared at an inertial number of 4e-4 fluctuate by about 10 %).
    let sxx = sheared.iter().map(|r| r["stress_xx"]).sum::<f64>() / sheared.len() as f64;
    assert!(relative(sxx, 1e4) < 0.05, "{sxx}");
    assert!(out.join("micro.png").exists());
}

#[test]
fn measures_without_a_box_of_walls_stop_the_run_with_exit_2() {
    let dir = temp_dir("micro_no_box");
    let drop = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/drop/scene.toml");
    let text = std::fs::read_to_string(drop).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(
        &path,
        text.replace("[output]", "[output]\nmicro = \"walls\""),
    )
    .unwrap();
    let run = run_scene(&path, &dir.join("out"), &["--quiet"]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("scene.toml: [output] micro: the walls") && stderr.contains("along x"),
        "{stderr}"
    );
}
