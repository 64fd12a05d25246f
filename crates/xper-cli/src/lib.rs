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
