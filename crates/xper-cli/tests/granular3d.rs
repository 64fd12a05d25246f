//! The 3D granular laboratory between walls: a servo wall moves under its pressure times the
//! cross-section it follows (against the theta-method worked out here), servo walls hold
//! their pressure on a packing at rest, and the packing's granular stress equals the wall
//! forces over the wall areas (two independent measures of one stress); the walled triaxial
//! test of `scenes/triaxial_walls_3d` keeps its confinement while it is compressed.

use std::path::Path;
use xper_math3d::{Real, Vector};
use xper_nscd3d::micro::{contact_force, measure, VolumeSource};
use xper_nscd3d::{MoreauJean, World};
use xper_scene::{AnyScene, Scene3};
use xper_simulation::rigid3d::build::world_from_scene;

const SCENE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenes/triaxial_walls_3d"
);

/// The scene's walls, bodies 0 to 5 (walls come before generated bodies).
const BOTTOM: usize = 0;
const TOP: usize = 1;
const XMIN: usize = 2;
const XMAX: usize = 3;
const YMIN: usize = 4;
const YMAX: usize = 5;
const CONFINING: Real = 1e4;

fn scene3(text: &str) -> Scene3 {
    match xper_scene::parse_any_scene(text, Path::new("scene.toml")) {
        Ok(AnyScene::Rigid3(s)) => s,
        Ok(_) => panic!("not a 3D scene"),
        Err(e) => panic!("{e}"),
    }
}

fn relative(a: Real, b: Real) -> Real {
    (a - b).abs() / b.abs()
}

/// A wall of mass `m` under a pressure `P` over the distances between two pairs of walls,
/// one of which is driven apart at 1 m/s from rest: with the area `A_k` measured at the
/// beginning of step `k`, `v_{k+1} = v_k - h P A_k / m` and `x_{k+1} = x_k + h (v_k +
/// v_{k+1}) / 2` (theta 1/2); the driven wall moves by `h (0 + 1) / 2` in its first step (its
/// velocity goes from 0 to the imposed 1 m/s), then by `h` per step.
#[test]
fn a_servo_wall_moves_under_its_pressure_times_the_cross_section_it_follows() {
    let (m, p, h, steps) = (0.5, 10.0, 1e-3, 40);
    let walls = [
        ("bottom", [0.5, 0.5, 0.0], [0.0, 0.0, 1.0], ""),
        ("top", [0.5, 0.5, 1.0], [0.0, 0.0, -1.0], ""),
        ("ymin", [0.5, 0.0, 0.5], [0.0, 1.0, 0.0], ""),
        (
            "ymax",
            [0.5, 1.0, 0.5],
            [0.0, -1.0, 0.0],
            "drive = { y = { velocity = 1.0 } }",
        ),
    ];
    let mut text = format!(
        "[scene]\nname = \"servo\"\ndimension = 3\ndt = {h}\nsteps = {steps}\ngravity = [0.0, 0.0, 0.0]\n"
    );
    for (group, point, normal, extra) in walls {
        text += &format!(
            "\n[[walls]]\npoint = {point:?}\nnormal = {normal:?}\ngroup = \"{group}\"\n{extra}\n"
        );
    }
    text += &format!(
        "\n[[walls]]\npoint = [1.0, 0.5, 0.5]\nnormal = [-1.0, 0.0, 0.0]\ngroup = \"xmax\"\nmass = {m}\n\
         drive = {{ x = {{ pressure = {p}, between = [[\"ymin\", \"ymax\"], [\"bottom\", \"top\"]] }} }}\n"
    );
    let mut world = world_from_scene(&scene3(&text));
    let mut stepper = MoreauJean::new();
    let (mut x, mut v) = (1.0, 0.0);
    let (mut y, mut vy) = (1.0, 0.0);
    for k in 0..steps {
        let area = (y - 0.0) * (1.0 - 0.0);
        let v1 = v - h * p * area / m;
        x += h * (v + v1) / 2.0;
        v = v1;
        y += h * (vy + 1.0) / 2.0;
        vy = 1.0;
        stepper.step(&mut world).unwrap();
        let (got_x, got_v) = (world.bodies.position[4].x, world.bodies.velocity[4].x);
        assert!(
            (got_v - v).abs() <= 1e-12 * v.abs(),
            "step {k}: v {got_v} against {v}"
        );
        assert!(
            (got_x - x).abs() <= 1e-12,
            "step {k}: x {got_x} against {x}"
        );
        // Its other degrees of freedom stay at rest.
        let w = &world.bodies;
        assert_eq!([w.velocity[4].y, w.velocity[4].z], [0.0, 0.0]);
        assert_eq!(w.angular_velocity[4].norm(), 0.0);
    }
    // Far from the constant-area answer: the followed area matters here.
    let constant = 1.0 - p / m * (h * steps as Real).powi(2) / 2.0;
    assert!((x - constant).abs() > 1e3 * 1e-12, "{x} {constant}");
}

