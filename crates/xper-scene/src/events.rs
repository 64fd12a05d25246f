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

use crate::bodies::{drives_of, Driven};
use crate::read::{as_num, Ctx, Got, Tbl};
use crate::sections::between;
use crate::shared::{Built, Groups};
use crate::tree::Kind;
use crate::types::{Drive, EventDesc, LawDesc};

/// Reads `[[events]]`, sorted by time (stable: events at the same time keep their order).
pub(crate) fn events(
    ctx: &mut Ctx,
    root: &Tbl,
    groups: &Groups,
    built: &Built,
    laws: &[LawDesc],
) -> Vec<EventDesc> {
    let mut out = Vec::new();
    for (_, t) in root.tables(ctx, "events") {
        t.check_keys(ctx, &["time", "friction", "drives"]);
        let time = match t.num(ctx, "time").req(ctx, &t, "time") {
            Some((v, _)) if v >= 0.0 => Some(v),
            Some((v, pos)) => {
                ctx.err(pos, &t.field("time"), format!("must be >= 0 (s), got {v}"));
                None
            }
            None => None,
        };
        let frictions = frictions(ctx, &t, groups, laws);
        let drives = drives(ctx, &t, groups, built);
        if let (Some(time), Some(frictions), Some(drives)) = (time, frictions, drives) {
            out.push(EventDesc {
                time,
                frictions,
                drives,
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
fn drives(
    ctx: &mut Ctx,
    t: &Tbl,
    groups: &Groups,
    built: &Built,
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
            Got::Val(d, _) => drives_of(ctx, &d, Driven::Event, ["x", "y", "rotation"], None),
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
        for (b, body) in (built.bodies.iter().enumerate()).filter(|(_, b)| b.group == group) {
            for (dof, d) in drive.iter().enumerate() {
                let Some(d) = d else { continue };
                if matches!(d, Drive::Force(_)) && !body.mass.is_finite() {
                    let why = format!(
                        "group `{}` holds a wall without a `mass`: a force cannot move it",
                        groups.names[group]
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
