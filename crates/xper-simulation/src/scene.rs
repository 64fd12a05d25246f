//! A scene file read once and turned into the simulation of its kind.

use crate::checkpoint::fnv1a;
use crate::simulation::Simulation;
use crate::simulation::{OutputSchedule, RunOptions};
use crate::RunError;
use std::path::Path;
use xper_domain::Communicator;
use xper_scene::{AnyScene, FractureScene, MeshSource, Scene, Scene3};

/// A parsed scene of any kind, with the hash of its files (a checkpoint resumes only the
/// scene it was written for).
pub enum LoadedScene {
    /// Rigid bodies in contact.
    Rigid {
        /// The scene.
        scene: Scene,
        /// FNV-1a of the scene file.
        hash: u64,
    },
    /// Rigid grains in a fluid (a scene with `[fluid]`).
    Fluid {
        /// The scene.
        scene: Scene,
        /// FNV-1a of the scene file.
        hash: u64,
    },
    /// Rigid bodies in contact in 3D (`[scene] dimension = 3`).
    Rigid3 {
        /// The scene.
        scene: Scene3,
        /// FNV-1a of the scene file.
        hash: u64,
    },
    /// A meshed specimen with cohesive interfaces (a scene with `[mesh]`).
    Fracture {
        /// The scene.
        scene: FractureScene,
        /// FNV-1a of the scene file followed by its mesh file, if any.
        hash: u64,
    },
}

fn bad(e: impl std::fmt::Display) -> RunError {
    RunError::BadInput(e.to_string())
}

impl LoadedScene {
    /// Reads and validates the scene file at `path` (every problem is a bad-input error
    /// naming the file and the place in it).
    pub fn read(path: &Path) -> Result<Self, RunError> {
        Self::read_with_text(path).map(|(scene, _)| scene)
    }

    /// Hash of the scene's files (its text, and its mesh file if any).
    pub fn hash(&self) -> u64 {
        match self {
            LoadedScene::Rigid { hash, .. }
            | LoadedScene::Rigid3 { hash, .. }
            | LoadedScene::Fluid { hash, .. }
            | LoadedScene::Fracture { hash, .. } => *hash,
        }
    }

    /// [`LoadedScene::read`], also returning the scene file's text (kept in checkpoints).
    pub fn read_with_text(path: &Path) -> Result<(Self, String), RunError> {
        let text = match std::fs::read_to_string(path) {
            Ok(text) => text,
            // The reader's own message for a file it cannot read.
            Err(_) => {
                return Err(bad(xper_scene::load_any_scene(path).err().map_or_else(
                    || format!("{}: cannot read the scene file", path.display()),
                    |e| e.to_string(),
                )))
            }
        };
        let mut hash_bytes = text.as_bytes().to_vec();
        let scene = match xper_scene::parse_any_scene(&text, path).map_err(bad)? {
            AnyScene::Fracture(scene) => {
                // A mesh file that cannot be read fails the model's build, which names the
                // place in the scene that refers to it.
                if let MeshSource::File(mesh) = &scene.mesh.source {
                    if let Ok(bytes) = std::fs::read(mesh) {
                        hash_bytes.extend(bytes);
                    }
                }
                let hash = fnv1a(&hash_bytes);
                LoadedScene::Fracture { scene, hash }
            }
            AnyScene::Rigid(scene) if scene.fluid.is_some() => LoadedScene::Fluid {
                scene,
                hash: fnv1a(&hash_bytes),
            },
            AnyScene::Rigid(scene) => LoadedScene::Rigid {
                scene,
                hash: fnv1a(&hash_bytes),
            },
            AnyScene::Rigid3(scene) => LoadedScene::Rigid3 {
                scene,
                hash: fnv1a(&hash_bytes),
            },
        };
        Ok((scene, text))
    }

    /// How often the scene asks for frames and checkpoints.
    pub fn output_schedule(&self) -> OutputSchedule {
        let (frame_every, checkpoint_every) = match self {
            LoadedScene::Rigid { scene, .. } | LoadedScene::Fluid { scene, .. } => {
                (scene.output.frame_every, scene.output.checkpoint_every)
            }
            LoadedScene::Rigid3 { scene, .. } => {
                (scene.output.frame_every, scene.output.checkpoint_every)
            }
            LoadedScene::Fracture { scene, .. } => {
                (scene.output.frame_every, scene.output.checkpoint_every)
            }
        };
        OutputSchedule {
            frame_every,
            checkpoint_every,
        }
    }

    /// The simulation of this scene at time 0 or, with `opts.resume`, restored from the
    /// checkpoint in `opts.out`; distributed over `comm` when it has more than one process.
    pub fn into_simulation<'c>(
        self,
        opts: &RunOptions,
        comm: Option<&'c dyn Communicator>,
    ) -> Result<Box<dyn Simulation + 'c>, RunError> {
        let comm = comm.filter(|c| c.size() > 1);
        Ok(match self {
            LoadedScene::Rigid { scene, hash } => {
                Box::new(crate::rigid::RigidSimulation::new(scene, hash, opts, comm)?)
            }
            LoadedScene::Rigid3 { scene, hash } => {
                Box::new(xper_rigid3d::RigidSimulation::new(scene, hash, opts, comm)?)
            }
            LoadedScene::Fluid { scene, hash } => {
                Box::new(crate::fluid::FluidSimulation::new(scene, hash, opts, comm)?)
            }
            LoadedScene::Fracture { scene, hash } => Box::new(
                crate::fracture::FractureSimulation::new(scene, hash, opts, comm)?,
            ),
        })
    }
}
