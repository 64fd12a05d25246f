//! Reader for `[fluid]` and `[fluid.boundary]`: a viscous fluid around the scene's disks
//! (FORMAT.md, "Fluid"). Plain data; the CLI builds the `xper_fluid` solver from it.

use crate::read::{choose, ensure, int_in, Ctx, Got, Tbl};
use crate::shared::Built;
use crate::types::{
    BodyDesc, FluidDesc, FluidSideDesc, Forcing, Lubrication, MarkerForcingParams, ShapeDesc,
    TimeScheme,
};

const FLUID_KEYS: &[&str] = &[
    "density",
    "viscosity",
    "domain",
    "cell_size",
    "cells_per_diameter",
    "body_force",
    "cfl",
    "viscous_safety",
    "upwinding",
    "indicator",
    "pressure_tolerance",
    "pressure_max_cycles",
    "time_scheme",
    "lubrication_range",
    "lubrication_roughness",
    "forcing",
    "forcing_iterations",
    "marker_retraction",
    "boundary",
];

/// Reads `[fluid]` when present; `Some(None)` when absent, `None` when invalid.
pub(crate) fn fluid(ctx: &mut Ctx, root: &Tbl, built: &Built) -> Option<Option<FluidDesc>> {
    let t = match root.table(ctx, "fluid") {
        Got::Absent => return Some(None),
        Got::Bad => return None,
        Got::Val(t, _) => t,
    };
    let before = ctx.errors.len();
    t.check_keys(ctx, FLUID_KEYS);
    let positive = |ctx: &mut Ctx, key: &str, unit: &str| {
        let got = t.num(ctx, key).req(ctx, &t, key);
        ensure(ctx, got, &t.field(key), |v| v > 0.0, &format!("> 0 {unit}"))
    };
    let density = positive(ctx, "density", "kg/m^3");
    let viscosity = positive(ctx, "viscosity", "Pa s");
    let domain = domain(ctx, &t);
    let cell_size = cell_size(ctx, &t, &built.bodies);
    let body_force = t.vec2(ctx, "body_force").or([0.0, 0.0]);
    let bounded = |ctx: &mut Ctx, key: &str, default: f64, lo: f64, hi: f64| match t.num(ctx, key) {
        Got::Absent => Some(default),
        g => ensure(
            ctx,
            g.ok(),
            &t.field(key),
            |v| v > lo && v <= hi,
            &format!("in ({lo}, {hi}]"),
        ),
    };
    let cfl = bounded(ctx, "cfl", 0.5, 0.0, 1.0);
    let viscous_safety = bounded(ctx, "viscous_safety", 0.8, 0.0, 1.0);
    let pressure_tolerance = bounded(ctx, "pressure_tolerance", 1e-8, 0.0, 1.0);
    let upwinding = match t.num(ctx, "upwinding") {
        Got::Absent => Some(0.0),
        g => ensure(
            ctx,
            g.ok(),
            &t.field("upwinding"),
            |v| (0.0..=1.0).contains(&v),
            "in [0, 1]",
        ),
    };
    let sharp = match t.string(ctx, "indicator") {
        Got::Absent => Some(false),
        g => choose(
            ctx,
            g.ok(),
            &t.field("indicator"),
            "solid indicator",
            &[("smoothed", false), ("sharp", true)],
        ),
    };
    let time_scheme = match t.string(ctx, "time_scheme") {
        Got::Absent => Some(TimeScheme::Euler),
        g => choose(
            ctx,
            g.ok(),
            &t.field("time_scheme"),
            "time scheme",
            &[("euler", TimeScheme::Euler), ("rk3", TimeScheme::Rk3)],
        ),
    };
    let lubrication = lubrication(ctx, &t);
    let forcing = forcing(ctx, &t);
    let pressure_max_cycles = match t.int(ctx, "pressure_max_cycles") {
        Got::Absent => Some(50),
        g => int_in(ctx, g.ok(), &t.field("pressure_max_cycles"), 1, 10_000).map(|v| v as u32),
    };
    let boundary = boundary(ctx, &t);
    if let (Some(domain), Some(h)) = (domain, cell_size) {
        cells(ctx, &t, domain, h);
        bodies_inside(ctx, &t, domain, &built.bodies);
    }
    if ctx.errors.len() != before {
        return None;
    }
    Some(Some(FluidDesc {
        density: density?,
        viscosity: viscosity?,
        lower: domain?[0],
        upper: domain?[1],
        cell_size: cell_size?,
        body_force: body_force?,
        cfl: cfl?,
        viscous_safety: viscous_safety?,
        upwinding: upwinding?,
        sharp_indicator: sharp?,
        pressure_tolerance: pressure_tolerance?,
        pressure_max_cycles: pressure_max_cycles?,
        time_scheme: time_scheme?,
        lubrication: lubrication?,
        forcing: forcing?,
        boundary: boundary?,
    }))
}

