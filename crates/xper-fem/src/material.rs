//! Bulk materials of the deformable bodies: isotropic linear elasticity and J2
//! elastoplasticity with linear isotropic hardening, in plane strain or plane stress.
//!
//! Sources: linear elasticity and its plane reductions, O.C. Zienkiewicz, R.L. Taylor,
//! J.Z. Zhu, "The Finite Element Method: its Basis and Fundamentals", 7th ed., 2013,
//! section 6.2; J2 plasticity, J.C. Simo, T.J.R. Hughes, "Computational Inelasticity",
//! Springer 1998, boxes 3.1 and 3.2 (see [`crate::j2`]). Plane strain restricts the 3D
//! return map to `e_zz = 0` (the in-plane block of the 3D consistent tangent is then exact);
//! plane stress solves `s_zz(e_zz) = 0` for the out-of-plane strain with a safeguarded
//! Newton method and condenses the tangent, `D = C_pp - C_pz C_zp / C_zz` (the approach of
//! S. Klinkel, S. Govindjee, "Using finite strain 3D-material models in beam and shell
//! elements", Engineering Computations 19 (2002) 254-271).
//!
//! Conventions: in-plane strains `[e_xx, e_yy, 2 e_xy]`; tangents map them to
//! `[s_xx, s_yy, s_xy]` (Pa); states keep `[xx, yy, zz, xy]` components.

use crate::error::FemError;
use crate::j2::{von_mises, Return3, J2};
use crate::root::solve_increasing;
use serde::{Deserialize, Serialize};

/// The plane reduction of the 3D problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Hypothesis {
    /// `e_zz = e_xz = e_yz = 0`; `s_zz` follows from the material (the default, as in the
    /// paper's runs).
    #[default]
    PlaneStrain,
    /// `s_zz = s_xz = s_yz = 0`; `e_zz` follows from the material.
    PlaneStress,
}

/// An isotropic bulk material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Material {
    /// Isotropic linear elasticity.
    LinearElastic {
        /// Young's modulus `E` (Pa), > 0.
        young: f64,
        /// Poisson's ratio `nu` (dimensionless), in (-1, 0.5).
        poisson: f64,
        /// Mass density `rho` (kg/m^3), > 0.
        density: f64,
    },
    /// Von Mises (J2) elastoplasticity with linear isotropic hardening,
    /// `sigma_y = sigma_0 + H p`, `p` the equivalent plastic strain.
    J2Plastic {
        /// Young's modulus `E` (Pa), > 0.
        young: f64,
        /// Poisson's ratio `nu` (dimensionless), in (-1, 0.5).
        poisson: f64,
        /// Mass density `rho` (kg/m^3), > 0.
        density: f64,
        /// Initial yield stress `sigma_0` (Pa), > 0.
        yield_stress: f64,
        /// Hardening modulus `H` (Pa), >= 0: slope of the yield stress against the
        /// equivalent plastic strain (the uniaxial tangent modulus is `E H / (E + H)`).
        hardening: f64,
    },
}

/// The state of a material point.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
pub struct MaterialState {
    /// Stress `[s_xx, s_yy, s_zz, s_xy]` (Pa); `s_zz` is 0 in plane stress.
    pub stress: [f64; 4],
    /// Plastic strain `[e_xx, e_yy, e_zz, 2 e_xy]` (engineering shear, like the total
    /// strain), trace-free; zero for an elastic material.
    pub plastic_strain: [f64; 4],
    /// Equivalent (accumulated) plastic strain `p = int sqrt(2/3 de_p : de_p)`.
    pub equivalent_plastic_strain: f64,
}

impl MaterialState {
    /// The in-plane stress `[s_xx, s_yy, s_xy]` (Pa), the input of
    /// [`crate::Triangle3::internal_force`].
    pub fn in_plane_stress(&self) -> [f64; 3] {
        [self.stress[0], self.stress[1], self.stress[3]]
    }

    /// The von Mises equivalent stress `sqrt(3/2 s : s)` of the 3D stress (Pa).
    pub fn von_mises(&self) -> f64 {
        let s = self.stress;
        von_mises(&[s[0], s[1], s[2], s[3], 0.0, 0.0])
    }
}

