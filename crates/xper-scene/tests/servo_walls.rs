//! Walls with a mass driven by a force or a pressure (servo walls), and `[output] micro`:
//! what is accepted, what the scene holds, and every refusal with its field, line and reason.

mod common;
use common::*;
use xper_scene::{Drive, ExtentDesc, MicroVolume, TimeFunction};

/// Four walls round [0, 1] x [0, 1] drawn counter-clockwise, groups `bottom`, `right`, `top`,
/// `left`; `top` gets `top_extra` lines.
fn box_walls(top_extra: &str) -> String {
    let wall = |from: [f64; 2], to: [f64; 2], group: &str, extra: &str| {
        format!("[[walls]]\nfrom = {from:?}\nto = {to:?}\ngroup = \"{group}\"\n{extra}\n")
    };
    [
        wall([0.0, 0.0], [1.0, 0.0], "bottom", ""),
        wall([1.0, 0.0], [1.0, 1.0], "right", ""),
        wall([1.0, 1.0], [0.0, 1.0], "top", top_extra),
        wall([0.0, 1.0], [0.0, 0.0], "left", ""),
    ]
    .concat()
}

#[test]
fn a_pressure_pushes_along_the_inward_normal_over_the_followed_length() {
    let s = ok(&with_header(&box_walls(
        "mass = 2.0\ndrive = { y = { pressure = 1e4, between = [\"left\", \"right\"] } }",
    )));
    let top = &s.bodies[2];
    assert_eq!(top.mass, 2.0);
    // A rod of length 1 m: I = m L^2 / 12.
    assert!((top.inertia - 2.0 / 12.0).abs() < 1e-15);
    let Drive::Pressure(p) = &top.drives[1] else {
        panic!("{:?}", top.drives[1]);
    };
    assert_eq!(p.pressure, TimeFunction::Constant(1e4));
    // Drawn from (1, 1) to (0, 1): its left normal points down, into the box.
    assert!((p.direction + 1.0).abs() < 1e-15);
    let ExtentDesc::Between { bodies, axis } = &p.extent[0] else {
        panic!("{:?}", p.extent);
    };
    assert_eq!(*bodies, [3, 1]);
    assert!((axis[0] + 1.0).abs() < 1e-15 && axis[1].abs() < 1e-15);
    // The other dofs stay imposed at rest.
    assert_eq!(top.drives[0], Drive::Velocity(TimeFunction::Constant(0.0)));
    // Without `between`, the wall's own length.
    let s = ok(&with_header(&box_walls(
        "mass = 2.0\ndrive = { y = { pressure = 1e4 } }",
    )));
    let Drive::Pressure(p) = &s.bodies[2].drives[1] else {
        panic!();
    };
    assert_eq!(p.extent, vec![ExtentDesc::Fixed(1.0)]);
    // A force on a wall with a mass is accepted too.
    let s = ok(&with_header(&box_walls(
        "mass = 2.0\ndrive = { y = { force = -5.0 } }",
    )));
    assert_eq!(
        s.bodies[2].drives[1],
        Drive::Force(TimeFunction::Constant(-5.0))
    );
}

#[test]
fn refused_pressures_name_the_field_and_the_reason() {
    let t = with_header(&box_walls("drive = { y = { pressure = 1e4 } }"));
    expect_error(
        &t,
        "walls[2].drive.y.pressure",
        "pressure",
        "only when it has a `mass`",
    );
    let t = with_header(&box_walls("mass = 1.0\ndrive = { x = { pressure = 1e4 } }"));
    expect_error(
        &t,
        "walls[2].drive.x.pressure",
        "pressure",
        "no component along",
    );
    let t = with_header(&box_walls(
        "mass = 1.0\ndrive = { rotation = { pressure = 1e4 } }",
    ));
    expect_error(
        &t,
        "walls[2].drive.rotation.pressure",
        "pressure",
        "not a rotation",
    );
    let t = with_header(&box_walls("mass = -1.0"));
    expect_error(&t, "walls[2].mass", "mass = -1.0", "must be positive");
    let t = with_header(&box_walls(
        "mass = 1.0\ndrive = { y = { pressure = 1e4, between = [\"left\", \"nowhere\"] } }",
    ));
    expect_error(
        &t,
        "walls[2].drive.y.between",
        "between",
        "no body is in group `nowhere`",
    );
    let t = with_header(&box_walls(
        "mass = 1.0\ndrive = { y = { pressure = 1e4, between = [\"left\"] } }",
    ));
    expect_error(&t, "walls[2].drive.y.between", "between", "two group names");
    let two = box_walls(
        "mass = 1.0\ndrive = { y = { pressure = 1e4, between = [\"left\", \"right\"] } }",
    )
    .replace("group = \"left\"", "group = \"right\"");
    let t = with_header(&two);
    expect_error(
        &t,
        "walls[2].drive.y.between",
        "between",
        "more than one body",
    );
    let t = with_header(
        "[[bodies]]\nshape = \"disk\"\ncenter = [0.0, 0.0]\nradius = 0.01\nmaterial = \"glass\"\n\
         group = \"g\"\ndrive = { x = { pressure = 1.0 } }\n",
    );
    expect_error(
        &t,
        "bodies[0].drive.x.pressure",
        "drive",
        "drive a body by a `force`",
    );
    let t = with_header(&box_walls("drive = { y = { force = 1.0 } }"));
    expect_error(&t, "walls[2].drive.y.force", "force", "give it a `mass`");
}

