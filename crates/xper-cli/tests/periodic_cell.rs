//! A periodic cell through `xper run` on `scenes/simple_shear`: a run stopped and resumed
//! ends in exactly the state of an uninterrupted one (the cell, its wraps and its shear are
//! in the checkpoint), the cell holds its pressure in `micro.csv`, and `xper post` measures the
//! checkpoint over the cell as the run's last frame does.

mod common;
use common::{
    assert_post_matches_last_row, assert_success, run_scene, shipped_scene, temp_dir, xper,
};
use xper_io::SeriesTable;

#[test]
fn a_sheared_cell_resumes_exactly_holds_its_pressure_and_post_agrees() {
    let dir = temp_dir("periodic_cell");
    let scene = shipped_scene("simple_shear", 2400, [200, 300], &dir);
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    assert_success(&run_scene(&scene, &straight, &["--quiet"]));
    assert_success(&run_scene(
        &scene,
        &split,
        &["--quiet", "--stop-at-step", "1000"],
    ));
    assert_success(&run_scene(&scene, &split, &["--quiet", "--resume"]));
    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "the resumed run ends in another state");

    // From a shear strain of 0.2 on (the loose packing has compacted), sigma_yy within 5 %
    // of the imposed 10 kPa at every frame, and the cell's height what the pressure made it.
    let micro = SeriesTable::read_csv(&straight.join("micro.csv")).unwrap();
    let col = |name: &str| micro.column(name).unwrap();
    let (time, syy, height) = (col("time"), col("stress_yy"), col("extent_y"));
    let settled: Vec<usize> = (0..time.len()).filter(|&k| time[k] >= 0.2).collect();
    assert!(settled.len() >= 3, "{time:?}");
    for &k in &settled {
        assert!(
            (syy[k] - 1e4).abs() < 0.05 * 1e4,
            "sigma_yy {} Pa at {} s",
            syy[k],
            time[k]
        );
        assert!(height[k] < 0.03, "height {} m at {} s", height[k], time[k]);
    }
    assert_eq!(col("extent_x").last(), Some(&0.06));

    let post = xper(&["post", straight.to_str().unwrap(), "--volume", "cell"]);
    assert_success(&post);
    assert_post_matches_last_row(&straight.join("post"), &micro);
}
