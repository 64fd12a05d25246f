//! Faults of issue 38's campaign, each a regression test named after it.

mod common;
use common::{shipped_scene, temp_dir, xper};
use std::path::Path;

fn run(scene: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    xper(&args)
}

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
