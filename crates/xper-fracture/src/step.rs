//! One time step of non-smooth fracture dynamics (NSFD): Moreau-Jean's theta-method on
//! deformable elements joined by frictional cohesive interfaces.
//!
//! For each element (BRIEF.md section 2; M. Jean, CMAME 177, 1999):
//! `M_eff (v - v_i) = h (F_ext - F_int(q_i)) - h^2 theta K v_i + H R + P`,
//! `M_eff = M + h^2 theta^2 K`, `q_i+1 = q_i + h ((1 - theta) v_i + theta v)`,
//! with `P` the reactions on imposed degrees of freedom. For each interface point the impulse
//! is `R = R_c + R_coh`: `R_c` obeys Signorini-Coulomb and the adhesive part is the theta-
//! average of the cohesive force over the step with the intensity beta frozen,
//! `R_coh = -h A beta C ((1 - theta) [u]_i + theta [u]_i+1)` (A = half the edge length times
//! the thickness), eliminated exactly in each local solve ([`xper_solver::CohesiveTerm`]);
//! beta is updated once per step from the new jump (F. Perales, S. Bourgeois,
//! A. Chrysochoos, Y. Monerie, Eng. Fract. Mech. 75, 2008).
//!
//! Stages: `free_velocity`, `assemble` (rows, shifts, adhesive terms), `solve` (NLGS),
//! `update` (velocities, displacements, materials, reactions), `interfaces` (jumps,
//! intensities, energies).

use std::time::Instant;

use xper_bodies::Drive;
use xper_solver::{CohesiveTerm, SolveError};

use crate::cell::{CellState, MacroDrive, SHEAR_WEIGHT};
use crate::dense::{masked_spd_inverse, mul_vec, Mat6};
use crate::interface::cohesive;
use crate::model::{FractureEnergy, FractureModel, PlasticStiffness};
use crate::operator::{CellWork, ElementContactOperator, ElementWork, InterfaceRow};
use xper_solver::ContactSolve;
use xper_solver::OneProcessSolve;

/// Reading of one load over a step.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LoadReading {
    /// Force exerted on the specimen through the load's nodes (N), x and y: the reaction of
    /// imposed velocities, or the imposed force.
    pub force: [f64; 2],
    /// Mean displacement of the load's nodes (m).
    pub displacement: [f64; 2],
}

/// What a step did.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct FractureStepReport {
    /// Step number (1-based).
    pub step: u64,
    /// Time at the end of the step (s).
    pub time: f64,
    /// Contact points in the problem.
    pub contacts: usize,
    /// Broken interface points (intensity 0).
    pub broken_points: usize,
    /// Fully broken interfaces ([`FractureModel::is_broken`]).
    pub broken_interfaces: usize,
    /// The energy budget at the end of the step (of the whole model in a distributed run).
    pub energy: FractureEnergy,
    /// NLGS sweeps.
    pub iterations: u32,
    /// Final residual of the convergence norm.
    pub residual: f64,
    /// Whether NLGS converged.
    pub converged: bool,
    /// One reading per load.
    pub loads: Vec<LoadReading>,
    /// Wall time of the step and of its solve (s).
    pub wall_time: f64,
    /// Wall time of the solve (s).
    pub solve_time: f64,
    /// The macroscopic state of a periodic cell at the end of the step (`None` otherwise).
    pub cell: Option<CellState>,
    /// Points of cohesive interfaces that have lost adhesion (counted for periodic cells
    /// only, 0 otherwise), and all points of cohesive interfaces.
    pub damaged_points: [usize; 2],
}

/// Why a step failed.
#[derive(Clone, Debug, PartialEq)]
pub enum FractureStepError {
    /// The effective mass of an element is not positive definite.
    SingularElement(usize),
    /// The solver refused the problem.
    Solver(SolveError),
    /// A non-finite velocity or displacement appeared.
    NonFinite {
        /// The element.
        element: usize,
    },
    /// The energy budget blew up ([`crate::FractureEnergy::divergence`]); the model holds the
    /// diverged state.
    Diverging(String),
}

