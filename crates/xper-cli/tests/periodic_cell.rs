//! A periodic cell through `xper run` on `scenes/simple_shear` and `scenes/simple_shear_3d`: a
//! run stopped and resumed ends in exactly the state of an uninterrupted one (the cell, its
//! wraps and its shear are in the checkpoint), the cell holds its pressure in `micro.csv`, and
//! `xper post` measures the checkpoint over the cell as the run's last frame does.

mod common;
use common::{
    assert_post_matches_last_row, assert_success, run_scene, shipped_scene, temp_dir, xper,
};
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
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    assert_success(&run_scene(&scene, &straight, &["--quiet"]));
    let stop = (steps * 5 / 12).to_string();
    assert_success(&run_scene(
        &scene,
        &split,
        &["--quiet", "--stop-at-step", &stop],
    ));
    assert_success(&run_scene(&scene, &split, &["--quiet", "--resume"]));
    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "the resumed run ends in another state");

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