/// `scenes/triaxial_walls_3d` cut to 250 spheres in a 25 mm box, with friction 0.3 from the
/// start (a frictional packing jams and comes to rest), its event at `event` s.
fn reduced_scene(event: Real, steps: u64) -> String {
    let text = std::fs::read_to_string(Path::new(SCENE).join("scene.toml")).unwrap();
    let mut text = text
        .replace("count = 1000", "count = 250")
        .replace("steps = 5300 ", &format!("steps = {steps} "))
        .replace("time = 0.3 ", &format!("time = {event} "))
        .replace(
            "friction = 0.0          # stage 1",
            "friction = 0.3          # stage 1",
        );
    for (from, to) in [
        ("0.04", "0.025"),
        ("0.02,", "0.0125,"),
        ("0.02]", "0.0125]"),
    ] {
        text = text.replace(from, to);
    }
    assert!(text.contains("count = 250") && text.contains("friction = 0.3 "));
    text
}

/// The stresses the walls bear (top, xmax, ymax, bottom, xmin, ymin), each the contacts'
/// force along the wall's normal over the sample's cross-section the wall sees (Pa).
fn wall_stresses(world: &World) -> [Real; 6] {
    let x = |b: usize| world.bodies.position[b];
    let size = Vector::new(
        x(XMAX).x - x(XMIN).x,
        x(YMAX).y - x(YMIN).y,
        x(TOP).z - x(BOTTOM).z,
    );
    let f = |b| contact_force(world, b);
    [
        f(TOP).z / (size.x * size.y),
        f(XMAX).x / (size.y * size.z),
        f(YMAX).y / (size.x * size.z),
        -f(BOTTOM).z / (size.x * size.y),
        -f(XMIN).x / (size.y * size.z),
        -f(YMIN).y / (size.x * size.z),
    ]
}

#[test]
fn servo_walls_hold_their_pressure_and_the_granular_stress_is_the_wall_stress_in_3d() {
    let scene = scene3(&reduced_scene(10.0, 3000));
    let mut world = world_from_scene(&scene);
    let mut stepper = MoreauJean::new();
    for _ in 0..scene.steps {
        stepper.step(&mut world).unwrap();
    }
    let walls = wall_stresses(&world);
    let m = measure(&world, VolumeSource::Walls).unwrap();
    let s = |k: usize| m.stress[(k, k)];
    eprintln!(
        "wall stresses (top, xmax, ymax, bottom, xmin, ymin) {walls:?} Pa; sigma {:?} Pa; \
         kinetic energy {} J",
        [s(0), s(1), s(2)],
        world.kinetic_energy()
    );
    // The servo walls hold their pressure within 1 % once the sample is at rest (0.1 s after
    // the ramp to 10 kPa ends).
    for w in &walls[..3] {
        assert!(relative(*w, CONFINING) < 0.01, "{walls:?}");
    }
    // The granular stress from every contact's branch vector equals the fixed walls' forces
    // over their areas: 1e-3 covers the solver's relative tolerance (1e-4) and the residual
    // inertia.
    assert!(relative(s(2), walls[3]) < 1e-3, "{} {walls:?}", s(2));
    assert!(relative(s(0), walls[4]) < 1e-3, "{} {walls:?}", s(0));
    assert!(relative(s(1), walls[5]) < 1e-3, "{} {walls:?}", s(1));
    // Shear stresses: symmetric (moment balance of the grains).
    for (a, b) in [(0, 1), (0, 2), (1, 2)] {
        assert!((m.stress[(a, b)] - m.stress[(b, a)]).abs() < 1e-6 * s(0));
    }
}

