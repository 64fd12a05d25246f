//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod fracture;

use std::path::Path;

use xper_scene::{parse_any_scene, parse_scene, AnyScene, Scene, Scene3, SceneError, SceneErrors};

/// A valid header: scene, one material `glass` (2500 kg/m^3).
pub const HEADER: &str = r#"[scene]
name = "t"
dt = 1e-3
steps = 10

[[materials]]
name = "glass"
density = 2500.0
"#;

/// `HEADER` followed by `rest`.
pub fn with_header(rest: &str) -> String {
    format!("{HEADER}\n{rest}")
}

pub fn parse(text: &str) -> Result<Scene, SceneErrors> {
    parse_scene(text, Path::new("test.toml"))
}

pub fn ok(text: &str) -> Scene {
    parse(text).unwrap_or_else(|e| panic!("unexpected errors:\n{e}\n--- in:\n{text}"))
}

pub fn errs(text: &str) -> SceneErrors {
    match parse(text) {
        Ok(s) => panic!("expected errors, parsed {s:?}\n--- in:\n{text}"),
        Err(e) => e,
    }
}

/// 1-based line of the first line of `text` containing `marker`.
pub fn line_of(text: &str, marker: &str) -> usize {
    text.lines()
        .position(|l| l.contains(marker))
        .unwrap_or_else(|| panic!("marker {marker:?} not in text"))
        + 1
}

/// Asserts that the scene fails with an error on exactly `field`, at the line holding
/// `marker`, whose message contains `needle`; returns that error.
pub fn expect_error(text: &str, field: &str, marker: &str, needle: &str) -> SceneError {
    find_error(&errs(text), text, field, marker, needle)
}

/// The error of `e` on exactly `field`, at the line of `text` holding `marker`, whose message
/// contains `needle` (in `test.toml`, with a column); panics listing `e` if there is none.
pub fn find_error(
    e: &SceneErrors,
    text: &str,
    field: &str,
    marker: &str,
    needle: &str,
) -> SceneError {
    let line = line_of(text, marker);
    let found =
        e.0.iter()
            .find(|x| x.field == field && x.line == line && x.message.contains(needle));
    match found {
        Some(x) => {
            assert_eq!(x.file, Path::new("test.toml"));
            assert!(x.column >= 1);
            x.clone()
        }
        None => panic!("no error on `{field}` at line {line} containing {needle:?}; got:\n{e}"),
    }
}

/// A 3D scene read from `text` (in `test.toml`), or its errors; panics on a 2D scene.
pub fn parse3(text: &str) -> Result<Scene3, SceneErrors> {
    match parse_any_scene(text, Path::new("test.toml"))? {
        AnyScene::Rigid3(s) => Ok(s),
        _ => panic!("not read as a 3D scene"),
    }
}

/// The 3D scene of `text`, panicking with its errors if it has any.
pub fn ok3_text(text: &str) -> Scene3 {
    parse3(text).unwrap_or_else(|e| panic!("unexpected errors:\n{e}\n--- in:\n{text}"))
}

/// Asserts that `text`, read as any scene, has an error on `field` at the line holding
/// `marker` whose message has `needle`.
pub fn expect_error_any(text: &str, field: &str, marker: &str, needle: &str) {
    let errors = match parse_any_scene(text, Path::new("test.toml")) {
        Ok(_) => panic!("expected errors in:\n{text}"),
        Err(e) => e,
    };
    find_error(&errors, text, field, marker, needle);
}
