//! Faults of issue 38's campaign, each a regression test named after it.

mod common;
use common::{grain_in_box, run_scene as run, shipped_scene, temp_dir, xper};
use std::path::Path;

/// `scenes/drop` cut to `steps` steps with `edit` applied to its TOML document.
fn drop_scene(dir: &Path, steps: u64, edit: impl FnOnce(&mut toml::Table)) -> std::path::PathBuf {
    let path = shipped_scene("drop", steps, [10, 10], dir);
    let mut doc: toml::Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
    edit(&mut doc);
    std::fs::write(&path, toml::to_string(&doc).unwrap()).unwrap();
    path
}

#[test]
fn a_blow_up_to_infinite_energy_is_not_reported_as_success() {
    let dir = temp_dir("fault-infinite-energy");
    let scene = drop_scene(&dir, 50, |doc| {
        let gravity = toml::Value::Array(vec![0.0.into(), (-1e200).into()]);
        doc["scene"]
            .as_table_mut()
            .unwrap()
            .insert("gravity".into(), gravity);
    });
    let out = dir.join("out");
    let result = run(&scene, &out, &["--quiet"]);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{err}");
    assert!(err.contains("blow-up"), "{err}");
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"failed\""), "{summary}");
}

#[test]
fn a_second_run_into_a_locked_output_directory_is_refused_with_the_first_named() {
    let dir = temp_dir("fault-two-runs");
    let scene = drop_scene(&dir, 20, |_| {});
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // A live process holds the lock: this test's own.
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default();
    let holder = format!(
        "pid {} on host {} since 0 s\n",
        std::process::id(),
        host.trim()
    );
    std::fs::write(out.join("xper.lock"), &holder).unwrap();
    let result = run(&scene, &out, &["--quiet"]);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{err}");
    assert!(
        err.contains("another run") && err.contains(&format!("pid {}", std::process::id())),
        "{err}"
    );
    assert!(
        !out.join("series.csv").exists(),
        "the refused run wrote outputs"
    );
    // Once the holder is gone, the run goes ahead and leaves no lock behind.
    std::fs::remove_file(out.join("xper.lock")).unwrap();
    assert!(run(&scene, &out, &["--quiet"]).status.success());
    assert!(!out.join("xper.lock").exists());
}

