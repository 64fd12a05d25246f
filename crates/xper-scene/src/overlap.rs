//! Detection of interpenetrating initial bodies, on a uniform grid (O(N) on average for
//! bodies of similar sizes).

use crate::geometry::{add, cross, dot, norm, point_segment_distance, rotate, sub, V2};
use crate::read::Ctx;
use crate::shared::{Built, Origin};
use crate::types::ShapeDesc;

/// At most this many overlap errors are listed; the rest are counted in one more error.
pub const MAX_OVERLAP_REPORTS: usize = 100;

enum Geo {
    Disk { c: V2, r: f64 },
    Poly { v: Vec<V2> },
    Seg { a: V2, b: V2 },
}

struct Item {
    geo: Geo,
    lo: V2,
    hi: V2,
    /// Diameter (disk), circumscribed diameter (polygon) or length (segment).
    size: f64,
}

fn item(shape: &ShapeDesc, p: V2, angle: f64) -> Item {
    match shape {
        ShapeDesc::Disk { radius: r } => Item {
            geo: Geo::Disk { c: p, r: *r },
            lo: [p[0] - r, p[1] - r],
            hi: [p[0] + r, p[1] + r],
            size: 2.0 * r,
        },
        ShapeDesc::Polygon { vertices } => {
            let v: Vec<V2> = vertices.iter().map(|q| add(p, rotate(*q, angle))).collect();
            let (lo, hi) = bounds(&v);
            let size = 2.0 * crate::geometry::circumradius(vertices);
            Item {
                geo: Geo::Poly { v },
                lo,
                hi,
                size,
            }
        }
        ShapeDesc::Segment { half_length } => {
            let d = rotate([*half_length, 0.0], angle);
            let (a, b) = (sub(p, d), add(p, d));
            let (lo, hi) = bounds(&[a, b]);
            Item {
                geo: Geo::Seg { a, b },
                lo,
                hi,
                size: 2.0 * half_length,
            }
        }
    }
}

fn bounds(v: &[V2]) -> (V2, V2) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for q in v {
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    (lo, hi)
}

/// The smallest and largest projection of a counter-clockwise convex polygon on an axis that
/// turns counter-clockwise from call to call (the edge normals of a convex polygon, in order):
/// each extreme vertex then only moves forward, so a full turn costs O(n) instead of O(n^2).
struct Extremes<'a> {
    v: &'a [V2],
    /// Indices of the lowest and highest vertex on the last axis (`None` before the first).
    at: Option<[usize; 2]>,
}

impl<'a> Extremes<'a> {
    fn new(v: &'a [V2]) -> Self {
        Extremes { v, at: None }
    }

    fn along(&mut self, axis: V2) -> (f64, f64) {
        let (v, n) = (self.v, self.v.len());
        let d = |k: usize| dot(v[k % n], axis);
        let [mut lo, mut hi] = match self.at {
            Some(at) => at,
            None => {
                let by = |a: &usize, b: &usize| d(*a).total_cmp(&d(*b));
                let lo = (0..n).min_by(by).unwrap_or(0);
                let hi = (0..n).max_by(by).unwrap_or(0);
                [lo, hi]
            }
        };
        for _ in 0..n {
            if d(lo + 1) >= d(lo) {
                break;
            }
            lo = (lo + 1) % n;
        }
        for _ in 0..n {
            if d(hi + 1) <= d(hi) {
                break;
            }
            hi = (hi + 1) % n;
        }
        self.at = Some([lo, hi]);
        (d(lo), d(hi))
    }
}

/// Minimum overlap of the projections over the edge normals of both convex point sets
/// (counter-clockwise; negative when separated): the penetration depth by separating axes, in
/// time linear in the vertex counts ([`Extremes`]).
fn sat(a: &[V2], b: &[V2]) -> f64 {
    let mut best = f64::INFINITY;
    for poly in [a, b] {
        let (mut on_a, mut on_b) = (Extremes::new(a), Extremes::new(b));
        let n = poly.len();
        for i in 0..n {
            let e = sub(poly[(i + 1) % n], poly[i]);
            let l = norm(e);
            if !(l > 0.0) {
                continue;
            }
            let axis = [e[1] / l, -e[0] / l];
            let (a0, a1) = on_a.along(axis);
            let (b0, b1) = on_b.along(axis);
            // Smallest translation separating the projections (either way).
            best = best.min((a1 - b0).min(b1 - a0));
        }
    }
    best
}

/// Penetration of a disk into a counter-clockwise convex polygon.
fn poly_disk(v: &[V2], c: V2, r: f64) -> f64 {
    let n = v.len();
    let mut max_s = f64::NEG_INFINITY;
    let mut min_d = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        let e = sub(b, a);
        let l = norm(e);
        if l > 0.0 {
            max_s = max_s.max(cross(e, sub(c, a)) / -l);
        }
        min_d = min_d.min(point_segment_distance(c, a, b));
    }
    if max_s <= 0.0 {
        r - max_s
    } else {
        r - min_d
    }
}

