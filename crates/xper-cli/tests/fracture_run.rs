//! `xper check` / `xper run` on fracture scenes: malformed scenes exit 2 with file, line,
//! field and reason; a run writes frames that read back, a consistent series, valid PNGs and
//! a summary; a resumed run ends in the state of an uninterrupted one; a blow-up exits 1.

mod common;
use common::{assert_success as assert_ok, run_scene as run, temp_dir, xper};
use std::path::Path;
use xper_io::{read_vtu, DataValues, PvdCollection, SeriesTable, UnstructuredGrid};

/// The Nooru-Mohamed specimen, coarse (h = 20 mm), 40 steps.
const NOTCHED: &str = r#"[scene]
name = "tiny_notched"
dt = 2e-7
steps = 40
gravity = [0.0, 0.0]

[output]
frame_every = 20
checkpoint_every = 15

[fracture]
thickness = 0.05

[mesh]
generator = "double_edge_notched"
side = 0.2
notch_depth = 0.025
notch_width = 0.005
element_size = 0.02

[[regions]]
name = "concrete"
material = { kind = "elastic", young = 32e9, poisson = 0.2, density = 2200.0 }

[[interfaces]]
between = ["concrete", "concrete"]
law = { kind = "cohesive", normal_stiffness = 2e14, tangential_stiffness = 2e14, fracture_energy = 110.0, strength = 3e6 }

[[loads]]
name = "top"
nodes = { set = "top" }
velocity = ["free", 0.1]

[[loads]]
name = "bottom"
nodes = { set = "bottom" }
velocity = ["free", -0.1]

[[loads]]
name = "left_upper"
nodes = { set = "left_upper" }
velocity = [0.1, "free"]

[[loads]]
name = "right_lower"
nodes = { set = "right_lower" }
velocity = [-0.1, "free"]
"#;

/// A bimaterial square (J2 matrix, one elastic inclusion, pre-crack) pulled fast enough for
/// the matrix to yield at once: the checkpoint must carry plastic states and tangents.
const BIMATERIAL: &str = r#"[scene]
name = "tiny_bimaterial"
dt = 1e-11
steps = 50
gravity = [0.0, 0.0]

[output]
frame_every = 25
checkpoint_every = 20

[fracture]
thickness = 1.0
broken = ["precrack"]

[mesh]
generator = "rectangle_with_inclusions"
width = 5e-5
height = 5e-5
inclusions = [[2.0e-5, 2.0e-5, 3.0e-5, 3.0e-5]]
precrack = [[2.5e-5, 0.0], [2.5e-5, 0.5e-5]]
element_size = 5e-6

[[regions]]
name = "matrix"
material = { kind = "j2", young = 99e9, poisson = 0.325, density = 7850.0, yield_stress = 250e6, hardening = 850e6 }

[[regions]]
name = "inclusion"
material = { kind = "elastic", young = 135e9, poisson = 0.32, density = 7850.0 }

[[interfaces]]
between = ["matrix", "matrix"]
law = { kind = "cohesive", normal_stiffness = 2e19, tangential_stiffness = 2e19, fracture_energy = 0.5, strength = 1e9 }

[[interfaces]]
between = ["inclusion", "inclusion"]
law = { kind = "cohesive", normal_stiffness = 4e19, tangential_stiffness = 4e19, fracture_energy = 0.4, strength = 1e9 }

[[interfaces]]
between = ["matrix", "inclusion"]
law = { kind = "cohesive", normal_stiffness = 4e19, tangential_stiffness = 4e19, fracture_energy = 5.0, strength = 1e9 }

[[loads]]
name = "left"
nodes = { set = "left" }
velocity = [-50.0, "free"]

[[loads]]
name = "right"
nodes = { set = "right" }
velocity = [50.0, "free"]
"#;

fn write_scene(name: &str, text: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let dir = temp_dir(name);
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    (scene, dir)
}

/// `check` and `run` both exit 2 naming the scene file, the line (`:line:`) and each fragment.
fn expect_error(name: &str, text: &str, line: usize, fragments: &[&str]) {
    let (scene, dir) = write_scene(name, text);
    for cmd in ["check", "run"] {
        let out = if cmd == "run" {
            run(&scene, &dir.join("out"), &[])
        } else {
            xper(&["check", scene.to_str().unwrap()])
        };
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}/{cmd}: {stderr}");
        let place = format!("{}:{line}:", scene.display());
        assert!(
            stderr.contains(&place),
            "{name}/{cmd}: no `{place}` in {stderr}"
        );
        for f in fragments {
            assert!(stderr.contains(f), "{name}/{cmd}: `{f}` not in {stderr}");
        }
    }
}

