//! Convex polyhedron against convex polyhedron: separating axes, then the contact polygon by
//! clipping.
//!
//! The candidate axes are the face normals of both bodies and the cross products of their
//! edges; the one of largest separation `min_B n.x - max_A n.x` is the contact normal (the
//! separating-axis theorem; for overlapping bodies its opposite is the penetration depth).
//! On a face axis the other body's most opposed face is clipped against the side planes of
//! the reference face (Sutherland-Hodgman) and every clipped point within the alert distance
//! of the reference plane is a contact, at most four kept spanning the largest area, as
//! LMGC90's polyhedra give up to four points on a face-to-face contact. On an edge-edge axis
//! the contact is the pair of nearest points of the two edges. A face axis is preferred when
//! its separation is within a small tolerance of the best edge axis, so that resting faces do
//! not flicker to edge contacts. The separation on these axes never exceeds the distance
//! between the bodies, so no contact within the alert distance is missed.

use super::dim3::{inside_face, reduce};
use super::{ContactPoint, Manifold};
use xper_bodies::ConvexPolyhedron;
use xper_math::{Real, Rotation, Vector};

/// A polyhedron placed in the world: vertices, faces and outward normals.
struct Placed<'a> {
    poly: &'a ConvexPolyhedron,
    vertices: Vec<Vector>,
    normals: Vec<Vector>,
}

impl<'a> Placed<'a> {
    fn new(poly: &'a ConvexPolyhedron, c: &Vector, q: Rotation) -> Self {
        Placed {
            poly,
            vertices: poly.vertices.iter().map(|v| c + q * v).collect(),
            normals: poly.normals.iter().map(|n| q * n).collect(),
        }
    }

