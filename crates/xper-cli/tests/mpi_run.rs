//! `mpirun -np N xper run` (binary built with `--features mpi`) against the run on one process,
//! on a deposit of 400 disks (random placement, so bodies fall across the cuts and migrate).
//!
//! The measure: the largest distance between a body's positions in two runs after 300 steps (0.06 s: the lower disks land and collide).
//! NLGS stops at its tolerance, not at the solution, so the scale is the serial run's own error,
//! estimated as its distance to the serial run at a tolerance ten times smaller. Every mpirun
//! is under `timeout`, so a hang fails the test instead of the CI job.
#![cfg(feature = "mpi")]

mod common;

use common::{assert_success, deposit_scene, temp_dir, xper};
use std::path::Path;
use std::process::{Command, Output};
use xper_nscd::World;

/// Open MPI's settings for these runs: as root, more processes than cores, yielding when idle.
fn with_mpi_env(command: &mut Command) -> &mut Command {
    command
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_rmaps_base_oversubscribe", "1")
        .env("OMPI_MCA_mpi_yield_when_idle", "1")
}

fn mpirun(ranks: usize, args: &[&str]) -> Output {
    with_mpi_env(
        Command::new("timeout")
            .args(["300", "mpirun", "-np", &ranks.to_string()])
            .arg(env!("CARGO_BIN_EXE_xper"))
            .args(args),
    )
    .output()
    .expect("mpirun could not be started (is openmpi-bin installed?)")
}

/// The payload of `dir/checkpoint.bin`, its envelope verified.
fn payload(dir: &Path) -> Vec<u8> {
    xper_simulation::checkpoint::open(dir, "test")
        .unwrap()
        .payload
}

fn checkpoint(dir: &Path) -> World {
    let bytes = payload(dir);
    let (_, _, world): (u32, u64, Vec<u8>) = bincode::deserialize(&bytes).unwrap();
    World::from_bytes(&world).unwrap()
}

fn distance(a: &World, b: &World) -> f64 {
    assert_eq!(a.step, b.step);
    (0..a.bodies.len())
        .map(|k| (a.bodies.position[k] - b.bodies.position[k]).norm())
        .fold(0.0, f64::max)
}

/// `xper run scene --out out --quiet extra..`: the plain binary for `ranks` 0, else under
/// `mpirun -np ranks`; it must succeed.
fn run_xper(ranks: usize, scene: &Path, out: &Path, extra: &[&str]) {
    let (scene, out) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let mut args = vec!["run", scene, "--out", out, "--quiet"];
    args.extend_from_slice(extra);
    assert_success(&if ranks == 0 {
        xper(&args)
    } else {
        mpirun(ranks, &args)
    });
}

