//! 3D walls with a mass driven by a force or a pressure (servo walls of a triaxial test): what
//! the scene holds (mass, plate inertia, the loaded area's factors and axes), and every
//! refusal with its field, line and reason.

mod common;

use common::{expect_error_any, ok3_text};
use xper_scene::{Drive, ExtentDesc, TimeFunction};

const HEADER3: &str = r#"[scene]
name = "t"
dimension = 3
dt = 1e-3
steps = 10
"#;

/// Six half-spaces round the unit cube, normals inwards, groups `bottom`, `top`, `xmin`,
/// `xmax`, `ymin`, `ymax` in that order; the lines of `extra` are added to the wall of group
/// `driven`.
fn cube(driven: &str, extra: &str) -> String {
    let walls = [
        ("bottom", [0.5, 0.5, 0.0], [0.0, 0.0, 1.0]),
        ("top", [0.5, 0.5, 1.0], [0.0, 0.0, -1.0]),
        ("xmin", [0.0, 0.5, 0.5], [1.0, 0.0, 0.0]),
        ("xmax", [1.0, 0.5, 0.5], [-1.0, 0.0, 0.0]),
        ("ymin", [0.5, 0.0, 0.5], [0.0, 1.0, 0.0]),
        ("ymax", [0.5, 1.0, 0.5], [0.0, -1.0, 0.0]),
    ];
    let mut text = HEADER3.to_string();
    for (group, point, normal) in walls {
        text +=
            &format!("\n[[walls]]\npoint = {point:?}\nnormal = {normal:?}\ngroup = \"{group}\"\n");
        if group == driven {
            text += extra;
            text += "\n";
        }
    }
    text
}

#[test]
fn a_pressure_acts_on_the_cross_section_between_two_pairs_of_walls() {
    let s = ok3_text(&cube(
        "xmax",
        "mass = 0.5\ndrive = { x = { pressure = 1e4, between = [[\"ymin\", \"ymax\"], [\"top\", \"bottom\"]] } }",
    ));
    let wall = &s.bodies[3];
    assert_eq!(wall.mass, 0.5);
    // A half-space: infinite inertia, its rotations imposed.
    assert!(wall.inertia.iter().flatten().all(|x| x.is_infinite()));
    let Drive::Pressure(p) = &wall.drives[0] else {
        panic!("{:?}", wall.drives[0]);
    };
    assert_eq!(p.pressure, TimeFunction::Constant(1e4));
    // The normal points along -x, into the cube.
    assert!((p.direction + 1.0).abs() < 1e-15);
    // Each distance along the normal of its pair's first wall: ymin's +y, top's -z.
    let expected = [([4, 5], [0.0, 1.0, 0.0]), ([1, 0], [0.0, 0.0, -1.0])];
    assert_eq!(p.extent.len(), 2);
    for (factor, (bodies, axis)) in p.extent.iter().zip(expected) {
        let ExtentDesc::Between { bodies: b, axis: a } = factor else {
            panic!("{factor:?}");
        };
        assert_eq!(*b, bodies);
        assert!((0..3).all(|k| (a[k] - axis[k]).abs() < 1e-15), "{a:?}");
    }
    // The other degrees of freedom stay imposed at rest.
    for d in 1..6 {
        assert_eq!(wall.drives[d], Drive::Velocity(TimeFunction::Constant(0.0)));
    }
    // A finite wall without `between`: its own area, and a plate's inertia
    // diag(m b^2, m a^2, m (a^2 + b^2)) / 12 along its edges.
    let s = ok3_text(&cube(
        "top",
        "size = [2.0, 3.0]\nedge = [1.0, 0.0, 0.0]\nmass = 1.2\ndrive = { z = { pressure = 5e3 }, rz = { force = 1.0 } }",
    ));
    let top = &s.bodies[1];
    let Drive::Pressure(p) = &top.drives[2] else {
        panic!("{:?}", top.drives[2]);
    };
    assert_eq!(
        p.extent,
        vec![ExtentDesc::Fixed(2.0), ExtentDesc::Fixed(3.0)]
    );
    assert!((p.direction + 1.0).abs() < 1e-15);
    let i = top.inertia;
    let diag = [1.2 * 9.0 / 12.0, 1.2 * 4.0 / 12.0, 1.2 * 13.0 / 12.0];
    for r in 0..3 {
        for c in 0..3 {
            let want = if r == c { diag[r] } else { 0.0 };
            assert!((i[r][c] - want).abs() < 1e-15, "{i:?}");
        }
    }
    assert_eq!(top.drives[5], Drive::Force(TimeFunction::Constant(1.0)));
}

