//! `xper bench`: figures of the benchmark scenes (`../shared/bench/box10k.md`), printed,
//! saved as JSON in the output directory, and gathered into BENCHMARKS.md.
//!
//! Each scene runs in a child process of its own so that its peak memory is its own.

pub mod fluid;
pub mod fracture;
pub mod headline;
pub mod periodic;
pub mod poisson;
pub mod python;
pub mod reading;
pub mod solvers;
mod stats;

use std::path::{Path, PathBuf};
pub use xper_simulation::rigid::bench::BenchResult;
use xper_simulation::RunError;

/// Arguments of `xper bench`.
#[derive(clap::Args)]
pub struct BenchArgs {
    /// Scene files or directories holding scene.toml (default: scenes/box10k,
    /// scenes/box10k_anderson and scenes/box100k).
    #[arg(long = "scene", value_parser = scene_path_parser())]
    scenes: Vec<PathBuf>,
    /// Run at most this many steps of each scene (default: the scene's own count).
    #[arg(long)]
    steps: Option<u64>,
    /// Steps at the end of the run over which the "settled" medians are taken.
    #[arg(long, default_value_t = 200)]
    settled: usize,
    /// Directory of the JSON results.
    #[arg(long, default_value = "bench-results")]
    out: PathBuf,
    /// The Markdown report regenerated from every JSON result in `--out`.
    #[arg(long, default_value = "BENCHMARKS.md")]
    report: PathBuf,
    /// Also run every contact solver on the problem files of this suite folder
    /// (e.g. ../shared/fclib); without `--scene`, only the suite runs.
    #[arg(long)]
    fclib: Option<PathBuf>,
    /// Run the fluid benchmarks (multigrid, fluid step, two-grain scene); without `--scene`,
    /// only these run.
    #[arg(long)]
    fluid: bool,
    /// Compare the periodic bimaterial cell with a plain specimen of the same mesh (the cost
    /// of the periodic coupling); without `--scene`, only this runs.
    #[arg(long)]
    periodic: bool,
    /// Time `xper check` on generated scenes of 0.5 to 50 MB (reading in linear time and
    /// memory); without `--scene`, only these run.
    #[arg(long)]
    reading: bool,
    /// Check one scene in this process and print its time and peak heap (used by `--reading`).
    #[arg(long, hide = true, value_name = "SCENE")]
    read_one: Option<PathBuf>,
    /// Run nothing: regenerate the report from the JSON results in `--out` (linking its NOTES.md).
    #[arg(long)]
    report_only: bool,
    /// Run exactly one scene in this process (used by the parent process).
    #[arg(long, hide = true)]
    single: bool,
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{cpu}, {cores} cores, one thread used")
}

