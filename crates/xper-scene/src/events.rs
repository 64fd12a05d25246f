//! `[[events]]`: changes of drives and friction coefficients at given times, the stages of a
//! staged test. For instance a biaxial test, whose sample is first compacted without
//! friction by servo walls and then sheared with friction by a wall at an imposed velocity:
//!
//! ```toml
//! [[events]]
//! time = 0.6   # s
//! friction = [{ between = ["grains", "grains"], value = 0.5 }]
//! drives = [{ group = "top", drive = { y = { velocity = -0.02 } } }]
//! ```
//!
//! In 3D scenes the drives' degrees of freedom are `x`, `y`, `z`, `rx`, `ry`, `rz`. In a scene
//! with a `[cell]`, `cell = { zz = { rate = -0.05 } }` changes the control of the cell's
//! components given (`rate` in 1/s or `stress` in Pa, as in `[cell]`): a triaxial test
//! compacts the cell under an isotropic stress, then imposes the axial strain rate.

use crate::bodies::{drives_of, Driven};
use crate::read::{as_num, Ctx, Got, Tbl};
use crate::sections::between;
use crate::shared::{Built, Groups};
use crate::tree::Kind;
use crate::types::{BodyDesc, CellDesc, Drive, EventDesc, LawDesc};
use crate::types3d::BodyDesc3;

/// What an event needs to know of a body: its group, its mass, and whether its rotations
/// have a finite inertia.
pub(crate) trait EventBody {
    /// Index of the body's group.
    fn group(&self) -> usize;
    /// Mass in kg (kg per m in 2D), infinite for walls without one.
    fn mass(&self) -> f64;
    /// Whether a torque can turn it (false for walls without a mass, and for half-spaces).
    fn turns(&self) -> bool;
}

impl EventBody for BodyDesc {
    fn group(&self) -> usize {
        self.group
    }
    fn mass(&self) -> f64 {
        self.mass
    }
    fn turns(&self) -> bool {
        self.inertia.is_finite()
    }
}

impl EventBody for BodyDesc3 {
    fn group(&self) -> usize {
        self.group
    }
    fn mass(&self) -> f64 {
        self.mass
    }
    fn turns(&self) -> bool {
        self.inertia.iter().flatten().all(|i| i.is_finite())
    }
}

/// The scene an event changes: its groups, bodies, laws, drives' degrees of freedom (`N`
/// names) and periodic cell of dimension `D`.
pub(crate) struct EventScene<'a, const D: usize, const N: usize, B> {
    pub groups: &'a Groups,
    pub built: &'a Built<B>,
    pub laws: &'a [LawDesc],
    pub dofs: [&'static str; N],
    pub cell: Option<&'a CellDesc<D>>,
}

/// Reads `[[events]]`, sorted by time (stable: events at the same time keep their order).
pub(crate) fn events<const D: usize, const N: usize, B: EventBody>(
    ctx: &mut Ctx,
    root: &Tbl,
    scene: EventScene<D, N, B>,
) -> Vec<EventDesc> {
    let EventScene {
        groups,
        built,
        laws,
        dofs,
        cell,
    } = scene;
    let mut out = Vec::new();
    for (_, t) in root.tables(ctx, "events") {
        t.check_keys(ctx, &["time", "friction", "drives", "cell"]);
        let time = match t.num(ctx, "time").req(ctx, &t, "time") {
            Some((v, _)) if v >= 0.0 => Some(v),
            Some((v, pos)) => {
                ctx.err(pos, &t.field("time"), format!("must be >= 0 (s), got {v}"));
                None
            }
            None => None,
        };
        let frictions = frictions(ctx, &t, groups, laws);
        let drives = drives(ctx, &t, groups, built, dofs);
        let cell = crate::cell::event_loads(ctx, &t, cell);
        if let (Some(time), Some(frictions), Some(drives), Some(cell)) =
            (time, frictions, drives, cell)
        {
            out.push(EventDesc {
                time,
                frictions,
                drives,
                cell,
            });
        }
    }
    out.sort_by(|a: &EventDesc, b| a.time.total_cmp(&b.time));
    out
}

