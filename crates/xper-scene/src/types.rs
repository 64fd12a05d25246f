//! The resolved scene: plain data, fully expanded, in SI units.

use serde::Serialize;

/// A fully resolved scene (generators expanded, defaults applied, everything validated).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scene {
    /// Scene name (`scene.name`).
    pub name: String,
    /// Time step in s.
    pub dt: f64,
    /// Number of time steps to run.
    pub steps: u64,
    /// Moreau-Jean theta parameter, in [0.5, 1].
    pub theta: f64,
    /// Gravity acceleration in m/s^2.
    pub gravity: [f64; 2],
    /// Contact detection distance in m (pairs closer than this are candidate contacts).
    pub alert_distance: f64,
    /// The configuration contacts are detected on (`detection`).
    pub detection: Detection,
    /// Contact solver settings.
    pub solver: SolverSettings,
    /// Output cadence.
    pub output: OutputSettings,
    /// Every group name used by a body, in first-use order (bodies in [`Scene::bodies`] order).
    pub groups: Vec<String>,
    /// Interaction laws between pairs of groups; pairs with no law do not interact.
    pub laws: Vec<LawDesc>,
    /// All bodies: `[[bodies]]`, then `[[walls]]`, then generated bodies, each in file order.
    pub bodies: Vec<BodyDesc>,
    /// The fluid around the disks, when the scene has a `[fluid]` section.
    pub fluid: Option<FluidDesc>,
    /// `[[events]]` by increasing time.
    pub events: Vec<EventDesc>,
    /// The periodic cell the bodies are in (`[cell]`), if any.
    pub cell: Option<CellDesc<2>>,
}

/// A periodic cell (`[cell]`, see `cell.rs`) of a scene of dimension `D` (2 or 3).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(bound(serialize = "[f64; D]: Serialize, [bool; D]: Serialize, \
                           [[CellLoadDesc; D]; D]: Serialize"))]
pub struct CellDesc<const D: usize> {
    /// Lower corner (m).
    pub origin: [f64; D],
    /// Sides along each axis (m).
    pub size: [f64; D],
    /// The axes along which bodies repeat.
    pub periodic: [bool; D],
    /// Mass of the cell (2D: kg per m of thickness; 3D: kg), the inertia of components under
    /// stress (0 when there is none).
    pub mass: f64,
    /// Control of the velocity gradient's components `L_kl = dv_k/dx_l`, by row `k`.
    pub loads: [[CellLoadDesc; D]; D],
}

/// How a component of a periodic cell's velocity gradient is controlled.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum CellLoadDesc {
    /// Imposed (1/s).
    Rate(TimeFunction),
    /// Following an imposed stress (Pa, compression positive).
    Stress(TimeFunction),
}

impl Default for CellLoadDesc {
    fn default() -> Self {
        CellLoadDesc::Rate(TimeFunction::Constant(0.0))
    }
}

/// Which contact solver to use for the velocity problem of each step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum VelocitySolverKind {
    /// Non-linear Gauss-Seidel on the factorised Delassus operator (`"nlgs"`).
    Nlgs,
    /// Generalized Newton method on the assembled problem (`"newton"`).
    Newton,
    /// Proximal-point iterations around the generalized Newton method (`"proximal_newton"`).
    ProximalNewton,
}

/// The norm used by the solver's convergence test.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ConvergenceNorm {
    /// Quadratic (relative) norm, `quad`.
    Quad,
    /// Maximum norm, `maxm`.
    Maxm,
    /// Natural-map residual, `natural_map`.
    NaturalMap,
}

/// Acceleration of the NLGS sweeps (`acceleration`, `anderson_depth`, `anderson_period`): the
/// solver's own type, `none` or `anderson` (depth and period 3 unless given).
pub use xper_solver::{Acceleration, CheckPass};

/// The lubrication correction (`[fluid] lubrication_range`, `lubrication_roughness`), the
/// solver's own type.
pub use xper_fluid::Lubrication;
/// The fluid's time integration (`[fluid] time_scheme`), the solver's own type.
pub use xper_fluid::TimeScheme;
/// The fluid's direct forcing (`[fluid] forcing`, `forcing_iterations`, `marker_retraction`),
/// the solver's own types.
pub use xper_fluid::{Forcing, MarkerForcingParams};
/// The configuration each step detects its contacts on (`[scene] detection`: `"begin"` or
/// `"predicted"`): the stepper's own type.
pub use xper_nscd::Detection;