/// `xper bench`.
pub fn bench(args: &BenchArgs) -> Result<(), RunError> {
    if args.report_only {
        return write_report(&args.out, &args.report);
    }
    if let Some(dir) = &args.fclib {
        std::fs::create_dir_all(&args.out)
            .map_err(|e| RunError::BadInput(format!("{}: {e}", args.out.display())))?;
        let suite = crate::solvers::bench_suite(dir, machine())?;
        let file = args.out.join(crate::solvers::RESULTS_FILE);
        xper_io::write_json_atomic(&file, &suite).map_err(|e| RunError::Runtime(e.to_string()))?;
        if args.scenes.is_empty() {
            return write_report(&args.out, &args.report);
        }
    }
    if let Some(path) = &args.read_one {
        return crate::reading::read_one(path);
    }
    if args.reading {
        std::fs::create_dir_all(&args.out)
            .map_err(|e| RunError::BadInput(format!("{}: {e}", args.out.display())))?;
        crate::reading::bench_reading(&args.out, machine())?;
        if args.scenes.is_empty() && !args.fluid {
            return write_report(&args.out, &args.report);
        }
    }
    if args.periodic {
        std::fs::create_dir_all(&args.out)
            .map_err(|e| RunError::BadInput(format!("{}: {e}", args.out.display())))?;
        crate::periodic::bench_periodic(&args.out, machine())?;
        if args.scenes.is_empty() && !args.fluid {
            return write_report(&args.out, &args.report);
        }
    }
    if args.fluid {
        std::fs::create_dir_all(&args.out)
            .map_err(|e| RunError::BadInput(format!("{}: {e}", args.out.display())))?;
        crate::fluid::bench_fluid(&args.out, machine())?;
        if args.scenes.is_empty() {
            return write_report(&args.out, &args.report);
        }
    }
    let scenes = if args.scenes.is_empty() {
        vec![
            PathBuf::from("scenes/box10k/scene.toml"),
            PathBuf::from("scenes/box10k_anderson/scene.toml"),
            PathBuf::from("scenes/box100k/scene.toml"),
        ]
    } else {
        args.scenes.clone()
    };
    std::fs::create_dir_all(&args.out)
        .map_err(|e| RunError::BadInput(format!("{}: {e}", args.out.display())))?;
    if args.single {
        let any = xper_scene::load_any_scene(&scenes[0])
            .map_err(|e| RunError::BadInput(e.to_string()))?;
        let (rigid, path, steps, settled) = (
            &xper_simulation::rigid::bench::bench_one,
            &scenes[0],
            args.steps,
            args.settled,
        );
        let result = match any {
            xper_scene::AnyScene::Rigid(scene) => rigid(scene, path, steps, settled, machine())?,
            xper_scene::AnyScene::Rigid3(scene) => {
                xper_simulation::rigid3d::bench::bench_one(scene, path, steps, settled, machine())?
            }
            xper_scene::AnyScene::Fracture(fracture) => {
                // `bench_fracture::bench_one` builds its model from the file itself.
                drop(fracture);
                let result = crate::fracture::bench_one(&scenes[0], args.steps, machine())?;
                let file = args.out.join(format!(
                    "{}{}.json",
                    crate::fracture::FILE_PREFIX,
                    result.scene
                ));
                xper_io::write_json_atomic(&file, &result)
                    .map_err(|e| RunError::Runtime(e.to_string()))?;
                println!(
                    "{}",
                    serde_json::to_string_pretty(&result).unwrap_or_default()
                );
                return Ok(());
            }
        };
        let file = args.out.join(format!("{}.json", result.scene));
        xper_io::write_json_atomic(&file, &result).map_err(|e| RunError::Runtime(e.to_string()))?;
        println!(
            "{}",
            serde_json::to_string_pretty(&result).unwrap_or_default()
        );
        return Ok(());
    }
    let exe = std::env::current_exe().map_err(|e| RunError::Runtime(e.to_string()))?;
    for scene in &scenes {
        let mut cmd = std::process::Command::new(&exe);
        cmd.args([
            "bench",
            "--single",
            "--settled",
            &args.settled.to_string(),
            "--out",
        ])
        .arg(&args.out)
        .arg("--scene")
        .arg(scene);
        if let Some(s) = args.steps {
            cmd.args(["--steps", &s.to_string()]);
        }
        let status = cmd.status().map_err(|e| RunError::Runtime(e.to_string()))?;
        if !status.success() {
            return Err(RunError::Runtime(format!(
                "benchmark of {} failed ({status})",
                scene.display()
            )));
        }
    }
    write_report(&args.out, &args.report)
}

/// The JSON files of `dir` whose name starts with `prefix` (or, without a prefix, those that
/// are not the solver suite's nor a fracture result), parsed; sorted by file name.
fn read_results<T: serde::de::DeserializeOwned>(
    dir: &Path,
    prefix: Option<&str>,
) -> Result<Vec<T>, RunError> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| RunError::Runtime(format!("{}: {e}", dir.display())))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            let fracture = name.starts_with(crate::fracture::FILE_PREFIX);
            name.ends_with(".json")
                && match prefix {
                    Some(prefix) => name.starts_with(prefix),
                    None => {
                        !fracture
                            && name != crate::solvers::RESULTS_FILE
                            && name != crate::fluid::RESULTS_FILE
                            && name != crate::periodic::RESULTS_FILE
                            && name != crate::reading::RESULTS_FILE
                            && name != crate::python::RESULTS_FILE
                    }
                }
        })
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p)
                .map_err(|e| RunError::Runtime(format!("{}: {e}", p.display())))?;
            serde_json::from_str(&text).map_err(|e| {
                RunError::Runtime(format!(
                    "{}: not a benchmark result of this version ({e}); re-run its benchmark \
                     or delete it",
                    p.display()
                ))
            })
        })
        .collect()
}

