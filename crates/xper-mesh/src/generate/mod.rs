//! Built-in specimen generators by constrained Delaunay refinement.
//!
//! A generator writes its domain as a planar straight-line graph (PSLG): boundary and
//! internal lines, each cut into pieces no longer than the element size `h`. Spade builds
//! the constrained Delaunay triangulation of that graph and refines it with Ruppert's
//! algorithm (J. Ruppert, "A Delaunay refinement algorithm for quality 2-dimensional mesh
//! generation", J. Algorithms 18(3):548-585, 1995; Chew's and Shewchuk's variants, see
//! J. R. Shewchuk, "Delaunay refinement algorithms for triangular mesh generation",
//! Comput. Geom. 22:21-74, 2002) with a minimum angle of [`MIN_ANGLE_DEGREES`] and a maximum
//! triangle area of [`MAX_AREA_FACTOR`] `h^2`. Nodes that the refinement put on a
//! straight axis-aligned line are snapped back onto it exactly, so that boundary conditions
//! and areas are exact. The result is deterministic: the same specification gives the same
//! mesh, node for node.

mod notched;
mod periodic;
mod rectangle;
pub mod symmetric;

pub use notched::{double_edge_notched, NotchedSpec};
pub use periodic::{periodic_cell, Circle, PeriodicCellSpec, RandomCircles};
pub use rectangle::{rectangle_with_inclusions, RectangleSpec};

use std::collections::HashMap;

use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};

use crate::error::{MeshError, MeshErrorKind};
use crate::select::distance_to_segment;

/// Smallest interior angle (degrees) the refinement asks for (spade's default). Ruppert's
/// algorithm is proven to terminate for limits up to about 20.7 degrees and in practice does
/// up to about 33 degrees; the inputs here have no angle below 90 degrees.
pub const MIN_ANGLE_DEGREES: f64 = 30.0;

/// The refinement splits every triangle whose area exceeds `MAX_AREA_FACTOR * h^2` (m^2):
/// sqrt(3)/4, the area of the equilateral triangle of side `h`. With the angle limit the
/// mesh comes out with a mean edge of about 0.83 h and a longest edge of about 1.4 h.
pub const MAX_AREA_FACTOR: f64 = 0.433_012_701_892_219_3;

/// Largest number of triangles a generator accepts to make (a guard against a forgotten
/// unit in `element_size`).
pub const MAX_TRIANGLES: f64 = 2.0e7;

/// A straight line of the domain (m), with the name of the edge set its mesh edges join.
#[derive(Clone, Debug)]
pub(crate) struct Line {
    pub a: [f64; 2],
    pub b: [f64; 2],
    pub set: &'static str,
}

/// The planar straight-line graph handed to the triangulator: points (m) and segments.
#[derive(Default)]
pub(crate) struct Pslg {
    pub points: Vec<[f64; 2]>,
    pub segments: Vec<[usize; 2]>,
    index: HashMap<[u64; 2], usize>,
}

impl Pslg {
    /// The index of point `p`, added if new (points are equal when bitwise equal).
    fn point(&mut self, p: [f64; 2]) -> usize {
        let key = [p[0].to_bits(), p[1].to_bits()];
        let next = self.points.len();
        *self.index.entry(key).or_insert_with(|| {
            self.points.push(p);
            next
        })
    }

    /// Adds the segment `a`-`b`, cut at the `breaks` that lie strictly inside it and then
    /// into pieces no longer than `h`. On an axis-aligned segment the cut points keep the
    /// constant coordinate exactly.
    pub fn add_line(&mut self, a: [f64; 2], b: [f64; 2], breaks: &[[f64; 2]], h: f64) {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let mut inner: Vec<(f64, [f64; 2])> = breaks
            .iter()
            .filter(|p| distance_to_segment(**p, a, b) <= 1e-12 * len2.sqrt())
            .map(|p| (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2, *p))
            .filter(|&(s, _)| s > 0.0 && s < 1.0)
            .collect();
        inner.sort_by(|x, y| x.0.total_cmp(&y.0));
        let stops: Vec<[f64; 2]> = std::iter::once(a)
            .chain(inner.into_iter().map(|(_, p)| p))
            .chain(std::iter::once(b))
            .collect();
        for w in stops.windows(2) {
            let (p, q) = (w[0], w[1]);
            let len = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
            let n = ((len / h).ceil() as usize).max(1);
            let mut prev = self.point(p);
            for i in 1..=n {
                let next = if i == n {
                    self.point(q)
                } else {
                    self.point(lerp(p, q, i as f64 / n as f64))
                };
                self.segments.push([prev, next]);
                prev = next;
            }
        }
    }
}