/// Contact solver settings (`[solver]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolverSettings {
    /// Solver algorithm.
    pub kind: VelocitySolverKind,
    /// Convergence tolerance, > 0: of `norm` for NLGS; of the natural-map error divided by
    /// `max(|q|, |r|, |u|)` (Siconos' scaling) for the Newton kinds.
    pub tolerance: f64,
    /// Maximum number of iterations per step, >= 1: NLGS sweeps, Newton iterations or
    /// proximal steps.
    pub max_iterations: u32,
    /// Convergence is checked every this many NLGS iterations, >= 1 (NLGS: the velocity
    /// problem and the position projection; Newton kinds: the projection only).
    pub check_every: u32,
    /// NLGS relaxation factor, in (0, 2) (as `check_every`).
    pub relaxation: f64,
    /// NLGS convergence norm (as `check_every`).
    pub norm: ConvergenceNorm,
    /// NLGS acceleration (the velocity problem; the position projection stays plain).
    pub acceleration: Acceleration,
    /// Which updates the NLGS convergence check measures (LMGC90's separate pass or the
    /// stricter check sweep itself; as `check_every`).
    pub check: CheckPass,
    /// Whether interpenetrations are corrected by a position projection after each step.
    pub position_projection: bool,
}

impl SolverSettings {
    /// The default iteration limit of a solver kind: 1000 NLGS sweeps, 200 Newton iterations,
    /// 100 proximal steps.
    pub fn default_max_iterations(kind: VelocitySolverKind) -> u32 {
        match kind {
            VelocitySolverKind::Nlgs => 1000,
            VelocitySolverKind::Newton => 200,
            VelocitySolverKind::ProximalNewton => 100,
        }
    }
}

impl Default for SolverSettings {
    /// The documented defaults: NLGS, tolerance 1.666e-4, 1000 iterations, check every 10,
    /// relaxation 1, quad norm, position projection on.
    fn default() -> Self {
        Self {
            kind: VelocitySolverKind::Nlgs,
            tolerance: 1.666e-4,
            max_iterations: 1000,
            check_every: 10,
            relaxation: 1.0,
            norm: ConvergenceNorm::Quad,
            acceleration: Acceleration::None,
            check: CheckPass::default(),
            position_projection: true,
        }
    }
}

/// Output cadence (`[output]`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct OutputSettings {
    /// Steps between two VTU frames, >= 1.
    pub frame_every: u64,
    /// Steps between two checkpoints, >= 1.
    pub checkpoint_every: u64,
    /// Steps (1-based, increasing, each in `1..=steps`) whose contact problem is written to a
    /// file before it is solved; empty when not asked for.
    pub dump_problems: Vec<u64>,
    /// Micromechanical measures at every step (`micro.csv`, columns of `series.csv`) with the
    /// volume they take (`[output] micro = "walls"` or `"grains"`); `None`: not computed.
    pub micro: Option<MicroVolume>,
}

/// The volume of the micromechanical measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum MicroVolume {
    /// The box spanned by the walls' positions (the bodies that are not free grains).
    Walls,
    /// The bounding box of the grains.
    Grains,
    /// The periodic cell (`[cell]`).
    Cell,
}

/// A Signorini-Coulomb law between two groups.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawDesc {
    /// Indices into [`Scene::groups`] (may be equal).
    pub groups: [usize; 2],
    /// Coulomb friction coefficient, >= 0.
    pub friction: f64,
    /// Newton normal restitution coefficient, in [0, 1].
    pub restitution: f64,
}

/// The shape of a body, in its body frame (centred on the centre of mass).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum ShapeDesc {
    /// A disk.
    Disk {
        /// Radius in m.
        radius: f64,
    },
    /// A convex polygon.
    Polygon {
        /// Vertices in m relative to the centroid, counter-clockwise, at angle 0.
        vertices: Vec<[f64; 2]>,
    },
    /// A wall: the segment from `position - half_length*dir` to `position + half_length*dir`,
    /// `dir = (cos angle, sin angle)`.
    Segment {
        /// Half of the segment length in m.
        half_length: f64,
    },
}

impl ShapeDesc {
    /// Twice the largest distance from the centroid to the shape (m): the diameter of a disk;
    /// `None` for a wall.
    pub(crate) fn size(&self) -> Option<f64> {
        match self {
            ShapeDesc::Disk { radius } => Some(2.0 * radius),
            ShapeDesc::Polygon { vertices } => Some(2.0 * crate::geometry::circumradius(vertices)),
            ShapeDesc::Segment { .. } => None,
        }
    }
}

/// One body of the resolved scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodyDesc {
    /// Shape in the body frame.
    pub shape: ShapeDesc,
    /// Centre of mass in m (centroid for polygons, midpoint for segments).
    pub position: [f64; 2],
    /// Orientation in rad.
    pub angle: f64,
    /// Initial velocity of the centre of mass in m/s.
    pub velocity: [f64; 2],
    /// Initial angular velocity in rad/s.
    pub angular_velocity: f64,
    /// Mass in kg (per unit thickness); `f64::INFINITY` for walls.
    pub mass: f64,
    /// Moment of inertia about the centre of mass in kg m^2 (per unit thickness);
    /// `f64::INFINITY` for walls.
    pub inertia: f64,
    /// Index into [`Scene::groups`].
    pub group: usize,
    /// Imposed motion of the x, y and rotation degrees of freedom.
    pub drives: [Drive; 3],
}

