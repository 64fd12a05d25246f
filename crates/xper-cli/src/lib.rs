//! The library behind the `xper` command: scene-to-world conversion, the run loop with its
//! outputs, benchmarks and validation cases.

pub mod bench;
pub mod bench_solvers;
pub mod frames;
pub mod run;
pub mod solve;
pub mod validation;
pub mod world_from_scene;

/// A failure with the exit code it maps to.
#[derive(Debug)]
pub enum CliError {
    /// Bad scene, command line or checkpoint: exit code 2.
    BadInput(String),
    /// The run could not complete: exit code 1.
    Runtime(String),
}
