//! `[cell]`: a periodic cell for the rigid bodies of a 2D or 3D scene. Bodies leaving it through a
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
//! In 3D the vectors have three entries, the components are `xx`, `yy`, `zz`, `xy`, `xz` and
//! `yz` (`yx`, `zx`, `zy` stay zero), and `mass` is in kg.

use crate::bodies::time_function;
use crate::read::{Ctx, Got, Tbl};
use crate::tree::{Node, Pos};
#[cfg(doc)]
use crate::types::ShapeDesc;
use crate::types::{BodyDesc, CellDesc, CellLoadDesc, MicroVolume, VelocitySolverKind};
use crate::types3d::BodyDesc3;
#[cfg(doc)]
use crate::types3d::ShapeDesc3;

/// The axes' names.
const AXES: [&str; 3] = ["x", "y", "z"];
/// The gradient's components `L_kl` by `3 k + l`.
const COMPONENTS: [&str; 9] = ["xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"];

/// Reads `[cell]` of a scene of dimension `D` whose largest body (not a wall) is `largest` m
/// across: `Some(None)` when absent, `None` when invalid.
pub(crate) fn cell<const D: usize>(
    ctx: &mut Ctx,
    root: &Tbl,
    largest: f64,
) -> Option<Option<CellDesc<D>>> {
    let t = match root.table(ctx, "cell") {
        Got::Absent => return Some(None),
        Got::Bad => return None,
        Got::Val(t, _) => t,
    };
    let before = ctx.errors.len();
    let mut keys = vec!["origin", "size", "periodic", "mass"];
    keys.extend(component_keys::<D>());
    t.check_keys(ctx, &keys);
    refuse_lower::<D>(ctx, &t);
    let origin = t.vector::<D>(ctx, "origin").or([0.0; D]);
    let size = match t.vector::<D>(ctx, "size").req(ctx, &t, "size") {
        Some((s, _)) if s.iter().all(|&x| x > 0.0) => Some(s),
        Some((s, pos)) => {
            let why = format!("every side must be > 0 m, got {s:?}");
            ctx.err(pos, &t.field("size"), why);
            None
        }
        None => None,
    };
    let periodic = periodic_axes::<D>(ctx, &t);
    let mut loads: [[CellLoadDesc; D]; D] =
        std::array::from_fn(|_| std::array::from_fn(|_| CellLoadDesc::default()));
    let mut stressed = None;
    for (k, l) in (0..D).flat_map(|k| (k..D).map(move |l| (k, l))) {
        let key = COMPONENTS[3 * k + l];
        let Some(n) = t.get(key) else {
            continue;
        };
        let Some((load, pos)) = component_load(ctx, n, &t.field(key)) else {
            continue;
        };
        if matches!(load, CellLoadDesc::Stress(_)) {
            stressed.get_or_insert(pos);
        }
        if let Some(p) = periodic {
            check_deforms(ctx, (n.pos, &t.field(key)), &load, l, p[l]);
            loads[k][l] = load;
        }
    }
    // The cell's mass: per m of thickness in 2D.
    let (unit, short) = match D {
        3 => ("kg", "kg"),
        _ => ("kg per m of thickness", "kg/m"),
    };
    let mass = match (t.num(ctx, "mass"), stressed) {
        (Got::Absent, None) => Some(0.0),
        (Got::Absent, Some(pos)) => {
            let why = format!("a component under `stress` needs the cell's `mass` ({unit})");
            ctx.err(pos, &t.field("mass"), why);
            None
        }
        (g, _) => {
            let what = format!("> 0 {short}");
            crate::read::ensure(ctx, g.ok(), &t.field("mass"), |v| v > 0.0, &what)
        }
    };
    if let (Some(size), Some(periodic)) = (size, periodic) {
        check_size(ctx, &t, size, periodic, largest);
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

/// The names of the gradient's `D x D` components, row by row.
fn component_keys<const D: usize>() -> impl Iterator<Item = &'static str> {
    (0..D).flat_map(|k| (0..D).map(move |l| COMPONENTS[3 * k + l]))
}

/// Refuses the components below the diagonal (`yx`, `zx`, `zy`) in `t`.
fn refuse_lower<const D: usize>(ctx: &mut Ctx, t: &Tbl) {
    for (k, l) in (0..D).flat_map(|k| (0..k).map(move |l| (k, l))) {
        if let Some(n) = t.get(COMPONENTS[3 * k + l]) {
            let why = format!(
                "d{}/d{} stays zero: the cell's edges stay upper triangular (shear with `{}`)",
                AXES[k],
                AXES[l],
                COMPONENTS[3 * l + k]
            );
            ctx.err(n.pos, &t.field(COMPONENTS[3 * k + l]), why);
        }
    }
}

/// One component's control, `{ rate = ... }` (1/s) or `{ stress = ... }` (Pa), with the
/// position of its value.
fn component_load(ctx: &mut Ctx, n: &Node, field: &str) -> Option<(CellLoadDesc, Pos)> {
    let e = Tbl::of(ctx, n, field.to_string())?;
    e.check_keys(ctx, &["rate", "stress"]);
    match (e.get("rate"), e.get("stress")) {
        (Some(r), None) => {
            time_function(ctx, r, &e.field("rate")).map(|f| (CellLoadDesc::Rate(f), r.pos))
        }
        (None, Some(s)) => {
            time_function(ctx, s, &e.field("stress")).map(|f| (CellLoadDesc::Stress(f), s.pos))
        }
        _ => {
            ctx.err(n.pos, field, "give either `rate` (1/s) or `stress` (Pa)");
            None
        }
    }
}

/// A component `L_kl` may deform the cell only along an axis `l` the cell is periodic along.
fn check_deforms(ctx: &mut Ctx, at: (Pos, &str), load: &CellLoadDesc, l: usize, periodic: bool) {
    let still = CellLoadDesc::Rate(xper_bodies::TimeFunction::Constant(0.0));
    if !periodic && *load != still {
        let why = format!(
            "the cell is not periodic along {}: its edge along that axis cannot deform",
            AXES[l]
        );
        ctx.err(at.0, at.1, why);
    }
}

/// An `[[events]]` entry's `cell = { zz = { rate = ... }, xx = { stress = ... } }`: the new
/// control of the components given, from the event on (the others keep theirs). A component
/// under stress needs the cell's `mass`; the scene must have a `[cell]`.
pub(crate) fn event_loads<const D: usize>(
    ctx: &mut Ctx,
    e: &Tbl,
    cell: Option<&CellDesc<D>>,
) -> Option<Vec<([usize; 2], CellLoadDesc)>> {
    let t = match e.table(ctx, "cell") {
        Got::Absent => return Some(Vec::new()),
        Got::Bad => return None,
        Got::Val(t, _) => t,
    };
    let before = ctx.errors.len();
    let Some(cell) = cell else {
        ctx.err(
            t.pos,
            &e.field("cell"),
            "the scene has no `[cell]` to change",
        );
        return None;
    };
    t.check_keys(ctx, &component_keys::<D>().collect::<Vec<_>>());
    refuse_lower::<D>(ctx, &t);
    let mut out = Vec::new();
    for (k, l) in (0..D).flat_map(|k| (k..D).map(move |l| (k, l))) {
        let key = COMPONENTS[3 * k + l];
        let Some(n) = t.get(key) else { continue };
        let Some((load, pos)) = component_load(ctx, n, &t.field(key)) else {
            continue;
        };
        check_deforms(ctx, (n.pos, &t.field(key)), &load, l, cell.periodic[l]);
        if matches!(load, CellLoadDesc::Stress(_)) && cell.mass == 0.0 {
            let why = "a component under `stress` needs the cell's `mass` in `[cell]`";
            ctx.err(pos, &t.field(key), why);
        }
        out.push(([k, l], load));
    }
    (ctx.errors.len() == before).then_some(out)
}

/// What a periodic cell asks of the rest of the scene: the NLGS solver, and measures over the
/// cell's volume (`[output] micro = "cell"`) only with a cell.
pub(crate) fn check_scene(
    ctx: &mut Ctx,
    root: &Tbl,
    has_cell: bool,
    solver: VelocitySolverKind,
    micro: Option<MicroVolume>,
) {
    if let (true, Some(t)) = (has_cell, root.get("solver")) {
        if solver != VelocitySolverKind::Nlgs {
            let pos = (Tbl::of(ctx, t, "solver".into()))
                .and_then(|t| t.get("kind").map(|n| n.pos))
                .unwrap_or(t.pos);
            let why = "a periodic cell is solved by NLGS (`kind = \"nlgs\"`)";
            ctx.err(pos, "solver.kind", why);
        }
    }
    if let (false, Some(MicroVolume::Cell), Some(t)) = (has_cell, micro, root.get("output")) {
        if let Some(n) = (Tbl::of(ctx, t, "output".into())).and_then(|t| t.get("micro")) {
            let why = "the measures' volume is the periodic cell's, and the scene has no `[cell]`";
            ctx.err(n.pos, "output.micro", why);
        }
    }
}

/// `periodic = ["x", "y"]` (the default: every axis) or a part of it.
fn periodic_axes<const D: usize>(ctx: &mut Ctx, t: &Tbl) -> Option<[bool; D]> {
    let Some(n) = t.get("periodic") else {
        return Some([true; D]);
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
        let what = format!("a non-empty array of axis names, e.g. {:?}", &AXES[..D]);
        ctx.expected(n, &field, &what);
        return None;
    };
    let mut axes = [false; D];
    for name in names {
        match AXES[..D].iter().position(|&a| a == name) {
            Some(k) if !axes[k] => axes[k] = true,
            Some(_) => {
                ctx.err(n.pos, &field, format!("axis \"{name}\" given twice"));
                return None;
            }
            None => {
                let why = format!("unknown axis \"{name}\" (one of {:?})", &AXES[..D]);
                ctx.err(n.pos, &field, why);
                return None;
            }
        }
    }
    Some(axes)
}

/// The cell must be at least four of its largest body's diameters (`largest`, m) wide along
/// each periodic axis: then a body meets at most one image of another (the detector relies
/// on it).
fn check_size<const D: usize>(
    ctx: &mut Ctx,
    t: &Tbl,
    size: [f64; D],
    periodic: [bool; D],
    largest: f64,
) {
    for k in (0..D).filter(|&k| periodic[k]) {
        if size[k] < 4.0 * largest {
            let pos = t.get("size").map_or(Pos::START, |n| n.pos);
            let why = format!(
                "the cell is {} m along {}, less than four times the largest body's diameter \
                 ({largest} m): a body could touch two images of another",
                size[k], AXES[k]
            );
            ctx.err(pos, &t.field("size"), why);
        }
    }
}

/// The largest size ([`ShapeDesc::size`]) of the bodies of a 2D scene that are not walls
/// (m; 0 without any).
pub(crate) fn largest_2d(bodies: &[BodyDesc]) -> f64 {
    (bodies.iter().filter_map(|b| b.shape.size())).fold(0.0, f64::max)
}

/// The largest size ([`ShapeDesc3::size`]) of the bodies of a 3D scene that are not walls
/// (m; 0 without any).
pub(crate) fn largest_3d(bodies: &[BodyDesc3]) -> f64 {
    (bodies.iter().filter_map(|b| b.shape.size())).fold(0.0, f64::max)
}
