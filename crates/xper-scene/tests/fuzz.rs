//! The parser never panics: random text, and random TOML assembled from the scene's own
//! keys (rigid and fracture scenes) with random (often wrong) values. A fracture scene that
//! parses is also built against its mesh when the mesh is small.

use std::path::Path;

use proptest::prelude::*;
use xper_scene::{parse_any_scene, AnyScene, MeshSource};

const KEYS: &[&str] = &[
    "name",
    "dt",
    "duration",
    "steps",
    "theta",
    "gravity",
    "alert_distance",
    "kind",
    "tolerance",
    "max_iterations",
    "check_every",
    "relaxation",
    "norm",
    "position_projection",
    "frame_every",
    "checkpoint_every",
    "density",
    "between",
    "friction",
    "restitution",
    "shape",
    "center",
    "radius",
    "vertices",
    "size",
    "angle",
    "material",
    "mass",
    "inertia",
    "group",
    "velocity",
    "angular_velocity",
    "fixed",
    "drive",
    "from",
    "to",
    "count",
    "box",
    "placement",
    "seed",
    "walls",
    "columns",
    "rows",
    "pitch",
    "x",
    "y",
    "rotation",
    "force",
    "sine",
    "amplitude",
    "frequency",
    "phase",
    "offset",
    "radious",
    "thickness",
    "hypothesis",
    "broken",
    "generator",
    "file",
    "side",
    "notch_depth",
    "notch_width",
    "element_size",
    "width",
    "height",
    "inclusions",
    "precrack",
    "young",
    "poisson",
    "yield_stress",
    "hardening",
    "law",
    "normal_stiffness",
    "tangential_stiffness",
    "fracture_energy",
    "strength",
    "initial_damage",
    "nodes",
    "set",
    "segment",
];

const HEADERS: &[&str] = &[
    "[scene]",
    "[solver]",
    "[output]",
    "[[materials]]",
    "[[laws]]",
    "[[bodies]]",
    "[[walls]]",
    "[[generators]]",
    "[bodies.drive]",
    "[bodies.drive.x]",
    "[walls.drive]",
    "[extra]",
    "[fracture]",
    "[mesh]",
    "[[regions]]",
    "[[interfaces]]",
    "[[loads]]",
    "[regions.material]",
    "[interfaces.law]",
    "[loads.nodes]",
];

const ATOMS: &[&str] = &[
    "0",
    "1",
    "-1",
    "2",
    "3",
    "100",
    "1e-3",
    "0.5",
    "-0.0",
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "9223372036854775807",
    "-9223372036854775808",
    "true",
    "false",
    "\"disk\"",
    "\"polygon\"",
    "\"rectangle\"",
    "\"glass\"",
    "\"g\"",
    "\"w\"",
    "\"nlgs\"",
    "\"newton\"",
    "\"proximal_newton\"",
    "\"quad\"",
    "\"box_of_disks\"",
    "\"hex_lattice\"",
    "\"signorini_coulomb\"",
    "\"random\"",
    "\"lattice\"",
    "\"\"",
    "1979-05-27",
    "0.2",
    "0.05",
    "0.025",
    "\"double_edge_notched\"",
    "\"rectangle_with_inclusions\"",
    "\"elastic\"",
    "\"j2\"",
    "\"cohesive\"",
    "\"contact\"",
    "\"rule_of_thumb\"",
    "\"free\"",
    "\"top\"",
    "\"concrete\"",
    "\"plane_strain\"",
    "\"lumped\"",
];

/// Triangles a generated mesh would have, roughly; files count as small.
fn estimated_triangles(source: &MeshSource) -> f64 {
    let (area, h) = match source {
        MeshSource::File(_) => return 0.0,
        MeshSource::DoubleEdgeNotched(s) => (s.side * s.side, s.element_size),
        MeshSource::RectangleWithInclusions(s) => (s.width * s.height, s.element_size),
        MeshSource::PeriodicCell(s) => (s.width * s.height, s.element_size),
    };
    2.0 * area / (0.433 * h * h)
}

fn value() -> impl Strategy<Value = String> {
    let atom = prop::sample::select(ATOMS).prop_map(str::to_string);
    atom.prop_recursive(3, 24, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(|v| format!("[{}]", v.join(", "))),
            prop::collection::vec((prop::sample::select(KEYS), inner), 0..3).prop_map(|kv| {
                let mut seen = std::collections::HashSet::new();
                let body: Vec<String> = kv
                    .into_iter()
                    .filter(|(k, _)| seen.insert(*k))
                    .map(|(k, v)| format!("{k} = {v}"))
                    .collect();
                format!("{{ {} }}", body.join(", "))
            }),
        ]
    })
}

fn line() -> impl Strategy<Value = String> {
    prop_oneof![
        1 => prop::sample::select(HEADERS).prop_map(str::to_string),
        4 => (prop::sample::select(KEYS), value()).prop_map(|(k, v)| format!("{k} = {v}")),
    ]
}

fn check(text: &str) {
    // Must return (Ok or Err), never panic; errors must carry positions inside the text.
    let lines = text.lines().count().max(1) + 1;
    let errors = match parse_any_scene(text, Path::new("fuzz.toml")) {
        Err(e) => e,
        Ok(AnyScene::Fracture(s)) if estimated_triangles(&s.mesh.source) < 3000.0 => {
            match s.build() {
                Ok(_) => return,
                Err(e) => e,
            }
        }
        Ok(_) => return,
    };
    assert!(!errors.0.is_empty());
    for x in &errors.0 {
        assert!(x.line >= 1 && x.line <= lines && x.column >= 1, "{x}");
    }
}

fn mutated(base: &str, lines: Vec<String>, at: usize) -> String {
    let mut all: Vec<String> = base.lines().map(str::to_string).collect();
    let at = at.min(all.len());
    for (k, l) in lines.into_iter().enumerate() {
        all.insert(at + k, l);
    }
    all.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_text_never_panics(text in "\\PC{0,200}") {
        check(&text);
    }

    #[test]
    fn random_toml_like_text_never_panics(text in "[\\[\\]a-z_=.,{}\"0-9 \\n-]{0,200}") {
        check(&text);
    }

    #[test]
    fn structured_wrong_toml_never_panics(lines in prop::collection::vec(line(), 0..30)) {
        check(&lines.join("\n"));
    }

    #[test]
    fn mutated_valid_scene_never_panics(
        lines in prop::collection::vec(line(), 0..6),
        at in 0usize..40,
    ) {
        check(&mutated(include_str!("../../../scenes/drop/scene.toml"), lines, at));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn mutated_fracture_scene_never_panics(
        lines in prop::collection::vec(line(), 0..6),
        at in 0usize..70,
    ) {
        let base = include_str!("../../../scenes/nooru_mohamed_small/scene.toml")
            .replace("element_size = 1e-2", "element_size = 2e-2");
        check(&mutated(&base, lines, at));
    }
}
