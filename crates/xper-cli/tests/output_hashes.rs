//! Output-hash regression test: every shipped scene, cut to a few steps, must give the same
//! `series.csv` (timing columns aside) and the same last frame, byte for byte, as when the
//! hashes in `output_hashes.txt` were recorded.
//!
//! A refactor must leave every hash unchanged. When the physics changes on purpose, refresh
//! the file with
//!
//! ```sh
//! XPER_UPDATE_HASHES=1 cargo test --release -p xper-cli --all-features --test output_hashes
//! ```
//!
//! (without the `mpi` feature the two-process list, `output_hashes_mpi.txt`, is left as it is).
//!
//! and say in the commit which scenes changed and why. The file lists, per scene, the number
//! of steps run; a scene directory missing from it fails the test, so a new scene cannot be
//! forgotten (add a line `name steps - -` and refresh).

mod common;
use std::path::{Path, PathBuf};

/// FNV-1a, 64 bits: a stable hash (std's `DefaultHasher` may change between Rust releases).
fn fnv1a(bytes: &[u8], mut hash: u64) -> u64 {
    for &b in bytes {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    hash
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The hash of series.csv without its timing columns.
fn series_hash(path: &Path) -> u64 {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let mut lines = text.lines();
    let header: Vec<&str> = lines
        .next()
        .expect("series.csv has a header")
        .split(',')
        .collect();
    let keep: Vec<bool> = header
        .iter()
        .map(|c| !xper_io::is_timing_column(c))
        .collect();
    let mut hash = FNV_OFFSET;
    for line in std::iter::once(header.join(",").as_str()).chain(lines) {
        for (field, keep) in line.split(',').zip(&keep) {
            if *keep {
                hash = fnv1a(field.as_bytes(), hash);
                hash = fnv1a(b",", hash);
            }
        }
        hash = fnv1a(b"\n", hash);
    }
    hash
}

/// The hash of every file of the last frame (the highest step number in `frames/`), in name
/// order, with the number of rows of series.csv checked by the caller.
fn last_frame_hash(frames: &Path) -> (u64, String) {
    let mut files: Vec<(u64, String)> = std::fs::read_dir(frames)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", frames.display()))
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter_map(|name| {
            let digits: String = name.chars().filter(char::is_ascii_digit).collect();
            digits.parse::<u64>().ok().map(|step| (step, name))
        })
        .collect();
    let last = files
        .iter()
        .map(|(s, _)| *s)
        .max()
        .expect("at least one frame");
    files.retain(|(s, _)| *s == last);
    files.sort();
    let mut hash = FNV_OFFSET;
    let mut names = Vec::new();
    for (_, name) in &files {
        hash = fnv1a(name.as_bytes(), hash);
        hash = fnv1a(&std::fs::read(frames.join(name)).unwrap(), hash);
        names.push(name.clone());
    }
    (hash, names.join("+"))
}

struct Entry {
    scene: String,
    steps: u64,
    series: String,
    frame: String,
}

fn read_entries(path: &Path) -> Vec<Entry> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            assert_eq!(f.len(), 4, "{}: bad line `{l}`", path.display());
            Entry {
                scene: f[0].into(),
                steps: f[1].parse().unwrap(),
                series: f[2].into(),
                frame: f[3].into(),
            }
        })
        .collect()
}

/// Runs `xper run` on the reduced scene, on one process or under `mpirun -np ranks`.
fn run_xper(scene: &Path, out: &Path, ranks: usize) -> std::process::Output {
    let args = [
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ];
    let mut command = if ranks == 1 {
        std::process::Command::new(env!("CARGO_BIN_EXE_xper"))
    } else {
        let mut c = std::process::Command::new("timeout");
        c.args([
            "600",
            "mpirun",
            "-np",
            &ranks.to_string(),
            env!("CARGO_BIN_EXE_xper"),
        ])
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_rmaps_base_oversubscribe", "1")
        .env("OMPI_MCA_mpi_yield_when_idle", "1");
        c
    };
    command.args(args).output().expect("xper runs")
}

/// Checks (or, with `XPER_UPDATE_HASHES`, rewrites) the hashes listed in `tests/LIST` of runs
/// on `ranks` processes; with `every_scene`, every shipped scene must be listed.
fn check_hashes(list: &str, ranks: usize, every_scene: bool) {
    let list = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join(list);
    let mut entries = read_entries(&list);
    let mut shipped: Vec<String> = std::fs::read_dir(repo_root().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.path().join("scene.toml").is_file())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    shipped.sort();
    let listed: Vec<String> = entries.iter().map(|e| e.scene.clone()).collect();
    let missing: Vec<&String> = shipped.iter().filter(|s| !listed.contains(s)).collect();
    assert!(
        !every_scene || missing.is_empty(),
        "scenes without a recorded hash in {}: {missing:?}",
        list.display()
    );

    let update = std::env::var_os("XPER_UPDATE_HASHES").is_some();
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("output-hashes-{ranks}"));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let mut failures = Vec::new();
    for entry in &mut entries {
        let scene = common::shipped_scene(&entry.scene, entry.steps, [entry.steps; 2], &tmp);
        let out = tmp.join(&entry.scene);
        let started = std::time::Instant::now();
        let run = run_xper(&scene, &out, ranks);
        assert!(
            run.status.success(),
            "{}: exit {:?}\n{}",
            entry.scene,
            run.status.code(),
            String::from_utf8_lossy(&run.stderr)
        );
        let mut series = series_hash(&out.join("series.csv"));
        let micro = out.join("micro.csv");
        if micro.exists() {
            series = fnv1a(&std::fs::read(&micro).unwrap(), series);
        }
        let series = format!("{series:016x}");
        let (frame, files) = last_frame_hash(&out.join("frames"));
        let frame = format!("{frame:016x}");
        eprintln!(
            "{:28} {:6} steps {:6.1} s  series {series}  frame {frame} ({files})",
            entry.scene,
            entry.steps,
            started.elapsed().as_secs_f64()
        );
        if series != entry.series || frame != entry.frame {
            failures.push(format!(
                "{}: series {} (recorded {}), last frame {} (recorded {})",
                entry.scene, series, entry.series, frame, entry.frame
            ));
        }
        entry.series = series;
        entry.frame = frame;
        // One scene's outputs at a time: box1m's frames alone take 1.5 GB, and CI disks are small.
        let _ = std::fs::remove_dir_all(&out);
    }
    let _ = std::fs::remove_dir_all(&tmp);
    if update {
        let mut text = format!(
            "# scene, steps run, FNV-1a of series.csv without timing columns (then of micro.csv where\n\
             # written), of the last frame\n\
             # ({ranks} process(es)). Refresh: XPER_UPDATE_HASHES=1 cargo test --release -p xper-cli \
             --all-features --test output_hashes\n",
        );
        for e in &entries {
            text.push_str(&format!(
                "{} {} {} {}\n",
                e.scene, e.steps, e.series, e.frame
            ));
        }
        std::fs::write(&list, text).unwrap();
        return;
    }
    assert!(
        failures.is_empty(),
        "outputs changed:\n{}",
        failures.join("\n")
    );
}

#[test]
fn every_shipped_scene_gives_its_recorded_outputs() {
    check_hashes("output_hashes.txt", 1, true);
}

/// Distributed runs are deterministic too: the same scenes on two processes.
#[cfg(feature = "mpi")]
#[test]
fn distributed_runs_give_their_recorded_outputs() {
    check_hashes("output_hashes_mpi.txt", 2, false);
}
