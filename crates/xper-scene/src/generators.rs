//! The `[[generators]]`: `box_of_disks` and `hex_lattice`.

use std::collections::HashMap;
use std::f64::consts::PI;

use crate::bodies::wall_body;
use crate::read::{choose, ensure, int_in, Ctx, Got, Tbl};
use crate::shared::{Built, Groups, Materials, Origin, Part};
use crate::tree::{Kind, Pos};
use crate::types::{BodyDesc, Drive, ShapeDesc};
use xper_math::SplitMix64;

/// Largest number of disks one generator may produce.
pub const MAX_GENERATED: i64 = 10_000_000;

#[derive(Clone, Copy)]
enum GenKind {
    BoxOfDisks,
    HexLattice,
}

/// Fields common to both generators.
struct Common {
    density: f64,
    group: usize,
    walls: Option<usize>,
    velocity: [f64; 2],
}

/// Reads `[[generators]]` and appends their bodies to `built`.
pub(crate) fn generators(
    ctx: &mut Ctx,
    root: &Tbl,
    mats: &Materials,
    groups: &mut Groups,
    built: &mut Built,
) {
    for (i, t) in root.tables(ctx, "generators") {
        let kinds = [
            ("box_of_disks", GenKind::BoxOfDisks),
            ("hex_lattice", GenKind::HexLattice),
        ];
        let kind_got = t.string(ctx, "kind").req(ctx, &t, "kind");
        let Some(kind) = choose(ctx, kind_got, &t.field("kind"), "generator kind", &kinds) else {
            continue;
        };
        let origin = |part| Origin {
            section: "generators",
            index: i,
            part,
            pos: t.pos,
        };
        let made = match kind {
            GenKind::BoxOfDisks => box_of_disks(ctx, &t, mats, groups),
            GenKind::HexLattice => hex_lattice(ctx, &t, mats, groups),
        };
        let Some((disks, common, corners)) = made else {
            continue;
        };
        let bad_mass = disks.iter().find_map(|&(_, r)| {
            let m = common.density * PI * r * r;
            let i = m * r * r / 2.0;
            (!(m > 0.0 && m.is_finite() && i > 0.0 && i.is_finite())).then_some((r, m, i))
        });
        if let Some((r, m, i)) = bad_mass {
            let msg = format!("a disk of radius {r} m gets mass {m} kg and inertia {i} kg m^2: both must be finite and > 0");
            ctx.err(t.pos, &t.field("radius"), msg);
            continue;
        }
        built.reserve(disks.len() + 4);
        for (k, (c, r)) in disks.into_iter().enumerate() {
            let m = common.density * PI * r * r;
            let body = BodyDesc {
                shape: ShapeDesc::Disk { radius: r },
                position: c,
                angle: 0.0,
                velocity: common.velocity,
                angular_velocity: 0.0,
                mass: m,
                inertia: m * r * r / 2.0,
                group: common.group,
                drives: [Drive::Free, Drive::Free, Drive::Free],
            };
            built.push(body, origin(Part::Disk(k)));
        }
        if let Some(g) = common.walls {
            let ([x0, y0], [x1, y1]) = corners;
            let sides = [
                ([x0, y0], [x1, y0]),
                ([x1, y0], [x1, y1]),
                ([x1, y1], [x0, y1]),
                ([x0, y1], [x0, y0]),
            ];
            for (w, (a, b)) in sides.into_iter().enumerate() {
                built.push(wall_body(a, b, g), origin(Part::Wall(w)));
            }
        }
    }
}

/// Disks (centre, radius), common fields and the box corners.
type Made = (Vec<([f64; 2], f64)>, Common, ([f64; 2], [f64; 2]));