/// `lubrication_range` (cells, > 0: the correction is on) and `lubrication_roughness`
/// (fraction of the smaller radius, in (0, 1), default 1e-3, only with a range).
fn lubrication(ctx: &mut Ctx, t: &Tbl) -> Option<Option<Lubrication>> {
    let range = match t.num(ctx, "lubrication_range") {
        Got::Absent => None,
        g => Some(ensure(
            ctx,
            g.ok(),
            &t.field("lubrication_range"),
            |v| v > 0.0 && v <= 100.0,
            "in (0, 100] cells",
        )),
    };
    let roughness = match t.num(ctx, "lubrication_roughness") {
        Got::Absent => Some(Lubrication::default().roughness),
        Got::Val(_, pos) if range.is_none() => {
            ctx.err(
                pos,
                &t.field("lubrication_roughness"),
                "given without `lubrication_range`, which turns the correction on",
            );
            None
        }
        g => ensure(
            ctx,
            g.ok(),
            &t.field("lubrication_roughness"),
            |v| v > 0.0 && v < 1.0,
            "in (0, 1) (a fraction of the smaller radius)",
        ),
    };
    match range {
        None => roughness.map(|_| None),
        Some(range) => Some(Some(Lubrication {
            range: range?,
            roughness: roughness?,
        })),
    }
}

/// `forcing` (`"markers"`, the default, or `"fraction"`), with `forcing_iterations` (1 to 100,
/// default 2) and `marker_retraction` (cells, in [0, 1/2], default 0.3) only with markers.
fn forcing(ctx: &mut Ctx, t: &Tbl) -> Option<Forcing> {
    let markers = match t.string(ctx, "forcing") {
        Got::Absent => Some(true),
        g => choose(
            ctx,
            g.ok(),
            &t.field("forcing"),
            "forcing",
            &[("markers", true), ("fraction", false)],
        ),
    };
    let defaults = MarkerForcingParams::default();
    let only_with_markers = |ctx: &mut Ctx, key: &str| match (markers, t.get(key)) {
        (Some(false), Some(n)) => {
            ctx.err(
                n.pos,
                &t.field(key),
                "given with `forcing = \"fraction\"`: it tunes only the marker forcing",
            );
            false
        }
        _ => true,
    };
    let iterations_allowed = only_with_markers(ctx, "forcing_iterations");
    let retraction_allowed = only_with_markers(ctx, "marker_retraction");
    let iterations = match t.int(ctx, "forcing_iterations") {
        Got::Absent => Some(defaults.iterations),
        g => int_in(ctx, g.ok(), &t.field("forcing_iterations"), 1, 100).map(|v| v as u32),
    };
    let retraction = match t.num(ctx, "marker_retraction") {
        Got::Absent => Some(defaults.retraction),
        g => ensure(
            ctx,
            g.ok(),
            &t.field("marker_retraction"),
            |v| (0.0..=0.5).contains(&v),
            "in [0, 0.5] cells",
        ),
    };
    if !(iterations_allowed && retraction_allowed) {
        return None;
    }
    Some(if markers? {
        Forcing::Markers(MarkerForcingParams {
            iterations: iterations?,
            retraction: retraction?,
        })
    } else {
        Forcing::Fraction
    })
}

