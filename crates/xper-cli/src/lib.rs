//! The `xper` command's own code: its arguments and `xper solve`. Running scenes is
//! [`xper_simulation`], benchmarks [`xper_bench`], validation [`xper_validation`].

pub mod solve;

/// A failure with the exit code it maps to (bad input: 2, a failed run: 1).
pub use xper_simulation::RunError as CliError;

pub use xper_simulation::scene_path;

/// [`scene_path`] as clap's parser of a scene argument (any path the system accepts).
pub fn scene_path_parser() -> impl clap::builder::TypedValueParser<Value = std::path::PathBuf> {
    use clap::builder::TypedValueParser;
    clap::builder::PathBufValueParser::new().try_map(scene_path)
}
