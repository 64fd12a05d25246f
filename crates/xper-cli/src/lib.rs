//! The library behind the `xper` command: scene-to-world conversion, the run loops (rigid
//! scenes and fracture scenes) with their outputs, benchmarks and validation cases.

pub mod bench;
pub mod bench_fluid;
pub mod bench_fracture;
pub mod bench_solvers;
pub mod crack;
pub mod fracture_frames;
pub mod fracture_outputs;
pub mod frames;
pub mod run;
pub mod run_distributed;
pub mod run_fluid;
pub mod run_fluid_distributed;
pub mod run_fracture;
pub mod run_fracture_distributed;
pub mod serial_comparison;
pub mod solve;
pub mod validation;
pub mod validation_fluid;
pub mod validation_paper;
pub mod world_from_scene;

/// A failure with the exit code it maps to.
#[derive(Debug)]
pub enum CliError {
    /// Bad scene, command line or checkpoint: exit code 2.
    BadInput(String),
    /// The run could not complete: exit code 1.
    Runtime(String),
}

/// The scene file a command-line argument names: the path itself, or `DIR/scene.toml` when it
/// is a directory (the layout of `scenes/<name>/`). A directory without `scene.toml` is an
/// error naming both.
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

/// [`scene_path`] as clap's parser of a scene argument (any path the system accepts).
pub fn scene_path_parser() -> impl clap::builder::TypedValueParser<Value = std::path::PathBuf> {
    use clap::builder::TypedValueParser;
    clap::builder::PathBufValueParser::new().try_map(scene_path)
}
