//! Pressure drives of walls with a mass (servo walls): `drive.<dof> = { pressure = p,
//! between = ["bottom", "top"] }` in 2D, `between = [["ymin", "ymax"], ["bottom", "top"]]`
//! in 3D.
//!
//! The wall is pushed along its normal by the force `p A n_d` on the driven translation, with
//! `A` its loaded extent measured at the beginning of each step:
//!
//! - 2D: the distance between the two walls `between` names (one body per group), along the
//!   wall, or the wall's own length;
//! - 3D: the product of two such distances, each between the walls of one pair and measured
//!   along the normal of the pair's first wall (which must lie in the driven wall's plane),
//!   or the wall's own area `a b`.
//!
//! This is the servo-controlled boundary of a biaxial or triaxial test at constant confining
//! pressure (e.g. LMGC90's examples, where the same force is recomputed from the sample's
//! current dimensions).

use crate::read::{Ctx, Tbl};
use crate::shared::{Built, Groups};
use crate::tree::{Kind, Node, Pos};
use crate::types::{BodyDesc, Drive, ExtentDesc, PressureDesc};
use crate::types3d::{BodyDesc3, ShapeDesc3};

/// A `between` whose groups are resolved to bodies once every body is built.
pub(crate) struct PendingSpan {
    /// The index of the driven wall in the scene's bodies.
    pub body: usize,
    /// The driven degree of freedom.
    pub dof: usize,
    /// The pairs of group names: one in 2D, two in 3D.
    pub pairs: Vec<[String; 2]>,
    /// Where `between` is.
    pub pos: Pos,
    /// Its field path.
    pub field: String,
}

/// The wall a pressure drives: its index among the bodies, unit normal (the push direction),
/// unit direction along it and length (m).
pub(crate) struct WallFrame {
    pub body: usize,
    pub normal: [f64; 2],
    pub along: [f64; 2],
    pub length: f64,
}

/// The wall a 3D pressure drives: its index among the bodies, unit normal (the push
/// direction) and full edge lengths (m; infinite for a half-space).
pub(crate) struct WallFrame3 {
    pub body: usize,
    pub normal: [f64; 3],
    pub size: [f64; 2],
}

/// The pressure of a `{ pressure = ..., between = ... }` entry and the push direction's
/// component `n_d` on degree of freedom `dof`, given the wall's unit `normal`.
fn pressure_and_direction(
    ctx: &mut Ctx,
    dof: usize,
    e: &Tbl,
    normal: &[f64],
    translations: &str,
) -> Option<(crate::types::TimeFunction, f64)> {
    e.check_keys(ctx, &["pressure", "between"]);
    let p = e.get("pressure")?;
    let pressure = crate::bodies::time_function(ctx, p, &e.field("pressure"));
    let Some(&direction) = normal.get(dof) else {
        let why = format!("a pressure drives a translation ({translations}), not a rotation");
        ctx.err(p.pos, &e.field("pressure"), why);
        return None;
    };
    if direction.abs() < 1e-12 {
        let why = format!(
            "the wall's normal {normal:?} has no component along this degree of freedom: the \
             pressure cannot push it this way"
        );
        ctx.err(p.pos, &e.field("pressure"), why);
        return None;
    }
    Some((pressure?, direction))
}

/// Two group names `["a", "b"]`, or `None` (nothing reported).
fn pair(n: &Node) -> Option<[String; 2]> {
    match &n.kind {
        Kind::Array(a) if a.len() == 2 => {
            let name = |k: usize| match &a[k].kind {
                Kind::Str(s) => Some(s.clone()),
                _ => None,
            };
            name(0).zip(name(1)).map(|(a, b)| [a, b])
        }
        _ => None,
    }
}

