//! Finite-element kernels for the deformable bodies of xper: the linear 3-node triangle,
//! isotropic linear elasticity and J2 elastoplasticity with linear isotropic hardening, in
//! plane strain (the default) or plane stress.
//!
//! In xper's fracture runs every triangle of a mesh is its own deformable body (BRIEF.md
//! section 3), so these kernels work element by element: the engine assembles, integrates
//! in time (Moreau-Jean, `M + h^2 theta^2 K_t`) and handles contact. Nothing here steps in
//! time.
//!
//! Units are SI: coordinates and displacements in m, stresses and moduli in Pa, densities in
//! kg/m^3, energies in J (per element) or J/m^3 (per volume). In-plane strains are
//! `[e_xx, e_yy, 2 e_xy]`, in-plane stresses `[s_xx, s_yy, s_xy]`, element degrees of
//! freedom `[u1x, u1y, u2x, u2y, u3x, u3y]`.
//!
//! Energies for the engine's balance: [`Triangle3::elastic_energy`] (`A t psi_e`) and the
//! plastic dissipation of an update, `Triangle3::volume() * MaterialUpdate::plastic_work`.

mod error;
mod j2;
mod material;
mod root;
mod triangle;
mod uniaxial;

pub use error::FemError;
pub use material::{Hypothesis, Material, MaterialState, MaterialUpdate};
pub use triangle::Triangle3;
pub use uniaxial::{uniaxial_stress_response, UniaxialPoint};
