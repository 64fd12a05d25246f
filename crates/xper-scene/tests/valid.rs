//! A valid scene using every feature parses to the expected values.

mod common;
use common::*;
use std::f64::consts::PI;
use xper_scene::{ConvergenceNorm, Drive, ShapeDesc, TimeFunction};

const FULL: &str = r#"
[scene]
name = "everything"
dt = 1e-3
duration = 0.1
theta = 0.75
gravity = [1.0, -5.0]

[solver]
kind = "nlgs"
tolerance = 1e-6
max_iterations = 500
check_every = 5
relaxation = 0.9
norm = "natural_map"
position_projection = false

[output]
frame_every = 7
checkpoint_every = 50

[[materials]]
name = "glass"
density = 2500.0

[[materials]]
name = "steel"
density = 7800

[[laws]]
between = ["grains", "walls"]
kind = "signorini_coulomb"
friction = 0.3
restitution = 0.5

[[laws]]
between = ["blocks", "grains"]
kind = "signorini_coulomb"
friction = 0.0

[[bodies]]
shape = "disk"
center = [0.0, 0.1]
radius = 0.01
angle = 0.2
material = "glass"
group = "grains"
velocity = [1.0, 2.0]
angular_velocity = 3.0
[bodies.drive]
x = { velocity = 0.1 }
y = { velocity = [[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]] }
rotation = { force = { sine = { amplitude = 1.0, frequency = 2.0 } } }

[[bodies]]
shape = "rectangle"
center = [0.5, 0.5]
size = [0.02, 0.01]
angle = 0.3
material = "steel"
group = "blocks"

[[bodies]]
shape = "polygon"
vertices = [[1.0, 1.0], [1.0, 2.0], [2.0, 1.0]]   # clockwise
material = "steel"
group = "blocks"

[[bodies]]
shape = "disk"
center = [3.0, 3.0]
radius = 0.5
mass = 2.0
inertia = 0.125
group = "grains"
fixed = true

[[walls]]
from = [-1.0, -1.0]
to = [1.0, -1.0]
group = "walls"
drive = { x = { velocity = { sine = { amplitude = 0.01, frequency = 5.0, phase = 1.0, offset = 0.5 } } } }

[[generators]]
kind = "box_of_disks"
count = 4
radius = [0.002, 0.002]
box = [[10.0, 10.0], [10.1, 10.1]]
material = "glass"
group = "generated"
"#;

