//! A periodic cell: the rectangle `[0, width] x [0, height]` with circular inclusions, placed
//! or random at an area fraction, that wrap across its sides (a circle crossing `x = width`
//! re-enters at `x = 0`), and rectangular inclusions strictly inside. Opposite sides carry the
//! same nodes, so that [`Mesh::periodic_edges`] matches every boundary edge.
//!
//! Each circle is a regular polygon inscribed in it, with sides no longer than the element
//! size. Its nine images (shifted by `-1, 0, 1` periods along each axis) are clipped to the
//! cell (Liang-Barsky, see [`super::rectangle`]) in the circle's own frame, so that a crossing
//! of `x = 0` and the matching crossing of `x = width` are computed from the same numbers and
//! agree to the bit; the refinement never splits a line, so the sides keep those nodes.

use serde::{Deserialize, Serialize};

use super::{
    check_count, finish_mesh, inclusion_outline, matrix_and_inclusions, positive, rectangle_sides,
    triangulate, Line, Pslg, Refine,
};
use crate::error::{MeshError, MeshErrorKind};
use crate::mesh::Mesh;
use crate::periodic::PeriodicCell;

const ORIGIN: &str = "periodic_cell";

/// A circle (m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Circle {
    /// Centre `[x, y]` (m), anywhere (taken modulo the cell).
    pub center: [f64; 2],
    /// Radius (m), > 0.
    pub radius: f64,
}

/// Circles of one radius placed at random (random sequential addition) until an area
/// fraction is reached.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RandomCircles {
    /// Target area fraction of the circles, in (0, 0.6): the number placed is the nearest
    /// integer to `fraction W H / (pi r^2)`.
    pub fraction: f64,
    /// Radius (m).
    pub radius: f64,
    /// Smallest gap (m) between two circles, and between a circle and a rectangle.
    pub min_spacing: f64,
    /// Seed of the SplitMix64 generator ([`xper_math::SplitMix64`]; the same seed gives the
    /// same cell).
    pub seed: u64,
}

/// The periodic cell `[0, width] x [0, height]` and its inclusions.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeriodicCellSpec {
    /// Width along x (m).
    pub width: f64,
    /// Height along y (m).
    pub height: f64,
    /// Circular inclusions placed explicitly.
    pub circles: Vec<Circle>,
    /// Rectangular inclusions `[xmin, ymin, xmax, ymax]` (m), strictly inside the cell.
    pub rectangles: Vec<[f64; 4]>,
    /// Circles added at random after the placed ones.
    pub random: Option<RandomCircles>,
    /// Target element size `h` (m).
    pub element_size: f64,
}

fn spec_error(place: impl Into<String>, reason: impl Into<String>) -> MeshError {
    MeshError::new(MeshErrorKind::Spec, ORIGIN, reason).at(place)
}

/// `x` reduced to `[0, period)`.
fn wrap(x: f64, period: f64) -> f64 {
    let r = x.rem_euclid(period);
    if r >= period {
        0.0
    } else {
        r
    }
}

/// The shortest periodic difference `b - a` along one axis.
fn periodic_delta(a: f64, b: f64, period: f64) -> f64 {
    let d = (b - a).rem_euclid(period);
    if d > 0.5 * period {
        d - period
    } else {
        d
    }
}

struct Cell {
    size: [f64; 2],
    h: f64,
}

impl Cell {
    /// Periodic distance between two points.
    fn distance(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        let dx = periodic_delta(a[0], b[0], self.size[0]);
        let dy = periodic_delta(a[1], b[1], self.size[1]);
        dx.hypot(dy)
    }

    /// Periodic distance from a point to a rectangle inside the cell.
    fn distance_to_rectangle(&self, p: [f64; 2], r: [f64; 4]) -> f64 {
        let c = [0.5 * (r[0] + r[2]), 0.5 * (r[1] + r[3])];
        let half = [0.5 * (r[2] - r[0]), 0.5 * (r[3] - r[1])];
        let d: [f64; 2] = std::array::from_fn(|k| {
            (periodic_delta(c[k], p[k], self.size[k]).abs() - half[k]).max(0.0)
        });
        d[0].hypot(d[1])
    }

