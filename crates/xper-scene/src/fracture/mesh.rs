//! `[mesh]`: a Gmsh file or a generator with its parameters.

use std::path::Path;

use xper_mesh::{Circle, NotchedSpec, PeriodicCellSpec, RandomCircles, RectangleSpec};

use super::types::{MeshDesc, MeshSource};
use super::{number, place, required_table};
use crate::read::{as_num, as_vec2, choose, int_in, Ctx, Tbl};
use crate::tree::{Kind, Node};

/// `[mesh]`: a file, or a generator with its parameters.
pub(super) fn mesh(ctx: &mut Ctx, root: &Tbl, file: &Path) -> Option<MeshDesc> {
    let t = required_table(ctx, root, "mesh")?;
    let keys = (t.entries.iter())
        .map(|e| (e.key.clone(), place(e.value.pos, t.field(&e.key))))
        .collect();
    let source = match (t.get("file"), t.get("generator")) {
        (Some(_), Some(g)) => {
            ctx.err(
                g.pos,
                &t.field("generator"),
                "give either `file` or `generator`, not both",
            );
            None
        }
        (None, None) => {
            ctx.err(
                t.pos,
                &t.field("generator"),
                "missing `generator` (double_edge_notched, rectangle_with_inclusions, \
                 periodic_cell) or `file` (a Gmsh MSH 4.1 file)",
            );
            None
        }
        (Some(_), None) => {
            t.check_keys(ctx, &["file"]);
            let (s, pos) = t.string(ctx, "file").ok()?;
            if s.trim().is_empty() {
                ctx.err(pos, &t.field("file"), "must name a .msh file, got \"\"");
                return None;
            }
            let dir = file.parent().unwrap_or(Path::new(""));
            Some(MeshSource::File(dir.join(s)))
        }
        (None, Some(_)) => {
            let kinds = [
                ("double_edge_notched", 0),
                ("rectangle_with_inclusions", 1),
                ("periodic_cell", 2),
            ];
            let got = t.string(ctx, "generator").ok();
            match choose(ctx, got, &t.field("generator"), "mesh generator", &kinds)? {
                0 => notched(ctx, &t),
                1 => rectangle(ctx, &t),
                _ => periodic_cell(ctx, &t),
            }
        }
    }?;
    Some(MeshDesc {
        source,
        place: place(t.pos, t.path.clone()),
        keys,
    })
}

fn length(ctx: &mut Ctx, t: &Tbl, key: &str) -> Option<f64> {
    number(ctx, t, key, |v| v > 0.0, "> 0 m")
}

fn notched(ctx: &mut Ctx, t: &Tbl) -> Option<MeshSource> {
    const KEYS: &[&str] = &[
        "generator",
        "side",
        "notch_depth",
        "notch_width",
        "element_size",
        "point_symmetric",
    ];
    t.check_keys(ctx, KEYS);
    let [side, notch_depth, notch_width, element_size] =
        [KEYS[1], KEYS[2], KEYS[3], KEYS[4]].map(|k| length(ctx, t, k));
    let point_symmetric = t.boolean(ctx, KEYS[5]).or(false);
    Some(MeshSource::DoubleEdgeNotched(NotchedSpec {
        side: side?,
        notch_depth: notch_depth?,
        notch_width: notch_width?,
        element_size: element_size?,
        point_symmetric: point_symmetric?,
    }))
}

fn rectangle(ctx: &mut Ctx, t: &Tbl) -> Option<MeshSource> {
    t.check_keys(
        ctx,
        &[
            "generator",
            "width",
            "height",
            "inclusions",
            "precrack",
            "element_size",
        ],
    );
    let [width, height, element_size] =
        ["width", "height", "element_size"].map(|k| length(ctx, t, k));
    let inclusions = match t.get("inclusions") {
        None => Some(Vec::new()),
        Some(n) => inclusions(ctx, n, &t.field("inclusions")),
    };
    let precrack = match t.get("precrack") {
        None => Some(None),
        Some(n) => two_points(ctx, n, &t.field("precrack")).map(|[a, b]| Some((a, b))),
    };
    Some(MeshSource::RectangleWithInclusions(RectangleSpec {
        width: width?,
        height: height?,
        inclusions: inclusions?,
        precrack: precrack?,
        element_size: element_size?,
    }))
}

