//! Nothing lost, nothing trusted blindly (issue 38): an interrupted run resumed with
//! `--resume` ends with the outputs of an uninterrupted one, bit for bit, or is refused; a
//! corrupted checkpoint is refused with exit 2, never a panic, never a silent continuation.
//!
//! One scene per physics (rigid: `drop`, fluid: `single_grain_settling`, fracture:
//! `nooru_mohamed_small`), cut to a few hundred steps. `XPER_KILLS` sets the number of random
//! kills per physics (20 by default; the long form of the test is `XPER_KILLS=200`), and
//! `XPER_KILL_SCENES` (comma-separated names) keeps only some of the three scenes.

mod common;
use common::{assert_success as ok, run_scene, shipped_scene, temp_dir};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// (scene, steps, [frame every, checkpoint every])
const SCENES: [(&str, u64, [u64; 2]); 3] = [
    ("drop", 600, [50, 100]),
    ("single_grain_settling", 200, [20, 30]),
    ("nooru_mohamed_small", 60, [10, 15]),
];

/// `xper run` without its progress and lines.
fn run(scene: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    run_scene(scene, out, &[&["--quiet"], extra].concat())
}

/// A table's text without its wall-clock columns.
fn without_timing(path: &Path) -> String {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    xper_io::without_timing_columns(&text)
}

/// Fails unless `b` holds the outputs of `a`: checkpoint, tables (timing aside), result.pvd
/// and every frame file of `a`, byte for byte.
fn assert_same_outputs(a: &Path, b: &Path, what: &str) {
    let bytes = |dir: &Path, name: &str| {
        std::fs::read(dir.join(name))
            .unwrap_or_else(|e| panic!("{what}: cannot read {}: {e}", dir.join(name).display()))
    };
    for name in ["checkpoint.bin", "result.pvd"] {
        assert!(bytes(a, name) == bytes(b, name), "{what}: {name} differs");
    }
    for table in ["series.csv", "particles.csv"] {
        if a.join(table).exists() {
            assert_eq!(
                without_timing(&a.join(table)),
                without_timing(&b.join(table)),
                "{what}: {table} differs"
            );
        }
    }
    for entry in std::fs::read_dir(a.join("frames")).unwrap() {
        let name = PathBuf::from("frames").join(entry.unwrap().file_name());
        let name = name.to_str().unwrap();
        assert!(bytes(a, name) == bytes(b, name), "{what}: {name} differs");
    }
}

#[test]
fn a_kill_between_the_tables_and_the_checkpoint_resumes_to_the_same_outputs() {
    let dir = temp_dir("crash-between");
    for (name, steps, every) in SCENES {
        let scene = shipped_scene(name, steps, every, &dir);
        let (straight, split) = (dir.join(format!("{name}-a")), dir.join(format!("{name}-b")));
        ok(&run(&scene, &straight, &[]));
        let [first, second] = [every[1], 2 * every[1]].map(|s| s.to_string());
        ok(&run(&scene, &split, &["--stop-at-step", &first]));
        let early = std::fs::read(split.join("checkpoint.bin")).unwrap();
        ok(&run(
            &scene,
            &split,
            &["--resume", "--stop-at-step", &second],
        ));
        // The tables reach the second checkpoint, the checkpoint is still the first: a kill
        // after the tables were written and before the checkpoint was renamed into place.
        std::fs::write(split.join("checkpoint.bin"), early).unwrap();
        ok(&run(&scene, &split, &["--resume"]));
        assert_same_outputs(&straight, &split, name);
    }
}

#[test]
fn tables_that_end_before_their_checkpoint_are_refused() {
    let dir = temp_dir("crash-rows-lost");
    for (name, steps, every) in SCENES {
        let scene = shipped_scene(name, steps, every, &dir);
        let out = dir.join(name);
        ok(&run(
            &scene,
            &out,
            &["--stop-at-step", &(2 * every[1]).to_string()],
        ));
        let series = out.join("series.csv");
        let text = std::fs::read_to_string(&series).unwrap();
        let kept: Vec<&str> = text.lines().take(every[1] as usize).collect();
        std::fs::write(&series, kept.join("\n") + "\n").unwrap();
        let resumed = run(&scene, &out, &["--resume"]);
        let err = String::from_utf8_lossy(&resumed.stderr);
        assert_eq!(resumed.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains("series.csv") && err.contains("rows were lost"),
            "{name}: {err}"
        );
    }
}

/// A reproducible sequence of numbers in `0..n` (a linear congruential generator).
struct Lcg(u64);
impl Lcg {
    fn below(&mut self, n: u64) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) % n.max(1)
    }
}

