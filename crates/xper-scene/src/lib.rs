//! The TOML scene format: parsing, validation with file/line/column errors, generators.
//!
//! [`parse_scene`] reads the text of a scene file (format described in `FORMAT.md`),
//! validates everything, collecting *all* errors (each with file, line, column, field path
//! and reason), expands the generators and returns a flat [`Scene`] of plain data that
//! knows nothing of the engine. It never panics, whatever the input.

// Negated float comparisons (`!(x > 0.0)`) are deliberate: they also reject NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]

pub mod error;
pub mod rng;
pub mod types;

mod bodies;
mod generators;
mod geometry;
mod overlap;
mod read;
mod sections;
mod shared;
mod tree;

use std::path::Path;

pub use error::{SceneError, SceneErrors};
pub use generators::MAX_GENERATED;
pub use overlap::MAX_OVERLAP_REPORTS;
pub use rng::SplitMix64;
pub use types::{
    BodyDesc, ConvergenceNorm, Drive, LawDesc, OutputSettings, Scene, ShapeDesc, SolverKind,
    SolverSettings, TimeFunction,
};

use read::{Ctx, Tbl};
use shared::{Built, Groups};
use tree::{LineIndex, Pos};

/// Top-level keys of a scene file.
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

/// Reads and parses the scene file at `path`. An I/O error is reported as a single
/// [`SceneError`] with line and column 0.
pub fn load_scene(path: &Path) -> Result<Scene, SceneErrors> {
    match std::fs::read_to_string(path) {
        Ok(text) => parse_scene(&text, path),
        Err(e) => Err(SceneErrors(vec![SceneError {
            file: path.to_path_buf(),
            line: 0,
            column: 0,
            field: String::new(),
            message: format!("cannot read the scene file: {e}"),
        }])),
    }
}

/// Parses and validates the text of a scene file; `file` is only used in messages.
/// Returns every error found, sorted by position.
pub fn parse_scene(text: &str, file: &Path) -> Result<Scene, SceneErrors> {
    let idx = LineIndex::new(text);
    let mut ctx = Ctx::new(file);
    let doc = match toml_edit::ImDocument::parse(text) {
        Ok(doc) => doc,
        Err(e) => {
            let pos = idx.span_pos(e.span(), Pos::START);
            let msg = e.message().trim().replace('\n', "; ");
            ctx.err(pos, "", format!("TOML syntax error: {msg}"));
            return Err(SceneErrors(ctx.errors));
        }
    };
    let root_node = tree::root(doc.as_table(), &idx);
    let Some(root) = Tbl::of(&mut ctx, &root_node, String::new()) else {
        return Err(SceneErrors(ctx.errors));
    };
    root.check_keys(&mut ctx, TOP_KEYS);
    let header = sections::header(&mut ctx, &root);
    let solver = sections::solver(&mut ctx, &root);
    let output = sections::output(&mut ctx, &root, header.steps);
    let materials = sections::materials(&mut ctx, &root);

    let before = ctx.errors.len();
    let mut groups = Groups::default();
    let mut built = Built::default();
    bodies::bodies(&mut ctx, &root, &materials, &mut groups, &mut built);
    bodies::walls(&mut ctx, &root, &mut groups, &mut built);
    generators::generators(&mut ctx, &root, &materials, &mut groups, &mut built);
    if ctx.errors.len() == before {
        // Only when every body was built, so that indices are those of the scene.
        overlap::check(&mut ctx, &built);
    }
    let laws = sections::laws(&mut ctx, &root, &groups);

    let steps = header.steps.unwrap_or(1);
    let alert_distance = header
        .alert_distance
        .unwrap_or(None)
        .unwrap_or_else(|| default_alert_distance(&built));
    let scene = Scene {
        name: header.name.unwrap_or_default(),
        dt: header.dt.unwrap_or(0.0),
        steps,
        theta: header.theta.unwrap_or(0.5),
        gravity: header.gravity.unwrap_or([0.0, 0.0]),
        alert_distance,
        solver,
        output: OutputSettings {
            frame_every: output
                .frame_every
                .flatten()
                .unwrap_or(steps.div_ceil(100).max(1)),
            checkpoint_every: output
                .checkpoint_every
                .flatten()
                .unwrap_or(steps.div_ceil(10).max(1)),
            dump_problems: output.dump_problems,
        },
        groups: groups.names,
        laws,
        bodies: built.bodies,
    };
    if ctx.errors.is_empty() {
        Ok(scene)
    } else {
        let mut errors = ctx.errors;
        errors.sort_by_key(|e| (e.line, e.column));
        Err(SceneErrors(errors))
    }
}

/// 0.1 x the smallest disk radius; without disks, 1e-3 x the smallest polygon size
/// (twice the largest centroid-vertex distance); without either, 0.
fn default_alert_distance(built: &Built) -> f64 {
    let min_of = |f: &dyn Fn(&ShapeDesc) -> Option<f64>| {
        built
            .bodies
            .iter()
            .filter_map(|b| f(&b.shape))
            .fold(f64::INFINITY, f64::min)
    };
    let r = min_of(&|s| match s {
        ShapeDesc::Disk { radius } => Some(*radius),
        _ => None,
    });
    if r.is_finite() {
        return 0.1 * r;
    }
    let p = min_of(&|s| match s {
        ShapeDesc::Polygon { vertices } => Some(2.0 * geometry::circumradius(vertices)),
        _ => None,
    });
    if p.is_finite() {
        1e-3 * p
    } else {
        0.0
    }
}
