//! Body shapes and their mass properties (2D, per unit thickness).

use serde::{Deserialize, Serialize};
use xper_math::{cross, rotate, Aabb, Real, Vector};

/// A convex polygon given by its vertices relative to its centroid, counter-clockwise.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConvexPolygon {
    /// Vertices in the body frame (centroid at the origin), counter-clockwise.
    pub vertices: Vec<Vector>,
    /// Outward unit normal of edge `k` (from vertex `k` to vertex `k + 1`), body frame.
    pub normals: Vec<Vector>,
    /// Largest distance from the centroid to a vertex.
    pub bounding_radius: Real,
}

impl ConvexPolygon {
    /// A polygon from counter-clockwise vertices already centred on their centroid.
    pub fn new(vertices: Vec<Vector>) -> Self {
        let n = vertices.len();
        let normals = (0..n)
            .map(|k| {
                let e = vertices[(k + 1) % n] - vertices[k];
                Vector::new(e.y, -e.x).normalize()
            })
            .collect();
        let bounding_radius = vertices.iter().map(|v| v.norm()).fold(0.0, Real::max);
        ConvexPolygon {
            vertices,
            normals,
            bounding_radius,
        }
    }

    /// Area (m^2) and polar second moment of area about the centroid (m^4).
    pub fn area_and_polar_moment(&self) -> (Real, Real) {
        let n = self.vertices.len();
        let (mut area, mut moment) = (0.0, 0.0);
        for k in 0..n {
            let (a, b) = (self.vertices[k], self.vertices[(k + 1) % n]);
            let c = cross(&a, &b);
            area += c / 2.0;
            moment += c * (a.dot(&a) + a.dot(&b) + b.dot(&b)) / 12.0;
        }
        (area, moment)
    }
}

/// The geometry of a body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Shape {
    /// A disk of the given radius (m) centred on the body position.
    Disk {
        /// Radius (m).
        radius: Real,
    },
    /// A convex polygon, boxed so that the enum is 16 bytes instead of 56: a set of disks does
    /// not pay for vertex lists (a polygon body pays one more allocation and indirection).
    Polygon(Box<ConvexPolygon>),
    /// A wall: the segment of half-length `half_length` (m) along the body's x axis.
    Segment {
        /// Half of the segment's length (m).
        half_length: Real,
    },
}

// The size the per-body memory figures of BENCHMARKS.md count on.
const _: () = assert!(std::mem::size_of::<Shape>() == 16);

impl Shape {
    /// Whether the shape is a wall (held in place, of any size): the broad phase tests walls
    /// against the cells they cover instead of binning them.
    #[inline]
    pub fn is_wall(&self) -> bool {
        matches!(self, Shape::Segment { .. })
    }

    /// Bounding box of the shape placed at `position` with rotation `angle`.
    pub fn aabb(&self, position: &Vector, angle: Real) -> Aabb {
        match self {
            Shape::Disk { radius } => Aabb::from_center(*position, Vector::repeat(*radius)),
            Shape::Polygon(p) => {
                let mut b = Aabb {
                    min: *position,
                    max: *position,
                };
                for v in &p.vertices {
                    let w = position + rotate(v, angle);
                    b.min = b.min.inf(&w);
                    b.max = b.max.sup(&w);
                }
                b
            }
            Shape::Segment { half_length } => {
                let d = rotate(&Vector::new(*half_length, 0.0), angle);
                let (a, b) = (position - d, position + d);
                Aabb {
                    min: a.inf(&b),
                    max: a.sup(&b),
                }
            }
        }
    }

    /// Mass (kg per m of thickness) and moment of inertia about the centroid for a density (kg/m^3).
    pub fn mass_properties(&self, density: Real) -> (Real, Real) {
        match self {
            Shape::Disk { radius } => {
                let m = density * std::f64::consts::PI * radius * radius;
                (m, m * radius * radius / 2.0)
            }
            Shape::Polygon(p) => {
                let (area, polar) = p.area_and_polar_moment();
                (density * area, density * polar)
            }
            Shape::Segment { .. } => (Real::INFINITY, Real::INFINITY),
        }
    }

    /// A length characterising the body: the disk radius, the polygon's bounding radius,
    /// the segment's half-length.
    pub fn size(&self) -> Real {
        match self {
            Shape::Disk { radius } => *radius,
            Shape::Polygon(p) => p.bounding_radius,
            Shape::Segment { half_length } => *half_length,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_mass_properties_match_formula() {
        let (w, h) = (0.4, 0.1);
        let p = ConvexPolygon::new(vec![
            Vector::new(-w / 2.0, -h / 2.0),
            Vector::new(w / 2.0, -h / 2.0),
            Vector::new(w / 2.0, h / 2.0),
            Vector::new(-w / 2.0, h / 2.0),
        ]);
        let (m, i) = Shape::Polygon(Box::new(p.clone())).mass_properties(1000.0);
        assert!((m - 1000.0 * w * h).abs() < 1e-12);
        assert!((i - m * (w * w + h * h) / 12.0).abs() < 1e-15);
        assert!((p.normals[0] - Vector::new(0.0, -1.0)).norm() < 1e-15);
    }

    #[test]
    fn rotated_segment_box() {
        let s = Shape::Segment { half_length: 1.0 };
        let b = s.aabb(&Vector::new(1.0, 1.0), std::f64::consts::FRAC_PI_2);
        assert!((b.min - Vector::new(1.0, 0.0)).norm() < 1e-15);
        assert!((b.max - Vector::new(1.0, 2.0)).norm() < 1e-15);
    }
}
