//! The resolved 3D scene (`[scene] dimension = 3`): plain data, fully expanded, in SI units.

use serde::Serialize;

use crate::types::{Detection, Drive, LawDesc, OutputSettings, SolverSettings};

/// A fully resolved 3D rigid scene (generators expanded, defaults applied, validated).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scene3 {
    /// Scene name (`scene.name`).
    pub name: String,
    /// Time step in s.
    pub dt: f64,
    /// Number of time steps to run.
    pub steps: u64,
    /// Moreau-Jean theta parameter, in [0.5, 1].
    pub theta: f64,
    /// Gravity acceleration in m/s^2.
    pub gravity: [f64; 3],
    /// Contact detection distance in m.
    pub alert_distance: f64,
    /// The configuration contacts are detected on (`detection`).
    pub detection: Detection,
    /// Contact solver settings.
    pub solver: SolverSettings,
    /// Output cadence.
    pub output: OutputSettings,
    /// Every group name used by a body, in first-use order.
    pub groups: Vec<String>,
    /// Interaction laws between pairs of groups.
    pub laws: Vec<LawDesc>,
    /// All bodies: `[[bodies]]`, then `[[walls]]`, then generated bodies, each in file order.
    pub bodies: Vec<BodyDesc3>,
    /// The periodic cell the bodies are in (`[cell]`), if any.
    pub cell: Option<crate::types::CellDesc<3>>,
    /// `[[events]]` by increasing time.
    pub events: Vec<crate::types::EventDesc>,
}

/// The shape of a 3D body in its body frame (centred on the centre of mass).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum ShapeDesc3 {
    /// A sphere.
    Sphere {
        /// Radius in m.
        radius: f64,
    },
    /// A convex polyhedron, the hull of its vertices.
    Polyhedron {
        /// Vertices in m relative to the centroid, body frame.
        vertices: Vec<[f64; 3]>,
    },
    /// A planar wall: the rectangle of half-extents (m) along the body's x and y axes
    /// (infinite for a half-space), its outward normal the body's z axis.
    Plane {
        /// Half-extents in m along the body's x and y axes.
        half_extents: [f64; 2],
    },
}

impl ShapeDesc3 {
    /// Twice the largest distance from the centroid to the shape (m): the diameter of a
    /// sphere; `None` for a wall.
    pub(crate) fn size(&self) -> Option<f64> {
        match self {
            ShapeDesc3::Sphere { radius } => Some(2.0 * radius),
            ShapeDesc3::Polyhedron { vertices } => Some(
                2.0 * (vertices.iter())
                    .map(|v| v.iter().map(|x| x * x).sum::<f64>().sqrt())
                    .fold(0.0, f64::max),
            ),
            ShapeDesc3::Plane { .. } => None,
        }
    }
}

/// One body of the resolved 3D scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BodyDesc3 {
    /// Shape in the body frame.
    pub shape: ShapeDesc3,
    /// Centre of mass in m (a point of the plane for walls).
    pub position: [f64; 3],
    /// Orientation: the rotation vector (unit axis times angle, rad) that turns the body
    /// frame into the scene's.
    pub orientation: [f64; 3],
    /// Initial velocity of the centre of mass in m/s.
    pub velocity: [f64; 3],
    /// Initial angular velocity in rad/s (scene frame).
    pub angular_velocity: [f64; 3],
    /// Mass in kg; `f64::INFINITY` for walls.
    pub mass: f64,
    /// Inertia tensor about the centre of mass in the body frame, row-major, kg m^2;
    /// infinite for walls.
    pub inertia: [[f64; 3]; 3],
    /// Index into [`Scene3::groups`].
    pub group: usize,
    /// Imposed motion of the x, y, z translations and the rotations about x, y, z.
    pub drives: [Drive; 6],
}
