//! `xper`: check, run and benchmark scenes of rigid bodies in frictional contact, and check
//! and run fracture scenes (meshed specimens with cohesive interfaces).
//!
//! Exit codes: 0 success, 1 the run failed (I/O error, blow-up), 2 bad input (scene, command
//! line, checkpoint).

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

use xper_bench as bench;
use xper_cli::solve;
use xper_simulation::RunError;
use xper_simulation::RunOptions;

/// Counts heap bytes, so that benchmarks report the memory a run's data needs exactly.
#[global_allocator]
static ALLOCATOR: xper_io::CountingAllocator = xper_io::CountingAllocator;

#[derive(Parser)]
#[command(
    name = "xper",
    version,
    about = "Non-smooth contact dynamics (Moreau-Jean, NLGS): rigid bodies, and fracture of meshed specimens"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Validate a scene file: exit 0, or print every error (file:line:column: field: reason) and exit 2.
    Check {
        /// Scene file (TOML), or a directory holding scene.toml.
        #[arg(value_parser = xper_bench::scene_path_parser())]
        scene: PathBuf,
    },
    /// Run a scene and write result.pvd, frames/, series.csv, series.png, summary.json,
    /// checkpoint.bin (fracture scenes: also force_displacement.png and crack_pattern.png).
    Run {
        /// Scene file (TOML), or a directory holding scene.toml.
        #[arg(value_parser = xper_bench::scene_path_parser())]
        scene: PathBuf,
        /// Output directory (created if needed).
        #[arg(long)]
        out: PathBuf,
        /// Continue from the last checkpoint in the output directory.
        #[arg(long)]
        resume: bool,
        /// Stop after this step (writing a checkpoint), as if the run had been interrupted.
        #[arg(long)]
        stop_at_step: Option<u64>,
        /// Print nothing but errors: no progress bar (shown only on a terminal), no notes, no
        /// first and closing lines (a run off a terminal prints these two for batch logs).
        #[arg(long)]
        quiet: bool,
        /// Under mpirun: after the run, run the same steps on one process and write the
        /// parallel efficiency and the largest position difference into summary.json.
        #[arg(long)]
        compare_serial: bool,
        /// Largest memory the run may need by the estimate `xper check` prints (GB); the
        /// memory available when the run starts by default.
        #[arg(long, value_parser = positive_gb, allow_negative_numbers = true)]
        max_memory: Option<f64>,
    },
    /// Compute the effective elastic tensor of a fracture scene's periodic cell (three static
    /// solves) and print it with its symmetry and positive-definiteness checks.
    Homogenize {
        /// Scene file (TOML) with a [periodic] section, or a directory holding scene.toml.
        #[arg(value_parser = xper_bench::scene_path_parser())]
        scene: PathBuf,
        /// Also write the tensor and its checks to this JSON file.
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Measure the packing a rigid run's checkpoint holds: granular stress, fabric,
    /// coordination, solid fraction, normal-force distribution and force chains, written to
    /// micro.json, forces.csv and force_chains.vtu.
    Post {
        /// The run's output directory (holding checkpoint.bin).
        run: PathBuf,
        /// Where to write (default: <run>/post).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The volume of the measures: the box of the walls' positions, the grains'
        /// bounding box, or the periodic cell (default: the scene's `[output] micro`, else
        /// `walls`).
        #[arg(long, value_parser = ["walls", "grains", "cell"])]
        volume: Option<String>,
    },
    /// Run benchmark scenes without outputs; print figures, save JSON and regenerate BENCHMARKS.md.
    Bench(bench::BenchArgs),
    /// Solve a frictional contact problem file (Siconos .dat, FCLib .hdf5) and print JSON.
    Solve(solve::SolveArgs),
    /// Run the validation cases against their exact answers and regenerate VALIDATION.md.
    Validate {
        /// The report to write.
        #[arg(long, default_value = "VALIDATION.md")]
        report: PathBuf,
        /// Also run (or continue, from their checkpoints in validation-runs/) the paper's
        /// fracture applications at the paper's resolution: hours of computation.
        #[arg(long)]
        full: bool,
        /// Run nothing: rewrite the summary table that opens the report from its tables.
        #[arg(long, conflicts_with = "full")]
        summary_only: bool,
        /// Run only the robustness campaign (damaged inputs, corrupted checkpoints, killed
        /// runs) and replace its section of the report, then the summary.
        #[arg(long, conflicts_with_all = ["full", "summary_only"])]
        robustness_only: bool,
    },
}

