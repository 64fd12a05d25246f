//! Broad phase: a uniform cell grid, O(N) per step.
//!
//! Bodies that fit in a cell ("small": every disk and polygon; the cell edge is the largest of
//! their bounding-box extents plus the alert distance) are binned by centre with a counting
//! sort and tested against their own cell and four neighbour cells (half of the 3x3
//! neighbourhood, so each pair is met once). Walls ("large") are tested against the small
//! bodies in the cells their bounding box covers, and against each other by brute force.
//!
//! The boxes are kept in single precision, rounded outwards ([`OuterBox`]): half the bytes
//! to hold and read, and every pair the double-precision boxes would find is still found.

use xper_bodies::{BodySet, Shape};
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
    nx: usize,
    ny: usize,
}

impl Grid {
    #[inline(always)]
    fn coords(&self, p: &Vector) -> (usize, usize) {
        let cx = ((p.x - self.origin.x) / self.cell)
            .floor()
            .clamp(0.0, (self.nx - 1) as Real) as usize;
        let cy = ((p.y - self.origin.y) / self.cell)
            .floor()
            .clamp(0.0, (self.ny - 1) as Real) as usize;
        (cx, cy)
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
        let n = bodies.len();
        clear_for(&mut self.aabbs, n);
        clear_for(&mut self.small, n);
        self.large.clear();
        for b in 0..n {
            let aabb = bodies.shape[b]
                .aabb(&bodies.position[b], bodies.rotation[b])
                .loosened(alert / 2.0);
            self.aabbs.push(OuterBox::around(&aabb));
            if matches!(bodies.shape[b], Shape::Segment { .. }) {
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
        if (extent.x / cell).ceil() * (extent.y / cell).ceil() > max_cells {
            cell = (extent.x * extent.y / max_cells).sqrt().max(cell);
        }
        let nx = ((extent.x / cell).ceil() as usize).max(1);
        let ny = ((extent.y / cell).ceil() as usize).max(1);
        let grid = Grid {
            origin: bounds.min,
            cell,
            nx,
            ny,
        };
        refill(&mut self.cell_start, std::iter::repeat_n(0, nx * ny + 1));
        clear_for(&mut self.cell_of, self.small.len());
        for &b in &self.small {
            let bb = self.aabbs[b as usize].aabb();
            let (cx, cy) = grid.coords(&((bb.min + bb.max) / 2.0));
            let c = (cy * nx + cx) as u32;
            self.cell_of.push(c);
            self.cell_start[c as usize + 1] += 1;
        }
        for c in 0..nx * ny {
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
        let (nx, ny) = (grid.nx as isize, grid.ny as isize);
        let mut push = |a: u32, b: u32| pairs.push((a.min(b), a.max(b)));
        for cy in 0..ny {
            for cx in 0..nx {
                let (here, here_boxes) = self.cell_slices((cy * nx + cx) as usize);
                for (k, (&a, box_a)) in here.iter().zip(here_boxes).enumerate() {
                    for (&b, box_b) in here[k + 1..].iter().zip(&here_boxes[k + 1..]) {
                        if box_a.intersects(box_b) {
                            push(a, b);
                        }
                    }
                }
                for (dx, dy) in [(1, 0), (-1, 1), (0, 1), (1, 1)] {
                    let (ox, oy) = (cx + dx, cy + dy);
                    if ox < 0 || ox >= nx || oy >= ny {
                        continue;
                    }
                    let (other, other_boxes) = self.cell_slices((oy * nx + ox) as usize);
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
    }

    fn large_small_pairs(&self, grid: &Grid, pairs: &mut Vec<(u32, u32)>) {
        for &l in &self.large {
            // Small bodies are binned by centre and reach half a cell beyond it.
            let bb = self.aabbs[l as usize].aabb().loosened(grid.cell / 2.0);
            let (x0, y0) = grid.coords(&bb.min);
            let (x1, y1) = grid.coords(&bb.max);
            for cy in y0..=y1 {
                for cx in x0..=x1 {
                    for &b in self.cell_range(cy * grid.nx + cx) {
                        if self.aabbs[l as usize].intersects(&self.aabbs[b as usize]) {
                            pairs.push((l.min(b), l.max(b)));
                        }
                    }
                }
            }
        }
    }
}