/// `domain = [[x0, y0], [x1, y1]]` with `x1 > x0`, `y1 > y0`.
fn domain(ctx: &mut Ctx, t: &Tbl) -> Option<[[f64; 2]; 2]> {
    let field = t.field("domain");
    let Some(n) = t.get("domain") else {
        t.missing(ctx, "domain");
        return None;
    };
    let crate::tree::Kind::Array(items) = &n.kind else {
        ctx.expected(n, &field, "[[x0, y0], [x1, y1]] (m)");
        return None;
    };
    if items.len() != 2 {
        ctx.expected(n, &field, "two corners [[x0, y0], [x1, y1]] (m)");
        return None;
    }
    let lo = crate::read::as_vec2(ctx, &items[0], &format!("{field}[0]"))?;
    let hi = crate::read::as_vec2(ctx, &items[1], &format!("{field}[1]"))?;
    if !(hi[0] > lo[0] && hi[1] > lo[1]) {
        ctx.err(
            n.pos,
            &field,
            "the upper corner must be above and to the right of the lower one",
        );
        return None;
    }
    Some([lo, hi])
}

/// `cell_size` (m), or `cells_per_diameter` over the smallest disk.
fn cell_size(ctx: &mut Ctx, t: &Tbl, bodies: &[BodyDesc]) -> Option<f64> {
    let size = t.num(ctx, "cell_size");
    let per = t.num(ctx, "cells_per_diameter");
    match (size, per) {
        (Got::Absent, Got::Absent) => {
            ctx.err(
                t.pos,
                &t.field("cell_size"),
                "missing: give `cell_size` (m) or `cells_per_diameter`",
            );
            None
        }
        (Got::Val(..), Got::Val(_, p)) => {
            ctx.err(
                p,
                &t.field("cells_per_diameter"),
                "give one of `cell_size` and `cells_per_diameter`, not both",
            );
            None
        }
        (Got::Bad, _) | (_, Got::Bad) => None,
        (s, Got::Absent) => ensure(ctx, s.ok(), &t.field("cell_size"), |v| v > 0.0, "> 0 m"),
        (Got::Absent, p) => {
            let (cells, pos) = p.ok()?;
            let diameter = bodies
                .iter()
                .filter_map(|b| match b.shape {
                    ShapeDesc::Disk { radius } => Some(2.0 * radius),
                    _ => None,
                })
                .fold(f64::INFINITY, f64::min);
            if !diameter.is_finite() {
                ctx.err(
                    pos,
                    &t.field("cells_per_diameter"),
                    "the scene has no disk: give `cell_size` (m)",
                );
                return None;
            }
            ensure(
                ctx,
                Some((cells, pos)),
                &t.field("cells_per_diameter"),
                |v| v > 0.0,
                "> 0",
            )
            .map(|c| diameter / c)
        }
    }
}

/// The domain must hold a whole number of cells (at least 4) along each axis.
/// Largest fluid grid a scene may ask for (cells): 2^28, about 70 GB at the solver's ~260 bytes
/// per cell; a larger one is an input error (usually a unit), never an allocation failure.
pub const MAX_FLUID_CELLS: f64 = 268_435_456.0;

