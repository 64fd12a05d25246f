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
//! [`predict_stage`] evaluates the same stencils as one stage of a three-stage Runge-Kutta
//! scheme ([`RK3_STAGES`]).

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
    let dt = coefficients.dt;
    let force = coefficients.body_force;
    each_face(
        grid,
        boundary,
        coefficients,
        u,
        p,
        u_star,
        |d, _, c, advection, diffusion, pressure| {
            c + dt * (diffusion - advection - pressure + force[d])
        },
    );
}

/// One stage of a low-storage Runge-Kutta scheme: the weights of the tendency of this stage
/// and of the last, and of the pressure gradient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RungeKuttaStage {
    /// Weight `gamma_k` of this stage's tendency.
    pub gamma: Real,
    /// Weight `zeta_k` of the last stage's tendency.
    pub zeta: Real,
    /// Weight `2 alpha_k = gamma_k + zeta_k` of the pressure gradient and of the stage's
    /// projection.
    pub pressure: Real,
}

/// Stage `k` of the explicit three-stage Runge-Kutta scheme of Wray (1990) in the form of Rai
/// and Moin, J. Comput. Phys. 96 (1991) 15, and Uhlmann, J. Comput. Phys. 209 (2005) 448,
/// eq. 9 (there with the viscous term implicit; here every term is explicit):
///
/// ```text
/// u*  = u^(k-1) + dt ( gamma_k N(u^(k-1)) + zeta_k N(u^(k-2)) - 2 alpha_k grad p^(k-1) / rho )
/// gamma = (8/15, 5/12, 3/4),  zeta = (0, -17/60, -5/12),  2 alpha_k = gamma_k + zeta_k,
/// ```
///
/// `N(u) = nu lap u - div(u u) + f`, each stage followed by a projection over `2 alpha_k dt`.
/// Third order for ordinary differential equations; with the pressure of the last stage
/// (the incremental projection) the velocity is second order (Le and Moin, J. Comput. Phys.
/// 92 (1991) 369).
pub const RK3_STAGES: [RungeKuttaStage; 3] = [
    RungeKuttaStage {
        gamma: 8.0 / 15.0,
        zeta: 0.0,
        pressure: 8.0 / 15.0,
    },
    RungeKuttaStage {
        gamma: 5.0 / 12.0,
        zeta: -17.0 / 60.0,
        pressure: 2.0 / 15.0,
    },
    RungeKuttaStage {
        gamma: 3.0 / 4.0,
        zeta: -5.0 / 12.0,
        pressure: 1.0 / 3.0,
    },
];

/// The largest Courant number (per velocity component, `|u_d| dt / h`) at which the
/// three-stage scheme is stable for the central advection whatever the viscosity: its
/// amplification `1 + z + z^2/2 + z^3/6` has modulus at most 1 on the imaginary axis up to
/// `sqrt(3)`, and the two components' central differences reach `2 |u_d| dt / h`.
pub const RK3_LARGEST_CFL: Real = 0.866;

/// Writes the Runge-Kutta stage `stage` of `u` into `u_star` on the predicted faces (other
/// entries are copied from `u`); `tendency` holds `N(u^(k-2))` on entry (read only when
/// `zeta != 0`) and `N(u^(k-1))` on exit.
#[allow(clippy::too_many_arguments)]
pub fn predict_stage(
    grid: &MacGrid,
    boundary: &FluidBoundary,
    coefficients: &PredictorCoefficients,
    stage: RungeKuttaStage,
    u: &[Vec<Real>; DIM],
    p: &[Real],
    tendency: &mut [Vec<Real>; DIM],
    u_star: &mut [Vec<Real>; DIM],
) {
    let dt = coefficients.dt;
    let force = coefficients.body_force;
    let RungeKuttaStage {
        gamma,
        zeta,
        pressure: weight,
    } = stage;
    each_face(
        grid,
        boundary,
        coefficients,
        u,
        p,
        u_star,
        |d, k, c, advection, diffusion, pressure| {
            let now = diffusion - advection + force[d];
            let before = if zeta == 0.0 { 0.0 } else { tendency[d][k] };
            tendency[d][k] = now;
            c + dt * (gamma * now + zeta * before - weight * pressure)
        },
    );
}