fn common(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<Common> {
    let shared = material_and_groups(ctx, t, mats, groups);
    let velocity = t.vec2(ctx, "velocity").or([0.0, 0.0]);
    let (density, group, walls) = shared?;
    Some(Common {
        density,
        group,
        walls,
        velocity: velocity?,
    })
}

/// What generators of both dimensions read alike: the material's density, the group of the
/// bodies and the group of the walls (if any).
pub(crate) fn material_and_groups(
    ctx: &mut Ctx,
    t: &Tbl,
    mats: &Materials,
    groups: &mut Groups,
) -> Option<(f64, usize, Option<usize>)> {
    t.forbid(ctx, "mass", "generators take a `material`, not `mass`");
    t.forbid(
        ctx,
        "inertia",
        "generators take a `material`, not `inertia`",
    );
    let name = t.string(ctx, "material").req(ctx, t, "material");
    let density = mats.density(ctx, name, &t.field("material"));
    let group = t
        .string(ctx, "group")
        .req(ctx, t, "group")
        .map(|(g, _)| groups.index(g));
    let walls = match t.string(ctx, "walls") {
        Got::Absent => Some(None),
        Got::Bad => None,
        Got::Val(g, _) => Some(Some(groups.index(g))),
    };
    Some((density?, group?, walls?))
}

/// The `radius = [min, max]` (m) of a box generator, `0 < min <= max`.
pub(crate) fn radius_range(ctx: &mut Ctx, t: &Tbl) -> Option<(f64, f64)> {
    t.vec2(ctx, "radius")
        .req(ctx, t, "radius")
        .and_then(|([lo, hi], pos)| {
            if lo > 0.0 && lo <= hi {
                Some((lo, hi))
            } else {
                ctx.err(
                    pos,
                    &t.field("radius"),
                    format!("must be [min, max] m with 0 < min <= max, got [{lo}, {hi}]"),
                );
                None
            }
        })
}

/// The generator's `seed` (0 unless given).
pub(crate) fn seed(ctx: &mut Ctx, t: &Tbl) -> Option<u64> {
    match t.int(ctx, "seed") {
        Got::Absent => Some(0),
        g => int_in(ctx, g.ok(), &t.field("seed"), 0, i64::MAX).map(|s| s as u64),
    }
}

fn box_corners(ctx: &mut Ctx, t: &Tbl) -> Option<([f64; 2], [f64; 2])> {
    let field = t.field("box");
    let Some(n) = t.get("box") else {
        t.missing(ctx, "box");
        return None;
    };
    let what = "[[xmin, ymin], [xmax, ymax]]";
    let Kind::Array(a) = &n.kind else {
        ctx.expected(n, &field, what);
        return None;
    };
    if a.len() != 2 {
        ctx.expected(n, &field, what);
        return None;
    }
    let lo = crate::read::as_vec2(ctx, &a[0], &format!("{field}[0]"));
    let hi = crate::read::as_vec2(ctx, &a[1], &format!("{field}[1]"));
    let (lo, hi) = (lo?, hi?);
    if !((hi[0] - lo[0]).is_finite() && (hi[1] - lo[1]).is_finite()) {
        ctx.err(
            n.pos,
            &field,
            format!("box size must be finite, got {lo:?} and {hi:?}"),
        );
        return None;
    }
    if !(hi[0] > lo[0] && hi[1] > lo[1]) {
        ctx.err(
            n.pos,
            &field,
            format!("max corner must exceed min corner, got {lo:?} and {hi:?}"),
        );
        return None;
    }
    Some((lo, hi))
}

/// The keys of the box generators (`box_of_disks`, `box_of_spheres`).
pub(crate) const BOX_KEYS: &[&str] = &[
    "kind",
    "count",
    "radius",
    "box",
    "placement",
    "seed",
    "material",
    "group",
    "walls",
    "velocity",
];

fn box_of_disks(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<Made> {
    t.check_keys(ctx, BOX_KEYS);
    let count_got = t.int(ctx, "count").req(ctx, t, "count");
    let count = int_in(ctx, count_got, &t.field("count"), 1, MAX_GENERATED);
    let radius = radius_range(ctx, t);
    let corners = box_corners(ctx, t);
    let placements = [("lattice", false), ("random", true)];
    let random = match t.string(ctx, "placement") {
        Got::Absent => Some(false),
        g => choose(ctx, g.ok(), &t.field("placement"), "placement", &placements),
    };
    let seed = seed(ctx, t);
    let common = common(ctx, t, mats, groups);
    let (count, (rmin, rmax), (lo, hi), random, seed, common) =
        (count? as usize, radius?, corners?, random?, seed?, common?);
    let mut rng = SplitMix64::new(seed);
    let radii: Vec<f64> = (0..count)
        .map(|_| rmin + (rmax - rmin) * rng.next_f64())
        .collect();
    let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
    let count_pos = t.get("count").map_or(t.pos, |n| n.pos);
    let centres = if random {
        random_placement(ctx, t, count_pos, &radii, rmax, (lo, hi), &mut rng)?
    } else {
        let pitch = 2.0 * rmax * 1.05;
        let nx = (w / pitch).floor().max(0.0) as u64;
        let ny = (h / pitch).floor().max(0.0) as u64;
        let fits = nx.saturating_mul(ny);
        if (count as u64) > fits {
            let msg = format!("{count} disks do not fit: a square lattice of pitch {pitch} m holds {fits} ({nx} x {ny}) in the box");
            ctx.err(count_pos, &t.field("count"), msg);
            return None;
        }
        let nx = nx as usize;
        (0..count)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                [
                    lo[0] + pitch / 2.0 + i as f64 * pitch,
                    lo[1] + pitch / 2.0 + j as f64 * pitch,
                ]
            })
            .collect()
    };
    let disks = centres.into_iter().zip(radii).collect();
    Some((disks, common, (lo, hi)))
}