    /// `(min, max)` of `n . x` over the vertices.
    fn extent(&self, n: &Vector) -> (Real, Real) {
        self.vertices
            .iter()
            .map(|v| n.dot(v))
            .fold((Real::INFINITY, Real::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    }

    /// The edges, each once, as vertex index pairs.
    fn edges(&self) -> Vec<[usize; 2]> {
        let mut edges = Vec::new();
        for face in &self.poly.faces {
            for k in 0..face.len() {
                let (a, b) = (face[k] as usize, face[(k + 1) % face.len()] as usize);
                if a < b {
                    edges.push([a, b]);
                }
            }
        }
        edges
    }

    /// The vertices of face `f`, counter-clockwise seen from outside.
    fn face(&self, f: usize) -> Vec<Vector> {
        self.poly.faces[f]
            .iter()
            .map(|&v| self.vertices[v as usize])
            .collect()
    }
}

/// The axis of a contact: a face of the first body, a face of the second, or an edge of each.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Axis {
    FaceA(usize),
    FaceB(usize),
    Edges(usize, usize),
}

/// Contact between polyhedron `a` (centroid `ca`, orientation `qa`) and polyhedron `b`;
/// normal from `a` to `b`, points midway between the surfaces. `feature` encodes the axis
/// (face of `a`, face of `b`, pair of edges) and the point's place in the contact polygon.
pub fn collide_polyhedra(
    a: &ConvexPolyhedron,
    ca: &Vector,
    qa: Rotation,
    b: &ConvexPolyhedron,
    cb: &Vector,
    qb: Rotation,
    alert: Real,
) -> Manifold {
    if (cb - ca).norm() - a.bounding_radius - b.bounding_radius > alert {
        return Manifold::EMPTY;
    }
    let (pa, pb) = (Placed::new(a, ca, qa), Placed::new(b, cb, qb));
    // Best face axis of either body.
    let mut best_face = (Real::NEG_INFINITY, Axis::FaceA(0), Vector::zeros());
    for (f, n) in pa.normals.iter().enumerate() {
        let sep = pb.extent(n).0 - pa.extent(n).1;
        if sep > best_face.0 {
            best_face = (sep, Axis::FaceA(f), *n);
        }
    }
    for (f, n) in pb.normals.iter().enumerate() {
        let sep = pb.extent(&-n).0 - pa.extent(&-n).1;
        if sep > best_face.0 {
            best_face = (sep, Axis::FaceB(f), -n);
        }
    }
    if best_face.0 > alert {
        return Manifold::EMPTY;
    }
    // Best edge-edge axis, oriented from a to b.
    let (edges_a, edges_b) = (pa.edges(), pb.edges());
    let mut best_edge = (Real::NEG_INFINITY, Axis::Edges(0, 0), Vector::zeros());
    let scale = a.bounding_radius.max(b.bounding_radius);
    for (i, ea) in edges_a.iter().enumerate() {
        let da = pa.vertices[ea[1]] - pa.vertices[ea[0]];
        for (j, eb) in edges_b.iter().enumerate() {
            let db = pb.vertices[eb[1]] - pb.vertices[eb[0]];
            let c = da.cross(&db);
            let len = c.norm();
            if len <= 1e-9 * da.norm() * db.norm() {
                continue;
            }
            let mut n = c / len;
            if n.dot(&(cb - ca)) < 0.0 {
                n = -n;
            }
            let ((_, hi_a), (lo_b, _)) = (pa.extent(&n), pb.extent(&n));
            // Only edges on the two support planes: the others give the same axis (parallel
            // edges) but not the contact.
            let on = |x: Real, plane: Real| (x - plane).abs() <= 1e-9 * scale;
            let supporting = on(n.dot(&pa.vertices[ea[0]]), hi_a)
                && on(n.dot(&pa.vertices[ea[1]]), hi_a)
                && on(n.dot(&pb.vertices[eb[0]]), lo_b)
                && on(n.dot(&pb.vertices[eb[1]]), lo_b);
            let sep = lo_b - hi_a;
            if supporting && sep > best_edge.0 {
                best_edge = (sep, Axis::Edges(i, j), n);
            }
        }
    }
    if best_edge.0 > alert {
        return Manifold::EMPTY;
    }
    let tolerance = 1e-6 * scale;
    let (separation, axis, normal) = if best_edge.0 > best_face.0 + tolerance {
        best_edge
    } else {
        best_face
    };
    let on_face = match axis {
        Axis::FaceA(f) => face_contact(&pa, f, &pb, normal, alert, 0),
        Axis::FaceB(f) => face_contact(&pb, f, &pa, -normal, alert, 1).flipped(),
        Axis::Edges(..) => Manifold::EMPTY,
    };
    if on_face.len > 0 {
        return on_face;
    }
    match axis {
        // The other body's face lies beside the reference face (a vertex or edge near the
        // reference face's border): the nearest points of the two surfaces.
        Axis::FaceA(_) | Axis::FaceB(_) => nearest_points(&pa, &edges_a, &pb, &edges_b, alert),
        Axis::Edges(i, j) => {
            let (ea, eb) = (edges_a[i], edges_b[j]);
            let (p, q) = nearest_on_segments(
                pa.vertices[ea[0]],
                pa.vertices[ea[1]],
                pb.vertices[eb[0]],
                pb.vertices[eb[1]],
            );
            Manifold::one(ContactPoint {
                point: (p + q) / 2.0,
                normal,
                gap: separation,
                feature: (2 << 28) | ((i * edges_b.len() + j) as u32 & 0x0fff_ffff),
            })
        }
    }
}

/// The contact of reference face `f` of `r` (outward normal `normal`) with the most opposed
/// face of `other`, clipped to the reference face; normal from `r` to `other`. `side` (0 or 1)
/// tells which body the reference is, for the feature code.
fn face_contact(
    r: &Placed,
    f: usize,
    other: &Placed,
    normal: Vector,
    alert: Real,
    side: u32,
) -> Manifold {
    let incident = (0..other.normals.len())
        .min_by(|&i, &j| {
            other.normals[i]
                .dot(&normal)
                .total_cmp(&other.normals[j].dot(&normal))
        })
        .unwrap_or(0);
    let reference = r.face(f);
    let mut polygon = other.face(incident);
    for k in 0..reference.len() {
        let (p, q) = (reference[k], reference[(k + 1) % reference.len()]);
        // Side plane through the edge, normal pointing out of the face.
        let out = (q - p).cross(&normal);
        polygon = clip(&polygon, &p, &out);
        if polygon.is_empty() {
            return Manifold::EMPTY;
        }
    }
    let origin = reference[0];
    let candidates: Vec<(Vector, Real)> = polygon
        .iter()
        .map(|x| (*x, normal.dot(&(x - origin))))
        .filter(|&(_, gap)| gap <= alert)
        .collect();
    let mut m = Manifold::EMPTY;
    let keep = reduce(
        candidates.len(),
        |k| candidates[k].0,
        |k| candidates[k].1,
        &normal,
    );
    for (k, &i) in keep.iter().enumerate() {
        let (x, gap) = candidates[i];
        m.push(ContactPoint {
            point: x - normal * (gap / 2.0),
            normal,
            gap,
            feature: (side << 28) | ((f as u32 & 0x00ff_ffff) << 4) | k as u32,
        });
    }
    m
}

/// One contact at the nearest points of two separated bodies (within `alert`), from every
/// pair of edges and every vertex against every face of the other body: the features that
/// hold the nearest points of two convex polyhedra. Nothing when they overlap or are farther.
fn nearest_points(
    pa: &Placed,
    edges_a: &[[usize; 2]],
    pb: &Placed,
    edges_b: &[[usize; 2]],
    alert: Real,
) -> Manifold {
    let mut best: Option<(Real, Vector, Vector, u32)> = None;
    let mut consider = |p: Vector, q: Vector, feature: u32| {
        let d = (q - p).norm();
        if best.is_none_or(|(bd, ..)| d < bd) {
            best = Some((d, p, q, feature));
        }
    };
    for (i, ea) in edges_a.iter().enumerate() {
        for (j, eb) in edges_b.iter().enumerate() {
            let (p, q) = nearest_on_segments(
                pa.vertices[ea[0]],
                pa.vertices[ea[1]],
                pb.vertices[eb[0]],
                pb.vertices[eb[1]],
            );
            consider(
                p,
                q,
                (3 << 28) | ((i * edges_b.len() + j) as u32 & 0x0fff_ffff),
            );
        }
    }
    for (from, to, flip) in [(pa, pb, false), (pb, pa, true)] {
        for (k, v) in from.vertices.iter().enumerate() {
            for f in 0..to.normals.len() {
                let face = to.face(f);
                let n = to.normals[f];
                let x = v - n * n.dot(&(v - face[0]));
                if inside_face(face.len(), |e| face[e], &n, &x) {
                    let feature = (3 << 28) | (1 << 27) | (k as u32 & 0x07ff_ffff);
                    if flip {
                        consider(x, *v, feature);
                    } else {
                        consider(*v, x, feature);
                    }
                }
            }
        }
    }
    match best {
        Some((d, p, q, feature)) if d > 0.0 && d <= alert => Manifold::one(ContactPoint {
            point: (p + q) / 2.0,
            normal: (q - p) / d,
            gap: d,
            feature,
        }),
        _ => Manifold::EMPTY,
    }
}

/// The part of polygon `poly` on the inner side of the plane through `p` with outward normal
/// `out` (Sutherland-Hodgman, one plane).
fn clip(poly: &[Vector], p: &Vector, out: &Vector) -> Vec<Vector> {
    let mut kept = Vec::with_capacity(poly.len() + 1);
    for k in 0..poly.len() {
        let (x, y) = (poly[k], poly[(k + 1) % poly.len()]);
        let (dx, dy) = (out.dot(&(x - p)), out.dot(&(y - p)));
        if dx <= 0.0 {
            kept.push(x);
        }
        if (dx < 0.0) != (dy < 0.0) && dx != dy {
            kept.push(x + (y - x) * (dx / (dx - dy)));
        }
    }
    kept
}

/// The nearest points of segments `[p0, p1]` and `[q0, q1]` (clamped closest points of the
/// two lines; V. Lumelsky, Inf. Process. Lett. 21, 1985).
fn nearest_on_segments(p0: Vector, p1: Vector, q0: Vector, q1: Vector) -> (Vector, Vector) {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let (b, c) = (d1.dot(&d2), d1.dot(&r));
    let denom = a * e - b * b;
    let mut s = if denom > 0.0 {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (p0 + d1 * s, q0 + d2 * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use xper_math::SplitMix64;

    /// A box resting on a wider box, shifted: four points at the corners of the overlap
    /// rectangle, all at the same gap, normal up.
    #[test]
    fn box_on_box_gives_the_corners_of_the_overlap() {
        let base = ConvexPolyhedron::cuboid(Vector::new(1.0, 1.0, 0.5));
        let top = ConvexPolyhedron::cuboid(Vector::new(0.5, 0.3, 0.2));
        let id = Rotation::identity();
        let cb = Vector::new(0.8, -0.2, 0.5 + 0.2 + 1e-3);
        let m = collide_polyhedra(&base, &Vector::zeros(), id, &top, &cb, id, 0.01);
        assert_eq!(m.len, 4, "{m:?}");
        let mut xs: Vec<(Real, Real)> = Vec::new();
        for p in m.as_slice() {
            assert!((p.gap - 1e-3).abs() < 1e-12 && (p.normal - Vector::z()).norm() < 1e-15);
            assert!((p.point.z - (0.5 + 5e-4)).abs() < 1e-12);
            xs.push((p.point.x, p.point.y));
        }
        xs.sort_by(|a, b| a.partial_cmp(b).unwrap());
        // Overlap of [0.3, 1.3] x [-0.5, 0.1] with [-1, 1]^2: [0.3, 1] x [-0.5, 0.1].
        let expected = [(0.3, -0.5), (0.3, 0.1), (1.0, -0.5), (1.0, 0.1)];
        for (x, e) in xs.iter().zip(expected) {
            assert!(
                (x.0 - e.0).abs() < 1e-12 && (x.1 - e.1).abs() < 1e-12,
                "{xs:?}"
            );
        }
        // Seen from the other side: the same points, the normal reversed.
        let flipped = collide_polyhedra(&top, &cb, id, &base, &Vector::zeros(), id, 0.01);
        assert_eq!(flipped.len, 4);
        assert!((flipped.points[0].normal + Vector::z()).norm() < 1e-15);
    }

    /// Two cubes turned 45 degrees about crossed axes touch edge on edge: one point, the gap
    /// between the edges.
    #[test]
    fn crossed_edges() {
        let cube = ConvexPolyhedron::cuboid(Vector::repeat(0.5));
        let quarter = std::f64::consts::FRAC_PI_4;
        let qa = Rotation::from_scaled_axis(Vector::x() * quarter);
        let qb = Rotation::from_scaled_axis(Vector::y() * quarter);
        let reach = 0.5 * 2f64.sqrt();
        let cb = Vector::new(0.0, 0.0, 2.0 * reach + 0.01);
        let m = collide_polyhedra(&cube, &Vector::zeros(), qa, &cube, &cb, qb, 0.1);
        assert_eq!(m.len, 1, "{m:?}");
        let p = m.points[0];
        assert!((p.gap - 0.01).abs() < 1e-12, "{p:?}");
        assert!((p.normal - Vector::z()).norm() < 1e-12);
        assert!((p.point - Vector::new(0.0, 0.0, reach + 0.005)).norm() < 1e-12);
    }

    /// Random pairs: the gap never exceeds the distance between the surfaces found by
    /// sampling them (an independent computation), and separated pairs beyond the alert
    /// distance give nothing.
    #[test]
    fn gaps_never_exceed_the_sampled_distance() {
        let mut rng = SplitMix64::new(13);
        let cloud = |rng: &mut SplitMix64| -> Vec<Vector> {
            (0..10)
                .map(|_| {
                    Vector::new(rng.next_f64(), rng.next_f64(), rng.next_f64())
                        - Vector::repeat(0.5)
                })
                .collect()
        };
        let sample = |p: &Placed| -> Vec<Vector> {
            let mut s = Vec::new();
            for f in 0..p.poly.faces.len() {
                let face = p.face(f);
                for w in face[1..].windows(2) {
                    for i in 0..=20 {
                        for j in 0..=20 - i {
                            let (u, v) = (i as Real / 20.0, j as Real / 20.0);
                            s.push(face[0] + (w[0] - face[0]) * u + (w[1] - face[0]) * v);
                        }
                    }
                }
            }
            s
        };
        let mut touching = 0;
        for _ in 0..40 {
            let (a, _) = ConvexPolyhedron::hull(&cloud(&mut rng)).unwrap();
            let (b, _) = ConvexPolyhedron::hull(&cloud(&mut rng)).unwrap();
            let qa =
                Rotation::from_scaled_axis(Vector::new(rng.next_f64(), rng.next_f64(), 0.3) * 3.0);
            let qb =
                Rotation::from_scaled_axis(Vector::new(0.2, rng.next_f64(), rng.next_f64()) * 3.0);
            let cb = Vector::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 1.2;
            let m = collide_polyhedra(&a, &Vector::zeros(), qa, &b, &cb, qb, 0.3);
            let (sa, sb) = (
                sample(&Placed::new(&a, &Vector::zeros(), qa)),
                sample(&Placed::new(&b, &cb, qb)),
            );
            let distance = sa
                .iter()
                .flat_map(|x| sb.iter().map(move |y| (x - y).norm()))
                .fold(Real::INFINITY, Real::min);
            if m.len == 0 {
                assert!(distance > 0.3 - 1e-9, "a pair at {distance} was missed");
                continue;
            }
            let gap = m
                .as_slice()
                .iter()
                .map(|p| p.gap)
                .fold(Real::INFINITY, Real::min);
            assert!(
                gap <= distance + 1e-9,
                "gap {gap} over the distance {distance}"
            );
            touching += 1;
        }
        assert!(touching > 10, "{touching} pairs in contact");
    }
}
