//! Conversion of a validated scene description into an engine [`World`]: the bodies per
//! dimension (`bodies2d.rs`, `bodies3d.rs`), the laws and time-stepping parameters here.

#[cfg(feature = "dim2")]
#[path = "bodies2d.rs"]
mod dimension;
#[cfg(feature = "dim3")]
#[path = "bodies3d.rs"]
mod dimension;

pub use dimension::RigidScene;
use xper_bodies::{Drive, ExtentFactor, PressureDrive, TimeFunction};
use xper_geometry::Lattice;
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Tensor, Vector, DIM};
use xper_nscd::events::{Change, Event, Events};
use xper_nscd::{CellLoad, Detection, PeriodicCell, StepParams, VelocitySolver, World};
use xper_solver::{ConvergenceNorm, ErrorScaling, NlgsParams, SolverKind, SolverParams};

/// Overlap allowed before the position projection runs, relative to the smallest body size.
pub const PROJECTION_TOLERANCE_RELATIVE: Real = 1e-4;

/// A drive of the scene as the engine's (the scene names the 2D build's types, which the 3D
/// build of the engine does not share).
pub(crate) fn drive(d: &xper_scene::Drive) -> Drive {
    match d {
        xper_scene::Drive::Free => Drive::Free,
        xper_scene::Drive::Velocity(f) => Drive::Velocity(time_function(f)),
        xper_scene::Drive::Force(f) => Drive::Force(time_function(f)),
        xper_scene::Drive::Pressure(p) => Drive::Pressure(PressureDrive {
            pressure: time_function(&p.pressure),
            direction: p.direction,
            extent: (p.extent.iter())
                .map(|e| match e {
                    xper_scene::ExtentDesc::Fixed(l) => ExtentFactor::Fixed(*l),
                    xper_scene::ExtentDesc::Between { bodies, axis } => ExtentFactor::Between {
                        bodies: bodies.map(|b| b as u32),
                        axis: Vector::from_fn(|k, _| axis[k]),
                    },
                })
                .collect(),
        }),
    }
}

fn time_function(f: &xper_scene::TimeFunction) -> TimeFunction {
    match f {
        xper_scene::TimeFunction::Constant(v) => TimeFunction::Constant(*v),
        xper_scene::TimeFunction::Table(points) => TimeFunction::Table(points.clone()),
        &xper_scene::TimeFunction::Sine {
            amplitude,
            frequency,
            phase,
            offset,
        } => TimeFunction::Sine {
            amplitude,
            frequency,
            phase,
            offset,
        },
    }
}

fn detection(d: xper_scene::Detection) -> Detection {
    match d {
        xper_scene::Detection::Begin => Detection::Begin,
        xper_scene::Detection::Predicted => Detection::Predicted,
    }
}

/// The velocity solver of a scene: NLGS, or an assembled-problem solver with the scene's
/// tolerance on the natural-map error under Siconos' scaling `max(|q|, |r|, |u|)`.
pub fn velocity_solver(settings: &xper_scene::SolverSettings) -> VelocitySolver {
    let kind = match settings.kind {
        xper_scene::VelocitySolverKind::Nlgs => return VelocitySolver::Nlgs,
        xper_scene::VelocitySolverKind::Newton => SolverKind::Newton,
        xper_scene::VelocitySolverKind::ProximalNewton => SolverKind::ProximalNewton,
    };
    VelocitySolver::Assembled(SolverParams {
        tolerance: settings.tolerance,
        max_iterations: settings.max_iterations,
        scaling: ErrorScaling::RelativeMax,
        ..SolverParams::with_kind(kind)
    })
}

/// Builds the world of a scene at time 0.
pub fn world_from_scene(scene: &RigidScene) -> World {
    let (bodies, smallest) = dimension::bodies(scene);
    let mut laws = LawTable::new(scene.groups.len());
    for law in &scene.laws {
        laws.set(
            law.groups[0],
            law.groups[1],
            InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
                friction: law.friction,
                restitution: law.restitution,
            }),
        );
    }
    let s = &scene.solver;
    let params = StepParams {
        dt: scene.dt,
        theta: scene.theta,
        gravity: Vector::from(scene.gravity),
        alert_distance: scene.alert_distance,
        detection: detection(scene.detection),
        nlgs: NlgsParams {
            tolerance: s.tolerance,
            max_iterations: s.max_iterations,
            check_every: s.check_every,
            relaxation: s.relaxation,
            norm: match s.norm {
                xper_scene::ConvergenceNorm::Quad => ConvergenceNorm::Quad,
                xper_scene::ConvergenceNorm::Maxm => ConvergenceNorm::Maxm,
                xper_scene::ConvergenceNorm::NaturalMap => ConvergenceNorm::NaturalMap,
            },
            acceleration: s.acceleration,
            check: s.check,
        },
        solver: velocity_solver(s),
        projection_tolerance: (s.position_projection && smallest.is_finite())
            .then_some(PROJECTION_TOLERANCE_RELATIVE * smallest),
    };
    let count = bodies.len();
    let mut world = World::new(bodies, laws, params);
    world.events = events(dimension::events(scene));
    match dimension::cell(scene) {
        Some(cell) => world.with_cell(periodic_cell(cell, count)),
        None => world,
    }
}

