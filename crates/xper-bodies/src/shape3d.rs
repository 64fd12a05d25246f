//! Body shapes and their mass properties in 3D: spheres, convex polyhedra and planar walls.
//!
//! A polyhedron is the convex hull of the points it is given, found by testing every plane
//! through three of them (exact for any point set, `O(n^4)` in the number of points, so at most
//! [`ConvexPolyhedron::MAX_POINTS`] points). Its volume, centroid and inertia tensor come from
//! the divergence theorem over its faces cut into tetrahedra with a common apex (J. Blow and
//! A. N. Binstock, "How to find the inertia tensor (or other mass properties) of a 3D solid
//! body represented by a triangle mesh", 2004; the same integrals as B. Mirtich, J. Graphics
//! Tools 1(2), 1996): each tetrahedron `(0, a, b, c)` of signed volume `det[a b c] / 6`
//! contributes `det[a b c] / 120 (a a^T + b b^T + c c^T + s s^T)`, `s = a + b + c`, to the
//! covariance `C = int x x^T dV`, and the inertia is `tr(C) I - C`.

use serde::{Deserialize, Serialize};
use xper_math::{rotate, tangents, Aabb, AngMatrix, Real, Rotation, Vector};

/// A convex polyhedron in its body frame (centroid at the origin).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConvexPolyhedron {
    /// Vertices (m), body frame.
    pub vertices: Vec<Vector>,
    /// Each face's vertices (indices into `vertices`), counter-clockwise seen from outside.
    pub faces: Vec<Vec<u32>>,
    /// Outward unit normal of each face, body frame.
    pub normals: Vec<Vector>,
    /// Largest distance from the centroid to a vertex (m).
    pub bounding_radius: Real,
}

impl ConvexPolyhedron {
    /// The most points [`ConvexPolyhedron::hull`] takes (its cost grows as the fourth power).
    pub const MAX_POINTS: usize = 256;

    /// The convex hull of `points` and the position of its centroid in their frame; the
    /// polyhedron's vertices are relative to that centroid. An error when there are fewer
    /// than four points off a common plane, or too many points.
    pub fn hull(points: &[Vector]) -> Result<(Self, Vector), String> {
        if points.len() > Self::MAX_POINTS {
            return Err(format!(
                "{} points: a polyhedron takes at most {}",
                points.len(),
                Self::MAX_POINTS
            ));
        }
        if points.iter().any(|p| !p.iter().all(|x| x.is_finite())) {
            return Err("a point is not finite".into());
        }
        let scale = points
            .iter()
            .map(|p| (p - points[0]).norm())
            .fold(0.0, Real::max);
        let eps = 1e-9 * scale;
        let mut planes: Vec<(Vector, Real)> = Vec::new();
        let mut faces: Vec<Vec<usize>> = Vec::new();
        let n = points.len();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let (a, b, c) = (points[i], points[j], points[k]);
                    let normal = (b - a).cross(&(c - a));
                    if normal.norm() <= eps * scale {
                        continue;
                    }
                    let mut normal = normal.normalize();
                    let side = |m: &Vector| normal.dot(&(m - a));
                    let (above, below) = points.iter().fold((false, false), |(up, down), m| {
                        let s = side(m);
                        (up || s > eps, down || s < -eps)
                    });
                    if above && below {
                        continue;
                    }
                    if above {
                        normal = -normal;
                    }
                    let offset = normal.dot(&a);
                    let known = planes
                        .iter()
                        .any(|(m, d)| m.dot(&normal) > 1.0 - 1e-12 && (d - offset).abs() <= eps);
                    if known {
                        continue;
                    }
                    let on: Vec<usize> = (0..n)
                        .filter(|&m| (normal.dot(&points[m]) - offset).abs() <= eps)
                        .collect();
                    planes.push((normal, offset));
                    faces.push(counter_clockwise(points, on, &normal));
                }
            }
        }
        if planes.len() < 4 {
            return Err(format!(
                "{} points do not span a volume (all on one plane, a line or a point)",
                n
            ));
        }
        // Vertices: the points on some face, each once (repeated points merged).
        let mut index = vec![u32::MAX; n];
        let mut vertices = Vec::new();
        for face in &faces {
            for &p in face {
                if index[p] == u32::MAX {
                    let same = vertices
                        .iter()
                        .position(|v: &Vector| (v - points[p]).norm() <= eps);
                    index[p] = match same {
                        Some(v) => v as u32,
                        None => {
                            vertices.push(points[p]);
                            (vertices.len() - 1) as u32
                        }
                    };
                }
            }
        }
        let mut faces: Vec<Vec<u32>> = faces
            .iter()
            .map(|f| f.iter().map(|&p| index[p]).collect())
            .collect();
        for f in &mut faces {
            f.dedup();
            if f.len() > 1 && f[0] == f[f.len() - 1] {
                f.pop();
            }
        }
        let mut shape = ConvexPolyhedron {
            vertices,
            faces,
            normals: planes.iter().map(|(n, _)| *n).collect(),
            bounding_radius: 0.0,
        };
        let (_, centroid, _) = shape.integrals();
        for v in &mut shape.vertices {
            *v -= centroid;
        }
        shape.bounding_radius = shape.vertices.iter().map(|v| v.norm()).fold(0.0, Real::max);
        Ok((shape, centroid))
    }

    /// The box of half-extents `half` (m) along the body axes.
    pub fn cuboid(half: Vector) -> Self {
        let corners: Vec<Vector> = (0..8)
            .map(|k| {
                let s = |bit: usize| if k >> bit & 1 == 1 { 1.0 } else { -1.0 };
                Vector::new(s(0) * half.x, s(1) * half.y, s(2) * half.z)
            })
            .collect();
        Self::hull(&corners).expect("a box spans a volume").0
    }

    /// Volume (m^3), centroid (m) and covariance `int x x^T dV` about the frame's origin (m^5).
    fn integrals(&self) -> (Real, Vector, AngMatrix) {
        let (mut volume, mut first, mut covariance) = (0.0, Vector::zeros(), AngMatrix::zeros());
        for face in &self.faces {
            let a = self.vertices[face[0] as usize];
            for w in face[1..].windows(2) {
                let (b, c) = (self.vertices[w[0] as usize], self.vertices[w[1] as usize]);
                let det = a.dot(&b.cross(&c));
                let s = a + b + c;
                volume += det / 6.0;
                first += s * (det / 24.0);
                covariance +=
                    (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose())
                        * (det / 120.0);
            }
        }
        (volume, first / volume, covariance)
    }

    /// Volume (m^3) and the inertia tensor about the centroid per unit density (m^5).
    pub fn volume_and_inertia(&self) -> (Real, AngMatrix) {
        let (volume, centroid, covariance) = self.integrals();
        let about_centroid = covariance - centroid * centroid.transpose() * volume;
        let inertia = AngMatrix::identity() * about_centroid.trace() - about_centroid;
        (volume, inertia)
    }
}

