//! `[cell]`: a periodic cell for the rigid bodies of a 2D scene. Bodies leaving it through a
//! side re-enter through the opposite one, contacts across the sides are found, and the cell
//! deforms homogeneously with a velocity gradient whose components are imposed (`rate`, 1/s)
//! or follow an imposed stress (`stress`, Pa, compression positive). For a simple shear at
//! constant pressure (a Lees-Edwards cell):
//!
//! ```toml
//! [cell]
//! origin = [0.0, 0.0]           # m, the lower left corner
//! size = [0.1, 0.1]             # m
//! mass = 0.5                    # kg per m: the inertia of the components under stress
//! xy = { rate = 1.0 }           # 1/s: dv_x/dy
//! yy = { stress = 1e4 }         # Pa
//! ```
//!
//! `xx`, `yy` and `xy` are the components `L_xx`, `L_yy`, `L_xy = dv_x/dy` of the gradient,
//! `rate = 0` when absent; `yx` stays zero (the cell's edges stay upper triangular).
//! `periodic = ["x"]` makes the cell periodic along x only (walls bound it along y).

use crate::bodies::time_function;
use crate::read::{Ctx, Got, Tbl};
use crate::tree::Pos;
use crate::types::{BodyDesc, CellDesc, CellLoadDesc, ShapeDesc};

const KEYS: &[&str] = &["origin", "size", "periodic", "mass", "xx", "yy", "xy", "yx"];

/// Reads `[cell]`: `Some(None)` when absent, `None` when invalid.
pub(crate) fn cell(ctx: &mut Ctx, root: &Tbl, bodies: &[BodyDesc]) -> Option<Option<CellDesc>> {
    let t = match root.table(ctx, "cell") {
        Got::Absent => return Some(None),
        Got::Bad => return None,
        Got::Val(t, _) => t,
    };
    let before = ctx.errors.len();
    t.check_keys(ctx, KEYS);
    if let Some(n) = t.get("yx") {
        let why = "dv_y/dx stays zero: the cell's edges stay upper triangular (shear with `xy`)";
        ctx.err(n.pos, &t.field("yx"), why);
    }
    let origin = t.vec2(ctx, "origin").or([0.0, 0.0]);
    let size = match t.vec2(ctx, "size").req(ctx, &t, "size") {
        Some((s, _)) if s.iter().all(|&x| x > 0.0) => Some(s),
        Some((s, pos)) => {
            ctx.err(
                pos,
                &t.field("size"),
                format!("both sides must be > 0 m, got {s:?}"),
            );
            None
        }
        None => None,
    };
    let periodic = periodic_axes(ctx, &t);
    let mut loads: [[CellLoadDesc; 2]; 2] = Default::default();
    let mut stressed = None;
    for (key, k, l) in [("xx", 0, 0), ("yy", 1, 1), ("xy", 0, 1)] {
        let Some(n) = t.get(key) else {
            continue;
        };
        let field = t.field(key);
        let Some(e) = Tbl::of(ctx, n, field.clone()) else {
            continue;
        };
        e.check_keys(ctx, &["rate", "stress"]);
        let load = match (e.get("rate"), e.get("stress")) {
            (Some(r), None) => time_function(ctx, r, &e.field("rate")).map(CellLoadDesc::Rate),
            (None, Some(s)) => {
                stressed.get_or_insert(s.pos);
                time_function(ctx, s, &e.field("stress")).map(CellLoadDesc::Stress)
            }
            _ => {
                ctx.err(n.pos, &field, "give either `rate` (1/s) or `stress` (Pa)");
                None
            }
        };
        if let (Some(load), Some(p)) = (load, periodic) {
            let still = CellLoadDesc::Rate(xper_bodies::TimeFunction::Constant(0.0));
            if !p[l] && load != still {
                let why = format!(
                    "the cell is not periodic along {}: its edge along that axis cannot deform",
                    ["x", "y"][l]
                );
                ctx.err(n.pos, &field, why);
            }
            loads[k][l] = load;
        }
    }
    let mass = match (t.num(ctx, "mass"), stressed) {
        (Got::Absent, None) => Some(0.0),
        (Got::Absent, Some(pos)) => {
            let why = "a component under `stress` needs the cell's `mass` (kg per m of thickness)";
            ctx.err(pos, &t.field("mass"), why);
            None
        }
        (g, _) => crate::read::ensure(ctx, g.ok(), &t.field("mass"), |v| v > 0.0, "> 0 kg/m"),
    };
    if let (Some(size), Some(periodic)) = (size, periodic) {
        check_size(ctx, &t, size, periodic, bodies);
    }
    if ctx.errors.len() > before {
        return None;
    }
    Some(Some(CellDesc {
        origin: origin?,
        size: size?,
        periodic: periodic?,
        mass: mass?,
        loads,
    }))
}

/// `periodic = ["x", "y"]` (the default) or a part of it.
fn periodic_axes(ctx: &mut Ctx, t: &Tbl) -> Option<[bool; 2]> {
    let Some(n) = t.get("periodic") else {
        return Some([true, true]);
    };
    let field = t.field("periodic");
    let names = match &n.kind {
        crate::tree::Kind::Array(a) if !a.is_empty() => a
            .iter()
            .map(|e| match &e.kind {
                crate::tree::Kind::Str(s) => Some(s.as_str()),
                _ => None,
            })
            .collect::<Option<Vec<_>>>(),
        _ => None,
    };
    let Some(names) = names else {
        ctx.expected(
            n,
            &field,
            "a non-empty array of axis names, e.g. [\"x\", \"y\"]",
        );
        return None;
    };
    let mut axes = [false; 2];
    for name in names {
        match ["x", "y"].iter().position(|&a| a == name) {
            Some(k) if !axes[k] => axes[k] = true,
            Some(_) => {
                ctx.err(n.pos, &field, format!("axis \"{name}\" given twice"));
                return None;
            }
            None => {
                ctx.err(
                    n.pos,
                    &field,
                    format!("unknown axis \"{name}\" (\"x\" or \"y\")"),
                );
                return None;
            }
        }
    }
    Some(axes)
}

/// The cell must be at least four of its largest body's diameters wide along each periodic
/// axis: then a body meets at most one image of another (the detector relies on it).
fn check_size(ctx: &mut Ctx, t: &Tbl, size: [f64; 2], periodic: [bool; 2], bodies: &[BodyDesc]) {
    let largest = (bodies.iter())
        .map(|b| match &b.shape {
            ShapeDesc::Disk { radius } => 2.0 * radius,
            ShapeDesc::Polygon { vertices } => {
                2.0 * (vertices.iter())
                    .map(|v| v[0].hypot(v[1]))
                    .fold(0.0, f64::max)
            }
            ShapeDesc::Segment { .. } => 0.0,
        })
        .fold(0.0, f64::max);
    for k in (0..2).filter(|&k| periodic[k]) {
        if size[k] < 4.0 * largest {
            let pos = t.get("size").map_or(Pos::START, |n| n.pos);
            let why = format!(
                "the cell is {} m along {}, less than four times the largest body's diameter \
                 ({largest} m): a body could touch two images of another",
                size[k],
                ["x", "y"][k]
            );
            ctx.err(pos, &t.field("size"), why);
        }
    }
}