/// The entries of an array of tables `key` of `t`.
fn entries<'a>(ctx: &mut Ctx, t: &Tbl<'a>, key: &str) -> Option<Vec<Tbl<'a>>> {
    let Some(n) = t.get(key) else {
        return Some(Vec::new());
    };
    let Kind::Array(items) = &n.kind else {
        ctx.expected(n, &t.field(key), "an array of tables");
        return None;
    };
    let field = t.field(key);
    (items.iter().enumerate())
        .map(|(k, e)| Tbl::of(ctx, e, format!("{field}[{k}]")))
        .collect()
}

/// `friction = [{ between = [a, b], value = mu }, ...]`: the law between `a` and `b` must exist.
fn frictions(
    ctx: &mut Ctx,
    t: &Tbl,
    groups: &Groups,
    laws: &[LawDesc],
) -> Option<Vec<([usize; 2], f64)>> {
    let mut out = Vec::new();
    let mut ok = true;
    for e in entries(ctx, t, "friction")? {
        e.check_keys(ctx, &["between", "value"]);
        let pair = between(ctx, &e, groups);
        let value = match e.get("value") {
            None => {
                e.missing(ctx, "value");
                None
            }
            Some(n) => as_num(ctx, n, &e.field("value")).and_then(|v| {
                (v >= 0.0).then_some(v).or_else(|| {
                    ctx.err(n.pos, &e.field("value"), format!("must be >= 0, got {v}"));
                    None
                })
            }),
        };
        match (pair, value) {
            (Some((pair, pos)), Some(value)) => {
                let same = |l: &LawDesc| l.groups == pair || l.groups == [pair[1], pair[0]];
                if laws.iter().any(same) {
                    out.push((pair, value));
                } else {
                    let (a, b) = (&groups.names[pair[0]], &groups.names[pair[1]]);
                    let why = format!("no law between `{a}` and `{b}` to change");
                    ctx.err(pos, &e.field("between"), why);
                    ok = false;
                }
            }
            _ => ok = false,
        }
    }
    ok.then_some(out)
}

/// `drives = [{ group = g, drive = { x = {...}, ... } }, ...]`: every body of `g` gets the
/// drives given (velocity, or force on bodies of finite mass).
fn drives<const N: usize, B: EventBody>(
    ctx: &mut Ctx,
    t: &Tbl,
    groups: &Groups,
    built: &Built<B>,
    dofs: [&str; N],
) -> Option<Vec<(usize, usize, Drive)>> {
    let mut out = Vec::new();
    let mut ok = true;
    for e in entries(ctx, t, "drives")? {
        e.check_keys(ctx, &["group", "drive"]);
        let group = match e.string(ctx, "group").req(ctx, &e, "group") {
            Some((name, pos)) => match groups.find(name) {
                Some(g) => Some(g),
                None => {
                    ctx.err(pos, &e.field("group"), format!("no group named `{name}`"));
                    None
                }
            },
            None => None,
        };
        let drive = match e.table(ctx, "drive") {
            Got::Val(d, _) => drives_of(ctx, &d, Driven::Event, dofs, None),
            Got::Absent => {
                e.missing(ctx, "drive");
                None
            }
            Got::Bad => None,
        };
        let (Some(group), Some(drive)) = (group, drive) else {
            ok = false;
            continue;
        };
        for (b, body) in (built.bodies.iter().enumerate()).filter(|(_, b)| b.group() == group) {
            for (dof, d) in drive.iter().enumerate() {
                let Some(d) = d else { continue };
                if matches!(d, Drive::Force(_)) && !body.mass().is_finite() {
                    let why = format!(
                        "group `{}` holds a wall without a `mass`: a force cannot move it",
                        groups.names[group]
                    );
                    ctx.err(e.pos, &e.field("drive"), why);
                    return None;
                }
                // The rotations follow the translations: `x y rotation`, `x y z rx ry rz`.
                let rotation = dof >= N.div_ceil(2);
                if matches!(d, Drive::Force(_)) && rotation && !body.turns() {
                    let why = format!(
                        "group `{}` holds a body of infinite moment of inertia (a half-space): \
                         a torque on `{}` cannot turn it",
                        groups.names[group], dofs[dof]
                    );
                    ctx.err(e.pos, &e.field("drive"), why);
                    return None;
                }
                out.push((b, dof, d.clone()));
            }
        }
    }
    ok.then_some(out)
}
