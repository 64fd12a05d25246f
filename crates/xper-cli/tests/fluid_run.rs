//! A scene with `[fluid]` through the command: its outputs, `--resume` ending bit-identical to
//! an uninterrupted run, and a bad `[fluid]` section reported with its place and exit code 2.

mod common;
use common::{assert_success, grain_in_box, temp_dir, xper};

fn scene(duration: f64, viscosity: &str) -> String {
    grain_in_box(
        &format!("dt = 1e-3\nduration = {duration}"),
        "[output]\nframe_every = 20\ncheckpoint_every = 25\n\n",
        &format!(
            "viscosity = {viscosity}\ndomain = [[0.0, 0.0], [0.016, 0.016]]\ncells_per_diameter = 8"
        ),
    )
}

#[test]
fn fluid_scene_writes_its_outputs_and_resumes_exactly() {
    writes_its_outputs_and_resumes_exactly("fluid_run", "1e-2");
}

/// The Runge-Kutta scheme keeps no state between steps beyond the fluid's: a resumed run ends
/// as the uninterrupted one.
#[test]
fn rk3_fluid_scene_resumes_exactly() {
    writes_its_outputs_and_resumes_exactly("fluid_run_rk3", "1e-2\ntime_scheme = \"rk3\"");
}

/// The fraction forcing (the marker forcing is the default) keeps no state between steps either.
#[test]
fn fraction_forcing_scene_resumes_exactly() {
    writes_its_outputs_and_resumes_exactly("fluid_run_fraction", "1e-2\nforcing = \"fraction\"");
}

fn writes_its_outputs_and_resumes_exactly(name: &str, viscosity: &str) {
    let dir = temp_dir(name);
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene(0.05, viscosity)).unwrap();
    let s = path.to_str().unwrap();
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    let out = xper(&["run", s, "--out", straight.to_str().unwrap()]);
    assert_success(&out);
    for file in [
        "result.pvd",
        "series.csv",
        "particles.csv",
        "series.png",
        "particles.png",
        "summary.json",
    ] {
        assert!(straight.join(file).exists(), "{file} missing");
    }
    let vti = std::fs::read_to_string(straight.join("frames/fluid_00000000.vti")).unwrap();
    assert!(
        vti.contains("WholeExtent=\"0 64 0 64 0 0\"") && vti.contains("Name=\"vorticity\""),
        "{vti}"
    );
    let particles = xper_io::SeriesTable::read_csv(&straight.join("particles.csv")).unwrap();
    let vy = particles.column("vy").unwrap();
    assert!(
        vy.last().copied().unwrap() < -1e-3,
        "the grain does not settle: {vy:?}"
    );

    let out = xper(&[
        "run",
        s,
        "--out",
        split.to_str().unwrap(),
        "--stop-at-step",
        "60",
    ]);
    assert_success(&out);
    let out = xper(&["run", s, "--out", split.to_str().unwrap(), "--resume"]);
    assert_success(&out);
    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "final states differ after a resume");
    let pa = std::fs::read_to_string(straight.join("particles.csv")).unwrap();
    let pb = std::fs::read_to_string(split.join("particles.csv")).unwrap();
    assert_eq!(pa, pb);
}

#[test]
fn bad_fluid_section_is_reported_with_its_place() {
    let dir = temp_dir("fluid_bad");
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene(0.05, "-1.0")).unwrap();
    let out = xper(&["check", path.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("scene.toml:34:13:") && err.contains("fluid.viscosity") && err.contains("> 0"),
        "{err}"
    );
}

#[test]
fn unknown_time_scheme_is_reported_with_the_choices() {
    let dir = temp_dir("fluid_bad_scheme");
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene(0.05, "1e-3\ntime_scheme = \"rk4\"")).unwrap();
    let out = xper(&["check", path.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("scene.toml:35:15:")
            && err.contains("fluid.time_scheme")
            && err.contains("euler")
            && err.contains("rk3"),
        "{err}"
    );
}

#[test]
fn lubrication_roughness_without_a_range_is_refused() {
    let dir = temp_dir("fluid_bad_lubrication");
    let path = dir.join("scene.toml");
    for (fluid, field, reason) in [
        (
            "1e-3\nlubrication_roughness = 0.01",
            "fluid.lubrication_roughness",
            "without `lubrication_range`",
        ),
        (
            "1e-3\nlubrication_range = -1.0",
            "fluid.lubrication_range",
            "in (0, 100] cells",
        ),
    ] {
        std::fs::write(&path, scene(0.05, fluid)).unwrap();
        let out = xper(&["check", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains("scene.toml:35:") && err.contains(field) && err.contains(reason),
            "{err}"
        );
    }
}

#[test]
fn marker_settings_are_checked() {
    let dir = temp_dir("fluid_bad_forcing");
    let path = dir.join("scene.toml");
    for (fluid, field, reason) in [
        (
            "1e-3\nforcing = \"fraction\"\nforcing_iterations = 3",
            "fluid.forcing_iterations",
            "with `forcing = \"fraction\"`: it tunes only the marker forcing",
        ),
        (
            "1e-3\nmarker_retraction = 0.7",
            "fluid.marker_retraction",
            "in [0, 0.5] cells",
        ),
        ("1e-3\nforcing = \"delta\"", "fluid.forcing", "markers"),
    ] {
        std::fs::write(&path, scene(0.05, fluid)).unwrap();
        let out = xper(&["check", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains("scene.toml:3") && err.contains(field) && err.contains(reason),
            "{err}"
        );
    }
}
