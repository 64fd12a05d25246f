//! Recursive coordinate bisection (Berger and Bokhari, IEEE Trans. Comput. 36 (1987) 570):
//! the set of points is cut across its longest extent so that the two halves hold numbers of
//! points proportional to the numbers of parts they receive, and each half is cut again. The
//! cuts are kept, so any point (a body that moved, a fluid cell) finds its part in
//! O(log parts).

mod distributed;
pub use distributed::{across_gravity, ACROSS_GRAVITY};

use xper_math::{Real, Vector, DIM};

/// A node of the bisection tree.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Node {
    /// Points with `x[axis] < cut` go to `below`, the others to `above`.
    Cut {
        axis: usize,
        cut: Real,
        below: Box<Node>,
        above: Box<Node>,
    },
    Part(u32),
}

/// A partition of the plane into `parts` regions by recursive coordinate bisection.
#[derive(Clone, Debug, PartialEq)]
pub struct Bisection {
    root: Node,
    parts: usize,
}

impl Bisection {
    /// Cuts `points` into `parts` groups of sizes differing by at most one (ties on a cut
    /// coordinate are broken by index, so the result depends only on the input).
    ///
    /// # Panics
    /// If `parts` is 0.
    pub fn new(points: &[Vector], parts: usize) -> Self {
        assert!(parts > 0, "a partition needs at least one part");
        let mut order: Vec<u32> = (0..points.len() as u32).collect();
        let root = build(points, &mut order, 0, parts);
        Bisection { root, parts }
    }

    pub(crate) fn from_root(root: Node, parts: usize) -> Self {
        Bisection { root, parts }
    }

    /// Number of parts.
    pub fn parts(&self) -> usize {
        self.parts
    }

    /// The part of a point.
    pub fn part_of(&self, x: &Vector) -> u32 {
        let mut node = &self.root;
        loop {
            match node {
                Node::Part(p) => return *p,
                Node::Cut {
                    axis,
                    cut,
                    below,
                    above,
                } => node = if x[*axis] < *cut { below } else { above },
            }
        }
    }

    /// The part of each point.
    pub fn assign(&self, points: &[Vector]) -> Vec<u32> {
        points.iter().map(|x| self.part_of(x)).collect()
    }

    /// The parts whose regions come within `distance` of `x` (in the max norm, so a superset
    /// of those within Euclidean `distance`), in increasing order, `x`'s own part included.
    pub fn parts_near(&self, x: &Vector, distance: Real, parts: &mut Vec<u32>) {
        parts.clear();
        collect_parts_near(&self.root, x, distance, parts);
        parts.sort_unstable();
    }

    /// Each part's region as a box `[lo, hi)` (unbounded sides at `+-infinity`), by part.
    pub fn regions(&self) -> Vec<(Vector, Vector)> {
        let everywhere = (
            Vector::repeat(Real::NEG_INFINITY),
            Vector::repeat(Real::INFINITY),
        );
        let mut regions = vec![everywhere; self.parts];
        let mut stack = vec![(&self.root, everywhere)];
        while let Some((node, (lo, hi))) = stack.pop() {
            match node {
                Node::Part(p) => regions[*p as usize] = (lo, hi),
                Node::Cut {
                    axis,
                    cut,
                    below,
                    above,
                } => {
                    let (mut below_hi, mut above_lo) = (hi, lo);
                    below_hi[*axis] = *cut;
                    above_lo[*axis] = *cut;
                    stack.push((below, (lo, below_hi)));
                    stack.push((above, (above_lo, hi)));
                }
            }
        }
        regions
    }

    /// The other parts whose regions come within `distance` of `part`'s, in increasing order:
    /// every part [`Bisection::parts_near`] can return for a point of `part`'s region. The
    /// relation is symmetric, so two processes agree on being neighbours.
    pub fn neighbours(&self, part: u32, distance: Real) -> Vec<u32> {
        let regions = self.regions();
        let (lo, hi) = regions[part as usize];
        (0..self.parts as u32)
            .filter(|&q| q != part)
            .filter(|&q| {
                let (lo_q, hi_q) = regions[q as usize];
                (0..DIM).all(|a| lo[a] - distance < hi_q[a] && lo_q[a] < hi[a] + distance)
            })
            .collect()
    }
}