impl std::fmt::Display for FractureStepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FractureStepError::SingularElement(e) => {
                write!(f, "element {e}: effective mass not positive definite")
            }
            FractureStepError::Solver(e) => write!(f, "interface solver: {e}"),
            FractureStepError::NonFinite { element } => {
                write!(f, "element {element}: non-finite velocity (blow-up)")
            }
            FractureStepError::Diverging(why) => f.write_str(why),
        }
    }
}

impl std::error::Error for FractureStepError {}

/// The stepper with its working buffers.
#[derive(Debug, Default)]
pub struct FractureStepper {
    op: ElementContactOperator,
    inv_mass_valid: Vec<bool>,
    rhs: Vec<[f64; 6]>,
    v_begin: Vec<[f64; 6]>,
    mu: Vec<f64>,
    shift: Vec<f64>,
    cohesion: Vec<CohesiveTerm>,
    impulses: Vec<[f64; 2]>,
    points: Vec<PointWork>,
    /// The strain rate at the start of the step (the step's increment over h for an
    /// imposed component).
    cell_begin: [f64; 3],
    /// The masses of the cell's strain components (computed once: they do not change).
    cell_mass: Option<[f64; 3]>,
    started: bool,
}

impl FractureStepper {
    /// A stepper with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Advances the model by one step.
    pub fn step(&mut self, m: &mut FractureModel) -> Result<FractureStepReport, FractureStepError> {
        self.step_with(m, &mut OneProcessSolve)
    }

    /// Advances the model by one step, the interface problem solved and the step's totals
    /// summed by `solver`: [`OneProcessSolve`] for a whole model, a domain-decomposition
    /// solver for a part of one ([`FractureModel::part`]), whose report then holds the totals
    /// of the whole model.
    pub fn step_with(
        &mut self,
        m: &mut FractureModel,
        solver: &mut dyn ContactSolve<ElementContactOperator>,
    ) -> Result<FractureStepReport, FractureStepError> {
        let start = Instant::now();
        if m.step == 0 && !self.started {
            m.energy.initial = m.kinetic_energy() + elastic_energy(m) + stored_energy(m);
        }
        self.started = true;
        self.prepare(m);
        let (t_begin, t_end) = (m.time, m.time + m.spec.dt);
        let ext = self.free_velocity(m, t_begin, t_end)?;
        self.free_cell(m, t_begin, t_end);
        self.assemble(m);
        let t_solve = Instant::now();
        let info = solver
            .solve(
                &mut self.op,
                &self.mu,
                &self.shift,
                &self.cohesion,
                &mut self.impulses,
                &m.spec.nlgs,
            )
            .map_err(FractureStepError::Solver)?;
        let solve_time = t_solve.elapsed().as_secs_f64();
        let load_sums = self.update(m, ext)?;
        crate::update::interfaces(self, m);
        let cell_sums = crate::update::cell(self, m);
        m.step += 1;
        m.time = t_end;
        let totals =
            crate::update::StepTotals::sum(m, self.op.rows.len(), load_sums, cell_sums, solver);
        if let Some(cell) = &mut m.cell {
            totals.apply_to(cell);
        }
        if let Some(why) = totals.energy.divergence() {
            return Err(FractureStepError::Diverging(why));
        }
        Ok(FractureStepReport {
            step: m.step,
            time: m.time,
            contacts: totals.contacts,
            broken_points: totals.broken_points,
            broken_interfaces: totals.broken_interfaces,
            energy: totals.energy,
            iterations: info.iterations,
            residual: info.residual,
            converged: info.converged,
            loads: totals.loads,
            wall_time: start.elapsed().as_secs_f64(),
            solve_time,
            cell: m.cell,
            damaged_points: [totals.damaged_points, totals.cohesive_points],
        })
    }

    fn prepare(&mut self, m: &FractureModel) {
        let n = m.elements.len();
        if self.inv_mass_valid.len() != n {
            self.inv_mass_valid = vec![false; n];
            self.op.bodies = vec![ElementWork::default(); n];
        }
        self.rhs.resize(n, [0.0; 6]);
        self.v_begin.resize(n, [0.0; 6]);
    }

