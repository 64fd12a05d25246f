//! `xper check`: reads a scene, builds what it describes and prints what it holds.

use crate::scene::LoadedScene;
use crate::RunError;
use std::path::Path;
use xper_scene::Scene;

/// Validates the scene at `path`; prints a line of what it holds (and notes), or returns
/// every error (file:line:column: field: reason) as a bad-input error.
pub fn check(path: &Path) -> Result<(), RunError> {
    match LoadedScene::read(path)? {
        LoadedScene::Fracture { scene, .. } => crate::fracture::build::check(&scene, path),
        LoadedScene::Rigid { scene, .. } | LoadedScene::Fluid { scene, .. } => {
            check_rigid(&scene, path);
            Ok(())
        }
    }
}

fn check_rigid(scene: &Scene, path: &Path) {
    let walls = scene
        .bodies
        .iter()
        .filter(|b| matches!(b.shape, xper_scene::ShapeDesc::Segment { .. }))
        .count();
    println!(
        "{}: scene `{}` is valid: {} bodies ({} walls), {} groups, {} laws, {} steps of {} s",
        path.display(),
        scene.name,
        scene.bodies.len(),
        walls,
        scene.groups.len(),
        scene.laws.len(),
        scene.steps,
        scene.dt
    );
    if let Some(fluid) = &scene.fluid {
        let grid = crate::fluid::build::fluid_grid(fluid);
        println!(
            "fluid: {} x {} cells of {} m, density {} kg/m^3, viscosity {} Pa s; runs to t = {} s",
            grid.nx,
            grid.ny,
            grid.h,
            fluid.density,
            fluid.viscosity,
            scene.steps as f64 * scene.dt
        );
    }
    let n = scene.groups.len();
    for a in 0..n {
        for b in a..n {
            if !scene
                .laws
                .iter()
                .any(|l| (l.groups == [a, b]) || (l.groups == [b, a]))
            {
                println!(
                    "note: groups `{}` and `{}` have no law: they do not interact",
                    scene.groups[a], scene.groups[b]
                );
            }
        }
    }
}
