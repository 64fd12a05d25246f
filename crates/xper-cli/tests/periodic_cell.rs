//! A periodic cell through `xper run` on `scenes/simple_shear` and `scenes/simple_shear_3d`: a
//! run stopped and resumed ends in exactly the state of an uninterrupted one (the cell, its
//! wraps and its shear are in the checkpoint), the cell holds its pressure in `micro.csv`, and
//! `xper post` measures the checkpoint over the cell as the run's last frame does; and
//! `scenes/triaxial_3d`'s event switches the cell's z side from stress to an imposed rate.

mod common;
use common::{
    assert_post_matches_last_row, assert_success, run_scene, shipped_scene, temp_dir, xper,
};
use std::path::{Path, PathBuf};
use xper_io::SeriesTable;

#[test]
fn a_sheared_cell_resumes_exactly_holds_its_pressure_and_post_agrees() {
    sheared_cell("simple_shear", 2400, 0.2, "yy", 0.03, 0.4);
}

/// Frictionless: with friction the jammed 3D packing ends steps at the sweep cap, and the
/// pressure of a step scatters by about 10 % (scenes/simple_shear_3d/README.md).
#[test]
fn a_sheared_3d_cell_resumes_exactly_holds_its_pressure_and_post_agrees() {
    sheared_cell("simple_shear_3d", 1200, 0.05, "zz", 0.014, 0.0);
}

/// `scene` (whose cell has the side 0.06 m (2D) or 0.012 m (3D) along x, shears x over its
/// last axis `axis` and holds 10 kPa along it) cut to `steps`, with the grains' `friction`:
/// resumed exactly, the pressure held within 5 % from `settled` s on with the height below
/// `height` m, `xper post` as the last row.
fn sheared_cell(scene: &str, steps: u64, settled: f64, axis: &str, height: f64, friction: f64) {
    let dir = temp_dir(scene);
    let scene = shipped_scene(scene, steps, [steps / 12, steps / 8], &dir);
    let text = std::fs::read_to_string(&scene).unwrap();
    let mut doc: toml::Table = text.parse().unwrap();
    doc["laws"][0]["friction"] = toml::Value::Float(friction);
    std::fs::write(&scene, toml::to_string(&doc).unwrap()).unwrap();
    let straight = runs_resume_exactly(&scene, &dir, steps * 5 / 12);

    // Once the loose packing has compacted, sigma along `axis` within 5 % of the imposed
    // 10 kPa at every frame, and the cell's height what the pressure made it.
    let micro = SeriesTable::read_csv(&straight.join("micro.csv")).unwrap();
    let col = |name: &str| micro.column(name).unwrap();
    let (time, sigma) = (col("time"), col(&format!("stress_{axis}")));
    let h = col(&format!("extent_{}", &axis[..1]));
    let held: Vec<usize> = (0..time.len()).filter(|&k| time[k] >= settled).collect();
    assert!(held.len() >= 3, "{time:?}");
    for &k in &held {
        let (s, t) = (sigma[k], time[k]);
        assert!((s - 1e4).abs() < 0.05 * 1e4, "sigma_{axis} {s} Pa at {t} s");
        assert!(h[k] < height, "height {} m at {t} s", h[k]);
    }
    let width = if axis == "zz" { 0.012 } else { 0.06 };
    assert_eq!(col("extent_x").last(), Some(&width));

    let post = xper(&["post", straight.to_str().unwrap(), "--volume", "cell"]);
    assert_success(&post);
    assert_post_matches_last_row(&straight.join("post"), &micro);
}