    /// Stage: `v_free = v_i + M_eff^-1 rhs` on free degrees of freedom, imposed velocities at
    /// `t_end`; returns the external forces at `t_theta` per element (N).
    fn free_velocity(
        &mut self,
        m: &FractureModel,
        t_begin: f64,
        t_end: f64,
    ) -> Result<Vec<[f64; 6]>, FractureStepError> {
        let (h, th) = (m.spec.dt, m.spec.theta);
        let t_theta = t_begin + th * h;
        let g = m.spec.gravity;
        let mut ext_all = Vec::with_capacity(m.elements.len());
        for (e, el) in m.elements.iter().enumerate() {
            let free: [bool; 6] = std::array::from_fn(|d| !m.is_imposed(e, d));
            let m_eff = m.effective_mass(e);
            if !self.inv_mass_valid[e] {
                self.op.bodies[e].inv_mass = masked_spd_inverse(&m_eff, free)
                    .ok_or(FractureStepError::SingularElement(e))?;
                self.inv_mass_valid[e] = true;
            }
            let mut ext = mul_vec(&el.mass, &[g[0], g[1], g[0], g[1], g[0], g[1]]);
            let mut dv = [0.0; 6];
            for d in 0..6 {
                let l = el.load[d];
                if l == u16::MAX {
                    continue;
                }
                let load = &m.spec.loads[l as usize];
                match &load.drives[d % 2] {
                    Drive::Velocity(f) => dv[d] = f.eval(t_end) - el.velocity[d],
                    Drive::Force(f) => ext[d] += f.eval(t_theta) * el.load_share[d / 2],
                    Drive::Free | Drive::Pressure(_) => {}
                }
            }
            let kv = mul_vec(&el.stiffness, &el.velocity);
            let mut rhs = [0.0; 6];
            for d in 0..6 {
                rhs[d] = h * (ext[d] - el.internal_force[d]) - h * h * th * kv[d];
            }
            let mut r = rhs;
            let coupling = mul_vec(&m_eff, &dv);
            for d in 0..6 {
                r[d] -= coupling[d];
            }
            let dv_free = mul_vec(&self.op.bodies[e].inv_mass, &r);
            let work = &mut self.op.bodies[e];
            for d in 0..6 {
                let step = if free[d] { dv_free[d] } else { dv[d] };
                work.velocity[d] = el.velocity[d] + step;
            }
            self.rhs[e] = rhs;
            self.v_begin[e] = el.velocity;
            ext_all.push(ext);
        }
        Ok(ext_all)
    }

    /// Stage: the strain rate of a periodic cell before the interfaces act: the increment of
    /// an imposed component over h; for a free one, the rate so far plus the impulse of the
    /// imposed stress, `h c_k V Sigma_k(t_theta) / M_k` ([`crate::cell`]).
    fn free_cell(&mut self, m: &FractureModel, t_begin: f64, t_end: f64) {
        self.op.cell = CellWork::default();
        let (Some(p), Some(state)) = (&m.spec.periodic, &m.cell) else {
            return;
        };
        let (h, th) = (m.spec.dt, m.spec.theta);
        let volume = p.cell.area() * m.spec.thickness;
        let mass = *self.cell_mass.get_or_insert_with(|| m.cell_mass());
        for (k, drive) in p.drives.iter().enumerate() {
            match drive {
                MacroDrive::Strain(f) => {
                    let rate = (f.eval(t_end) - f.eval(t_begin)) / h;
                    self.cell_begin[k] = rate;
                    self.op.cell.rate[k] = rate;
                }
                MacroDrive::Stress(f) => {
                    let sigma = f.eval(t_begin + th * h);
                    self.cell_begin[k] = state.rate[k];
                    self.op.cell.inv_mass[k] = 1.0 / mass[k];
                    self.op.cell.rate[k] =
                        state.rate[k] + h * SHEAR_WEIGHT[k] * volume * sigma / mass[k];
                }
            }
        }
    }

