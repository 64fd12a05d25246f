//! `[periodic]` and the `periodic_cell` generator in a fracture scene: a valid cell builds its
//! interfaces across the sides and its drives; each error names its key.

mod common;

use common::fracture::*;

const PERIODIC: &str = r#"[scene]
name = "cell"
dt = 1e-10
steps = 10
gravity = [0.0, 0.0]

[fracture]
thickness = 1.0

[mesh]
generator = "periodic_cell"
width = 5e-5
height = 4e-5
element_size = 5e-6
circles = [{ center = [0.0, 2e-5], radius = 1e-5 }]
random = { fraction = 0.1, radius = 5e-6, min_spacing = 2e-6, seed = 4 }

[periodic]
strain_xx = [[0.0, 0.0], [1e-6, 0.01]]
stress_yy = 0.0
strain_xy = 0.0

[[regions]]
name = "matrix"
material = { kind = "elastic", young = 99e9, poisson = 0.325, density = 7850.0 }

[[regions]]
name = "inclusion"
material = { kind = "elastic", young = 135e9, poisson = 0.32, density = 7850.0 }

[[interfaces]]
between = ["matrix", "matrix"]
law = { kind = "cohesive", normal_stiffness = 2e19, tangential_stiffness = 2e19, fracture_energy = 0.5, strength = 3e8 }

[[interfaces]]
between = ["matrix", "inclusion"]
law = { kind = "cohesive", normal_stiffness = 4e19, tangential_stiffness = 4e19, fracture_energy = 5.0, strength = 3e8 }

[[interfaces]]
between = ["inclusion", "inclusion"]
law = { kind = "cohesive", normal_stiffness = 4e19, tangential_stiffness = 4e19, fracture_energy = 0.4, strength = 3e8 }
"#;

#[test]
fn periodic_cell_scene_builds_its_cell_and_drives() {
    use xper_fracture::MacroDrive;
    let s = parse(PERIODIC).unwrap_or_else(|e| panic!("{e}"));
    let setup = s.build().unwrap_or_else(|e| panic!("{e}"));
    let p = setup.spec.periodic.as_ref().unwrap();
    assert_eq!(p.cell.size, [5e-5, 4e-5]);
    assert!(matches!(p.drives[0], MacroDrive::Strain(_)));
    assert!(matches!(p.drives[1], MacroDrive::Stress(_)));
    let pairs = setup.mesh.periodic_edges(&p.cell).unwrap();
    assert!(!pairs.is_empty());
    let model = xper_fracture::FractureModel::new(setup.mesh, setup.spec).unwrap();
    let across = model
        .interfaces
        .iter()
        .filter(|i| i.period != [0.0; 2])
        .count();
    assert_eq!(across, pairs.len());
    assert_eq!(2 * model.interfaces.len(), 3 * model.elements.len());
}

#[test]
fn periodic_errors_name_the_key() {
    let t = PERIODIC.replace("stress_yy = 0.0", "stress_yy = 0.0\nstrain_yy = 0.0");
    expect_error(&t, "periodic.stress_yy", "stress_yy", "not both");
    let t = PERIODIC.replace("strain_xy = 0.0\n", "");
    expect_error(
        &t,
        "periodic.strain_xy",
        "[periodic]",
        "give strain_xy or stress_xy",
    );
    let t = PERIODIC.replace("strain_xy = 0.0", "strain_xy = 0.0\nstrain_zz = 0.0");
    expect_error(&t, "periodic.strain_zz", "strain_zz", "unknown key");
    let t = PERIODIC.replace("stress_yy = 0.0", "stress_yy = \"free\"");
    expect_error(&t, "periodic.stress_yy", "stress_yy", "a number, an array");
    let t = PERIODIC.replace(
        "strain_xy = 0.0",
        "strain_xy = 0.0\ncell = [[0.0, 0.0], [6e-5, 4e-5]]",
    );
    expect_error(
        &t,
        "periodic",
        "[periodic]",
        "the mesh is not a periodic cell",
    );
    let t = PERIODIC.replace("radius = 1e-5 }", "radius = 3e-5 }");
    expect_error(&t, "mesh.circles", "circles", "radius in (0");
    let t = PERIODIC.replace("fraction = 0.1", "fraction = 0.7");
    expect_error(&t, "mesh.random.fraction", "random", "in (0, 0.6)");
}