/// The points `on` a face of outward normal `normal`, ordered counter-clockwise seen from
/// outside (by their angle about the face's mean point).
fn counter_clockwise(points: &[Vector], mut on: Vec<usize>, normal: &Vector) -> Vec<usize> {
    let [t1, t2] = tangents(normal);
    let centre = on.iter().map(|&m| points[m]).sum::<Vector>() / on.len() as Real;
    let angle = |m: usize| {
        let d = points[m] - centre;
        d.dot(&t2).atan2(d.dot(&t1))
    };
    on.sort_by(|&p, &q| angle(p).total_cmp(&angle(q)));
    on
}

/// The geometry of a body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Shape {
    /// A sphere of the given radius (m) centred on the body position.
    Sphere {
        /// Radius (m).
        radius: Real,
    },
    /// A convex polyhedron, boxed so that a set of spheres does not pay for vertex lists.
    Polyhedron(Box<ConvexPolyhedron>),
    /// A wall: the rectangle of half-extents `half_extents` (m) along the body's x and y axes,
    /// its outward normal the body's z axis.
    Plane {
        /// Half-extents along the body's x and y axes (m).
        half_extents: [Real; 2],
    },
}

impl Shape {
    /// Whether the shape is a wall (held in place, of any size): the broad phase tests walls
    /// against the cells they cover instead of binning them.
    #[inline]
    pub fn is_wall(&self) -> bool {
        matches!(self, Shape::Plane { .. })
    }

