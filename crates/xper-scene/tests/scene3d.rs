//! 3D scenes (`[scene] dimension = 3`): the box3d10k lattice rules, mass properties, wall
//! frames, and errors with their file, line, field and reason.

mod common;

use common::{expect_error_any, find_error, ok3_text, parse3};
use std::f64::consts::PI;
use std::path::Path;
use xper_math3d::{Rotation, Vector};
use xper_scene::{parse_any_scene, Scene3, SceneErrors, ShapeDesc3};

const HEADER3: &str = r#"[scene]
name = "t"
dimension = 3
dt = 1e-3
steps = 10

[[materials]]
name = "glass"
density = 2500.0
"#;

fn ok3(rest: &str) -> Scene3 {
    ok3_text(&format!("{HEADER3}\n{rest}"))
}

/// Asserts an error on `field` at the line holding `marker` whose message has `needle`.
fn error3(rest: &str, field: &str, marker: &str, needle: &str) {
    expect_error_any(&format!("{HEADER3}\n{rest}"), field, marker, needle);
}

/// The shipped box3d10k scene follows ../shared/bench/box3d10k.md: sphere `n = 400 k + 20 j +
/// i` at its lattice site, radii `1e-3 (1 + u_n)` from SplitMix64 seed 12345 (the first two
/// printed in the spec), six walls on the box's faces, gravity along -z.
#[test]
fn box3d10k_follows_the_benchmark_rules() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/box3d10k/scene.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let scene = parse3(&text).unwrap();
    assert_eq!(scene.bodies.len(), 10_006);
    assert_eq!(scene.gravity, [0.0, 0.0, -9.81]);
    let p = 4.1e-3;
    let mut rng = xper_math::SplitMix64::new(12345);
    for (n, b) in scene.bodies[..10_000].iter().enumerate() {
        let (i, j, k) = (n % 20, n / 20 % 20, n / 400);
        let s = if k % 2 == 1 { p / 2.0 } else { 0.0 };
        let site = [
            p / 2.0 + i as f64 * p + s,
            p / 2.0 + j as f64 * p + s,
            p / 2.0 + k as f64 * p,
        ];
        assert_eq!(b.position, site, "sphere {n}");
        let r = 1e-3 * (1.0 + rng.next_f64());
        assert_eq!(b.shape, ShapeDesc3::Sphere { radius: r });
        let m = 2600.0 * 4.0 / 3.0 * PI * r.powi(3);
        assert!((b.mass - m).abs() <= 1e-15 * m);
        assert!((b.inertia[0][0] - 0.4 * m * r * r).abs() <= 1e-15 * m * r * r);
    }
    let radius = |n: usize| match scene.bodies[n].shape {
        ShapeDesc3::Sphere { radius } => radius,
        _ => unreachable!(),
    };
    assert!((radius(0) - 1.133080e-3).abs() < 5e-10 && (radius(1) - 1.204817e-3).abs() < 5e-10);
    // Walls: a point and the normal pointing into the box.
    let w = 20.5 * p;
    let expected = [
        ([0.0, 0.0, 0.0], Vector::z()),
        ([w, w, 0.12], -Vector::z()),
        ([0.0, 0.0, 0.0], Vector::x()),
        ([w, w, 0.12], -Vector::x()),
        ([0.0, 0.0, 0.0], Vector::y()),
        ([w, w, 0.12], -Vector::y()),
    ];
    for (b, (point, n)) in scene.bodies[10_000..].iter().zip(expected) {
        assert!(
            matches!(b.shape, ShapeDesc3::Plane { half_extents } if half_extents[0].is_infinite())
        );
        assert!((0..3).all(|k| (b.position[k] - point[k]).abs() < 1e-15));
        let q = Rotation::from_scaled_axis(Vector::from(b.orientation));
        assert!((q * Vector::z() - n).norm() < 1e-15, "{n:?}");
        assert!(b.mass.is_infinite());
    }
}

