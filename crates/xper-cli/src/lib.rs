//! The library behind the `xper` command besides the run driver (which is
//! [`xper_simulation`]): `xper solve`, the benchmarks and the validation cases.

pub mod bench;
pub mod bench_fluid;
pub mod bench_fracture;
pub mod bench_solvers;
pub mod solve;
pub mod validation;
pub mod validation_fluid;
pub mod validation_paper;

/// A failure with the exit code it maps to (bad input: 2, a failed run: 1).
pub use xper_simulation::RunError as CliError;

pub use xper_simulation::scene_path;

/// [`scene_path`] as clap's parser of a scene argument (any path the system accepts).
pub fn scene_path_parser() -> impl clap::builder::TypedValueParser<Value = std::path::PathBuf> {
    use clap::builder::TypedValueParser;
    clap::builder::PathBufValueParser::new().try_map(scene_path)
}