/// The outcome of [`Material::update`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialUpdate {
    /// The new state.
    pub state: MaterialState,
    /// The consistent (algorithmic) tangent `d[s_xx, s_yy, s_xy] / d[e_xx, e_yy, 2 e_xy]`
    /// (Pa); symmetric.
    pub tangent: [[f64; 3]; 3],
    /// Plastic work of the increment per unit volume (J/m^3): `dp (sigma_0 + H (p_n +
    /// p_n+1) / 2)`, the exact `int sigma_y dp` over the increment. It equals
    /// `int sigma : de_p` along any path on which the flow direction is constant (a
    /// radial-return step), so that `int sigma : de = psi_e + sum plastic_work` holds
    /// exactly on such paths. It counts the hardening energy `H p^2 / 2` as spent.
    pub plastic_work: f64,
}

/// In-plane components of the 3D Voigt vectors: xx, yy, xy.
const IN_PLANE: [usize; 3] = [0, 1, 3];

impl Material {
    /// Checks the parameters: all finite, `E > 0`, `-1 < nu < 0.5`, `rho > 0`, and for J2
    /// `sigma_0 > 0`, `H >= 0`. Both hypotheses are supported by both materials.
    pub fn validate(&self) -> Result<(), FemError> {
        let check = |parameter, value: f64, ok: bool, expected| {
            if value.is_finite() && ok {
                Ok(())
            } else {
                Err(FemError::InvalidMaterial {
                    parameter,
                    value,
                    expected,
                })
            }
        };
        let (young, poisson, density) = (self.young(), self.poisson(), self.density());
        check("young", young, young > 0.0, "finite and > 0 (Pa)")?;
        let nu_ok = poisson > -1.0 && poisson < 0.5;
        check("poisson", poisson, nu_ok, "in (-1, 0.5)")?;
        check("density", density, density > 0.0, "finite and > 0 (kg/m^3)")?;
        if let Material::J2Plastic {
            yield_stress,
            hardening,
            ..
        } = *self
        {
            let s0 = yield_stress;
            check("yield_stress", s0, s0 > 0.0, "finite and > 0 (Pa)")?;
            check(
                "hardening",
                hardening,
                hardening >= 0.0,
                "finite and >= 0 (Pa)",
            )?;
        }
        Ok(())
    }

    /// Young's modulus `E` (Pa).
    pub fn young(&self) -> f64 {
        match *self {
            Material::LinearElastic { young, .. } | Material::J2Plastic { young, .. } => young,
        }
    }

    /// Poisson's ratio `nu`.
    pub fn poisson(&self) -> f64 {
        match *self {
            Material::LinearElastic { poisson, .. } | Material::J2Plastic { poisson, .. } => {
                poisson
            }
        }
    }

    /// Mass density `rho` (kg/m^3).
    pub fn density(&self) -> f64 {
        match *self {
            Material::LinearElastic { density, .. } | Material::J2Plastic { density, .. } => {
                density
            }
        }
    }

    /// The 3D constants: shear and bulk moduli, yield stress and hardening (an elastic
    /// material yields at an infinite stress).
    fn j2(&self) -> J2 {
        let (e, nu) = (self.young(), self.poisson());
        let (yield_stress, hardening) = match *self {
            Material::LinearElastic { .. } => (f64::INFINITY, 0.0),
            Material::J2Plastic {
                yield_stress,
                hardening,
                ..
            } => (yield_stress, hardening),
        };
        J2 {
            shear: e / (2.0 * (1.0 + nu)),
            bulk: e / (3.0 * (1.0 - 2.0 * nu)),
            yield_stress,
            hardening,
        }
    }

    /// The elastic tangent (Pa): plane strain `[[l + 2m, l, 0], [l, l + 2m, 0], [0, 0, m]]`
    /// (Lame constants `l`, `m`), plane stress `E / (1 - nu^2) [[1, nu, 0], [nu, 1, 0],
    /// [0, 0, (1 - nu) / 2]]`.
    pub fn elastic_tangent(&self, hypothesis: Hypothesis) -> [[f64; 3]; 3] {
        reduce(&self.j2().elastic_tangent(), hypothesis)
    }

