//! Fracture scenes: a valid scene parses and builds to the expected specification; each
//! kind of error names the field, the line of the offending value and the reason.

mod common;

use common::fracture::*;
use std::path::{Path, PathBuf};

use xper_bodies::{Drive, TimeFunction};
use xper_fem::{Hypothesis, Material};
use xper_fracture::{InterfaceLaw, MassMatrix};
use xper_scene::{load_any_scene, parse_any_scene, parse_scene, AnyScene, MeshSource, Stiffness};

const NOTCHED: &str = r#"[scene]
name = "notched"
dt = 2e-7
steps = 10
gravity = [0.0, 0.0]

[fracture]
thickness = 0.05
hypothesis = "plane_stress"

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
name = "pull"
nodes = { box = [[0.0, 0.0], [0.2, 0.0]] }
velocity = [[[0.0, 0.0], [1e-6, -0.1]], "free"]
force = ["free", { sine = { amplitude = 10.0, frequency = 1e3 } }]
"#;

const BIMATERIAL: &str = r#"[scene]
name = "bimaterial"
dt = 1e-11
steps = 10

[fracture]
thickness = 1.0
mass = "lumped"
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
law = { kind = "cohesive", normal_stiffness = "rule_of_thumb", tangential_stiffness = "rule_of_thumb", fracture_energy = 0.4, strength = 1e8 }

[[interfaces]]
between = ["matrix", "inclusion"]
law = { kind = "contact", friction = 0.3 }

[[loads]]
name = "left"
nodes = { segment = [[0.0, 0.0], [0.0, 5e-5]] }
velocity = [2.0, "free"]
"#;

#[test]
fn notched_scene_parses_and_builds() {
    let s = parse(NOTCHED).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((s.name.as_str(), s.steps, s.dt), ("notched", 10, 2e-7));
    assert_eq!(s.hypothesis, Hypothesis::PlaneStress);
    assert_eq!(s.mass, MassMatrix::Consistent);
    assert!(
        matches!(s.mesh.source, MeshSource::DoubleEdgeNotched(ref n) if n.element_size == 0.02)
    );
    assert_eq!(
        s.loads[1].drives[0],
        Drive::Velocity(TimeFunction::Table(vec![(0.0, 0.0), (1e-6, -0.1)]))
    );
    assert!(
        matches!(s.loads[1].drives[1], Drive::Force(TimeFunction::Sine { amplitude, .. }) if amplitude == 10.0)
    );
    let setup = s.build().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(setup.mesh.regions.len(), 1);
    assert_eq!(setup.spec.materials.len(), 1);
    assert_eq!(setup.spec.thickness, 0.05);
    assert_eq!(setup.spec.loads.len(), 2);
    let top = &setup.spec.loads[0];
    assert_eq!(top.nodes, setup.mesh.node_sets["top"]);
    assert!(top
        .nodes
        .iter()
        .all(|&n| setup.mesh.nodes[n as usize][1] == 0.2));
    let bottom = &setup.spec.loads[1];
    assert_eq!(bottom.nodes, setup.mesh.node_sets["bottom"]);
    assert_eq!(
        setup.interfaces,
        setup.mesh.neighbours().unwrap().interior.len()
    );
    let InterfaceLaw::Cohesive(z) = setup.spec.interface_laws[0].law else {
        panic!("cohesive law expected");
    };
    assert_eq!((z.initial_damage, z.friction, z.strength), (1.0, 0.0, 3e6));
}