/// Penetration depth of two shapes (<= 0 when they do not interpenetrate).
fn depth(a: &Geo, b: &Geo) -> f64 {
    match (a, b) {
        (Geo::Disk { c: c1, r: r1 }, Geo::Disk { c: c2, r: r2 }) => r1 + r2 - norm(sub(*c1, *c2)),
        (Geo::Disk { c, r }, Geo::Seg { a, b }) | (Geo::Seg { a, b }, Geo::Disk { c, r }) => {
            r - point_segment_distance(*c, *a, *b)
        }
        (Geo::Disk { c, r }, Geo::Poly { v }) | (Geo::Poly { v }, Geo::Disk { c, r }) => {
            poly_disk(v, *c, *r)
        }
        (Geo::Poly { v }, Geo::Seg { a, b }) | (Geo::Seg { a, b }, Geo::Poly { v }) => {
            sat(v, &[*a, *b])
        }
        (Geo::Poly { v: v1 }, Geo::Poly { v: v2 }) => sat(v1, v2),
        (Geo::Seg { .. }, Geo::Seg { .. }) => 0.0,
    }
}

/// A uniform grid over the non-wall bodies, in compressed (CSR) form.
struct Grid {
    lo: V2,
    cell: f64,
    nx: usize,
    ny: usize,
    start: Vec<usize>,
    ids: Vec<usize>,
}

impl Grid {
    fn cell_of(&self, p: V2) -> (usize, usize) {
        let f = |x: f64, lo: f64, n: usize| {
            (((x - lo) / self.cell).floor().max(0.0) as usize).min(n - 1)
        };
        (f(p[0], self.lo[0], self.nx), f(p[1], self.lo[1], self.ny))
    }

    fn range(&self, lo: V2, hi: V2) -> ((usize, usize), (usize, usize)) {
        (self.cell_of(lo), self.cell_of(hi))
    }

    fn build(items: &[Item], solids: &[usize]) -> Grid {
        let lo = solids.iter().fold([f64::INFINITY; 2], |m, &i| {
            [m[0].min(items[i].lo[0]), m[1].min(items[i].lo[1])]
        });
        let hi = solids.iter().fold([f64::NEG_INFINITY; 2], |m, &i| {
            [m[0].max(items[i].hi[0]), m[1].max(items[i].hi[1])]
        });
        let mut cell = solids.iter().map(|&i| items[i].size).fold(0.0, f64::max);
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if !(cell > 0.0) || !cell.is_finite() {
            cell = extent.max(1.0);
        }
        let limit = 4.0 * solids.len() as f64 + 64.0;
        let dims = |cell: f64| {
            (
                ((hi[0] - lo[0]) / cell).floor() + 1.0,
                ((hi[1] - lo[1]) / cell).floor() + 1.0,
            )
        };
        while {
            let (x, y) = dims(cell);
            !(x * y <= limit)
        } {
            cell *= 2.0;
            if !cell.is_finite() {
                cell = f64::MAX;
                break;
            }
        }
        let (x, y) = dims(cell);
        let (mut nx, mut ny) = (
            (x.max(1.0) as usize).min(1 << 24),
            (y.max(1.0) as usize).min(1 << 24),
        );
        if !(nx as f64 * ny as f64 <= limit) {
            // Pathological extents (e.g. near f64::MAX): one cell, quadratic but safe.
            (nx, ny) = (1, 1);
        }
        let mut g = Grid {
            lo,
            cell,
            nx,
            ny,
            start: vec![0; nx * ny + 1],
            ids: Vec::new(),
        };
        for &i in solids {
            let ((x0, y0), (x1, y1)) = g.range(items[i].lo, items[i].hi);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    g.start[y * nx + x + 1] += 1;
                }
            }
        }
        for c in 0..nx * ny {
            g.start[c + 1] += g.start[c];
        }
        let mut fill = g.start.clone();
        g.ids = vec![0; g.start[nx * ny]];
        for &i in solids {
            let ((x0, y0), (x1, y1)) = g.range(items[i].lo, items[i].hi);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    g.ids[fill[y * nx + x]] = i;
                    fill[y * nx + x] += 1;
                }
            }
        }
        g
    }

    fn cell_ids(&self, x: usize, y: usize) -> &[usize] {
        let c = y * self.nx + x;
        &self.ids[self.start[c]..self.start[c + 1]]
    }
}

fn boxes_overlap(a: &Item, b: &Item) -> bool {
    a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1]
}

