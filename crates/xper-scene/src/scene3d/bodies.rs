//! Readers for the `[[bodies]]` and `[[walls]]` of a 3D scene.
//!
//! Polyhedra (`polyhedron`, `box` and the regular solids) are the convex hulls of their
//! vertices, with the mass properties of `xper_bodies3d` (divergence theorem over the faces);
//! a sphere of radius `r` and density `rho` has `m = rho 4/3 pi r^3`, `I = 2/5 m r^2`.

use crate::bodies::{drives_of, read_bodies, Driven};
use crate::pressure::{PendingSpan, WallFrame3};
use crate::read::{as_vec3, choose, ensure, Ctx, Got, Tbl};
use crate::shared::{Built3, Groups, Materials, Origin, Part};
use crate::tree::Kind;
use crate::types::{Drive, TimeFunction};
use crate::types3d::{BodyDesc3, ShapeDesc3};
use xper_bodies3d::{ConvexPolyhedron, Shape};
use xper_math3d::{tangents, AngMatrix, Rotation, Vector};

/// The degrees of freedom of a 3D body, as `drive` names them.
pub(crate) const DOFS3: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

const BODY_KEYS: &[&str] = &[
    "shape",
    "center",
    "radius",
    "size",
    "vertices",
    "orientation",
    "material",
    "mass",
    "inertia",
    "group",
    "velocity",
    "angular_velocity",
    "fixed",
    "drive",
];

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind3 {
    Sphere,
    Polyhedron,
    Box,
    Tetrahedron,
    Octahedron,
    Dodecahedron,
    Icosahedron,
}

/// A body's geometry: shape, position of its centre of mass, orientation and the engine's
/// shape (for mass properties).
pub(crate) struct Geom3 {
    pub shape: ShapeDesc3,
    pub position: [f64; 3],
    pub orientation: [f64; 3],
    pub engine: Shape,
}

/// The vertices of a regular solid of circumradius 1 centred at the origin.
fn regular(kind: Kind3) -> Vec<Vector> {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let cyclic = |a: f64, b: f64| {
        let mut v = Vec::new();
        for (s, t) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let (x, y) = (s * a, t * b);
            v.extend([
                Vector::new(0.0, x, y),
                Vector::new(x, y, 0.0),
                Vector::new(y, 0.0, x),
            ]);
        }
        v
    };
    let corners = || {
        (0..8).map(|k| {
            let s = |bit: usize| if k >> bit & 1 == 1 { 1.0 } else { -1.0 };
            Vector::new(s(0), s(1), s(2))
        })
    };
    let points: Vec<Vector> = match kind {
        Kind3::Tetrahedron => corners().filter(|c| c.x * c.y * c.z > 0.0).collect(),
        Kind3::Octahedron => (0..6)
            .map(|k| {
                let mut v = Vector::zeros();
                v[k % 3] = if k < 3 { 1.0 } else { -1.0 };
                v
            })
            .collect(),
        Kind3::Icosahedron => cyclic(1.0, phi),
        Kind3::Dodecahedron => corners().chain(cyclic(1.0 / phi, phi)).collect(),
        _ => Vec::new(),
    };
    points.iter().map(|p| p / p.norm()).collect()
}

/// Reads `[[bodies]]` into `built`.
pub(crate) fn bodies(
    ctx: &mut Ctx,
    root: &Tbl,
    mats: &Materials,
    groups: &mut Groups,
    built: &mut Built3,
) {
    read_bodies(ctx, root, built, |ctx, t| body(ctx, t, mats, groups));
}