/// How one degree of freedom is driven.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum Drive {
    /// Not driven: follows the dynamics.
    Free,
    /// Velocity imposed (m/s or rad/s) as a function of time.
    Velocity(TimeFunction),
    /// External force (N) or torque (N m) applied as a function of time, added to gravity.
    Force(TimeFunction),
    /// A pressure on a wall with a mass, applied as the force `p A n_d` on this translational
    /// degree of freedom (`[[walls]] drive.<dof> = { pressure = ..., between = [...] }`).
    Pressure(PressureDesc),
}

/// An `[[events]]` entry: changes made at a time, the stages of a staged test.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventDesc {
    /// When, in s: before the first step that begins at or after it.
    pub time: f64,
    /// New friction coefficients of the laws between pairs of groups (indices into
    /// [`Scene::groups`]).
    pub frictions: Vec<([usize; 2], f64)>,
    /// New drives: `(body, degree of freedom, drive)`, bodies indexing the scene's bodies.
    pub drives: Vec<(usize, usize, Drive)>,
    /// New controls of components `[k, l]` of the periodic cell's velocity gradient.
    pub cell: Vec<([usize; 2], CellLoadDesc)>,
}

/// A pressure drive of a wall: a servo wall at constant confining pressure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PressureDesc {
    /// Pressure in Pa as a function of time; positive pushes the wall along its normal (the
    /// left of `from -> to` in 2D: walls drawn counter-clockwise round a sample push inwards).
    pub pressure: TimeFunction,
    /// `n_d`, the component of that normal along the driven degree of freedom.
    pub direction: f64,
    /// The loaded length (m, 2D) or area (m^2, 3D): the product of these factors.
    pub extent: Vec<ExtentDesc>,
}

/// A factor of a pressure's loaded extent.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum ExtentDesc {
    /// A fixed length in m (the wall's own length when no `between` is given).
    Fixed(f64),
    /// The distance in m between two bodies (indices into [`Scene::bodies`]) along the unit
    /// `axis` (z = 0 in 2D): the sample's extent between two other walls.
    Between {
        /// The two bodies.
        bodies: [usize; 2],
        /// The axis (the wall's direction).
        axis: [f64; 3],
    },
}

/// A scalar function of time (the engine's own type: the scene builds it directly).
pub use xper_bodies::TimeFunction;

/// A viscous incompressible fluid filling a rectangle around the scene's disks (`[fluid]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FluidDesc {
    /// Density rho_f in kg/m^3.
    pub density: f64,
    /// Dynamic viscosity in Pa s.
    pub viscosity: f64,
    /// Lower-left corner of the domain in m.
    pub lower: [f64; 2],
    /// Upper-right corner of the domain in m.
    pub upper: [f64; 2],
    /// Side of the square grid cells in m; the domain holds a whole number of them.
    pub cell_size: f64,
    /// Body force per unit mass on the fluid in m/s^2 (gravity acts on grains through
    /// buoyancy; this drives e.g. a periodic channel).
    pub body_force: [f64; 2],
    /// Courant number of the adaptive time step, in (0, 1].
    pub cfl: f64,
    /// Fraction of the explicit viscous time-step limit, in (0, 1].
    pub viscous_safety: f64,
    /// Donor-cell blending of the advection, in [0, 1] (0: central).
    pub upwinding: f64,
    /// The paper's sharp solid indicator instead of the smoothed solid fraction.
    pub sharp_indicator: bool,
    /// Relative residual of the pressure solve.
    pub pressure_tolerance: f64,
    /// Largest number of multigrid cycles per pressure solve.
    pub pressure_max_cycles: u32,
    /// Time integration of the momentum equation (`"euler"`, the default, or `"rk3"`).
    pub time_scheme: TimeScheme,
    /// The lubrication correction, when `lubrication_range` is given.
    pub lubrication: Option<Lubrication>,
    /// The direct forcing (`"markers"`, the default, or `"fraction"`).
    pub forcing: Forcing,
    /// Conditions on the left, right, bottom and top sides.
    pub boundary: [FluidSideDesc; 4],
}

/// The condition on one side of the fluid domain.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum FluidSideDesc {
    /// Fixed wall.
    NoSlip,
    /// Wall sliding along itself (m/s, along +x on bottom/top, +y on left/right).
    MovingWall {
        /// Tangential velocity in m/s.
        velocity: f64,
    },
    /// Periodic with the opposite side.
    Periodic,
    /// Imposed inward velocity: uniform, or parabolic with `speed` at the middle.
    Inflow {
        /// Poiseuille profile instead of uniform.
        parabolic: bool,
        /// Inward speed in m/s (the maximum for a parabolic profile).
        speed: f64,
    },
    /// Zero normal derivative and zero pressure.
    Outflow,
}