/// Mass properties against closed forms: a sphere `(4/3 pi r^3 rho, 2/5 m r^2)`, a box
/// `(abc rho, m (b^2 + c^2) / 12, ...)` turned by its orientation (the tensor stays in the
/// body frame), regular solids with every vertex on the circumsphere and an isotropic tensor.
#[test]
fn shapes_and_mass_properties() {
    let s = ok3(r#"
[[bodies]]
shape = "sphere"
center = [0.0, 0.0, 1.0]
radius = 0.1
material = "glass"
group = "g"

[[bodies]]
shape = "box"
center = [1.0, 0.0, 1.0]
size = [0.3, 0.2, 0.1]
orientation = [0.0, 0.0, 0.5]
material = "glass"
group = "g"

[[bodies]]
shape = "icosahedron"
center = [2.0, 0.0, 1.0]
radius = 0.1
material = "glass"
group = "g"

[[bodies]]
shape = "dodecahedron"
center = [3.0, 0.0, 1.0]
radius = 0.1
material = "glass"
group = "g"

[[bodies]]
shape = "tetrahedron"
center = [4.0, 0.0, 1.0]
radius = 0.1
mass = 2.0
inertia = [0.1, 0.2, 0.3]
group = "g"
"#);
    let m = 2500.0 * 4.0 / 3.0 * PI * 1e-3;
    assert!((s.bodies[0].mass - m).abs() < 1e-12 * m);
    assert!((s.bodies[0].inertia[1][1] - 0.4 * m * 0.01).abs() < 1e-12 * m);
    let boxed = &s.bodies[1];
    let m = 2500.0 * 0.3 * 0.2 * 0.1;
    assert!((boxed.mass - m).abs() < 1e-12 * m);
    let expected = [
        m * (0.04 + 0.01) / 12.0,
        m * (0.09 + 0.01) / 12.0,
        m * (0.09 + 0.04) / 12.0,
    ];
    for (k, e) in expected.iter().enumerate() {
        assert!((boxed.inertia[k][k] - e).abs() < 1e-12 * m, "{k}");
    }
    assert!((0..3).all(|k| (boxed.position[k] - [1.0, 0.0, 1.0][k]).abs() < 1e-15));
    assert_eq!(boxed.orientation, [0.0, 0.0, 0.5]);
    for (b, count) in [(&s.bodies[2], 12), (&s.bodies[3], 20), (&s.bodies[4], 4)] {
        let ShapeDesc3::Polyhedron { vertices } = &b.shape else {
            panic!("a polyhedron")
        };
        assert_eq!(vertices.len(), count);
        for v in vertices {
            assert!((Vector::from(*v).norm() - 0.1).abs() < 1e-12, "{v:?}");
        }
    }
    for b in &s.bodies[2..4] {
        let i = b.inertia;
        assert!((i[0][0] - i[1][1]).abs() < 1e-12 * i[0][0] && i[0][1].abs() < 1e-12 * i[0][0]);
    }
    assert_eq!(s.bodies[4].mass, 2.0);
    assert_eq!(s.bodies[4].inertia[2][2], 0.3);
}

/// A wall's frame: its z axis is the normal, its x axis the given edge (projected on the
/// plane); a finite wall keeps its half-extents.
#[test]
fn wall_frames() {
    let s = ok3(r#"
[[walls]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 2.0]
group = "w"

[[walls]]
point = [1.0, 2.0, 3.0]
normal = [1.0, 1.0, 0.0]
edge = [0.0, 0.3, 1.0]
size = [0.4, 0.2]
group = "w"
"#);
    let q = Rotation::from_scaled_axis(Vector::from(s.bodies[1].orientation));
    let n = Vector::new(1.0, 1.0, 0.0).normalize();
    assert!((q * Vector::z() - n).norm() < 1e-15);
    let edge = Vector::new(0.0, 0.3, 1.0);
    let along = (edge - n * n.dot(&edge)).normalize();
    assert!((q * Vector::x() - along).norm() < 1e-15);
    assert_eq!(
        s.bodies[1].shape,
        ShapeDesc3::Plane {
            half_extents: [0.2, 0.1]
        }
    );
    assert!(s.bodies[0].orientation.iter().all(|&x| x == 0.0));
}

#[test]
fn errors_name_the_place_and_the_reason() {
    let sphere = |extra: &str| {
        format!(
            "[[bodies]]\nshape = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 0.1\nmaterial = \"glass\"\ngroup = \"g\"\n{extra}"
        )
    };
    error3(
        "[[bodies]]\nshape = \"cylinder\"\ngroup = \"g\"\nmaterial = \"glass\"",
        "bodies[0].shape",
        "cylinder",
        "cylinder",
    );
    error3(
        &sphere("orientation = [0.0, 0.0, 1.0]"),
        "bodies[0].orientation",
        "orientation",
        "not used",
    );
    error3(
        "[[bodies]]\nshape = \"polyhedron\"\nvertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]\nmaterial = \"glass\"\ngroup = \"g\"",
        "bodies[0].vertices",
        "vertices",
        "plane",
    );
    error3(
        "[[bodies]]\nshape = \"box\"\ncenter = [0.0, 0.0, 0.0]\nsize = [1.0, -1.0, 1.0]\nmaterial = \"glass\"\ngroup = \"g\"",
        "bodies[0].size",
        "size",
        "> 0",
    );
    error3(
        "[[walls]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 0.0]\ngroup = \"w\"",
        "walls[0].normal",
        "normal",
        "non-zero",
    );
    error3(
        "[[walls]]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\nedge = [0.0, 0.0, -3.0]\ngroup = \"w\"",
        "walls[0].edge",
        "edge",
        "parallel",
    );
    error3(
        "[[walls]]\npoint = [0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\ngroup = \"w\"",
        "walls[0].point",
        "point",
        "[x, y, z]",
    );
    error3(
        "[[generators]]\nkind = \"lattice3d\"\ncolumns = 3\nrows = 3\nlayers = 3\npitch = 1.0\nradius = 0.3\nbox = [3.0, 3.0, 2.0]\nmaterial = \"glass\"\ngroup = \"g\"",
        "generators[0].box",
        "box =",
        "does not fit",
    );
    // Two spheres overlapping by 0.05 m, and one crossing the floor.
    let overlapping = format!(
        "{}\n{}\n[[walls]]\npoint = [0.0, 0.0, -0.05]\nnormal = [0.0, 0.0, 1.0]\ngroup = \"w\"",
        sphere(""),
        sphere("").replace("[0.0, 0.0, 0.0]", "[0.15, 0.0, 0.0]")
    );
    let text = format!("{HEADER3}\n{overlapping}");
    let e = parse3(&text).unwrap_err();
    assert!(
        e.0.iter()
            .any(|x| x.field == "bodies[1]" && x.message.contains("by 5.000e-2 m")),
        "{e}"
    );
    assert!(
        e.0.iter()
            .any(|x| x.field == "walls[0]" && x.message.contains("overlaps body 0")),
        "{e}"
    );
}

/// The header's own checks, and 3D scenes refused where they do not apply.
#[test]
fn dimension_and_header() {
    let text = HEADER3.replace("dimension = 3", "dimension = 4");
    let e = parse_any_scene(&text, Path::new("test.toml")).unwrap_err();
    find_error(&e, &text, "scene.dimension", "dimension", "4");
    let text = HEADER3.replace("dimension = 3", "dimension = 3\ngravity = [0.0, -9.81]");
    let e = parse_any_scene(&text, Path::new("test.toml")).unwrap_err();
    find_error(&e, &text, "scene.gravity", "gravity", "[x, y, z]");
    let text = format!("{HEADER3}\n[fluid]\ndensity = 1000.0");
    let e = parse_any_scene(&text, Path::new("test.toml")).unwrap_err();
    find_error(&e, &text, "fluid", "[fluid]", "not available in 3D");
    let e = xper_scene::parse_scene(HEADER3, Path::new("test.toml")).unwrap_err();
    find_error(&e, HEADER3, "scene.dimension", "dimension", "3D scene");
    let text = format!("{HEADER3}\n[mesh]\nfile = \"m.msh\"");
    let e = parse_any_scene(&text, Path::new("test.toml")).unwrap_err();
    find_error(&e, &text, "scene.dimension", "dimension", "2D only");
    // Gravity defaults to -z in 3D.
    assert_eq!(ok3("").gravity, [0.0, 0.0, -9.81]);
}

/// Polyhedra in the overlap check, with depths known exactly: two unit cubes whose centres are
/// 0.9 m apart overlap by 0.1 m; touching face to face (1.0 m) they do not; a cube 0.2 m into
/// the floor overlaps it by 0.2 m, and a sphere of radius 0.25 m whose centre is 0.7 m from a
/// cube's centre along x (0.2 m from its face) overlaps it by 0.05 m; a turned octahedron is
/// told from its bounding sphere.
#[test]
fn polyhedra_overlaps_are_errors_with_their_depth() {
    let cube = |i: usize, x: f64, z: f64| {
        format!("[[bodies]]\nshape = \"box\"\ncenter = [{x}, 0.0, {z}]\nsize = [1.0, 1.0, 1.0]\nmaterial = \"glass\"\ngroup = \"g{i}\"\n")
    };
    let floor = "[[walls]]\npoint = [0.0, 0.0, -10.0]\nnormal = [0.0, 0.0, 1.0]\ngroup = \"w\"\n";
    // Touching face to face, and resting on the floor: no error.
    ok3(&format!(
        "{}{}{floor}",
        cube(0, 0.0, -9.5),
        cube(1, 1.0, -9.5)
    ));
    let depth_of = |e: &SceneErrors, field: &str| -> f64 {
        let m = (e.0.iter())
            .find(|x| x.field == field && x.message.contains("overlaps"))
            .unwrap_or_else(|| panic!("no overlap reported on {field}:\n{e}"));
        let tail = m.message.rsplit(" by ").next().unwrap();
        tail.trim_end_matches(" m").parse().unwrap()
    };
    let text = format!(
        "{HEADER3}\n{}{}{}{floor}[[bodies]]\nshape = \"sphere\"\ncenter = [20.7, 0.0, -9.7]\nradius = 0.25\nmaterial = \"glass\"\ngroup = \"s\"\n",
        cube(0, 0.0, 0.0),
        cube(1, 0.9, 0.0),
        cube(2, 20.0, -9.7),
    );
    let e = parse3(&text).unwrap_err();
    assert!((depth_of(&e, "bodies[1]") - 0.1).abs() < 1e-12, "{e}");
    assert!((depth_of(&e, "walls[0]") - 0.2).abs() < 1e-12, "{e}");
    assert!((depth_of(&e, "bodies[3]") - 0.05).abs() < 1e-12, "{e}");
    assert_eq!(e.0.len(), 3, "only those three pairs:\n{e}");
    // An octahedron of circumradius 1 m (|x| + |y| + |z| <= 1) turned by 45 degrees about z
    // reaches x = 1/sqrt(2) = 0.7071 m: clear of a cube whose face is at x = 0.9 m (the
    // bounding spheres meet, the narrow phase decides), into one whose face is at 0.7 m.
    let turned = format!(
        "[[bodies]]\nshape = \"octahedron\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\norientation = [0.0, 0.0, {}]\nmaterial = \"glass\"\ngroup = \"o\"\n{}",
        std::f64::consts::FRAC_PI_4,
        cube(1, 1.4, 0.0)
    );
    ok3(&turned);
    let e = parse3(&format!("{HEADER3}\n{}", turned.replace("[1.4,", "[1.2,"))).unwrap_err();
    assert!(depth_of(&e, "bodies[1]") > 0.0, "{e}");
}

const SPHERES: &str = r#"
[[laws]]
between = ["g", "g"]
kind = "signorini_coulomb"
friction = 0.4

[[generators]]
kind = "box_of_spheres"
count = 20
radius = [0.01, 0.01]
box = [[0.0, 0.0, 0.0], [0.2, 0.2, 0.2]]
placement = "random"
seed = 1
material = "glass"
group = "g"
"#;

/// `[cell]` in 3D: three axes, six components, the mass in kg; refusals as in 2D with the
/// third axis.
#[test]
fn a_3d_cell_has_three_axes_and_six_components() {
    let s = ok3(&format!(
        "{SPHERES}\n[cell]\nsize = [0.2, 0.2, 0.3]\nmass = 0.5\nxz = {{ rate = 2.0 }}\n\
         zz = {{ stress = 1e4 }}\nperiodic = [\"x\", \"z\"]\n"
    ));
    let c = s.cell.unwrap();
    assert_eq!((c.origin, c.size), ([0.0; 3], [0.2, 0.2, 0.3]));
    assert_eq!(c.periodic, [true, false, true]);
    use xper_scene::{CellLoadDesc, TimeFunction};
    assert_eq!(
        c.loads[0][2],
        CellLoadDesc::Rate(TimeFunction::Constant(2.0))
    );
    assert_eq!(
        c.loads[2][2],
        CellLoadDesc::Stress(TimeFunction::Constant(1e4))
    );
    assert_eq!(
        c.loads[1][2],
        CellLoadDesc::Rate(TimeFunction::Constant(0.0))
    );
    let cases = [
        (
            "size = [0.2, 0.2]",
            "cell.size",
            "size",
            "a triple of numbers",
        ),
        (
            "size = [0.2, 0.2, 0.07]",
            "cell.size",
            "size",
            "along z, less than four times",
        ),
        (
            "size = [0.2, 0.2, 0.2]\nzx = { rate = 1.0 }",
            "cell.zx",
            "zx",
            "dz/dx stays zero",
        ),
        (
            "size = [0.2, 0.2, 0.2]\nzy = { rate = 1.0 }",
            "cell.zy",
            "zy",
            "shear with `yz`",
        ),
        (
            "size = [0.2, 0.2, 0.2]\nzz = { stress = 1e4 }",
            "cell.mass",
            "zz",
            "(kg)",
        ),
        (
            "size = [0.2, 0.2, 0.2]\nperiodic = [\"w\"]",
            "cell.periodic",
            "periodic",
            "\"z\"]",
        ),
        (
            "size = [0.2, 0.2, 0.2]\nperiodic = [\"x\", \"y\"]\nyz = { rate = 1.0 }",
            "cell.yz",
            "yz",
            "not periodic along z",
        ),
    ];
    for (cell, field, marker, needle) in cases {
        error3(
            &format!("{SPHERES}\n[cell]\n{cell}\n"),
            field,
            marker,
            needle,
        );
    }
    let newton =
        format!("{SPHERES}\n[solver]\nkind = \"newton\"\n[cell]\nsize = [0.2, 0.2, 0.2]\n");
    error3(
        &newton,
        "solver.kind",
        "kind = \"newton\"",
        "solved by NLGS",
    );
    let micro = format!("{SPHERES}\n[output]\nmicro = \"cell\"\n");
    error3(&micro, "output.micro", "micro", "has no `[cell]`");
}

/// `[[events]]` in 3D: friction, drives of the six degrees of freedom, and the cell's
/// components (a triaxial test's stages); refusals with their field and reason.
#[test]
fn events_in_3d_change_friction_drives_and_the_cell() {
    use xper_scene::{CellLoadDesc, Drive, TimeFunction};
    let cell = "[cell]\nsize = [0.2, 0.2, 0.2]\nmass = 0.5\nxx = { stress = 1e4 }\n\
                yy = { stress = 1e4 }\nzz = { stress = 1e4 }\n";
    let s = ok3(&format!(
        "{SPHERES}\n{cell}\n[[events]]\ntime = 0.5\n\
         friction = [{{ between = [\"g\", \"g\"], value = 0.5 }}]\n\
         cell = {{ zz = {{ rate = -0.1 }}, xz = {{ rate = 1.0 }} }}\n\
         [[events]]\ntime = 0.2\ndrives = [{{ group = \"g\", drive = {{ z = {{ velocity = 1.0 }}, rz = {{ force = 2.0 }} }} }}]\n"
    ));
    assert_eq!(s.events.len(), 2);
    let (first, second) = (&s.events[0], &s.events[1]);
    assert_eq!(first.time, 0.2);
    assert_eq!(first.drives.len(), 40);
    assert_eq!(
        first.drives[0],
        (0, 2, Drive::Velocity(TimeFunction::Constant(1.0)))
    );
    assert_eq!(
        first.drives[1],
        (0, 5, Drive::Force(TimeFunction::Constant(2.0)))
    );
    assert_eq!(second.frictions, vec![([0, 0], 0.5)]);
    assert_eq!(
        second.cell,
        vec![
            ([0, 2], CellLoadDesc::Rate(TimeFunction::Constant(1.0))),
            ([2, 2], CellLoadDesc::Rate(TimeFunction::Constant(-0.1))),
        ]
    );
    let event = |body: &str| format!("{SPHERES}\n{cell}\n[[events]]\ntime = 0.1\n{body}\n");
    let cases = [
        (
            event("cell = { zx = { rate = 1.0 } }"),
            "events[0].cell.zx",
            "zx",
            "dz/dx stays zero",
        ),
        (
            event("cell = { zz = { rate = 1.0, stress = 2.0 } }"),
            "events[0].cell.zz",
            "cell = {",
            "either `rate` (1/s) or `stress` (Pa)",
        ),
        (
            event("cell = { ww = { rate = 1.0 } }"),
            "events[0].cell.ww",
            "ww",
            "unknown key",
        ),
        (
            event("drives = [{ group = \"g\", drive = { rotation = { velocity = 1.0 } } }]"),
            "events[0].drives[0].drive.rotation",
            "rotation",
            "unknown key",
        ),
        (
            format!(
                "{SPHERES}\n[cell]\nsize = [0.2, 0.2, 0.2]\n[[events]]\ntime = 0.1\n\
                 cell = {{ zz = {{ stress = 1e4 }} }}\n"
            ),
            "events[0].cell.zz",
            "cell = {",
            "needs the cell's `mass`",
        ),
        (
            format!(
                "{SPHERES}\n[cell]\nsize = [0.2, 0.2, 0.2]\nperiodic = [\"x\", \"y\"]\n\
                 [[events]]\ntime = 0.1\ncell = {{ zz = {{ rate = -1.0 }} }}\n"
            ),
            "events[0].cell.zz",
            "cell = {",
            "not periodic along z",
        ),
        (
            format!("{SPHERES}\n[[events]]\ntime = 0.1\ncell = {{ zz = {{ rate = -1.0 }} }}\n"),
            "events[0].cell",
            "cell = {",
            "no `[cell]` to change",
        ),
    ];
    for (text, field, marker, needle) in cases {
        error3(&text, field, marker, needle);
    }
}