/// The point `a + s (b - a)`, keeping a coordinate that `a` and `b` share exactly.
fn lerp(a: [f64; 2], b: [f64; 2], s: f64) -> [f64; 2] {
    let c = |i: usize| {
        if a[i] == b[i] {
            a[i]
        } else {
            a[i] + s * (b[i] - a[i])
        }
    };
    [c(0), c(1)]
}

/// Checks that a length (m) is finite and positive.
pub(crate) fn positive(origin: &str, field: &str, value: f64) -> Result<(), MeshError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(MeshError::new(
            MeshErrorKind::Spec,
            origin,
            format!("must be finite and positive, got {value}"),
        )
        .at(field))
    }
}

/// About how many triangles meshing `area` (m^2) with element size `h` (m) gives (before
/// meshing: the estimate behind [`MAX_TRIANGLES`] and the memory estimate of a scene).
pub fn estimated_triangles(area: f64, h: f64) -> f64 {
    area / (MAX_AREA_FACTOR * h * h) * 2.0
}

/// Checks that meshing `area` (m^2) with element size `h` (m) stays below [`MAX_TRIANGLES`].
pub(crate) fn check_count(origin: &str, area: f64, h: f64) -> Result<(), MeshError> {
    let estimate = estimated_triangles(area, h);
    if estimate > MAX_TRIANGLES {
        return Err(MeshError::new(
            MeshErrorKind::Spec,
            origin,
            format!(
                "element size {h} m would give about {estimate:.2e} triangles \
                 (more than {MAX_TRIANGLES:.0e}); check the units (m)"
            ),
        )
        .at("element_size"));
    }
    Ok(())
}

/// A triangulated domain: nodes (m) and counter-clockwise triangles.
pub(crate) struct RawMesh {
    pub nodes: Vec<[f64; 2]>,
    pub triangles: Vec<[u32; 3]>,
}

/// How [`triangulate`] refines.
#[derive(Clone, Copy, Default)]
pub(crate) struct Refine {
    /// The refinement skips the faces outside the closed outline (a non-convex domain with a
    /// single outline).
    pub exclude_outer: bool,
    /// The refinement never splits a line of the PSLG (a periodic cell: its opposite sides
    /// must keep the same nodes).
    pub keep_lines: bool,
}

/// Triangulates and refines `pslg` for element size `h` (m) as `refine` says, keeps the
/// triangles whose centroid satisfies `inside`, drops unused nodes, and snaps the nodes lying
/// on an axis-aligned line of `lines` onto it.
pub(crate) fn triangulate(
    origin: &str,
    pslg: Pslg,
    h: f64,
    refine: Refine,
    inside: impl Fn([f64; 2]) -> bool,
    lines: &[Line],
) -> Result<RawMesh, MeshError> {
    let fail = |reason: String| MeshError::new(MeshErrorKind::Spec, origin, reason);
    let points: Vec<Point2<f64>> = pslg
        .points
        .iter()
        .map(|p| Point2::new(p[0], p[1]))
        .collect();
    let mut conflicts = Vec::new();
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::try_bulk_load_cdt(points, pslg.segments, |e| {
            conflicts.push(e)
        })
        .map_err(|e| fail(format!("triangulation failed: {e:?}")))?;
    if !conflicts.is_empty() {
        return Err(fail(format!(
            "{} boundary or internal lines cross each other",
            conflicts.len()
        )));
    }
    let area: f64 = cdt.inner_faces().map(|f| f.area()).sum();
    let budget = (8.0 * area / (MAX_AREA_FACTOR * h * h)) as usize + 10_000;
    let mut parameters = RefinementParameters::<f64>::new()
        .with_angle_limit(AngleLimit::from_deg(MIN_ANGLE_DEGREES))
        .with_max_allowed_area(MAX_AREA_FACTOR * h * h)
        .with_max_additional_vertices(budget)
        .exclude_outer_faces(refine.exclude_outer);
    if refine.keep_lines {
        parameters = parameters.keep_constraint_edges();
    }
    // Spade panics when a circumcentre cannot be represented (features far below h in
    // floating point): that is reported as an error, and the triangulation is dropped.
    let refined = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| cdt.refine(parameters)));
    let Ok(result) = refined else {
        return Err(fail(
            "Delaunay refinement failed (features too small for the element size?)".into(),
        ));
    };
    if !result.refinement_complete {
        return Err(fail(format!(
            "Delaunay refinement did not finish within {budget} added nodes"
        )));
    }
    let mut map = vec![u32::MAX; cdt.num_vertices()];
    let mut nodes = Vec::new();
    let mut triangles = Vec::new();
    for face in cdt.inner_faces() {
        let v = face.vertices();
        let p = v.map(|v| {
            let q = v.position();
            [q.x, q.y]
        });
        let centroid = [
            (p[0][0] + p[1][0] + p[2][0]) / 3.0,
            (p[0][1] + p[1][1] + p[2][1]) / 3.0,
        ];
        if !inside(centroid) {
            continue;
        }
        let tri = [0, 1, 2].map(|k| {
            let i = v[k].fix().index();
            if map[i] == u32::MAX {
                map[i] = nodes.len() as u32;
                nodes.push(p[k]);
            }
            map[i]
        });
        triangles.push(tri);
    }
    snap(&mut nodes, lines, h);
    Ok(RawMesh { nodes, triangles })
}