    /// Why a circle's outline would pass too close to a side or a corner of the cell (closer
    /// than h/2 without crossing it clearly), if it would.
    fn grazes(&self, c: &Circle) -> Option<String> {
        let margin = 0.5 * self.h;
        for k in 0..2 {
            let x = wrap(c.center[k], self.size[k]);
            let d = x.min(self.size[k] - x);
            if (d - c.radius).abs() < margin {
                let name = ["x = 0 (and its image x = width)", "y = 0 (and y = height)"][k];
                return Some(format!(
                    "its outline passes within h/2 = {margin} m of the side {name} \
                     without crossing it clearly"
                ));
            }
        }
        let d = self.distance(c.center, [0.0, 0.0]);
        ((d - c.radius).abs() < margin)
            .then(|| format!("its outline passes within h/2 = {margin} m of a corner of the cell"))
    }
}

fn check(spec: &PeriodicCellSpec) -> Result<(), MeshError> {
    positive(ORIGIN, "width", spec.width)?;
    positive(ORIGIN, "height", spec.height)?;
    positive(ORIGIN, "element_size", spec.element_size)?;
    check_count(ORIGIN, spec.width * spec.height, spec.element_size)?;
    let cell = Cell {
        size: [spec.width, spec.height],
        h: spec.element_size,
    };
    let half = 0.5 * spec.width.min(spec.height);
    for (i, c) in spec.circles.iter().enumerate() {
        let place = format!("circles[{i}]");
        if c.center.iter().any(|v| !v.is_finite()) || !(c.radius > 0.0 && c.radius < half) {
            return Err(spec_error(
                place,
                format!(
                    "a circle needs a finite centre and a radius in (0, {half}) m (half the \
                     shorter side: it must not meet its own image), got {c:?}"
                ),
            ));
        }
        if let Some(why) = cell.grazes(c) {
            return Err(spec_error(place, why));
        }
        for (j, o) in spec.circles[..i].iter().enumerate() {
            if cell.distance(c.center, o.center) <= c.radius + o.radius {
                return Err(spec_error(
                    place,
                    format!("overlaps or touches circles[{j}] (distances are periodic)"),
                ));
            }
        }
    }
    for (i, r) in spec.rectangles.iter().enumerate() {
        let place = format!("rectangles[{i}] = {r:?}");
        if r.iter().any(|v| !v.is_finite()) || !(r[0] < r[2] && r[1] < r[3]) {
            return Err(spec_error(
                place,
                "a rectangle is [xmin, ymin, xmax, ymax] with finite xmin < xmax, ymin < ymax",
            ));
        }
        if !(r[0] > 0.0 && r[1] > 0.0 && r[2] < spec.width && r[3] < spec.height) {
            return Err(spec_error(
                place,
                "a rectangular inclusion must lie strictly inside the cell",
            ));
        }
        for (j, s) in spec.rectangles[..i].iter().enumerate() {
            if r[0] <= s[2] && s[0] <= r[2] && r[1] <= s[3] && s[1] <= r[3] {
                return Err(spec_error(
                    place,
                    format!("overlaps or touches rectangles[{j}]"),
                ));
            }
        }
        if let Some(j) =
            (spec.circles.iter()).position(|c| cell.distance_to_rectangle(c.center, *r) <= c.radius)
        {
            return Err(spec_error(
                place,
                format!("overlaps or touches circles[{j}]"),
            ));
        }
    }
    if let Some(r) = &spec.random {
        let ok = r.fraction > 0.0
            && r.fraction < 0.6
            && r.radius > 0.0
            && r.radius < half
            && r.min_spacing >= 0.0
            && r.min_spacing.is_finite();
        if !ok {
            return Err(spec_error(
                "random",
                format!(
                    "needs a fraction in (0, 0.6), a radius in (0, {half}) m and a finite \
                     min_spacing >= 0 m, got {r:?}"
                ),
            ));
        }
    }
    Ok(())
}

