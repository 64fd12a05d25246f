//! Helpers shared by the command-line tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Output;

/// A fresh directory under cargo's target tmp dir.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("xper-cli-tests").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the `xper` binary.
pub fn xper(args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_xper")).args(args).output().expect("xper runs")
}

/// A box of disks deposited under gravity.
pub fn deposit_scene(count: usize, steps: usize) -> String {
    format!(
        r#"[scene]
name = "deposit"
dt = 2e-4
steps = {steps}
alert_distance = 5e-4

[output]
frame_every = 50
checkpoint_every = 40

[[materials]]
name = "glass"
density = 2500.0

[[laws]]
between = ["grains", "grains"]
kind = "signorini_coulomb"
friction = 0.3

[[laws]]
between = ["grains", "walls"]
kind = "signorini_coulomb"
friction = 0.5

[[generators]]
kind = "box_of_disks"
count = {count}
radius = [0.002, 0.003]
box = [[0.0, 0.0], [0.1, 0.15]]
placement = "random"
seed = 7
material = "glass"
group = "grains"
walls = "walls"
"#
    )
}