/// Reports every pair of interpenetrating bodies (walls may touch or cross each other).
pub(crate) fn check(ctx: &mut Ctx, built: &Built) {
    let items: Vec<Item> = built
        .bodies
        .iter()
        .map(|b| item(&b.shape, b.position, b.angle))
        .collect();
    let is_wall = |i: usize| matches!(items[i].geo, Geo::Seg { .. });
    let solids: Vec<usize> = (0..items.len()).filter(|&i| !is_wall(i)).collect();
    if solids.is_empty() {
        return;
    }
    let grid = Grid::build(&items, &solids);
    let mut found: Vec<(usize, usize, f64)> = Vec::new();
    let mut total = 0usize;
    let mut test = |a: usize, b: usize, found: &mut Vec<(usize, usize, f64)>| {
        let d = depth(&items[a].geo, &items[b].geo);
        let tol = 1e-9 + 1e-6 * items[a].size.min(items[b].size);
        if d > tol {
            total += 1;
            if found.len() < MAX_OVERLAP_REPORTS {
                found.push((a.min(b), a.max(b), d));
            }
        }
    };
    for y in 0..grid.ny {
        for x in 0..grid.nx {
            let ids = grid.cell_ids(x, y);
            for (k, &a) in ids.iter().enumerate() {
                for &b in &ids[k + 1..] {
                    let (ia, ib) = (&items[a], &items[b]);
                    if !boxes_overlap(ia, ib) {
                        continue;
                    }
                    // Test each pair once: in the cell holding the corner max(lo_a, lo_b).
                    let corner = [ia.lo[0].max(ib.lo[0]), ia.lo[1].max(ib.lo[1])];
                    if grid.cell_of(corner) == (x, y) {
                        test(a, b, &mut found);
                    }
                }
            }
        }
    }
    let mut seen = vec![usize::MAX; items.len()];
    for w in (0..items.len()).filter(|&i| is_wall(i)) {
        let iw = &items[w];
        let ((x0, y0), (x1, y1)) = grid.range(iw.lo, iw.hi);
        for y in y0..=y1 {
            for x in x0..=x1 {
                for &b in grid.cell_ids(x, y) {
                    if seen[b] != w && boxes_overlap(iw, &items[b]) {
                        seen[b] = w;
                        test(w, b, &mut found);
                    }
                }
            }
        }
    }
    report(ctx, &built.origins, found, total);
}

/// Reports the overlapping pairs `found` (bodies `a < b` and depth, m), sorted by the later
/// body, at the later body's entry, and how many more of the `total` were not listed.
pub(crate) fn report(
    ctx: &mut Ctx,
    origins: &[Origin],
    mut found: Vec<(usize, usize, f64)>,
    total: usize,
) {
    found.sort_by_key(|&(a, b, _)| (b, a));
    for &(a, b, d) in &found {
        let (oa, ob) = (&origins[a], &origins[b]);
        let msg = format!(
            "body {b} ({}) overlaps body {a} ({}, at {}:{}:{}) by {d:.3e} m",
            ob.describe(),
            oa.describe(),
            ctx.file.display(),
            oa.pos.line,
            oa.pos.column
        );
        ctx.err(ob.pos, &ob.field(), msg);
    }
    if total > found.len() {
        if let Some(&(_, b, _)) = found.first() {
            let ob = &origins[b];
            let msg = format!("... and {} more overlapping pairs", total - found.len());
            ctx.err(ob.pos, &ob.field(), msg);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The separating-axis depth with every projection taken over every vertex.
    fn brute_force_sat(a: &[V2], b: &[V2]) -> f64 {
        let mut best = f64::INFINITY;
        for poly in [a, b] {
            let n = poly.len();
            for i in 0..n {
                let e = sub(poly[(i + 1) % n], poly[i]);
                let l = norm(e);
                if !(l > 0.0) {
                    continue;
                }
                let axis = [e[1] / l, -e[0] / l];
                let proj = |s: &[V2]| {
                    (s.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                        (lo.min(dot(*q, axis)), hi.max(dot(*q, axis)))
                    })
                };
                let ((a0, a1), (b0, b1)) = (proj(a), proj(b));
                best = best.min((a1 - b0).min(b1 - a0));
            }
        }
        best
    }

    struct Lcg(u64);
    impl Lcg {
        fn unit(&mut self) -> f64 {
            self.0 = (self.0)
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A counter-clockwise convex polygon: `n` points at sorted random angles on an ellipse.
    fn convex(rng: &mut Lcg, n: usize) -> Vec<V2> {
        let (cx, cy) = (rng.unit() * 2.0, rng.unit() * 2.0);
        let (rx, ry) = (0.2 + rng.unit(), 0.2 + rng.unit());
        let mut angles: Vec<f64> = (0..n).map(|_| rng.unit() * std::f64::consts::TAU).collect();
        angles.sort_by(f64::total_cmp);
        angles.dedup();
        angles
            .iter()
            .map(|t| [cx + rx * t.cos(), cy + ry * t.sin()])
            .collect()
    }

    #[test]
    fn linear_separating_axes_give_the_brute_force_depth_bit_for_bit() {
        let mut rng = Lcg(7);
        for case in 0..2000 {
            let (n, m) = (3 + case % 40, 3 + (case / 40) % 25);
            let a = convex(&mut rng, n);
            let b = if case % 5 == 0 {
                let s = convex(&mut rng, 2);
                vec![s[0], s[1 % s.len()]]
            } else {
                convex(&mut rng, m)
            };
            let (fast, brute) = (sat(&a, &b), brute_force_sat(&a, &b));
            assert_eq!(
                fast.to_bits(),
                brute.to_bits(),
                "case {case}: {fast} vs {brute}"
            );
        }
    }
}