/// Reads a `{ pressure = ..., between = [a, b] }` entry for degree of freedom `dof` of a 2D
/// `wall`.
pub(crate) fn read(
    ctx: &mut Ctx,
    dof: usize,
    e: &Tbl,
    wall: &WallFrame,
    pending: &mut Vec<PendingSpan>,
) -> Option<Drive> {
    let (pressure, direction) = pressure_and_direction(ctx, dof, e, &wall.normal, "`x` or `y`")?;
    let extent = match e.get("between") {
        None => ExtentDesc::Fixed(wall.length),
        Some(n) => {
            let field = e.field("between");
            let Some(names) = pair(n) else {
                ctx.expected(n, &field, "two group names, e.g. [\"bottom\", \"top\"]");
                return None;
            };
            pending.push(PendingSpan {
                body: wall.body,
                dof,
                pairs: vec![names],
                pos: n.pos,
                field,
            });
            ExtentDesc::Between {
                bodies: [usize::MAX; 2],
                axis: [wall.along[0], wall.along[1], 0.0],
            }
        }
    };
    Some(Drive::Pressure(PressureDesc {
        pressure,
        direction,
        extent: vec![extent],
    }))
}

/// Reads a `{ pressure = ..., between = [[a, b], [c, d]] }` entry for degree of freedom
/// `dof` of a 3D `wall`; the axes of the two distances are set by [`resolve3`].
pub(crate) fn read3(
    ctx: &mut Ctx,
    dof: usize,
    e: &Tbl,
    wall: &WallFrame3,
    pending: &mut Vec<PendingSpan>,
) -> Option<Drive> {
    let translations = "`x`, `y` or `z`";
    let (pressure, direction) = pressure_and_direction(ctx, dof, e, &wall.normal, translations)?;
    let extent = match e.get("between") {
        None if wall.size.iter().all(|a| a.is_finite()) => wall.size.map(ExtentDesc::Fixed),
        None => {
            let why = "a half-space has no area: give `between = [[\"a\", \"b\"], [\"c\", \
                       \"d\"]]` (the loaded area is the product of the distances between the \
                       walls of each pair) or the wall's `size`";
            ctx.err(e.pos, &e.field("between"), why);
            return None;
        }
        Some(n) => {
            let field = e.field("between");
            let pairs = match &n.kind {
                Kind::Array(a) if a.len() == 2 => pair(&a[0]).zip(pair(&a[1])),
                _ => None,
            };
            let Some((first, second)) = pairs else {
                let what = "two pairs of group names, e.g. [[\"ymin\", \"ymax\"], [\"bottom\", \
                            \"top\"]]";
                ctx.expected(n, &field, what);
                return None;
            };
            pending.push(PendingSpan {
                body: wall.body,
                dof,
                pairs: vec![first, second],
                pos: n.pos,
                field,
            });
            let unresolved = ExtentDesc::Between {
                bodies: [usize::MAX; 2],
                axis: [0.0; 3],
            };
            [unresolved.clone(), unresolved]
        }
    };
    Some(Drive::Pressure(PressureDesc {
        pressure,
        direction,
        extent: extent.to_vec(),
    }))
}

/// The one body of group `name` (reported, with `None`, when it holds none or several).
fn one_body<B>(
    ctx: &mut Ctx,
    groups: &Groups,
    bodies: &[B],
    group_of: impl Fn(&B) -> usize,
    name: &str,
    span: &PendingSpan,
) -> Option<usize> {
    let members: Vec<usize> = match groups.find(name) {
        Some(g) => (bodies.iter().enumerate())
            .filter(|(_, b)| group_of(b) == g)
            .map(|(k, _)| k)
            .take(2)
            .collect(),
        None => Vec::new(),
    };
    match members[..] {
        [k] => Some(k),
        [] => {
            ctx.err(
                span.pos,
                &span.field,
                format!("no body is in group `{name}`"),
            );
            None
        }
        _ => {
            let why = format!(
                "group `{name}` holds more than one body: `between` names groups of one wall \
                 each (the loaded extent is the distance between them)"
            );
            ctx.err(span.pos, &span.field, why);
            None
        }
    }
}

