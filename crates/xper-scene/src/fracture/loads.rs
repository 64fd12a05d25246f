//! `[[loads]]`: node selections and the drive of each component.

use xper_bodies::{Drive, TimeFunction};
use xper_mesh::NodeSelector;

use super::mesh::two_points;
use super::types::LoadDesc;
use super::{number_or, place, required_table};
use crate::bodies::time_function;
use crate::read::{Ctx, Tbl};
use crate::tree::{Kind, Pos};

/// `[[loads]]`.
pub(super) fn loads(ctx: &mut Ctx, root: &Tbl) -> Option<Vec<LoadDesc>> {
    let (mut out, mut ok) = (Vec::<LoadDesc>::new(), true);
    for (_, t) in root.tables(ctx, "loads") {
        t.check_keys(ctx, &["name", "nodes", "velocity", "force"]);
        let name = t.string(ctx, "name").req(ctx, &t, "name");
        let nodes = required_table(ctx, &t, "nodes").and_then(|n| selector(ctx, &n));
        let drives = drives(ctx, &t);
        let name = name.and_then(|(name, pos)| {
            let valid = !name.is_empty()
                && (name.chars()).all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            let why = if !valid {
                "must be non-empty and use only letters, digits, `_` and `-` (it names the \
                 series columns)"
                    .to_string()
            } else if out.iter().any(|l| l.name == name) {
                format!("duplicate load name `{name}`")
            } else {
                return Some(name.to_string());
            };
            ctx.err(pos, &t.field("name"), format!("{why}, got {name:?}"));
            None
        });
        let nodes_pos = t.get("nodes").map_or(t.pos, |n| n.pos);
        match (name, nodes, drives) {
            (Some(name), Some(nodes), Some(drives)) => out.push(LoadDesc {
                name,
                nodes,
                drives,
                place: place(nodes_pos, t.field("nodes")),
            }),
            _ => ok = false,
        }
    }
    ok.then_some(out)
}

/// `nodes = { set = "top" }`, `{ segment = [[x0, y0], [x1, y1]], tolerance = 1e-9 }` or
/// `{ box = [[xmin, ymin], [xmax, ymax]] }`.
fn selector(ctx: &mut Ctx, n: &Tbl) -> Option<NodeSelector> {
    n.check_keys(ctx, &["set", "segment", "tolerance", "box"]);
    let given: Vec<&str> = (["set", "segment", "box"].into_iter())
        .filter(|k| n.has(k))
        .collect();
    match given.as_slice() {
        [] => {
            let msg = "missing `set`, `segment` or `box`";
            ctx.err(n.pos, &n.field("set"), msg);
            None
        }
        ["set"] => {
            n.forbid(ctx, "tolerance", "applies to `segment` only");
            let (s, _) = n.string(ctx, "set").ok()?;
            Some(NodeSelector::Set(s.to_string()))
        }
        ["segment"] => {
            let seg = n.get("segment")?;
            let [from, to] = two_points(ctx, seg, &n.field("segment"))?;
            let len = ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2)).sqrt();
            let tolerance = number_or(ctx, n, "tolerance", 1e-6 * len, |v| v >= 0.0, ">= 0 m")?;
            Some(NodeSelector::Segment {
                from,
                to,
                tolerance,
            })
        }
        ["box"] => {
            n.forbid(ctx, "tolerance", "applies to `segment` only");
            let b = n.get("box")?;
            let [min, max] = two_points(ctx, b, &n.field("box"))?;
            if min[0] > max[0] || min[1] > max[1] {
                let msg = format!("the first corner {min:?} must be below and left of {max:?}");
                ctx.err(b.pos, &n.field("box"), msg);
                return None;
            }
            Some(NodeSelector::Box { min, max })
        }
        [_] => None,
        [_, second, ..] => {
            let pos = n.get(second).map_or(n.pos, |v| v.pos);
            let msg = "give exactly one of `set`, `segment` and `box`";
            ctx.err(pos, &n.field(second), msg);
            None
        }
    }
}

/// One component of `velocity` / `force`, with where it was written.
type Component = (Option<TimeFunction>, Pos);

/// `velocity = [x, y]` and `force = [x, y]`, each component `"free"`, a number, a table or a
/// sine; a component may not have both.
fn drives(ctx: &mut Ctx, t: &Tbl) -> Option<[Drive; 2]> {
    if !t.has("velocity") && !t.has("force") {
        let msg = "missing `velocity` or `force` (per component: \"free\", a number, \
                   [[t, v], ...] or { sine = {...} })";
        ctx.err(t.pos, &t.field("velocity"), msg);
        return None;
    }
    let velocity = components(ctx, t, "velocity");
    let force = components(ctx, t, "force");
    let (velocity, force) = (velocity?, force?);
    let mut out = [Drive::Free, Drive::Free];
    let mut ok = true;
    for d in 0..2 {
        out[d] = match (velocity[d].0.clone(), force[d].0.clone()) {
            (Some(_), Some(_)) => {
                let msg = format!(
                    "component {} has both a velocity and a force: make one of them \"free\"",
                    ["x", "y"][d]
                );
                ctx.err(force[d].1, &format!("{}[{d}]", t.field("force")), msg);
                ok = false;
                Drive::Free
            }
            (Some(v), None) => Drive::Velocity(v),
            (None, Some(f)) => Drive::Force(f),
            (None, None) => Drive::Free,
        };
    }
    if ok && out.iter().all(|d| matches!(d, Drive::Free)) {
        let key = if t.has("velocity") {
            "velocity"
        } else {
            "force"
        };
        let pos = t.get(key).map_or(t.pos, |n| n.pos);
        let msg = "every component is \"free\": the load drives nothing";
        ctx.err(pos, &t.field(key), msg);
        return None;
    }
    ok.then_some(out)
}

fn components(ctx: &mut Ctx, t: &Tbl, key: &str) -> Option<[Component; 2]> {
    let field = t.field(key);
    let Some(n) = t.get(key) else {
        return Some([(None, t.pos), (None, t.pos)]);
    };
    let what = "two components [x, y], each \"free\", a number, [[t, v], ...] or { sine = {...} }";
    let Kind::Array(a) = &n.kind else {
        ctx.expected(n, &field, what);
        return None;
    };
    if a.len() != 2 {
        ctx.expected(n, &field, what);
        return None;
    }
    let mut out = [(None, n.pos), (None, n.pos)];
    let mut ok = true;
    for (k, e) in a.iter().enumerate() {
        let f = format!("{field}[{k}]");
        out[k].1 = e.pos;
        match &e.kind {
            Kind::Str(s) if s == "free" => {}
            Kind::Str(s) => {
                let msg = format!("unknown component {s:?}: expected \"free\", a number, [[t, v], ...] or {{ sine = {{...}} }}");
                ctx.err(e.pos, &f, msg);
                ok = false;
            }
            _ => match time_function(ctx, e, &f) {
                Some(tf) => out[k].0 = Some(tf),
                None => ok = false,
            },
        }
    }
    ok.then_some(out)
}
