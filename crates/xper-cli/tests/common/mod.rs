//! Helpers shared by the command-line tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Output;

/// A fresh directory under cargo's target tmp dir.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("xper-cli-tests")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the `xper` binary.
pub fn xper(args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_xper"))
        .args(args)
        .output()
        .expect("xper runs")
}

/// `xper run SCENE --out OUT EXTRA..`.
pub fn run_scene(scene: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    xper(&args)
}

/// Fails with the exit code and both output streams unless the command succeeded.
pub fn assert_success(output: &Output) {
    assert!(
        output.status.success(),
        "exit {:?}\n{}{}",
        output.status.code(),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// A box of disks deposited under gravity, with frames and checkpoints.
pub fn deposit_scene(count: usize, steps: usize) -> String {
    xper_validation::rigid::deposit_scene(count, steps).replace(
        "[[materials]]",
        "[output]\nframe_every = 50\ncheckpoint_every = 40\n\n[[materials]]",
    )
}

/// The scene of `scenes/NAME/scene.toml` cut to `steps` steps, with a frame every
/// `[frames, checkpoints][0]` steps and a checkpoint every `[..][1]` (no shipped scene names a
/// file by a relative path); problem dumps, which need the hdf5 feature, are left out.
pub fn shipped_scene(name: &str, steps: u64, every: [u64; 2], dir: &Path) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join("scenes").join(name).join("scene.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut doc: toml::Table = text.parse().unwrap();
    let scene = doc["scene"].as_table_mut().expect("[scene]");
    scene.remove("duration");
    scene.insert("steps".into(), toml::Value::Integer(steps as i64));
    let output = doc
        .entry("output")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()))
        .as_table_mut()
        .unwrap();
    output.insert("frame_every".into(), toml::Value::Integer(every[0] as i64));
    output.insert(
        "checkpoint_every".into(),
        toml::Value::Integer(every[1] as i64),
    );
    output.remove("dump_problems");
    let out = dir.join(format!("{name}.toml"));
    std::fs::write(&out, toml::to_string(&doc).unwrap()).unwrap();
    out
}

/// A disk above a wall in a fluid box (a `[fluid]` scene): `length` holds the `[scene]` lines
/// of its time step and length, `output` an `[output]` table (or nothing), `fluid` the
/// `[fluid]` lines after its density (viscosity, domain, grid).
pub fn grain_in_box(length: &str, output: &str, fluid: &str) -> String {
    format!(
        r#"[scene]
name = "grain_in_box"
{length}
gravity = [0.0, -9.81]

{output}[[materials]]
name = "grain"
density = 1500.0

[[laws]]
between = ["grain", "wall"]
kind = "signorini_coulomb"
friction = 0.5

[[bodies]]
shape = "disk"
center = [0.008, 0.012]
radius = 0.001
material = "grain"
group = "grain"

[[walls]]
from = [0.0, 0.0]
to = [0.016, 0.0]
group = "wall"

[fluid]
density = 1000.0
{fluid}
"#
    )
}

/// The first Python interpreter that has the `vtk` module (a pyenv `python3` may hide the
/// system's), if any.
pub fn python_with_vtk() -> Option<&'static str> {
    ["python3", "/usr/bin/python3"].into_iter().find(|p| {
        std::process::Command::new(p)
            .args(["-c", "import vtk"])
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// Asserts that `xper post`'s `micro.json` in `post_dir` holds the last row of the run's
/// `micro.csv` (`table`), equal up to serde_json's parsing of decimals (not always correctly
/// rounded).
pub fn assert_post_matches_last_row(post_dir: &Path, table: &xper_io::SeriesTable) {
    let text = std::fs::read_to_string(post_dir.join("micro.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let last = table.rows.last().unwrap();
    for (name, value) in table.columns.iter().zip(last) {
        let got = json[name].as_f64().unwrap();
        assert!(
            (got - value).abs() <= 1e-14 * value.abs(),
            "{name}: {got} {value}"
        );
    }
}
