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