#[test]
fn the_walled_triaxial_test_compresses_at_its_velocity_and_keeps_its_confinement() {
    // Compaction to 0.25 s, then 300 steps of compression.
    let scene = scene3(&reduced_scene(0.25, 2800));
    let mut world = world_from_scene(&scene);
    let mut stepper = MoreauJean::new();
    let mut lateral = Vec::new();
    let mut top_before = None;
    for k in 0..scene.steps {
        stepper.step(&mut world).unwrap();
        if k + 1 == 2500 {
            top_before = Some((world.bodies.position[TOP].z, world.bodies.velocity[TOP].z));
            let walls = wall_stresses(&world);
            // Isotropic before the event.
            for w in &walls[..3] {
                assert!(relative(*w, CONFINING) < 0.02, "{walls:?}");
            }
        }
        if k + 1 > 2600 {
            let walls = wall_stresses(&world);
            lateral.push([walls[1], walls[2]]);
        }
    }
    // The top wall moved at its imposed 24 mm/s after the event: in the event's step by the
    // theta-mean of its servo velocity then and the new one, by `h` times 24 mm/s after.
    let (z0, v0) = top_before.unwrap();
    let h = scene.dt;
    let expected = h * (0.024 - v0) / 2.0 + 299.0 * h * 0.024;
    let moved = z0 - world.bodies.position[TOP].z;
    assert!(relative(moved, expected) < 1e-12, "{moved} {expected}");
    // The lateral servo walls keep the confinement on average.
    let n = lateral.len() as Real;
    let mean = |k: usize| lateral.iter().map(|w| w[k]).sum::<Real>() / n;
    eprintln!(
        "lateral stresses while compressed: {} {} Pa",
        mean(0),
        mean(1)
    );
    assert!(relative(mean(0), CONFINING) < 0.05 && relative(mean(1), CONFINING) < 0.05);
    // The axial stress rises above the confinement: a deviator.
    let walls = wall_stresses(&world);
    let m = measure(&world, VolumeSource::Walls).unwrap();
    eprintln!("end: walls {walls:?} Pa, q/p {}", m.stress_ratio());
    assert!(walls[0] > 1.5 * CONFINING, "{walls:?}");
    assert!(m.stress_ratio() > 0.5, "{}", m.stress_ratio());
}

/// The volume of the measures is the box the walls face: a plane bounds the axis of its
/// normal only, so a top wall lowered below the lateral walls' given points (their centres)
/// still sets the height, and a finite plate turned about its normal bounds the same axis.
#[test]
fn the_box_of_the_walls_takes_each_wall_along_the_axis_it_faces() {
    let walls = [
        ("bottom", [0.5, 0.5, 0.0], [0.0, 0.0, 1.0], ""),
        (
            "top",
            [0.5, 0.5, 0.3],
            [0.0, 0.0, -1.0],
            "size = [2.0, 2.0]\nedge = [1.0, 1.0, 0.0]",
        ),
        ("xmin", [0.0, 0.5, 0.5], [1.0, 0.0, 0.0], ""),
        ("xmax", [1.0, 0.5, 0.5], [-1.0, 0.0, 0.0], ""),
        ("ymin", [0.5, 0.0, 0.5], [0.0, 1.0, 0.0], ""),
        ("ymax", [0.5, 1.0, 0.5], [0.0, -1.0, 0.0], ""),
    ];
    let mut text = "[scene]\nname = \"box\"\ndimension = 3\ndt = 1e-3\nsteps = 1\n\n\
                    [[bodies]]\nshape = \"sphere\"\ncenter = [0.5, 0.5, 0.15]\nradius = 0.1\n\
                    mass = 1.0\ninertia = [1.0, 1.0, 1.0]\ngroup = \"grain\"\n"
        .to_string();
    for (group, point, normal, extra) in walls {
        text += &format!(
            "\n[[walls]]\npoint = {point:?}\nnormal = {normal:?}\ngroup = \"{group}\"\n{extra}\n"
        );
    }
    let world = world_from_scene(&scene3(&text));
    let m = measure(&world, VolumeSource::Walls).unwrap();
    let want = [1.0, 1.0, 0.3];
    for (got, want) in m.extent.iter().zip(want) {
        assert!((got - want).abs() < 1e-15, "{:?}", m.extent);
    }
    let sphere = 4.0 / 3.0 * std::f64::consts::PI * 1e-3;
    assert!((m.solid_fraction - sphere / 0.3).abs() < 1e-15 * sphere / 0.3);
}
