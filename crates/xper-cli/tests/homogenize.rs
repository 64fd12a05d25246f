//! `xper homogenize`: the effective tensor of a periodic cell printed and written as JSON
//! (the library's numbers, which `xper-fracture`'s tests check against exact answers), and
//! the refusals of scenes without a periodic cell.

mod common;
use common::*;
use std::path::Path;

fn scene(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn the_cell_tensor_is_printed_and_written() {
    let dir = temp_dir("homogenize");
    let json = dir.join("c.json");
    let path = scene("periodic_bimaterial_small");
    let out = xper(&["homogenize", &path, "--json", json.to_str().unwrap()]);
    assert_success(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("positive definite: yes"), "{text}");
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let (_, model) =
        xper_simulation::fracture::build::load_model(&Path::new(&path).join("scene.toml")).unwrap();
    let direct = xper_fracture::effective_tensor(&model).unwrap();
    for r in 0..3 {
        for c in 0..3 {
            // serde_json reads floats to within one unit of the last place.
            let got = written["tensor"][r][c].as_f64().unwrap();
            assert!((got - direct.tensor[r][c]).abs() <= 1e-15 * direct.tensor[r][c].abs());
        }
    }
    assert_eq!(written["positive_definite"], true);
    assert!(written["asymmetry"].as_f64().unwrap() < 1e-12);
    assert!(written["stress_difference"].as_f64().unwrap() < 1e-9);
    assert_eq!(
        written["elements"].as_u64().unwrap() as usize,
        model.elements.len()
    );
}

#[test]
fn scenes_without_a_cell_are_refused() {
    let out = xper(&["homogenize", &scene("bimaterial_small")]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no [periodic] section"), "{err}");
    let out = xper(&["homogenize", &scene("drop")]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("not a fracture scene"), "{err}");
}
