//! Malformed scenes and command lines give a message naming file, line, field and reason,
//! and exit code 2.

mod common;
use common::{temp_dir, xper};

const VALID: &str = r#"[scene]
name = "ok"
dt = 1e-3
steps = 10

[[materials]]
name = "steel"
density = 7800.0

[[laws]]
between = ["a", "a"]
kind = "signorini_coulomb"
friction = 0.3

[[bodies]]
shape = "disk"
center = [0.0, 0.0]
radius = 0.1
material = "steel"
group = "a"

[[bodies]]
shape = "disk"
center = [0.5, 0.0]
radius = 0.1
material = "steel"
group = "a"
"#;

fn expect_error(name: &str, text: &str, fragments: &[&str]) {
    let dir = temp_dir(name);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    for cmd in ["check", "run"] {
        let mut args = vec![cmd, scene.to_str().unwrap()];
        let out_dir = dir.join("out");
        if cmd == "run" {
            args.extend(["--out", out_dir.to_str().unwrap()]);
        }
        let out = xper(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}/{cmd}: {stderr}");
        assert!(
            stderr.contains(scene.to_str().unwrap()),
            "{name}: no file name in {stderr}"
        );
        for f in fragments {
            assert!(stderr.contains(f), "{name}: `{f}` not in {stderr}");
        }
    }
}

#[test]
fn valid_scene_checks() {
    let dir = temp_dir("valid");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, VALID).unwrap();
    let out = xper(&["check", scene.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn negative_density() {
    expect_error(
        "density",
        &VALID.replace("density = 7800.0", "density = -1.0"),
        &[":8:", "materials[0].density"],
    );
}

#[test]
fn non_positive_time_step() {
    expect_error(
        "dt",
        &VALID.replace("dt = 1e-3", "dt = 0.0"),
        &[":3:", "dt"],
    );
}

#[test]
fn unknown_law() {
    expect_error(
        "law",
        &VALID.replace("kind = \"signorini_coulomb\"", "kind = \"glue\""),
        &[":12:8:", "laws[0].kind", "glue"],
    );
}

#[test]
fn missing_material() {
    expect_error(
        "material",
        &VALID.replacen("material = \"steel\"", "material = \"stel\"", 1),
        &[":19:12:", "bodies[0].material", "stel"],
    );
}

#[test]
fn overlapping_bodies() {
    expect_error(
        "overlap",
        &VALID.replace("center = [0.5, 0.0]", "center = [0.15, 0.0]"),
        &["bodies[1]", "overlap"],
    );
}

#[test]
fn not_toml_at_all() {
    expect_error("garbage", "this is [not toml", &[":1:"]);
}

#[test]
fn missing_file_and_bad_flags() {
    let out = xper(&["check", "/nonexistent/scene.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/scene.toml"));
    let out = xper(&["run", "x.toml"]);
    assert_eq!(out.status.code(), Some(2), "missing --out");
}

/// A scene directory stands for its `scene.toml`; a directory without one is refused with
/// both names and exit code 2.
#[test]
fn a_scene_directory_stands_for_its_scene_file() {
    let dir = temp_dir("scene_directory");
    std::fs::write(dir.join("scene.toml"), VALID).unwrap();
    let out = xper(&["check", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let empty = temp_dir("scene_directory_empty");
    let out_dir = empty.join("out");
    for args in [
        vec!["check"],
        vec!["run", "--out", out_dir.to_str().unwrap()],
    ] {
        let cmd = args[0];
        let out = xper(&[&args[..], &[empty.to_str().unwrap()]].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{cmd}: {stderr}");
        assert!(
            stderr.contains(empty.to_str().unwrap()) && stderr.contains("scene.toml"),
            "{cmd}: {stderr}"
        );
    }
}