#[test]
fn frames_of_an_earlier_longer_run_are_not_mixed_with_a_new_one() {
    let dir = temp_dir("fault-stale-frames");
    let long = drop_scene(&dir, 60, |_| {});
    let out = dir.join("out");
    assert!(run(&long, &out, &["--quiet"]).status.success());
    let frames = |out: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(out.join("frames"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    let before = frames(&out);
    let short = drop_scene(&dir, 20, |_| {});
    assert!(run(&short, &out, &["--quiet"]).status.success());
    let fresh = dir.join("fresh");
    assert!(run(&short, &fresh, &["--quiet"]).status.success());
    assert!(frames(&out).len() < before.len());
    assert_eq!(frames(&out), frames(&fresh));
}

#[test]
fn a_run_off_a_terminal_says_when_it_starts_and_when_it_ends() {
    let dir = temp_dir("fault-silent-batch");
    let scene = drop_scene(&dir, 20, |_| {});
    let result = run(&scene, &dir.join("out"), &[]);
    assert!(result.status.success());
    let err = String::from_utf8_lossy(&result.stderr);
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert!(lines.len() >= 2, "{err}");
    assert!(
        lines[0].contains("running") && lines[0].contains("from step 0 of 20"),
        "{err}"
    );
}

/// A grain in a fluid box of `side` m with `cells` (a `[fluid]` line setting the grid).
fn fluid_scene(dir: &Path, side: &str, cells: &str) -> std::path::PathBuf {
    let text = grain_in_box(
        "dt = 1e-4\nsteps = 3",
        "",
        &format!("viscosity = 1e-2\ndomain = [[0.0, 0.0], [{side}, {side}]]\n{cells}"),
    );
    let path = dir.join("fluid.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn absurd_fluid_grids_are_errors_of_check_never_aborts_of_run() {
    let dir = temp_dir("fault-absurd-grids");
    let cases = [
        ("0.064", "cells_per_diameter = 1e6", "a fluid grid may have"),
        ("0.064", "cell_size = 1e-300", "cells of 1e-300 m"),
        ("1e300", "cells_per_diameter = 8", "holds"),
    ];
    for (side, cells, expected) in cases {
        let scene = fluid_scene(&dir, side, cells);
        for command in ["check", "run"] {
            let mut args = vec![command, scene.to_str().unwrap()];
            let out = dir.join("out");
            if command == "run" {
                args.extend(["--out", out.to_str().unwrap(), "--quiet"]);
            }
            let result = xper(&args);
            let err = String::from_utf8_lossy(&result.stderr);
            assert_eq!(result.status.code(), Some(2), "{command} {cells}: {err}");
            assert!(
                err.contains("fluid.domain") && err.contains(expected),
                "{err}"
            );
            assert!(err.len() < 400, "a short message: {err}");
        }
    }
}

#[test]
fn a_scene_larger_than_the_memory_is_refused_by_run_with_its_estimate() {
    let dir = temp_dir("fault-memory");
    // 16000 x 16000 cells: under the grid cap, about 67 GB.
    let scene = fluid_scene(&dir, "0.064", "cells_per_diameter = 500");
    let check = xper(&["check", scene.to_str().unwrap()]);
    let printed = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success(), "{printed}");
    assert!(
        printed.contains("needs: about 6") && printed.contains("256000000 fluid cells"),
        "{printed}"
    );
    let out = dir.join("out");
    let result = run(&scene, &out, &["--quiet", "--max-memory", "8"]);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{err}");
    assert!(
        err.contains("needs about 6") && err.contains("8.0 GB available"),
        "{err}"
    );
    let bad = run(&scene, &out, &["--max-memory", "-1"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("positive number of GB"));
}

#[test]
fn an_impossible_random_placement_is_refused_at_once() {
    let dir = temp_dir("fault-random-placement");
    let scene = drop_scene(&dir, 10, |doc| {
        let generator: toml::Table = toml::from_str(
            r#"kind = "box_of_disks"
count = 100000
radius = [0.004, 0.005]
box = [[-0.5, 0.0], [0.5, 1.0]]
placement = "random"
material = "water_like"
group = "ball""#,
        )
        .unwrap();
        doc.insert(
            "generators".into(),
            toml::Value::Array(vec![generator.into()]),
        );
    });
    let result = xper(&["check", scene.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{err}");
    // The message of the refusal before any attempt, not of the attempts running out.
    assert!(err.contains("random placement jams"), "{err}");
}

#[test]
fn solver_names_are_the_same_on_the_command_line_in_scenes_and_in_outputs() {
    let problem = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/fclib/siconos_dat_2d/FrictionContactProblem00031.dat");
    let problem = problem.to_str().unwrap();
    for (given, reported) in [
        ("nlgs", "nlgs"),
        ("nsgs", "nlgs"),
        ("proximal_newton", "proximal_newton"),
        ("proximal-newton", "proximal_newton"),
        ("newton", "newton"),
    ] {
        let out = xper(&["solve", problem, "--solver", given]);
        let json = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{given}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            json.contains(&format!("\"solver\": \"{reported}\"")),
            "{given}: {json}"
        );
    }
    let out = xper(&["solve", problem, "--tol", "-1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("negative"));
}

#[test]
fn a_fluid_checkpoint_with_another_grid_size_is_refused_not_indexed() {
    let dir = temp_dir("fault-fluid-grid");
    let scene = fluid_scene(&dir, "0.016", "cells_per_diameter = 8");
    let out = dir.join("out");
    assert!(run(&scene, &out, &["--quiet", "--stop-at-step", "2"])
        .status
        .success());
    // The damage the campaign found (one byte of the grid size), re-sealed with a valid
    // checksum, as a file written by a faulty build would be.
    let sealed = xper_simulation::checkpoint::open(&out, "test").unwrap();
    type Payload = (u32, u64, xper_fluid::CoupledState);
    let (tag, hash, mut state): Payload = bincode::deserialize(&sealed.payload).unwrap();
    state.fluid.grid.nx += 256;
    let payload = bincode::serialize(&(tag, hash, state)).unwrap();
    let bytes = xper_simulation::checkpoint::seal(sealed.header, &payload).unwrap();
    std::fs::write(out.join("checkpoint.bin"), bytes).unwrap();
    let result = run(&scene, &out, &["--quiet", "--resume"]);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(2), "{err}");
    assert!(err.contains("fluid grid of 320 x 64"), "{err}");
}

#[test]
fn step_counts_beyond_2_pow_53_are_refused_and_printed_as_numbers() {
    let dir = temp_dir("fault-steps");
    for (key, value, expected) in [
        ("steps", toml::Value::Integer(i64::MAX), "9007199254740992"),
        ("duration", toml::Value::Float(1e300), "1.000e303 steps"),
    ] {
        let scene = drop_scene(&dir, 10, |doc| {
            let s = doc["scene"].as_table_mut().unwrap();
            s.remove("steps");
            s.insert(key.into(), value);
        });
        let result = xper(&["check", scene.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{err}");
        assert!(err.contains(expected) && err.len() < 300, "{err}");
    }
}

#[test]
fn a_fluid_blow_up_fails_instead_of_completing() {
    let dir = temp_dir("fault-fluid-blow-up");
    let lines = "cells_per_diameter = 8\nbody_force = [0.0, -1e200]";
    let scene = fluid_scene(&dir, "0.016", lines);
    let out = dir.join("out");
    let result = run(&scene, &out, &["--quiet"]);
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{err}");
    assert!(
        err.contains("step 1") && err.contains("non-finite"),
        "{err}"
    );
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"failed\""), "{summary}");
}
