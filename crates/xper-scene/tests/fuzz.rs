//! The parser never panics: random text, and random TOML assembled from the scene's own
//! keys with random (often wrong) values.

use std::path::Path;

use proptest::prelude::*;
use xper_scene::parse_scene;

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
];

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
    if let Err(e) = parse_scene(text, Path::new("fuzz.toml")) {
        assert!(!e.0.is_empty());
        let lines = text.lines().count().max(1) + 1;
        for x in &e.0 {
            assert!(x.line >= 1 && x.line <= lines && x.column >= 1, "{x}");
        }
    }
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
        let base = include_str!("../../../scenes/drop/scene.toml");
        let mut all: Vec<String> = base.lines().map(str::to_string).collect();
        let at = at.min(all.len());
        for (k, l) in lines.into_iter().enumerate() {
            all.insert(at + k, l);
        }
        check(&all.join("\n"));
    }
}
