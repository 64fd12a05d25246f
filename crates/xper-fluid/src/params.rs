//! The fluid's physical and numerical parameters, and those of its pressure multigrid.

use crate::boundary::FluidBoundary;
use crate::grid::MacGrid;
use crate::immersed::SolidIndicator;
use serde::{Deserialize, Serialize};
use xper_math::{Real, Vector};
use xper_poisson::{GridShape, MultigridParams};

/// The parameters of the pressure multigrid of `params` over the whole `grid`.
pub fn pressure_multigrid(
    grid: &MacGrid,
    params: &FluidParams,
) -> (GridShape, xper_poisson::Boundary, MultigridParams) {
    let shape = GridShape {
        nx: grid.nx,
        ny: grid.ny,
        hx: grid.h,
        hy: grid.h,
    };
    let multigrid_params = MultigridParams {
        relative_tolerance: params.pressure_tolerance,
        max_cycles: params.pressure_max_cycles,
        ..MultigridParams::default()
    };
    (shape, params.boundary.pressure_boundary(), multigrid_params)
}

/// Physical and numerical parameters of the fluid (SI units).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FluidParams {
    /// Density rho_f (kg/m^3).
    pub density: Real,
    /// Dynamic viscosity mu (Pa s).
    pub viscosity: Real,
    /// Body force per unit mass on the fluid (m/s^2); gravity on grains is buoyancy-corrected by
    /// the coupling instead, so this is usually zero.
    pub body_force: Vector,
    /// Conditions on the four sides.
    pub boundary: FluidBoundary,
    /// Courant number of the adaptive time step: `dt <= cfl h / max |u|`.
    pub cfl: Real,
    /// Fraction of the explicit diffusion limit `h^2 / (2 DIM nu)` (and, for the central scheme,
    /// of the advection-diffusion limit `2 nu / max |u|^2`) allowed as time step.
    pub viscous_safety: Real,
    /// Largest time step (s).
    pub dt_max: Real,
    /// Donor-cell blending of the advection, 0 (central, second order) to 1 (donor cell).
    pub upwinding: Real,
    /// Solid fraction of the faces near grains.
    pub indicator: SolidIndicator,
    /// Relative residual of the pressure solve, `||r|| / ||rhs||`.
    pub pressure_tolerance: Real,
    /// Largest number of multigrid cycles per pressure solve.
    pub pressure_max_cycles: u32,
    /// Time integration of the momentum equation.
    #[serde(default)]
    pub time_scheme: TimeScheme,
    /// The lubrication correction between grains (and with the domain's walls) closer than
    /// the grid resolves; none by default.
    #[serde(default)]
    pub lubrication: Option<crate::Lubrication>,
    /// How the grains' rigid velocities are imposed on the fluid.
    #[serde(default)]
    pub forcing: Forcing,
}

/// How the direct forcing imposes the grains' rigid velocities on the fluid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Forcing {
    /// Every face near or inside a grain is pulled towards the rigid velocity in proportion
    /// to its solid fraction ([`crate::immersed`], [`FluidParams::indicator`]): the paper's.
    Fraction,
    /// Lagrangian markers on the grains' surfaces with a regularised delta, repeated
    /// (multi-direct forcing, [`crate::markers`]); the default, with its default parameters.
    Markers(crate::markers::MarkerForcingParams),
}

/// The marker forcing with two passes and markers 0.3 cells inside the surface: as cheap as the
/// fraction forcing (no slower on the two-grain scene, BENCHMARKS.md) and closer to every
/// published run measured (VALIDATION.md: the single disk within 0.2 % of Koblitz et al.
/// where the fraction forcing is 2.2 % fast on 16 cells per diameter; the Schaefer-Turek drag
/// 1.1 % from the benchmark on 20 cells per diameter where the fraction forcing is 3.1 %).
impl Default for Forcing {
    fn default() -> Self {
        Forcing::Markers(crate::markers::MarkerForcingParams::default())
    }
}

/// The time integration of the momentum equation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeScheme {
    /// Explicit Euler and one projection per step: first order (the paper's).
    #[default]
    Euler,
    /// Wray's three-stage Runge-Kutta with a projection after each stage
    /// ([`crate::momentum::RK3_STAGES`]): second order in the velocity (third on the
    /// Taylor-Green vortex), three predictor and pressure solves per step; its stability region
    /// holds the central advection's imaginary eigenvalues, so the step is not limited by
    /// `2 nu / |u|^2` as Euler's is (its Courant number is capped at
    /// [`crate::momentum::RK3_LARGEST_CFL`], 0.866, where the central advection stays stable
    /// without viscosity). The grains are held at their state at the start of the step. The
    /// fraction forcing acts once, before the last stage's projection: forced before every
    /// stage (over the stage's length, the forces weighted by it), the settling disks of the
    /// validation cases (density ratios 1.25 and 1.5) blew up within the first steps. The
    /// marker forcing acts before every stage over its length, as in Uhlmann 2005, and the
    /// step's force on a grain is the stages' forces weighted by their lengths: forced only
    /// before the last stage, the fluid at the markers was free during the first two, and
    /// Uhlmann's two disks drafted too slowly and never tumbled (VALIDATION.md).
    Rk3,
}

impl FluidParams {
    /// Defaults: central advection, CFL 0.5, explicit Euler, the marker forcing, no lubrication
    /// correction.
    pub fn new(density: Real, viscosity: Real, boundary: FluidBoundary) -> Self {
        FluidParams {
            density,
            viscosity,
            body_force: Vector::zeros(),
            boundary,
            cfl: 0.5,
            viscous_safety: 0.8,
            dt_max: Real::INFINITY,
            upwinding: 0.0,
            indicator: SolidIndicator::default(),
            pressure_tolerance: 1e-8,
            pressure_max_cycles: 50,
            time_scheme: TimeScheme::Euler,
            lubrication: None,
            forcing: Forcing::default(),
        }
    }

    /// Kinematic viscosity nu = mu / rho (m^2/s).
    pub fn kinematic_viscosity(&self) -> Real {
        self.viscosity / self.density
    }

    /// Checks signs and ranges.
    pub fn validate(&self) -> Result<(), String> {
        let positive = [
            ("density", self.density),
            ("viscosity", self.viscosity),
            ("cfl", self.cfl),
            ("viscous_safety", self.viscous_safety),
            ("dt_max", self.dt_max),
            ("pressure_tolerance", self.pressure_tolerance),
        ];
        for (name, value) in positive {
            if value.is_nan() || value <= 0.0 {
                return Err(format!("{name} must be positive, got {value}"));
            }
        }
        if let Some(l) = &self.lubrication {
            if !(l.range > 0.0 && l.range.is_finite() && l.roughness > 0.0 && l.roughness < 1.0) {
                return Err(format!(
                    "lubrication range must be positive and roughness in (0, 1), got {} and {}",
                    l.range, l.roughness
                ));
            }
        }
        if let Forcing::Markers(m) = &self.forcing {
            if !(1..=100).contains(&m.iterations) || !(0.0..=0.5).contains(&m.retraction) {
                return Err(format!(
                    "marker forcing needs 1 to 100 iterations and a retraction in [0, 1/2] \
                     cells, got {} and {}",
                    m.iterations, m.retraction
                ));
            }
        }
        if !(0.0..=1.0).contains(&self.upwinding) {
            return Err(format!(
                "upwinding must be in [0, 1], got {}",
                self.upwinding
            ));
        }
        if self.cfl > 1.0 || self.viscous_safety > 1.0 {
            return Err("cfl and viscous_safety must be at most 1 (explicit stability)".into());
        }
        self.boundary.validate()
    }
}