fn run(ranks: usize, scene: &Path, out: &Path, extra: &[&str]) -> World {
    run_xper(ranks, scene, out, extra);
    checkpoint(out)
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// Checks the summary of a distributed run in `out` with `--compare-serial`: its process
/// count, the difference it reports (`difference`, measured by the test), a positive
/// efficiency, and `owned` bodies owned once over the ranks. Returns the summary.
fn assert_distributed_summary(
    out: &Path,
    processes: usize,
    difference: f64,
    owned: u64,
) -> serde_json::Value {
    let summary = summary(out);
    assert_eq!(summary["processes"], processes);
    let comparison = &summary["serial_comparison"];
    let reported = comparison["max_position_difference_m"].as_f64().unwrap();
    assert!(
        (reported - difference).abs() <= 1e-15,
        "--compare-serial: {reported:e} vs {difference:e}"
    );
    assert!(comparison["efficiency"].as_f64().unwrap() > 0.0);
    let counted: u64 = (summary["ranks"].as_array().unwrap().iter())
        .map(|r| r["bodies"].as_u64().unwrap())
        .sum();
    assert_eq!(counted, owned, "every body owned by one process");
    summary
}

/// Frames listed in `result.pvd` (one data set per part and step).
fn data_sets(out: &Path) -> usize {
    let pvd = std::fs::read_to_string(out.join("result.pvd")).unwrap();
    pvd.matches("<DataSet").count()
}

#[test]
fn mpirun_xper_run_agrees_with_the_serial_run_and_resumes_on_another_count() {
    let dir = temp_dir("mpi_run");
    let text = deposit_scene(400, 300);
    let scene = dir.join("deposit.toml");
    std::fs::write(&scene, &text).unwrap();
    let finer = dir.join("deposit_finer.toml");
    std::fs::write(
        &finer,
        text.replace(
            "[[materials]]",
            "[solver]\ntolerance = 1.666e-5\n\n[[materials]]",
        ),
    )
    .unwrap();
    // 0: the plain binary on this process.
    let serial = run(0, &scene, &dir.join("serial"), &[]);
    let spread = distance(&serial, &run(0, &finer, &dir.join("finer"), &[]));
    assert!(spread > 0.0, "the two tolerances gave the same run");
    let one = run(1, &scene, &dir.join("np1"), &[]);
    assert_eq!(one.bodies.position, serial.bodies.position, "mpirun -np 1");
    for ranks in [2, 4] {
        let out = dir.join(format!("np{ranks}"));
        let world = run(ranks, &scene, &out, &["--compare-serial"]);
        let d = distance(&world, &serial);
        eprintln!("{ranks} processes: {d:.3e} m from serial (serial error {spread:.3e} m)");
        assert!(
            d <= 10.0 * spread,
            "{ranks} processes: {d:.3e} m vs {spread:.3e} m"
        );
        assert_distributed_summary(&out, ranks, d, 400);
        assert_eq!(data_sets(&out), 3 * 7, "frames at 0, 50, ..., 300");
    }
    // Stopped at step 160 on 2 processes, resumed on 4 and on this process alone.
    let stopped = dir.join("resumed_np4");
    run(2, &scene, &stopped, &["--stop-at-step", "160"]);
    let copy = dir.join("resumed_serial");
    std::fs::create_dir_all(&copy).unwrap();
    for file in ["checkpoint.bin", "series.csv", "result.pvd"] {
        std::fs::copy(stopped.join(file), copy.join(file)).unwrap();
    }
    let on_four = run(4, &scene, &stopped, &["--resume"]);
    let on_one = run(0, &scene, &copy, &["--resume"]);
    let whole = checkpoint(&dir.join("np2"));
    for (name, world) in [("4 processes", &on_four), ("one process", &on_one)] {
        let d = distance(world, &whole);
        eprintln!("resumed on {name}: {d:.3e} m from the run on 2 (serial error {spread:.3e} m)");
        assert!(d <= 10.0 * spread, "resumed on {name}: {d:.3e} m");
    }
    let series = std::fs::read_to_string(stopped.join("series.csv")).unwrap();
    assert_eq!(
        series.lines().count(),
        301,
        "header and one row per step after the resume"
    );
}

#[test]
fn what_a_distributed_run_cannot_do_is_refused_on_every_process() {
    let dir = temp_dir("mpi_refused");
    let scene = dir.join("newton.toml");
    std::fs::write(
        &scene,
        deposit_scene(50, 10).replace(
            "[[materials]]",
            "[solver]\nkind = \"newton\"\n\n[[materials]]",
        ),
    )
    .unwrap();
    refused_on_two_processes(
        &scene,
        &dir,
        "newton.toml: [solver] kind: a distributed run solves by NLGS only",
    );
    // A 3D servo wall: its area follows walls another process may hold.
    let walls = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/compaction_walls_3d");
    let text = std::fs::read_to_string(walls.join("scene.toml")).unwrap();
    let scene = dir.join("servo3d.toml");
    std::fs::write(&scene, text.replace("count = 1000", "count = 20")).unwrap();
    refused_on_two_processes(
        &scene,
        &dir,
        "servo3d.toml: body 1 is driven by a pressure, which runs on one process only for now",
    );
}

/// Regression: under `mpirun` a process's stdout is the terminal and its stderr a pipe, and
/// the progress bar and final message, shown only when stderr was a terminal, never appeared.
/// `script` gives mpirun a terminal; rank 0 must then draw the bar and say it completed.
#[test]
fn the_progress_bar_shows_on_rank_0_when_mpirun_has_a_terminal() {
    let dir = temp_dir("mpi_progress");
    let scene = dir.join("deposit.toml");
    std::fs::write(&scene, deposit_scene(50, 20)).unwrap();
    let (out, typescript) = (dir.join("out"), dir.join("typescript"));
    let command = format!(
        "timeout 300 mpirun -np 2 {} run {} --out {}",
        env!("CARGO_BIN_EXE_xper"),
        scene.display(),
        out.display()
    );
    let status = with_mpi_env(
        Command::new("script")
            .args(["-qec", &command])
            .arg(&typescript),
    )
    .output()
    .expect("script (util-linux) runs");
    assert_success(&status);
    let text = String::from_utf8_lossy(&std::fs::read(&typescript).unwrap()).into_owned();
    assert!(text.contains("20/20 steps"), "no progress bar in:\n{text}");
    assert!(
        text.contains("completed: 20 of 20 steps"),
        "no final message in:\n{text}"
    );
}

/// The coarse Nooru-Mohamed scene cut to 400 steps (cracks start from both notches), with
/// the tolerance `tolerance`.
fn fracture_scene(dir: &Path, name: &str, tolerance: &str) -> std::path::PathBuf {
    let source =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/nooru_mohamed_small/scene.toml");
    let text = std::fs::read_to_string(source)
        .unwrap()
        .replace("steps = 1500", "steps = 400")
        .replace("frame_every = 50", "frame_every = 100")
        .replace("checkpoint_every = 500", "checkpoint_every = 200")
        .replace("tolerance = 1.666e-4", &format!("tolerance = {tolerance}"));
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn fracture_run(ranks: usize, scene: &Path, out: &Path, extra: &[&str]) -> Vec<[f64; 6]> {
    run_xper(ranks, scene, out, extra);
    xper_simulation::fracture::checkpoint::checkpoint_displacements(out)
        .unwrap()
        .1
}

fn displacement_difference(a: &[[f64; 6]], b: &[[f64; 6]]) -> f64 {
    assert_eq!(a.len(), b.len());
    (a.iter().zip(b))
        .flat_map(|(x, y)| (0..6).map(|d| (x[d] - y[d]).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn mpirun_fracture_run_agrees_with_the_serial_run_and_resumes_on_another_count() {
    let dir = temp_dir("mpi_fracture");
    let scene = fracture_scene(&dir, "nm.toml", "1.666e-4");
    let finer = fracture_scene(&dir, "nm_finer.toml", "1.666e-6");
    let serial = fracture_run(0, &scene, &dir.join("serial"), &[]);
    let spread =
        displacement_difference(&serial, &fracture_run(0, &finer, &dir.join("finer"), &[]));
    assert!(spread > 0.0, "the two tolerances gave the same run");
    let one = fracture_run(1, &scene, &dir.join("np1"), &[]);
    assert_eq!(one, serial, "mpirun -np 1");
    let out = dir.join("np2");
    let two = fracture_run(2, &scene, &out, &["--compare-serial"]);
    let d = displacement_difference(&two, &serial);
    eprintln!("fracture on 2 processes: {d:.3e} m from serial (serial error {spread:.3e} m)");
    assert!(
        d <= 10.0 * spread,
        "2 processes: {d:.3e} m vs {spread:.3e} m"
    );
    let elements = summary(&out)["elements"].as_u64().unwrap();
    let summary = assert_distributed_summary(&out, 2, d, elements);
    assert_eq!(
        summary["final_broken_points"],
        self::summary(&dir.join("serial"))["final_broken_points"]
    );
    assert_eq!(data_sets(&out), 2 * 5, "frames at 0, 100, ..., 400");
    // Stopped at step 200 on 2 processes, resumed on 3.
    let stopped = dir.join("resumed_np3");
    fracture_run(2, &scene, &stopped, &["--stop-at-step", "200"]);
    let resumed = fracture_run(3, &scene, &stopped, &["--resume"]);
    let d = displacement_difference(&resumed, &two);
    eprintln!("fracture resumed on 3 processes: {d:.3e} m from the run on 2");
    assert!(
        d <= 10.0 * spread,
        "resumed on 3: {d:.3e} m vs {spread:.3e} m"
    );
    let series = std::fs::read_to_string(stopped.join("series.csv")).unwrap();
    assert_eq!(
        series.lines().count(),
        401,
        "header and one row per step after the resume"
    );
}

/// The periodic bimaterial cell (`scenes/periodic_bimaterial_small`: E_xx imposed,
/// Sigma_yy = Sigma_xy = 0, so E_yy and E_xy are free) cut to 600 steps (E_xx = 1.2e-3, the
/// matrix not yet yielding), with the tolerance `tolerance`.
fn periodic_scene(dir: &Path, name: &str, tolerance: &str) -> std::path::PathBuf {
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/periodic_bimaterial_small/scene.toml");
    let text = std::fs::read_to_string(source)
        .unwrap()
        .replace("steps = 5000", "steps = 600")
        .replace("frame_every = 250", "frame_every = 300")
        .replace("checkpoint_every = 1000", "checkpoint_every = 300");
    let text: String = (text.lines())
        .map(|line| match line.starts_with("tolerance =") {
            true => format!("tolerance = {tolerance}\n"),
            false => format!("{line}\n"),
        })
        .collect();
    assert!(text.contains(&format!("tolerance = {tolerance}\n")));
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The macroscopic strain a periodic run in `out` ended with.
fn cell_strain(out: &Path) -> Vec<f64> {
    (summary(out)["cell"]["strain"].as_array().unwrap().iter())
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// A periodic cell under a macroscopic stress on 2 processes: the free strain components are
/// shared by both processes' solvers; displacements and the free strains agree with the
/// serial run within 10 times the serial run's own error (its difference with a run at a
/// hundredth of the tolerance).
#[test]
fn mpirun_periodic_cell_under_a_macroscopic_stress_agrees_with_the_serial_run() {
    let dir = temp_dir("mpi_periodic");
    let scene = periodic_scene(&dir, "cell.toml", "1.666e-4");
    let finer = periodic_scene(&dir, "cell_finer.toml", "1.666e-6");
    let serial = fracture_run(0, &scene, &dir.join("serial"), &[]);
    let spread =
        displacement_difference(&serial, &fracture_run(0, &finer, &dir.join("finer"), &[]));
    let strain_spread = (cell_strain(&dir.join("serial")).iter())
        .zip(cell_strain(&dir.join("finer")))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let out = dir.join("np2");
    let two = fracture_run(2, &scene, &out, &["--compare-serial"]);
    let d = displacement_difference(&two, &serial);
    let strain = (cell_strain(&out).iter())
        .zip(cell_strain(&dir.join("serial")))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "periodic cell on 2 processes: {d:.3e} m from serial (serial error {spread:.3e} m), \
         strain {strain:.3e} (serial error {strain_spread:.3e})"
    );
    assert!(d <= 10.0 * spread, "{d:.3e} m vs {spread:.3e} m");
    let e_xx = cell_strain(&out)[0];
    assert!(strain <= 10.0 * strain_spread.max(1e-9 * e_xx));
    assert!(
        cell_strain(&out)[1] < -0.1 * e_xx,
        "E_yy follows Sigma_yy = 0"
    );
    let elements = summary(&out)["elements"].as_u64().unwrap();
    assert_distributed_summary(&out, 2, d, elements);
}

/// The two-grain sedimentation scene at 8 cells per diameter (32 x 320 cells) cut to 300
/// steps, with the pressure tolerance `tolerance` (the grains fall about 0.2 mm).
fn two_grains_scene(dir: &Path, name: &str, tolerance: &str) -> std::path::PathBuf {
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/two_grains_sedimentation/scene.toml");
    let text = std::fs::read_to_string(source)
        .unwrap()
        .replace("duration = 2.0", "duration = 0.03")
        .replace("frame_every = 200", "frame_every = 100")
        .replace("checkpoint_every = 2000", "checkpoint_every = 100")
        .replace(
            "cells_per_diameter = 16",
            &format!("cells_per_diameter = 8\npressure_tolerance = {tolerance}"),
        );
    let scene = dir.join(name);
    std::fs::write(&scene, text).unwrap();
    scene
}

/// The grains' positions in the checkpoint of a fluid run.
fn grains(dir: &Path) -> Vec<f64> {
    let bytes = payload(dir);
    let (_, _, state): (u32, u64, xper_fluid::CoupledState) = bincode::deserialize(&bytes).unwrap();
    (state.world.bodies.position.iter())
        .flat_map(|p| [p.x, p.y])
        .collect()
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The grid cut into blocks of rows: 2 and 4 processes (grains across the cuts) against the
/// serial run, the serial error measured at pressure tolerances 1e-5 and 1e-7; stopped on 2
/// and resumed on 3.
#[test]
fn mpirun_fluid_run_agrees_with_the_serial_run_and_resumes_on_another_count() {
    let dir = temp_dir("mpi_fluid");
    let scene = two_grains_scene(&dir, "grains.toml", "1e-5");
    let finer = two_grains_scene(&dir, "grains_finer.toml", "1e-7");
    run_xper(0, &scene, &dir.join("serial"), &[]);
    run_xper(0, &finer, &dir.join("finer"), &[]);
    let serial = grains(&dir.join("serial"));
    let spread = largest_difference(&serial, &grains(&dir.join("finer")));
    assert!(spread > 0.0, "the two tolerances gave the same run");
    for ranks in [2, 4] {
        let out = dir.join(format!("np{ranks}"));
        run_xper(ranks, &scene, &out, &["--compare-serial"]);
        let d = largest_difference(&grains(&out), &serial);
        eprintln!("{ranks} processes: {d:.3e} m from serial (serial error {spread:.3e} m)");
        assert!(
            d <= 10.0 * spread,
            "{ranks} processes: {d:.3e} m vs {spread:.3e} m"
        );
        let summary = summary(&out);
        assert_eq!(summary["processes"], ranks);
        let cells: u64 = (summary["ranks"].as_array().unwrap().iter())
            .map(|r| r["cells"].as_u64().unwrap())
            .sum();
        assert_eq!(cells, 32 * 320, "every cell held by one process");
        let reported = summary["serial_comparison"]["max_position_difference_m"]
            .as_f64()
            .unwrap();
        assert!(reported <= 10.0 * spread, "--compare-serial: {reported:e}");
        assert_eq!(data_sets(&out), 3 * 4, "frames at 0, 100, 200, 300");
    }
    let stopped = dir.join("resumed");
    run_xper(2, &scene, &stopped, &["--stop-at-step", "100"]);
    run_xper(3, &scene, &stopped, &["--resume"]);
    let d = largest_difference(&grains(&stopped), &serial);
    assert!(
        d <= 10.0 * spread,
        "resumed on 3: {d:.3e} m vs {spread:.3e} m"
    );
    let series = std::fs::read_to_string(stopped.join("series.csv")).unwrap();
    assert_eq!(series.lines().count(), 301, "header and one row per step");
}

/// Glowinski's channel (160 x 640 cells) on 16 processes: 40-row blocks whose pressure levels
/// get too thin at 20 x 80 and are re-cut onto 8 of them, so rank 0 relaxes the 10 x 40 grid
/// (400 cells; 1,600 without the agglomeration). 50 steps agree with the serial run within the
/// serial run's own error (pressure tolerances 1e-8 and 1e-6).
#[test]
fn mpirun_fluid_run_with_agglomerated_pressure_levels_agrees_with_the_serial_run() {
    let dir = temp_dir("mpi_fluid_agglomerated");
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/glowinski_sedimentation/scene.toml");
    let text = std::fs::read_to_string(source).unwrap();
    let scene_with = |name: &str, tolerance: &str| {
        let scene = dir.join(name);
        let edited = text
            .replace("duration = 5.0", "duration = 0.05")
            .replace("frame_every = 200", "frame_every = 50")
            .replace("checkpoint_every = 2000", "checkpoint_every = 50")
            .replace(
                "cells_per_diameter = 16",
                &format!("cells_per_diameter = 16\npressure_tolerance = {tolerance}"),
            );
        std::fs::write(&scene, edited).unwrap();
        scene
    };
    let (scene, coarser) = (scene_with("g.toml", "1e-8"), scene_with("g6.toml", "1e-6"));
    run_xper(0, &scene, &dir.join("serial"), &[]);
    run_xper(0, &coarser, &dir.join("coarser"), &[]);
    let serial = grains(&dir.join("serial"));
    let spread = largest_difference(&serial, &grains(&dir.join("coarser")));
    assert!(spread > 0.0, "the two tolerances gave the same run");
    let out = dir.join("np16");
    run_xper(16, &scene, &out, &[]);
    let d = largest_difference(&grains(&out), &serial);
    assert!(
        d <= 10.0 * spread,
        "16 processes: {d:.3e} m vs {spread:.3e} m"
    );
    assert_eq!(summary(&out)["pressure_gathered_cells"], 400);
}

/// `mpirun -np 2 xper run scene` exits with code 2 and a message containing `expected`.
fn refused_on_two_processes(scene: &Path, out: &Path, expected: &str) {
    let (scene, out) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let output = mpirun(2, &["run", scene, "--out", out]);
    assert_eq!(output.status.code(), Some(2));
    let text = String::from_utf8_lossy(&output.stderr);
    assert!(text.contains(expected), "{text}");
}
