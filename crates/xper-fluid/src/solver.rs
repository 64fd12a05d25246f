//! One fluid time step as a sequence of named stages (Basilisk style): boundary values,
//! momentum predictor, immersed forcing, projection, grain forces.

use crate::blocks::{BlockLinks, WholeGrid};
use crate::boundary::FluidBoundary;
use crate::grid::MacGrid;
use crate::immersed::{HydrodynamicForce, ImmersedDisk, ImmersedForcing, InnerMomentum};
use crate::markers::MarkerForcing;
use crate::momentum::{predict, predict_stage, PredictorCoefficients, RK3_LARGEST_CFL, RK3_STAGES};
use crate::projection::{exchange_velocity_and_pressure, Projection, ProjectionInfo};
use serde::{Deserialize, Serialize};
use std::time::Instant;
use xper_math::{Real, Vector, DIM};
use xper_poisson::{Multigrid, MultigridError, MultigridInfo};

pub use crate::params::{pressure_multigrid, FluidParams, Forcing, TimeScheme};

/// The evolving fluid: velocities, pressure, time. Serialisable for checkpoints.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FluidState {
    /// The grid.
    pub grid: MacGrid,
    /// Velocity components on their faces (padded layout, m/s).
    pub velocity: [Vec<Real>; DIM],
    /// Pressure at cell centres (padded layout, Pa).
    pub pressure: Vec<Real>,
    /// Last pressure increment (unpadded), the warm start of the next solve.
    pub increment: Vec<Real>,
    /// Time (s).
    pub time: Real,
    /// Steps done.
    pub step: u64,
    /// Fluid momentum inside each grain at the end of the last step.
    pub inner: Vec<InnerMomentum>,
}

impl FluidState {
    /// Fluid at rest on `grid`, boundary values set.
    pub fn at_rest(grid: MacGrid, boundary: &FluidBoundary) -> Self {
        let mut state = FluidState {
            grid,
            velocity: grid.zero_velocity(),
            pressure: grid.zeros(),
            increment: vec![0.0; grid.num_cells()],
            time: 0.0,
            step: 0,
            inner: Vec::new(),
        };
        boundary.fill_velocity(&grid, &mut state.velocity);
        state
    }

    /// Sets every face velocity from `field(component, position)`, then the boundary values.
    pub fn set_velocity(
        &mut self,
        boundary: &FluidBoundary,
        mut field: impl FnMut(usize, Vector) -> Real,
    ) {
        let grid = self.grid;
        for d in 0..DIM {
            for j in -1..=grid.ny as isize + 1 {
                for i in -1..=grid.nx as isize + 1 {
                    self.velocity[d][grid.index(i, j)] = field(d, grid.face_position(d, i, j));
                }
            }
        }
        boundary.fill_velocity(&grid, &mut self.velocity);
    }

    /// Velocity interpolated at the centre of cell `(i, j)`.
    pub fn cell_velocity(&self, i: usize, j: usize) -> Vector {
        let k = self.grid.index(i as isize, j as isize);
        let mut v = Vector::zeros();
        for d in 0..DIM {
            v[d] = 0.5 * (self.velocity[d][k] + self.velocity[d][k + self.grid.stride(d)]);
        }
        v
    }

    /// Vorticity `dv/dx - du/dy` at the centre of cell `(i, j)`, the mean of its four corners.
    pub fn cell_vorticity(&self, i: usize, j: usize) -> Real {
        let g = &self.grid;
        let (u, v) = (&self.velocity[0], &self.velocity[1]);
        let corner = |i: isize, j: isize| {
            let k = g.index(i, j);
            ((v[k] - v[k - 1]) - (u[k] - u[k - g.width()])) / g.h
        };
        let (i, j) = (i as isize, j as isize);
        0.25 * (corner(i, j) + corner(i + 1, j) + corner(i, j + 1) + corner(i + 1, j + 1))
    }

    /// Pressure of cell `(i, j)` (Pa).
    pub fn cell_pressure(&self, i: usize, j: usize) -> Real {
        self.pressure[self.grid.index(i as isize, j as isize)]
    }

