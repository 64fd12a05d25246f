//! Broad phase: a uniform cell grid, O(N) per step.
//!
//! Bodies that fit in a cell ("small": every disk, polygon, sphere and polyhedron; the cell
//! edge is the largest of their bounding-box extents plus the alert distance) are binned by
//! centre with a counting sort and tested against their own cell and half of its neighbours
//! (4 of the 3x3 neighbourhood in 2D, 13 of the 3x3x3 one in 3D, so each pair is met once).
//! Walls ("large": segments, planes) are tested against the small bodies in the cells their
//! bounding box covers, and against each other by brute force. Written once over `DIM`.
//!
//! The boxes are kept in single precision, rounded outwards ([`OuterBox`]): half the bytes
//! to hold and read, and every pair the double-precision boxes would find is still found.

use xper_bodies::BodySet;
use xper_math::buffer::{clear_for, refill};
use xper_math::{Aabb, Real, Vector, DIM};

/// A bounding box in single precision that contains the double-precision box it was made
/// from (each bound rounded outwards), so that boxes that overlap still overlap. The broad
/// phase's pairs are thus a superset of the exact boxes' pairs, and the narrow phase, in
/// double precision, finds the same contacts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OuterBox {
    /// Lower corner, rounded down.
    pub min: [f32; DIM],
    /// Upper corner, rounded up.
    pub max: [f32; DIM],
}

impl OuterBox {
    /// A single-precision box containing `b`: each bound rounded to nearest, then moved
    /// outwards by two units in the last place (the rounding error is at most half of one,
    /// the move's own rounding another half) and the smallest normal number (for bounds
    /// near zero). Without branches, so that the loop over the bodies vectorises.
    pub fn around(b: &Aabb) -> Self {
        const WIDEN: f32 = 1.0 / (1u32 << 22) as f32;
        let near = |x: Real| (x as f32).clamp(-f32::MAX, f32::MAX);
        let margin = |f: f32| f.abs() * WIDEN + f32::MIN_POSITIVE;
        OuterBox {
            min: std::array::from_fn(|k| {
                let f = near(b.min[k]);
                f - margin(f)
            }),
            max: std::array::from_fn(|k| {
                let f = near(b.max[k]);
                f + margin(f)
            }),
        }
    }

    /// The box in double precision (exact).
    pub fn aabb(&self) -> Aabb {
        Aabb {
            min: Vector::from_fn(|k, _| self.min[k] as Real),
            max: Vector::from_fn(|k, _| self.max[k] as Real),
        }
    }

    /// Whether two boxes overlap (touching counts), without branches.
    #[inline(always)]
    pub fn intersects(&self, other: &OuterBox) -> bool {
        (0..DIM).fold(true, |hit, k| {
            hit & (self.min[k] <= other.max[k]) & (other.min[k] <= self.max[k])
        })
    }
}

/// The broad phase with its reusable buffers.
#[derive(Clone, Debug, Default)]
pub struct BroadPhase {
    aabbs: Vec<OuterBox>,
    small: Vec<u32>,
    large: Vec<u32>,
    cell_of: Vec<u32>,
    cell_start: Vec<u32>,
    cell_bodies: Vec<u32>,
    /// `aabbs[cell_bodies[k]]`: the boxes in cell order, read contiguously by the pair loops.
    cell_boxes: Vec<OuterBox>,
    fill: Vec<u32>,
}

struct Grid {
    origin: Vector,
    cell: Real,
    /// Cells along each axis.
    n: [usize; DIM],
}

impl Grid {
    /// The cell holding `p` (clamped to the grid).
    #[inline(always)]
    fn coords(&self, p: &Vector) -> [usize; DIM] {
        std::array::from_fn(|k| {
            ((p[k] - self.origin[k]) / self.cell)
                .floor()
                .clamp(0.0, (self.n[k] - 1) as Real) as usize
        })
    }