fn body(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<BodyDesc3> {
    t.check_keys(ctx, BODY_KEYS);
    let shapes = [
        ("sphere", Kind3::Sphere),
        ("polyhedron", Kind3::Polyhedron),
        ("box", Kind3::Box),
        ("tetrahedron", Kind3::Tetrahedron),
        ("octahedron", Kind3::Octahedron),
        ("dodecahedron", Kind3::Dodecahedron),
        ("icosahedron", Kind3::Icosahedron),
    ];
    let shape_got = t.string(ctx, "shape").req(ctx, t, "shape");
    let kind = choose(ctx, shape_got, &t.field("shape"), "shape", &shapes);
    let geom = kind.and_then(|kind| geom(ctx, t, kind));
    let mass_inertia = mass_inertia(ctx, t, mats, geom.as_ref());
    let group = t
        .string(ctx, "group")
        .req(ctx, t, "group")
        .map(|(g, _)| groups.index(g));
    let velocity = t.vec3(ctx, "velocity").or([0.0; 3]);
    let angular_velocity = t.vec3(ctx, "angular_velocity").or([0.0; 3]);
    let fixed = t.boolean(ctx, "fixed").or(false);
    let drive = match t.table(ctx, "drive") {
        Got::Absent => Some(std::array::from_fn(|_| None)),
        Got::Bad => None,
        Got::Val(d, pos) => {
            if fixed == Some(true) {
                let why = "`drive` cannot be combined with `fixed = true`";
                ctx.err(pos, &t.field("drive"), why);
            }
            drives_of(ctx, &d, Driven::Body, DOFS3, None)
        }
    };
    let (geom, (mass, inertia), group) = (geom?, mass_inertia?, group?);
    let drives = if fixed? {
        std::array::from_fn(|_| Drive::Velocity(TimeFunction::Constant(0.0)))
    } else {
        drive?.map(|d| d.unwrap_or(Drive::Free))
    };
    Some(BodyDesc3 {
        shape: geom.shape,
        position: geom.position,
        orientation: geom.orientation,
        velocity: velocity?,
        angular_velocity: angular_velocity?,
        mass,
        inertia,
        group,
        drives,
    })
}

fn geom(ctx: &mut Ctx, t: &Tbl, kind: Kind3) -> Option<Geom3> {
    let unused = |key: &str| format!("`{key}` is not used by this shape");
    let forbidden: &[&str] = match kind {
        Kind3::Sphere => &["vertices", "size", "orientation"],
        Kind3::Polyhedron => &["center", "radius", "size", "orientation"],
        Kind3::Box => &["radius", "vertices"],
        _ => &["size", "vertices"],
    };
    for key in forbidden {
        t.forbid(ctx, key, &unused(key));
    }
    let orientation = t.vec3(ctx, "orientation").or([0.0; 3]);
    if kind == Kind3::Sphere {
        let center = t.vec3(ctx, "center").req(ctx, t, "center");
        let r = t.num(ctx, "radius").req(ctx, t, "radius");
        let radius = ensure(ctx, r, &t.field("radius"), |v| v > 0.0, "> 0 m")?;
        return Some(Geom3 {
            shape: ShapeDesc3::Sphere { radius },
            position: center?.0,
            orientation: [0.0; 3],
            engine: Shape::Sphere { radius },
        });
    }
    let (points, centre, field, pos) = match kind {
        Kind3::Polyhedron => {
            let field = t.field("vertices");
            let Some(n) = t.get("vertices") else {
                t.missing(ctx, "vertices");
                return None;
            };
            let Kind::Array(a) = &n.kind else {
                ctx.expected(n, &field, "an array of [x, y, z] vertices");
                return None;
            };
            let points: Vec<Option<[f64; 3]>> = (a.iter().enumerate())
                .map(|(k, v)| as_vec3(ctx, v, &format!("{field}[{k}]")))
                .collect();
            let points: Vec<Vector> = (points.into_iter())
                .map(|p| p.map(Vector::from))
                .collect::<Option<_>>()?;
            (points, Vector::zeros(), field, n.pos)
        }
        Kind3::Box => {
            let center = t.vec3(ctx, "center").req(ctx, t, "center");
            let (size, pos) = t.vec3(ctx, "size").req(ctx, t, "size")?;
            if !size.iter().all(|&s| s > 0.0 && s.is_finite()) {
                let msg = format!("edge lengths must be finite and > 0 m, got {size:?}");
                ctx.err(pos, &t.field("size"), msg);
                return None;
            }
            let half = Vector::from(size) / 2.0;
            let points = ConvexPolyhedron::cuboid(half).vertices;
            (points, Vector::from(center?.0), t.field("size"), pos)
        }
        _ => {
            let center = t.vec3(ctx, "center").req(ctx, t, "center");
            let r = t.num(ctx, "radius").req(ctx, t, "radius");
            let pos = r.map_or(t.pos, |(_, p)| p);
            let r = ensure(
                ctx,
                r,
                &t.field("radius"),
                |v| v > 0.0,
                "> 0 m (circumradius)",
            )?;
            let points = regular(kind).into_iter().map(|p| p * r).collect();
            (points, Vector::from(center?.0), t.field("radius"), pos)
        }
    };
    let orientation = orientation?;
    let (hull, centroid) = match ConvexPolyhedron::hull(&points) {
        Ok(h) => h,
        Err(msg) => {
            ctx.err(pos, &field, msg);
            return None;
        }
    };
    let rotation = Rotation::from_scaled_axis(Vector::from(orientation));
    let position = centre + rotation * centroid;
    Some(Geom3 {
        shape: ShapeDesc3::Polyhedron {
            vertices: hull.vertices.iter().map(|v| [v.x, v.y, v.z]).collect(),
        },
        position: position.into(),
        orientation,
        engine: Shape::Polyhedron(Box::new(hull)),
    })
}

fn mass_inertia(
    ctx: &mut Ctx,
    t: &Tbl,
    mats: &Materials,
    geom: Option<&Geom3>,
) -> Option<(f64, [[f64; 3]; 3])> {
    if t.has("material") && (t.has("mass") || t.has("inertia")) {
        let why = "give either `material` or both `mass` and `inertia`, not both";
        t.forbid(ctx, "mass", why);
        t.forbid(ctx, "inertia", why);
        return None;
    }
    if t.has("material") {
        let name = t.string(ctx, "material").ok();
        let rho = mats.density(ctx, name, &t.field("material"))?;
        let (m, i) = geom?.engine.mass_properties(rho);
        if !(m > 0.0 && m.is_finite() && i.iter().all(|x| x.is_finite()) && i.trace() > 0.0) {
            let msg = format!(
                "mass {m} kg and inertia {i:?} kg m^2 from the material must be finite and > 0"
            );
            ctx.err(t.pos, &t.field("material"), msg);
            return None;
        }
        return Some((m, i.transpose().into()));
    }
    if !t.has("mass") && !t.has("inertia") {
        let why = "missing `material` (or both `mass` and `inertia`)";
        ctx.err(t.pos, &t.field("material"), why);
        return None;
    }
    let m = t.num(ctx, "mass").req(ctx, t, "mass");
    let m = ensure(ctx, m, &t.field("mass"), |v| v > 0.0, "> 0 kg");
    let i = t.vec3(ctx, "inertia").req(ctx, t, "inertia");
    let i = i.and_then(|(i, pos)| {
        if i.iter().all(|&x| x > 0.0 && x.is_finite()) {
            Some(i)
        } else {
            let msg = format!(
                "principal moments [Ixx, Iyy, Izz] must be finite and > 0 kg m^2, got {i:?}"
            );
            ctx.err(pos, &t.field("inertia"), msg);
            None
        }
    });
    let inertia = AngMatrix::from_diagonal(&Vector::from(i?));
    Some((m?, inertia.into()))
}

/// Reads `[[walls]]` (planes) into `built`; the groups of pressure drives' `between` are
/// resolved into `pending` once every body is built ([`crate::pressure::resolve3`]).
pub(crate) fn walls(
    ctx: &mut Ctx,
    root: &Tbl,
    groups: &mut Groups,
    built: &mut Built3,
    pending: &mut Vec<PendingSpan>,
) {
    for (i, t) in root.tables(ctx, "walls") {
        let keys = ["point", "normal", "size", "edge", "group", "drive", "mass"];
        t.check_keys(ctx, &keys);
        let point = t.vec3(ctx, "point").req(ctx, &t, "point");
        let normal = t.vec3(ctx, "normal").req(ctx, &t, "normal");
        let normal = normal.and_then(|(n, pos)| {
            let v = Vector::from(n);
            let length = v.norm();
            if length > 0.0 && length.is_finite() {
                Some(v / length)
            } else {
                let msg = format!("must be a non-zero finite vector, got {n:?}");
                ctx.err(pos, &t.field("normal"), msg);
                None
            }
        });
        let half = match t.vec2(ctx, "size") {
            Got::Absent => Some([f64::INFINITY; 2]),
            Got::Bad => None,
            Got::Val(s, _) if s.iter().all(|&x| x > 0.0 && x.is_finite()) => {
                Some([s[0] / 2.0, s[1] / 2.0])
            }
            Got::Val(s, pos) => {
                let msg = format!("edge lengths must be finite and > 0 m, got {s:?}");
                ctx.err(pos, &t.field("size"), msg);
                None
            }
        };
        let edge = t.vec3(ctx, "edge");
        let group = t
            .string(ctx, "group")
            .req(ctx, &t, "group")
            .map(|(g, _)| groups.index(g));
        let mass = match t.num(ctx, "mass") {
            Got::Absent => Some(None),
            Got::Bad => None,
            Got::Val(m, pos) => {
                ensure(ctx, Some((m, pos)), &t.field("mass"), |m| m > 0.0, "> 0 kg").map(Some)
            }
        };
        let (Some((point, _)), Some(n), Some(half), Some(mass)) = (point, normal, half, mass)
        else {
            continue;
        };
        let e1 = match edge {
            Got::Absent => tangents(&n)[0],
            Got::Bad => continue,
            Got::Val(e, pos) => {
                let e = Vector::from(e);
                let along = e - n * n.dot(&e);
                if !(along.norm() > 1e-9 * e.norm()) {
                    let msg = format!(
                        "must not be parallel to the normal, got {:?}",
                        [e.x, e.y, e.z]
                    );
                    ctx.err(pos, &t.field("edge"), msg);
                    continue;
                }
                along.normalize()
            }
        };
        let frame = WallFrame3 {
            body: built.bodies.len(),
            normal: n.into(),
            size: half.map(|h| 2.0 * h),
        };
        let spans_before = pending.len();
        let mut read = |ctx: &mut Ctx, dof: usize, e: &Tbl| {
            crate::pressure::read3(ctx, dof, e, &frame, pending)
        };
        let driven = match mass {
            Some(_) => Driven::MassiveWall,
            None => Driven::Wall,
        };
        let drive = match t.table(ctx, "drive") {
            Got::Absent => Some(std::array::from_fn(|_| None)),
            Got::Bad => None,
            Got::Val(d, pos) => {
                let drive = drives_of(ctx, &d, driven, DOFS3, Some(&mut read));
                let turned = |d: &Option<Drive>| matches!(d, Some(Drive::Force(_)));
                let half_space = half.iter().any(|h| h.is_infinite());
                if let Some(k) = (drive.iter().flat_map(|d| d[3..].iter()))
                    .position(turned)
                    .filter(|_| half_space)
                {
                    let why = format!(
                        "`{}`: a half-space has an infinite moment of inertia, so a force \
                         cannot turn it; give the wall a `size` or drive the rotation by \
                         `velocity`",
                        DOFS3[3 + k]
                    );
                    ctx.err(pos, &t.field("drive"), why);
                    pending.truncate(spans_before);
                    continue;
                }
                drive
            }
        };
        let (Some(group), Some(drive)) = (group, drive) else {
            // Not built: its `between` would name a body that is not this wall.
            pending.truncate(spans_before);
            continue;
        };
        let mut wall = wall_body(point, n, e1, half, group);
        if let Some(m) = mass {
            wall.mass = m;
            wall.inertia = plate_inertia(m, half);
        }
        for (slot, d) in wall.drives.iter_mut().zip(drive) {
            if let Some(d) = d {
                *slot = d;
            }
        }
        let origin = Origin {
            section: "walls",
            index: i,
            part: Part::Whole,
            pos: t.pos,
        };
        built.push(wall, origin);
    }
}

/// The inertia tensor (kg m^2, body frame) of a thin rectangular plate of mass `m` (kg) and
/// half-extents `half` (m) along the body's x and y axes, about its centre:
/// `diag(m b^2, m a^2, m (a^2 + b^2)) / 12` with `a`, `b` its edge lengths; infinite for a
/// half-space (its rotations then stay imposed unless driven by a velocity).
fn plate_inertia(m: f64, half: [f64; 2]) -> [[f64; 3]; 3] {
    if half.iter().any(|h| h.is_infinite()) {
        return [[f64::INFINITY; 3]; 3];
    }
    let [a, b] = half.map(|h| 2.0 * h);
    let d = [b * b, a * a, a * a + b * b].map(|x| m * x / 12.0);
    std::array::from_fn(|r| std::array::from_fn(|c| if r == c { d[r] } else { 0.0 }))
}

/// A fixed planar wall through `point` with unit `normal`, its first edge along the unit
/// in-plane `edge`, of half-extents `half` (m; infinite for a half-space).
pub(crate) fn wall_body(
    point: [f64; 3],
    normal: Vector,
    edge: Vector,
    half: [f64; 2],
    group: usize,
) -> BodyDesc3 {
    let frame = nalgebra::Matrix3::from_columns(&[edge, normal.cross(&edge), normal]);
    let rotation =
        Rotation::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(frame));
    BodyDesc3 {
        shape: ShapeDesc3::Plane { half_extents: half },
        position: point,
        orientation: rotation.scaled_axis().into(),
        velocity: [0.0; 3],
        angular_velocity: [0.0; 3],
        mass: f64::INFINITY,
        inertia: [[f64::INFINITY; 3]; 3],
        group,
        drives: std::array::from_fn(|_| Drive::Velocity(TimeFunction::Constant(0.0))),
    }
}