    /// Kinetic energy of the fluid, `rho/2 sum u^2 h^2` over the low faces of every cell
    /// (J per m of thickness).
    pub fn kinetic_energy(&self, density: Real) -> Real {
        let g = &self.grid;
        let mut sum = 0.0;
        for ud in &self.velocity {
            for j in 0..g.ny as isize {
                for i in 0..g.nx as isize {
                    sum += ud[g.index(i, j)].powi(2);
                }
            }
        }
        0.5 * density * sum * g.h * g.h
    }

    /// Largest speed component on any face (m/s).
    pub fn max_speed(&self) -> Real {
        self.velocity
            .iter()
            .flatten()
            .fold(0.0, |m: Real, &x| m.max(x.abs()))
    }
}

/// What one fluid step did.
#[derive(Clone, Debug, Default)]
pub struct FluidStepReport {
    /// Time step used (s).
    pub dt: Real,
    /// Time at the end of the step (s).
    pub time: Real,
    /// The pressure solve.
    pub pressure: MultigridInfo,
    /// Norm of the divergence before and after the projection (1/s).
    pub divergence: [Real; 2],
    /// Largest velocity component after the step (m/s).
    pub max_speed: Real,
    /// Kinetic energy of the fluid after the step ([`FluidState::kinetic_energy`], J/m).
    pub kinetic_energy: Real,
    /// Force and torque of the fluid on each grain.
    pub forces: Vec<HydrodynamicForce>,
    /// Wall time of the stages: predictor, forcing, projection, total (s).
    pub times: [f64; 4],
}

/// A fluid step that failed.
#[derive(Clone, Debug, PartialEq)]
pub enum FluidError {
    /// Parameters or grid refused.
    Setup(String),
    /// The pressure solve failed.
    Pressure(MultigridError),
    /// The velocity became NaN or infinite.
    NonFinite {
        /// Step that produced it.
        step: u64,
    },
}

impl std::fmt::Display for FluidError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FluidError::Setup(m) => write!(f, "fluid set-up: {m}"),
            FluidError::Pressure(e) => write!(f, "pressure solve: {e}"),
            FluidError::NonFinite { step } => {
                write!(
                    f,
                    "the fluid velocity became non-finite at step {step} (time step too large?)"
                )
            }
        }
    }
}

impl std::error::Error for FluidError {}

/// The fluid stepper and its workspaces.
pub struct FluidSolver {
    grid: MacGrid,
    /// The serial pressure solver of a solver built for the whole grid.
    whole: Option<WholeGrid>,
    projection: Projection,
    forcing: ImmersedForcing,
    markers: MarkerForcing,
    predicted: [Vec<Real>; DIM],
    /// The last Runge-Kutta stage's tendency (empty with Euler).
    tendency: [Vec<Real>; DIM],
    inner: Vec<InnerMomentum>,
    /// The forces of the Runge-Kutta stages so far, weighted by their lengths.
    stage_forces: Vec<HydrodynamicForce>,
    /// The step count of the state this solver's last step left, its halos exchanged after
    /// its last change: the next step of that state needs no exchange before it starts.
    halos_current_at: Option<u64>,
}

impl FluidSolver {
    /// A solver for the whole `grid` (checks the parameters, builds the multigrid hierarchy).
    pub fn new(grid: MacGrid, params: &FluidParams) -> Result<Self, FluidError> {
        let mut solver = Self::new_block(grid, params)?;
        let (shape, boundary, multigrid_params) = pressure_multigrid(&grid, params);
        let multigrid = Multigrid::new(shape, boundary, multigrid_params)
            .map_err(|e| FluidError::Setup(e.to_string()))?;
        solver.whole = Some(WholeGrid { multigrid });
        Ok(solver)
    }