    /// The index of a cell, x fastest.
    #[inline(always)]
    fn index(&self, c: [usize; DIM]) -> usize {
        (0..DIM).rev().fold(0, |i, k| i * self.n[k] + c[k])
    }

    /// Number of cells.
    fn count(&self) -> usize {
        self.n.iter().product()
    }

    /// Every cell of the box of cells from `lo` to `hi` (inclusive), x fastest.
    fn cells_between(
        &self,
        lo: [usize; DIM],
        hi: [usize; DIM],
    ) -> impl Iterator<Item = usize> + '_ {
        let total: usize = (0..DIM).map(|k| hi[k] + 1 - lo[k]).product();
        (0..total).map(move |mut r| {
            let c: [usize; DIM] = std::array::from_fn(|k| {
                let width = hi[k] + 1 - lo[k];
                let ck = lo[k] + r % width;
                r /= width;
                ck
            });
            self.index(c)
        })
    }
}

/// The neighbour offsets visited from each cell: those after the cell in the order of the
/// grid (last axis slowest), half of the `3^DIM - 1` neighbours, in that order. In 2D:
/// `(1, 0), (-1, 1), (0, 1), (1, 1)`.
fn half_stencil() -> Vec<[isize; DIM]> {
    let count = 3usize.pow(DIM as u32);
    (0..count)
        .map(|mut r| {
            std::array::from_fn(|_| {
                let d = (r % 3) as isize - 1;
                r /= 3;
                d
            })
        })
        .filter(|d: &[isize; DIM]| {
            // After the cell: the last non-zero offset, from the slowest axis, is positive.
            d.iter().rev().find(|&&x| x != 0).is_some_and(|&x| x > 0)
        })
        .collect()
}

/// The `DIM`-th root (the edge of a cell of a given volume).
#[inline]
fn dim_root(x: Real) -> Real {
    match DIM {
        2 => x.sqrt(),
        _ => x.cbrt(),
    }
}

impl BroadPhase {
    /// A broad phase with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends to `pairs` every pair `(i, j)`, `i < j`, whose bounding boxes grown by `alert`
    /// overlap. The order is deterministic.
    pub fn find_pairs(&mut self, bodies: &BodySet, alert: Real, pairs: &mut Vec<(u32, u32)>) {
        self.find_pairs_of(
            bodies.len(),
            |b| {
                let aabb = bodies.shape[b].aabb(&bodies.position[b], bodies.rotation[b]);
                (aabb, bodies.shape[b].is_wall())
            },
            alert,
            pairs,
        );
    }

    /// [`BroadPhase::find_pairs`] over `n` boxes given by `box_of(k) = (box, is_wall)`
    /// rather than a body set's (e.g. bodies and the periodic images of some of them).
    pub fn find_pairs_of(
        &mut self,
        n: usize,
        box_of: impl Fn(usize) -> (Aabb, bool),
        alert: Real,
        pairs: &mut Vec<(u32, u32)>,
    ) {
        clear_for(&mut self.aabbs, n);
        clear_for(&mut self.small, n);
        self.large.clear();
        for b in 0..n {
            let (aabb, wall) = box_of(b);
            self.aabbs
                .push(OuterBox::around(&aabb.loosened(alert / 2.0)));
            if wall {
                self.large.push(b as u32);
            } else {
                self.small.push(b as u32);
            }
        }
        if let Some(grid) = self.bin_small_bodies() {
            self.small_pairs(&grid, pairs);
            self.large_small_pairs(&grid, pairs);
        }
        for (k, &a) in self.large.iter().enumerate() {
            for &b in &self.large[k + 1..] {
                if self.aabbs[a as usize].intersects(&self.aabbs[b as usize]) {
                    pairs.push((a.min(b), a.max(b)));
                }
            }
        }
    }