#[test]
fn bimaterial_scene_computes_the_rule_of_thumb() {
    let s = parse(BIMATERIAL).unwrap_or_else(|e| panic!("{e}"));
    assert!(matches!(
        s.interfaces[1].law,
        xper_scene::InterfaceLawDesc::Cohesive {
            normal_stiffness: Stiffness::RuleOfThumb,
            ..
        }
    ));
    let setup = s.build().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(setup.spec.mass, MassMatrix::Lumped);
    assert_eq!(setup.spec.broken_edge_sets, vec!["precrack".to_string()]);
    let names: Vec<&str> = setup.mesh.regions.iter().map(|r| r.name.as_str()).collect();
    let m = names.iter().position(|&n| n == "matrix").unwrap();
    let i = names.iter().position(|&n| n == "inclusion").unwrap();
    assert!(
        matches!(setup.spec.materials[m], Material::J2Plastic { yield_stress, .. } if yield_stress == 250e6)
    );
    let rule = (setup.spec.interface_laws.iter())
        .find(|r| r.regions == [i as u32, i as u32])
        .unwrap();
    let InterfaceLaw::Cohesive(z) = rule.law else {
        panic!("cohesive law expected");
    };
    // C_N = 23 E / (L (1 - 2 nu)), C_T = 2 (1 - 2 nu) / (1 + 3 nu) C_N with L = 5e-6 m.
    let c_n = 23.0 * 135e9 / (5e-6 * (1.0 - 0.64));
    assert!((z.normal_stiffness - c_n).abs() < 1e-9 * c_n);
    assert!((z.tangential_stiffness - 2.0 * 0.36 / 1.96 * c_n).abs() < 1e-9 * c_n);
    assert_eq!(setup.notes.len(), 1, "{:?}", setup.notes);
    // With R_max = 1 GPa the softer rule-of-thumb stiffness leaves no softening branch.
    let t = BIMATERIAL.replace(
        "fracture_energy = 0.4, strength = 1e8",
        "fracture_energy = 0.4, strength = 1e9",
    );
    expect_error(
        &t,
        "interfaces[1].between",
        "[\"inclusion\", \"inclusion\"]",
        "strength too high",
    );
    let left = &setup.spec.loads[0];
    assert!(left
        .nodes
        .iter()
        .all(|&n| setup.mesh.nodes[n as usize][0] == 0.0));
    assert!(left.nodes.len() >= 11);
}

#[test]
fn rigid_reader_refuses_a_fracture_scene() {
    let e = parse_scene(NOTCHED, file()).unwrap_err();
    assert_eq!(e.0.len(), 1);
    assert_eq!(e.0[0].field, "mesh");
    assert!(e.0[0].message.contains("fracture scene"), "{}", e.0[0]);
}

#[test]
fn bad_materials_are_reported_with_their_place() {
    let t = NOTCHED.replace("young = 32e9", "young = -1.0");
    expect_error(
        &t,
        "regions[0].material.young",
        "young",
        "must be > 0 Pa, got -1",
    );
    let t = NOTCHED.replace("poisson = 0.2", "poisson = 0.5");
    expect_error(
        &t,
        "regions[0].material.poisson",
        "poisson",
        "in (-1, 0.5), got 0.5",
    );
    let t = NOTCHED.replace("density = 2200.0", "density = 0");
    expect_error(&t, "regions[0].material.density", "density", "> 0 kg/m^3");
    let t = NOTCHED.replace("kind = \"elastic\"", "kind = \"rubber\"");
    expect_error(
        &t,
        "regions[0].material.kind",
        "rubber",
        "unknown material kind `rubber`",
    );
    let t = BIMATERIAL.replace("hardening = 850e6", "hardening = -1.0");
    expect_error(&t, "regions[0].material.hardening", "hardening", ">= 0 Pa");
}

#[test]
fn interface_errors() {
    let t = NOTCHED.replace(
        "between = [\"concrete\", \"concrete\"]",
        "between = [\"concrete\", \"concret\"]",
    );
    expect_error(
        &t,
        "interfaces[0].between[1]",
        "between",
        "unknown region `concret` (regions: concrete)",
    );
    // w = 1e-6 J/m^2 is far below R_max d0 / 2: no softening branch.
    let t = NOTCHED.replace("fracture_energy = 110.0", "fracture_energy = 1e-6");
    expect_error(
        &t,
        "interfaces[0].law.strength",
        "fracture_energy",
        "strength too high",
    );
    let t = NOTCHED.replace("strength = 3e6", "strength = 3e6, initial_damage = 1.5");
    expect_error(
        &t,
        "interfaces[0].law.initial_damage",
        "initial_damage",
        "in (0, 1]",
    );
    let t = NOTCHED.replace("normal_stiffness = 2e14", "normal_stiffness = \"big\"");
    expect_error(
        &t,
        "interfaces[0].law.normal_stiffness",
        "big",
        "\"rule_of_thumb\"",
    );
    let t = BIMATERIAL.replace(
        "between = [\"matrix\", \"inclusion\"]",
        "between = [\"inclusion\", \"inclusion\"] # dup",
    );
    expect_error(&t, "interfaces[2].between", "# dup", "already given");
}

#[test]
fn neighbouring_regions_without_a_law() {
    let cut = BIMATERIAL
        .find("[[interfaces]]\nbetween = [\"matrix\", \"inclusion\"]")
        .unwrap();
    let end = BIMATERIAL[cut..].find("[[loads]]").unwrap() + cut;
    let t = format!("{}{}", &BIMATERIAL[..cut], &BIMATERIAL[end..]);
    let e = expect_error(
        &t,
        "interfaces",
        "between = [\"matrix\", \"matrix\"]",
        "regions `matrix` and `inclusion` are neighbours",
    );
    assert!(e.message.contains("add an [[interfaces]] entry"), "{e}");
}

