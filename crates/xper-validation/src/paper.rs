//! The paper's fracture applications at the paper's resolution (BRIEF.md section 6 items 1
//! and 2), compared with what the paper shows: their section of VALIDATION.md.
//!
//! The runs take hours, so they live in `validation-runs/<scene>/` and are resumable:
//! `xper validate --full` runs (or continues) them; a plain `xper validate` reports the runs
//! found there, as far as they went, without stepping them.

use std::path::{Path, PathBuf};

use crate::RunError;
use xper_simulation::fracture::outputs::FractureSummary;
use xper_simulation::RunOptions;

/// Directory of the paper-resolution runs.
pub const RUNS_DIR: &str = "validation-runs";

/// The paper's scenes at its resolution.
const SCENES: [&str; 3] = [
    "nooru_mohamed",
    "bimaterial_tension",
    "bimaterial_compression",
];

/// The summary of a paper run: stepped to its end when `full`, else only reloaded from its
/// last checkpoint; `None` when it has no checkpoint and `full` is off.
fn paper_run(name: &str, full: bool) -> Result<Option<FractureSummary>, RunError> {
    let out = Path::new(RUNS_DIR).join(name);
    let resume = out.join("checkpoint.bin").exists();
    if !resume && !full {
        return Ok(None);
    }
    let opts = RunOptions {
        scene: PathBuf::from(format!("scenes/{name}/scene.toml")),
        out,
        resume,
        stop_at_step: if full { None } else { Some(0) },
        compare_serial: false,
        max_memory: None,
    };
    let quiet = !full || !std::io::IsTerminal::is_terminal(&std::io::stderr());
    let summary = xper_simulation::run(&opts, quiet)?;
    serde_json::from_value(summary)
        .map(Some)
        .map_err(|e| RunError::Runtime(format!("{name}: summary: {e}")))
}

fn progress(s: &FractureSummary) -> String {
    format!(
        "{} (step {}, t = {:.3e} s, {} elements, {} interfaces, energy error \
         {:.1e} of the work)",
        s.status,
        s.steps,
        s.simulated_time,
        s.elements,
        s.interfaces,
        s.energy_error / s.energy.external_work.abs().max(f64::MIN_POSITIVE)
    )
}

/// One row: `(case, reference, measured, result)`.
type Row = (String, String, String, String);

fn verdict(ok: bool) -> String {
    if ok { "pass" } else { "FAIL" }.to_string()
}

fn nooru_mohamed_rows(s: &FractureSummary) -> Vec<Row> {
    let c = &s.crack;
    let [left, right] = c.broken_length_left_right_m;
    let [hl, hr] = c.height_left_right_m;
    let h = c.edge_length_m;
    let balance = if left.max(right) > 0.0 {
        left.min(right) / left.max(right)
    } else {
        0.0
    };
    vec![
        (
            "Nooru-Mohamed, paper mesh: a crack from each notch".into(),
            "two cracks, one from each notch (paper; Nooru-Mohamed 1992, load path 4): broken \
             length on each side at least 0.05 m and within a factor 2 of the other"
                .into(),
            format!(
                "broken length left {left:.4} m, right {right:.4} m ({} interfaces broken, {} \
                 damaged)",
                c.broken_interfaces, c.damaged_interfaces
            ),
            verdict(left.min(right) >= 0.05 && balance >= 0.5),
        ),
        (
            "Nooru-Mohamed, paper mesh: anti-symmetric cracks".into(),
            "the pattern is point-symmetric (a half-turn about the centre), not mirror-symmetric: \
             point symmetry >= 0.5 and above the mirror symmetry (fractions of broken length \
             matched within 1.5 edges)"
                .into(),
            format!(
                "point symmetry {:.2}, mirror symmetry {:.2}",
                c.point_symmetry, c.mirror_symmetry
            ),
            verdict(c.point_symmetry >= 0.5 && c.point_symmetry > c.mirror_symmetry),
        ),
        (
            "Nooru-Mohamed, paper mesh: curved cracks".into(),
            "each crack leaves the notch line: its height is at least 5 edge lengths".into(),
            format!(
                "heights left {:.1} mm, right {:.1} mm; edge {:.2} mm",
                hl * 1e3,
                hr * 1e3,
                h * 1e3
            ),
            verdict(hl.min(hr) >= 5.0 * h),
        ),
    ]
}