/// The result `file` of a `what` benchmark in `dir`, if that benchmark was run; an error when
/// the file cannot be read or is not a result of this version.
fn optional_result<T: serde::de::DeserializeOwned>(
    dir: &Path,
    file: &str,
    what: &str,
) -> Result<Option<T>, RunError> {
    let path = dir.join(file);
    if !path.exists() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&path)
        .map_err(|e| RunError::Runtime(format!("{}: {e}", path.display())))?;
    serde_json::from_str(&text).map(Some).map_err(|e| {
        RunError::Runtime(format!(
            "{}: not a {what} benchmark result of this version ({e})",
            path.display()
        ))
    })
}

/// The machine the rows were measured on or, when they differ, each machine with its scenes.
fn machines_line<'a>(rows: impl Iterator<Item = (&'a str, &'a str)>) -> String {
    let mut machines: Vec<(&str, Vec<&str>)> = Vec::new();
    for (scene, machine) in rows {
        match machines.iter_mut().find(|(m, _)| *m == machine) {
            Some((_, scenes)) => scenes.push(scene),
            None => machines.push((machine, vec![scene])),
        }
    }
    match machines.as_slice() {
        [] => String::new(),
        [(machine, _)] => format!("\nMachine: {machine}.\n"),
        _ => {
            let each: Vec<String> = (machines.iter())
                .map(|(machine, scenes)| format!("{}: {machine}", scenes.join(", ")))
                .collect();
            format!("\nMachines: {}.\n", each.join("; "))
        }
    }
}

/// The table of rigid benchmark results, one row each.
fn rigid_table(results: &[BenchResult]) -> String {
    let mut md = String::from(
        "| scene | bodies | steps | step (ms) | settled step (ms) | sweeps | settled sweeps | contacts | settled contacts | ns / contact update | detection (ms) | detection ns / body (median, mean) | candidate-list builds | peak memory (MB) | bytes / body | heap bytes / body (peak) | overlap median / p99 / max (um) | non-converged steps |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in results {
        md.push_str(&format!(
            "| {} | {} | {} | {:.2} | {:.2} | {} | {} | {} | {} | {:.1} | {:.2} | {:.0}, {} | {} | {:.0} | {:.0} | {} | {:.3} / {:.3} / {:.3} | {} |\n",
            r.scene, r.bodies, r.steps, r.median_step_ms, r.median_settled_step_ms, r.median_sweeps, r.median_settled_sweeps,
            r.median_contacts, r.median_settled_contacts, r.median_ns_per_contact_update, r.median_detect_ms,
            r.median_detect_ns_per_body,
            r.mean_detect_ns_per_body.map_or("-".into(), |m| format!("{m:.0}")),
            r.candidate_list_builds.map_or("-".into(), |b| b.to_string()),
            r.peak_memory_bytes as f64 / 1e6, r.peak_memory_bytes_per_body,
            r.peak_heap_bytes.map_or("-".into(), |b| format!(
                "{:.0}",
                b as f64 / r.bodies as f64
            )),
            r.overlap_median_m * 1e6, r.overlap_p99_m * 1e6, r.overlap_max_m * 1e6, r.non_converged_steps
        ));
    }
    md.push_str(&machines_line(
        results
            .iter()
            .map(|r| (r.scene.as_str(), r.machine.as_str())),
    ));
    md
}

