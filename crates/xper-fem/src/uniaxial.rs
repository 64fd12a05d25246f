//! A strain driver for material tests: uniaxial stress in the plane.
//!
//! The axial strain `e_xx` follows a prescribed path; the lateral strain `e_yy` is solved at
//! every step (safeguarded Newton with the consistent tangent, [`crate::root`]) so that
//! `s_yy = 0`, with `e_xy = 0`. In plane strain `e_zz = 0` and `s_zz` builds up; in plane
//! stress `s_zz = 0` as well, which makes it the 3D uniaxial stress test, where J2 with
//! linear hardening gives exactly `s_xx = sigma_0 + H p` and `p = e_p,xx`
//! (J.C. Simo, T.J.R. Hughes, "Computational Inelasticity", Springer 1998, section 2.2).

use crate::error::FemError;
use crate::material::{Hypothesis, Material, MaterialState};
use crate::root::solve_increasing;

/// One converged step of [`uniaxial_stress_response`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UniaxialPoint {
    /// The prescribed axial strain `e_xx`.
    pub axial_strain: f64,
    /// The lateral strain `e_yy` that makes `s_yy` vanish.
    pub lateral_strain: f64,
    /// The material state.
    pub state: MaterialState,
    /// Plastic work of the step per unit volume (J/m^3).
    pub plastic_work: f64,
}

/// Drives the axial strain along `strain_path` from a virgin state and returns one point
/// per entry. Fails with [`FemError::InvalidMaterial`] for invalid parameters,
/// [`FemError::NonFiniteStrain`] for a NaN or infinite strain and
/// [`FemError::NotConverged`] if `s_yy = 0` cannot be met (it always can for a valid
/// material). `s_yy` is solved to `1e-13` of the stress scale `E |e_xx| + sigma_y`.
pub fn uniaxial_stress_response(
    material: &Material,
    hypothesis: Hypothesis,
    strain_path: &[f64],
) -> Result<Vec<UniaxialPoint>, FemError> {
    material.validate()?;
    let mut state = MaterialState::default();
    let mut lateral = 0.0;
    let mut points = Vec::with_capacity(strain_path.len());
    for (step, &axial) in strain_path.iter().enumerate() {
        if !axial.is_finite() {
            return Err(FemError::NonFiniteStrain { step });
        }
        let yield_scale = match *material {
            Material::LinearElastic { .. } => 0.0,
            Material::J2Plastic {
                yield_stress,
                hardening,
                ..
            } => yield_stress + hardening * state.equivalent_plastic_strain,
        };
        let tolerance = 1e-13 * (material.young() * axial.abs() + yield_scale);
        let residual = |e_yy: f64| {
            let u = material.update(hypothesis, &state, [axial, e_yy, 0.0]);
            (u.state.stress[1], u.tangent[1][1])
        };
        // Guess: the previous lateral strain shifted by the elastic Poisson contraction.
        let previous_axial = points
            .last()
            .map_or(0.0, |p: &UniaxialPoint| p.axial_strain);
        let nu = material.poisson();
        let poisson = match hypothesis {
            Hypothesis::PlaneStrain => nu / (1.0 - nu),
            Hypothesis::PlaneStress => nu,
        };
        let guess = lateral - poisson * (axial - previous_axial);
        lateral = solve_increasing(residual, guess, tolerance)
            .map_err(|residual| FemError::NotConverged { step, residual })?;
        let update = material.update(hypothesis, &state, [axial, lateral, 0.0]);
        state = update.state;
        points.push(UniaxialPoint {
            axial_strain: axial,
            lateral_strain: lateral,
            state,
            plastic_work: update.plastic_work,
        });
    }
    Ok(points)
}
