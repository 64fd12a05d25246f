//! `xper check`: reads a scene, builds what it describes and prints what it holds.

use crate::scene::LoadedScene;
use crate::RunError;
use std::path::Path;
use xper_scene::{Scene, Scene3};

/// Validates the scene at `path`; prints a line of what it holds (and notes), or returns
/// every error (file:line:column: field: reason) as a bad-input error.
pub fn check(path: &Path) -> Result<(), RunError> {
    let scene = LoadedScene::read(path)?;
    let needs = crate::resources::estimate(&scene);
    let result = match scene {
        LoadedScene::Fracture { scene, .. } => crate::fracture::build::check(&scene, path),
        LoadedScene::Rigid { scene, .. } | LoadedScene::Fluid { scene, .. } => {
            crate::rigid::dumps_supported(&scene, path)?;
            check_rigid(&scene, path);
            Ok(())
        }
        LoadedScene::Rigid3 { scene, .. } => {
            crate::rigid3d::dumps_supported(&scene, path)?;
            check_rigid3(&scene, path);
            Ok(())
        }
    };
    if result.is_ok() {
        println!("needs: {} on one process", needs.describe());
        if let Some(available) = crate::resources::available_memory() {
            if needs.memory_bytes > available {
                println!(
                    "note: more than the {} available here: `xper run` refuses it unless \
                     given --max-memory",
                    crate::resources::bytes(available)
                );
            }
        }
    }
    result
}

fn check_rigid3(scene: &Scene3, path: &Path) {
    let count = |f: fn(&xper_scene::ShapeDesc3) -> bool| {
        scene.bodies.iter().filter(|b| f(&b.shape)).count()
    };
    println!(
        "{}: 3D scene `{}` is valid: {} bodies ({} spheres, {} polyhedra, {} walls), {} groups, \
         {} laws, {} steps of {} s",
        path.display(),
        scene.name,
        scene.bodies.len(),
        count(|s| matches!(s, xper_scene::ShapeDesc3::Sphere { .. })),
        count(|s| matches!(s, xper_scene::ShapeDesc3::Polyhedron { .. })),
        count(|s| matches!(s, xper_scene::ShapeDesc3::Plane { .. })),
        scene.groups.len(),
        scene.laws.len(),
        scene.steps,
        scene.dt
    );
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
        let scheme = match fluid.time_scheme {
            xper_fluid::TimeScheme::Euler => "explicit Euler",
            xper_fluid::TimeScheme::Rk3 => "three-stage Runge-Kutta",
        };
        let lubrication = match &fluid.lubrication {
            Some(l) => format!("lubrication within {} cell(s)", l.range),
            None => "no lubrication correction".into(),
        };
        let forcing = match &fluid.forcing {
            xper_fluid::Forcing::Fraction => "forcing by solid fraction".into(),
            xper_fluid::Forcing::Markers(m) => format!(
                "forcing on markers {} cell(s) inside, {} pass(es)",
                m.retraction, m.iterations
            ),
        };
        println!(
            "fluid: {} x {} cells of {} m, density {} kg/m^3, viscosity {} Pa s, {scheme}, \
             {forcing}, {lubrication}; runs to t = {} s",
            grid.nx,
            grid.ny,
            grid.h,
            fluid.density,
            fluid.viscosity,
            scene.steps as f64 * scene.dt
        );
    }
    let n = scene.groups.len();
    let mut members = vec![0usize; n];
    // Walls (segments) never interact with each other: they are not counted.
    for b in &scene.bodies {
        if !matches!(b.shape, xper_scene::ShapeDesc::Segment { .. }) {
            members[b.group] += 1;
        }
    }
    for (a, &members_a) in members.iter().enumerate() {
        for b in a..n {
            let law = (scene.laws.iter()).any(|l| l.groups == [a, b] || l.groups == [b, a]);
            if law {
                continue;
            }
            if a != b {
                println!(
                    "note: groups `{}` and `{}` have no law: they do not interact",
                    scene.groups[a], scene.groups[b]
                );
            } else if members_a > 1 {
                println!(
                    "note: group `{}` has no law with itself: its {} bodies do not interact \
                     with each other",
                    scene.groups[a], members_a
                );
            }
        }
    }
}