    /// The state and consistent tangent at the total in-plane strain `[e_xx, e_yy, 2 e_xy]`
    /// reached from `previous` (backward Euler; exact for an elastic material). The
    /// parameters are assumed valid ([`Material::validate`]). The plane-stress condition
    /// `s_zz = 0` is solved to round-off by Newton's method kept inside a bracket: `s_zz`
    /// increases with `e_zz` at a rate of at least the bulk modulus, so the bracket always
    /// exists and bisection always closes it; only non-finite strains (which give
    /// non-finite stresses) end without a root.
    pub fn update(
        &self,
        hypothesis: Hypothesis,
        previous: &MaterialState,
        total_strain: [f64; 3],
    ) -> MaterialUpdate {
        let j2 = self.j2();
        let ep = previous.plastic_strain;
        let plastic = [ep[0], ep[1], ep[2], ep[3], 0.0, 0.0];
        let p = previous.equivalent_plastic_strain;
        let strain3 = |e_zz: f64| {
            [
                total_strain[0],
                total_strain[1],
                e_zz,
                total_strain[2],
                0.0,
                0.0,
            ]
        };
        let result = match hypothesis {
            Hypothesis::PlaneStrain => j2.radial_return(&plastic, p, &strain3(0.0)),
            Hypothesis::PlaneStress => {
                // Elastic guess with the plastic strain frozen, then s_zz(e_zz) = 0.
                let nu = self.poisson();
                let guess =
                    ep[2] - nu / (1.0 - nu) * (total_strain[0] - ep[0] + total_strain[1] - ep[1]);
                let scale = 1e-14 * (self.young() * strain_size(&total_strain) + j2_scale(&j2, p));
                let solve = |e_zz| {
                    let r = j2.radial_return(&plastic, p, &strain3(e_zz));
                    (r.stress[2], r.tangent[2][2])
                };
                let e_zz = solve_increasing(solve, guess, scale).unwrap_or(guess);
                let mut r = j2.radial_return(&plastic, p, &strain3(e_zz));
                r.stress[2] = 0.0;
                r
            }
        };
        let Return3 {
            stress,
            plastic_strain,
            equivalent_plastic_strain,
            tangent,
            plastic_work,
        } = result;
        MaterialUpdate {
            state: MaterialState {
                stress: [stress[0], stress[1], stress[2], stress[3]],
                plastic_strain: [
                    plastic_strain[0],
                    plastic_strain[1],
                    plastic_strain[2],
                    plastic_strain[3],
                ],
                equivalent_plastic_strain,
            },
            tangent: reduce(&tangent, hypothesis),
            plastic_work,
        }
    }

    /// The recoverable elastic energy per unit volume (J/m^3) of a state,
    /// `psi_e = 1/2 s : C^-1 : s = ((1 + nu) s : s - nu (tr s)^2) / (2 E)` with the 3D
    /// stress (so it includes the `s_zz` of plane strain).
    pub fn elastic_energy_density(&self, state: &MaterialState) -> f64 {
        let (e, nu) = (self.young(), self.poisson());
        let s = state.stress;
        let contraction = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * s[3] * s[3];
        let trace = s[0] + s[1] + s[2];
        ((1.0 + nu) * contraction - nu * trace * trace) / (2.0 * e)
    }
}

/// `|e|` of an in-plane strain (for tolerances only).
fn strain_size(e: &[f64; 3]) -> f64 {
    e.iter().map(|x| x.abs()).sum()
}

/// A stress scale of a J2 material at equivalent plastic strain `p` (an elastic material
/// has none).
fn j2_scale(j2: &J2, p: f64) -> f64 {
    let y = j2.yield_stress + j2.hardening * p;
    if y.is_finite() {
        y
    } else {
        0.0
    }
}

/// The in-plane 3x3 tangent of a 3D tangent: the xx, yy, xy block in plane strain, the
/// static condensation of zz in plane stress.
fn reduce(c: &[[f64; 6]; 6], hypothesis: Hypothesis) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let (a, b) = (IN_PLANE[i], IN_PLANE[j]);
            match hypothesis {
                Hypothesis::PlaneStrain => c[a][b],
                Hypothesis::PlaneStress => c[a][b] - c[a][2] * c[2][b] / c[2][2],
            }
        })
    })
}
