//! Simulations of every physics of xper and the one run driver that steps them.
//!
//! * [`scene`]: a scene file read once and turned into a [`Simulation`] of its kind: rigid
//!   bodies ([`rigid`]), fracture of a meshed specimen ([`fracture`]) or grains in a fluid
//!   ([`fluid`]), on one process or on the processes of a communicator.
//! * [`run`], [`run_on`]: a scene file read once, its memory checked, its simulation built
//!   and driven by the one time loop of `xper-run` ([`drive`]: series, frames, checkpoints,
//!   resume, failures, summary, progress, the comparison with a serial run, the same for all).
//! * [`check`]: `xper check`, what a scene builds.
//!
//! The `xper` command parses its arguments and calls this crate; so will the Python module.

pub mod check;
mod driver;
pub mod fluid;
pub mod fracture;
pub mod homogenize;
pub mod post;
pub mod resources;
pub mod scene;

pub use driver::{prepare, run, run_on, Prepared};
pub use scene::LoadedScene;
pub use xper_rigid as rigid;
pub use xper_rigid3d as rigid3d;
pub use xper_run::{checkpoint, comparison, lock, outputs, ranks, resume, simulation, state};
pub use xper_run::{
    drive, OutputSchedule, Run, RunError, RunFacts, RunOptions, SceneFile, Simulation, StepFailure,
};

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