#[test]
fn refused_3d_pressures_name_the_field_and_the_reason() {
    let between = "between = [[\"ymin\", \"ymax\"], [\"bottom\", \"top\"]]";
    let pressure = |dof: &str, rest: &str| {
        format!("mass = 1.0\ndrive = {{ {dof} = {{ pressure = 1e4{rest} }} }}")
    };
    let text = cube(
        "xmax",
        &format!("drive = {{ x = {{ pressure = 1e4, {between} }} }}"),
    );
    expect_error_any(
        &text,
        "walls[3].drive.x.pressure",
        "pressure",
        "only when it has a `mass`",
    );
    let text = cube("xmax", &pressure("x", ""));
    expect_error_any(
        &text,
        "walls[3].drive.x.between",
        "pressure",
        "a half-space has no area",
    );
    let text = cube("xmax", &pressure("x", ", between = [\"ymin\", \"ymax\"]"));
    expect_error_any(
        &text,
        "walls[3].drive.x.between",
        "pressure",
        "two pairs of group names",
    );
    let text = cube("xmax", &pressure("y", &format!(", {between}")));
    expect_error_any(
        &text,
        "walls[3].drive.y.pressure",
        "pressure",
        "no component along",
    );
    let text = cube("xmax", &pressure("rz", &format!(", {between}")));
    expect_error_any(
        &text,
        "walls[3].drive.rz.pressure",
        "pressure",
        "not a rotation",
    );
    // A pair measured across the wall's normal, two pairs along one axis, groups that are
    // not one wall each.
    let across = ", between = [[\"xmin\", \"xmax\"], [\"bottom\", \"top\"]]";
    let text = cube("xmax", &pressure("x", across));
    expect_error_any(
        &text,
        "walls[3].drive.x.between",
        "pressure",
        "does not lie in the plane",
    );
    let same = ", between = [[\"ymin\", \"ymax\"], [\"ymax\", \"ymin\"]]";
    let text = cube("xmax", &pressure("x", same));
    expect_error_any(
        &text,
        "walls[3].drive.x.between",
        "pressure",
        "the same axis",
    );
    let unknown = ", between = [[\"ymin\", \"nowhere\"], [\"bottom\", \"top\"]]";
    let text = cube("xmax", &pressure("x", unknown));
    expect_error_any(
        &text,
        "walls[3].drive.x.between",
        "pressure",
        "no body is in group `nowhere`",
    );
    let sphere = "\n[[bodies]]\nshape = \"sphere\"\ncenter = [0.5, 0.5, 0.5]\nradius = 0.1\nmass = 1.0\ninertia = [1.0, 1.0, 1.0]\ngroup = \"ball\"\n";
    let ball = ", between = [[\"ball\", \"ymax\"], [\"bottom\", \"top\"]]";
    let text = cube("xmax", &pressure("x", ball)) + sphere;
    expect_error_any(
        &text,
        "walls[3].drive.x.between",
        "pressure",
        "is not a wall",
    );
    let twice = cube("xmax", &pressure("x", &format!(", {between}")))
        + "\n[[walls]]\npoint = [0.5, 0.0, 0.5]\nnormal = [0.0, 1.0, 0.0]\ngroup = \"ymin\"\n";
    expect_error_any(
        &twice,
        "walls[3].drive.x.between",
        "pressure",
        "more than one body",
    );
    // Walls apart by 0 along the pair's axis.
    let flat = cube("xmax", &pressure("x", &format!(", {between}")))
        .replace("point = [0.5, 1.0, 0.5]", "point = [0.5, 0.0, 0.5]");
    expect_error_any(&flat, "walls[3].drive.x.between", "pressure", "0 m apart");
    // Masses, forces and rotations.
    let text = cube("xmax", "mass = -1.0");
    expect_error_any(&text, "walls[3].mass", "mass = -1.0", "> 0 kg");
    let text = cube("xmax", "drive = { x = { force = 1.0 } }");
    expect_error_any(
        &text,
        "walls[3].drive.x.force",
        "force",
        "cannot be driven by a force",
    );
    let text = cube("xmax", "mass = 1.0\ndrive = { ry = { force = 1.0 } }");
    expect_error_any(
        &text,
        "walls[3].drive",
        "drive",
        "infinite moment of inertia",
    );
    // Events: a force on the translation of a wall with a mass is taken, a torque on a
    // half-space is not.
    let event = |drive: &str| {
        cube("xmax", "mass = 1.0")
            + &format!("\n[[events]]\ntime = 0.1\ndrives = [{{ group = \"xmax\", drive = {{ {drive} }} }}]\n")
    };
    let s = ok3_text(&event("x = { force = -2.0 }"));
    assert_eq!(
        s.events[0].drives,
        vec![(3, 0, Drive::Force(TimeFunction::Constant(-2.0)))]
    );
    let text = event("rx = { force = 1.0 }");
    let field = "events[0].drives[0].drive";
    expect_error_any(
        &text,
        field,
        "drives",
        "infinite moment of inertia (a half-space)",
    );
}