/// A number as a person writes it: plain between 1e-4 and 1e7, in exponent form otherwise.
fn short(v: f64) -> String {
    if v == 0.0 || (1e-4..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn cells(ctx: &mut Ctx, t: &Tbl, domain: [[f64; 2]; 2], h: f64) {
    let pos = t.get("domain").map_or(t.pos, |n| n.pos);
    let mut counts = [0.0; 2];
    for (d, axis) in ["width", "height"].iter().enumerate() {
        let length = domain[1][d] - domain[0][d];
        let n = (length / h).round();
        counts[d] = n;
        if !n.is_finite() || n > MAX_FLUID_CELLS {
            let msg = format!(
                "the domain {axis} {} m holds {n:e} cells of {} m",
                short(length),
                short(h)
            );
            ctx.err(pos, &t.field("domain"), msg);
            return;
        }
        if (n * h - length).abs() > 1e-6 * h || n < 4.0 {
            ctx.err(
                pos,
                &t.field("domain"),
                format!(
                    "the domain {axis} {} m is not a whole number (>= 4) of cells of {} m",
                    short(length),
                    short(h)
                ),
            );
        }
    }
    let total = counts[0] * counts[1];
    if total > MAX_FLUID_CELLS {
        ctx.err(
            pos,
            &t.field("domain"),
            format!(
                "{} x {} = {total:.3e} cells of {} m: more than the {MAX_FLUID_CELLS:.3e} a \
                 fluid grid may have (check the units: m)",
                counts[0],
                counts[1],
                short(h)
            ),
        );
    }
}

/// Every dynamic body must be a disk inside the domain.
fn bodies_inside(ctx: &mut Ctx, t: &Tbl, domain: [[f64; 2]; 2], bodies: &[BodyDesc]) {
    for (k, body) in bodies.iter().enumerate() {
        match body.shape {
            ShapeDesc::Disk { radius } => {
                let c = body.position;
                let inside =
                    (0..2).all(|d| c[d] - radius >= domain[0][d] && c[d] + radius <= domain[1][d]);
                if !inside {
                    ctx.err(
                        t.pos,
                        &t.field("domain"),
                        format!("body {k} (a disk at {c:?}) is not inside the fluid domain"),
                    );
                }
            }
            ShapeDesc::Polygon { .. } => ctx.err(
                t.pos,
                "fluid",
                format!(
                    "body {k} is a polygon: only disks can be immersed in a fluid (walls are fine)"
                ),
            ),
            _ => {}
        }
    }
}

/// `[fluid.boundary]`: `left`, `right`, `bottom`, `top`, each `"no_slip"`, `"periodic"`,
/// `"outflow"`, or a table `{ kind = "moving_wall", velocity = 1.0 }`,
/// `{ kind = "inflow", profile = "parabolic" | "uniform", speed = 0.3 }`; default no slip.
fn boundary(ctx: &mut Ctx, t: &Tbl) -> Option<[FluidSideDesc; 4]> {
    let b = match t.table(ctx, "boundary") {
        Got::Absent => return Some([FluidSideDesc::NoSlip; 4]),
        Got::Bad => return None,
        Got::Val(b, _) => b,
    };
    const SIDES: [&str; 4] = ["left", "right", "bottom", "top"];
    b.check_keys(ctx, &SIDES);
    let mut out = [FluidSideDesc::NoSlip; 4];
    let mut ok = true;
    for (k, side) in SIDES.iter().enumerate() {
        match side_condition(ctx, &b, side) {
            Some(c) => out[k] = c,
            None => ok = false,
        }
    }
    for (a, c) in [(0, 1), (2, 3)] {
        if (out[a] == FluidSideDesc::Periodic) != (out[c] == FluidSideDesc::Periodic) {
            let pos = b.get(SIDES[a]).or(b.get(SIDES[c])).map_or(b.pos, |n| n.pos);
            ctx.err(
                pos,
                &b.field(SIDES[a]),
                format!(
                    "`{}` and `{}` must both be periodic or neither",
                    SIDES[a], SIDES[c]
                ),
            );
            ok = false;
        }
    }
    ok.then_some(out)
}

fn side_condition(ctx: &mut Ctx, b: &Tbl, side: &str) -> Option<FluidSideDesc> {
    let field = b.field(side);
    let Some(n) = b.get(side) else {
        return Some(FluidSideDesc::NoSlip);
    };
    if let crate::tree::Kind::Str(s) = &n.kind {
        return choose(
            ctx,
            Some((s.as_str(), n.pos)),
            &field,
            "boundary condition",
            &[
                ("no_slip", FluidSideDesc::NoSlip),
                ("periodic", FluidSideDesc::Periodic),
                ("outflow", FluidSideDesc::Outflow),
            ],
        );
    }
    let t = Tbl::of(ctx, n, field.clone())?;
    let kind = t.string(ctx, "kind").req(ctx, &t, "kind");
    let kind = choose(
        ctx,
        kind,
        &t.field("kind"),
        "boundary condition",
        &[("moving_wall", 0), ("inflow", 1)],
    )?;
    if kind == 0 {
        t.check_keys(ctx, &["kind", "velocity"]);
        let v = t.num(ctx, "velocity").req(ctx, &t, "velocity")?.0;
        return Some(FluidSideDesc::MovingWall { velocity: v });
    }
    t.check_keys(ctx, &["kind", "profile", "speed"]);
    let profile = t.string(ctx, "profile").req(ctx, &t, "profile");
    let parabolic = choose(
        ctx,
        profile,
        &t.field("profile"),
        "inflow profile",
        &[("uniform", false), ("parabolic", true)],
    );
    let speed = t.num(ctx, "speed").req(ctx, &t, "speed");
    let speed = ensure(
        ctx,
        speed,
        &t.field("speed"),
        |v| v >= 0.0,
        ">= 0 m/s (inward)",
    );
    Some(FluidSideDesc::Inflow {
        parabolic: parabolic?,
        speed: speed?,
    })
}
