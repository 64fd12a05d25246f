//! The robustness campaign of VALIDATION.md: damaged inputs of every reader, corrupted
//! checkpoints, and runs killed at random instants then resumed, each counted as read,
//! refused with an error, or panicked, with the slowest case (a reader must never hang).
//!
//! The inputs are reproducible (a fixed-seed generator edits the shipped scenes, the test
//! meshes, the shared Siconos files and a real checkpoint); the kill instants are random.

use crate::RunError;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The heading of the campaign's section in VALIDATION.md.
pub const HEADING: &str = "## Robustness: damaged inputs, corrupted checkpoints, killed runs";

/// Cases slower than this count as hangs.
const HANG: Duration = Duration::from_secs(10);

/// Damaged inputs per source file.
const EDITS_PER_FILE: usize = 60;

/// A reproducible sequence (a linear congruential generator).
struct Lcg(u64);

impl Lcg {
    fn below(&mut self, n: usize) -> usize {
        self.0 = (self.0)
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 33) as usize) % n.max(1)
    }
}

/// Values that break readers: wrong signs, huge counts, non-numbers.
const BAD_TOKENS: [&str; 10] = [
    "-1",
    "0",
    "1e308",
    "1e-300",
    "nan",
    "inf",
    "4294967297",
    "99999999999999999999",
    "\"",
    "[",
];

/// `text` with one to four edits: a word replaced by a bad token, a line deleted or repeated,
/// a byte changed, or the text cut.
fn damaged(text: &[u8], rng: &mut Lcg) -> Vec<u8> {
    let mut bytes = text.to_vec();
    for _ in 0..1 + rng.below(4) {
        if bytes.is_empty() {
            break;
        }
        match rng.below(5) {
            0 => {
                let at = rng.below(bytes.len());
                bytes[at] = b"0123456789-+.e[]{}=\",\n #"[rng.below(24)];
            }
            1 => bytes.truncate(rng.below(bytes.len())),
            k => {
                let s = String::from_utf8_lossy(&bytes).into_owned();
                let mut lines: Vec<String> = s.lines().map(str::to_string).collect();
                if lines.is_empty() {
                    break;
                }
                let l = rng.below(lines.len());
                match k {
                    2 => {
                        lines.remove(l);
                    }
                    3 => {
                        let line = lines[l].clone();
                        lines.insert(l, line);
                    }
                    _ => {
                        let mut words: Vec<String> =
                            lines[l].split(' ').map(str::to_string).collect();
                        let w = rng.below(words.len());
                        words[w] = BAD_TOKENS[rng.below(BAD_TOKENS.len())].to_string();
                        lines[l] = words.join(" ");
                    }
                }
                bytes = lines.join("\n").into_bytes();
            }
        }
    }
    bytes
}

/// Counts of one category.
#[derive(Default)]
struct Tally {
    tried: usize,
    read: usize,
    refused: usize,
    panics: usize,
    slowest: Duration,
}

impl Tally {
    /// Runs `read` on one input, counting its outcome.
    fn case(&mut self, read: impl FnOnce() -> bool) {
        let start = Instant::now();
        match catch_unwind(AssertUnwindSafe(read)) {
            Ok(true) => self.read += 1,
            Ok(false) => self.refused += 1,
            Err(_) => self.panics += 1,
        }
        self.tried += 1;
        self.slowest = self.slowest.max(start.elapsed());
    }

    fn row(&self, md: &mut String, what: &str) -> usize {
        let failed = self.panics > 0 || self.slowest > HANG;
        md.push_str(&format!(
            "| {what} | {} | {} | {} | {} | {:.3} | {} |\n",
            self.tried,
            self.read,
            self.refused,
            self.panics,
            self.slowest.as_secs_f64(),
            if failed { "FAIL" } else { "pass" }
        ));
        usize::from(failed)
    }
}

fn files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.retain(|p| p.extension().is_some_and(|e| e == ext));
    v.sort();
    v
}

/// The campaign's table; returns its failed rows. `root` is the repository (its `scenes/`,
/// the test meshes, `../shared` beside it), `xper` the binary the kill rounds run (`None`:
/// they are left out, as in the test suite), `kills` how many.
pub fn robustness_section(
    md: &mut String,
    root: &Path,
    xper: Option<&Path>,
    kills: usize,
) -> Result<usize, RunError> {
    // Panics are counted, not printed, while the readers run.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let read = catch_unwind(AssertUnwindSafe(|| readers(md, root)));
    std::panic::set_hook(hook);
    let mut failures = read.map_err(|_| {
        RunError::Runtime("the robustness campaign itself panicked outside a reader".into())
    })??;
    let mut rng = Lcg(2026);
    if let Some(xper) = xper {
        failures += kill_rounds(md, root, xper, kills, &mut rng)?;
    }
    Ok(failures)
}