/// Largest fraction of the box area the disks of a random placement may cover.
const RANDOM_JAMMING: f64 = 0.60;

/// Random sequential addition without overlap, at most `1000 * count` attempts in total.
fn random_placement(
    ctx: &mut Ctx,
    t: &Tbl,
    count_pos: Pos,
    radii: &[f64],
    rmax: f64,
    (lo, hi): ([f64; 2], [f64; 2]),
    rng: &mut SplitMix64,
) -> Option<Vec<[f64; 2]>> {
    let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
    if 2.0 * rmax > w.min(h) {
        let msg = format!("a disk of radius {rmax} m does not fit in a {w} x {h} m box");
        ctx.err(count_pos, &t.field("radius"), msg);
        return None;
    }
    // Random sequential addition of equal disks jams at a covered fraction of 0.547 (Feder,
    // J. Theor. Biol. 87 (1980) 237); polydisperse disks reach a little more. Above 0.60 of
    // the box the placement cannot end: say so at once instead of trying 1000 times per disk.
    let covered: f64 = radii
        .iter()
        .map(|r| std::f64::consts::PI * r * r)
        .sum::<f64>()
        / (w * h);
    if !(covered <= RANDOM_JAMMING) {
        let msg = format!(
            "{} disks cover {covered:.3} of the box area: random placement jams at about 0.55 \
             (at most {RANDOM_JAMMING} accepted); use fewer or smaller disks, a larger box or \
             placement = \"lattice\"",
            radii.len()
        );
        ctx.err(count_pos, &t.field("count"), msg);
        return None;
    }
    let cell = 2.0 * rmax;
    let key = |p: [f64; 2]| {
        (
            ((p[0] - lo[0]) / cell).floor() as i64,
            ((p[1] - lo[1]) / cell).floor() as i64,
        )
    };
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut centres: Vec<[f64; 2]> = Vec::with_capacity(radii.len());
    let budget = (radii.len() as u64).saturating_mul(1000);
    let mut attempts = 0u64;
    for &r in radii {
        loop {
            if attempts >= budget {
                let msg = format!(
                    "random placement failed after {attempts} attempts: placed {} of {} disks",
                    centres.len(),
                    radii.len()
                );
                ctx.err(count_pos, &t.field("count"), msg);
                return None;
            }
            attempts += 1;
            let p = [
                lo[0] + r + rng.next_f64() * (w - 2.0 * r),
                lo[1] + r + rng.next_f64() * (h - 2.0 * r),
            ];
            let (cx, cy) = key(p);
            let free = (-1..=1).all(|dx| {
                (-1..=1).all(|dy| {
                    let cell = (cx.saturating_add(dx), cy.saturating_add(dy));
                    grid.get(&cell).into_iter().flatten().all(|&j| {
                        let q = centres[j];
                        (p[0] - q[0]).hypot(p[1] - q[1]) >= r + radii[j]
                    })
                })
            });
            if free {
                grid.entry((cx, cy)).or_default().push(centres.len());
                centres.push(p);
                break;
            }
        }
    }
    Some(centres)
}

