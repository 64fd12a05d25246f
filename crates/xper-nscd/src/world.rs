//! The state of a run: bodies, contacts, laws, parameters, time and energy budget.

use serde::{Deserialize, Serialize};
use xper_bodies::BodySet;
use xper_geometry::ContactSet;
use xper_laws::{InteractionLaw, LawTable};
use xper_math::{Real, Vector};
use xper_solver::{NlgsParams, SolverParams};

/// Parameters of the time stepping.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepParams {
    /// Time step h (s).
    pub dt: Real,
    /// theta of the theta-method, in [1/2, 1].
    pub theta: Real,
    /// Gravity (m/s^2).
    pub gravity: Vector,
    /// Alert distance (m): pairs closer than this are contacts.
    pub alert_distance: Real,
    /// The configuration on which contacts are detected and their gaps measured.
    pub detection: Detection,
    /// NLGS parameters: the velocity solve when `solver` is [`VelocitySolver::Nlgs`], and
    /// always the position projection.
    pub nlgs: NlgsParams,
    /// Solver of the velocity problem of each step.
    pub solver: VelocitySolver,
    /// Overlap (m) beyond which the position projection runs; `None` disables it. Contacts with
    /// restitution whose predicted gap is below it count as closed (see `normal_shift`).
    pub projection_tolerance: Option<Real>,
}

#[cfg(all(test, feature = "dim2"))]
impl StepParams {
    /// Time step `dt` (s), theta 0.5, no gravity, no alert distance, the default NLGS: the
    /// parameters of the unit tests.
    pub(crate) fn for_tests(dt: Real) -> Self {
        StepParams {
            dt,
            theta: 0.5,
            gravity: Vector::zeros(),
            alert_distance: 0.0,
            detection: Default::default(),
            nlgs: Default::default(),
            solver: Default::default(),
            projection_tolerance: None,
        }
    }
}

/// The configuration on which a step detects its contacts (pairs within the alert distance)
/// and measures their gaps, normals and lever arms.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Detection {
    /// The configuration at the beginning of the step, `q_i`; the Signorini condition uses
    /// the gap predicted to first order, `g_TT = g(q_i) + h (1 - theta) U_N,i`.
    #[default]
    Begin,
    /// The configuration the explicit part of the motion reaches, `q_TT = q_i + h (1 - theta)
    /// v_i`, on which the gap `g_TT = g(q_TT)` is measured exactly: LMGC90's detection
    /// configuration (`coorTT` of its rigid bodies). A pair approaching at speed `V` is then
    /// found `h (1 - theta) V` earlier than on `q_i`, which matters when a step's approach
    /// `h V` exceeds the alert distance.
    Predicted,
}

/// The solver of the velocity problem of each step.
///
/// The position projection always runs NLGS with [`StepParams::nlgs`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum VelocitySolver {
    /// NLGS on the factorised operator with [`StepParams::nlgs`] (O(1) per contact update).
    #[default]
    Nlgs,
    /// [`xper_solver::solve`] on the assembled problem ([`crate::assemble_problem`]) with
    /// these parameters (generalized Newton, proximal Newton, NSGS or Lemke), warm-started
    /// from the impulses of the previous step; convergence is judged by the natural-map error
    /// under `scaling`.
    Assembled(SolverParams),
}

/// Energies accumulated over the run (J per m of thickness).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct EnergyBudget {
    /// Kinetic + potential energy at the start of the run.
    pub initial: Real,
    /// Energy dissipated at contacts (friction and inelastic impacts), `-sum R.(U_i + U_i+1)/2`.
    pub dissipated: Real,
    /// Work done on the bodies by imposed velocities and imposed forces.
    pub external_work: Real,
    /// Potential energy added by position projections (they move bodies, not velocities).
    pub projection_work: Real,
    /// Largest |kinetic + potential - initial| seen, and external work: the scale of the budget.
    pub scale: Real,
}

/// Everything that evolves during a run; serialisable for checkpoints.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct World {
    /// The bodies.
    pub bodies: BodySet,
    /// Contacts of the last step, with their impulses (the warm start) and their linearised
    /// gaps at its end.
    pub contacts: ContactSet,
    /// Laws per pair of groups.
    pub laws: LawTable,
    /// Time-stepping parameters.
    pub params: StepParams,
    /// Current time (s).
    pub time: Real,
    /// Steps done.
    pub step: u64,
    /// Energy budget.
    pub energy: EnergyBudget,
    /// Changes of drives and laws at given times (a staged test), and how many were made.
    pub events: crate::events::Events,
    /// The periodic cell the bodies are in, if any (see [`crate::cell`]).
    pub cell: Option<crate::cell::PeriodicCell>,
}

impl World {
    /// A world at time 0. The body set's spare room is released: it is complete.
    pub fn new(mut bodies: BodySet, laws: LawTable, params: StepParams) -> Self {
        bodies.shrink_to_fit();
        let initial = bodies.kinetic_energy() + bodies.potential_energy(&params.gravity);
        World {
            bodies,
            contacts: ContactSet::default(),
            laws,
            params,
            time: 0.0,
            step: 0,
            energy: EnergyBudget {
                initial,
                ..Default::default()
            },
            events: Default::default(),
            cell: None,
        }
    }

    /// Puts the bodies in a periodic cell: its gradient starts at the imposed one at the
    /// current time (zero on the components under stress), the bodies are wrapped into it,
    /// and the energy budget starts afresh.
    pub fn with_cell(mut self, mut cell: crate::cell::PeriodicCell) -> Self {
        cell.gradient = cell.imposed_gradient(self.time);
        cell.wraps = vec![[0; xper_math::DIM]; self.bodies.len()];
        self.cell = Some(cell);
        self.wrap_into_cell();
        self.energy = EnergyBudget {
            initial: self.kinetic_energy() + self.potential_energy(),
            ..Default::default()
        };
        self
    }

    /// The interaction law of a contact between `bodies` (that of their groups), if any.
    #[inline]
    pub fn contact_law(&self, bodies: [u32; 2]) -> Option<InteractionLaw> {
        let group = |b: u32| self.bodies.group[b as usize];
        let k = self.laws.between(group(bodies[0]), group(bodies[1]))?;
        Some(*self.laws.law(k))
    }

    /// Kinetic energy (J per m), the periodic cell's included.
    pub fn kinetic_energy(&self) -> Real {
        // Without a cell, the bodies' alone (adding 0 would turn a -0 of no bodies into 0).
        match &self.cell {
            Some(c) => self.bodies.kinetic_energy() + c.kinetic_energy(),
            None => self.bodies.kinetic_energy(),
        }
    }

    /// Gravitational potential energy (J per m).
    pub fn potential_energy(&self) -> Real {
        self.bodies.potential_energy(&self.params.gravity)
    }

    /// `kinetic + potential + dissipated - external work - projection work - initial`: zero up
    /// to round-off for theta = 1/2.
    pub fn energy_error(&self) -> Real {
        self.kinetic_energy() + self.potential_energy() + self.energy.dissipated
            - self.energy.external_work
            - self.energy.projection_work
            - self.energy.initial
    }

    /// Serialises the world (checkpoint format: bincode of this struct).
    pub fn to_bytes(&self) -> Vec<u8> {
        bincode::serialize(self).expect("serialising plain data cannot fail")
    }

    /// Reads a world written by [`World::to_bytes`].
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        bincode::deserialize(bytes).map_err(|e| format!("not a valid xper checkpoint: {e}"))
    }
}