    /// Bounding box of the shape placed at `position` with orientation `rotation`.
    pub fn aabb(&self, position: &Vector, rotation: Rotation) -> Aabb {
        let around = |points: &mut dyn Iterator<Item = Vector>| {
            let mut b = Aabb {
                min: *position,
                max: *position,
            };
            for v in points {
                let w = position + rotate(&v, rotation);
                b.min = b.min.inf(&w);
                b.max = b.max.sup(&w);
            }
            b
        };
        match self {
            Shape::Sphere { radius } => Aabb::from_center(*position, Vector::repeat(*radius)),
            Shape::Polyhedron(p) => around(&mut p.vertices.iter().copied()),
            Shape::Plane {
                half_extents: [a, b],
            } => {
                // Per world axis k, |R_k0| a + |R_k1| b, with an axis the rectangle does not
                // span contributing 0 even for an infinite half-extent (a half-space). An
                // orientation that went through a rotation vector leaves ~1e-16 where the
                // matrix has zeros: below 1e-12 an entry counts as 0 for an infinite extent.
                let r = rotation.to_rotation_matrix();
                let spread = |c: Real, e: Real| {
                    if c == 0.0 || (e.is_infinite() && c.abs() <= 1e-12) {
                        0.0
                    } else {
                        c.abs() * e
                    }
                };
                let half = Vector::from_fn(|k, _| spread(r[(k, 0)], *a) + spread(r[(k, 1)], *b));
                Aabb {
                    min: position - half,
                    max: position + half,
                }
            }
        }
    }

    /// Mass (kg) and inertia tensor about the centroid in the body frame (kg m^2) for a
    /// density (kg/m^3); a plane is a wall of infinite mass.
    pub fn mass_properties(&self, density: Real) -> (Real, AngMatrix) {
        match self {
            Shape::Sphere { radius } => {
                let m = density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
                (
                    m,
                    AngMatrix::from_diagonal_element(0.4 * m * radius * radius),
                )
            }
            Shape::Polyhedron(p) => {
                let (volume, inertia) = p.volume_and_inertia();
                (density * volume, inertia * density)
            }
            Shape::Plane { .. } => (
                Real::INFINITY,
                AngMatrix::from_diagonal_element(Real::INFINITY),
            ),
        }
    }