/// The circles of `spec` with the random ones added.
fn all_circles(spec: &PeriodicCellSpec) -> Result<Vec<Circle>, MeshError> {
    let mut circles = spec.circles.clone();
    let Some(r) = spec.random else {
        return Ok(circles);
    };
    let cell = Cell {
        size: [spec.width, spec.height],
        h: spec.element_size,
    };
    let area = spec.width * spec.height;
    let wanted = (r.fraction * area / (std::f64::consts::PI * r.radius * r.radius)).round();
    let wanted = wanted.max(1.0) as usize;
    let budget = 2000 * wanted;
    let mut rng = xper_math::SplitMix64::new(r.seed);
    let mut uniform = move || rng.next_f64();
    let (mut placed, mut attempts) = (0, 0);
    while placed < wanted {
        if attempts == budget {
            return Err(spec_error(
                "random",
                format!(
                    "placed {placed} of {wanted} circles in {budget} attempts: lower the \
                     fraction, the radius or min_spacing"
                ),
            ));
        }
        attempts += 1;
        let c = Circle {
            center: [uniform() * spec.width, uniform() * spec.height],
            radius: r.radius,
        };
        let free = circles
            .iter()
            .all(|o| cell.distance(c.center, o.center) >= c.radius + o.radius + r.min_spacing)
            && (spec.rectangles.iter())
                .all(|q| cell.distance_to_rectangle(c.center, *q) >= c.radius + r.min_spacing)
            && cell.grazes(&c).is_none();
        if free {
            circles.push(c);
            placed += 1;
        }
    }
    Ok(circles)
}

/// The vertices of the polygon standing for `c` (centre reduced into the cell), rotated so
/// that no vertex lies near a side line of the cell or one of its images.
fn polygon(c: &Circle, size: [f64; 2], h: f64) -> Vec<[f64; 2]> {
    let center = [wrap(c.center[0], size[0]), wrap(c.center[1], size[1])];
    let tau = std::f64::consts::TAU;
    let n = ((tau * c.radius / h).ceil() as usize).max(16);
    let chord = 2.0 * c.radius * (std::f64::consts::PI / n as f64).sin();
    let vertices = |phase: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|k| {
                let a = phase + tau * k as f64 / n as f64;
                [
                    center[0] + c.radius * a.cos(),
                    center[1] + c.radius * a.sin(),
                ]
            })
            .collect()
    };
    let clear = |v: &[[f64; 2]]| {
        v.iter().all(|p| {
            (0..2).all(|k| {
                let x = wrap(p[k], size[k]);
                x.min(size[k] - x) > 0.1 * chord
            })
        })
    };
    (0..16)
        .map(|j| vertices(tau / n as f64 * j as f64 / 16.0))
        .find(|v| clear(v))
        .unwrap_or_else(|| vertices(0.0))
}

/// Liang-Barsky clipping of `a`-`b` to the box `[lo, hi]`: the parameters `t0 <= t1` of the
/// part inside and, for each end, the axis of the box side it lies on (if cut there).
fn clip(a: [f64; 2], b: [f64; 2], lo: [f64; 2], hi: [f64; 2]) -> Option<ClipPart> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let mut part = ClipPart {
        t: [0.0, 1.0],
        side: [None, None],
    };
    for axis in 0..2 {
        for (p, q, value) in [
            (-d[axis], a[axis] - lo[axis], lo[axis]),
            (d[axis], hi[axis] - a[axis], hi[axis]),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
                continue;
            }
            let t = q / p;
            if p < 0.0 && t > part.t[0] {
                part.t[0] = t;
                part.side[0] = Some((axis, value));
            } else if p > 0.0 && t < part.t[1] {
                part.t[1] = t;
                part.side[1] = Some((axis, value));
            }
        }
    }
    (part.t[0] < part.t[1]).then_some(part)
}

struct ClipPart {
    t: [f64; 2],
    side: [Option<(usize, f64)>; 2],
}

/// Adds the clipped images of the polygon `v` to `segments`, and the points where they meet
/// the sides to `breaks`.
fn clipped_images(
    v: &[[f64; 2]],
    size: [f64; 2],
    segments: &mut Vec<([f64; 2], [f64; 2])>,
    breaks: &mut Vec<[f64; 2]>,
) {
    for sx in [-1.0, 0.0, 1.0] {
        for sy in [-1.0, 0.0, 1.0] {
            let s = [sx * size[0], sy * size[1]];
            let lo = [0.0 - s[0], 0.0 - s[1]];
            let hi = [size[0] - s[0], size[1] - s[1]];
            for k in 0..v.len() {
                let (a, b) = (v[k], v[(k + 1) % v.len()]);
                let Some(part) = clip(a, b, lo, hi) else {
                    continue;
                };
                let ends = [0, 1].map(|e| {
                    let t = part.t[e];
                    let mut p = match part.side[e] {
                        None => [a, b][e],
                        Some(_) => [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])],
                    };
                    if let Some((axis, value)) = part.side[e] {
                        p[axis] = value;
                    }
                    [p[0] + s[0], p[1] + s[1]]
                });
                for (e, p) in ends.iter().enumerate() {
                    if part.side[e].is_some() {
                        breaks.push(*p);
                    }
                }
                segments.push((ends[0], ends[1]));
            }
        }
    }
}

