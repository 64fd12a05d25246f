//! The `[[generators]]` of a 3D scene: `box_of_spheres` and `lattice3d` (the rules of
//! ../shared/bench/box3d10k.md), each with the six walls of its box when `walls` names a group.

use std::collections::HashMap;
use std::f64::consts::PI;

use super::bodies::wall_body;
use crate::generators::{material_and_groups, radius_range, seed, BOX_KEYS};
use crate::read::{as_vec3, choose, ensure, int_in, Ctx, Got, Tbl};
use crate::shared::{Built3, Groups, Materials, Origin, Part};
use crate::tree::{Kind, Pos};
use crate::types::Drive;
use crate::types3d::{BodyDesc3, ShapeDesc3};
use crate::MAX_GENERATED;
use xper_math::SplitMix64;
use xper_math3d::Vector;

/// Fields common to both generators.
struct Common {
    density: f64,
    group: usize,
    walls: Option<usize>,
    velocity: [f64; 3],
}

/// Spheres (centre, radius), common fields and the box corners.
type Made = (Vec<([f64; 3], f64)>, Common, ([f64; 3], [f64; 3]));

/// Reads `[[generators]]` and appends their bodies to `built`.
pub(crate) fn generators(
    ctx: &mut Ctx,
    root: &Tbl,
    mats: &Materials,
    groups: &mut Groups,
    built: &mut Built3,
) {
    for (i, t) in root.tables(ctx, "generators") {
        let kinds = [("box_of_spheres", false), ("lattice3d", true)];
        let kind_got = t.string(ctx, "kind").req(ctx, &t, "kind");
        let Some(lattice) = choose(ctx, kind_got, &t.field("kind"), "generator kind", &kinds)
        else {
            continue;
        };
        let made = if lattice {
            lattice3d(ctx, &t, mats, groups)
        } else {
            box_of_spheres(ctx, &t, mats, groups)
        };
        let Some((spheres, common, (lo, hi))) = made else {
            continue;
        };
        let origin = |part| Origin {
            section: "generators",
            index: i,
            part,
            pos: t.pos,
        };
        built.reserve(spheres.len() + 6);
        for (k, (c, r)) in spheres.into_iter().enumerate() {
            let m = common.density * 4.0 / 3.0 * PI * r * r * r;
            let moment = 0.4 * m * r * r;
            let body = BodyDesc3 {
                shape: ShapeDesc3::Sphere { radius: r },
                position: c,
                orientation: [0.0; 3],
                velocity: common.velocity,
                angular_velocity: [0.0; 3],
                mass: m,
                inertia: [[moment, 0.0, 0.0], [0.0, moment, 0.0], [0.0, 0.0, moment]],
                group: common.group,
                drives: std::array::from_fn(|_| Drive::Free),
            };
            built.push(body, origin(Part::Sphere(k)));
        }
        if let Some(g) = common.walls {
            let faces = [
                (lo, Vector::z()),
                (hi, -Vector::z()),
                (lo, Vector::x()),
                (hi, -Vector::x()),
                (lo, Vector::y()),
                (hi, -Vector::y()),
            ];
            for (w, (point, n)) in faces.into_iter().enumerate() {
                let edge = if n.x != 0.0 { Vector::y() } else { Vector::x() };
                let wall = wall_body(point, n, edge, [f64::INFINITY; 2], g);
                built.push(wall, origin(Part::Face(w)));
            }
        }
    }
}

