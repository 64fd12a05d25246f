//! Narrow phase: exact contact points between two placed shapes.

mod disk_disk;
mod disk_polygon;
mod disk_segment;
mod polygon_polygon;
mod polygon_segment;

use xper_bodies::Shape;
use xper_math::{Real, Vector};

pub use disk_disk::{collide_disk_disk, disk_disk_point};
pub use disk_polygon::collide_disk_polygon;
pub use disk_segment::collide_disk_segment;
pub use polygon_polygon::{collide_polygons, WorldPolygon};
pub use polygon_segment::collide_polygon_segment;

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

/// Up to two contact points between two bodies.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Manifold {
    /// Storage; only the first `len` entries are meaningful.
    pub points: [ContactPoint; 2],
    /// Number of points.
    pub len: usize,
}

impl Manifold {
    /// No contact.
    pub const EMPTY: Manifold = Manifold {
        points: [ContactPoint {
            point: Vector::new(0.0, 0.0),
            normal: Vector::new(0.0, 0.0),
            gap: 0.0,
            feature: 0,
        }; 2],
        len: 0,
    };

    /// A manifold of one point.
    pub fn one(p: ContactPoint) -> Self {
        Manifold {
            points: [p, p],
            len: 1,
        }
    }

    /// Adds a point (at most two are kept).
    pub fn push(&mut self, p: ContactPoint) {
        if self.len < 2 {
            self.points[self.len] = p;
            self.len += 1;
        }
    }

    /// The points.
    pub fn as_slice(&self) -> &[ContactPoint] {
        &self.points[..self.len]
    }

    fn flipped(mut self) -> Self {
        for p in &mut self.points[..self.len] {
            *p = p.flipped();
        }
        self
    }
}

/// Contact points between shape `a` placed at (`pa`, `angle_a`) and shape `b`, with normals
/// from `a` to `b`, keeping points whose gap is at most `alert`.
pub fn collide(
    a: &Shape,
    pa: &Vector,
    angle_a: Real,
    b: &Shape,
    pb: &Vector,
    angle_b: Real,
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