    /// A solver for one block of a split grid (`grid` the block's rows, `params` with the
    /// block's sides, [`FluidBoundary::block`]), stepped by [`FluidSolver::step_with`].
    pub fn new_block(grid: MacGrid, params: &FluidParams) -> Result<Self, FluidError> {
        params.validate().map_err(FluidError::Setup)?;
        if grid.nx < 2 || grid.ny < 2 || grid.h.is_nan() || grid.h <= 0.0 {
            return Err(FluidError::Setup(format!(
                "the grid needs at least 2 x 2 cells of positive size, got {} x {} of {}",
                grid.nx, grid.ny, grid.h
            )));
        }
        Ok(FluidSolver {
            grid,
            whole: None,
            projection: Projection::new(&grid),
            forcing: ImmersedForcing::default(),
            markers: MarkerForcing::default(),
            predicted: grid.zero_velocity(),
            tendency: match params.time_scheme {
                TimeScheme::Euler => [Vec::new(), Vec::new()],
                TimeScheme::Rk3 => grid.zero_velocity(),
            },
            inner: Vec::new(),
            stage_forces: Vec::new(),
            halos_current_at: None,
        })
    }

    /// The largest stable time step for the current velocities and grains moving at up to
    /// `grain_speed` (m/s).
    pub fn stable_dt(&self, params: &FluidParams, state: &FluidState, grain_speed: Real) -> Real {
        self.stable_dt_for(params, state.max_speed().max(grain_speed))
    }

    /// The largest stable time step for velocities up to `speed` (m/s).
    pub fn stable_dt_for(&self, params: &FluidParams, speed: Real) -> Real {
        let h = self.grid.h;
        let nu = params.kinematic_viscosity();
        let mut dt = params
            .dt_max
            .min(params.viscous_safety * h * h / (2.0 * DIM as Real * nu));
        if speed > 0.0 {
            let cfl = match params.time_scheme {
                TimeScheme::Euler => params.cfl,
                TimeScheme::Rk3 => params.cfl.min(RK3_LARGEST_CFL),
            };
            dt = dt.min(cfl * h / speed);
            if params.upwinding < 1.0 && params.time_scheme == TimeScheme::Euler {
                dt = dt.min(params.viscous_safety * 2.0 * nu / (DIM as Real * speed * speed));
            }
        }
        dt
    }

    /// Advances the fluid by `dt` with the grains `disks` held at their current state.
    pub fn step(
        &mut self,
        params: &FluidParams,
        state: &mut FluidState,
        dt: Real,
        disks: &[ImmersedDisk],
    ) -> Result<FluidStepReport, FluidError> {
        let mut whole = self.whole.take().ok_or_else(|| {
            FluidError::Setup("a block of a split grid is stepped by step_with".into())
        })?;
        let report = self.step_with(params, state, dt, disks, &mut whole);
        self.whole = Some(whole);
        report
    }

    /// Makes the next [`FluidSolver::step_with`] exchange the halos before it starts (after
    /// the caller changed the fields of the state that the last step left).
    pub fn fields_changed(&mut self) {
        self.halos_current_at = None;
    }

