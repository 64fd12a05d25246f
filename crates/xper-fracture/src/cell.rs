//! A periodic cell under a macroscopic strain or stress: the displacement of every element
//! node is `u = E x + u~` with `u~` periodic (F. Perales, S. Bourgeois, A. Chrysochoos,
//! Y. Monerie, "Two-field multibody method for periodic homogenization in fracture
//! mechanics of nonlinear heterogeneous materials", Eng. Fract. Mech. 75 (2008) 3378).
//!
//! The elements carry the whole displacement `u`; the macroscopic strain
//! `E = [[E_xx, E_xy], [E_xy, E_yy]]` (dimensionless, Voigt order `[xx, yy, xy]`, tensor
//! shear) enters only through the interfaces that join a side of the cell to the opposite
//! one. Their node copies sit one period `T` apart, so their jump is that of the periodic
//! fluctuation, `[u~] = u_b - u_a - E T`, and their local velocity is
//! `U = (v_b - v_a - E' T) . (n, t)` (`E'` the strain rate).
//!
//! Each component of `E` is either imposed (`E(t)` given: its rate over a step is the
//! increment over `h`, so that the jumps gain exactly `(E(t_i+1) - E(t_i)) T`) or free under
//! an imposed macroscopic stress `Sigma(t)`. A free component is a degree of freedom of the
//! contact problem, as a body is: its generalised impulse from an interface point of impulse
//! `p` (on `b`, global frame) is `-(p (x) T)` symmetrised (`-(p_x T_y + p_y T_x)` for `xy`,
//! whose component appears twice in `E`), and its equation of motion over a step is
//! `M_k (E'_i+1 - E'_i) = h c_k V Sigma_k(t_theta) + P_k` with `c = [1, 1, 2]` and `V` the
//! cell's volume. Its mass `M_k` is the kinetic inertia of the affine motion `v = E' x` of
//! the cell, `rho V [W^2, H^2, W^2 + H^2] / 12` (kg m^2), as the cell-shape degrees of freedom
//! of M. Parrinello, A. Rahman, J. Appl. Phys. 52 (1981) 7182 carry a mass; at equilibrium
//! the boundary stress `Sigma = (1 / (V h)) sum sym(p (x) T)` equals the imposed one.

use serde::{Deserialize, Serialize};
use xper_bodies::TimeFunction;
use xper_mesh::PeriodicCell;

use crate::model::{BuildError, ElementBody, FractureModel};

/// What drives one component of the macroscopic strain.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MacroDrive {
    /// The strain `E_k(t)` is imposed (dimensionless).
    Strain(TimeFunction),
    /// The stress `Sigma_k(t)` is imposed (Pa); the strain follows.
    Stress(TimeFunction),
}

/// A periodic cell and its macroscopic loading.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeriodicSpec {
    /// The cell; the mesh must fill it and match side to side.
    pub cell: PeriodicCell,
    /// Drives of `[E_xx, E_yy, E_xy]`.
    pub drives: [MacroDrive; 3],
}

/// The macroscopic state of a periodic cell.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CellState {
    /// Macroscopic strain `[E_xx, E_yy, E_xy]` (dimensionless).
    pub strain: [f64; 3],
    /// Its rate over the last step (1/s): the end-of-step rate of free components.
    pub rate: [f64; 3],
    /// Macroscopic stress `[xx, yy, xy]` (Pa) from the forces across the periodic sides,
    /// `(1 / (V h)) sum sym(p (x) T)`.
    pub stress_boundary: [f64; 3],
    /// Macroscopic stress (Pa) as the volume average of the element stresses.
    pub stress_volume: [f64; 3],
    /// Work of the macroscopic loading since the start (J): what the imposed strain or
    /// stress gave to the cell, counted in the external work of the energy budget.
    pub work: f64,
}

/// `c_k` of the work `V c_k Sigma_k dE_k`: the shear component appears twice in `E`.
pub const SHEAR_WEIGHT: [f64; 3] = [1.0, 1.0, 2.0];

/// `E T` for the strain (or rate) `e` in Voigt order and a period `t` (m).
#[inline(always)]
pub fn strain_times(e: &[f64; 3], t: [f64; 2]) -> [f64; 2] {
    [e[0] * t[0] + e[2] * t[1], e[2] * t[0] + e[1] * t[1]]
}