/// `--max-memory`: a positive, finite number of gigabytes.
fn positive_gb(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(gb) if gb > 0.0 && gb.is_finite() => Ok(gb),
        Ok(gb) => Err(format!("must be a positive number of GB, got {gb}")),
        Err(e) => Err(format!("not a number of GB: {e}")),
    }
}

/// Restores the default action of SIGPIPE (end the process quietly), as C programs have, so
/// that `xper check scene | head -1` does not end in a panic when `head` closes the pipe
/// (Rust's runtime ignores SIGPIPE, which turns the closed pipe into a failed `println!`).
#[cfg(unix)]
fn default_sigpipe() {
    extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    const SIGPIPE: i32 = 13;
    const SIG_DFL: usize = 0;
    // SAFETY: setting a signal's disposition to its default has no precondition.
    unsafe {
        signal(SIGPIPE, SIG_DFL);
    }
}

fn main() -> ExitCode {
    #[cfg(unix)]
    default_sigpipe();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check { scene } => xper_simulation::check::check(&scene),
        Command::Run {
            scene,
            out,
            resume,
            stop_at_step,
            quiet,
            compare_serial,
            max_memory,
        } => {
            let opts = RunOptions {
                scene,
                out,
                resume,
                stop_at_step,
                compare_serial,
                max_memory: max_memory.map(|gb| gb * 1e9),
            };
            run_maybe_distributed(&opts, quiet)
        }
        Command::Homogenize { scene, json } => {
            xper_simulation::homogenize::homogenize(&scene, json.as_deref())
        }
        Command::Post { run, out, volume } => {
            let volume = volume.map(|v| match v.as_str() {
                "grains" => xper_scene::MicroVolume::Grains,
                "cell" => xper_scene::MicroVolume::Cell,
                _ => xper_scene::MicroVolume::Walls,
            });
            xper_simulation::post::post(&run, out.as_deref(), volume)
        }
        Command::Bench(args) => bench::bench(&args),
        Command::Solve(args) => solve::run_solve(&args),
        Command::Validate {
            report,
            summary_only: true,
            ..
        } => xper_validation::report::rewrite_summary(&report),
        Command::Validate {
            report,
            robustness_only: true,
            ..
        } => xper_validation::report::rewrite_robustness(&report),
        Command::Validate { report, full, .. } => {
            xper_validation::report::write_report(&report, full)
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(RunError::BadInput(message)) => {
            eprintln!("{message}");
            ExitCode::from(2)
        }
        Err(RunError::Runtime(message)) => {
            eprintln!("error: {message}");
            ExitCode::from(1)
        }
    }
}

/// `xper run`: under `mpirun` with more than one process (binary built with `--features mpi`)
/// a distributed run, otherwise a run on this process.
#[cfg(feature = "mpi")]
fn run_maybe_distributed(opts: &RunOptions, quiet: bool) -> Result<(), RunError> {
    let comm = xper_domain::MpiCommunicator::launched()
        .then(xper_domain::MpiCommunicator::init)
        .flatten();
    match comm {
        Some(comm) => {
            let result = xper_simulation::run_on(opts, quiet, Some(&comm)).map(drop);
            // A failure every process met alike (bad input) ends them all normally; anything
            // else a process met alone would leave the others waiting: end them all.
            match (&result, xper_domain::Communicator::size(&comm)) {
                (Err(RunError::Runtime(message)), n) if n > 1 => {
                    xper_domain::Communicator::abort(&comm, message, 1)
                }
                _ => result,
            }
        }
        None => xper_simulation::run(opts, quiet).map(drop),
    }
}

/// `xper run` on this process (built without MPI).
#[cfg(not(feature = "mpi"))]
fn run_maybe_distributed(opts: &RunOptions, quiet: bool) -> Result<(), RunError> {
    xper_simulation::run(opts, quiet).map(drop)
}
