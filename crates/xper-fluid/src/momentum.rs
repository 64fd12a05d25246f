//! The explicit momentum predictor on the MAC grid:
//!
//! ```text
//! u*_d = u_d + dt ( - div(u u_d) + nu lap(u_d) - (1/rho) d_d p + f_d )
//! ```
//!
//! Advection in conservative form with centred interpolation to cell centres and cell corners,
//! blended with donor-cell upwinding by the factor `gamma` (Griebel, Dornseifer and
//! Neunhoeffer, "Numerical Simulation in Fluid Dynamics", SIAM 1998, section 3.1.2: `gamma = 0`
//! is the second-order central scheme, `gamma = 1` first-order donor cell); diffusion by the
//! 5-point Laplacian. One stencil serves every component `d`, written with the neighbour
//! offsets `s_d` (along the component) and `s_e` (across it) of the shared padded layout.

use crate::boundary::FluidBoundary;
use crate::grid::MacGrid;
use xper_math::{Real, Vector, DIM};

/// The coefficients of one predictor evaluation.
#[derive(Clone, Copy, Debug)]
pub struct PredictorCoefficients {
    /// Time step (s).
    pub dt: Real,
    /// Kinematic viscosity (m^2/s).
    pub kinematic_viscosity: Real,
    /// Fluid density (kg/m^3).
    pub density: Real,
    /// Body force per unit mass (m/s^2).
    pub body_force: Vector,
    /// Donor-cell blending factor in [0, 1].
    pub upwinding: Real,
}

/// Writes `u*` into `u_star` on the predicted faces (other entries are copied from `u`).
pub fn predict(
    grid: &MacGrid,
    boundary: &FluidBoundary,
    coefficients: &PredictorCoefficients,
    u: &[Vec<Real>; DIM],
    p: &[Real],
    u_star: &mut [Vec<Real>; DIM],
) {
    let h = grid.h;
    let inv_h = 1.0 / h;
    let nu_h2 = coefficients.kinematic_viscosity / (h * h);
    let gamma = coefficients.upwinding;
    let dt = coefficients.dt;
    let pressure_factor = inv_h / coefficients.density;
    for d in 0..DIM {
        let e = 1 - d;
        let (sd, se) = (grid.stride(d), grid.stride(e));
        let (ud, ue) = (&u[d], &u[e]);
        u_star[d].copy_from_slice(ud);
        let out = &mut u_star[d];
        let force = coefficients.body_force[d];
        for run in grid.face_rows(d, boundary.predicted_faces(grid, d)) {
            let (r, n) = (run.start, run.len());
            let window = |field, offset| window(field, r, offset, n);
            let (sd_i, se_i) = (sd as isize, se as isize);
            let centre = window(ud, 0);
            let (plus_d, minus_d) = (window(ud, sd_i), window(ud, -sd_i));
            let (plus_e, minus_e) = (window(ud, se_i), window(ud, -se_i));
            let (upper_back, upper) = (window(ue, se_i - sd_i), window(ue, se_i));
            let (lower_back, lower) = (window(ue, -sd_i), window(ue, 0));
            let (p_here, p_back) = (window(p, 0), window(p, -sd_i));
            let out = &mut out[r..r + n];
            for k in 0..n {
                let c = centre[k];
                let (dp, dm, ep, em) = (plus_d[k], minus_d[k], plus_e[k], minus_e[k]);
                let right = 0.5 * (c + dp);
                let left = 0.5 * (dm + c);
                let flux_d = right * right + gamma * right.abs() * 0.5 * (c - dp)
                    - left * left
                    - gamma * left.abs() * 0.5 * (dm - c);
                let up = 0.5 * (upper_back[k] + upper[k]);
                let low = 0.5 * (lower_back[k] + lower[k]);
                let flux_e = up * 0.5 * (c + ep) + gamma * up.abs() * 0.5 * (c - ep)
                    - low * 0.5 * (em + c)
                    - gamma * low.abs() * 0.5 * (em - c);
                let advection = (flux_d + flux_e) * inv_h;
                let diffusion = nu_h2 * (dp + dm + ep + em - 4.0 * c);
                let pressure = (p_here[k] - p_back[k]) * pressure_factor;
                out[k] = c + dt * (diffusion - advection - pressure + force);
            }
        }
    }
}

/// The `n` entries of `field` from `start + offset`.
#[inline]
fn window(field: &[Real], start: usize, offset: isize, n: usize) -> &[Real] {
    let from = (start as isize + offset) as usize;
    &field[from..from + n]
}
