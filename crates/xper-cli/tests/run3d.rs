//! `xper run` on 3D scenes (`[scene] dimension = 3`): the outputs, a resume that is bit-exact,
//! and, with the `mpi` feature, `mpirun -np 2` against the serial run.

mod common;

use common::{assert_success, run_scene, temp_dir, xper};
use std::path::Path;
use xper_nscd3d::World;

/// 64 spheres on a 4 x 4 x 4 lattice falling onto a box and a tetrahedron in a box of
/// half-spaces, NLGS at `tolerance`.
fn scene(steps: u64, tolerance: f64) -> String {
    format!(
        r#"[scene]
name = "small3d"
dimension = 3
dt = 1e-3
steps = {steps}

[solver]
tolerance = {tolerance:e}

[output]
frame_every = 50
checkpoint_every = 40

[[materials]]
name = "glass"
density = 2500.0

[[laws]]
between = ["grains", "grains"]
kind = "signorini_coulomb"
friction = 0.3

[[laws]]
between = ["grains", "walls"]
kind = "signorini_coulomb"
friction = 0.5

[[bodies]]
shape = "box"
center = [0.02, 0.02, 0.0051]
size = [0.02, 0.02, 0.01]
orientation = [0.0, 0.0, 0.2]
material = "glass"
group = "grains"

[[bodies]]
shape = "tetrahedron"
center = [0.045, 0.04, 0.012]
radius = 0.008
material = "glass"
group = "grains"

[[generators]]
kind = "lattice3d"
columns = 4
rows = 4
layers = 4
pitch = 0.0145
radius = 0.0025
seed = 5
box = [0.065, 0.065, 0.1]
material = "glass"
group = "grains"
velocity = [0.0, 0.0, 0.0]

[[walls]]
point = [0.0, 0.0, -0.03]
normal = [0.0, 0.0, 1.0]
group = "walls"

[[walls]]
point = [-0.001, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
group = "walls"

[[walls]]
point = [0.066, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
group = "walls"

[[walls]]
point = [0.0, -0.001, 0.0]
normal = [0.0, 1.0, 0.0]
group = "walls"

[[walls]]
point = [0.0, 0.066, 0.0]
normal = [0.0, -1.0, 0.0]
group = "walls"
"#
    )
    .replace(
        "center = [0.02, 0.02, 0.0051]",
        "center = [0.02, 0.02, -0.0249]",
    )
    .replace(
        "center = [0.045, 0.04, 0.012]",
        "center = [0.045, 0.04, -0.018]",
    )
}

fn write_scene(dir: &Path, steps: u64, tolerance: f64) -> std::path::PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene(steps, tolerance)).unwrap();
    path
}

fn checkpoint(dir: &Path) -> World {
    let payload = xper_simulation::checkpoint::open(dir, "test")
        .unwrap()
        .payload;
    let (_, _, world): (u32, u64, Vec<u8>) = bincode::deserialize(&payload).unwrap();
    World::from_bytes(&world).unwrap()
}

fn distance(a: &World, b: &World) -> f64 {
    assert_eq!(a.step, b.step);
    (0..a.bodies.len())
        .map(|k| (a.bodies.position[k] - b.bodies.position[k]).norm())
        .fold(0.0, f64::max)
}