    /// Stage: one row per interface point, its normal shift (gap closure, LMGC90's IQS) and
    /// the adhesive term of cohesive points.
    fn assemble(&mut self, m: &FractureModel) {
        let (h, th) = (m.spec.dt, m.spec.theta);
        self.op.rows.clear();
        for v in [&mut self.mu, &mut self.shift] {
            v.clear();
        }
        self.cohesion.clear();
        self.impulses.clear();
        self.points.clear();
        let any_cohesive = m.laws.iter().any(|l| cohesive(l).is_some());
        for i in &m.interfaces {
            let law = &m.laws[i.law as usize];
            let area = 0.5 * i.length * m.spec.thickness;
            for (k, p) in i.points.iter().enumerate() {
                let row = self
                    .op
                    .row(i.elements, i.local_nodes[k], i.normal, i.period);
                let [a, b] = i.elements.map(|e| e as usize);
                let u0 = ElementContactOperator::local_velocity_of(
                    &row,
                    &self.v_begin[a],
                    &self.v_begin[b],
                    &self.cell_begin,
                );
                let g_tt = p.jump[0] + h * (1.0 - th) * u0[0];
                let shift = g_tt.max(0.0) / h;
                let (mut stiffness, mut offset) = ([0.0; 2], [0.0; 2]);
                if let Some(z) = cohesive(law).filter(|_| p.intensity > 0.0) {
                    let c = z.stiffness(p.intensity);
                    for d in 0..2 {
                        offset[d] = h * area * c[d] * (p.jump[d] + h * th * (1.0 - th) * u0[d]);
                        stiffness[d] = h * h * th * th * area * c[d];
                    }
                }
                let mut work = PointWork {
                    row,
                    u_begin: u0,
                    offset,
                    stiffness,
                    impulse: p.impulse,
                    solved: NOT_SOLVED,
                };
                if row.block[0] > 0.0 {
                    work.solved = self.op.rows.len() as u32;
                    self.op.rows.push(row);
                    self.mu.push(law.friction());
                    self.shift.push(shift);
                    if any_cohesive {
                        self.cohesion.push(CohesiveTerm {
                            stiffness,
                            offset: [offset[0] - stiffness[0] * shift, offset[1]],
                        });
                    }
                    self.impulses.push(p.impulse);
                } else {
                    // Both sides imposed: the motion is known, the impulse is the adhesive part.
                    let u = self.end_velocity(&row);
                    work.impulse = [
                        -(offset[0] + stiffness[0] * u[0]),
                        -(offset[1] + stiffness[1] * u[1]),
                    ];
                }
                self.points.push(work);
            }
        }
    }

    /// Local velocity of a row from the working (end-of-step) element velocities.
    pub(crate) fn end_velocity(&self, row: &InterfaceRow) -> [f64; 2] {
        let [a, b] = row.elements.map(|e| e as usize);
        ElementContactOperator::local_velocity_of(
            row,
            &self.op.bodies[a].velocity,
            &self.op.bodies[b].velocity,
            &self.op.cell.rate,
        )
    }

    /// The strain rate of a periodic cell at the start and at the end of the solved step
    /// (1/s).
    pub(crate) fn cell_rates(&self) -> ([f64; 3], [f64; 3]) {
        (self.cell_begin, self.op.cell.rate)
    }

