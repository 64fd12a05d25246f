//! `xper bench --reading`: the time and memory `xper check` needs for generated scenes of
//! growing size, in three layouts (one table per body, every body on one line, one polygon
//! on one line), to show that reading is linear in the size of the file; saved as
//! `reading.json`, reported in BENCHMARKS.md.

use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;
use xper_simulation::RunError;

/// File of the results in the benchmark directory.
pub const RESULTS_FILE: &str = "reading.json";

/// The layouts of a generated scene.
const LAYOUTS: [(&str, &[f64]); 3] = [
    ("disks, one [[bodies]] table each", &[1.0, 5.0, 25.0, 50.0]),
    ("disks, all on one line", &[1.0, 5.0, 25.0, 50.0]),
    // A regular polygon of more than about 40,000 vertices is refused as collinear (turns
    // below 1e-12 of its size squared): 1 MB is about 25,000 vertices.
    ("one polygon on one line", &[0.1, 0.25, 0.5, 1.0]),
];

/// Figures of one scene file.
#[derive(Serialize, Deserialize)]
pub struct ReadFigures {
    pub(crate) layout: String,
    pub(crate) bytes: u64,
    /// Bodies, or vertices of the polygon.
    pub(crate) items: u64,
    /// Wall time of the whole check (read, parse, validate, expand, estimate) (s).
    pub(crate) seconds: f64,
    /// Peak heap of the checking process (bytes).
    pub(crate) peak_heap_bytes: u64,
}

/// Everything `--reading` measures.
#[derive(Serialize, Deserialize)]
pub struct ReadingBench {
    pub(crate) machine: String,
    pub(crate) files: Vec<ReadFigures>,
}

const HEADER: &str = "[scene]\nname = \"reading\"\ndt = 1e-3\nduration = 0.01\n\
    gravity = [0.0, -9.81]\n\n[[materials]]\nname = \"m\"\ndensity = 1000.0\n\n\
    [[laws]]\nbetween = [\"grain\", \"grain\"]\nkind = \"signorini_coulomb\"\nfriction = 0.3\n\n";

/// A scene of about `bytes` bytes in `layout` (0, 1 or 2 of [`LAYOUTS`]); its item count.
fn generate(layout: usize, bytes: usize) -> (String, u64) {
    let mut text = String::from(HEADER);
    let mut items = 0u64;
    match layout {
        0 | 1 => {
            let mut bodies = String::new();
            while HEADER.len() + bodies.len() < bytes {
                let (x, y) = ((items % 1000) as f64 * 0.01, (items / 1000) as f64 * 0.01);
                if layout == 0 {
                    let _ = write!(
                        bodies,
                        "[[bodies]]\nshape = \"disk\"\ncenter = [{x:.6}, {y:.6}]\nradius = 0.004\n\
                         material = \"m\"\ngroup = \"grain\"\n\n"
                    );
                } else {
                    let _ = write!(
                        bodies,
                        "{}{{ shape = \"disk\", center = [{x:.6}, {y:.6}], radius = 0.004, \
                         material = \"m\", group = \"grain\" }}",
                        if items == 0 { "" } else { ", " }
                    );
                }
                items += 1;
            }
            if layout == 0 {
                text.push_str(&bodies);
            } else {
                // A top-level key: before the first header.
                text = format!("bodies = [{bodies}]\n{HEADER}");
            }
        }
        _ => {
            // A regular polygon: about 40 bytes per vertex at full precision.
            let n = (bytes.saturating_sub(text.len()) / 40).max(3);
            text.push_str(
                "[[bodies]]\nshape = \"polygon\"\nmaterial = \"m\"\ngroup = \"grain\"\nvertices = [",
            );
            for k in 0..n {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let sep = if k == 0 { "" } else { ", " };
                let _ = write!(text, "{sep}[{:?}, {:?}]", a.cos(), a.sin());
            }
            text.push_str("]\n");
            items = n as u64;
        }
    }
    (text, items)
}

/// Checks the scene at `path` in this process and prints its figures as one JSON line
/// (`xper bench --read-one`): the caller runs each file in a fresh process so that the peak
/// heap is that file's.
pub fn read_one(path: &Path) -> Result<(), RunError> {
    let start = Instant::now();
    xper_simulation::check::check(path)?;
    let seconds = start.elapsed().as_secs_f64();
    let peak = xper_io::memory::peak_heap_bytes().unwrap_or(0);
    println!("{{\"seconds\": {seconds}, \"peak_heap_bytes\": {peak}}}");
    Ok(())
}

#[derive(Deserialize)]
struct ChildFigures {
    seconds: f64,
    peak_heap_bytes: u64,
}

