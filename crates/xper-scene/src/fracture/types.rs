//! The resolved fracture scene (a scene with a `[mesh]` section): plain data in SI units,
//! each item that can only be checked against the mesh carrying the [`Place`] it was
//! written at, so that [`FractureScene::build`] reports file, line, column and field.

use std::path::PathBuf;

use serde::Serialize;
use xper_bodies::Drive;
use xper_fem::{Hypothesis, Material};
use xper_fracture::{MacroDrive, MassMatrix, PlasticStiffness};
use xper_mesh::{NodeSelector, NotchedSpec, PeriodicCellSpec, RectangleSpec};
use xper_solver::NlgsParams;

use crate::types::{OutputSettings, Scene};

/// A scene file of either kind.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[allow(clippy::large_enum_variant)]
pub enum AnyScene {
    /// Rigid bodies in contact (no `[mesh]` section).
    Rigid(Scene),
    /// A meshed specimen that can fracture (a `[mesh]` section).
    Fracture(FractureScene),
    /// Rigid bodies in contact in 3D (`[scene] dimension = 3`).
    Rigid3(crate::Scene3),
}

/// Where a value was written in the scene file.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Default)]
pub struct Place {
    /// 1-based line.
    pub line: usize,
    /// 1-based column (in characters).
    pub column: usize,
    /// Field path, e.g. `loads[1].nodes`.
    pub field: String,
}

/// A fracture scene: a mesh exploded into one deformable body per triangle, cohesive or
/// contact interfaces between neighbouring triangles, loads on node sets.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FractureScene {
    /// The scene file (mesh files are relative to its directory; errors name it).
    pub file: PathBuf,
    /// Scene name (`scene.name`).
    pub name: String,
    /// Time step h (s).
    pub dt: f64,
    /// Number of time steps to run.
    pub steps: u64,
    /// theta of the theta-method, in [0.5, 1].
    pub theta: f64,
    /// Body force per unit mass (m/s^2).
    pub gravity: [f64; 2],
    /// NLGS parameters of the interface problem (`[solver]`).
    pub nlgs: NlgsParams,
    /// Output cadence (`[output]`; `dump_problems` is always empty).
    pub output: OutputSettings,
    /// Out-of-plane thickness (m).
    pub thickness: f64,
    /// Plane strain or plane stress.
    pub hypothesis: Hypothesis,
    /// Element mass matrix.
    pub mass: MassMatrix,
    /// Stiffness of elastoplastic elements in the implicit part of a step.
    pub plastic_stiffness: PlasticStiffness,
    /// Where the mesh comes from.
    pub mesh: MeshDesc,
    /// Material of each region, in file order.
    pub regions: Vec<RegionDesc>,
    /// Interface law per pair of regions, in file order.
    pub interfaces: Vec<InterfaceDesc>,
    /// Edge sets whose interfaces start broken (`fracture.broken`).
    pub broken: Vec<EdgeSetRef>,
    /// Loads, in file order.
    pub loads: Vec<LoadDesc>,
    /// A periodic cell and its macroscopic loading (`[periodic]`).
    pub periodic: Option<Box<PeriodicDesc>>,
}

/// The `[periodic]` section.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PeriodicDesc {
    /// The cell `[[xmin, ymin], [xmax, ymax]]` (m); the mesh's bounding box when absent.
    pub cell: Option<[[f64; 2]; 2]>,
    /// Drive of each component `[xx, yy, xy]` of the macroscopic strain.
    pub drives: [MacroDrive; 3],
    /// The `[periodic]` table.
    pub place: Place,
}

/// The `[mesh]` section.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshDesc {
    /// File or generator.
    pub source: MeshSource,
    /// The `[mesh]` table.
    pub place: Place,
    /// Each key of the table with where its value was written (to place generator errors).
    pub keys: Vec<(String, Place)>,
}

/// Where the mesh comes from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum MeshSource {
    /// A Gmsh MSH 4.1 file, resolved against the scene file's directory.
    File(PathBuf),
    /// `xper_mesh::double_edge_notched`.
    DoubleEdgeNotched(NotchedSpec),
    /// `xper_mesh::rectangle_with_inclusions`.
    RectangleWithInclusions(RectangleSpec),
    /// `xper_mesh::periodic_cell`.
    PeriodicCell(PeriodicCellSpec),
}

/// A `[[regions]]` entry: the material of the mesh region of that name.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegionDesc {
    /// Region name (a region of the mesh).
    pub name: String,
    /// Bulk material.
    pub material: Material,
    /// Where the name was written.
    pub place: Place,
}

/// An interface stiffness: a value (Pa/m) or LMGC90's rule of thumb.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Stiffness {
    /// A given value (Pa/m), > 0.
    Value(f64),
    /// `C_N = 23 E / (L (1 - 2 nu))`, `C_T = 2 (1 - 2 nu) / (1 + 3 nu) C_N` with the E and nu
    /// of the stiffer region of the pair and L the element size (generators) or the mean
    /// edge length (mesh files).
    RuleOfThumb,
}

/// The law of an `[[interfaces]]` entry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum InterfaceLawDesc {
    /// Frictional cohesive zone (`xper_laws::cohesive::CohesiveZone`).
    Cohesive {
        /// `C_N` (Pa/m).
        normal_stiffness: Stiffness,
        /// `C_T` (Pa/m).
        tangential_stiffness: Stiffness,
        /// Fracture energy w (J/m^2), > 0.
        fracture_energy: f64,
        /// Strength R_max (Pa), > 0.
        strength: f64,
        /// Initial intensity beta0, in (0, 1].
        initial_damage: f64,
        /// Coulomb friction after failure (dimensionless), >= 0.
        friction: f64,
    },
    /// Unilateral contact with Coulomb friction, no adhesion.
    Contact {
        /// Friction coefficient (dimensionless), >= 0.
        friction: f64,
    },
}

/// An `[[interfaces]]` entry.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InterfaceDesc {
    /// The two region names (unordered; equal for interfaces inside one region).
    pub regions: [String; 2],
    /// The law.
    pub law: InterfaceLawDesc,
    /// Where `between` was written.
    pub place: Place,
}

/// A reference to an edge set of the mesh.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EdgeSetRef {
    /// Edge set name.
    pub name: String,
    /// Where it was written.
    pub place: Place,
}

/// A `[[loads]]` entry.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoadDesc {
    /// Load name (series columns `<name>_fx`, ...).
    pub name: String,
    /// Which nodes.
    pub nodes: NodeSelector,
    /// Drive of the x and y components: imposed velocity (m/s), total force (N) or free.
    pub drives: [Drive; 2],
    /// Where `nodes` was written.
    pub place: Place,
}