    /// A length characterising the body: the sphere's radius, the polyhedron's bounding
    /// radius, the plane's larger half-extent.
    pub fn size(&self) -> Real {
        match self {
            Shape::Sphere { radius } => *radius,
            Shape::Polyhedron(p) => p.bounding_radius,
            Shape::Plane { half_extents } => half_extents[0].max(half_extents[1]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use xper_math::SplitMix64;

    fn close(a: &AngMatrix, b: &AngMatrix, tol: Real) -> bool {
        (a - b).norm() <= tol * b.norm().max(1e-300)
    }

    /// A box: volume `8 abc`, inertia `m (b^2 + c^2) / 3` and so on for half-extents `a, b, c`;
    /// six faces of four vertices.
    #[test]
    fn box_mass_properties_match_the_formula() {
        let half = Vector::new(0.3, 0.2, 0.1);
        let p = ConvexPolyhedron::cuboid(half);
        assert_eq!((p.vertices.len(), p.faces.len()), (8, 6));
        assert!(p.faces.iter().all(|f| f.len() == 4));
        let (v, i) = p.volume_and_inertia();
        assert!((v - 8.0 * half.x * half.y * half.z).abs() < 1e-15);
        let [a2, b2, c2] = [half.x * half.x, half.y * half.y, half.z * half.z];
        let exact = AngMatrix::from_diagonal(&Vector::new(b2 + c2, a2 + c2, a2 + b2)) * (v / 3.0);
        assert!(close(&i, &exact, 1e-14), "{i} vs {exact}");
    }

    /// A regular tetrahedron of edge `e`: volume `e^3 / (6 sqrt 2)`, isotropic inertia
    /// `m e^2 / 20`; its hull from points given off-centre and with an interior point.
    #[test]
    fn regular_tetrahedron() {
        let offset = Vector::new(1.0, -2.0, 0.5);
        let corners = [
            Vector::new(1.0, 1.0, 1.0),
            Vector::new(1.0, -1.0, -1.0),
            Vector::new(-1.0, 1.0, -1.0),
            Vector::new(-1.0, -1.0, 1.0),
        ];
        let mut points: Vec<Vector> = corners.iter().map(|c| c + offset).collect();
        points.push(offset + Vector::new(0.1, 0.0, -0.2));
        let (p, centroid) = ConvexPolyhedron::hull(&points).unwrap();
        assert!((centroid - offset).norm() < 1e-14);
        assert_eq!((p.vertices.len(), p.faces.len()), (4, 4));
        let e = 8f64.sqrt();
        let (v, i) = p.volume_and_inertia();
        assert!((v - e.powi(3) / (6.0 * 2f64.sqrt())).abs() < 1e-14);
        let exact = AngMatrix::from_diagonal_element(v * e * e / 20.0);
        assert!(close(&i, &exact, 1e-14), "{i}");
    }

    /// Random point clouds: every point inside the hull, Euler's formula `V - E + F = 2`,
    /// faces counter-clockwise seen from outside, and the mass properties transforming as they
    /// must under a rotation (`R I R^T`) and a scaling by `s` (`s^3 V`, `s^5 I`).
    #[test]
    fn hulls_of_random_clouds_are_consistent() {
        let mut rng = SplitMix64::new(7);
        for case in 0..20 {
            let n = 5 + case * 3;
            let points: Vec<Vector> = (0..n)
                .map(|_| Vector::new(rng.next_f64(), 2.0 * rng.next_f64(), rng.next_f64()))
                .collect();
            let (p, centroid) = ConvexPolyhedron::hull(&points).unwrap();
            for (face, normal) in p.faces.iter().zip(&p.normals) {
                let d = normal.dot(&p.vertices[face[0] as usize]);
                assert!(points
                    .iter()
                    .all(|q| normal.dot(&(q - centroid)) <= d + 1e-12));
                let (a, b, c) = (
                    p.vertices[face[0] as usize],
                    p.vertices[face[1] as usize],
                    p.vertices[face[2] as usize],
                );
                assert!(
                    (b - a).cross(&(c - a)).dot(normal) > 0.0,
                    "case {case}: clockwise"
                );
            }
            let edges: usize = p.faces.iter().map(Vec::len).sum::<usize>() / 2;
            assert_eq!(p.vertices.len() + p.faces.len(), edges + 2, "case {case}");
            let (v, i) = p.volume_and_inertia();
            let q = Rotation::from_scaled_axis(Vector::new(0.3, -1.1, 0.7));
            let turned: Vec<Vector> = points.iter().map(|x| q * x * 1.5).collect();
            let (pt, _) = ConvexPolyhedron::hull(&turned).unwrap();
            let (vt, it) = pt.volume_and_inertia();
            let r = q.to_rotation_matrix();
            assert!((vt - v * 1.5f64.powi(3)).abs() < 1e-12 * vt, "case {case}");
            let expected = r.matrix() * i * r.matrix().transpose() * 1.5f64.powi(5);
            assert!(close(&it, &expected, 1e-12), "case {case}");
        }
    }

    /// Points that do not span a volume, and too many points, are errors.
    #[test]
    fn degenerate_point_sets_are_refused() {
        let flat: Vec<Vector> = (0..6)
            .map(|k| Vector::new(k as Real, (k * k) as Real, 0.0))
            .collect();
        assert!(ConvexPolyhedron::hull(&flat)
            .unwrap_err()
            .contains("do not span"));
        let many = vec![Vector::zeros(); ConvexPolyhedron::MAX_POINTS + 1];
        assert!(ConvexPolyhedron::hull(&many)
            .unwrap_err()
            .contains("at most"));
    }

    /// A half-space's box is finite along its normal when the normal is an axis, also for an
    /// orientation that went through a rotation vector (entries of ~1e-16 off the axes).
    #[test]
    fn half_spaces_aligned_with_an_axis_have_finite_boxes_along_it() {
        let plane = Shape::Plane {
            half_extents: [Real::INFINITY; 2],
        };
        for normal in [
            Vector::x(),
            -Vector::x(),
            Vector::y(),
            -Vector::y(),
            -Vector::z(),
        ] {
            let exact = Rotation::rotation_between(&Vector::z(), &normal)
                .unwrap_or_else(|| Rotation::from_scaled_axis(Vector::x() * std::f64::consts::PI));
            let rounded = Rotation::from_scaled_axis(exact.scaled_axis());
            for q in [exact, rounded] {
                let b = plane.aabb(&Vector::new(1.0, 2.0, 3.0), q);
                let k = normal.iamax();
                assert_eq!(
                    (b.min[k], b.max[k]),
                    ([1.0, 2.0, 3.0][k], [1.0, 2.0, 3.0][k])
                );
                assert!((0..3).filter(|&a| a != k).all(|a| b.min[a].is_infinite()));
            }
        }
    }

    #[test]
    fn sphere_mass_properties() {
        let (m, i) = Shape::Sphere { radius: 0.5 }.mass_properties(2000.0);
        let exact = 2000.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.125;
        assert!((m - exact).abs() < 1e-12 * m);
        assert!(close(&i, &AngMatrix::from_diagonal_element(0.1 * m), 1e-15));
    }
}