    fn bin_small_bodies(&mut self) -> Option<Grid> {
        let first = *self.small.first()?;
        let mut bounds = self.aabbs[first as usize].aabb();
        let mut cell: Real = 0.0;
        for &b in &self.small {
            let bb = self.aabbs[b as usize].aabb();
            bounds = bounds.merged(&bb);
            cell = cell.max(bb.max_extent());
        }
        let extent = bounds.max - bounds.min;
        // Keep the number of cells within a small multiple of the number of bodies.
        let max_cells = (4 * self.small.len()).max(16) as Real;
        if extent.iter().map(|e| (e / cell).ceil()).product::<Real>() > max_cells {
            cell = dim_root(extent.iter().product::<Real>() / max_cells).max(cell);
        }
        let grid = Grid {
            origin: bounds.min,
            cell,
            n: std::array::from_fn(|k| ((extent[k] / cell).ceil() as usize).max(1)),
        };
        let cells = grid.count();
        refill(&mut self.cell_start, std::iter::repeat_n(0, cells + 1));
        clear_for(&mut self.cell_of, self.small.len());
        for &b in &self.small {
            let bb = self.aabbs[b as usize].aabb();
            let c = grid.index(grid.coords(&((bb.min + bb.max) / 2.0))) as u32;
            self.cell_of.push(c);
            self.cell_start[c as usize + 1] += 1;
        }
        for c in 0..cells {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        refill(
            &mut self.cell_bodies,
            std::iter::repeat_n(0, self.small.len()),
        );
        refill(&mut self.fill, self.cell_start.iter().copied());
        for (k, &b) in self.small.iter().enumerate() {
            let c = self.cell_of[k] as usize;
            self.cell_bodies[self.fill[c] as usize] = b;
            self.fill[c] += 1;
        }
        let aabbs = &self.aabbs;
        refill(
            &mut self.cell_boxes,
            self.cell_bodies.iter().map(|&b| aabbs[b as usize]),
        );
        Some(grid)
    }

    fn cell_range(&self, c: usize) -> &[u32] {
        &self.cell_bodies[self.cell_start[c] as usize..self.cell_start[c + 1] as usize]
    }

    /// The bodies of cell `c` and their boxes.
    #[inline(always)]
    fn cell_slices(&self, c: usize) -> (&[u32], &[OuterBox]) {
        let range = self.cell_start[c] as usize..self.cell_start[c + 1] as usize;
        (&self.cell_bodies[range.clone()], &self.cell_boxes[range])
    }

    fn small_pairs(&self, grid: &Grid, pairs: &mut Vec<(u32, u32)>) {
        let stencil = half_stencil();
        let mut push = |a: u32, b: u32| pairs.push((a.min(b), a.max(b)));
        // The cell's coordinates, advanced with it (x fastest).
        let mut at = [0isize; DIM];
        for cell in 0..grid.count() {
            if cell > 0 {
                for (a, &n) in at.iter_mut().zip(&grid.n) {
                    *a += 1;
                    if *a < n as isize {
                        break;
                    }
                    *a = 0;
                }
            }
            let (here, here_boxes) = self.cell_slices(cell);
            for (k, (&a, box_a)) in here.iter().zip(here_boxes).enumerate() {
                for (&b, box_b) in here[k + 1..].iter().zip(&here_boxes[k + 1..]) {
                    if box_a.intersects(box_b) {
                        push(a, b);
                    }
                }
            }
            if here.is_empty() {
                continue;
            }
            for d in &stencil {
                let o: [isize; DIM] = std::array::from_fn(|k| at[k] + d[k]);
                if (0..DIM).any(|k| o[k] < 0 || o[k] >= grid.n[k] as isize) {
                    continue;
                }
                let (other, other_boxes) = self.cell_slices(grid.index(o.map(|x| x as usize)));
                for (&a, box_a) in here.iter().zip(here_boxes) {
                    for (&b, box_b) in other.iter().zip(other_boxes) {
                        if box_a.intersects(box_b) {
                            push(a, b);
                        }
                    }
                }
            }
        }
    }

    fn large_small_pairs(&self, grid: &Grid, pairs: &mut Vec<(u32, u32)>) {
        for &l in &self.large {
            // Small bodies are binned by centre and reach half a cell beyond it.
            let bb = self.aabbs[l as usize].aabb().loosened(grid.cell / 2.0);
            for cell in grid.cells_between(grid.coords(&bb.min), grid.coords(&bb.max)) {
                for &b in self.cell_range(cell) {
                    if self.aabbs[l as usize].intersects(&self.aabbs[b as usize]) {
                        pairs.push((l.min(b), l.max(b)));
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stencil is half of the neighbourhood: no offset and its opposite both, none zero.
    #[test]
    fn half_stencil_covers_each_neighbour_pair_once() {
        let s = half_stencil();
        assert_eq!(s.len(), (3usize.pow(DIM as u32) - 1) / 2);
        for d in &s {
            assert!(d.iter().any(|&x| x != 0));
            assert!(!s.contains(&d.map(|x| -x)));
        }
        if DIM == 2 {
            let order: Vec<Vec<isize>> = s.iter().map(|d| d.to_vec()).collect();
            assert_eq!(order, [[1, 0], [-1, 1], [0, 1], [1, 1]].map(|d| d.to_vec()));
        }
    }
}

/// The 3D grid against an all-pairs search, on random spheres and polyhedra of mixed sizes
/// with planar walls, a dense cluster among sparse bodies (the cell-size cap) and bodies
/// outside the walls.
#[cfg(all(test, feature = "dim3"))]
mod tests_3d {
    use super::*;
    use xper_bodies::Body;
    use xper_math::{Rotation, SplitMix64};

    fn brute_force(set: &BodySet, alert: Real) -> Vec<(u32, u32)> {
        let boxes: Vec<OuterBox> = (0..set.len())
            .map(|b| {
                let aabb = set.shape[b].aabb(&set.position[b], set.rotation[b]);
                OuterBox::around(&aabb.loosened(alert / 2.0))
            })
            .collect();
        let mut pairs = Vec::new();
        for i in 0..set.len() {
            for j in i + 1..set.len() {
                if boxes[i].intersects(&boxes[j]) {
                    pairs.push((i as u32, j as u32));
                }
            }
        }
        pairs
    }

    #[test]
    fn grid_pairs_equal_brute_force_pairs_in_3d() {
        let mut rng = SplitMix64::new(41);
        for case in 0..12 {
            let mut set = BodySet::new();
            let n = 50 + 150 * case;
            let spread = if case % 3 == 0 { 0.5 } else { 10.0 };
            for k in 0..n {
                let p = Vector::new(
                    spread * rng.next_f64(),
                    spread * rng.next_f64(),
                    10.0 * rng.next_f64(),
                );
                let r = 0.05 + 0.4 * rng.next_f64();
                let body = if k % 5 == 0 {
                    let points: Vec<Vector> = (0..8)
                        .map(|_| {
                            p + Vector::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * r
                        })
                        .collect();
                    let q = Rotation::from_scaled_axis(Vector::new(1.0, 2.0, 0.5) * k as Real);
                    Body::polyhedron(&points, 1000.0).unwrap().with_rotation(q)
                } else {
                    Body::sphere(r, 1000.0, p)
                };
                set.insert(body);
            }
            set.insert(Body::plane(Vector::zeros(), Vector::z(), [20.0, 20.0]));
            set.insert(Body::plane(
                Vector::new(0.0, 5.0, 5.0),
                -Vector::y(),
                [3.0, 1.0],
            ));
            let alert = 0.1 * rng.next_f64();
            let mut pairs = Vec::new();
            BroadPhase::new().find_pairs(&set, alert, &mut pairs);
            pairs.sort_unstable();
            let before = pairs.len();
            pairs.dedup();
            assert_eq!(before, pairs.len(), "case {case}: a pair reported twice");
            let brute = brute_force(&set, alert);
            assert!(brute.len() > n / 10, "case {case}: {} pairs", brute.len());
            assert_eq!(pairs, brute, "case {case}");
        }
    }
}
