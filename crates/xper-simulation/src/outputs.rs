//! Pieces every run's outputs share: the output directory, the progress bar, I/O errors and
//! the averages of summaries.

use crate::RunError;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;

/// An I/O failure while writing outputs: the run fails (exit code 1).
pub fn io_err(e: std::io::Error) -> RunError {
    RunError::Runtime(e.to_string())
}

/// Creates an output directory (and its parents), a bad-input error naming it otherwise.
pub fn create_output_dir(dir: &Path) -> Result<(), RunError> {
    std::fs::create_dir_all(dir).map_err(|e| {
        RunError::BadInput(format!(
            "{}: cannot create output directory: {e}",
            dir.display()
        ))
    })
}

/// The progress bar of a run: steps/s, ETA and a message; hidden when `quiet`.
pub fn progress_bar(quiet: bool, steps: u64, position: u64) -> ProgressBar {
    // Under an MPI launcher only stdout may be the terminal.
    let target = if quiet {
        ProgressDrawTarget::hidden()
    } else if std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::stdout()
    };
    let bar = ProgressBar::with_draw_target(Some(steps), target);
    let style =
        ProgressStyle::with_template("{bar:30} {pos}/{len} steps, {per_sec}, ETA {eta}, {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_position(position);
    bar
}

/// Arithmetic mean (0 for no value).
pub fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}
