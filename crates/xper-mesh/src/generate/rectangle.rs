//! A rectangle with rectangular inclusions and an optional straight pre-crack: the
//! bimaterial specimen (a 5e-5 m square matrix with stiff inclusions, element size about
//! 5e-7 m, a pre-crack rising from the bottom edge).

use serde::{Deserialize, Serialize};

use super::{
    check_count, finish_mesh, inclusion_outline, matrix_and_inclusions, positive, rectangle_sides,
    triangulate, Line, Pslg,
};
use crate::error::{MeshError, MeshErrorKind};
use crate::mesh::Mesh;

const ORIGIN: &str = "rectangle_with_inclusions";

/// The rectangle `[0, width] x [0, height]` with inclusions and a pre-crack.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RectangleSpec {
    /// Width along x (m).
    pub width: f64,
    /// Height along y (m).
    pub height: f64,
    /// Rectangular inclusions `[xmin, ymin, xmax, ymax]` (m), strictly inside the rectangle
    /// and apart from each other (no overlap, no contact).
    pub inclusions: Vec<[f64; 4]>,
    /// The pre-crack segment `(from, to)` (m): inside the closed rectangle (an end may lie on
    /// the boundary), apart from the inclusions, not along a side.
    pub precrack: Option<([f64; 2], [f64; 2])>,
    /// Target element size `h` (m): no boundary piece is longer than `h`.
    pub element_size: f64,
}

fn spec_error(place: impl Into<String>, reason: impl Into<String>) -> MeshError {
    MeshError::new(MeshErrorKind::Spec, ORIGIN, reason).at(place)
}

/// Whether the segment `a`-`b` meets the closed box `[xmin, ymin, xmax, ymax]`, by
/// Liang-Barsky clipping (Y.-D. Liang, B. A. Barsky, "A new concept and method for line
/// clipping", ACM Trans. Graph. 3(1):1-22, 1984).
fn segment_meets_box(a: [f64; 2], b: [f64; 2], r: [f64; 4]) -> bool {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for axis in 0..2 {
        for (p, q) in [
            (-d[axis], a[axis] - r[axis]),
            (d[axis], r[axis + 2] - a[axis]),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
    }
    t0 <= t1
}

fn check(spec: &RectangleSpec) -> Result<(), MeshError> {
    positive(ORIGIN, "width", spec.width)?;
    positive(ORIGIN, "height", spec.height)?;
    positive(ORIGIN, "element_size", spec.element_size)?;
    check_count(ORIGIN, spec.width * spec.height, spec.element_size)?;
    let (w, h) = (spec.width, spec.height);
    for (i, r) in spec.inclusions.iter().enumerate() {
        let place = format!("inclusions[{i}] = {r:?}");
        if r.iter().any(|v| !v.is_finite()) || !(r[0] < r[2] && r[1] < r[3]) {
            return Err(spec_error(
                place,
                "an inclusion is [xmin, ymin, xmax, ymax] with finite xmin < xmax, ymin < ymax",
            ));
        }
        if !(r[0] > 0.0 && r[1] > 0.0 && r[2] < w && r[3] < h) {
            return Err(spec_error(
                place,
                format!("the inclusion must lie strictly inside the rectangle {w} x {h} m"),
            ));
        }
        for (j, s) in spec.inclusions[..i].iter().enumerate() {
            if r[0] <= s[2] && s[0] <= r[2] && r[1] <= s[3] && s[1] <= r[3] {
                return Err(spec_error(
                    place,
                    format!("overlaps or touches inclusions[{j}] = {s:?}"),
                ));
            }
        }
    }
    if let Some((a, b)) = spec.precrack {
        let place = format!("precrack = ({a:?}, {b:?})");
        if a.iter().chain(&b).any(|v| !v.is_finite()) || a == b {
            return Err(spec_error(
                place,
                "the pre-crack needs two distinct finite ends",
            ));
        }
        let inside = |p: [f64; 2]| p[0] >= 0.0 && p[0] <= w && p[1] >= 0.0 && p[1] <= h;
        if !inside(a) || !inside(b) {
            return Err(spec_error(
                place,
                format!("the pre-crack must lie inside the rectangle {w} x {h} m"),
            ));
        }
        let along = |axis: usize, value: f64| a[axis] == value && b[axis] == value;
        if along(0, 0.0) || along(0, w) || along(1, 0.0) || along(1, h) {
            return Err(spec_error(place, "the pre-crack lies along a side"));
        }
        if let Some(j) = (spec.inclusions.iter()).position(|r| segment_meets_box(a, b, *r)) {
            return Err(spec_error(
                place,
                format!("the pre-crack meets inclusions[{j}]"),
            ));
        }
    }
    Ok(())
}

/// Meshes the rectangle of `spec`.
///
/// Regions: `matrix` (tag 1) and `inclusion` (tag 2, all inclusions; present even without
/// inclusions, then with no triangle). Edge sets (each with its node set): `left` (x = 0),
/// `right` (x = width), `bottom` (y = 0), `top` (y = height), `inclusion_boundary` (the
/// outlines of the inclusions) and `precrack` (the mesh edges on the pre-crack segment, whose
/// interfaces start broken); the last two are empty when there is nothing to put in them.
///
/// Errors (kind [`MeshErrorKind::Spec`]): a non-positive or non-finite size, an inclusion not
/// strictly inside or overlapping another, a pre-crack outside, along a side or meeting an
/// inclusion, an element size giving more than [`MAX_TRIANGLES`](super::MAX_TRIANGLES).
pub fn rectangle_with_inclusions(spec: &RectangleSpec) -> Result<Mesh, MeshError> {
    check(spec)?;
    let (w, ht, h) = (spec.width, spec.height, spec.element_size);
    let mut lines = rectangle_sides(w, ht);
    for r in &spec.inclusions {
        lines.extend(inclusion_outline(*r));
    }
    let mut breaks = Vec::new();
    if let Some((a, b)) = spec.precrack {
        lines.push(Line {
            a,
            b,
            set: "precrack",
        });
        breaks = vec![a, b];
    }
    let mut pslg = Pslg::default();
    for line in &lines {
        pslg.add_line(line.a, line.b, &breaks, h);
    }
    let raw = triangulate(ORIGIN, pslg, h, Default::default(), |_| true, &lines)?;
    let in_inclusion = |p: [f64; 2]| {
        (spec.inclusions.iter()).any(|r| p[0] > r[0] && p[0] < r[2] && p[1] > r[1] && p[1] < r[3])
    };
    let (triangle_region, regions) = matrix_and_inclusions(&raw, in_inclusion);
    let sets = [
        "left",
        "right",
        "bottom",
        "top",
        "inclusion_boundary",
        "precrack",
    ];
    finish_mesh(ORIGIN, raw, triangle_region, regions, &lines, h, &sets)
}

#[cfg(test)]
mod tests {
    use super::segment_meets_box;

    #[test]
    fn liang_barsky_cases() {
        let r = [1.0, 1.0, 2.0, 2.0];
        assert!(segment_meets_box([0.0, 0.0], [3.0, 3.0], r));
        assert!(segment_meets_box([0.0, 1.0], [1.0, 1.0], r));
        assert!(!segment_meets_box([0.0, 0.0], [0.9, 3.0], r));
        assert!(!segment_meets_box([0.0, 2.5], [3.0, 2.5], r));
        assert!(segment_meets_box([1.5, 1.5], [1.6, 1.6], r));
    }
}
