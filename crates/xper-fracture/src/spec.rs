//! What a fracture model is built from ([`FractureSpec`]): the interface laws between
//! regions, the loads on node sets, the mass matrix and the elastoplastic stiffness options.

use serde::{Deserialize, Serialize};
use xper_bodies::Drive;
use xper_fem::{Hypothesis, Material};
use xper_laws::cohesive::CohesiveZone;
use xper_solver::NlgsParams;

use crate::cell::PeriodicSpec;

/// The law of an interface between two elements.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum InterfaceLaw {
    /// Frictional cohesive zone (BRIEF.md section 3; LMGC90's MP3_CZM); once broken, unilateral
    /// contact with the zone's friction coefficient.
    Cohesive(CohesiveZone),
    /// Unilateral contact with Coulomb friction `mu` and no adhesion.
    Contact {
        /// Friction coefficient (dimensionless).
        friction: f64,
    },
}

impl InterfaceLaw {
    /// Friction coefficient of the contact part.
    pub fn friction(&self) -> f64 {
        match self {
            InterfaceLaw::Cohesive(z) => z.friction,
            InterfaceLaw::Contact { friction } => *friction,
        }
    }
}

/// The law between the elements of two regions (an unordered pair of region indices).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct InterfaceRule {
    /// Region indices into `Mesh::regions`; `[r, r]` for interfaces inside region `r`.
    pub regions: [u32; 2],
    /// The law.
    pub law: InterfaceLaw,
}

/// A load on a set of mesh nodes: per component, free, an imposed velocity (m/s) or a total
/// force (N). The force is spread as a uniform traction over the boundary edges joining two
/// nodes of the set (consistent nodal forces); a set without such an edge (a point) shares
/// it equally among the copies of its nodes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NodeLoad {
    /// Name of the load (reported in the series).
    pub name: String,
    /// Mesh node indices.
    pub nodes: Vec<u32>,
    /// Drive of the x and y components (velocity or force; a pressure is refused by
    /// [`FractureModel::new`]).
    pub drives: [Drive; 2],
}

/// Element mass matrix.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum MassMatrix {
    /// Consistent mass `rho A t / 12 [2 1 1; 1 2 1; 1 1 2]`.
    #[default]
    Consistent,
    /// Row-sum lumped mass `rho A t / 3` per node.
    Lumped,
}

/// The stiffness `K` of an elastoplastic element in its effective mass `M + h^2 theta^2 K`
/// and in the implicit part `h^2 theta K v` of a step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum PlasticStiffness {
    /// The tangent of the last radial return (softer while the element yields).
    #[default]
    Tangent,
    /// The elastic stiffness throughout. An element that unloads elastically after yielding
    /// is then integrated implicitly at its true stiffness: with the tangent, an element held
    /// by few interfaces (a fragment after a crack) can oscillate with a growing amplitude
    /// when `h` exceeds its own period (measured in `scenes/periodic_bimaterial_small`).
    Elastic,
}

/// Everything needed to build a [`FractureModel`] from a mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FractureSpec {
    /// Out-of-plane thickness t (m).
    pub thickness: f64,
    /// Plane strain or plane stress.
    pub hypothesis: Hypothesis,
    /// Material of each region, in the order of `Mesh::regions`.
    pub materials: Vec<Material>,
    /// Interface law per pair of regions; every pair of neighbouring regions needs one.
    pub interface_laws: Vec<InterfaceRule>,
    /// Interfaces on these edge sets start broken (pre-cracks, notches closed in the mesh).
    pub broken_edge_sets: Vec<String>,
    /// Loads on node sets.
    pub loads: Vec<NodeLoad>,
    /// Body force per unit mass (m/s^2).
    pub gravity: [f64; 2],
    /// Element mass matrix.
    pub mass: MassMatrix,
    /// Time step h (s).
    pub dt: f64,
    /// theta of the theta-method, in [1/2, 1].
    pub theta: f64,
    /// NLGS parameters of the interface problem.
    pub nlgs: NlgsParams,
    /// A periodic cell and its macroscopic loading (the crate's `cell` module); `None` for a specimen.
    #[serde(default)]
    pub periodic: Option<PeriodicSpec>,
    /// The stiffness of elastoplastic elements in the step's implicit part.
    #[serde(default)]
    pub plastic_stiffness: PlasticStiffness,
}

/// Why a model cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub struct BuildError(pub String);

impl std::fmt::Display for BuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BuildError {}
