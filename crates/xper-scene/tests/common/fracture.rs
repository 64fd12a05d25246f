//! Helpers of the fracture scene tests: parsing a scene text and finding an error from
//! parsing or building it.

use std::path::Path;

use xper_scene::{parse_any_scene, AnyScene, FractureScene, SceneError, SceneErrors};

/// The file name the tests' scenes are parsed as.
pub fn file() -> &'static Path {
    Path::new("test.toml")
}

/// `text` parsed as a fracture scene (panics if it is a rigid one).
pub fn parse(text: &str) -> Result<FractureScene, SceneErrors> {
    match parse_any_scene(text, file())? {
        AnyScene::Fracture(s) => Ok(s),
        AnyScene::Rigid(_) | AnyScene::Rigid3(_) => panic!("parsed as a rigid scene"),
    }
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
    super::find_error(&e, text, field, marker, needle)
}