/// The rows of the readers and of the checkpoints; returns the failed ones.
fn readers(md: &mut String, root: &Path) -> Result<usize, RunError> {
    let mut rng = Lcg(38);
    let mut failures = 0;
    md.push_str(
        "\n## Robustness: damaged inputs, corrupted checkpoints, killed runs\n\n\
         Regenerated with the rest, or alone by `cargo run --release -p xper-cli -- validate \
         --robustness-only`. Each input is a shipped file with one to four edits (a word \
         replaced by a bad value, a line deleted or repeated, a byte changed, the file cut), \
         read in this process; \"read\" inputs were still valid, \"refused\" gave an error, a \
         panic fails the row, as does a case slower than 10 s (a hang). The kill rounds kill \
         `xper run` at random instants, resume until the run ends, and compare its outputs \
         with an uninterrupted run's, byte for byte (timing columns aside).\n\n\
         | inputs | tried | read | refused with an error | panics | slowest (s) | result |\n\
         |---|---|---|---|---|---|---|\n",
    );
    let mut scenes = Tally::default();
    let mut shipped: Vec<PathBuf> = std::fs::read_dir(root.join("scenes"))
        .map(|d| {
            d.filter_map(|e| e.ok().map(|e| e.path().join("scene.toml")))
                .collect()
        })
        .unwrap_or_default();
    shipped.retain(|p| p.exists());
    shipped.sort();
    for path in &shipped {
        let text = std::fs::read(path).unwrap_or_default();
        for _ in 0..EDITS_PER_FILE {
            let bad = String::from_utf8_lossy(&damaged(&text, &mut rng)).into_owned();
            scenes.case(|| xper_scene::parse_any_scene(&bad, path).is_ok());
        }
    }
    failures += scenes.row(md, &format!("scenes ({} shipped scenes)", shipped.len()));
    let mut meshes = Tally::default();
    let mesh_files = files(&root.join("crates/xper-mesh/tests/data"), "msh");
    for path in &mesh_files {
        let bytes = std::fs::read(path).unwrap_or_default();
        for _ in 0..EDITS_PER_FILE {
            let bad = damaged(&bytes, &mut rng);
            meshes.case(|| xper_mesh::parse_msh(&bad, "damaged.msh").is_ok());
        }
    }
    failures += meshes.row(
        md,
        &format!("Gmsh meshes ({} test meshes)", mesh_files.len()),
    );
    let mut dats = Tally::default();
    let dat_files = files(&root.join("../shared/fclib/siconos_dat_2d"), "dat");
    let small: Vec<&PathBuf> = (dat_files.iter())
        .filter(|p| std::fs::metadata(p).is_ok_and(|m| m.len() < 200_000))
        .collect();
    for path in &small {
        let text = std::fs::read(path).unwrap_or_default();
        for _ in 0..EDITS_PER_FILE {
            let bad = String::from_utf8_lossy(&damaged(&text, &mut rng)).into_owned();
            let kind = xper_fclib::SiconosKind::Auto;
            dats.case(|| xper_fclib::parse_siconos(&bad, Path::new("damaged.dat"), kind).is_ok());
        }
    }
    failures += dats.row(md, &format!("Siconos .dat ({} shared files)", small.len()));
    failures += checkpoints(md, root, &mut rng)?;
    Ok(failures)
}