const HEX_KEYS: &[&str] = &[
    "kind", "columns", "rows", "pitch", "radius", "seed", "box", "material", "group", "walls",
    "velocity",
];

fn hex_lattice(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<Made> {
    t.check_keys(ctx, HEX_KEYS);
    let cols = t.int(ctx, "columns").req(ctx, t, "columns");
    let cols = int_in(ctx, cols, &t.field("columns"), 1, MAX_GENERATED);
    let rows = t.int(ctx, "rows").req(ctx, t, "rows");
    let rows = int_in(ctx, rows, &t.field("rows"), 1, MAX_GENERATED);
    let pitch = t.num(ctx, "pitch").req(ctx, t, "pitch");
    let pitch = ensure(ctx, pitch, &t.field("pitch"), |v| v > 0.0, "> 0 m");
    let radius = t.num(ctx, "radius").req(ctx, t, "radius");
    let radius = ensure(ctx, radius, &t.field("radius"), |v| v > 0.0, "> 0 m");
    let seed = seed(ctx, t);
    let size = t.vec2(ctx, "box").req(ctx, t, "box").and_then(|(s, pos)| {
        if s[0] > 0.0 && s[1] > 0.0 {
            Some(s)
        } else {
            ctx.err(
                pos,
                &t.field("box"),
                format!("width and height must be > 0 m, got {s:?}"),
            );
            None
        }
    });
    let common = common(ctx, t, mats, groups);
    let (cols, rows) = (cols?, rows?);
    if cols.saturating_mul(rows) > MAX_GENERATED {
        let pos = t.get("rows").map_or(t.pos, |n| n.pos);
        let msg = format!(
            "columns x rows = {} exceeds the limit of {MAX_GENERATED} disks",
            cols.saturating_mul(rows)
        );
        ctx.err(pos, &t.field("rows"), msg);
        return None;
    }
    let (cols, rows, p, radius, seed, [bw, bh], common) = (
        cols as usize,
        rows as usize,
        pitch?,
        radius?,
        seed?,
        size?,
        common?,
    );
    let mut rng = SplitMix64::new(seed);
    let mut disks = Vec::with_capacity(cols * rows);
    for j in 0..rows {
        for i in 0..cols {
            let x = p / 2.0 + i as f64 * p + if j % 2 == 1 { p / 2.0 } else { 0.0 };
            let y = p / 2.0 + j as f64 * p * 3f64.sqrt() / 2.0;
            let r = radius * (1.0 + rng.next_f64());
            disks.push(([x, y], r));
        }
    }
    let outside = |&([x, y], r): &([f64; 2], f64)| {
        let tol = 1e-9 + 1e-6 * r;
        x - r < -tol || y - r < -tol || x + r > bw + tol || y + r > bh + tol
    };
    let n_out = disks.iter().filter(|d| outside(d)).count();
    if let Some((k, ([x, y], r))) = disks.iter().enumerate().find(|(_, d)| outside(d)) {
        let pos = t.get("box").map_or(t.pos, |n| n.pos);
        let msg = format!(
            "the lattice does not fit: {n_out} of {} disks extend beyond the {bw} x {bh} m box, e.g. disk {k} at ({x}, {y}) with radius {r}",
            disks.len()
        );
        ctx.err(pos, &t.field("box"), msg);
        return None;
    }
    Some((disks, common, ([0.0, 0.0], [bw, bh])))
}