/// Regenerates the Markdown report from every JSON result in `dir`.
fn write_report(dir: &Path, report: &Path) -> Result<(), RunError> {
    let mut results: Vec<BenchResult> = read_results(dir, None)?;
    results.sort_by_key(|r| r.bodies);
    let (flat, solid): (Vec<BenchResult>, Vec<BenchResult>) = results
        .into_iter()
        .partition(|r| r.dimension.unwrap_or(2) == 2);
    let mut headlines = headline::rigid(&flat);
    let mut md = String::from(
        "\n## Rigid bodies\n\nRegenerated by `cargo run --release -p xper-cli -- bench` (see README). Scenes as specified in\n\
         `../shared/bench/box10k.md`; one thread; medians over the run and over its last 200 steps (settled).\n\n",
    );
    md.push_str(&rigid_table(&flat));
    md.push_str(
        "\n## Reference figures of other codes on box10k (from `../shared/bench/box10k.md`, same kind of machine)\n\n\
         | code | step (ms) | settled step (ms) | sweeps settled | contacts settled | ns / contact update | detection (ms) | peak memory (MB) | overlap median / p99 (um) |\n\
         |---|---|---|---|---|---|---|---|---|\n\
         | LMGC90 2025.rc1 (NLGS, stored Delassus loops) | 99 | 79 | ~10 | 21,700 | 25 | 20-25 | 260 | 0.04 / 0.43 |\n\
         | pymunk 7.3 (impulses, not NSCD) | 6.5 | - | 10 | - | - | - | - | 6 / 180 |\n",
    );
    if !solid.is_empty() {
        md.push_str(
            "\n## Rigid bodies in 3D\n\n`xper bench --scene scenes/box3d10k` (and box3d100k, box3d1m): scenes as specified in\n\
             `../shared/bench/box3d10k.md`; one thread; medians as above. Targets of issue 34: at most 60 ns per 3D contact\n\
             update (memory traffic alone allows 20-30 ns), at most 200 ns per body for detection, at most 1.5 kB per sphere.\n\n",
        );
        md.push_str(&rigid_table(&solid));
    }
    let fracture: Vec<crate::fracture::FractureBenchResult> =
        read_results(dir, Some(crate::fracture::FILE_PREFIX))?;
    if !fracture.is_empty() {
        headlines.extend(headline::fracture(&fracture));
        md.push_str(&crate::fracture::markdown(&fracture));
    }
    if let Some(suite) = std::fs::read_to_string(dir.join(crate::solvers::RESULTS_FILE))
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok())
    {
        headlines.extend(headline::solvers(&suite));
        md.push_str(&crate::solvers::markdown(&suite));
    }
    if let Some(fluid) = optional_result(dir, crate::fluid::RESULTS_FILE, "fluid")? {
        headlines.extend(headline::fluid(&fluid));
        md.push_str(&crate::fluid::markdown(&fluid));
    }
    if let Some(periodic) = optional_result::<crate::periodic::PeriodicBench>(
        dir,
        crate::periodic::RESULTS_FILE,
        "periodic",
    )? {
        md.push_str(&crate::periodic::markdown(&periodic));
    }
    if let Some(reading) = optional_result(dir, crate::reading::RESULTS_FILE, "reading")? {
        headlines.extend(headline::reading(&reading));
        md.push_str(&crate::reading::markdown(&reading));
    }
    if let Some(python) =
        optional_result::<crate::python::PythonBench>(dir, crate::python::RESULTS_FILE, "python")?
    {
        headlines.extend(crate::python::headlines(&python));
        md.push_str(&crate::python::markdown(&python));
    }
    if dir.join("NOTES.md").exists() {
        md.push_str(&format!(
            "\n## Notes\n\nDistributed runs (strong scaling, the efficiency model), the memory and speed passes \
             and how to read these figures: [{0}/NOTES.md]({0}/NOTES.md) (written by hand, not \
             regenerated).\n",
            dir.display()
        ));
    }
    let md = format!(
        "# Benchmarks\n\nEach section is regenerated by the command it names (see README); the \
         figures come from the JSON results in `{}`.\n\n{}{md}",
        dir.display(),
        headline::markdown(&headlines)
    );
    xper_io::write_atomic(report, md.as_bytes()).map_err(|e| RunError::Runtime(e.to_string()))?;
    println!("wrote {}", report.display());
    Ok(())
}

/// [`xper_simulation::scene_path`] as clap's parser of a scene argument: the path itself, or
/// `DIR/scene.toml` for a directory.
pub fn scene_path_parser() -> impl clap::builder::TypedValueParser<Value = PathBuf> {
    use clap::builder::TypedValueParser;
    clap::builder::PathBufValueParser::new().try_map(xper_simulation::scene_path)
}

#[cfg(test)]
mod tests {
    use super::machines_line;

    #[test]
    fn rows_from_several_machines_name_each_machine_with_its_scenes() {
        let one = machines_line([("box10k", "M1"), ("box100k", "M1")].into_iter());
        assert_eq!(one, "\nMachine: M1.\n");
        let two = machines_line([("a", "M1"), ("b", "M2"), ("c", "M1")].into_iter());
        assert_eq!(two, "\nMachines: a, c: M1; b: M2.\n");
        assert_eq!(machines_line(std::iter::empty()), "");
    }
}
