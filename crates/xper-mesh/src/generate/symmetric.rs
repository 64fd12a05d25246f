//! Point-symmetric meshes of point-symmetric domains.
//!
//! A domain invariant under the half-turn `p -> 2c - p` about its centre `c` (the
//! double-edge-notched square) meshed by Delaunay refinement gets a mesh that is not: the
//! refinement inserts nodes in an order that has no symmetry. A crack pattern that the
//! loading makes point-symmetric (Nooru-Mohamed's two anti-symmetric cracks) then inherits
//! the mesh's bias. Here the refined mesh is made symmetric:
//! - the nodes left of a vertical seam through `c`, at least [`SEAM_CLEARANCE`] `h` from it,
//!   are kept, and their half-turn images replace the nodes on the right;
//! - the seam gets nodes of its own, evenly spaced and symmetric about `c`;
//! - the constrained Delaunay triangulation of these nodes (no refinement, which would add
//!   nodes without symmetry), with the domain's lines as constraints, is the mesh.
//!
//! The Delaunay triangulation of a point-symmetric node set is point-symmetric unless four
//! nodes are cocircular across the seam; that is checked, and reported as an error.

use std::collections::HashSet;

use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use super::{snap, Line, RawMesh};
use crate::error::{MeshError, MeshErrorKind};
use crate::select::distance_to_segment;

/// Distance (in element sizes) between the seam and the nearest kept node on either side.
pub const SEAM_CLEARANCE: f64 = 0.35;

/// The point-symmetric remesh of `raw` (a mesh of a domain invariant under the half-turn
/// about `centre`, bounded by `lines`, whose seam through `centre` runs vertically from
/// `y = y_min` to the image of that point), keeping the triangles whose centroid satisfies
/// `inside`.
pub(crate) fn point_symmetric(
    origin: &str,
    raw: &RawMesh,
    centre: [f64; 2],
    y_min: f64,
    h: f64,
    lines: &[Line],
    inside: impl Fn([f64; 2]) -> bool,
) -> Result<RawMesh, MeshError> {
    let fail = |reason: String| MeshError::new(MeshErrorKind::Spec, origin, reason);
    // Work in coordinates centred on `centre`, where the half-turn is an exact negation.
    let centred = |p: [f64; 2]| [p[0] - centre[0], p[1] - centre[1]];
    let kept: Vec<[f64; 2]> = (raw.nodes.iter())
        .map(|&p| centred(p))
        .filter(|p| p[0] < -SEAM_CLEARANCE * h)
        .collect();
    let half_length = centre[1] - y_min;
    let seam_pieces = ((2.0 * half_length / h).ceil() as usize).max(2);
    let seam = (0..=seam_pieces).map(|k| {
        let s = (2.0 * k as f64 - seam_pieces as f64) / seam_pieces as f64;
        [0.0, s * half_length]
    });
    let mut points: Vec<[f64; 2]> = kept.clone();
    points.extend(kept.iter().map(|p| [-p[0], -p[1]]));
    points.extend(seam);
    let image = |i: usize| {
        let n = kept.len();
        if i < n {
            i + n
        } else if i < 2 * n {
            i - n
        } else {
            2 * n + seam_pieces - (i - 2 * n)
        }
    };

    let segments = boundary_segments(&points, lines, centre, h);
    let cdt_points = points.iter().map(|p| Point2::new(p[0], p[1])).collect();
    let mut conflicts = 0;
    let cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::try_bulk_load_cdt(cdt_points, segments, |_| {
            conflicts += 1
        })
        .map_err(|e| fail(format!("point-symmetric triangulation failed: {e:?}")))?;
    if conflicts > 0 || cdt.num_vertices() != points.len() {
        return Err(fail(format!(
            "point-symmetric triangulation: {conflicts} crossing boundary pieces, {} of {} \
             nodes kept",
            cdt.num_vertices(),
            points.len()
        )));
    }
    let mut triangles = Vec::new();
    for face in cdt.inner_faces() {
        let v = face.vertices().map(|v| v.fix().index());
        let c = v.iter().fold([0.0, 0.0], |acc, &i| {
            [acc[0] + points[i][0] / 3.0, acc[1] + points[i][1] / 3.0]
        });
        if inside([c[0] + centre[0], c[1] + centre[1]]) {
            triangles.push(v.map(|i| i as u32));
        }
    }
    let key = |t: [u32; 3]| {
        let mut k = t;
        k.sort_unstable();
        k
    };
    let all: HashSet<[u32; 3]> = triangles.iter().map(|&t| key(t)).collect();
    let asymmetric = (triangles.iter())
        .filter(|t| !all.contains(&key(t.map(|i| image(i as usize) as u32))))
        .count();
    if asymmetric > 0 {
        return Err(fail(format!(
            "the Delaunay triangulation of the point-symmetric nodes is not point-symmetric \
             ({asymmetric} triangles without an image: cocircular nodes); change the element \
             size slightly"
        )));
    }
    let mut nodes: Vec<[f64; 2]> = (points.iter())
        .map(|p| [p[0] + centre[0], p[1] + centre[1]])
        .collect();
    snap(&mut nodes, lines, h);
    Ok(RawMesh { nodes, triangles })
}

/// Constraint segments joining consecutive `points` (centred on `centre`) along each line.
fn boundary_segments(
    points: &[[f64; 2]],
    lines: &[Line],
    centre: [f64; 2],
    h: f64,
) -> Vec<[usize; 2]> {
    let tol = 1e-9 * h;
    let mut segments = Vec::new();
    for line in lines {
        let a = [line.a[0] - centre[0], line.a[1] - centre[1]];
        let b = [line.b[0] - centre[0], line.b[1] - centre[1]];
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let mut on: Vec<(f64, usize)> = (points.iter().enumerate())
            .filter(|(_, p)| distance_to_segment(**p, a, b) <= tol)
            .map(|(i, p)| ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy, i))
            .collect();
        on.sort_by(|x, y| x.0.total_cmp(&y.0));
        segments.extend(on.windows(2).map(|w| [w[0].1, w[1].1]));
    }
    segments
}