fn build(points: &[Vector], ids: &mut [u32], first_part: u32, parts: usize) -> Node {
    if parts == 1 || ids.is_empty() {
        return Node::Part(first_part);
    }
    let (mut lo, mut hi) = (
        Vector::repeat(Real::INFINITY),
        Vector::repeat(Real::NEG_INFINITY),
    );
    for &i in ids.iter() {
        lo = lo.inf(&points[i as usize]);
        hi = hi.sup(&points[i as usize]);
    }
    let extent = hi - lo;
    let axis = (0..DIM)
        .max_by(|&a, &b| extent[a].total_cmp(&extent[b]).then(b.cmp(&a)))
        .unwrap_or(0);
    let below_parts = parts / 2;
    let target = ids.len() * below_parts / parts;
    let coordinate = |i: u32| points[i as usize][axis];
    ids.sort_unstable_by(|&a, &b| coordinate(a).total_cmp(&coordinate(b)).then(a.cmp(&b)));
    // Cut between two distinct coordinates, at the boundary of the group of equal coordinates
    // nearest the target count, so that `part_of` puts every point back where it was counted.
    let c = coordinate(ids[target.min(ids.len() - 1)]);
    let first_equal = ids.partition_point(|&i| coordinate(i) < c);
    let after_equal = ids.partition_point(|&i| coordinate(i) <= c);
    let split = if (first_equal > 0 && target - first_equal <= after_equal - target)
        || after_equal == ids.len()
    {
        first_equal
    } else {
        after_equal
    };
    if split == 0 || split == ids.len() {
        return Node::Part(first_part);
    }
    let (below_ids, above_ids) = ids.split_at_mut(split);
    let cut = 0.5 * (coordinate(below_ids[split - 1]) + coordinate(above_ids[0]));
    Node::Cut {
        axis,
        cut,
        below: Box::new(build(points, below_ids, first_part, below_parts)),
        above: Box::new(build(
            points,
            above_ids,
            first_part + below_parts as u32,
            parts - below_parts,
        )),
    }
}

/// Whether `x` lies in the box `[lo, hi)` shrunk by `margin` on every side. For a part's
/// region ([`Bisection::regions`]) this is a shortcut of the tree: then the part is `x`'s
/// ([`Bisection::part_of`]), and with `margin >= distance` it is the only one near
/// ([`Bisection::parts_near`]), since the regions tile space.
pub(crate) fn in_box(x: &Vector, (lo, hi): &(Vector, Vector), margin: Real) -> bool {
    (0..x.len()).all(|d| x[d] - margin >= lo[d] && x[d] + margin < hi[d])
}

/// Appends the parts under `node` whose regions come within `distance` of `x` (max norm);
/// recursive, so that the 50,000 calls of a step allocate nothing.
fn collect_parts_near(node: &Node, x: &Vector, distance: Real, parts: &mut Vec<u32>) {
    match node {
        Node::Part(p) => parts.push(*p),
        Node::Cut {
            axis,
            cut,
            below,
            above,
        } => {
            if x[*axis] - distance < *cut {
                collect_parts_near(below, x, distance, parts);
            }
            if x[*axis] + distance >= *cut {
                collect_parts_near(above, x, distance, parts);
            }
        }
    }
}

// Tests of the 2D build (their scenes are planar).
#[cfg(all(test, feature = "dim2"))]
mod tests {
    use super::*;

    #[test]
    fn parts_near_finds_every_part_within_the_distance() {
        let points = lattice(20, 0.3);
        let bisection = Bisection::new(&points, 5);
        let mut near = Vec::new();
        for x in points.iter().step_by(7) {
            bisection.parts_near(x, 1.5, &mut near);
            // Brute force: the parts of the lattice points within 1.5 in the max norm.
            for y in &points {
                if (y - x).amax() <= 1.5 {
                    assert!(near.contains(&bisection.part_of(y)), "{x:?} {y:?}");
                }
            }
            assert!(near.contains(&bisection.part_of(x)));
        }
    }