/// Whether a bimaterial run shows the paper's picture: a crack through the matrix (broken
/// matrix/matrix length at least a tenth of the specimen's width) reaching the inclusions
/// (broken inclusion or matrix/inclusion interfaces).
fn bimaterial_row(name: &str, s: &FractureSummary) -> Row {
    let c = &s.crack;
    let get = |k: &str| c.broken_length_by_regions.get(k).copied().unwrap_or(0.0);
    let (matrix, inclusion, mixed) = (
        get("matrix/matrix"),
        get("inclusion/inclusion"),
        get("inclusion/matrix"),
    );
    let width = 5e-5;
    let reproduces = matrix >= 0.1 * width && inclusion + mixed > 0.0;
    (
        format!("{name}, paper mesh: crack through the matrix, then the inclusions"),
        "the paper's Figure 1: a crack grows through the matrix and then crosses the \
         inclusions (broken matrix length >= 5e-6 m and broken inclusion interfaces)"
            .into(),
        format!(
            "broken length: matrix {:.2e} m, inclusions {:.2e} m, matrix/inclusion {:.2e} m; \
             {} interfaces broken, {} damaged",
            matrix, inclusion, mixed, c.broken_interfaces, c.damaged_interfaces
        ),
        if reproduces {
            "reproduces the paper".into()
        } else {
            "does not reproduce the paper".into()
        },
    )
}

/// Appends the section of the paper runs to `md`; returns the number of failed checks
/// (the bimaterial rows say which load sign reproduces the paper and fail nothing).
pub fn paper_section(md: &mut String, full: bool) -> Result<usize, RunError> {
    md.push_str(
        "\n## The paper's fracture applications at the paper's resolution\n\n\
         Run (or continued from their checkpoints) by `cargo run --release -p xper-cli -- validate \
         --full`, which takes hours; outputs in `validation-runs/<scene>/` (crack pattern, \
         series, VTK). A plain `xper validate` reports the runs found there as far as they went; on a machine \
         without them, it keeps this section from the report it regenerates. \
         Crack measures on the reference mesh, pre-cracks excluded (`crates/xper-simulation/src/fracture/crack.rs`).\n\n\
         | case | reference | measured | result |\n|---|---|---|---|\n",
    );
    let mut failures = 0;
    for name in SCENES {
        let summary = match paper_run(name, full) {
            Ok(Some(s)) => s,
            Ok(None) => {
                md.push_str(&format!(
                    "| {name} | - | not run here (no checkpoint in {RUNS_DIR}/{name}) | - |\n"
                ));
                continue;
            }
            Err(e) => {
                failures += 1;
                let message = match e {
                    RunError::BadInput(m) | RunError::Runtime(m) => m,
                };
                md.push_str(&format!("| {name} | - | run failed: {message} | FAIL |\n"));
                continue;
            }
        };
        md.push_str(&format!(
            "| {name}: run | the scene's {:.3e} s | {} | - |\n",
            summary.dt * scene_steps(name)? as f64,
            progress(&summary)
        ));
        let rows = if name == "nooru_mohamed" {
            nooru_mohamed_rows(&summary)
        } else {
            vec![bimaterial_row(name, &summary)]
        };
        for (case, reference, measured, result) in rows {
            failures += usize::from(result == "FAIL");
            println!("{result}: {case}");
            md.push_str(&format!(
                "| {case} | {reference} | {measured} | {result} |\n"
            ));
        }
    }
    Ok(failures)
}

fn scene_steps(name: &str) -> Result<u64, RunError> {
    let path = PathBuf::from(format!("scenes/{name}/scene.toml"));
    match xper_scene::load_any_scene(&path).map_err(|e| RunError::BadInput(e.to_string()))? {
        xper_scene::AnyScene::Fracture(s) => Ok(s.steps),
        xper_scene::AnyScene::Rigid(s) => Ok(s.steps),
        xper_scene::AnyScene::Rigid3(s) => Ok(s.steps),
    }
}