    /// Stage: velocities and displacements, material update, reactions and work of the loads.
    /// Returns per load the sums of this model's share: force x and y, displacement x and y
    /// and the number of degrees of freedom summed, x and y. A shadow element adds only the
    /// impulses of this model's interfaces to a reaction; its owner adds the rest.
    fn update(
        &mut self,
        m: &mut FractureModel,
        ext: Vec<[f64; 6]>,
    ) -> Result<Vec<[f64; 6]>, FractureStepError> {
        let (h, th) = (m.spec.dt, m.spec.theta);
        // Generalised contact impulses per element.
        let mut contact = vec![[0.0; 6]; m.elements.len()];
        for point in &mut self.points {
            if point.solved != NOT_SOLVED {
                point.impulse = self.impulses[point.solved as usize];
            }
        }
        for point in &self.points {
            let row = &point.row;
            let p = ElementContactOperator::global_impulse(row, point.impulse);
            for (k, sign) in [(0usize, -1.0), (1, 1.0)] {
                let c = 2 * row.nodes[k] as usize;
                let g = &mut contact[row.elements[k] as usize];
                g[c] += sign * p[0];
                g[c + 1] += sign * p[1];
            }
        }
        let mut sums = vec![[0.0; 6]; m.spec.loads.len()];
        let (hypothesis, mut work, mut plastic) = (m.spec.hypothesis, 0.0, 0.0);
        for e in 0..m.elements.len() {
            let v = self.op.bodies[e].velocity;
            if v.iter().any(|x| !x.is_finite()) {
                return Err(FractureStepError::NonFinite { element: e });
            }
            let owned = if m.is_shadow(e) { 0.0 } else { 1.0 };
            let m_eff: Mat6 = m.effective_mass(e);
            let el = &mut m.elements[e];
            let v0 = el.velocity;
            let dv: [f64; 6] = std::array::from_fn(|d| v[d] - v0[d]);
            let inertia = mul_vec(&m_eff, &dv);
            for d in 0..6 {
                let du = h * ((1.0 - th) * v0[d] + th * v[d]);
                el.displacement[d] += du;
                let force_on_body = ext[e][d];
                let l = el.load[d];
                if l != u16::MAX {
                    let sum = &mut sums[l as usize];
                    if m.spec.loads[l as usize].drives[d % 2].is_imposed_velocity() {
                        let reaction = owned * (inertia[d] - self.rhs[e][d]) - contact[e][d];
                        sum[d % 2] += reaction / h;
                        work += reaction * du / h;
                    } else if let Drive::Force(_) = m.spec.loads[l as usize].drives[d % 2] {
                        let g = m.spec.gravity[d % 2];
                        let gravity: f64 = (0..6)
                            .filter(|k| k % 2 == d % 2)
                            .map(|k| el.mass[d][k] * g)
                            .sum();
                        sum[d % 2] += owned * (ext[e][d] - gravity);
                    }
                    sum[2 + d % 2] += owned * el.displacement[d];
                    sum[4 + d % 2] += owned;
                }
                work += owned * force_on_body * du;
            }
            el.velocity = v;
            let material = &m.spec.materials[el.region as usize];
            let strain = el.triangle.strain(&el.displacement);
            let up = material.update(hypothesis, &el.state, strain);
            el.state = up.state;
            el.internal_force = el.triangle.internal_force(&up.state.in_plane_stress());
            plastic += owned * up.plastic_work * el.triangle.volume();
            let tangent = m.spec.plastic_stiffness == PlasticStiffness::Tangent;
            if tangent && matches!(material, xper_fem::Material::J2Plastic { .. }) {
                el.stiffness = el.triangle.stiffness(&up.tangent);
                self.inv_mass_valid[e] = false;
            }
        }
        m.energy.external_work += work;
        m.energy.plastic += plastic;
        m.energy.kinetic = m.kinetic_energy();
        m.energy.elastic = elastic_energy(m);
        Ok(sums)
    }

    /// The step's interface points, in interface order (two per interface).
    pub(crate) fn points(&self) -> &[PointWork] {
        &self.points
    }
}

/// Everything the step knows about one interface point.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PointWork {
    /// Its row (frame, nodes, diagonal block).
    pub row: InterfaceRow,
    /// Local velocity at the start of the step.
    pub u_begin: [f64; 2],
    /// Adhesive offset `o` (impulse), without the normal shift.
    pub offset: [f64; 2],
    /// Adhesive stiffness `K` (impulse per velocity).
    pub stiffness: [f64; 2],
    /// Total impulse: the warm start, then the solution.
    pub impulse: [f64; 2],
    /// Index in the solved problem, or `NOT_SOLVED` when both sides are imposed.
    pub solved: u32,
}

const NOT_SOLVED: u32 = u32::MAX;

/// Elastic energy of the elements, shadows excepted (J).
pub fn elastic_energy(m: &FractureModel) -> f64 {
    m.elements
        .iter()
        .enumerate()
        .filter(|(k, _)| !m.is_shadow(*k))
        .map(|(_, e)| {
            e.triangle
                .elastic_energy(&m.spec.materials[e.region as usize], &e.state)
        })
        .sum()
}

/// Elastic energy stored in the cohesive interfaces (J).
pub fn stored_energy(m: &FractureModel) -> f64 {
    m.interfaces
        .iter()
        .filter_map(|i| cohesive(&m.laws[i.law as usize]).map(|z| (i, z)))
        .map(|(i, z)| {
            let area = 0.5 * i.length * m.spec.thickness;
            i.points
                .iter()
                .map(|p| area * z.stored_energy_per_area(p.jump, p.intensity))
                .sum::<f64>()
        })
        .sum()
}