fn line_of(text: &str, marker: &str) -> usize {
    text.lines().position(|l| l.contains(marker)).unwrap() + 1
}

#[test]
fn malformed_fracture_scenes_exit_2_with_the_place_and_reason() {
    let t = NOTCHED.replace("[\"concrete\", \"concrete\"]", "[\"concrete\", \"steel\"]");
    let line = line_of(&t, "steel");
    expect_error(
        "unknown_region",
        &t,
        line,
        &["interfaces[0].between[1]", "unknown region `steel`"],
    );
    let t = NOTCHED.replace("poisson = 0.2", "poisson = 0.5");
    let line = line_of(&t, "poisson");
    expect_error(
        "poisson",
        &t,
        line,
        &["regions[0].material.poisson", "in (-1, 0.5), got 0.5"],
    );
    let t = NOTCHED.replace("thickness = 0.05", "thickness = 0.05\nbroken = [\"crack\"]");
    let line = line_of(&t, "broken");
    expect_error(
        "broken",
        &t,
        line,
        &[
            "fracture.broken[0]",
            "unknown edge set `crack`",
            "notch_left",
        ],
    );
    let t = NOTCHED.replace(
        "generator = \"double_edge_notched\"",
        "file = \"specimen.msh\"",
    );
    let t = t
        .replace("side = 0.2\n", "")
        .replace("notch_depth = 0.025\n", "");
    let t = t
        .replace("notch_width = 0.005\n", "")
        .replace("element_size = 0.02\n", "");
    let line = line_of(&t, "specimen.msh");
    expect_error(
        "mesh_file",
        &t,
        line,
        &["mesh.file", "specimen.msh", "cannot read"],
    );
    let t = NOTCHED.replace(
        "velocity = [0.1, \"free\"]",
        "velocity = [0.1, \"free\"]\nforce = [5.0, \"free\"]",
    );
    let line = line_of(&t, "force");
    expect_error(
        "velocity_and_force",
        &t,
        line,
        &["loads[2].force[0]", "both a velocity and a force"],
    );
    let t = NOTCHED.replace(
        "{ set = \"top\" }",
        "{ segment = [[0.0, 0.3], [0.2, 0.3]] }",
    );
    let line = line_of(&t, "segment");
    expect_error(
        "empty_selection",
        &t,
        line,
        &["loads[0].nodes", "selects no node"],
    );
    let cut = BIMATERIAL
        .find("[[interfaces]]\nbetween = [\"matrix\", \"inclusion\"]")
        .unwrap();
    let end = BIMATERIAL.find("[[loads]]").unwrap();
    let t = format!("{}{}", &BIMATERIAL[..cut], &BIMATERIAL[end..]);
    let line = line_of(&t, "[\"matrix\", \"matrix\"]");
    expect_error(
        "missing_law",
        &t,
        line,
        &["regions `matrix` and `inclusion` are neighbours"],
    );
    let t = NOTCHED.replace("strength = 3e6", "strength = 3e9");
    let line = line_of(&t, "strength");
    expect_error(
        "no_softening",
        &t,
        line,
        &["interfaces[0].law.strength", "strength too high"],
    );
}

#[test]
fn resume_without_a_checkpoint_is_bad_input() {
    let (scene, dir) = write_scene("fracture_resume_missing", NOTCHED);
    let out = run(&scene, &dir.join("out"), &["--resume"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("checkpoint.bin") && stderr.contains("cannot resume"),
        "{stderr}"
    );
}

fn f64s(g: &UnstructuredGrid, name: &str) -> Vec<f64> {
    let a = (g.cell_data.iter().chain(&g.point_data))
        .find(|a| a.name == name)
        .unwrap_or_else(|| panic!("no array `{name}`"));
    match &a.values {
        DataValues::F64(v) => v.clone(),
        DataValues::I32(v) => v.iter().map(|&x| f64::from(x)).collect(),
    }
}

fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{}", path.display());
    assert_eq!(&bytes[12..16], b"IHDR");
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert!(w >= 800 && h >= 400, "{}: {w} x {h}", path.display());
    assert!(
        bytes.len() > 15_000,
        "{}: only {} bytes",
        path.display(),
        bytes.len()
    );
}

