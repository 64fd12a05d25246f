//! Small 2D geometry helpers: polygon properties, convexity, distances.

pub(crate) type V2 = [f64; 2];

pub(crate) fn sub(a: V2, b: V2) -> V2 {
    [a[0] - b[0], a[1] - b[1]]
}

pub(crate) fn add(a: V2, b: V2) -> V2 {
    [a[0] + b[0], a[1] + b[1]]
}

pub(crate) fn scale(a: V2, s: f64) -> V2 {
    [a[0] * s, a[1] * s]
}

pub(crate) fn dot(a: V2, b: V2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

pub(crate) fn cross(a: V2, b: V2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

pub(crate) fn norm(a: V2) -> f64 {
    a[0].hypot(a[1])
}

/// `v` rotated by `angle`.
pub(crate) fn rotate(v: V2, angle: f64) -> V2 {
    let (s, c) = angle.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// Distance from `p` to the segment `[a, b]`.
pub(crate) fn point_segment_distance(p: V2, a: V2, b: V2) -> f64 {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(sub(p, add(a, scale(ab, t))))
}

/// Mass properties of a validated convex polygon.
#[derive(Debug, Clone)]
pub(crate) struct PolyProps {
    /// Centroid (absolute).
    pub centroid: V2,
    /// Area, > 0.
    pub area: f64,
    /// Vertices relative to the centroid, counter-clockwise.
    pub rel: Vec<V2>,
    /// Second moment of area about the centroid (inertia = density * this).
    pub second_moment: f64,
}

/// Largest distance from the centroid to a vertex.
pub(crate) fn circumradius(rel: &[V2]) -> f64 {
    rel.iter().map(|v| norm(*v)).fold(0.0, f64::max)
}

/// A vertex list for an error message: whole when short, else its first vertices and the count
/// (a message must not repeat a whole 100,000-vertex line).
fn listed(v: &[V2]) -> String {
    const SHOWN: usize = 8;
    if v.len() <= SHOWN {
        format!("{v:?}")
    } else {
        let head = format!("{:?}", &v[..SHOWN]);
        format!("{}, ...] ({} vertices)", &head[..head.len() - 1], v.len())
    }
}

/// Checks an absolute vertex list (>= 3 vertices, non-degenerate, strictly convex, simple;
/// clockwise lists are reversed) and computes its centroid, area and second moment.
pub(crate) fn polygon(abs: &[V2]) -> Result<PolyProps, String> {
    let n = abs.len();
    if n < 3 {
        return Err(format!("a polygon needs at least 3 vertices, got {n}"));
    }
    // Work relative to the first vertex for precision.
    let o = abs[0];
    let mut pts: Vec<V2> = abs.iter().map(|v| sub(*v, o)).collect();
    let size = pts.iter().map(|v| norm(*v)).fold(0.0, f64::max);
    let twice_area: f64 = (0..n).map(|i| cross(pts[i], pts[(i + 1) % n])).sum();
    if !(twice_area.abs() > 1e-12 * size * size) || !twice_area.is_finite() {
        return Err(format!(
            "degenerate polygon (area {}), vertices {}",
            twice_area / 2.0,
            listed(abs)
        ));
    }
    if twice_area < 0.0 {
        pts.reverse();
    }
    let area = twice_area.abs() / 2.0;
    let mut turning = 0.0;
    for i in 0..n {
        let e0 = sub(pts[(i + 1) % n], pts[i]);
        let e1 = sub(pts[(i + 2) % n], pts[(i + 1) % n]);
        let c = cross(e0, e1);
        if !(c > 1e-12 * size * size) {
            let what = if c < 0.0 {
                "not convex"
            } else {
                "has collinear or repeated vertices"
            };
            return Err(format!(
                "polygon {what} (at vertex {:?}), vertices {}",
                add(pts[(i + 1) % n], o),
                listed(abs)
            ));
        }
        turning += c.atan2(dot(e0, e1));
    }
    if (turning - 2.0 * std::f64::consts::PI).abs() > 1e-6 {
        return Err(format!(
            "polygon is self-intersecting, vertices {}",
            listed(abs)
        ));
    }
    let (mut cx, mut cy) = (0.0, 0.0);
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        let c = cross(a, b);
        cx += (a[0] + b[0]) * c;
        cy += (a[1] + b[1]) * c;
    }
    let c_rel = [cx / (6.0 * area), cy / (6.0 * area)];
    let rel: Vec<V2> = pts.iter().map(|v| sub(*v, c_rel)).collect();
    let mut j = 0.0;
    for i in 0..n {
        let (a, b) = (rel[i], rel[(i + 1) % n]);
        let c = cross(a, b);
        j +=
            c * (a[0] * a[0] + a[0] * b[0] + b[0] * b[0] + a[1] * a[1] + a[1] * b[1] + b[1] * b[1]);
    }
    Ok(PolyProps {
        centroid: add(o, c_rel),
        area,
        rel,
        second_moment: j / 12.0,
    })
}

/// The counter-clockwise vertices of a `w` x `h` rectangle centred on the origin.
pub(crate) fn rectangle(w: f64, h: f64) -> Vec<V2> {
    let (a, b) = (w / 2.0, h / 2.0);
    vec![[-a, -b], [a, -b], [a, b], [-a, b]]
}
