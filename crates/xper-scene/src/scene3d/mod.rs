//! 3D rigid scenes (`[scene] dimension = 3`): spheres, convex polyhedra and planar walls
//! (FORMAT.md, "3D scenes"). The sections shared with 2D scenes (`[solver]`, `[output]`,
//! `[[materials]]`, `[[laws]]`) are read by the same readers.

mod bodies;
mod generators;

use std::collections::HashMap;

use crate::read::{Ctx, Tbl};
use crate::sections::{self, Header};
use crate::shared::{Built3, Groups};
use crate::types3d::{Scene3, ShapeDesc3};
use crate::MAX_OVERLAP_REPORTS;
use xper_math3d::{Rotation, Vector};

/// Top-level keys of a 3D scene.
const TOP_KEYS: &[&str] = &[
    "scene",
    "solver",
    "output",
    "materials",
    "laws",
    "bodies",
    "walls",
    "generators",
];

/// Reads the rest of a 3D rigid scene whose `[scene]` table gave `header`.
pub(crate) fn rigid_scene3(ctx: &mut Ctx, root: &Tbl, header: Header) -> Option<Scene3> {
    if let Some(n) = root.get("fluid") {
        let msg = "a fluid is not available in 3D scenes yet (`[scene] dimension = 3`)";
        ctx.err(n.pos, "fluid", msg);
    }
    root.check_keys(ctx, TOP_KEYS);
    let solver = sections::solver(ctx, root);
    let output = sections::output(ctx, root, header.steps);
    let materials = sections::materials(ctx, root);
    let before = ctx.errors.len();
    let mut groups = Groups::default();
    let mut built = Built3::default();
    bodies::bodies(ctx, root, &materials, &mut groups, &mut built);
    bodies::walls(ctx, root, &mut groups, &mut built);
    generators::generators(ctx, root, &materials, &mut groups, &mut built);
    if ctx.errors.len() == before {
        overlaps(ctx, &built);
    }
    let laws = sections::laws(ctx, root, &groups);
    let steps = header.steps.unwrap_or(1);
    let alert_distance = header
        .alert_distance
        .unwrap_or(None)
        .unwrap_or_else(|| default_alert_distance(&built));
    Some(Scene3 {
        name: header.name.unwrap_or_default(),
        dt: header.dt.unwrap_or(0.0),
        steps,
        theta: header.theta.unwrap_or(0.5),
        gravity: header.gravity3.unwrap_or([0.0, 0.0, 0.0]),
        alert_distance,
        detection: header.detection.unwrap_or_default(),
        solver,
        output: output.settings(steps),
        groups: groups.names,
        laws,
        bodies: built.bodies,
    })
}

/// 0.1 x the smallest sphere radius; without spheres, 1e-3 x the smallest polyhedron size
/// (twice the largest centroid-vertex distance); without either, 0.
fn default_alert_distance(built: &Built3) -> f64 {
    let smallest = |f: &dyn Fn(&ShapeDesc3) -> Option<f64>| {
        (built.bodies.iter())
            .filter_map(|b| f(&b.shape))
            .fold(f64::INFINITY, f64::min)
    };
    let r = smallest(&|s| match s {
        ShapeDesc3::Sphere { radius } => Some(*radius),
        _ => None,
    });
    if r.is_finite() {
        return 0.1 * r;
    }
    let size = smallest(&|s| match s {
        ShapeDesc3::Polyhedron { vertices } => Some(
            2.0 * (vertices.iter())
                .map(|v| Vector::from(*v).norm())
                .fold(0.0, f64::max),
        ),
        _ => None,
    });
    if size.is_finite() {
        1e-3 * size
    } else {
        0.0
    }
}

/// Reports spheres that overlap another sphere or lie partly behind a wall at the start, by
/// more than `1e-9 + 1e-6 x` the smaller size (m), on a grid of cells of the largest
/// diameter. Polyhedra are not checked.
fn overlaps(ctx: &mut Ctx, built: &Built3) {
    let spheres: Vec<(usize, Vector, f64)> = (built.bodies.iter().enumerate())
        .filter_map(|(k, b)| match b.shape {
            ShapeDesc3::Sphere { radius } => Some((k, Vector::from(b.position), radius)),
            _ => None,
        })
        .collect();
    let Some(rmax) = spheres.iter().map(|s| s.2).reduce(f64::max) else {
        return;
    };
    let cell = 2.0 * rmax;
    let key = |x: &Vector| -> [i64; 3] { std::array::from_fn(|k| (x[k] / cell).floor() as i64) };
    let walls: Vec<(usize, Rotation, Vector, [f64; 2])> = (built.bodies.iter().enumerate())
        .filter_map(|(w, b)| match b.shape {
            ShapeDesc3::Plane { half_extents } => Some((
                w,
                Rotation::from_scaled_axis(Vector::from(b.orientation)),
                Vector::from(b.position),
                half_extents,
            )),
            _ => None,
        })
        .collect();
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (s, (_, x, _)) in spheres.iter().enumerate() {
        grid.entry(key(x)).or_default().push(s);
    }
    let mut found: Vec<(usize, usize, f64)> = Vec::new();
    let mut total = 0usize;
    let mut record = |a: usize, b: usize, depth: f64, size: f64| {
        if depth > 1e-9 + 1e-6 * size {
            total += 1;
            if found.len() < MAX_OVERLAP_REPORTS {
                found.push((a.min(b), a.max(b), depth));
            }
        }
    };
    for (s, &(b, x, r)) in spheres.iter().enumerate() {
        let c = key(&x);
        for d in 0..27 {
            let offset = [d % 3, d / 3 % 3, d / 9].map(|v| v as i64 - 1);
            let at = std::array::from_fn(|k| c[k].saturating_add(offset[k]));
            for &o in grid.get(&at).into_iter().flatten().filter(|&&o| o > s) {
                let (a, y, q) = spheres[o];
                record(a, b, r + q - (x - y).norm(), 2.0 * r.min(q));
            }
        }
        for &(w, rotation, point, half_extents) in &walls {
            let local = rotation.inverse_transform_vector(&(x - point));
            let within = local.x.abs() <= half_extents[0] && local.y.abs() <= half_extents[1];
            if within && local.z > -r {
                record(w, b, r - local.z, 2.0 * r);
            }
        }
    }
    crate::overlap::report(ctx, &built.origins, found, total);
}