/// Generates every layout and size in a scratch folder, checks each file in its own process
/// and writes `reading.json` into `out`.
pub fn bench_reading(out: &Path, machine: String) -> Result<(), RunError> {
    let scratch = std::env::temp_dir().join(format!("xper-reading-{}", std::process::id()));
    std::fs::create_dir_all(&scratch)
        .map_err(|e| RunError::Runtime(format!("{}: {e}", scratch.display())))?;
    let exe = std::env::current_exe().map_err(|e| RunError::Runtime(e.to_string()))?;
    let mut files = Vec::new();
    for (layout, (name, sizes)) in LAYOUTS.iter().enumerate() {
        for &mb in *sizes {
            let (text, items) = generate(layout, (mb * 1e6) as usize);
            let path: PathBuf = scratch.join(format!("scene-{layout}-{mb}.toml"));
            std::fs::write(&path, &text)
                .map_err(|e| RunError::Runtime(format!("{}: {e}", path.display())))?;
            let output = std::process::Command::new(&exe)
                .args(["bench", "--read-one"])
                .arg(&path)
                .output()
                .map_err(|e| RunError::Runtime(e.to_string()))?;
            let stdout = String::from_utf8_lossy(&output.stdout);
            let figures: ChildFigures = (output.status.success())
                .then(|| {
                    stdout
                        .lines()
                        .last()
                        .and_then(|l| serde_json::from_str(l).ok())
                })
                .flatten()
                .ok_or_else(|| {
                    RunError::Runtime(format!(
                        "checking {} failed: {}{}",
                        path.display(),
                        stdout,
                        String::from_utf8_lossy(&output.stderr)
                    ))
                })?;
            let _ = std::fs::remove_file(&path);
            println!(
                "{name}: {:.1} MB, {items} items: {:.2} s, peak heap {:.0} MB",
                text.len() as f64 / 1e6,
                figures.seconds,
                figures.peak_heap_bytes as f64 / 1e6
            );
            files.push(ReadFigures {
                layout: name.to_string(),
                bytes: text.len() as u64,
                items,
                seconds: figures.seconds,
                peak_heap_bytes: figures.peak_heap_bytes,
            });
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    let bench = ReadingBench { machine, files };
    xper_io::write_json_atomic(&out.join(RESULTS_FILE), &bench)
        .map_err(|e| RunError::Runtime(e.to_string()))
}

/// Seconds per MB of the largest file of a layout over that of its second size (the smallest
/// carries the fixed costs): 1 for linear reading, k for a k-fold larger file if quadratic.
pub(crate) fn growth(bench: &ReadingBench, layout: &str) -> Option<f64> {
    let rows: Vec<&ReadFigures> = bench.files.iter().filter(|f| f.layout == layout).collect();
    let per_mb = |f: &ReadFigures| f.seconds / (f.bytes as f64 / 1e6);
    Some(per_mb(rows.last()?) / per_mb(rows.get(1)?))
}

/// The BENCHMARKS.md section.
pub fn markdown(bench: &ReadingBench) -> String {
    let mut md = String::from(
        "\n## Reading scenes\n\nRegenerated by `cargo run --release -p xper-cli -- bench --reading`. \
         Generated scenes checked by `xper check` (read, parse, validate, expand, estimate), each \
         in its own process; the growth is the time per MB of the largest file over that of the \
         second size (1 when linear, the ratio of the sizes when quadratic: 10 for the disks, 4 for \
         the polygon). A document is parsed in runs of whole top-level statements, so a layout with \
         every body on one line holds all its tokens (24 bytes each) at once.\n\n\
         | layout | MB | bodies or vertices | check (s) | s / MB | peak heap (MB) | heap bytes / file byte |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for f in &bench.files {
        let mb = f.bytes as f64 / 1e6;
        let _ = writeln!(
            md,
            "| {} | {mb:.1} | {} | {:.2} | {:.3} | {:.0} | {:.1} |",
            f.layout,
            f.items,
            f.seconds,
            f.seconds / mb,
            f.peak_heap_bytes as f64 / 1e6,
            f.peak_heap_bytes as f64 / f.bytes as f64
        );
    }
    md.push('\n');
    for (name, _) in LAYOUTS {
        if let Some(g) = growth(bench, name) {
            let _ = writeln!(md, "Growth, {name}: {g:.2}.");
        }
    }
    let _ = writeln!(md, "\nMachine: {}.", bench.machine);
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_scenes_are_valid_and_hold_what_they_say() {
        for layout in 0..3 {
            let (text, items) = generate(layout, 20_000);
            let scene = xper_scene::parse_scene(&text, Path::new("gen.toml"))
                .unwrap_or_else(|e| panic!("layout {layout}: {e}"));
            let bodies = if layout == 2 { 1 } else { items as usize };
            assert_eq!(scene.bodies.len(), bodies, "layout {layout}");
            assert!(text.len() >= 20_000 - 40, "layout {layout}: {}", text.len());
        }
    }
}
