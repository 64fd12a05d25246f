//! Readers for `[[bodies]]` and `[[walls]]`, drives and time functions.

use std::f64::consts::PI;

use crate::geometry::{self, norm, sub};
use crate::pressure::{PendingSpan, WallFrame};
use crate::read::{as_num, as_vec2, choose, ensure, Ctx, Got, Tbl};
use crate::shared::{Built, Groups, Materials, Origin, Part};
use crate::tree::{Kind, Node};
use crate::types::{BodyDesc, Drive, ShapeDesc, TimeFunction};

const BODY_KEYS: &[&str] = &[
    "shape",
    "center",
    "radius",
    "vertices",
    "size",
    "angle",
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
enum ShapeKind {
    Disk,
    Polygon,
    Rectangle,
}

/// Reads `[[bodies]]` into `built`.
pub(crate) fn bodies(
    ctx: &mut Ctx,
    root: &Tbl,
    mats: &Materials,
    groups: &mut Groups,
    built: &mut Built,
) {
    read_bodies(ctx, root, built, |ctx, t| body(ctx, t, mats, groups));
}

/// Reads every `[[bodies]]` entry with `body` (2D or 3D) into `built`.
pub(crate) fn read_bodies<B>(
    ctx: &mut Ctx,
    root: &Tbl,
    built: &mut crate::shared::Built<B>,
    mut body: impl FnMut(&mut Ctx, &Tbl) -> Option<B>,
) {
    for (i, t) in root.tables(ctx, "bodies") {
        if let Some(b) = body(ctx, &t) {
            let origin = Origin {
                section: "bodies",
                index: i,
                part: Part::Whole,
                pos: t.pos,
            };
            built.push(b, origin);
        }
    }
}

/// Geometry of a body: shape, position, area and second moment of area.
struct Geom {
    shape: ShapeDesc,
    position: [f64; 2],
    area: f64,
    second_moment: f64,
}

fn body(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<BodyDesc> {
    t.check_keys(ctx, BODY_KEYS);
    let shapes = [
        ("disk", ShapeKind::Disk),
        ("polygon", ShapeKind::Polygon),
        ("rectangle", ShapeKind::Rectangle),
    ];
    let shape_got = t.string(ctx, "shape").req(ctx, t, "shape");
    let shape = choose(ctx, shape_got, &t.field("shape"), "shape", &shapes);
    let geom = match shape {
        Some(kind) => geom(ctx, t, kind),
        None => None,
    };
    let angle = t.num(ctx, "angle").or(0.0);
    let mass_inertia = mass_inertia(ctx, t, mats, geom.as_ref());
    let group = t
        .string(ctx, "group")
        .req(ctx, t, "group")
        .map(|(g, _)| groups.index(g));
    let velocity = t.vec2(ctx, "velocity").or([0.0, 0.0]);
    let angular_velocity = t.num(ctx, "angular_velocity").or(0.0);
    let fixed = t.boolean(ctx, "fixed").or(false);
    let drive = match t.table(ctx, "drive") {
        Got::Absent => Some([None, None, None]),
        Got::Bad => None,
        Got::Val(d, pos) => {
            if fixed == Some(true) {
                ctx.err(
                    pos,
                    &t.field("drive"),
                    "`drive` cannot be combined with `fixed = true`",
                );
            }
            drives(ctx, &d, Driven::Body)
        }
    };
    let (geom, (mass, inertia), group) = (geom?, mass_inertia?, group?);
    let drives = if fixed? {
        std::array::from_fn(|_| Drive::Velocity(TimeFunction::Constant(0.0)))
    } else {
        drive?.map(|d| d.unwrap_or(Drive::Free))
    };
    Some(BodyDesc {
        shape: geom.shape,
        position: geom.position,
        angle: angle?,
        velocity: velocity?,
        angular_velocity: angular_velocity?,
        mass,
        inertia,
        group,
        drives,
    })
}

fn geom(ctx: &mut Ctx, t: &Tbl, kind: ShapeKind) -> Option<Geom> {
    let name = match kind {
        ShapeKind::Disk => "disk",
        ShapeKind::Polygon => "polygon",
        ShapeKind::Rectangle => "rectangle",
    };
    let unused = |key: &str| format!("`{key}` is not used by shape `{name}`");
    let forbidden: &[&str] = match kind {
        ShapeKind::Disk => &["vertices", "size"],
        ShapeKind::Polygon => &["center", "radius", "size"],
        ShapeKind::Rectangle => &["radius", "vertices"],
    };
    for key in forbidden {
        t.forbid(ctx, key, &unused(key));
    }
    match kind {
        ShapeKind::Disk => {
            let center = t.vec2(ctx, "center").req(ctx, t, "center");
            let r = t.num(ctx, "radius").req(ctx, t, "radius");
            let r = ensure(ctx, r, &t.field("radius"), |v| v > 0.0, "> 0 m")?;
            Some(Geom {
                shape: ShapeDesc::Disk { radius: r },
                position: center?.0,
                area: PI * r * r,
                second_moment: PI * r * r * r * r / 2.0,
            })
        }
        ShapeKind::Rectangle => {
            let center = t.vec2(ctx, "center").req(ctx, t, "center");
            let size = t.vec2(ctx, "size").req(ctx, t, "size");
            let (size, pos) = size?;
            if !(size[0] > 0.0 && size[1] > 0.0) {
                ctx.err(
                    pos,
                    &t.field("size"),
                    format!("width and height must be > 0 m, got {size:?}"),
                );
                return None;
            }
            let [w, h] = size;
            let area = w * h;
            Some(Geom {
                shape: ShapeDesc::Polygon {
                    vertices: geometry::rectangle(w, h),
                },
                position: center?.0,
                area,
                second_moment: area * (w * w + h * h) / 12.0,
            })
        }
        ShapeKind::Polygon => {
            t.forbid(
                ctx,
                "angle",
                "`angle` is not used by shape `polygon`: its vertices are absolute",
            );
            let field = t.field("vertices");
            let Some(n) = t.get("vertices") else {
                t.missing(ctx, "vertices");
                return None;
            };
            let Kind::Array(a) = &n.kind else {
                ctx.expected(n, &field, "an array of [x, y] vertices");
                return None;
            };
            let verts: Vec<Option<[f64; 2]>> = a
                .iter()
                .enumerate()
                .map(|(k, v)| as_vec2(ctx, v, &format!("{field}[{k}]")))
                .collect();
            let verts: Vec<[f64; 2]> = verts.into_iter().collect::<Option<_>>()?;
            match geometry::polygon(&verts) {
                Ok(p) => Some(Geom {
                    shape: ShapeDesc::Polygon { vertices: p.rel },
                    position: p.centroid,
                    area: p.area,
                    second_moment: p.second_moment,
                }),
                Err(msg) => {
                    ctx.err(n.pos, &field, msg);
                    None
                }
            }
        }
    }
}

fn mass_inertia(
    ctx: &mut Ctx,
    t: &Tbl,
    mats: &Materials,
    geom: Option<&Geom>,
) -> Option<(f64, f64)> {
    let has_material = t.has("material");
    if has_material && (t.has("mass") || t.has("inertia")) {
        let why = "give either `material` or both `mass` and `inertia`, not both";
        t.forbid(ctx, "mass", why);
        t.forbid(ctx, "inertia", why);
        return None;
    }
    if has_material {
        let name = t.string(ctx, "material").ok();
        let rho = mats.density(ctx, name, &t.field("material"))?;
        let g = geom?;
        let (m, i) = (rho * g.area, rho * g.second_moment);
        if !(m > 0.0 && m.is_finite() && i > 0.0 && i.is_finite()) {
            let msg = format!(
                "mass {m} kg and inertia {i} kg m^2 from the material must be finite and > 0"
            );
            ctx.err(t.pos, &t.field("material"), msg);
            return None;
        }
        return Some((m, i));
    }
    if !t.has("mass") && !t.has("inertia") {
        ctx.err(
            t.pos,
            &t.field("material"),
            "missing `material` (or both `mass` and `inertia`)",
        );
        return None;
    }
    let m = t.num(ctx, "mass").req(ctx, t, "mass");
    let m = ensure(ctx, m, &t.field("mass"), |v| v > 0.0, "> 0 kg");
    let i = t.num(ctx, "inertia").req(ctx, t, "inertia");
    let i = ensure(ctx, i, &t.field("inertia"), |v| v > 0.0, "> 0 kg m^2");
    Some((m?, i?))
}

/// What a `drive` table may hold, by the kind of body it drives.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Driven {
    /// A body: velocity or force.
    Body,
    /// A wall without a mass: velocity only.
    Wall,
    /// A wall with a mass: velocity, force, or (on a translation) a pressure.
    MassiveWall,
    /// The bodies of a group from an `[[events]]` entry: velocity or force.
    Event,
}

/// A pressure entry of a `drive` table, read by the wall's reader (which knows its normal).
pub(crate) type PressureReader<'r> = dyn FnMut(&mut Ctx, usize, &Tbl) -> Option<Drive> + 'r;

/// Reads a 2D body's `drive` table: per dof (`x`, `y`, `rotation`), `None` when not driven.
pub(crate) fn drives(ctx: &mut Ctx, d: &Tbl, driven: Driven) -> Option<[Option<Drive>; 3]> {
    drives_of(ctx, d, driven, ["x", "y", "rotation"], None)
}

/// Reads a `drive` table whose degrees of freedom are named `dofs`; `pressure` reads the
/// entries with a `pressure` key (walls with a mass only).
pub(crate) fn drives_of<const N: usize>(
    ctx: &mut Ctx,
    d: &Tbl,
    driven: Driven,
    dofs: [&str; N],
    mut pressure: Option<&mut PressureReader>,
) -> Option<[Option<Drive>; N]> {
    d.check_keys(ctx, &dofs);
    let mut out: [Option<Drive>; N] = std::array::from_fn(|_| None);
    let mut ok = true;
    for (k, dof) in dofs.iter().enumerate() {
        let e = match d.table(ctx, dof) {
            Got::Absent => continue,
            Got::Bad => {
                ok = false;
                continue;
            }
            Got::Val(e, _) => e,
        };
        if let Some(p) = e.get("pressure") {
            let drive = match (driven, pressure.as_mut()) {
                (Driven::MassiveWall, Some(read)) => read(ctx, k, &e),
                (Driven::Body, _) => {
                    let why = "a pressure drives a wall with a `mass` (it needs the wall's normal \
                               and length); drive a body by a `force`";
                    ctx.err(p.pos, &e.field("pressure"), why);
                    None
                }
                (Driven::Event, _) => {
                    let why = "an event sets velocity or force drives; give a pressure in the \
                               wall's own `drive` (walls with a `mass`)";
                    ctx.err(p.pos, &e.field("pressure"), why);
                    None
                }
                _ => {
                    let why = "a wall is driven by a pressure only when it has a `mass` (kg, per \
                               m of thickness in 2D; walls without one have an infinite mass)";
                    ctx.err(p.pos, &e.field("pressure"), why);
                    None
                }
            };
            ok &= drive.is_some();
            out[k] = drive;
            continue;
        }
        e.check_keys(ctx, &["velocity", "force"]);
        let drive = match (e.get("velocity"), e.get("force")) {
            (Some(v), None) => time_function(ctx, v, &e.field("velocity")).map(Drive::Velocity),
            (None, Some(f)) if driven == Driven::Wall => {
                let why = "a wall without a `mass` cannot be driven by a force (its mass is \
                           infinite); give it a `mass` (kg, per m of thickness in 2D) or use \
                           `velocity`";
                ctx.err(f.pos, &e.field("force"), why);
                None
            }
            (None, Some(f)) => time_function(ctx, f, &e.field("force")).map(Drive::Force),
            (Some(_), Some(f)) => {
                ctx.err(
                    f.pos,
                    &e.field("force"),
                    "give either `velocity` or `force`, not both",
                );
                None
            }
            (None, None) => {
                ctx.err(e.pos, &e.field("velocity"), "missing `velocity` or `force`");
                None
            }
        };
        ok &= drive.is_some();
        out[k] = drive;
    }
    ok.then_some(out)
}

/// Reads a time function: a number, an array of `[t, value]` points, or `{ sine = {...} }`.
pub(crate) fn time_function(ctx: &mut Ctx, n: &Node, field: &str) -> Option<TimeFunction> {
    match &n.kind {
        Kind::Int(_) | Kind::Float(_) => as_num(ctx, n, field).map(TimeFunction::Constant),
        Kind::Array(a) => {
            if a.is_empty() {
                ctx.err(n.pos, field, "a table needs at least one [t, value] point");
                return None;
            }
            let mut points = Vec::with_capacity(a.len());
            let mut ok = true;
            for (k, e) in a.iter().enumerate() {
                let f = format!("{field}[{k}]");
                let Some([tk, v]) = as_vec2(ctx, e, &f) else {
                    ok = false;
                    continue;
                };
                if let Some(&(prev, _)) = points.last() {
                    if !(tk > prev) {
                        ctx.err(
                            e.pos,
                            &f,
                            format!("times must be strictly increasing: {tk} s after {prev} s"),
                        );
                        ok = false;
                    }
                }
                points.push((tk, v));
            }
            ok.then_some(TimeFunction::Table(points))
        }
        Kind::Table(_) => {
            let t = Tbl::of(ctx, n, field.to_string())?;
            t.check_keys(ctx, &["sine"]);
            let s = t.table(ctx, "sine").req(ctx, &t, "sine")?.0;
            s.check_keys(ctx, &["amplitude", "frequency", "phase", "offset"]);
            let amplitude = s.num(ctx, "amplitude").req(ctx, &s, "amplitude");
            let f = s.num(ctx, "frequency").req(ctx, &s, "frequency");
            let frequency = ensure(ctx, f, &s.field("frequency"), |v| v >= 0.0, ">= 0 Hz");
            let phase = s.num(ctx, "phase").or(0.0);
            let offset = s.num(ctx, "offset").or(0.0);
            Some(TimeFunction::Sine {
                amplitude: amplitude?.0,
                frequency: frequency?,
                phase: phase?,
                offset: offset?,
            })
        }
        _ => {
            ctx.expected(
                n,
                field,
                "a number, an array of [t, value] points or { sine = {...} }",
            );
            None
        }
    }
}

/// A wall from `from` to `to` (distinct), all dofs imposed at velocity 0.
pub(crate) fn wall_body(from: [f64; 2], to: [f64; 2], group: usize) -> BodyDesc {
    let d = sub(to, from);
    BodyDesc {
        shape: ShapeDesc::Segment {
            half_length: norm(d) / 2.0,
        },
        position: [(from[0] + to[0]) / 2.0, (from[1] + to[1]) / 2.0],
        angle: d[1].atan2(d[0]),
        velocity: [0.0, 0.0],
        angular_velocity: 0.0,
        mass: f64::INFINITY,
        inertia: f64::INFINITY,
        group,
        drives: std::array::from_fn(|_| Drive::Velocity(TimeFunction::Constant(0.0))),
    }
}

/// Reads `[[walls]]` into `built`; the groups of pressure drives' `between` are resolved
/// into `pending` once every body is built ([`crate::pressure::resolve`]).
pub(crate) fn walls(
    ctx: &mut Ctx,
    root: &Tbl,
    groups: &mut Groups,
    built: &mut Built,
    pending: &mut Vec<PendingSpan>,
) {
    for (i, t) in root.tables(ctx, "walls") {
        t.check_keys(ctx, &["from", "to", "group", "drive", "mass"]);
        let from = t.vec2(ctx, "from").req(ctx, &t, "from");
        let to = t.vec2(ctx, "to").req(ctx, &t, "to");
        let group = t
            .string(ctx, "group")
            .req(ctx, &t, "group")
            .map(|(g, _)| groups.index(g));
        let mass = match t.num(ctx, "mass") {
            Got::Absent => Some(None),
            Got::Bad => None,
            Got::Val(m, pos) => {
                let what = "positive (kg per m of thickness)";
                ensure(ctx, Some((m, pos)), &t.field("mass"), |m| m > 0.0, what).map(Some)
            }
        };
        let (Some((from, _)), Some((to, to_pos))) = (from, to) else {
            continue;
        };
        let length = norm(sub(to, from));
        if !length.is_finite() {
            ctx.err(
                to_pos,
                &t.field("to"),
                format!("wall length must be finite, from {from:?} to {to:?}"),
            );
            continue;
        }
        if !(length > 0.0) {
            ctx.err(
                to_pos,
                &t.field("to"),
                format!("`to` must differ from `from`, both are {from:?}"),
            );
            continue;
        }
        let Some(mass) = mass else {
            continue;
        };
        let along = [(to[0] - from[0]) / length, (to[1] - from[1]) / length];
        let frame = WallFrame {
            body: built.bodies.len(),
            normal: [-along[1], along[0]],
            along,
            length,
        };
        let driven = if mass.is_some() {
            Driven::MassiveWall
        } else {
            Driven::Wall
        };
        let spans_before = pending.len();
        let mut read = |ctx: &mut Ctx, dof: usize, e: &Tbl| {
            crate::pressure::read(ctx, dof, e, &frame, pending)
        };
        let drive = match t.table(ctx, "drive") {
            Got::Absent => Some([None, None, None]),
            Got::Bad => None,
            Got::Val(d, _) => drives_of(ctx, &d, driven, ["x", "y", "rotation"], Some(&mut read)),
        };
        let (Some(group), Some(drive)) = (group, drive) else {
            // Not built: its `between` would name a body that is not this wall.
            pending.truncate(spans_before);
            continue;
        };
        let mut b = wall_body(from, to, group);
        if let Some(m) = mass {
            // A rod of length L about its centre: I = m L^2 / 12 (its rotation stays imposed
            // unless driven).
            (b.mass, b.inertia) = (m, m * length * length / 12.0);
        }
        for (slot, d) in b.drives.iter_mut().zip(drive) {
            if let Some(d) = d {
                *slot = d;
            }
        }
        built.push(
            b,
            Origin {
                section: "walls",
                index: i,
                part: Part::Whole,
                pos: t.pos,
            },
        );
    }
}