/// Resolves the groups of every 2D `between` to their one body each.
pub(crate) fn resolve(
    ctx: &mut Ctx,
    groups: &Groups,
    built: &mut Built,
    pending: Vec<PendingSpan>,
) {
    for span in pending {
        let group = |b: &BodyDesc| b.group;
        let [a, b] = &span.pairs[0];
        let found = [a, b].map(|name| one_body(ctx, groups, &built.bodies, group, name, &span));
        let bodies = found.map(|k| k.unwrap_or(usize::MAX));
        if let Drive::Pressure(p) = &mut built.bodies[span.body].drives[span.dof] {
            for f in &mut p.extent {
                if let ExtentDesc::Between { bodies: b, .. } = f {
                    *b = bodies;
                }
            }
        }
    }
}

/// The unit normal of a 3D wall (its body z axis), `None` for other bodies.
fn wall_normal(b: &BodyDesc3) -> Option<[f64; 3]> {
    if !matches!(b.shape, ShapeDesc3::Plane { .. }) {
        return None;
    }
    let r = xper_math3d::Rotation::from_scaled_axis(xper_math3d::Vector::from(b.orientation));
    Some((r * xper_math3d::Vector::z()).into())
}

/// Resolves every 3D `between`: each pair's two bodies, and the axis its distance is measured
/// along, the normal of the pair's first wall. That wall must lie across the driven wall (its
/// normal in the driven wall's plane), the two axes must differ, and the walls of a pair must
/// be apart along their axis.
pub(crate) fn resolve3(
    ctx: &mut Ctx,
    groups: &Groups,
    built: &mut Built<BodyDesc3>,
    pending: Vec<PendingSpan>,
) {
    for span in pending {
        let group = |b: &BodyDesc3| b.group;
        let wall = wall_normal(&built.bodies[span.body]).unwrap_or([0.0; 3]);
        let mut factors = Vec::new();
        for (k, [a, b]) in span.pairs.iter().enumerate() {
            let found = [a, b].map(|name| one_body(ctx, groups, &built.bodies, group, name, &span));
            let [Some(first), Some(second)] = found else {
                continue;
            };
            let Some(axis) = wall_normal(&built.bodies[first]) else {
                let why = format!(
                    "between[{k}]: the body of group `{a}` is not a wall: the distance of a pair \
                     is measured along the normal of its first wall"
                );
                ctx.err(span.pos, &span.field, why);
                continue;
            };
            let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            if dot(axis, wall).abs() > 1e-9 {
                let why = format!(
                    "between[{k}]: the wall of group `{a}` faces along {axis:?}, which does not \
                     lie in the plane of the driven wall (normal {wall:?}): its distance to \
                     `{b}` would not be an edge of the loaded area"
                );
                ctx.err(span.pos, &span.field, why);
                continue;
            }
            let [pa, pb] = [first, second].map(|i| built.bodies[i].position);
            let apart = dot([pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]], axis).abs();
            if !(apart > 0.0) {
                let why = format!(
                    "between[{k}]: the bodies of groups `{a}` and `{b}` are 0 m apart along \
                     {axis:?}, the normal of `{a}`: the loaded area would be 0"
                );
                ctx.err(span.pos, &span.field, why);
                continue;
            }
            factors.push(ExtentDesc::Between {
                bodies: [first, second],
                axis,
            });
        }
        if let [ExtentDesc::Between { axis: u, .. }, ExtentDesc::Between { axis: v, .. }] =
            &factors[..]
        {
            let cos = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            if cos.abs() > 1.0 - 1e-9 {
                let why = format!(
                    "the two pairs are measured along the same axis {u:?}: give one pair across \
                     each edge of the wall"
                );
                ctx.err(span.pos, &span.field, why);
            }
        }
        if let Drive::Pressure(p) = &mut built.bodies[span.body].drives[span.dof] {
            if factors.len() == p.extent.len() {
                p.extent = factors;
            }
        }
    }
}