    /// Brute force on a lattice: every part met within the distance of a point is among the
    /// neighbours of the point's part, and the relation is symmetric.
    #[test]
    fn neighbours_hold_every_part_near_a_point_of_the_region() {
        let points = lattice(24, 0.3);
        for parts in [2, 5, 9, 16] {
            let bisection = Bisection::new(&points, parts);
            let all: Vec<Vec<u32>> = (0..parts as u32)
                .map(|p| bisection.neighbours(p, 1.2))
                .collect();
            let mut near = Vec::new();
            for x in &points {
                let p = bisection.part_of(x);
                bisection.parts_near(x, 1.2, &mut near);
                for q in near.iter().filter(|&&q| q != p) {
                    assert!(
                        all[p as usize].contains(q),
                        "{parts} parts: {q} near {x:?} in {p}"
                    );
                }
            }
            for (p, list) in all.iter().enumerate() {
                for &q in list {
                    assert!(
                        all[q as usize].contains(&(p as u32)),
                        "{p} -> {q} not symmetric"
                    );
                }
            }
            if parts == 16 {
                assert!(
                    all.iter().all(|list| list.len() < 15),
                    "every part a neighbour"
                );
            }
        }
    }

    /// The box shortcut must agree with the tree wherever it answers, cut points included
    /// (the lattice points with no jitter lie exactly on cuts).
    #[test]
    fn a_point_inside_its_shrunk_region_has_only_its_own_part_near() {
        for jitter in [0.0, 0.3] {
            let points = lattice(24, jitter);
            for parts in [2, 5, 9] {
                let bisection = Bisection::new(&points, parts);
                let regions = bisection.regions();
                let mut near = Vec::new();
                let (mut inside, mut shrunk) = (0, 0);
                for x in points.iter().chain(&lattice(31, 0.17)) {
                    for (p, region) in regions.iter().enumerate() {
                        if in_box(x, region, 0.0) {
                            assert_eq!(bisection.part_of(x), p as u32, "{x:?}");
                            inside += 1;
                        }
                        if in_box(x, region, 1.2) {
                            bisection.parts_near(x, 1.2, &mut near);
                            assert_eq!(near, [p as u32], "{x:?}");
                            shrunk += 1;
                        }
                    }
                }
                assert_eq!(
                    inside,
                    points.len() + 31 * 31,
                    "every point is in one region"
                );
                assert!(
                    shrunk > 0 && shrunk < inside,
                    "{parts} parts: {shrunk} of {inside}"
                );
            }
        }
    }

    fn lattice(n: usize, jitter: Real) -> Vec<Vector> {
        (0..n * n)
            .map(|k| {
                let wobble = jitter * (((k * 7919) % 101) as Real / 101.0 - 0.5);
                Vector::new((k % n) as Real * 1.3 + wobble, (k / n) as Real - wobble)
            })
            .collect()
    }

    #[test]
    fn parts_are_balanced_and_found_again_from_the_cuts() {
        let points = lattice(37, 0.3);
        for parts in [1, 2, 3, 4, 7, 16] {
            let b = Bisection::new(&points, parts);
            let owner = b.assign(&points);
            let mut count = vec![0usize; parts];
            for &p in &owner {
                count[p as usize] += 1;
            }
            let (min, max) = (count.iter().min().unwrap(), count.iter().max().unwrap());
            assert!(max - min <= 2, "parts {parts}: sizes {count:?}");
            assert!(*min > 0, "parts {parts}: an empty part");
        }
    }

    #[test]
    fn two_parts_cut_the_longest_side_in_half() {
        let points = lattice(10, 0.0);
        let b = Bisection::new(&points, 2);
        for x in &points {
            let expected = if x.x < 4.5 * 1.3 { 0 } else { 1 };
            assert_eq!(b.part_of(x), expected, "{x:?}");
        }
    }
}
