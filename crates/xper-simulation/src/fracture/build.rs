//! A fracture scene's model, and what `xper check` prints of it.

use crate::RunError;
use std::path::Path;
use xper_fracture::FractureModel;
use xper_scene::FractureScene;

fn bad(e: impl std::fmt::Display) -> RunError {
    RunError::BadInput(e.to_string())
}

/// Reads a fracture scene and builds its model; every problem is a bad-input error naming
/// the scene file (and the place in it).
pub fn load_model(path: &Path) -> Result<(FractureScene, FractureModel), RunError> {
    let scene = match xper_scene::load_any_scene(path).map_err(bad)? {
        xper_scene::AnyScene::Fracture(s) => s,
        xper_scene::AnyScene::Rigid(_) | xper_scene::AnyScene::Rigid3(_) => {
            return Err(RunError::BadInput(format!(
                "{}: not a fracture scene (it has no [mesh] section)",
                path.display()
            )))
        }
    };
    let (model, _) = build_model(&scene, path)?;
    Ok((scene, model))
}

/// The model of a fracture scene read from `path`, and the notes of its build (rule-of-thumb
/// stiffnesses).
pub fn build_model(
    scene: &FractureScene,
    path: &Path,
) -> Result<(FractureModel, Vec<String>), RunError> {
    let setup = scene.build().map_err(bad)?;
    let model = FractureModel::new(setup.mesh, setup.spec).map_err(|e| {
        RunError::BadInput(format!(
            "{}: cannot build the fracture model: {e}",
            path.display()
        ))
    })?;
    Ok((model, setup.notes))
}

/// `xper check` on a fracture scene: builds the model and prints what it holds.
pub fn check(scene: &FractureScene, path: &Path) -> Result<(), RunError> {
    let (model, notes) = build_model(scene, path)?;
    let mesh = &model.mesh;
    println!(
        "{}: fracture scene `{}` is valid: {} elements, {} nodes, {} interfaces ({} broken at \
         start), {} steps of {:e} s",
        path.display(),
        scene.name,
        model.elements.len(),
        mesh.nodes.len(),
        model.interfaces.len(),
        model.broken_interfaces(),
        scene.steps,
        scene.dt
    );
    for (r, region) in mesh.regions.iter().enumerate() {
        let n = model
            .elements
            .iter()
            .filter(|e| e.region as usize == r)
            .count();
        println!("region `{}`: {n} elements", region.name);
    }
    for load in &model.spec.loads {
        println!("load `{}`: {} nodes", load.name, load.nodes.len());
    }
    for note in notes {
        println!("note: {note}");
    }
    Ok(())
}
