//! Helpers of the fracture scene tests: parsing a scene text and finding an error by field,
//! line and message.
#![allow(dead_code)]

use std::path::Path;

use xper_scene::{parse_any_scene, AnyScene, FractureScene, SceneError, SceneErrors};

pub fn file() -> &'static Path {
    Path::new("test.toml")
}

pub fn parse(text: &str) -> Result<FractureScene, SceneErrors> {
    match parse_any_scene(text, file())? {
        AnyScene::Fracture(s) => Ok(s),
        AnyScene::Rigid(_) => panic!("parsed as a rigid scene"),
    }
}

pub fn line_of(text: &str, marker: &str) -> usize {
    text.lines()
        .position(|l| l.contains(marker))
        .unwrap_or_else(|| panic!("marker {marker:?} not in text"))
        + 1
}

/// The error on exactly `field`, at the line holding `marker`, whose message contains
/// `needle`; from parsing or, when parsing succeeds, from building.
pub fn expect_error(text: &str, field: &str, marker: &str, needle: &str) -> SceneError {
    let e = match parse(text) {
        Err(e) => e,
        Ok(s) => match s.build() {
            Err(e) => e,
            Ok(_) => panic!("expected an error on `{field}`, the scene builds:\n{text}"),
        },
    };
    let line = line_of(text, marker);
    let found =
        e.0.iter()
            .find(|x| x.field == field && x.line == line && x.message.contains(needle));
    match found {
        Some(x) => {
            assert_eq!(x.file, file());
            assert!(x.column >= 1);
            x.clone()
        }
        None => panic!("no error on `{field}` at line {line} containing {needle:?}; got:\n{e}"),
    }
}