/// The scene's `[cell]` as the engine's periodic cell for `bodies` bodies: edges along the axes.
fn periodic_cell(c: &xper_scene::CellDesc<DIM>, bodies: usize) -> PeriodicCell {
    let lattice = Lattice {
        origin: Vector::from(c.origin),
        edges: Tensor::from_diagonal(&Vector::from(c.size)),
        periodic: c.periodic,
        relabels: 0,
    };
    let loads = (c.loads.each_ref()).map(|row| row.each_ref().map(cell_load));
    PeriodicCell::new(lattice, loads, c.mass, bodies)
}

/// A control of a cell component as the engine's.
fn cell_load(load: &xper_scene::CellLoadDesc) -> CellLoad {
    match load {
        xper_scene::CellLoadDesc::Rate(f) => CellLoad::Rate(time_function(f)),
        xper_scene::CellLoadDesc::Stress(f) => CellLoad::Stress(time_function(f)),
    }
}

/// A scene's `[[events]]` (2D or 3D) as the engine's.
fn events(list: &[xper_scene::EventDesc]) -> Events {
    let list = (list.iter())
        .map(|e| Event {
            time: e.time,
            changes: (e.frictions.iter())
                .map(|&(groups, friction)| Change::Friction {
                    groups: groups.map(|g| g as u16),
                    friction,
                })
                .chain(e.drives.iter().map(|(body, dof, d)| Change::Drive {
                    body: *body as u32,
                    dof: *dof,
                    drive: drive(d),
                }))
                .chain(e.cell.iter().map(|(component, load)| Change::Cell {
                    component: *component,
                    load: cell_load(load),
                }))
                .collect(),
        })
        .collect();
    Events { list, applied: 0 }
}

/// Gives a world restored from a checkpoint the solver limits of its (possibly edited) scene:
/// tolerance, iteration limit and check interval are among the edits a resume may take
/// ([`xper_run::resume::COMPATIBLE`]).
pub fn take_solver_limits(world: &mut World, scene: &RigidScene) {
    let s = &scene.solver;
    world.params.nlgs.tolerance = s.tolerance;
    world.params.nlgs.max_iterations = s.max_iterations;
    world.params.nlgs.check_every = s.check_every;
    world.params.solver = velocity_solver(s);
}

/// Adds to `world` the bodies of `text`: a scene file holding only what they need (`[scene]`
/// with its required fields, the `[[materials]]` they use, `[[bodies]]` and `[[walls]]`), read
/// and checked as any scene (`file` names it in errors). Their groups must be among `groups`,
/// the world's (laws are the scene's). Their kinetic and potential energy count in the energy
/// budget's initial energy. Returns the new bodies' indices; nothing is added on an error.
pub fn add_bodies(
    world: &mut World,
    groups: &[String],
    text: &str,
    file: &std::path::Path,
) -> Result<Vec<usize>, String> {
    let any = xper_scene::parse_any_scene(text, file).map_err(|e| e.to_string())?;
    let scene = dimension::rigid_scene(any).ok_or_else(|| {
        format!(
            "{}: not the bodies of a rigid scene of this dimension",
            file.display()
        )
    })?;
    let map = (scene.groups.iter())
        .map(|g| match groups.iter().position(|h| h == g) {
            Some(k) => Ok(k as u16),
            None => Err(format!(
                "{}: group {g:?} is not one of the scene's ({}): its laws are the scene's",
                file.display(),
                groups.join(", ")
            )),
        })
        .collect::<Result<Vec<u16>, String>>()?;
    let (set, _) = dimension::bodies(&scene);
    let g = world.params.gravity;
    let before = world.bodies.kinetic_energy() + world.bodies.potential_energy(&g);
    let added = (0..set.len())
        .map(|b| {
            let mut body = set.body(b);
            body.group = map[body.group as usize];
            world.bodies.insert(body).index()
        })
        .collect();
    let after = world.bodies.kinetic_energy() + world.bodies.potential_energy(&g);
    world.energy.initial += after - before;
    Ok(added)
}

/// Frees the scene's list of body descriptions once the world is built from it (nothing after
/// needs it): for a generated scene of a million disks it is as large as the world.
pub fn release_body_descriptions(scene: &mut RigidScene) {
    scene.bodies = Vec::new();
}

/// Whether the scene's bodies are in a periodic cell (`[cell]`).
pub(crate) fn scene_has_cell(scene: &RigidScene) -> bool {
    dimension::cell(scene).is_some()
}

/// Whether the scene changes drives or laws during the run (`[[events]]`).
pub(crate) fn scene_has_events(scene: &RigidScene) -> bool {
    !dimension::events(scene).is_empty()
}