    /// [`FluidSolver::step`] on a block of a split grid, or on the whole grid with
    /// [`WholeGrid`]: the halos, sums and pressure solve go through `links`. The forces and
    /// the fluid momentum inside the grains (`state.inner`) are the whole grid's.
    ///
    /// A step ends with the halos of the velocity and pressure exchanged; the next step of the
    /// state it left (the same step count) starts from them without exchanging again. A caller
    /// that changes a block's fields between steps calls [`FluidSolver::fields_changed`].
    pub fn step_with(
        &mut self,
        params: &FluidParams,
        state: &mut FluidState,
        dt: Real,
        disks: &[ImmersedDisk],
        links: &mut dyn BlockLinks,
    ) -> Result<FluidStepReport, FluidError> {
        let start = Instant::now();
        let grid = self.grid;
        let boundary = &params.boundary;
        let mut report = FluidStepReport {
            dt,
            ..Default::default()
        };

        // Stage: boundary values and the grains' footprint.
        boundary.fill_velocity(&grid, &mut state.velocity);
        boundary.fill_pressure(&grid, &mut state.pressure);
        if self.halos_current_at.take() != Some(state.step) {
            exchange_velocity_and_pressure(links, &grid, &mut state.velocity, &mut state.pressure);
        }
        self.forcing.mark(&grid, boundary, disks, params.indicator);
        if let Forcing::Markers(markers) = &params.forcing {
            self.markers
                .place(&grid, boundary, disks, markers.retraction);
        }
        if state.inner.len() != disks.len() {
            self.forcing.inner_momentum(
                &grid,
                disks,
                params.density,
                &state.velocity,
                &mut state.inner,
            );
            let mut sums = pack(&[], &state.inner);
            links.sum(&mut sums);
            unpack(&sums, &mut [], &mut state.inner);
        }

        // Stages: momentum predictor, immersed forcing, projection (once, or per
        // Runge-Kutta stage).
        let coefficients = PredictorCoefficients {
            dt,
            kinematic_viscosity: params.kinematic_viscosity(),
            density: params.density,
            body_force: params.body_force,
            upwinding: params.upwinding,
        };
        let info = match params.time_scheme {
            TimeScheme::Euler => {
                predict(
                    &grid,
                    boundary,
                    &coefficients,
                    &state.velocity,
                    &state.pressure,
                    &mut self.predicted,
                );
                report.times[0] = start.elapsed().as_secs_f64();
                self.force_and_project(params, state, dt, dt, true, disks, links, &mut report)?
            }
            TimeScheme::Rk3 => {
                let mut info: Option<ProjectionInfo> = None;
                // The marker forcing acts at every stage over the stage's length (Uhlmann
                // 2005), the fraction forcing once, before the last stage's projection
                // ([`TimeScheme::Rk3`]).
                let every_stage = matches!(params.forcing, Forcing::Markers(_));
                report.times[0] = start.elapsed().as_secs_f64();
                for (k, stage) in RK3_STAGES.into_iter().enumerate() {
                    let t_stage = Instant::now();
                    predict_stage(
                        &grid,
                        boundary,
                        &coefficients,
                        stage,
                        &state.velocity,
                        &state.pressure,
                        &mut self.tendency,
                        &mut self.predicted,
                    );
                    report.times[0] += t_stage.elapsed().as_secs_f64();
                    let last = k + 1 == RK3_STAGES.len();
                    let now = self.force_and_project(
                        params,
                        state,
                        if every_stage { stage.pressure * dt } else { dt },
                        stage.pressure * dt,
                        every_stage || last,
                        disks,
                        links,
                        &mut report,
                    )?;
                    if every_stage {
                        // The step's force is the stages' forces weighted by their lengths.
                        if k == 0 {
                            self.stage_forces.clear();
                            self.stage_forces.resize(disks.len(), Default::default());
                        }
                        for (sum, f) in self.stage_forces.iter_mut().zip(&report.forces) {
                            sum.force += f.force * stage.pressure;
                            sum.torque += f.torque * stage.pressure;
                        }
                        if last {
                            report.forces.clone_from(&self.stage_forces);
                        }
                    }
                    info = Some(match info {
                        None => now,
                        Some(first) => ProjectionInfo {
                            solve: MultigridInfo {
                                cycles: first.solve.cycles + now.solve.cycles,
                                work_units: first.solve.work_units + now.solve.work_units,
                                ..now.solve
                            },
                            divergence_squares: [
                                first.divergence_squares[0],
                                now.divergence_squares[1],
                            ],
                        },
                    });
                }
                info.expect("three stages")
            }
        };

        // Stage: grain forces, with the change of the fluid momentum inside each grain.
        self.forcing.inner_momentum(
            &grid,
            disks,
            params.density,
            &state.velocity,
            &mut self.inner,
        );

        // Stage: the sums over the blocks (divergence norms, forces and inner momenta, kinetic
        // energy) and the largest speed, in one reduction.
        let mut sums = pack(&report.forces, &self.inner);
        sums.extend_from_slice(&info.divergence_squares);
        sums.push(state.kinetic_energy(params.density));
        let mut figures = [state.max_speed()];
        links.sum_and_max(&mut sums, &mut figures);
        let n = sums.len();
        let (divergence_before, divergence_after, kinetic_energy) =
            (sums[n - 3], sums[n - 2], sums[n - 1]);
        unpack(&sums, &mut report.forces, &mut self.inner);
        for ((force, new), old) in report.forces.iter_mut().zip(&self.inner).zip(&state.inner) {
            force.force += (new.linear - old.linear) / dt;
            force.torque += (new.angular - old.angular) / dt;
        }
        std::mem::swap(&mut state.inner, &mut self.inner);

        state.time += dt;
        state.step += 1;
        self.halos_current_at = Some(state.step);
        report.time = state.time;
        report.pressure = info.solve;
        report.divergence = [divergence_before.sqrt(), divergence_after.sqrt()];
        report.max_speed = figures[0];
        report.kinetic_energy = kinetic_energy;
        if !report.max_speed.is_finite() {
            return Err(FluidError::NonFinite { step: state.step });
        }
        report.times[3] = start.elapsed().as_secs_f64();
        Ok(report)
    }

