//! Simulations of every physics of xper and the one run driver that steps them.
//!
//! * [`scene`]: a scene file read once and turned into a [`Simulation`] of its kind: rigid
//!   bodies ([`rigid`]), fracture of a meshed specimen ([`fracture`]) or grains in a fluid
//!   ([`fluid`]), on one process or on the processes of a communicator.
//! * [`driver`]: the time loop with its schedule of series, frames and checkpoints, resume,
//!   failures, summary, progress and the comparison with a serial run, the same for all.
//! * [`check`]: `xper check`, what a scene builds.
//!
//! The `xper` command parses its arguments and calls this crate; so will the Python module.

pub mod check;
pub mod checkpoint;
pub mod comparison;
pub mod driver;
pub mod fluid;
pub mod fracture;
pub mod homogenize;
pub mod lock;
pub mod outputs;
pub mod ranks;
pub mod resources;
pub mod resume;
pub mod rigid;
pub mod scene;
pub mod simulation;

pub use driver::{drive, run, run_on, SceneFile};
pub use scene::LoadedScene;
pub use simulation::{OutputSchedule, RunFacts, RunOptions, Simulation, StepFailure};

/// A failure with the exit code it maps to.
#[derive(Debug)]
pub enum RunError {
    /// Bad scene, command line or checkpoint: exit code 2.
    BadInput(String),
    /// The run could not complete: exit code 1.
    Runtime(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::BadInput(m) | RunError::Runtime(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for RunError {}

/// The scene file a path names: the path itself, or `DIR/scene.toml` when it is a directory
/// (the layout of `scenes/<name>/`). A directory without `scene.toml` is an error naming both.
pub fn scene_path(path: std::path::PathBuf) -> Result<std::path::PathBuf, String> {
    if !path.is_dir() {
        return Ok(path);
    }
    let file = path.join("scene.toml");
    if file.is_file() {
        Ok(file)
    } else {
        Err(format!(
            "{} is a directory without a scene file ({} does not exist)",
            path.display(),
            file.display()
        ))
    }
}