/// Evaluates the stencils at every predicted face of every component and writes
/// `update(d, k, u_k, advection, diffusion, pressure gradient / rho)` at padded index `k` of
/// `u_star[d]` (other entries are copied from `u`).
#[inline(always)]
fn each_face(
    grid: &MacGrid,
    boundary: &FluidBoundary,
    coefficients: &PredictorCoefficients,
    u: &[Vec<Real>; DIM],
    p: &[Real],
    u_star: &mut [Vec<Real>; DIM],
    mut update: impl FnMut(usize, usize, Real, Real, Real, Real) -> Real,
) {
    let h = grid.h;
    let inv_h = 1.0 / h;
    let nu_h2 = coefficients.kinematic_viscosity / (h * h);
    let gamma = coefficients.upwinding;
    let pressure_factor = inv_h / coefficients.density;
    for d in 0..DIM {
        let e = 1 - d;
        let (sd, se) = (grid.stride(d), grid.stride(e));
        let (ud, ue) = (&u[d], &u[e]);
        u_star[d].copy_from_slice(ud);
        let out = &mut u_star[d];
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
                out[k] = update(d, r + k, c, advection, diffusion, pressure);
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

#[cfg(test)]
mod tests {
    use super::*;

    type Complex = (Real, Real);
    fn mul(a: Complex, b: Complex) -> Complex {
        (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
    }

    /// The amplification of the stages on `y' = lambda y`, `z = lambda dt`.
    fn amplification(z: Complex) -> Complex {
        let (mut y, mut previous) = ((1.0, 0.0), (0.0, 0.0));
        for stage in RK3_STAGES {
            let now = mul(z, y);
            let step = (
                stage.gamma * now.0 + stage.zeta * previous.0,
                stage.gamma * now.1 + stage.zeta * previous.1,
            );
            y = (y.0 + step.0, y.1 + step.1);
            previous = now;
        }
        y
    }

    /// The stages are third order: their amplification is the cubic Taylor polynomial of
    /// `e^z`; and the weights of the pressure sum to 1.
    #[test]
    fn the_stages_are_third_order() {
        for z in [(-0.3, 0.2), (0.1, -1.1), (-2.0, 0.5), (0.7, 0.0)] {
            let z2 = mul(z, z);
            let z3 = mul(z2, z);
            let taylor = (
                1.0 + z.0 + z2.0 / 2.0 + z3.0 / 6.0,
                z.1 + z2.1 / 2.0 + z3.1 / 6.0,
            );
            let a = amplification(z);
            assert!((a.0 - taylor.0).abs() < 1e-14 && (a.1 - taylor.1).abs() < 1e-14);
        }
        let sum: Real = RK3_STAGES.iter().map(|s| s.pressure).sum();
        assert!((sum - 1.0).abs() < 1e-15);
        for s in RK3_STAGES {
            assert!((s.pressure - (s.gamma + s.zeta)).abs() < 1e-15);
        }
    }

    /// Over the whole spectrum of the 2D central advection-diffusion operator (Fourier modes
    /// `xi` of both directions) at any diffusion number up to the explicit limit and Courant
    /// numbers up to [`RK3_LARGEST_CFL`], no mode grows; at a Courant number of 0.88 with no
    /// viscosity one does (the bound is not loose by much).
    #[test]
    fn the_largest_courant_number_keeps_every_mode_bounded() {
        let worst = |diffusion: Real, cfl: Real| {
            let n = 240;
            let mut worst: Real = 0.0;
            for i in 0..=n {
                for j in 0..=n {
                    let (x, y) = (
                        std::f64::consts::TAU * i as Real / n as Real,
                        std::f64::consts::TAU * j as Real / n as Real,
                    );
                    let a = 0.5 * diffusion * ((1.0 - x.cos()) + (1.0 - y.cos()));
                    let b = cfl * (x.sin() + y.sin());
                    let r = amplification((-a, -b));
                    worst = worst.max((r.0 * r.0 + r.1 * r.1).sqrt());
                }
            }
            worst
        };
        for diffusion in [0.0, 0.01, 0.2, 0.5, 0.8, 1.0] {
            let w = worst(diffusion, RK3_LARGEST_CFL);
            assert!(w <= 1.0 + 1e-12, "diffusion {diffusion}: {w}");
        }
        assert!(worst(0.0, 0.88) > 1.01);
    }
}
