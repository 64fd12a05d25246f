//! 3D rigid scenes (`[scene] dimension = 3`): spheres, convex polyhedra and planar walls
//! (FORMAT.md, "3D scenes"). The sections shared with 2D scenes (`[solver]`, `[output]`,
//! `[[materials]]`, `[[laws]]`) are read by the same readers.

mod bodies;
mod generators;
mod overlaps;

use crate::read::{Ctx, Tbl};
use crate::sections::{self, Header};
use crate::shared::{Built3, Groups};
use crate::types3d::{Scene3, ShapeDesc3};

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
    "cell",
    "events",
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
    let mut spans = Vec::new();
    bodies::walls(ctx, root, &mut groups, &mut built, &mut spans);
    generators::generators(ctx, root, &materials, &mut groups, &mut built);
    crate::pressure::resolve3(ctx, &groups, &mut built, spans);
    if ctx.errors.len() == before {
        overlaps::overlaps(ctx, &built);
    }
    let laws = sections::laws(ctx, root, &groups);
    let cell = crate::cell::cell::<3>(ctx, root, crate::cell::largest_3d(&built.bodies)).flatten();
    crate::cell::check_scene(ctx, root, cell.is_some(), solver.kind, output.micro);
    let event_scene = crate::events::EventScene {
        groups: &groups,
        built: &built,
        laws: &laws,
        dofs: bodies::DOFS3,
        cell: cell.as_ref(),
    };
    let events = crate::events::events(ctx, root, event_scene);
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
        cell,
        events,
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
        ShapeDesc3::Polyhedron { .. } => s.size(),
        _ => None,
    });
    if size.is_finite() {
        1e-3 * size
    } else {
        0.0
    }
}