fn common(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<Common> {
    let shared = material_and_groups(ctx, t, mats, groups);
    let velocity = t.vec3(ctx, "velocity").or([0.0; 3]);
    let (density, group, walls) = shared?;
    Some(Common {
        density,
        group,
        walls,
        velocity: velocity?,
    })
}

/// `box = [[xmin, ymin, zmin], [xmax, ymax, zmax]]`.
fn box_corners(ctx: &mut Ctx, t: &Tbl) -> Option<([f64; 3], [f64; 3])> {
    let field = t.field("box");
    let Some(n) = t.get("box") else {
        t.missing(ctx, "box");
        return None;
    };
    let what = "[[xmin, ymin, zmin], [xmax, ymax, zmax]]";
    let Kind::Array(a) = &n.kind else {
        ctx.expected(n, &field, what);
        return None;
    };
    if a.len() != 2 {
        ctx.expected(n, &field, what);
        return None;
    }
    let lo = as_vec3(ctx, &a[0], &format!("{field}[0]"));
    let hi = as_vec3(ctx, &a[1], &format!("{field}[1]"));
    let (lo, hi) = (lo?, hi?);
    if !(0..3).all(|k| hi[k] > lo[k] && (hi[k] - lo[k]).is_finite()) {
        let msg = format!(
            "the max corner must exceed the min corner by a finite amount, got {lo:?} and {hi:?}"
        );
        ctx.err(n.pos, &field, msg);
        return None;
    }
    Some((lo, hi))
}

fn box_of_spheres(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<Made> {
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
    let size: [f64; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
    let count_pos = t.get("count").map_or(t.pos, |n| n.pos);
    let centres = if random {
        random_placement(ctx, t, count_pos, &radii, rmax, (lo, hi), &mut rng)?
    } else {
        let pitch = 2.0 * rmax * 1.05;
        let fit = size.map(|s| (s / pitch).floor().max(0.0) as u64);
        let fits = fit[0].saturating_mul(fit[1]).saturating_mul(fit[2]);
        if (count as u64) > fits {
            let msg = format!(
                "{count} spheres do not fit: a cubic lattice of pitch {pitch} m holds {fits} ({} x {} x {}) in the box",
                fit[0], fit[1], fit[2]
            );
            ctx.err(count_pos, &t.field("count"), msg);
            return None;
        }
        let (nx, ny) = (fit[0] as usize, fit[1] as usize);
        (0..count)
            .map(|k| {
                let ijk = [k % nx, k / nx % ny, k / (nx * ny)];
                std::array::from_fn(|a| lo[a] + pitch / 2.0 + ijk[a] as f64 * pitch)
            })
            .collect()
    };
    Some((centres.into_iter().zip(radii).collect(), common, (lo, hi)))
}

/// Largest fraction of the box volume the spheres of a random placement may fill (random
/// sequential addition of equal spheres jams at about 0.38: J. Talbot, G. Tarjus, P. Viot,
/// Colloids Surf. A 165 (2000) 287).
const RANDOM_JAMMING: f64 = 0.35;

/// Random sequential addition without overlap, at most `1000 * count` attempts in total.
fn random_placement(
    ctx: &mut Ctx,
    t: &Tbl,
    count_pos: Pos,
    radii: &[f64],
    rmax: f64,
    (lo, hi): ([f64; 3], [f64; 3]),
    rng: &mut SplitMix64,
) -> Option<Vec<[f64; 3]>> {
    let size: [f64; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
    if 2.0 * rmax > size.iter().copied().fold(f64::INFINITY, f64::min) {
        let msg = format!("a sphere of radius {rmax} m does not fit in a {size:?} m box");
        ctx.err(count_pos, &t.field("radius"), msg);
        return None;
    }
    let filled: f64 = radii
        .iter()
        .map(|r| 4.0 / 3.0 * PI * r * r * r)
        .sum::<f64>()
        / (size[0] * size[1] * size[2]);
    if !(filled <= RANDOM_JAMMING) {
        let msg = format!(
            "{} spheres fill {filled:.3} of the box volume: random placement jams at about 0.38 \
             (at most {RANDOM_JAMMING} accepted); use fewer or smaller spheres, a larger box or \
             placement = \"lattice\"",
            radii.len()
        );
        ctx.err(count_pos, &t.field("count"), msg);
        return None;
    }
    let cell = 2.0 * rmax;
    let key = |p: &[f64; 3]| -> [i64; 3] {
        std::array::from_fn(|k| ((p[k] - lo[k]) / cell).floor() as i64)
    };
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let mut centres: Vec<[f64; 3]> = Vec::with_capacity(radii.len());
    let budget = (radii.len() as u64).saturating_mul(1000);
    let mut attempts = 0u64;
    for &r in radii {
        loop {
            if attempts >= budget {
                let msg = format!(
                    "random placement failed after {attempts} attempts: placed {} of {} spheres",
                    centres.len(),
                    radii.len()
                );
                ctx.err(count_pos, &t.field("count"), msg);
                return None;
            }
            attempts += 1;
            let p: [f64; 3] =
                std::array::from_fn(|k| lo[k] + r + rng.next_f64() * (size[k] - 2.0 * r));
            let c = key(&p);
            let mut free = true;
            for d in 0..27 {
                let cell = [d % 3, d / 3 % 3, d / 9].map(|x| x as i64 - 1);
                let at = std::array::from_fn(|k| c[k].saturating_add(cell[k]));
                free &= grid.get(&at).into_iter().flatten().all(|&j| {
                    let q = centres[j];
                    let d2: f64 = (0..3).map(|k| (p[k] - q[k]) * (p[k] - q[k])).sum();
                    d2.sqrt() >= r + radii[j]
                });
            }
            if free {
                grid.entry(c).or_default().push(centres.len());
                centres.push(p);
                break;
            }
        }
    }
    Some(centres)
}

const LATTICE_KEYS: &[&str] = &[
    "kind", "columns", "rows", "layers", "pitch", "radius", "seed", "box", "material", "group",
    "walls", "velocity",
];

/// The rules of ../shared/bench/box3d10k.md: sphere `n = columns rows k + columns j + i`
/// at `(p/2 + i p + s, p/2 + j p + s, p/2 + k p)`, `s = p/2` on odd layers, radius
/// `radius (1 + u_n)` drawn in `n` order; the box's lower corner is the origin.
fn lattice3d(ctx: &mut Ctx, t: &Tbl, mats: &Materials, groups: &mut Groups) -> Option<Made> {
    t.check_keys(ctx, LATTICE_KEYS);
    let mut dims = ["columns", "rows", "layers"].map(|key| {
        let n = t.int(ctx, key).req(ctx, t, key);
        int_in(ctx, n, &t.field(key), 1, MAX_GENERATED)
    });
    let pitch = t.num(ctx, "pitch").req(ctx, t, "pitch");
    let pitch = ensure(ctx, pitch, &t.field("pitch"), |v| v > 0.0, "> 0 m");
    let radius = t.num(ctx, "radius").req(ctx, t, "radius");
    let radius = ensure(ctx, radius, &t.field("radius"), |v| v > 0.0, "> 0 m");
    let seed = seed(ctx, t);
    let size = t.vec3(ctx, "box").req(ctx, t, "box").and_then(|(s, pos)| {
        if s.iter().all(|&x| x > 0.0 && x.is_finite()) {
            Some(s)
        } else {
            let msg = format!("width, depth and height must be finite and > 0 m, got {s:?}");
            ctx.err(pos, &t.field("box"), msg);
            None
        }
    });
    let common = common(ctx, t, mats, groups);
    let [nx, ny, nz] = [dims[0].take()?, dims[1].take()?, dims[2].take()?];
    let total = nx.saturating_mul(ny).saturating_mul(nz);
    if total > MAX_GENERATED {
        let pos = t.get("layers").map_or(t.pos, |n| n.pos);
        let msg = format!(
            "columns x rows x layers = {total} exceeds the limit of {MAX_GENERATED} spheres"
        );
        ctx.err(pos, &t.field("layers"), msg);
        return None;
    }
    let (p, radius, seed, size, common) = (pitch?, radius?, seed?, size?, common?);
    let (nx, ny, nz) = (nx as usize, ny as usize, nz as usize);
    let mut rng = SplitMix64::new(seed);
    let mut spheres = Vec::with_capacity(nx * ny * nz);
    for k in 0..nz {
        let shift = if k % 2 == 1 { p / 2.0 } else { 0.0 };
        for j in 0..ny {
            for i in 0..nx {
                let c = [
                    p / 2.0 + i as f64 * p + shift,
                    p / 2.0 + j as f64 * p + shift,
                    p / 2.0 + k as f64 * p,
                ];
                spheres.push((c, radius * (1.0 + rng.next_f64())));
            }
        }
    }
    let outside = |(c, r): &([f64; 3], f64)| {
        let tol = 1e-9 + 1e-6 * r;
        (0..3).any(|a| c[a] - r < -tol || c[a] + r > size[a] + tol)
    };
    let out = spheres.iter().filter(|s| outside(s)).count();
    if let Some((n, (c, r))) = spheres.iter().enumerate().find(|(_, s)| outside(s)) {
        let pos = t.get("box").map_or(t.pos, |n| n.pos);
        let msg = format!(
            "the lattice does not fit: {out} of {} spheres extend beyond the {size:?} m box, e.g. sphere {n} at {c:?} with radius {r}",
            spheres.len()
        );
        ctx.err(pos, &t.field("box"), msg);
        return None;
    }
    Some((spheres, common, ([0.0; 3], size)))
}