#[test]
fn every_feature() {
    let s = ok(FULL);
    assert_eq!(s.name, "everything");
    assert_eq!(
        (s.dt, s.steps, s.theta, s.gravity),
        (1e-3, 100, 0.75, [1.0, -5.0])
    );
    // Default alert distance: 0.1 x the smallest disk radius (0.002 m, generated).
    assert!((s.alert_distance - 2e-4).abs() < 1e-18);
    let sv = &s.solver;
    assert_eq!(
        (
            sv.tolerance,
            sv.max_iterations,
            sv.check_every,
            sv.relaxation
        ),
        (1e-6, 500, 5, 0.9)
    );
    assert_eq!(
        (sv.norm, sv.position_projection),
        (ConvergenceNorm::NaturalMap, false)
    );
    assert_eq!((s.output.frame_every, s.output.checkpoint_every), (7, 50));
    assert_eq!(s.groups, ["grains", "blocks", "walls", "generated"]);
    assert_eq!(s.laws.len(), 2);
    assert_eq!(
        (s.laws[0].groups, s.laws[0].friction, s.laws[0].restitution),
        ([0, 2], 0.3, 0.5)
    );
    assert_eq!(
        (s.laws[1].groups, s.laws[1].friction, s.laws[1].restitution),
        ([1, 0], 0.0, 0.0)
    );
    assert_eq!(s.bodies.len(), 4 + 1 + 4);

    let d = &s.bodies[0];
    assert_eq!(d.shape, ShapeDesc::Disk { radius: 0.01 });
    assert_eq!(
        (d.position, d.angle, d.velocity, d.angular_velocity),
        ([0.0, 0.1], 0.2, [1.0, 2.0], 3.0)
    );
    let m = 2500.0 * PI * 0.01 * 0.01;
    assert!((d.mass - m).abs() < 1e-15 && (d.inertia - m * 1e-4 / 2.0).abs() < 1e-18);
    assert_eq!(d.group, 0);
    assert_eq!(d.drives[0], Drive::Velocity(TimeFunction::Constant(0.1)));
    assert_eq!(
        d.drives[1],
        Drive::Velocity(TimeFunction::Table(vec![
            (0.0, 0.0),
            (1.0, 2.0),
            (2.0, 0.0)
        ]))
    );
    let sine = TimeFunction::Sine {
        amplitude: 1.0,
        frequency: 2.0,
        phase: 0.0,
        offset: 0.0,
    };
    assert_eq!(d.drives[2], Drive::Force(sine));

    let r = &s.bodies[1];
    let (w, h) = (0.02, 0.01);
    let m = 7800.0 * w * h;
    assert!((r.mass - m).abs() < 1e-15 && (r.inertia - m * (w * w + h * h) / 12.0).abs() < 1e-18);
    assert_eq!((r.position, r.angle, r.group), ([0.5, 0.5], 0.3, 1));
    assert_eq!(
        r.shape,
        ShapeDesc::Polygon {
            vertices: vec![
                [-0.01, -0.005],
                [0.01, -0.005],
                [0.01, 0.005],
                [-0.01, 0.005]
            ]
        }
    );
    assert_eq!(r.drives, [Drive::Free, Drive::Free, Drive::Free]);

    // Triangle: centroid, CCW relative vertices, I = m (a^2 + b^2 + c^2) / 36 (side lengths).
    let t = &s.bodies[2];
    assert!((t.position[0] - 4.0 / 3.0).abs() < 1e-14 && (t.position[1] - 4.0 / 3.0).abs() < 1e-14);
    let ShapeDesc::Polygon { vertices } = &t.shape else {
        panic!("{:?}", t.shape)
    };
    assert_eq!(vertices.len(), 3);
    let area2: f64 = (0..3)
        .map(|i| {
            let (a, b) = (vertices[i], vertices[(i + 1) % 3]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    assert!(
        (area2 - 1.0).abs() < 1e-14,
        "counter-clockwise, area 0.5: {area2}"
    );
    let m = 7800.0 * 0.5;
    let sides = 1.0 + 1.0 + 2.0;
    assert!((t.mass - m).abs() < 1e-9);
    assert!(
        (t.inertia - m * sides / 36.0).abs() < 1e-9,
        "{} vs {}",
        t.inertia,
        m * sides / 36.0
    );
    assert_eq!(t.angle, 0.0);

    let f = &s.bodies[3];
    assert_eq!((f.mass, f.inertia), (2.0, 0.125));
    let zero = Drive::Velocity(TimeFunction::Constant(0.0));
    assert_eq!(f.drives, [zero.clone(), zero.clone(), zero.clone()]);

    let wl = &s.bodies[4];
    assert_eq!(wl.shape, ShapeDesc::Segment { half_length: 1.0 });
    assert_eq!((wl.position, wl.angle, wl.group), ([0.0, -1.0], 0.0, 2));
    assert_eq!((wl.mass, wl.inertia), (f64::INFINITY, f64::INFINITY));
    let sine = TimeFunction::Sine {
        amplitude: 0.01,
        frequency: 5.0,
        phase: 1.0,
        offset: 0.5,
    };
    assert_eq!(wl.drives, [Drive::Velocity(sine), zero.clone(), zero]);

    assert!(s.bodies[5..]
        .iter()
        .all(|b| b.group == 3 && b.shape == ShapeDesc::Disk { radius: 0.002 }));
}

#[test]
fn steps_from_duration_and_output_defaults() {
    let sc = |d: &str| ok(&HEADER.replace("steps = 10", &format!("duration = {d}")));
    assert_eq!(sc("1.1").steps, 1100); // 1.1 / 1e-3 = 1100.0000000000002
    assert_eq!(sc("0.0105").steps, 11); // rounded up
    assert_eq!(sc("0.0001").steps, 1);
    let out = |n: u64| {
        let s = ok(&HEADER.replace("steps = 10", &format!("steps = {n}")));
        (s.output.frame_every, s.output.checkpoint_every)
    };
    assert_eq!(out(1500), (15, 150));
    assert_eq!(out(1), (1, 1));
    assert_eq!(out(101), (2, 11));
    let s = ok(HEADER);
    assert_eq!(
        (s.theta, s.gravity, s.alert_distance),
        (0.5, [0.0, -9.81], 0.0)
    );
    assert_eq!(s.solver, xper_scene::SolverSettings::default());
}

#[test]
fn detection_configuration() {
    use xper_scene::Detection;
    let with = |d: &str| ok(&HEADER.replace("steps = 10", &format!("steps = 10\ndetection = {d}")));
    assert_eq!(with("\"begin\"").detection, Detection::Begin);
    assert_eq!(with("\"predicted\"").detection, Detection::Predicted);
    assert_eq!(ok(HEADER).detection, Detection::Begin);
}

#[test]
fn alert_distance_default_from_polygons() {
    let t = with_header("[[bodies]]\nshape = \"rectangle\"\ncenter = [0, 0]\nsize = [0.3, 0.4]\nmaterial = \"glass\"\ngroup = \"g\"\n");
    // Polygon size = twice the largest centroid-vertex distance = the diagonal, 0.5 m.
    assert!((ok(&t).alert_distance - 5e-4).abs() < 1e-15);
}

#[test]
fn time_function_eval() {
    let t = TimeFunction::Table(vec![(0.0, 0.0), (1.0, 2.0), (3.0, -2.0)]);
    let cases = [
        (-1.0, 0.0),
        (0.0, 0.0),
        (0.5, 1.0),
        (1.0, 2.0),
        (2.0, 0.0),
        (3.0, -2.0),
        (9.0, -2.0),
    ];
    for (x, y) in cases {
        assert!(
            (t.eval(x) - y).abs() < 1e-15,
            "f({x}) = {} != {y}",
            t.eval(x)
        );
    }
    assert_eq!(TimeFunction::Table(vec![(1.0, 4.0)]).eval(0.0), 4.0);
    assert_eq!(TimeFunction::Table(vec![]).eval(0.0), 0.0);
    assert_eq!(TimeFunction::Constant(3.0).eval(5.0), 3.0);
    let s = TimeFunction::Sine {
        amplitude: 2.0,
        frequency: 0.25,
        phase: 0.0,
        offset: 1.0,
    };
    assert!((s.eval(1.0) - 3.0).abs() < 1e-15);
}

#[test]
fn format_doc_example_parses() {
    let all = include_str!("../FORMAT.md");
    let doc = &all[..all.find("# Fracture scenes").expect("fracture section")];
    let start = doc.rfind("```toml\n").expect("example") + "```toml\n".len();
    let end = start + doc[start..].find("```").expect("end of example");
    let s = ok(&doc[start..end]);
    assert_eq!((s.steps, s.bodies.len()), (1000, 1 + 1 + 300 + 4));
    assert_eq!(s.groups, ["grains", "walls"]);
}