fn periodic_cell(ctx: &mut Ctx, t: &Tbl) -> Option<MeshSource> {
    t.check_keys(
        ctx,
        &[
            "generator",
            "width",
            "height",
            "circles",
            "rectangles",
            "random",
            "element_size",
        ],
    );
    let [width, height, element_size] =
        ["width", "height", "element_size"].map(|k| length(ctx, t, k));
    let rectangles = match t.get("rectangles") {
        None => Some(Vec::new()),
        Some(n) => inclusions(ctx, n, &t.field("rectangles")),
    };
    let mut circles = Some(Vec::new());
    for (_, c) in t.tables(ctx, "circles") {
        c.check_keys(ctx, &["center", "radius"]);
        let center = c.vec2(ctx, "center").req(ctx, &c, "center");
        let radius = length(ctx, &c, "radius");
        match (center, radius, circles.as_mut()) {
            (Some((center, _)), Some(radius), Some(list)) => list.push(Circle { center, radius }),
            _ => circles = None,
        }
    }
    let random = match t.table(ctx, "random").ok() {
        None => Some(None),
        Some((r, _)) => {
            r.check_keys(ctx, &["fraction", "radius", "min_spacing", "seed"]);
            let fraction = number(ctx, &r, "fraction", |v| v > 0.0 && v < 0.6, "in (0, 0.6)");
            let radius = length(ctx, &r, "radius");
            let spacing = super::number_or(ctx, &r, "min_spacing", 0.0, |v| v >= 0.0, ">= 0 m");
            let got = r.int(ctx, "seed").req(ctx, &r, "seed");
            let seed = int_in(ctx, got, &r.field("seed"), 0, i64::MAX).map(|s| s as u64);
            match (fraction, radius, spacing, seed) {
                (Some(fraction), Some(radius), Some(min_spacing), Some(seed)) => {
                    Some(Some(RandomCircles {
                        fraction,
                        radius,
                        min_spacing,
                        seed,
                    }))
                }
                _ => None,
            }
        }
    };
    Some(MeshSource::PeriodicCell(PeriodicCellSpec {
        width: width?,
        height: height?,
        circles: circles?,
        rectangles: rectangles?,
        random: random?,
        element_size: element_size?,
    }))
}

/// `[[xmin, ymin, xmax, ymax], ...]`.
fn inclusions(ctx: &mut Ctx, n: &Node, field: &str) -> Option<Vec<[f64; 4]>> {
    let what = "an array of inclusions [[xmin, ymin, xmax, ymax], ...]";
    let Kind::Array(items) = &n.kind else {
        ctx.expected(n, field, what);
        return None;
    };
    let mut out = Vec::new();
    let mut ok = true;
    for (k, e) in items.iter().enumerate() {
        let f = format!("{field}[{k}]");
        let values: Option<Vec<f64>> = match &e.kind {
            Kind::Array(v) if v.len() == 4 => (v.iter().enumerate())
                .map(|(j, x)| as_num(ctx, x, &format!("{f}[{j}]")))
                .collect::<Vec<_>>()
                .into_iter()
                .collect(),
            _ => {
                ctx.expected(e, &f, "four numbers [xmin, ymin, xmax, ymax] (m)");
                None
            }
        };
        match values {
            Some(v) if v[0] < v[2] && v[1] < v[3] => out.push([v[0], v[1], v[2], v[3]]),
            Some(v) => {
                ctx.err(
                    e.pos,
                    &f,
                    format!("needs xmin < xmax and ymin < ymax, got {v:?}"),
                );
                ok = false;
            }
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// `[[x0, y0], [x1, y1]]`.
pub(super) fn two_points(ctx: &mut Ctx, n: &Node, field: &str) -> Option<[[f64; 2]; 2]> {
    match &n.kind {
        Kind::Array(a) if a.len() == 2 => {
            let p = as_vec2(ctx, &a[0], &format!("{field}[0]"));
            let q = as_vec2(ctx, &a[1], &format!("{field}[1]"));
            Some([p?, q?])
        }
        _ => {
            ctx.expected(n, field, "two points [[x0, y0], [x1, y1]] (m)");
            None
        }
    }
}
