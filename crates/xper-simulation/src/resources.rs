//! What a scene needs before it runs: its size (bodies, fluid cells, elements) and the memory
//! that size takes, so that `xper check` can print it and `xper run` can refuse a scene that
//! does not fit instead of failing on an allocation hours later.
//!
//! The bytes per item are peak resident sizes measured on this code's runs (BENCHMARKS.md and
//! the figures beside each constant), rounded up: the estimate aims at the right order of
//! magnitude, a little above the real peak (1.0 to 1.6 times the peaks measured).

use crate::scene::LoadedScene;
use crate::RunError;
use xper_scene::MeshSource;

/// Resident memory of the process before the scene's own data (bytes).
const BASE_BYTES: f64 = 30e6;
/// Peak bytes per rigid body of `xper run`, contacts and outputs included: box10k peaked at
/// 59 MB over its 1500 steps, box100k at 291 MB over its first 30 (its frames of 100k bodies
/// dominate; `xper bench`, without outputs, peaked at 790 B per disk). On two processes box10k
/// peaked at 74 MB on rank 0 and 31 MB on rank 1: [`ensure_fits`] counts twice the serial
/// estimate for a distributed run.
const BYTES_PER_BODY: f64 = 3000.0;
/// Peak bytes per 3D rigid body: `xper bench` (no outputs) peaked at 1.23 kB of heap per
/// sphere on box3d10k over its 1500 steps (BENCHMARKS.md); frames and the scene's description
/// come on top, as in 2D (3000 B per disk against 790 B for `xper bench`).
const BYTES_PER_BODY_3D: f64 = 4500.0;
/// Peak bytes per fluid cell: 252 B measured between grids of 256^2 and 1024^2 cells
/// (274 MB at 1024^2).
const BYTES_PER_CELL: f64 = 260.0;
/// Peak bytes per triangle of a fracture mesh with its cohesive interfaces: 3.7 kB on
/// notched_tension (20,936 triangles, 78 MB without outputs; `xper run` peaked at 114 MB over
/// its first 20 steps), 3.3 kB on nooru_mohamed_100k.
const BYTES_PER_ELEMENT: f64 = 4000.0;

/// The size of a scene and the memory it needs.
#[derive(Clone, Debug, PartialEq)]
pub struct Needs {
    /// What the scene holds, by name (bodies, cells, elements), for the messages.
    pub counts: Vec<(&'static str, f64)>,
    /// Estimated peak memory of a run on one process (bytes).
    pub memory_bytes: f64,
}

impl Needs {
    /// "about 274 MB (1048576 fluid cells, 1 bodies)".
    pub fn describe(&self) -> String {
        let counts: Vec<String> = (self.counts.iter())
            .map(|(name, n)| format!("{n:.0} {name}"))
            .collect();
        format!("about {} ({})", bytes(self.memory_bytes), counts.join(", "))
    }
}

/// A byte count for people (MB or GB).
pub fn bytes(b: f64) -> String {
    if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else {
        format!("{:.0} MB", b / 1e6)
    }
}

/// The needs of a parsed scene (before anything is built).
pub fn estimate(scene: &LoadedScene) -> Needs {
    match scene {
        LoadedScene::Rigid { scene, .. } | LoadedScene::Fluid { scene, .. } => {
            let bodies = scene.bodies.len() as f64;
            let mut counts = vec![("bodies", bodies)];
            let mut memory = BASE_BYTES + BYTES_PER_BODY * bodies;
            if let Some(fluid) = &scene.fluid {
                let grid = crate::fluid::build::fluid_grid(fluid);
                let cells = grid.nx as f64 * grid.ny as f64;
                counts.push(("fluid cells", cells));
                memory += BYTES_PER_CELL * cells;
            }
            Needs {
                counts,
                memory_bytes: memory,
            }
        }
        LoadedScene::Rigid3 { scene, .. } => {
            let bodies = scene.bodies.len() as f64;
            Needs {
                counts: vec![("bodies", bodies)],
                memory_bytes: BASE_BYTES + BYTES_PER_BODY_3D * bodies,
            }
        }
        LoadedScene::Fracture { scene, .. } => {
            let triangles = match &scene.mesh.source {
                MeshSource::DoubleEdgeNotched(s) => {
                    xper_mesh::estimated_triangles(s.side * s.side, s.element_size)
                }
                MeshSource::RectangleWithInclusions(s) => {
                    xper_mesh::estimated_triangles(s.width * s.height, s.element_size)
                }
                MeshSource::PeriodicCell(s) => {
                    xper_mesh::estimated_triangles(s.width * s.height, s.element_size)
                }
                // A mesh file is read whole: its size bounds what it holds. Gmsh 4.1 takes
                // about 50 bytes per triangle, ASCII or binary (ASCII: a 28-byte element line
                // and half of a 47-byte node; binary: four 8-byte tags and half of a 32-byte
                // node); the test mesh square_inclusion (313 elements and 152 nodes) is 10.9 kB
                // in ASCII and 16.5 kB in binary, 35 and 53 bytes per element.
                MeshSource::File(path) => {
                    std::fs::metadata(path).map_or(0.0, |m| m.len() as f64 / 50.0)
                }
            };
            Needs {
                counts: vec![("triangles (estimated before meshing)", triangles)],
                memory_bytes: BASE_BYTES + BYTES_PER_ELEMENT * triangles,
            }
        }
    }
}

/// Memory this machine has available now (bytes): `MemAvailable` of /proc/meminfo, `None`
/// where there is no such file.
pub fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Refuses a run whose estimated memory exceeds `limit` (bytes; the available memory when
/// `None`, no check when that is unknown). `processes` share the work of a distributed run.
pub fn ensure_fits(
    needs: &Needs,
    limit: Option<f64>,
    processes: usize,
    scene: &std::path::Path,
) -> Result<(), RunError> {
    let Some(limit) = limit.or_else(available_memory) else {
        return Ok(());
    };
    // Every process of a run on one machine holds its share, and rank 0 the whole state.
    let per_run = needs.memory_bytes * if processes > 1 { 2.0 } else { 1.0 };
    if per_run > limit {
        return Err(RunError::BadInput(format!(
            "{}: the scene needs {}, more than the {} available; reduce it, or raise the limit \
             with --max-memory GB if the estimate is too high for this scene",
            scene.display(),
            needs.describe(),
            bytes(limit)
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn needs(memory: f64) -> Needs {
        Needs {
            counts: vec![("bodies", 10.0)],
            memory_bytes: memory,
        }
    }

    #[test]
    fn a_scene_above_the_limit_is_refused_with_its_estimate_and_one_below_runs() {
        let scene = std::path::Path::new("s.toml");
        assert!(ensure_fits(&needs(1e9), Some(2e9), 1, scene).is_ok());
        let err = ensure_fits(&needs(3e9), Some(2e9), 1, scene)
            .unwrap_err()
            .to_string();
        assert!(err.contains("3.0 GB") && err.contains("2.0 GB") && err.contains("10 bodies"));
        assert!(ensure_fits(&needs(1.5e9), Some(2e9), 2, scene).is_err());
    }

    #[test]
    fn this_machine_reports_its_available_memory() {
        if std::path::Path::new("/proc/meminfo").exists() {
            let m = available_memory().unwrap();
            assert!(m > 1e6 && m < 1e15, "{m}");
        }
    }
}
