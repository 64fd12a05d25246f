//! The TOML scene format: parsing, validation with file/line/column errors, generators.
//!
//! [`parse_scene`] reads the text of a scene file (format described in `FORMAT.md`),
//! validates everything, collecting *all* errors (each with file, line, column, field path
//! and reason), expands the generators and returns a flat [`Scene`] of plain data that
//! knows nothing of the engine. It never panics, whatever the input.
//!
//! A scene with a `[mesh]` section is a fracture scene: [`parse_any_scene`] /
//! [`load_any_scene`] read either kind ([`AnyScene`]); a [`FractureScene`] is plain data too,
//! and [`FractureScene::build`] reads or generates its mesh and checks the rest against it,
//! giving the mesh and the `xper_fracture::FractureSpec` to build the model from.

// Negated float comparisons (`!(x > 0.0)`) are deliberate: they also reject NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]

pub mod error;
pub mod types;
pub mod types3d;

mod bodies;
mod cell;
mod document;
mod events;
mod fluid;
mod fracture;
mod generators;
mod geometry;
mod overlap;
mod pressure;
mod read;
mod scene3d;
mod sections;
mod shared;
mod tree;

use std::path::Path;

pub use error::{SceneError, SceneErrors};
pub use fracture::build::FractureSetup;
pub use fracture::types::{
    AnyScene, EdgeSetRef, FractureScene, InterfaceDesc, InterfaceLawDesc, LoadDesc, MeshDesc,
    MeshSource, Place, RegionDesc, Stiffness,
};
pub use generators::MAX_GENERATED;
pub use overlap::MAX_OVERLAP_REPORTS;
pub use types::{
    Acceleration, BodyDesc, CellDesc, CellLoadDesc, CheckPass, ConvergenceNorm, Detection, Drive,
    EventDesc, ExtentDesc, FluidDesc, FluidSideDesc, LawDesc, MicroVolume, OutputSettings,
    PressureDesc, Scene, ShapeDesc, SolverSettings, TimeFunction, VelocitySolverKind,
};
pub use types3d::{BodyDesc3, Scene3, ShapeDesc3};
pub use xper_math::SplitMix64;

use read::{Ctx, Tbl};
use shared::{Built, Groups};
use tree::{LineIndex, Pos};