/// A scratch directory for the campaign's runs.
fn scratch(name: &str) -> Result<PathBuf, RunError> {
    let dir = std::env::temp_dir().join(format!("xper-robustness-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir)
        .map_err(|e| RunError::Runtime(format!("{}: {e}", dir.display())))?;
    Ok(dir)
}

/// `scenes/drop` cut to `steps` steps, a frame every 50 and a checkpoint every 100, in `dir`.
fn drop_scene(root: &Path, dir: &Path, steps: u64) -> Result<PathBuf, RunError> {
    let source = root.join("scenes/drop/scene.toml");
    let text = std::fs::read_to_string(&source)
        .map_err(|e| RunError::Runtime(format!("{}: {e}", source.display())))?;
    let text = text
        .replace("duration = 1.0", &format!("steps = {steps}"))
        .replace("frame_every = 10", "frame_every = 50");
    let path = dir.join("drop.toml");
    std::fs::write(&path, text)
        .map_err(|e| RunError::Runtime(format!("{}: {e}", path.display())))?;
    Ok(path)
}

/// Damaged copies of a real checkpoint: each must be refused.
fn checkpoints(md: &mut String, root: &Path, rng: &mut Lcg) -> Result<usize, RunError> {
    let dir = scratch("checkpoint")?;
    let opts = xper_simulation::RunOptions {
        scene: drop_scene(root, &dir, 100)?,
        out: dir.join("out"),
        resume: false,
        stop_at_step: None,
        compare_serial: false,
        max_memory: None,
    };
    xper_simulation::run(&opts, true)?;
    let good = std::fs::read(opts.out.join("checkpoint.bin"))
        .map_err(|e| RunError::Runtime(e.to_string()))?;
    let mut tally = Tally::default();
    for _ in 0..500 {
        let mut bad = good.clone();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(bad.len());
            match rng.below(3) {
                0 if at < bad.len() => bad[at] ^= 1 + rng.below(255) as u8,
                1 => bad.truncate(at),
                _ => bad.insert(at, rng.below(256) as u8),
            }
        }
        if bad != good {
            tally.case(|| xper_simulation::checkpoint::unseal(bad).is_ok());
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    // A damaged checkpoint that is accepted would resume another state: it fails the row.
    let accepted = tally.read;
    let failed = tally.row(md, "checkpoints (the drop scene's, damaged)");
    Ok(failed.max(usize::from(accepted > 0)))
}

/// Kills `xper run` of the drop scene at random instants and resumes it until it ends, in
/// rounds, comparing each ending with an uninterrupted run.
fn kill_rounds(
    md: &mut String,
    root: &Path,
    xper: &Path,
    kills: usize,
    rng: &mut Lcg,
) -> Result<usize, RunError> {
    let dir = scratch("kills")?;
    let scene = drop_scene(root, &dir, 3000)?;
    let run = |out: &Path, resume: bool| {
        let mut c = std::process::Command::new(xper);
        c.args([
            "run",
            &scene.to_string_lossy(),
            "--out",
            &out.to_string_lossy(),
            "--quiet",
        ]);
        if resume {
            c.arg("--resume");
        }
        c.stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null());
        c
    };
    let err = |e: std::io::Error| RunError::Runtime(format!("{}: {e}", xper.display()));
    let straight = dir.join("straight");
    let started = Instant::now();
    run(&straight, false).status().map_err(err)?;
    let whole = started.elapsed().as_millis() as usize;
    let (mut killed, mut endings, mut same, mut refused) = (0, 0, 0, 0);
    let split = dir.join("split");
    while killed < kills {
        let resume = split.join("checkpoint.bin").exists();
        let mut child = run(&split, resume).spawn().map_err(err)?;
        std::thread::sleep(Duration::from_millis(rng.below(whole + 1) as u64));
        match child.try_wait().map_err(err)? {
            None => {
                let _ = child.kill();
                let _ = child.wait();
                killed += 1;
            }
            Some(status) => {
                endings += 1;
                if !status.success() {
                    refused += 1;
                } else if same_outputs(&straight, &split) {
                    same += 1;
                }
                let _ = std::fs::remove_dir_all(&split);
            }
        }
    }
    let last = run(&split, split.join("checkpoint.bin").exists())
        .status()
        .map_err(err)?;
    endings += 1;
    if !last.success() {
        refused += 1;
    } else if same_outputs(&straight, &split) {
        same += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    let failed = same != endings;
    md.push_str(&format!(
        "\n| killed runs of scenes/drop (3000 steps) | kills | runs ended after resumes | \
         outputs identical to the uninterrupted run | resumes refused | result |\n\
         |---|---|---|---|---|---|\n\
         | random instants over the run's {:.1} s | {killed} | {endings} | {same} | {refused} | {} |\n",
        whole as f64 / 1e3,
        if failed { "FAIL" } else { "pass" }
    ));
    Ok(usize::from(failed))
}

/// Whether `b` holds the checkpoint, result.pvd and tables (timing columns aside) of `a`.
fn same_outputs(a: &Path, b: &Path) -> bool {
    let bytes = |dir: &Path, name: &str| std::fs::read(dir.join(name)).ok();
    let table = |dir: &Path| {
        std::fs::read_to_string(dir.join("series.csv"))
            .ok()
            .map(|t| xper_io::without_timing_columns(&t))
    };
    ["checkpoint.bin", "result.pvd"]
        .iter()
        .all(|n| bytes(a, n).is_some() && bytes(a, n) == bytes(b, n))
        && table(a).is_some()
        && table(a) == table(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_readers_survive_the_campaign_without_panics_or_hangs() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mut md = String::new();
        let failed = robustness_section(&mut md, &root, None, 0).unwrap();
        assert_eq!(failed, 0, "{md}");
        let rows: Vec<&str> = md.lines().filter(|l| l.ends_with("| pass |")).collect();
        assert!(rows.len() >= 3, "{md}");
        assert!(rows[0].starts_with("| scenes ("), "{md}");
    }
}
