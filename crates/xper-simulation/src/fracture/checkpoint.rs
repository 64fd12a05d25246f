//! `checkpoint.bin` of a fracture run: the scene's hash and everything of the model that
//! evolves (the mesh and the model are rebuilt from the scene).

use crate::RunError;
use serde::{Deserialize, Serialize};
use std::path::Path;
use xper_fem::MaterialState;
use xper_fracture::{CellState, FractureEnergy, FractureModel, PointState};

/// The evolving state of one element, as checkpointed.
#[derive(Serialize, Deserialize)]
pub struct ElementState {
    pub displacement: [f64; 6],
    pub velocity: [f64; 6],
    pub state: MaterialState,
    pub internal_force: [f64; 6],
    pub stiffness: [[f64; 6]; 6],
}

/// A checkpoint: the scene's hash and everything of the model that evolves.
#[derive(Serialize, Deserialize)]
pub struct Checkpoint {
    pub scene_hash: u64,
    pub step: u64,
    pub time: f64,
    pub energy: FractureEnergy,
    pub elements: Vec<ElementState>,
    pub points: Vec<[PointState; 2]>,
    pub cell: Option<CellState>,
}

impl Checkpoint {
    pub fn of(m: &FractureModel, scene_hash: u64) -> Self {
        Checkpoint {
            scene_hash,
            step: m.step,
            time: m.time,
            energy: m.energy,
            elements: (m.elements.iter())
                .map(|e| ElementState {
                    displacement: e.displacement,
                    velocity: e.velocity,
                    state: e.state,
                    internal_force: e.internal_force,
                    stiffness: e.stiffness,
                })
                .collect(),
            points: m.interfaces.iter().map(|i| i.points).collect(),
            cell: m.cell,
        }
    }

    /// Overwrites the evolving state of a freshly built model.
    pub fn restore(self, m: &mut FractureModel, file: &Path) -> Result<(), RunError> {
        if self.elements.len() != m.elements.len() || self.points.len() != m.interfaces.len() {
            return Err(RunError::BadInput(format!(
                "{}: the checkpoint holds {} elements and {} interfaces, the scene builds {} and {}",
                file.display(),
                self.elements.len(),
                self.points.len(),
                m.elements.len(),
                m.interfaces.len()
            )));
        }
        for (el, s) in m.elements.iter_mut().zip(self.elements) {
            el.displacement = s.displacement;
            el.velocity = s.velocity;
            el.state = s.state;
            el.internal_force = s.internal_force;
            el.stiffness = s.stiffness;
        }
        for (i, p) in m.interfaces.iter_mut().zip(self.points) {
            i.points = p;
        }
        m.step = self.step;
        m.time = self.time;
        m.energy = self.energy;
        m.cell = self.cell;
        Ok(())
    }
}

/// The step and the nodal displacements of each element (m) held by the checkpoint of a
/// fracture run in `dir` (for comparing runs).
pub fn checkpoint_displacements(dir: &Path) -> Result<(u64, Vec<[f64; 6]>), RunError> {
    let (c, _) = Checkpoint::load(dir, "cannot read")?;
    Ok((c.step, c.elements.iter().map(|e| e.displacement).collect()))
}

impl Checkpoint {
    /// Reads `dir/checkpoint.bin` for a resume (whether it belongs to the scene is the driver's
    /// decision, [`crate::resume::check_resume`]); its state must name the scene its envelope
    /// names.
    pub fn read(dir: &Path) -> Result<Self, RunError> {
        let (c, envelope) = Self::load(dir, "cannot resume")?;
        if c.scene_hash != envelope {
            return Err(RunError::BadInput(format!(
                "{}: the checkpoint's state belongs to another scene than its envelope says",
                dir.join("checkpoint.bin").display()
            )));
        }
        Ok(c)
    }

    /// `dir/checkpoint.bin`, whatever scene it belongs to, with the scene hash its envelope
    /// names (the file is read once); `failing` opens the message of a file that cannot be read.
    fn load(dir: &Path, failing: &str) -> Result<(Self, u64), RunError> {
        let path = dir.join("checkpoint.bin");
        let sealed = crate::checkpoint::open(dir, failing)?;
        let envelope = sealed.header.scene_hash;
        let c = bincode::deserialize(&sealed.payload).map_err(|e| {
            RunError::BadInput(format!(
                "{}: not a fracture checkpoint of xper: {e}",
                path.display()
            ))
        })?;
        Ok((c, envelope))
    }
}
