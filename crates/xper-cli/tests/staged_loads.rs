//! Loading in stages (`scenes/nooru_mohamed_staged`): shear until 2e-4 s with top and bottom
//! held, then tension with the shear edges held. Each stage is a velocity table, so the
//! imposed displacements are known exactly: with theta = 1/2 a node starting at rest under a
//! velocity v switched on over one step moves by `v (t - t_switch - h / 2)`.

mod common;
use common::{assert_success, temp_dir, xper};
use std::path::Path;
use xper_io::SeriesTable;

const H: f64 = 4e-7;
const SWITCH: f64 = 2e-4;

#[test]
fn shear_then_tension_follows_the_stages_and_cracks_in_tension() {
    let scene =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/nooru_mohamed_staged/scene.toml");
    let out = temp_dir("staged_loads");
    assert_success(&xper(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]));
    let series = SeriesTable::read_csv(&out.join("series.csv")).unwrap();
    let col = |name: &str| series.column(name).unwrap();
    let (time, top_uy, shear_ux) = (col("time"), col("top_uy"), col("left_upper_ux"));
    let (top_fy, shear_fx, broken) = (
        col("top_fy"),
        col("left_upper_fx"),
        col("broken_interfaces"),
    );
    let stage_one = time.iter().filter(|&&t| t <= SWITCH * (1.0 + 1e-9)).count();
    assert_eq!(stage_one, 500, "500 steps of 4e-7 s in the first stage");
    for k in 0..stage_one {
        assert!(
            top_uy[k].abs() <= 1e-18,
            "step {}: top held, moved {:e} m",
            k + 1,
            top_uy[k]
        );
        let expected = 0.05 * (time[k] - H / 2.0);
        assert!(
            (shear_ux[k] - expected).abs() <= 1e-14,
            "step {}: shear edge at {:e} m, expected {expected:e} m",
            k + 1,
            shear_ux[k]
        );
    }
    let held = shear_ux[stage_one];
    assert!(
        (held - 0.05 * SWITCH).abs() <= 1e-14,
        "shear edge held at {held:e} m"
    );
    for k in stage_one + 1..time.len() {
        assert_eq!(shear_ux[k], held, "step {}: shear edge held", k + 1);
        let expected = 0.1 * (time[k] - SWITCH - H / 2.0);
        assert!(
            (top_uy[k] - expected).abs() <= 1e-14,
            "step {}: top at {:e} m, expected {expected:e} m",
            k + 1,
            top_uy[k]
        );
    }
    // The specimen carries shear in the first stage without cracking, then tension until it
    // cracks and softens.
    assert!(
        shear_fx[stage_one - 1] > 1e4,
        "shear force {:e} N",
        shear_fx[stage_one - 1]
    );
    assert_eq!(broken[stage_one - 1], 0.0, "no crack under shear alone");
    let peak = top_fy[stage_one..].iter().copied().fold(0.0, f64::max);
    assert!(peak > 1e4, "tension peak {peak:e} N");
    assert!(*broken.last().unwrap() > 0.0, "a crack in tension");
    assert!(
        *top_fy.last().unwrap() < 0.25 * peak,
        "softened after the peak"
    );
}
