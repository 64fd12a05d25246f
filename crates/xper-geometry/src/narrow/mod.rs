//! Narrow phase: exact contact points between two placed shapes, one file per shape pair
//! (2D: disks, polygons, segments; 3D: spheres, polyhedra, planes).

#[cfg(feature = "dim3")]
mod dim3;
#[cfg(feature = "dim2")]
mod disk_disk;
#[cfg(feature = "dim2")]
mod disk_polygon;
#[cfg(feature = "dim2")]
mod disk_segment;
#[cfg(feature = "dim2")]
mod polygon_polygon;
#[cfg(feature = "dim2")]
mod polygon_segment;
#[cfg(feature = "dim3")]
mod polyhedron_plane;
#[cfg(feature = "dim3")]
mod polyhedron_polyhedron;
#[cfg(feature = "dim3")]
mod sphere_plane;
#[cfg(feature = "dim3")]
mod sphere_polyhedron;
#[cfg(feature = "dim3")]
mod sphere_sphere;

#[cfg(feature = "dim2")]
use xper_bodies::Shape;
#[cfg(feature = "dim2")]
use xper_math::Rotation;
use xper_math::{Real, Vector, DIM};

#[cfg(feature = "dim3")]
pub use dim3::*;
#[cfg(feature = "dim2")]
pub use disk_disk::collide_disk_disk;
#[cfg(feature = "dim2")]
pub use disk_polygon::collide_disk_polygon;
#[cfg(feature = "dim2")]
pub use disk_segment::collide_disk_segment;
#[cfg(feature = "dim2")]
pub use polygon_polygon::{collide_polygons, WorldPolygon};
#[cfg(feature = "dim2")]
pub use polygon_segment::collide_polygon_segment;
#[cfg(feature = "dim3")]
pub use polyhedron_plane::collide_polyhedron_plane;
#[cfg(feature = "dim3")]
pub use polyhedron_polyhedron::collide_polyhedra;
#[cfg(feature = "dim3")]
pub use sphere_plane::collide_sphere_plane;
#[cfg(feature = "dim3")]
pub use sphere_polyhedron::collide_sphere_polyhedron;
#[cfg(feature = "dim3")]
pub use sphere_sphere::collide_spheres;

/// The most contact points between two bodies: 2 in 2D (an edge on an edge), 4 in 3D (a face
/// on a face, reduced to four).
pub const MANIFOLD_POINTS: usize = 2 * (DIM - 1);

/// One contact point between two bodies.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactPoint {
    /// Point midway between the two surfaces (m).
    pub point: Vector,
    /// Unit normal from the first body towards the second.
    pub normal: Vector,
    /// Signed distance between the surfaces along the normal (m), negative when overlapping.
    pub gap: Real,
    /// Identifies the pair of features in contact, stable while they stay in contact.
    pub feature: u32,
}

impl ContactPoint {
    /// The same contact seen from the other body.
    pub fn flipped(self) -> Self {
        ContactPoint {
            normal: -self.normal,
            ..self
        }
    }
}

/// Up to [`MANIFOLD_POINTS`] contact points between two bodies.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Manifold {
    /// Storage; only the first `len` entries are meaningful.
    pub points: [ContactPoint; MANIFOLD_POINTS],
    /// Number of points.
    pub len: usize,
}

impl Manifold {
    /// No contact.
    pub const EMPTY: Manifold = Manifold {
        points: [ContactPoint {
            point: ZERO,
            normal: ZERO,
            gap: 0.0,
            feature: 0,
        }; MANIFOLD_POINTS],
        len: 0,
    };

    /// A manifold of one point.
    pub fn one(p: ContactPoint) -> Self {
        Manifold {
            points: [p; MANIFOLD_POINTS],
            len: 1,
        }
    }

    /// Adds a point (at most [`MANIFOLD_POINTS`] are kept).
    pub fn push(&mut self, p: ContactPoint) {
        if self.len < MANIFOLD_POINTS {
            self.points[self.len] = p;
            self.len += 1;
        }
    }

    /// The points.
    pub fn as_slice(&self) -> &[ContactPoint] {
        &self.points[..self.len]
    }

    /// The same contacts seen from the other body.
    pub fn flipped(mut self) -> Self {
        for p in &mut self.points[..self.len] {
            *p = p.flipped();
        }
        self
    }
}

/// The contact point of two round shapes (disks in 2D, spheres in 3D) of centres `ca`, `cb`
/// and radii `ra`, `rb`: normal along the line of centres from `a` to `b` (the first axis
/// when they coincide), gap the distance between the surfaces, point midway; `None` beyond
/// the alert distance.
#[inline(always)]
pub fn round_point(
    ca: &Vector,
    ra: Real,
    cb: &Vector,
    rb: Real,
    alert: Real,
) -> Option<ContactPoint> {
    let d = cb - ca;
    let dist2 = d.norm_squared();
    let reach = ra + rb + alert;
    if dist2 > reach * reach {
        return None;
    }
    let dist = dist2.sqrt();
    let normal = if dist > 0.0 { d / dist } else { Vector::x() };
    let gap = dist - ra - rb;
    Some(ContactPoint {
        point: ca + normal * (ra + gap / 2.0),
        normal,
        gap,
        feature: 0,
    })
}

/// The zero vector, as a constant.
const ZERO: Vector = Vector::from_array_storage(nalgebra::ArrayStorage([[0.0; DIM]; 1]));

/// Contact points between shape `a` placed at (`pa`, `angle_a`) and shape `b`, with normals
/// from `a` to `b`, keeping points whose gap is at most `alert`.
#[cfg(feature = "dim2")]
pub fn collide(
    a: &Shape,
    pa: &Vector,
    angle_a: Rotation,
    b: &Shape,
    pb: &Vector,
    angle_b: Rotation,
    alert: Real,
) -> Manifold {
    use Shape::*;
    match (a, b) {
        (Disk { radius: ra }, Disk { radius: rb }) => collide_disk_disk(pa, *ra, pb, *rb, alert),
        (Segment { half_length }, Disk { radius }) => {
            collide_disk_segment(pb, *radius, pa, angle_a, *half_length, alert)
        }
        (Disk { radius }, Segment { half_length }) => {
            collide_disk_segment(pa, *radius, pb, angle_b, *half_length, alert).flipped()
        }
        (Polygon(p), Disk { radius }) => collide_disk_polygon(pb, *radius, p, pa, angle_a, alert),
        (Disk { radius }, Polygon(p)) => {
            collide_disk_polygon(pa, *radius, p, pb, angle_b, alert).flipped()
        }
        (Polygon(p), Polygon(q)) => collide_polygons(
            &WorldPolygon::from_polygon(p, pa, angle_a),
            &WorldPolygon::from_polygon(q, pb, angle_b),
            alert,
        ),
        (Polygon(p), Segment { half_length }) => {
            collide_polygon_segment(p, pa, angle_a, pb, angle_b, *half_length, alert)
        }
        (Segment { half_length }, Polygon(p)) => {
            collide_polygon_segment(p, pb, angle_b, pa, angle_a, *half_length, alert).flipped()
        }
        (Segment { .. }, Segment { .. }) => Manifold::EMPTY,
    }
}