/// `scenes/triaxial_3d` on 200 spheres in a 30 mm cell (the side stays above four diameters),
/// its event at 0.25 s, 300 steps of compression (3 % axial strain): the three stresses hold
/// 10 kPa before the event; after it the cell's z side shrinks by exactly `1 - h` per step
/// (the imposed 1 /s), x and y keep their stress on average and the deviator rises; a run
/// stopped before the event and resumed ends in the uninterrupted run's state.
#[test]
fn a_triaxial_cell_switches_its_axis_from_stress_to_rate_at_the_event() {
    let dir = temp_dir("triaxial_3d");
    let steps = 2800;
    let scene = shipped_scene("triaxial_3d", steps, [50, 1000], &dir);
    let mut doc: toml::Table = std::fs::read_to_string(&scene).unwrap().parse().unwrap();
    let generator = doc["generators"][0].as_table_mut().unwrap();
    generator.insert("count".into(), toml::Value::Integer(200));
    let cube = |a: f64| toml::Value::try_from([[0.0; 3], [a; 3]]).unwrap();
    generator.insert("box".into(), cube(0.03));
    let cell = doc["cell"].as_table_mut().unwrap();
    cell.insert("size".into(), toml::Value::try_from([0.03; 3]).unwrap());
    cell.insert("mass".into(), toml::Value::Float(0.004));
    doc["events"][0]["time"] = toml::Value::Float(0.25);
    std::fs::write(&scene, toml::to_string(&doc).unwrap()).unwrap();
    let straight = runs_resume_exactly(&scene, &dir, 2000);

    let micro = SeriesTable::read_csv(&straight.join("micro.csv")).unwrap();
    let col = |name: &str| micro.column(name).unwrap();
    let (step, time, ratio) = (col("step"), col("time"), col("stress_ratio"));
    let stress = |k: usize, r: usize| col(&format!("stress_{}{}", AXES[k], AXES[k]))[r];
    let rows = |from: f64, to: f64| -> Vec<usize> {
        (0..time.len())
            .filter(|&r| time[r] > from && time[r] <= to)
            .collect()
    };
    // Measured: within 0.23 % before the event; lateral means within 0.5 % after it; q/p
    // 1.06 and sigma_zz 25.9 kPa at the end.
    for r in rows(0.21, 0.25) {
        for k in 0..3 {
            let s = stress(k, r);
            assert!(
                (s - 1e4).abs() < 0.02e4,
                "sigma_{k}{k} {s} Pa at {} s",
                time[r]
            );
        }
    }
    // The event applies at the beginning of step 2501 (whose rate is the theta-mean of the
    // rate the cell had under stress and the new -1 /s); from step 2502 on, H_zz is
    // multiplied by 1 - h = 0.9999 at every step.
    let z = col("extent_z");
    let at_event = (0..time.len()).find(|&r| step[r] == 2500.0).unwrap();
    let after = rows(0.2505, 1.0);
    assert!(after.len() >= 5, "{time:?}");
    for pair in after.windows(2) {
        let n = (step[pair[1]] - step[pair[0]]) as i32;
        let expected = z[pair[0]] * 0.9999f64.powi(n);
        let (got, at) = (z[pair[1]], step[pair[1]]);
        assert!(
            (got / expected - 1.0).abs() < 1e-12,
            "H_zz {got} m at step {at}, expected {expected}"
        );
    }
    let last = *after.last().unwrap();
    let strain = 1.0 - z[last] / z[at_event];
    assert!((strain - 0.03).abs() < 0.001, "axial strain {strain}");
    // Lateral stresses: within 5 % of 10 kPa on average over the compression (a 200-sphere
    // sample's stresses scatter from frame to frame); the deviator has risen.
    let compressed = rows(0.255, 1.0);
    for k in 0..2 {
        let mean = compressed.iter().map(|&r| stress(k, r)).sum::<f64>() / compressed.len() as f64;
        assert!((mean - 1e4).abs() < 0.05e4, "mean sigma_{k}{k} {mean} Pa");
    }
    assert!(ratio[last] > 0.5, "q/p {} at the end", ratio[last]);
    assert!(
        stress(2, last) > 1.5e4,
        "sigma_zz {} Pa at the end",
        stress(2, last)
    );
}

const AXES: [&str; 3] = ["x", "y", "z"];

/// Runs `scene` into `dir/straight`, and into `dir/split` stopped at step `stop` and resumed:
/// both must end in the same checkpoint, byte for byte. Returns the straight run's folder.
fn runs_resume_exactly(scene: &Path, dir: &Path, stop: u64) -> PathBuf {
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    assert_success(&run_scene(scene, &straight, &["--quiet"]));
    let stop = stop.to_string();
    assert_success(&run_scene(
        scene,
        &split,
        &["--quiet", "--stop-at-step", &stop],
    ));
    assert_success(&run_scene(scene, &split, &["--quiet", "--resume"]));
    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "the resumed run ends in another state");
    straight
}
