//! `[cell]`: the periodic cell of a rigid scene: what a valid section holds, and every refusal
//! with its field, line and reason.

mod common;
use common::*;
use xper_scene::{CellLoadDesc, MicroVolume, TimeFunction};

const DISKS: &str = r#"
[[laws]]
between = ["g", "g"]
kind = "signorini_coulomb"
friction = 0.4

[[generators]]
kind = "box_of_disks"
count = 20
radius = [0.01, 0.01]
box = [[0.0, 0.0], [0.2, 0.2]]
placement = "random"
seed = 1
material = "glass"
group = "g"
"#;

fn scene(cell: &str) -> String {
    with_header(&format!("{DISKS}\n[cell]\n{cell}\n"))
}

#[test]
fn a_cell_holds_its_size_axes_mass_and_loads() {
    let s = ok(&scene(
        "origin = [0.0, 0.0]\nsize = [0.2, 0.2]\nmass = 0.5\nxy = { rate = 2.0 }\n\
         yy = { stress = [[0.0, 0.0], [1.0, 1e4]] }",
    ));
    let c = s.cell.unwrap();
    assert_eq!(c.size, [0.2, 0.2]);
    assert_eq!(c.periodic, [true, true]);
    assert_eq!(c.mass, 0.5);
    assert_eq!(
        c.loads[0][1],
        CellLoadDesc::Rate(TimeFunction::Constant(2.0))
    );
    assert_eq!(
        c.loads[1][1],
        CellLoadDesc::Stress(TimeFunction::Table(vec![(0.0, 0.0), (1.0, 1e4)]))
    );
    assert_eq!(
        c.loads[0][0],
        CellLoadDesc::Rate(TimeFunction::Constant(0.0))
    );
    let s = ok(&scene("size = [0.2, 0.2]\nperiodic = [\"x\"]"));
    assert_eq!(s.cell.unwrap().periodic, [true, false]);
    let text = format!(
        "{}\n[output]\nmicro = \"cell\"\n",
        scene("size = [0.2, 0.2]")
    );
    assert_eq!(ok(&text).output.micro, Some(MicroVolume::Cell));
}

#[test]
fn refused_cells_name_the_field_and_the_reason() {
    // (the `[cell]` lines, the field, a marker on the error's line, a part of its message)
    let cases = [
        ("size = [0.2, -0.2]", "cell.size", "size", "must be > 0 m"),
        ("origin = [0.0, 0.0]", "cell.size", "[cell]", "missing"),
        (
            "size = [0.2, 0.07]",
            "cell.size",
            "size",
            "four times the largest body",
        ),
        (
            "size = [0.2, 0.2]\nyx = { rate = 1.0 }",
            "cell.yx",
            "yx",
            "upper triangular",
        ),
        (
            "size = [0.2, 0.2]\nyy = { stress = 1e4 }",
            "cell.mass",
            "yy",
            "needs the cell's `mass`",
        ),
        (
            "size = [0.2, 0.2]\nmass = 0.0\nyy = { stress = 1e4 }",
            "cell.mass",
            "mass",
            "> 0 kg/m",
        ),
        (
            "size = [0.2, 0.2]\nxx = { rate = 1.0, stress = 2.0 }",
            "cell.xx",
            "xx",
            "either `rate`",
        ),
        (
            "size = [0.2, 0.2]\nperiodic = [\"x\"]\nyy = { rate = 1.0 }",
            "cell.yy",
            "yy",
            "not periodic along y",
        ),
        (
            "size = [0.2, 0.2]\nperiodic = [\"z\"]",
            "cell.periodic",
            "periodic",
            "unknown axis",
        ),
        (
            "size = [0.2, 0.2]\nspeed = 1.0",
            "cell.speed",
            "speed",
            "unknown",
        ),
    ];
    for (cell, field, marker, needle) in cases {
        expect_error(&scene(cell), field, marker, needle);
    }
    let t = format!(
        "{}\n[solver]\nkind = \"newton\"\n",
        scene("size = [0.2, 0.2]")
    );
    expect_error(&t, "solver.kind", "kind = \"newton\"", "solved by NLGS");
    let t = with_header(&format!("{DISKS}\n[output]\nmicro = \"cell\"\n"));
    expect_error(&t, "output.micro", "micro", "has no `[cell]`");
}

/// An `[[events]]` entry's `cell` table in 2D: the components given change their control;
/// the components of 3D cells and those below the diagonal are refused.
#[test]
fn events_change_the_control_of_cell_components() {
    let cell = "size = [0.2, 0.2]\nmass = 0.5\nxx = { stress = 1e4 }\nyy = { stress = 1e4 }\n\
                [[events]]\ntime = 0.3\n";
    let s = ok(&scene(&format!(
        "{cell}cell = {{ yy = {{ rate = [[0.3, 0.0], [0.4, -0.5]] }} }}"
    )));
    assert_eq!(
        s.events[0].cell,
        vec![(
            [1, 1],
            CellLoadDesc::Rate(TimeFunction::Table(vec![(0.3, 0.0), (0.4, -0.5)]))
        )]
    );
    expect_error(
        &scene(&format!("{cell}cell = {{ zz = {{ rate = 1.0 }} }}")),
        "events[0].cell.zz",
        "cell = {",
        "unknown key",
    );
    expect_error(
        &scene(&format!("{cell}cell = {{ yx = {{ rate = 1.0 }} }}")),
        "events[0].cell.yx",
        "cell = {",
        "upper triangular",
    );
}
