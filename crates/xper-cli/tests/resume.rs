//! `--resume` after a stop ends in exactly the state of an uninterrupted run.

mod common;
use common::{deposit_scene, temp_dir, xper};
use xper_io::SeriesTable;

#[test]
fn resume_after_stop_matches_uninterrupted_run() {
    let dir = temp_dir("resume");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, deposit_scene(120, 150)).unwrap();
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    let s = scene.to_str().unwrap();
    let out = xper(&["run", s, "--out", straight.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // Stop between two checkpoints (every 40 steps): the resume restarts from step 80.
    let out = xper(&[
        "run",
        s,
        "--out",
        split.to_str().unwrap(),
        "--stop-at-step",
        "97",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = std::fs::read_to_string(split.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"stopped\""), "{summary}");
    let out = xper(&["run", s, "--out", split.to_str().unwrap(), "--resume"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "final states differ");
    let sa = SeriesTable::read_csv(&straight.join("series.csv")).unwrap();
    let sb = SeriesTable::read_csv(&split.join("series.csv")).unwrap();
    assert_eq!(sa.rows.len(), 150);
    assert_eq!(sa.rows.len(), sb.rows.len());
    let timing = ["wall_time", "detect_time", "solve_time"];
    for (ra, rb) in sa.rows.iter().zip(&sb.rows) {
        for (k, name) in sa.columns.iter().enumerate() {
            if !timing.contains(&name.as_str()) {
                assert_eq!(
                    ra[k].to_bits(),
                    rb[k].to_bits(),
                    "column {name} at step {}",
                    ra[0]
                );
            }
        }
    }
    let pvd = std::fs::read_to_string(split.join("result.pvd")).unwrap();
    assert_eq!(
        pvd,
        std::fs::read_to_string(straight.join("result.pvd")).unwrap()
    );
}

#[test]
fn resume_refuses_a_changed_scene_and_a_missing_checkpoint() {
    let dir = temp_dir("resume-refuse");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, deposit_scene(20, 10)).unwrap();
    let out = xper(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        dir.join("none").to_str().unwrap(),
        "--resume",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("checkpoint.bin"));
    let run = dir.join("run");
    assert!(xper(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
        "--stop-at-step",
        "5"
    ])
    .status
    .success());
    std::fs::write(&scene, deposit_scene(21, 10)).unwrap();
    let out = xper(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        run.to_str().unwrap(),
        "--resume",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("different scene"));
}

/// Regression: a checkpoint written by an earlier build (layout without the tag, here the
/// scene hash first as before version 2) was deserialised with the new types; it is now refused
/// by name, with exit code 2.
#[test]
fn resume_refuses_a_checkpoint_of_another_layout() {
    let dir = temp_dir("resume-layout");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, deposit_scene(20, 10)).unwrap();
    let run = dir.join("run");
    let s = scene.to_str().unwrap();
    let args = [
        "run",
        s,
        "--out",
        run.to_str().unwrap(),
        "--stop-at-step",
        "5",
    ];
    assert!(xper(&args).status.success());
    let sealed = xper_simulation::checkpoint::open(&run, "test").unwrap();
    let (_, hash, world): (u32, u64, Vec<u8>) = bincode::deserialize(&sealed.payload).unwrap();
    let old_layout = bincode::serialize(&(hash, world)).unwrap();
    let resealed = xper_simulation::checkpoint::seal(sealed.header, &old_layout).unwrap();
    std::fs::write(run.join("checkpoint.bin"), resealed).unwrap();
    let out = xper(&["run", s, "--out", run.to_str().unwrap(), "--resume"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("checkpoint.bin") && err.contains("this version of xper"),
        "{err}"
    );
}

#[test]
fn resume_after_a_longer_duration_continues_and_lists_the_edit() {
    let dir = temp_dir("resume-compatible");
    let (scene, straight_scene) = (dir.join("scene.toml"), dir.join("straight.toml"));
    std::fs::write(&straight_scene, deposit_scene(60, 150)).unwrap();
    std::fs::write(&scene, deposit_scene(60, 100)).unwrap();
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    let ok = |args: &[&str]| {
        let out = xper(args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    ok(&[
        "run",
        straight_scene.to_str().unwrap(),
        "--out",
        straight.to_str().unwrap(),
    ]);
    let s = scene.to_str().unwrap();
    ok(&["run", s, "--out", split.to_str().unwrap()]);
    // The run ended at 100 steps; the scene now asks for 150 (and says so in a comment).
    std::fs::write(&scene, format!("# longer\n{}", deposit_scene(60, 150))).unwrap();
    let err = ok(&["run", s, "--out", split.to_str().unwrap(), "--resume"]);
    assert!(err.contains("scene.steps: 100 -> 150"), "{err}");
    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    let (a, b) = (
        xper_simulation::checkpoint::unseal(a).unwrap(),
        xper_simulation::checkpoint::unseal(b).unwrap(),
    );
    assert!(a.payload[12..] == b.payload[12..], "final states differ");
    let sa = SeriesTable::read_csv(&straight.join("series.csv")).unwrap();
    let sb = SeriesTable::read_csv(&split.join("series.csv")).unwrap();
    assert_eq!(sa.rows.len(), 150);
    let column = |t: &SeriesTable| t.column("kinetic_energy").unwrap();
    assert_eq!(column(&sa), column(&sb));
}

#[test]
fn resume_refuses_an_edit_of_the_physics_with_its_list() {
    let dir = temp_dir("resume-incompatible");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, deposit_scene(20, 10)).unwrap();
    let (s, run) = (scene.to_str().unwrap(), dir.join("run"));
    let r = run.to_str().unwrap();
    assert!(xper(&["run", s, "--out", r, "--stop-at-step", "5"])
        .status
        .success());
    let edited = deposit_scene(20, 10)
        .replace("friction = 0.3", "friction = 0.4")
        .replace("steps = 10", "steps = 20");
    std::fs::write(&scene, edited).unwrap();
    let out = xper(&["run", s, "--out", r, "--resume"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("different scene") && err.contains("laws[0].friction: 0.3 -> 0.4"),
        "{err}"
    );
    assert!(
        !err.contains("scene.steps"),
        "only what a resume cannot follow: {err}"
    );
}

/// A periodic cell with a free strain component (`periodic_bimaterial_small`: E_yy and E_xy
/// under zero stress, 120 steps): stopped between two checkpoints and resumed, it ends in the
/// uninterrupted run's state, macroscopic strain, its rate and the stresses included (the
/// checkpoint and every non-timing column of series.csv bit for bit).
#[test]
fn a_periodic_cell_resumes_bit_for_bit() {
    let dir = temp_dir("resume-periodic");
    let scene = common::shipped_scene("periodic_bimaterial_small", 120, [60, 40], &dir);
    let s = scene.to_str().unwrap();
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    for args in [
        vec!["run", s, "--out", straight.to_str().unwrap()],
        vec![
            "run",
            s,
            "--out",
            split.to_str().unwrap(),
            "--stop-at-step",
            "57",
        ],
        vec!["run", s, "--out", split.to_str().unwrap(), "--resume"],
    ] {
        common::assert_success(&xper(&args));
    }
    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "final states differ");
    let sa = SeriesTable::read_csv(&straight.join("series.csv")).unwrap();
    let sb = SeriesTable::read_csv(&split.join("series.csv")).unwrap();
    assert_eq!((sa.rows.len(), sb.rows.len()), (120, 120));
    let strain_yy = sa.columns.iter().position(|c| c == "strain_yy").unwrap();
    assert!(
        sa.rows[119][strain_yy] != 0.0,
        "the free component must move"
    );
    for (ra, rb) in sa.rows.iter().zip(&sb.rows) {
        for (k, name) in sa.columns.iter().enumerate() {
            if !["wall_time", "solve_time"].contains(&name.as_str()) {
                assert_eq!(ra[k].to_bits(), rb[k].to_bits(), "{name} at step {}", ra[0]);
            }
        }
    }
}
