//! Non-smooth fracture dynamics (NSFD): every triangle of a mesh is its own deformable body
//! and a frictional cohesive interface joins every pair of neighbouring triangles
//! (BRIEF.md sections 2 and 3; F. Perales, F. Dubois, Y. Monerie, B. Piar, L. Stainier,
//! "A NonSmooth Contact Dynamics-based multi-domain solver", EJCM 19, 2010).
//!
//! [`FractureModel::new`] explodes a [`xper_mesh::Mesh`] as a [`FractureSpec`] says
//! (materials per region, interface laws per pair of regions, pre-cracks, loads on node
//! sets); [`FractureStepper::step`] advances it by the theta-method, solving the interface
//! problem by NLGS on the factorised operator ([`ElementContactOperator`]) with the adhesive
//! part of each cohesive point eliminated exactly in its local solve.

// Dense 6x6 kernels read best with explicit indices.
#![allow(clippy::needless_range_loop)]

mod cell;
mod dense;
mod domain;
mod homogenize;
mod interface;
mod model;
mod operator;
mod part;
mod spec;
mod step;
mod update;

pub use cell::{
    drift_response, strain_times, tensor_weights, CellState, MacroDrive, PeriodicSpec, SHEAR_WEIGHT,
};
pub use dense::{masked_spd_inverse, Mat6};
pub use homogenize::{effective_tensor, HomogenizeError, Homogenized};
pub use model::{
    BuildError, ElementBody, FractureEnergy, FractureModel, FractureSpec, Interface, InterfaceLaw,
    InterfaceRule, MassMatrix, NodeLoad, PlasticStiffness, PointState,
};
pub use operator::{CellWork, ElementContactOperator, ElementWork, InterfaceRow};

pub use step::{
    elastic_energy, stored_energy, FractureStepError, FractureStepReport, FractureStepper,
    LoadReading,
};