/// Meshes the periodic cell of `spec`.
///
/// Regions: `matrix` (tag 1) and `inclusion` (tag 2, every circle and rectangle; present even
/// without inclusions, then with no triangle). Edge sets (each with its node set): `left`
/// (x = 0), `right` (x = width), `bottom` (y = 0), `top` (y = height), `inclusion_boundary`.
///
/// Errors (kind [`MeshErrorKind::Spec`]): a non-positive or non-finite size; a circle with a
/// radius not below half the shorter side, overlapping another (periodically), or whose
/// outline grazes a side or a corner (within h/2 without crossing clearly); a rectangle not
/// strictly inside or overlapping an inclusion; random circles that do not fit in 2000
/// attempts each; an element size giving more than [`MAX_TRIANGLES`](super::MAX_TRIANGLES).
pub fn periodic_cell(spec: &PeriodicCellSpec) -> Result<Mesh, MeshError> {
    check(spec)?;
    let (w, ht, h) = (spec.width, spec.height, spec.element_size);
    let size = [w, ht];
    let circles = all_circles(spec)?;
    let polygons: Vec<Vec<[f64; 2]>> = circles.iter().map(|c| polygon(c, size, h)).collect();
    let (mut segments, mut breaks) = (Vec::new(), Vec::new());
    for v in &polygons {
        clipped_images(v, size, &mut segments, &mut breaks);
    }
    breaks.sort_by(|a: &[f64; 2], b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    breaks.dedup();
    let mut lines = rectangle_sides(w, ht);
    let mut pslg = Pslg::default();
    for line in &lines {
        pslg.add_line(line.a, line.b, &breaks, h);
    }
    for r in &spec.rectangles {
        for line in inclusion_outline(*r) {
            pslg.add_line(line.a, line.b, &[], h);
            lines.push(line);
        }
    }
    for &(a, b) in &segments {
        pslg.add_line(a, b, &[], h);
        lines.push(Line {
            a,
            b,
            set: "inclusion_boundary",
        });
    }
    let refine = Refine {
        exclude_outer: false,
        keep_lines: true,
    };
    let raw = triangulate(ORIGIN, pslg, h, refine, |_| true, &lines[..4])?;
    let inside_polygon = |p: [f64; 2], c: &Circle, v: &[[f64; 2]]| {
        let center = [wrap(c.center[0], w), wrap(c.center[1], ht)];
        [-1.0, 0.0, 1.0].iter().any(|sx| {
            [-1.0, 0.0, 1.0].iter().any(|sy| {
                let q = [p[0] - sx * w, p[1] - sy * ht];
                (q[0] - center[0]).hypot(q[1] - center[1]) < c.radius
                    && (0..v.len()).all(|k| {
                        let (a, b) = (v[k], v[(k + 1) % v.len()]);
                        (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]) > 0.0
                    })
            })
        })
    };
    let in_inclusion = |p: [f64; 2]| {
        (spec.rectangles.iter()).any(|r| p[0] > r[0] && p[0] < r[2] && p[1] > r[1] && p[1] < r[3])
            || (circles.iter().zip(&polygons)).any(|(c, v)| inside_polygon(p, c, v))
    };
    let (triangle_region, regions) = matrix_and_inclusions(&raw, in_inclusion);
    let sets = ["left", "right", "bottom", "top", "inclusion_boundary"];
    let mesh = finish_mesh(ORIGIN, raw, triangle_region, regions, &lines, h, &sets)?;
    let cell = PeriodicCell {
        lower: [0.0, 0.0],
        size,
    };
    mesh.periodic_edges(&cell).map_err(|e| {
        spec_error(
            "sides",
            format!("the generated sides do not match (a bug): {e}"),
        )
    })?;
    Ok(mesh)
}