/// Top-level keys of a scene file.
const TOP_KEYS: &[&str] = &[
    "scene",
    "fluid",
    "solver",
    "output",
    "materials",
    "laws",
    "bodies",
    "walls",
    "generators",
    "events",
    "cell",
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

/// Reads and parses a scene file of either kind (see [`parse_any_scene`]).
pub fn load_any_scene(path: &Path) -> Result<AnyScene, SceneErrors> {
    match std::fs::read_to_string(path) {
        Ok(text) => parse_any_scene(&text, path),
        Err(e) => Err(SceneErrors(vec![SceneError {
            file: path.to_path_buf(),
            line: 0,
            column: 0,
            field: String::new(),
            message: format!("cannot read the scene file: {e}"),
        }])),
    }
}

/// Parses and validates a scene of either kind: a fracture scene when it has a `[mesh]`
/// section ([`parse_fracture_scene`]), else a rigid scene ([`parse_scene`]). The text is
/// parsed once.
pub fn parse_any_scene(text: &str, file: &Path) -> Result<AnyScene, SceneErrors> {
    with_root(text, file, |ctx, root| {
        if root.get("mesh").is_some() {
            return fracture::fracture_scene(ctx, root, file).map(AnyScene::Fracture);
        }
        let header = sections::header(ctx, root);
        if header.dimension == Some(3) {
            scene3d::rigid_scene3(ctx, root, header).map(AnyScene::Rigid3)
        } else {
            rigid_scene_with(ctx, root, header).map(AnyScene::Rigid)
        }
    })
}

/// Parses and validates the text of a fracture scene (FORMAT.md, "Fracture scenes"); `file`
/// is used in messages and to resolve a mesh file. Checks that need the mesh are left to
/// [`FractureScene::build`]. Returns every error found, sorted by position.
pub fn parse_fracture_scene(text: &str, file: &Path) -> Result<FractureScene, SceneErrors> {
    with_root(text, file, |ctx, root| {
        fracture::fracture_scene(ctx, root, file)
    })
}

/// The field a TOML syntax error on 1-based `line` of `text` is in: `table.key` (with the index
/// of an array of tables, `bodies[2].radius`) on a `key = value` line, `(table header)` on a
/// header line, `(no key)` otherwise. The lines are read once, up to `line`.
fn syntax_error_field(text: &str, line: usize) -> String {
    let mut table = String::new();
    let mut arrays: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    for (k, raw) in text.lines().take(line).enumerate() {
        let l = raw.trim();
        let last = k + 1 == line;
        if l.starts_with('[') {
            if last {
                return "(table header)".into();
            }
            let name = l
                .trim_start_matches('[')
                .split(']')
                .next()
                .unwrap_or("")
                .trim();
            table = if l.starts_with("[[") {
                let count = arrays.entry(name.to_string()).or_insert(0);
                *count += 1;
                format!("{name}[{}]", *count - 1)
            } else {
                name.to_string()
            };
        } else if last {
            return match l.split_once('=') {
                Some((key, _)) if !key.trim().is_empty() && !l.starts_with('#') => {
                    let key = key.trim().trim_matches(|c| c == '"' || c == '\'');
                    if table.is_empty() {
                        key.to_string()
                    } else {
                        format!("{table}.{key}")
                    }
                }
                _ => "(no key)".into(),
            };
        }
    }
    "(no key)".into()
}

/// Parses the TOML of `text` and hands its root table to `read`; the result is returned when
/// no error was recorded, else every error sorted by position.
fn with_root<T>(
    text: &str,
    file: &Path,
    read: impl FnOnce(&mut Ctx, &Tbl) -> Option<T>,
) -> Result<T, SceneErrors> {
    let idx = LineIndex::new(text);
    let mut ctx = Ctx::new(file);
    let root_node = match document::parse(text, &idx) {
        Ok(root) => root,
        Err(e) => {
            let pos = idx.pos(e.offset);
            let field = syntax_error_field(text, pos.line as usize);
            ctx.err(pos, &field, format!("TOML syntax error: {}", e.message));
            return Err(SceneErrors(ctx.errors));
        }
    };
    let value = Tbl::of(&mut ctx, &root_node, String::new()).and_then(|root| read(&mut ctx, &root));
    match value {
        Some(v) if ctx.errors.is_empty() => Ok(v),
        _ => {
            if ctx.errors.is_empty() {
                ctx.err(Pos::START, "", "invalid scene");
            }
            let mut errors = ctx.errors;
            errors.sort_by_key(|e| (e.line, e.column));
            Err(SceneErrors(errors))
        }
    }
}

/// Parses and validates the text of a rigid scene file; `file` is only used in messages.
/// Returns every error found, sorted by position. A fracture scene (with `[mesh]`) is an
/// error here: read it with [`parse_any_scene`].
pub fn parse_scene(text: &str, file: &Path) -> Result<Scene, SceneErrors> {
    with_root(text, file, rigid_scene)
}

fn rigid_scene(ctx: &mut Ctx, root: &Tbl) -> Option<Scene> {
    if let Some(n) = root.get("mesh") {
        let msg = "`[mesh]` makes this a fracture scene, which the rigid-scene reader does not \
                   read (use `parse_any_scene`; `xper check` and `xper run` read both kinds)";
        ctx.err(n.pos, "mesh", msg);
        return None;
    }
    let header = sections::header(ctx, root);
    if header.dimension == Some(3) {
        let pos = (root
            .get("scene")
            .and_then(|n| Tbl::of(ctx, n, "scene".into())))
        .and_then(|t| t.get("dimension").map(|n| n.pos))
        .unwrap_or(Pos::START);
        let msg = "a 3D scene: the 2D rigid-scene reader does not read it (use `parse_any_scene`; \
                   `xper check` and `xper run` read every kind)";
        ctx.err(pos, "scene.dimension", msg);
        return None;
    }
    rigid_scene_with(ctx, root, header)
}

/// [`rigid_scene`] once the `[scene]` table is read.
fn rigid_scene_with(ctx: &mut Ctx, root: &Tbl, header: sections::Header) -> Option<Scene> {
    root.check_keys(ctx, TOP_KEYS);
    let solver = sections::solver(ctx, root);
    let output = sections::output(ctx, root, header.steps);
    let materials = sections::materials(ctx, root);

    let before = ctx.errors.len();
    let mut groups = Groups::default();
    let mut built = Built::default();
    bodies::bodies(ctx, root, &materials, &mut groups, &mut built);
    let mut spans = Vec::new();
    bodies::walls(ctx, root, &mut groups, &mut built, &mut spans);
    generators::generators(ctx, root, &materials, &mut groups, &mut built);
    pressure::resolve(ctx, &groups, &mut built, spans);
    if ctx.errors.len() == before {
        // Only when every body was built, so that indices are those of the scene.
        overlap::check(ctx, &built);
    }
    let laws = sections::laws(ctx, root, &groups);
    let fluid = fluid::fluid(ctx, root, &built).flatten();
    let cell = cell::cell::<2>(ctx, root, cell::largest_2d(&built.bodies)).flatten();
    let event_scene = events::EventScene {
        groups: &groups,
        built: &built,
        laws: &laws,
        dofs: ["x", "y", "rotation"],
        cell: cell.as_ref(),
    };
    let events = events::events(ctx, root, event_scene);
    if let (Some(_), Some(n)) = (&fluid, root.get("cell")) {
        ctx.err(
            n.pos,
            "cell",
            "a periodic cell holds rigid scenes without `[fluid]`",
        );
    }
    cell::check_scene(ctx, root, cell.is_some(), solver.kind, output.micro);
    if let (Some(_), Some(n)) = (&fluid, root.get("events")) {
        let why = "events change rigid scenes without `[fluid]`";
        ctx.err(n.pos, "events", why);
    }
    if let (Some(_), Some(_), Some(t)) = (&fluid, output.micro, root.get("output")) {
        if let Some(n) = (Tbl::of(ctx, t, "output".into())).and_then(|t| t.get("micro")) {
            let why = "the granular measures are of rigid scenes without `[fluid]`";
            ctx.err(n.pos, "output.micro", why);
        }
    }

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
        detection: header.detection.unwrap_or_default(),
        solver,
        output: output.settings(steps),
        groups: groups.names,
        laws,
        bodies: built.bodies,
        fluid,
        events,
        cell,
    };
    Some(scene)
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