/// A run writes every part of every frame (spheres, polyhedra, walls, contacts, force
/// chains), its series and summary; the bodies stay in the box; a run stopped at step 70 and
/// resumed ends with the same checkpoint, bit for bit, as the uninterrupted one.
#[test]
fn a_3d_scene_runs_writes_its_frames_and_resumes_bit_for_bit() {
    let dir = temp_dir("run3d");
    let path = write_scene(&dir, 150, 1e-6);
    let scene = path.to_str().unwrap();
    let (whole, stopped) = (dir.join("whole"), dir.join("stopped"));
    assert_success(&xper(&["check", scene]));
    assert_success(&run_scene(&path, &whole, &["--quiet"]));
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(whole.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["status"], "completed");
    assert_eq!(summary["bodies"], 71);
    for part in ["spheres", "polyhedra", "walls", "contacts", "force_chains"] {
        for step in [0, 50, 100, 150] {
            let file = whole.join(format!("frames/{part}_{step:08}.vtu"));
            assert!(file.is_file(), "{} missing", file.display());
        }
    }
    let pvd = std::fs::read_to_string(whole.join("result.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 5 * 4);
    let end = checkpoint(&whole);
    for k in 0..end.bodies.len() {
        let x = end.bodies.position[k];
        if end.bodies.is_dynamic(k) {
            assert!(
                x.z > -0.03 && (-0.001..0.066).contains(&x.x),
                "body {k} at {x:?}"
            );
        }
    }
    assert!(end.contacts.len() > 64, "{} contacts", end.contacts.len());
    let stop = ["--quiet", "--stop-at-step", "70"];
    assert_success(&run_scene(&path, &stopped, &stop));
    assert_success(&run_scene(&path, &stopped, &["--quiet", "--resume"]));
    assert_eq!(
        std::fs::read(stopped.join("checkpoint.bin")).unwrap(),
        std::fs::read(whole.join("checkpoint.bin")).unwrap()
    );
}

/// `mpirun -np 2` against the serial run: within ten times the serial run's own error (its
/// distance to the run at a tolerance a hundred times smaller), as in 2D.
#[cfg(feature = "mpi")]
#[test]
fn mpirun_agrees_with_the_serial_run_in_3d() {
    let dir = temp_dir("run3d_mpi");
    let run = |name: &str, tolerance: f64, ranks: usize| {
        let path = write_scene(&dir.join(name), 150, tolerance);
        let out = dir.join(name).join("out");
        let args = [
            "run",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        let output = if ranks == 1 {
            xper(&args)
        } else {
            std::process::Command::new("timeout")
                .args(["300", "mpirun", "-np", &ranks.to_string()])
                .arg(env!("CARGO_BIN_EXE_xper"))
                .args(args)
                .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
                .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
                .env("OMPI_MCA_rmaps_base_oversubscribe", "1")
                .env("OMPI_MCA_mpi_yield_when_idle", "1")
                .output()
                .expect("mpirun could not be started")
        };
        assert_success(&output);
        checkpoint(&out)
    };
    let serial = run("serial", 1e-6, 1);
    let tighter = run("tighter", 1e-8, 1);
    let spread = distance(&serial, &tighter);
    assert!(spread > 0.0);
    let two = run("two", 1e-6, 2);
    let d = distance(&two, &serial);
    eprintln!("3d mpi: {d:.3e} m from serial, serial error {spread:.3e} m");
    assert!(
        d <= 10.0 * spread,
        "{d:.3e} m vs serial error {spread:.3e} m"
    );
}

/// VTK itself (the Python module, when installed) reads every part of a 3D frame: the
/// spheres' radii as point data within the scene's range, one polygon per face of the box
/// and the tetrahedron (6 + 4), the five walls, and contacts with their impulse vectors.
#[test]
fn python_vtk_reads_the_3d_frames() {
    let Some(python) = common::python_with_vtk() else {
        println!("skipped: python vtk module not installed");
        return;
    };
    let dir = temp_dir("run3d_vtk");
    let path = write_scene(&dir, 100, 1e-4);
    let out = dir.join("out");
    assert_success(&run_scene(&path, &out, &["--quiet"]));
    let script = r#"
import sys, vtk
def read(part):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(sys.argv[1] + "/frames/" + part + "_00000100.vtu")
    r.Update()
    assert r.GetErrorCode() == 0, part
    return r.GetOutput()
s = read("spheres")
assert s.GetNumberOfPoints() == 64 and s.GetNumberOfCells() == 64
radius = s.GetPointData().GetArray("radius")
assert all(0.0025 <= radius.GetValue(i) <= 0.005 for i in range(64))
assert s.GetPointData().GetArray("velocity").GetNumberOfComponents() == 3
p = read("polyhedra")
assert p.GetNumberOfCells() == 10, p.GetNumberOfCells()
assert read("walls").GetNumberOfCells() == 5
c = read("contacts")
assert c.GetNumberOfCells() > 0
assert c.GetCellData().GetArray("impulse").GetNumberOfTuples() == c.GetNumberOfCells()
"#;
    let run = std::process::Command::new(python)
        .args(["-c", script, out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// `[output] dump_problems` in 3D: the FCLib file of a step holds that step's problem
/// (`dim = 3`), and `xper solve` on it gives the impulses the time stepping found, on a heap of
/// spheres whose contact frames are independent (a unique solution).
#[cfg(feature = "hdf5")]
#[test]
fn a_dumped_3d_problem_solved_by_xper_solve_gives_the_stepping_impulses() {
    let dir = temp_dir("run3d_dump");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.toml");
    let spheres = [
        [0.0, 0.0, 0.01002],
        [0.021, 0.0, 0.01002],
        [0.0105, 0.019, 0.01002],
        [0.0105, 0.0063, 0.027],
    ];
    let bodies: String = spheres
        .iter()
        .map(|c| {
            format!(
                "[[bodies]]\nshape = \"sphere\"\ncenter = {c:?}\nradius = 0.01\nmaterial = \"glass\"\ngroup = \"grains\"\n\n"
            )
        })
        .collect();
    let text = format!(
        "[scene]\nname = \"dump3d\"\ndimension = 3\ndt = 1e-3\nsteps = 40\nalert_distance = 1e-3\n\n\
         [solver]\ntolerance = 1e-12\nnorm = \"natural_map\"\nmax_iterations = 100000\ncheck_every = 1\n\n\
         [output]\ndump_problems = [30]\n\n\
         [[materials]]\nname = \"glass\"\ndensity = 1000.0\n\n\
         [[laws]]\nbetween = [\"grains\", \"grains\"]\nkind = \"signorini_coulomb\"\nfriction = 0.3\n\n\
         [[laws]]\nbetween = [\"grains\", \"walls\"]\nkind = \"signorini_coulomb\"\nfriction = 0.3\n\n\
         {bodies}[[walls]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\ngroup = \"walls\"\n"
    );
    std::fs::write(&path, text).unwrap();
    let out = dir.join("out");
    assert_success(&run_scene(&path, &out, &["--quiet"]));
    let file = xper_simulation::rigid3d::outputs::problem_path(&out, 30);
    let got = xper_fclib::read_fclib_local(&file).unwrap();
    assert_eq!(got.dim, 3);

    // Independent path: the scene stepped here to step 29, its next problem, then step 30.
    let xper_scene::AnyScene::Rigid3(scene) = xper_scene::load_any_scene(&path).unwrap() else {
        panic!("a 3D scene")
    };
    let mut world = xper_simulation::rigid3d::build::world_from_scene(&scene);
    let mut stepper = xper_nscd3d::MoreauJean::new();
    while world.step < 29 {
        stepper.step(&mut world).unwrap();
    }
    assert!(
        stepper.next_problem(&world).unwrap() == got,
        "the file is the step's problem"
    );
    stepper.step(&mut world).unwrap();
    let stepping: Vec<f64> = world.contacts.impulses.iter().flatten().copied().collect();
    assert!(
        world.contacts.len() >= 6,
        "{} contacts",
        world.contacts.len()
    );

    let solution = dir.join("solution.json");
    assert_success(&xper(&[
        "solve",
        file.to_str().unwrap(),
        "--solver",
        "newton",
        "--tol",
        "1e-12",
        "--solution",
        solution.to_str().unwrap(),
    ]));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&solution).unwrap()).unwrap();
    let r: Vec<f64> = (json["r"].as_array().unwrap().iter())
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(r.len(), stepping.len());
    let scale = r.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let worst = (r.iter().zip(&stepping)).fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    // Both solve to 1e-12 of the natural-map error; W is positive definite here.
    assert!(
        worst <= 1e-8 * scale,
        "impulses differ by {worst:e} (largest {scale:e})"
    );
}

#[test]
fn micro_measures_of_a_3d_scene_take_the_box_of_the_walls() {
    use xper_scene::ShapeDesc3;
    let dir = common::temp_dir("micro3d");
    let path = common::shipped_scene("box3d10k", 20, [10, 20], &dir);
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(
        &path,
        text.replace("[output]", "[output]\nmicro = \"walls\""),
    )
    .unwrap();
    let out = dir.join("out");
    common::assert_success(&common::run_scene(&path, &out, &["--quiet"]));
    let table = xper_io::SeriesTable::read_csv(&out.join("micro.csv")).unwrap();
    for c in ["stress_xz", "stress_zz", "fabric_yz", "extent_z"] {
        assert!(table.columns.iter().any(|x| x == c), "{c}");
    }
    // Independently: the spheres' volume over the box spanned by the six walls' centres.
    let xper_scene::AnyScene::Rigid3(scene) = xper_scene::load_any_scene(&path).unwrap() else {
        panic!("a 3D scene");
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut spheres = 0.0;
    for b in &scene.bodies {
        match b.shape {
            ShapeDesc3::Sphere { radius } => {
                spheres += 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3)
            }
            ShapeDesc3::Plane { .. } => {
                for k in 0..3 {
                    lo[k] = lo[k].min(b.position[k]);
                    hi[k] = hi[k].max(b.position[k]);
                }
            }
            ShapeDesc3::Polyhedron { .. } => panic!("box3d10k holds spheres"),
        }
    }
    let volume: f64 = (0..3).map(|k| hi[k] - lo[k]).product();
    let phi = table.column("solid_fraction").unwrap()[0];
    assert!(
        (phi - spheres / volume).abs() < 1e-12 * phi,
        "{phi} {}",
        spheres / volume
    );
    assert!((table.column("volume").unwrap()[0] - volume).abs() < 1e-12 * volume);
}