/// Puts each node lying within `1e-9 h` of an axis-aligned line exactly on it.
fn snap(nodes: &mut [[f64; 2]], lines: &[Line], h: f64) {
    let tol = 1e-9 * h;
    for line in lines {
        let axis = if line.a[0] == line.b[0] {
            0
        } else if line.a[1] == line.b[1] {
            1
        } else {
            continue;
        };
        for p in nodes.iter_mut() {
            if p[axis] != line.a[axis] && distance_to_segment(*p, line.a, line.b) <= tol {
                p[axis] = line.a[axis];
            }
        }
    }
}

/// The mesh of a generator: `raw` with its regions, and one edge set per name in `sets`, made
/// of the mesh edges lying on the `lines` of that set (errors attributed to `origin`).
pub(crate) fn finish_mesh(
    origin: &str,
    raw: RawMesh,
    triangle_region: Vec<u32>,
    regions: Vec<crate::mesh::Region>,
    lines: &[Line],
    h: f64,
    sets: &[&str],
) -> Result<crate::mesh::Mesh, MeshError> {
    let edges: Vec<Vec<[u32; 2]>> = sets
        .iter()
        .map(|name| {
            (lines.iter().filter(|l| l.set == *name))
                .flat_map(|l| edges_on(&raw, l, h))
                .collect()
        })
        .collect();
    let mut mesh = crate::mesh::Mesh::new(raw.nodes, raw.triangles, triangle_region, regions)
        .map_err(|e| e.from_origin(origin))?;
    for (name, edges) in sets.iter().zip(edges) {
        mesh = mesh
            .with_edge_set(name, &edges)
            .map_err(|e| e.from_origin(origin))?;
    }
    Ok(mesh)
}

/// The edges of `triangles` whose two nodes lie within `1e-9 h` of `line`, nodes ascending,
/// sorted.
pub(crate) fn edges_on(raw: &RawMesh, line: &Line, h: f64) -> Vec<[u32; 2]> {
    let tol = 1e-9 * h;
    let on = |n: u32| distance_to_segment(raw.nodes[n as usize], line.a, line.b) <= tol;
    let mut edges: Vec<[u32; 2]> = Vec::new();
    for t in &raw.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if on(a) && on(b) {
                edges.push(if a < b { [a, b] } else { [b, a] });
            }
        }
    }
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// The four sides of `[0, w] x [0, h]` (m), lines of the edge sets `bottom`, `right`, `top`
/// and `left`, in that order.
pub(crate) fn rectangle_sides(w: f64, h: f64) -> Vec<Line> {
    vec![
        Line {
            a: [0.0, 0.0],
            b: [w, 0.0],
            set: "bottom",
        },
        Line {
            a: [w, 0.0],
            b: [w, h],
            set: "right",
        },
        Line {
            a: [0.0, h],
            b: [w, h],
            set: "top",
        },
        Line {
            a: [0.0, 0.0],
            b: [0.0, h],
            set: "left",
        },
    ]
}

/// The four sides of the box `[xmin, ymin, xmax, ymax]` (m), counter-clockwise from its lower
/// left corner, as lines of the edge set `inclusion_boundary`.
pub(crate) fn inclusion_outline(r: [f64; 4]) -> [Line; 4] {
    let c = [[r[0], r[1]], [r[2], r[1]], [r[2], r[3]], [r[0], r[3]]];
    std::array::from_fn(|k| Line {
        a: c[k],
        b: c[(k + 1) % 4],
        set: "inclusion_boundary",
    })
}

/// The region of each triangle of `raw`: 1 (`inclusion`) where `inclusion(centroid)`, else 0
/// (`matrix`); and the two regions (tags 1 and 2).
pub(crate) fn matrix_and_inclusions(
    raw: &RawMesh,
    inclusion: impl Fn([f64; 2]) -> bool,
) -> (Vec<u32>, Vec<crate::mesh::Region>) {
    let triangle_region = (raw.triangles.iter())
        .map(|t| {
            let p = t.map(|n| raw.nodes[n as usize]);
            let c = [
                (p[0][0] + p[1][0] + p[2][0]) / 3.0,
                (p[0][1] + p[1][1] + p[2][1]) / 3.0,
            ];
            u32::from(inclusion(c))
        })
        .collect();
    let regions = vec![
        crate::mesh::Region {
            name: "matrix".into(),
            tag: 1,
        },
        crate::mesh::Region {
            name: "inclusion".into(),
            tag: 2,
        },
    ];
    (triangle_region, regions)
}