#[test]
fn a_refused_wall_with_a_pressure_span_is_an_error_not_a_panic() {
    // The wall is not built (no group): its `between` must not be resolved for another body.
    let t = with_header(
        "[[walls]]\nfrom = [1.0, 1.0]\nto = [0.0, 1.0]\nmass = 1.0\n\
         drive = { y = { pressure = 1e4, between = [\"a\", \"b\"] } }\n",
    );
    expect_error(
        &t,
        "walls[0].group",
        "[[walls]]",
        "missing required key `group`",
    );
}

#[test]
fn micro_output_setting() {
    let s = ok(&with_header("[output]\nmicro = \"grains\"\n"));
    assert_eq!(s.output.micro, Some(MicroVolume::Grains));
    assert_eq!(ok(HEADER).output.micro, None);
    let t = with_header("[output]\nmicro = \"box\"\n");
    expect_error(&t, "output.micro", "micro", "box");
}

#[test]
fn events_change_friction_and_drives_at_their_time() {
    let walls = box_walls("mass = 2.0\ndrive = { y = { pressure = 1e4 } }");
    let laws =
        "[[laws]]\nbetween = [\"top\", \"top\"]\nkind = \"signorini_coulomb\"\nfriction = 0.0\n";
    let event = |time: &str, body: &str| format!("[[events]]\ntime = {time}\n{body}\n");
    let t = with_header(&format!(
        "{walls}{laws}{}{}",
        event(
            "0.5",
            "drives = [{ group = \"top\", drive = { y = { velocity = -0.1 } } }]"
        ),
        event(
            "0.25",
            "friction = [{ between = [\"top\", \"top\"], value = 0.4 }]"
        ),
    ));
    let s = ok(&t);
    // Sorted by time.
    assert_eq!(s.events.len(), 2);
    assert_eq!(s.events[0].time, 0.25);
    assert_eq!(s.events[0].frictions, vec![([2, 2], 0.4)]);
    assert_eq!(
        s.events[1].drives,
        vec![(2, 1, Drive::Velocity(TimeFunction::Constant(-0.1)))]
    );

    let bad = |body: &str| with_header(&format!("{walls}{laws}{}", event("0.5", body)));
    let t = bad("friction = [{ between = [\"top\", \"left\"], value = 0.4 }]");
    expect_error(
        &t,
        "events[0].friction[0].between",
        "value = 0.4",
        "no law between `top` and `left`",
    );
    let t = bad("friction = [{ between = [\"top\", \"top\"], value = -1.0 }]");
    expect_error(
        &t,
        "events[0].friction[0].value",
        "value = -1.0",
        "must be >= 0",
    );
    let t = bad("drives = [{ group = \"nowhere\", drive = { y = { velocity = 1.0 } } }]");
    expect_error(
        &t,
        "events[0].drives[0].group",
        "drives",
        "no group named `nowhere`",
    );
    let t = bad("drives = [{ group = \"left\", drive = { y = { force = 1.0 } } }]");
    expect_error(
        &t,
        "events[0].drives[0].drive",
        "drives",
        "a force cannot move it",
    );
    let t = bad("drives = [{ group = \"top\", drive = { y = { pressure = 1.0 } } }]");
    expect_error(
        &t,
        "events[0].drives[0].drive.y.pressure",
        "drives",
        "give a pressure in the wall's own",
    );
    let t = with_header(&format!("{walls}{laws}[[events]]\ntime = -1.0\n"));
    expect_error(&t, "events[0].time", "time = -1.0", "must be >= 0");
}