    /// The stages after a predictor wrote `self.predicted`: the outflow values, the direct
    /// forcing over `dt` when `force` (its integrals into `report.forces`), the halos, and the
    /// projection over `dt_projection`, which leaves the new velocity in `state.velocity`.
    #[allow(clippy::too_many_arguments)]
    fn force_and_project(
        &mut self,
        params: &FluidParams,
        state: &mut FluidState,
        dt: Real,
        dt_projection: Real,
        force: bool,
        disks: &[ImmersedDisk],
        links: &mut dyn BlockLinks,
        report: &mut FluidStepReport,
    ) -> Result<ProjectionInfo, FluidError> {
        let grid = self.grid;
        let boundary = &params.boundary;
        boundary.extrapolate_outflow(&grid, &mut self.predicted);
        let t_forcing = Instant::now();
        match (force, &params.forcing) {
            (false, _) => {}
            (true, Forcing::Fraction) => self.forcing.apply(
                &grid,
                disks,
                params.density,
                dt,
                &mut self.predicted,
                &mut report.forces,
            ),
            (true, Forcing::Markers(markers)) => self.markers.apply(
                &grid,
                disks,
                markers.iterations,
                params.density,
                dt,
                &mut self.predicted,
                &mut report.forces,
                links,
            ),
        }
        let [u0, u1] = &mut self.predicted;
        links.exchange_halo(&grid, &mut [u0.as_mut_slice(), u1.as_mut_slice()]);
        report.times[1] += t_forcing.elapsed().as_secs_f64();
        let t_projection = Instant::now();
        let info = self
            .projection
            .project(
                links,
                &grid,
                boundary,
                dt_projection,
                params.density,
                &mut self.predicted,
                &mut state.pressure,
                &mut state.increment,
            )
            .map_err(FluidError::Pressure)?;
        std::mem::swap(&mut state.velocity, &mut self.predicted);
        report.times[2] += t_projection.elapsed().as_secs_f64();
        Ok(info)
    }
}

/// The forces (force, torque) then the inner momenta (linear, angular) as one array, for one
/// reduction over the blocks.
fn pack(forces: &[HydrodynamicForce], inner: &[InnerMomentum]) -> Vec<Real> {
    let mut out = Vec::with_capacity(3 * (forces.len() + inner.len()));
    for f in forces {
        out.extend([f.force.x, f.force.y, f.torque]);
    }
    for m in inner {
        out.extend([m.linear.x, m.linear.y, m.angular]);
    }
    out
}

/// The inverse of [`pack`].
fn unpack(values: &[Real], forces: &mut [HydrodynamicForce], inner: &mut [InnerMomentum]) {
    let (f, m) = values.split_at(3 * forces.len());
    for (force, v) in forces.iter_mut().zip(f.chunks_exact(3)) {
        force.force = Vector::new(v[0], v[1]);
        force.torque = v[2];
    }
    for (momentum, v) in inner.iter_mut().zip(m.chunks_exact(3)) {
        momentum.linear = Vector::new(v[0], v[1]);
        momentum.angular = v[2];
    }
}