#[test]
fn corrupted_checkpoints_are_refused_with_exit_2() {
    let dir = temp_dir("crash-corrupted");
    let mut lcg = Lcg(38);
    for (name, steps, every) in SCENES {
        let scene = shipped_scene(name, steps, every, &dir);
        let out = dir.join(name);
        ok(&run(
            &scene,
            &out,
            &["--stop-at-step", &every[1].to_string()],
        ));
        let good = std::fs::read(out.join("checkpoint.bin")).unwrap();
        let mut damaged: Vec<Vec<u8>> = Vec::new();
        for _ in 0..12 {
            let mut bad = good.clone();
            let at = lcg.below(good.len() as u64) as usize;
            bad[at] ^= 1 + lcg.below(255) as u8;
            damaged.push(bad);
        }
        for keep in [0, 7, good.len() / 2, good.len() - 1] {
            damaged.push(good[..keep].to_vec());
        }
        let mut appended = good.clone();
        appended.extend_from_slice(b"tail");
        damaged.push(appended);
        for (k, bad) in damaged.into_iter().enumerate() {
            std::fs::write(out.join("checkpoint.bin"), &bad).unwrap();
            let resumed = run(&scene, &out, &["--resume"]);
            let err = String::from_utf8_lossy(&resumed.stderr);
            assert_eq!(resumed.status.code(), Some(2), "{name}, damage {k}: {err}");
            assert!(err.contains("checkpoint.bin"), "{name}, damage {k}: {err}");
        }
    }
}

#[test]
fn random_kills_resume_to_the_uninterrupted_outputs() {
    let kills: usize = std::env::var("XPER_KILLS")
        .ok()
        .and_then(|k| k.parse().ok())
        .unwrap_or(20);
    let only = std::env::var("XPER_KILL_SCENES").ok();
    let dir = temp_dir("crash-kills");
    let mut lcg = Lcg(2026);
    let chosen = SCENES.into_iter().filter(|(name, ..)| {
        only.as_ref()
            .is_none_or(|o| o.split(',').any(|n| n == *name))
    });
    for (name, steps, every) in chosen {
        let scene = shipped_scene(name, steps, every, &dir);
        let straight = dir.join(format!("{name}-a"));
        let started = Instant::now();
        ok(&run(&scene, &straight, &[]));
        let whole = started.elapsed().as_millis() as u64;
        let split = dir.join(format!("{name}-b"));
        let mut killed = 0;
        while killed < kills {
            let resume = split.join("checkpoint.bin").exists();
            let mut args = vec!["run", scene.to_str().unwrap(), "--out"];
            args.extend([split.to_str().unwrap(), "--quiet"]);
            if resume {
                args.push("--resume");
            }
            let log = dir.join(format!("{name}-stderr.txt"));
            let mut child = Command::new(env!("CARGO_BIN_EXE_xper"))
                .args(&args)
                .stdout(Stdio::null())
                .stderr(std::fs::File::create(&log).unwrap())
                .spawn()
                .unwrap();
            std::thread::sleep(Duration::from_millis(lcg.below(whole + 1)));
            match child.try_wait().unwrap() {
                Some(status) => {
                    // It ended before the kill: check this chain of resumes, start another.
                    assert!(
                        status.success(),
                        "{name}: a run ({}) exited with {status} after {killed} kills: {}",
                        args.join(" "),
                        std::fs::read_to_string(&log).unwrap_or_default()
                    );
                    assert_same_outputs(&straight, &split, &format!("{name}, {killed} kills"));
                    std::fs::remove_dir_all(&split).unwrap();
                }
                None => {
                    child.kill().unwrap();
                    child.wait().unwrap();
                    killed += 1;
                }
            }
        }
        let last = if split.join("checkpoint.bin").exists() {
            run(&scene, &split, &["--resume"])
        } else {
            run(&scene, &split, &[])
        };
        ok(&last);
        assert_same_outputs(&straight, &split, &format!("{name} after {kills} kills"));
    }
}

/// A tmpfs mounted for a test, unmounted when dropped.
struct Tmpfs(PathBuf);

impl Tmpfs {
    /// A `size` tmpfs at `dir`, or why there cannot be one (not root, no mount).
    fn mount(dir: &Path, size: &str) -> Result<Self, String> {
        std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
        let out = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(dir)
            .output()
            .map_err(|e| format!("mount: {e}"))?;
        if !out.status.success() {
            return Err(String::from_utf8_lossy(&out.stderr).trim().to_string());
        }
        Ok(Tmpfs(dir.to_path_buf()))
    }

    fn resize(&self, size: &str) {
        let ok = Command::new("mount")
            .args(["-o", &format!("remount,size={size}")])
            .arg(&self.0)
            .status()
            .unwrap()
            .success();
        assert!(ok, "remount {}", self.0.display());
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

#[test]
fn a_full_disk_then_resume_gives_the_uninterrupted_outputs() {
    let dir = temp_dir("crash-full-disk");
    let scene = shipped_scene("drop", 1000, [10, 100], &dir);
    let disk = match Tmpfs::mount(&dir.join("disk"), "256k") {
        Ok(disk) => disk,
        Err(why) => {
            println!("skipped: no small tmpfs to fill ({why}); run as root to test a full disk");
            return;
        }
    };
    let (straight, split) = (dir.join("straight"), disk.0.join("out"));
    ok(&run(&scene, &straight, &[]));
    let full = run(&scene, &split, &[]);
    let err = String::from_utf8_lossy(&full.stderr);
    assert_eq!(
        full.status.code(),
        Some(1),
        "a 256 kB disk holds the run: {err}"
    );
    assert!(err.contains("No space left"), "{err}");
    disk.resize("64m");
    ok(&run(&scene, &split, &["--resume"]));
    assert_same_outputs(&straight, &split, "drop after a full disk");
}