/// The components `sym(p (x) T)` in Voigt order weighted as the work is: `[p_x T_x,
/// p_y T_y, p_x T_y + p_y T_x]`, so that `p . (E T) = sum_k out_k E_k`.
#[inline(always)]
pub fn tensor_weights(p: [f64; 2], t: [f64; 2]) -> [f64; 3] {
    [p[0] * t[0], p[1] * t[1], p[0] * t[1] + p[1] * t[0]]
}

/// The global 2x2 matrix `S` (row-major) with `d(-E' T) = S p` when an impulse `p` acts on
/// the free components of inverse masses `inv_mass`.
pub fn drift_response(inv_mass: &[f64; 3], t: [f64; 2]) -> [f64; 4] {
    let [m1, m2, m3] = *inv_mass;
    [
        m1 * t[0] * t[0] + m3 * t[1] * t[1],
        m3 * t[0] * t[1],
        m3 * t[0] * t[1],
        m2 * t[1] * t[1] + m3 * t[0] * t[0],
    ]
}

impl PeriodicSpec {
    /// Whether component `k` is under an imposed stress.
    pub fn is_free(&self, k: usize) -> bool {
        matches!(self.drives[k], MacroDrive::Stress(_))
    }

    /// The mass of each component (kg m^2): the inertia of the affine motion of a cell of
    /// `mass` (kg); see the module documentation.
    pub fn component_mass(&self, mass: f64) -> [f64; 3] {
        let [w, h] = self.cell.size;
        [
            mass * w * w / 12.0,
            mass * h * h / 12.0,
            mass * (w * w + h * h) / 12.0,
        ]
    }
}

impl FractureModel {
    /// Mass of the whole mesh (kg).
    pub fn total_mass(&self) -> f64 {
        (0..self.mesh.triangles.len())
            .map(|t| {
                let region = self.mesh.triangle_region[t] as usize;
                self.spec.materials[region].density()
                    * self.mesh.triangle_area(t)
                    * self.spec.thickness
            })
            .sum()
    }

    /// Mass of each component of the macroscopic strain of a periodic cell (kg m^2), see
    /// the crate's `cell` module; zeros without one.
    pub fn cell_mass(&self) -> [f64; 3] {
        match &self.spec.periodic {
            Some(p) => p.component_mass(self.total_mass()),
            None => [0.0; 3],
        }
    }

    /// Kinetic energy of the free components of a periodic cell's strain, `M_k E'_k^2 / 2`
    /// (J); zero without one.
    pub(crate) fn cell_kinetic_energy(&self) -> f64 {
        let (Some(p), Some(c)) = (&self.spec.periodic, &self.cell) else {
            return 0.0;
        };
        if self.cell_copy || !(0..3).any(|k| p.is_free(k)) {
            return 0.0;
        }
        let mass = self.cell_mass();
        (0..3)
            .filter(|&k| p.is_free(k))
            .map(|k| 0.5 * mass[k] * c.rate[k] * c.rate[k])
            .sum()
    }
}

/// The state of a periodic cell at time 0; an imposed strain must start from zero (the
/// elements start undeformed). The elements start in the affine motion `v = E'(0) (X - X_c)`
/// of the imposed components' first rate (`X_c` the cell's centre), so that a homogeneous
/// cell loaded at a constant rate launches no wave (the free components start at rest).
pub(crate) fn initial_cell(
    p: &PeriodicSpec,
    dt: f64,
    elements: &mut [ElementBody],
) -> Result<CellState, BuildError> {
    let mut rate = [0.0; 3];
    for (k, d) in p.drives.iter().enumerate() {
        let MacroDrive::Strain(f) = d else {
            continue;
        };
        let e0 = f.eval(0.0);
        if e0 != 0.0 {
            return Err(BuildError(format!(
                "periodic cell: the imposed strain {} starts at {e0}, not 0 (the cell starts \
                 undeformed)",
                ["xx", "yy", "xy"][k]
            )));
        }
        rate[k] = (f.eval(dt) - e0) / dt;
    }
    let center = [
        p.cell.lower[0] + 0.5 * p.cell.size[0],
        p.cell.lower[1] + 0.5 * p.cell.size[1],
    ];
    if rate != [0.0; 3] {
        for el in elements.iter_mut() {
            for (j, x) in el.triangle.nodes().iter().enumerate() {
                let v = strain_times(&rate, [x[0] - center[0], x[1] - center[1]]);
                el.velocity[2 * j] = v[0];
                el.velocity[2 * j + 1] = v[1];
            }
        }
    }
    Ok(CellState {
        rate,
        ..Default::default()
    })
}