#[test]
fn run_writes_frames_series_summary_and_plots() {
    let (scene, dir) = write_scene("fracture_run", NOTCHED);
    let out_dir = dir.join("out");
    assert_ok(&run(&scene, &out_dir, &[]));

    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["status"], "completed");
    assert_eq!(summary["steps"], 40);
    let elements = summary["elements"].as_u64().unwrap() as usize;
    let interfaces = summary["interfaces"].as_u64().unwrap() as usize;
    assert!(elements > 200 && interfaces > 300, "{summary}");
    assert!(summary["ns_per_point_update"].as_f64().unwrap() > 0.0);
    assert!(summary["median_iterations"].as_f64().unwrap() >= 1.0);

    // Frames at steps 0, 20 and 40, two parts each.
    let pvd = PvdCollection::read(&out_dir.join("result.pvd")).unwrap();
    assert_eq!(pvd.entries.len(), 6);
    for step in [0, 20, 40] {
        let el = read_vtu(&out_dir.join(format!("frames/elements_{step:08}.vtu"))).unwrap();
        assert_eq!(el.num_cells(), elements);
        assert_eq!(el.points.len(), 3 * elements);
        let u = f64s(&el, "displacement");
        let top = f64s(&el, "stress_yy");
        assert_eq!(top.len(), elements);
        for name in [
            "stress_xx",
            "stress_xy",
            "stress_zz",
            "von_mises",
            "strain_xx",
            "equivalent_plastic_strain",
            "region",
        ] {
            assert_eq!(f64s(&el, name).len(), elements, "{name}");
        }
        assert_eq!(f64s(&el, "velocity").len(), 3 * elements);
        let max_u = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if step == 0 {
            assert_eq!(max_u, 0.0);
        } else {
            // Imposed: 0.1 m/s for (step - 1/2) steps of 2e-7 s at most.
            let bound = 0.1 * (step as f64 - 0.5) * 2e-7;
            assert!(
                max_u > 0.5 * bound && max_u < 1.5 * bound,
                "{max_u} vs {bound}"
            );
        }
        let it = read_vtu(&out_dir.join(format!("frames/interfaces_{step:08}.vtu"))).unwrap();
        assert_eq!(it.num_cells(), interfaces);
        let beta = f64s(&it, "beta");
        assert!(beta.iter().all(|b| (0.0..=1.0).contains(b)));
        for name in [
            "beta_min",
            "opening",
            "sliding",
            "normal_traction",
            "tangential_traction",
            "broken",
        ] {
            assert_eq!(f64s(&it, name).len(), interfaces, "{name}");
        }
    }

    let s = SeriesTable::read_csv(&out_dir.join("series.csv")).unwrap();
    assert_eq!(s.rows.len(), 40);
    let col = |n: &str| s.column(n).unwrap_or_else(|| panic!("no column {n}"));
    for load in ["top", "bottom", "left_upper", "right_lower"] {
        for c in ["fx", "fy", "ux", "uy"] {
            col(&format!("{load}_{c}"));
        }
    }
    let parts = [
        "kinetic",
        "elastic",
        "plastic",
        "cohesive_stored",
        "cohesive_dissipated",
        "contact_dissipated",
    ];
    let (time, external, initial, error) = (
        col("time"),
        col("external_work"),
        col("initial_energy"),
        col("energy_error"),
    );
    for r in 0..40 {
        let held: f64 = parts.iter().map(|p| col(p)[r]).sum();
        let balance = held - initial[r] - external[r];
        let scale = held.abs().max(external[r].abs()).max(1e-300);
        assert!(
            (balance - error[r]).abs() <= 1e-12 * scale,
            "row {r}: {balance} vs {}",
            error[r]
        );
        assert!(
            error[r].abs() < 1e-6 * scale,
            "row {r}: energy error {}",
            error[r]
        );
        assert!((time[r] - (r + 1) as f64 * 2e-7).abs() < 1e-18);
        // The top nodes move at the imposed 0.1 m/s (theta = 1/2: half a step at first).
        let uy = col("top_uy")[r];
        assert!(
            (uy - 0.1 * (time[r] - 1e-7)).abs() < 1e-9 * time[r],
            "row {r}: {uy}"
        );
    }
    assert!(external[39] > 0.0 && col("top_fy")[39] > 0.0 && col("bottom_fy")[39] < 0.0);

    for png in ["series.png", "force_displacement.png", "crack_pattern.png"] {
        assert_png(&out_dir.join(png));
    }
    let checkpoint = std::fs::metadata(out_dir.join("checkpoint.bin")).unwrap();
    assert!(checkpoint.len() > 1000);
}