#[test]
fn regions_must_match_the_mesh() {
    let t = NOTCHED
        .replace("name = \"concrete\"", "name = \"mortar\"")
        .replace("[\"concrete\", \"concrete\"]", "[\"mortar\", \"mortar\"]");
    expect_error(
        &t,
        "regions[0].name",
        "mortar",
        "region `mortar` is not in the mesh (mesh regions: concrete)",
    );
    expect_error(
        &t,
        "regions",
        "[mesh]",
        "region `concrete` with no [[regions]] entry",
    );
}

#[test]
fn edge_and_node_set_errors_list_the_known_ones() {
    let t = BIMATERIAL.replace("broken = [\"precrack\"]", "broken = [\"precrak\"]");
    let e = expect_error(
        &t,
        "fracture.broken[0]",
        "broken",
        "unknown edge set `precrak`",
    );
    assert!(
        e.message.contains("precrack") && e.message.contains("inclusion_boundary"),
        "{e}"
    );
    let t = NOTCHED.replace("{ set = \"top\" }", "{ set = \"roof\" }");
    let e = expect_error(&t, "loads[0].nodes", "roof", "unknown node set `roof`");
    assert!(
        e.message.contains("left_upper") && e.message.contains("top"),
        "{e}"
    );
    let t = NOTCHED.replace(
        "{ box = [[0.0, 0.0], [0.2, 0.0]] }",
        "{ box = [[1.0, 1.0], [2.0, 2.0]] }",
    );
    expect_error(&t, "loads[1].nodes", "box", "selects no node");
    let t = NOTCHED.replace(
        "{ box = [[0.0, 0.0], [0.2, 0.0]] }",
        "{ box = [[0.0, 0.19], [0.2, 0.2]] }",
    );
    expect_error(
        &t,
        "loads[1].nodes",
        "box",
        "already driven along y by load `top`",
    );
}

#[test]
fn load_errors() {
    let t = NOTCHED.replace("force = [\"free\", { sine", "force = [1.0, { sine");
    expect_error(
        &t,
        "loads[1].force[0]",
        "force",
        "component x has both a velocity and a force",
    );
    let t = NOTCHED.replace(
        "velocity = [\"free\", 0.1]",
        "velocity = [\"free\", \"free\"]",
    );
    expect_error(
        &t,
        "loads[0].velocity",
        "\"free\", \"free\"",
        "drives nothing",
    );
    let t = NOTCHED.replace("velocity = [\"free\", 0.1]", "velocity = [\"fixed\", 0.1]");
    expect_error(
        &t,
        "loads[0].velocity[0]",
        "fixed",
        "unknown component \"fixed\"",
    );
    let t = NOTCHED.replace("name = \"pull\"", "name = \"top\" # dup");
    expect_error(&t, "loads[1].name", "# dup", "duplicate load name `top`");
    let t = NOTCHED.replace(
        "{ set = \"top\" }",
        "{ set = \"top\", box = [[0, 0], [1, 1]] }",
    );
    expect_error(
        &t,
        "loads[0].nodes.box",
        "set = \"top\", box",
        "exactly one of",
    );
}

#[test]
fn mesh_errors_name_the_file_or_the_parameter() {
    let gen = "generator = \"double_edge_notched\"\nside = 0.2\nnotch_depth = 0.025\nnotch_width = 0.005\nelement_size = 0.02";
    let t = NOTCHED.replace(gen, "file = \"no_such_mesh.msh\"");
    let e = expect_error(&t, "mesh.file", "no_such_mesh", "no_such_mesh.msh");
    assert!(e.message.contains("cannot read"), "{e}");
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("xper-scene-fracture");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("bad.msh"),
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n",
    )
    .unwrap();
    let t = NOTCHED.replace(gen, "file = \"bad.msh\"");
    let s = match parse_any_scene(&t, &dir.join("scene.toml")).unwrap() {
        AnyScene::Fracture(s) => s,
        AnyScene::Rigid(_) | AnyScene::Rigid3(_) => panic!("rigid"),
    };
    let e = s.build().unwrap_err();
    assert_eq!(e.0[0].field, "mesh.file");
    assert!(
        e.0[0].message.contains("bad mesh file") && e.0[0].message.contains("bad.msh"),
        "{e}"
    );
    let t = NOTCHED.replace("notch_depth = 0.025", "notch_depth = 0.1");
    expect_error(&t, "mesh.notch_depth", "notch_depth", "would meet");
    let t = NOTCHED.replace("element_size = 0.02", "element_size = -0.02");
    expect_error(&t, "mesh.element_size", "element_size", "must be > 0 m");
    let t = NOTCHED.replace(
        "generator = \"double_edge_notched\"",
        "generator = \"double_edge_notched\"\nfile = \"a.msh\"",
    );
    expect_error(&t, "mesh.generator", "generator", "not both");
    let t = NOTCHED.replace("side = 0.2", "side = 0.2\nwidth = 0.2");
    expect_error(&t, "mesh.width", "width", "unknown key `width`");
}

