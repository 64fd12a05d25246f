//! `xper run` with `[solver] kind = "newton"`, and `[output] dump_problems`: the dumped
//! FCLib file holds exactly the problem of that step, which the solvers of `xper_solver` solve.

mod common;
use common::{temp_dir, xper};
use xper_io::SeriesTable;

/// A few dozen disks falling into a box and settling, with friction.
fn scene(kind: &str, steps: u64, dumps: &[u64]) -> String {
    format!(
        "[scene]\nname = \"dumps\"\ndt = 2e-4\nsteps = {steps}\nalert_distance = 5e-4\n\n\
         [solver]\nkind = \"{kind}\"\ntolerance = 1e-10\n\n\
         [output]\nframe_every = {steps}\ncheckpoint_every = {steps}\ndump_problems = {dumps:?}\n\n\
         [[materials]]\nname = \"glass\"\ndensity = 2500.0\n\n\
         [[laws]]\nbetween = [\"grains\", \"grains\"]\nkind = \"signorini_coulomb\"\nfriction = 0.3\n\n\
         [[laws]]\nbetween = [\"grains\", \"walls\"]\nkind = \"signorini_coulomb\"\nfriction = 0.5\n\n\
         [[generators]]\nkind = \"box_of_disks\"\ncount = 40\nradius = [0.002, 0.003]\n\
         box = [[0.0, 0.0], [0.03, 0.08]]\nplacement = \"random\"\nseed = 3\nmaterial = \"glass\"\n\
         group = \"grains\"\nwalls = \"walls\"\n"
    )
}

fn run_ok(scene: &std::path::Path, out: &std::path::Path) {
    let o = xper(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn newton_run_fills_series_and_summary() {
    let dir = temp_dir("newton_run");
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene("newton", 150, &[])).unwrap();
    let out = dir.join("out");
    run_ok(&path, &out);
    let series = SeriesTable::read_csv(&out.join("series.csv")).unwrap();
    let col = |name: &str| series.column(name).unwrap();
    let (iterations, residual, converged) = (col("iterations"), col("residual"), col("converged"));
    assert_eq!(iterations.len(), 150);
    // Newton converges in a few iterations on these small, loose problems.
    assert!(converged.iter().all(|&c| c == 1.0), "{converged:?}");
    assert!(
        residual.iter().all(|&r| (0.0..1e-10).contains(&r)),
        "{residual:?}"
    );
    assert!(iterations.iter().any(|&i| i >= 1.0));
    assert!(iterations.iter().all(|&i| i <= 20.0), "{iterations:?}");
    assert!(col("active_contacts").iter().any(|&c| c >= 10.0));
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    for needle in [
        "\"solver\": \"newton\"",
        "\"status\": \"completed\"",
        "\"non_converged_steps\": 0",
    ] {
        assert!(summary.contains(needle), "{needle} not in {summary}");
    }
    assert!(!out.join("problems").exists());

    // The same scene under NLGS ends in nearly the same state: both solve each step's
    // problem to 1e-10 (natural map, Siconos' scaling, for NLGS too).
    let nlgs = scene("nlgs", 150, &[]).replace(
        "tolerance = 1e-10\n",
        "tolerance = 1e-10\nnorm = \"natural_map\"\nmax_iterations = 100000\ncheck_every = 1\n",
    );
    std::fs::write(&path, nlgs).unwrap();
    let out_nlgs = dir.join("out_nlgs");
    run_ok(&path, &out_nlgs);
    let other = SeriesTable::read_csv(&out_nlgs.join("series.csv")).unwrap();
    let (ka, kb) = (
        col("kinetic_energy"),
        other.column("kinetic_energy").unwrap(),
    );
    let worst = ka
        .iter()
        .zip(&kb)
        .map(|(a, b)| (a - b).abs() / a.abs().max(1e-12))
        .fold(0.0, f64::max);
    println!("kinetic energy, newton vs nlgs: largest relative difference {worst:.3e}");
    assert!(
        worst < 1e-8,
        "kinetic energies differ by {worst:.3e} (relative)"
    );
}

#[test]
fn newton_run_resumes_exactly() {
    let dir = temp_dir("newton_resume");
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene("newton", 120, &[])).unwrap();
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    run_ok(&path, &straight);
    let (p, o) = (path.to_str().unwrap(), split.to_str().unwrap());
    assert!(xper(&["run", p, "--out", o, "--stop-at-step", "77"])
        .status
        .success());
    assert!(xper(&["run", p, "--out", o, "--resume"]).status.success());
    // The solver choice and the warm start are in the checkpoint: same final state.
    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "final states differ");
}

#[cfg(not(feature = "hdf5"))]
#[test]
fn dumps_need_hdf5() {
    let dir = temp_dir("dumps_no_hdf5");
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene("nlgs", 20, &[5])).unwrap();
    let out = dir.join("out");
    let o = xper(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("dump_problems: built without HDF5 support: rebuild with --features hdf5"),
        "{err}"
    );
    assert!(
        !out.join("series.csv").exists(),
        "refused before the first step"
    );
}

#[cfg(feature = "hdf5")]
#[test]
fn dumped_problem_is_the_problem_of_that_step() {
    use xper_nscd::MoreauJean;
    use xper_simulation::rigid::build::world_from_scene;
    use xper_simulation::rigid::outputs::problem_path;
    use xper_solver::{solve, SolverKind, SolverParams};

    let dir = temp_dir("dumps");
    let path = dir.join("scene.toml");
    let dumps = [200, 400];
    std::fs::write(&path, scene("newton", 400, &dumps)).unwrap();
    let out = dir.join("out");
    run_ok(&path, &out);

    // Independent path: the scene stepped in this process to the step before, then the
    // problem its next step would solve.
    let scene = xper_scene::load_scene(&path).unwrap();
    let mut world = world_from_scene(&scene);
    let mut stepper = MoreauJean::new();
    for step in dumps {
        while world.step + 1 < step {
            stepper.step(&mut world).unwrap();
        }
        let expected = stepper.next_problem(&world).unwrap();
        let file = problem_path(&out, step);
        assert!(file.ends_with(format!("problems/step_000{step}.hdf5")));
        let got = xper_fclib::read_fclib_local(&file).unwrap();
        assert!(
            got.contact_count() >= 20,
            "{} contacts",
            got.contact_count()
        );
        assert!(got.mu.contains(&0.3) && got.q.iter().any(|&q| q < 0.0));
        assert!(
            got == expected,
            "step {step}: the file differs from the step's problem"
        );

        for kind in [SolverKind::Newton, SolverKind::Nlgs] {
            let report = solve(&got, &SolverParams::with_kind(kind), None).unwrap();
            let e = report.error.relative_max;
            assert!(
                report.converged && e < 1e-8,
                "step {step}, {kind:?}: {e:.3e}"
            );
        }
    }
    let files: Vec<_> = std::fs::read_dir(out.join("problems"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(files.len(), 2, "{files:?}");
}