#[test]
fn python_vtk_reads_the_fracture_frames() {
    let Some(python) = common::python_with_vtk() else {
        println!("skipped: python vtk module not installed");
        return;
    };
    let (scene, dir) = write_scene("fracture_vtk", &NOTCHED.replace("steps = 40", "steps = 20"));
    let out_dir = dir.join("out");
    assert_ok(&run(&scene, &out_dir, &[]));
    for (part, array) in [("elements", "von_mises"), ("interfaces", "beta")] {
        let file = out_dir.join(format!("frames/{part}_00000020.vtu"));
        let script = "import sys, vtk\nr = vtk.vtkXMLUnstructuredGridReader()\nr.SetFileName(sys.argv[1])\nr.Update()\nassert r.GetErrorCode() == 0\no = r.GetOutput()\nassert o.GetNumberOfCells() > 0\nassert o.GetCellData().GetArray(sys.argv[2]).GetNumberOfTuples() == o.GetNumberOfCells()";
        let out = std::process::Command::new(python)
            .args(["-c", script, file.to_str().unwrap(), array])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn resume_after_stop_matches_uninterrupted_run() {
    let (scene, dir) = write_scene("fracture_resume", BIMATERIAL);
    let (straight, split) = (dir.join("straight"), dir.join("split"));
    assert_ok(&run(&scene, &straight, &[]));
    // Stop between checkpoints (every 20 steps): the resume restarts from step 20.
    assert_ok(&run(&scene, &split, &["--stop-at-step", "33"]));
    let summary = std::fs::read_to_string(split.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"stopped\""), "{summary}");
    assert_ok(&run(&scene, &split, &["--resume"]));

    let a = std::fs::read(straight.join("checkpoint.bin")).unwrap();
    let b = std::fs::read(split.join("checkpoint.bin")).unwrap();
    assert!(a == b, "final states differ");
    let sa = SeriesTable::read_csv(&straight.join("series.csv")).unwrap();
    let sb = SeriesTable::read_csv(&split.join("series.csv")).unwrap();
    assert_eq!((sa.rows.len(), sb.rows.len()), (50, 50));
    let plastic = sa.column("plastic").unwrap();
    assert!(plastic[49] > 0.0, "the matrix should have yielded");
    let timing = ["wall_time", "solve_time"];
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
    let pvd = PvdCollection::read(&split.join("result.pvd")).unwrap();
    assert_eq!(pvd.entries.len(), 6, "frames 0, 25 and 50, once each");

    // A checkpoint of another scene is refused (a longer run of the same one is not, see
    // tests/resume.rs).
    let other = dir.join("other.toml");
    std::fs::write(&other, BIMATERIAL.replace("young = 135e9", "young = 136e9")).unwrap();
    let out = run(&other, &split, &["--resume"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("different scene") && err.contains("young"),
        "{err}"
    );
}

#[test]
fn blow_up_stops_with_exit_1_and_a_failed_summary() {
    let t = NOTCHED.replace("velocity = [\"free\", 0.1]", "force = [\"free\", 1e300]");
    let (scene, dir) = write_scene("fracture_blow_up", &t);
    let out_dir = dir.join("out");
    let out = run(&scene, &out_dir, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("step ") && stderr.contains("no checkpoint was written"),
        "{stderr}"
    );
    let summary = std::fs::read_to_string(out_dir.join("summary.json")).unwrap();
    assert!(summary.contains("\"status\": \"failed\""), "{summary}");
    assert_png(&out_dir.join("series.png"));
}

#[test]
fn divergence_guard_flags_a_broken_energy_budget_only() {
    use xper_fracture::FractureEnergy;
    let diverging = |e: &FractureEnergy| e.divergence();
    let sound = FractureEnergy {
        kinetic: 1.0,
        elastic: 2.0,
        plastic: 0.5,
        external_work: 3.5 + 1e-9,
        ..FractureEnergy::default()
    };
    assert!(diverging(&sound).is_none());
    assert!(diverging(&FractureEnergy::default()).is_none());
    let blown = FractureEnergy {
        kinetic: 1e6,
        ..sound
    };
    let message = diverging(&blown).expect("diverging");
    assert!(
        message.contains("energy balance error") && message.contains("reduce dt"),
        "{message}"
    );
    let nan = FractureEnergy {
        kinetic: f64::NAN,
        ..sound
    };
    assert!(diverging(&nan).is_some());
}