#[test]
fn sections_that_do_not_apply_are_errors() {
    let t = NOTCHED.replace("steps = 10", "steps = 10\nalert_distance = 1e-3");
    expect_error(
        &t,
        "scene.alert_distance",
        "alert_distance",
        "does not apply",
    );
    let t = NOTCHED.replace("steps = 10", "steps = 10\ndetection = \"predicted\"");
    expect_error(&t, "scene.detection", "detection", "does not apply");
    let t = format!("{NOTCHED}\n[solver]\nkind = \"newton\"\n");
    expect_error(&t, "solver.kind", "newton", "NLGS only");
    let t = format!("{NOTCHED}\n[[bodies]]\nshape = \"disk\"\n");
    expect_error(&t, "bodies", "[[bodies]]", "unknown key `bodies`");
    let t = NOTCHED.replace("thickness = 0.05", "thickness = 0.0");
    expect_error(&t, "fracture.thickness", "thickness", "must be > 0 m");
    let t = NOTCHED.replace(
        "hypothesis = \"plane_stress\"",
        "hypothesis = \"axisymmetric\"",
    );
    expect_error(
        &t,
        "fracture.hypothesis",
        "axisymmetric",
        "unknown hypothesis",
    );
}

#[test]
fn several_errors_are_all_reported_in_order() {
    let t = NOTCHED
        .replace("young = 32e9", "young = 0")
        .replace("strength = 3e6", "strength = -3e6")
        .replace("velocity = [\"free\", 0.1]", "velocity = [\"free\"]");
    let e = parse(&t).unwrap_err();
    assert_eq!(e.0.len(), 3, "{e}");
    assert!(e.0.windows(2).all(|w| w[0].line <= w[1].line));
}

#[test]
fn shipped_fracture_scenes_parse_and_the_small_ones_build() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    for (name, elements) in [
        ("nooru_mohamed", None),
        ("bimaterial_tension", None),
        ("bimaterial_compression", None),
        ("nooru_mohamed_small", Some(1462)),
        ("bimaterial_small", Some(1570)),
    ] {
        let s = match load_any_scene(&scenes.join(name).join("scene.toml")) {
            Ok(AnyScene::Fracture(s)) => s,
            Ok(AnyScene::Rigid(_) | AnyScene::Rigid3(_)) => {
                panic!("{name}: parsed as a rigid scene")
            }
            Err(e) => panic!("{name}: {e}"),
        };
        assert_eq!(s.name, name);
        assert_eq!(s.gravity, [0.0, 0.0]);
        if let Some(count) = elements {
            let setup = s.build().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(setup.mesh.triangles.len(), count, "{name}");
        }
    }
    let tension = std::fs::read_to_string(scenes.join("bimaterial_tension/scene.toml")).unwrap();
    let compression =
        std::fs::read_to_string(scenes.join("bimaterial_compression/scene.toml")).unwrap();
    let velocities = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| l.starts_with("velocity"))
            .map(|l| l.split('#').next().unwrap().trim().to_string())
            .collect()
    };
    assert_eq!(
        velocities(&tension),
        ["velocity = [-2.0, \"free\"]", "velocity = [2.0, \"free\"]"]
    );
    assert_eq!(
        velocities(&compression),
        ["velocity = [2.0, \"free\"]", "velocity = [-2.0, \"free\"]"]
    );
}

#[test]
fn format_doc_fracture_example_parses_and_builds() {
    let doc = include_str!("../FORMAT.md");
    let start = doc.rfind("```toml\n").expect("example") + "```toml\n".len();
    let end = start + doc[start..].find("```").expect("end of example");
    let s = parse(&doc[start..end]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        (s.name.as_str(), s.steps, s.loads.len()),
        ("nooru_mohamed", 5000, 2)
    );
    let coarse = doc[start..end].replace("element_size = 2e-3", "element_size = 2e-2");
    let setup = parse(&coarse)
        .unwrap()
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(setup.spec.loads[1].nodes, setup.mesh.node_sets["bottom"]);
}
