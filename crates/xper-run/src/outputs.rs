//! Pieces every run's outputs share: the output directory, the progress bar, I/O errors, the
//! averages of summaries, VTU arrays and frame parts, and plot curves.

use crate::RunError;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use xper_io::{
    write_vtu, Curve, DataArray, DataValues, Panel, PvdCollection, SeriesTable, UnstructuredGrid,
};

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

/// A VTU data array of `f64` with `components` values per point or cell.
pub fn f64_array(name: &str, components: usize, values: Vec<f64>) -> DataArray {
    DataArray {
        name: name.into(),
        components,
        values: DataValues::F64(values),
    }
}

/// A VTU data array of one `i32` per point or cell.
pub fn i32_array(name: &str, values: Vec<i32>) -> DataArray {
    DataArray {
        name: name.into(),
        components: 1,
        values: DataValues::I32(values),
    }
}

/// Writes each part of the frame of `step` as `dir/frames/NAME_STEP.vtu` and lists it in `pvd`
/// at `time`, the parts numbered from `first_part`.
pub fn write_vtu_parts(
    dir: &Path,
    pvd: &mut PvdCollection,
    step: u64,
    time: f64,
    first_part: u32,
    parts: &[(&str, UnstructuredGrid)],
) -> Result<(), RunError> {
    for (part, (name, grid)) in (first_part..).zip(parts) {
        let file = format!("frames/{name}_{step:08}.vtu");
        write_vtu(&dir.join(&file), grid).map_err(io_err)?;
        pvd.push(time, part, file);
    }
    Ok(())
}

/// The curve of column `y` against column `x` of `series`.
pub fn series_curve(series: &SeriesTable, x: &str, y: &str, label: &str) -> Curve {
    Curve {
        label: label.into(),
        points: (series.column(x).unwrap_or_default().into_iter())
            .zip(series.column(y).unwrap_or_default())
            .collect(),
    }
}

/// A plot panel.
pub fn panel(title: &str, x_label: &str, y_label: &str, curves: Vec<Curve>, log_y: bool) -> Panel {
    Panel {
        title: title.into(),
        x_label: x_label.into(),
        y_label: y_label.into(),
        curves,
        log_y,
    }
}
