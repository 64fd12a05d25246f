//! Recursive coordinate bisection of points spread over processes, without gathering them:
//! for points with distinct coordinates, the cuts of [`Bisection::new`] (longest extent,
//! counts in the ratio of the parts, halfway between neighbours), found by reductions only
//! (Berger and Bokhari, IEEE Trans. Comput. 36 (1987) 570; the cut located by bisection on
//! counts, as in Zoltan's parallel RCB, Devine et al., Comput. Sci. Eng. 4 (2002) 90). The
//! tree is built level by level: per level, one reduction of the nodes' counts and boxes, a
//! few tens of reductions of the counts below trial cuts, and one of the points nearest the
//! cuts, all nodes of the level together. A re-partition thus costs `O(log P)` rounds of small
//! collectives instead of gathering every state on every process.
//!
//! The axis of a cut is that of the longest extent, each extent multiplied by `stretch`
//! (all ones: plain RCB); see [`across_gravity`] for why a run stretches them.
//!
//! Points may carry weights (the work they stand for, Zoltan's object weights): the halves
//! then hold weights, rather than counts, in the ratio of their parts. A point of integer
//! weight `w` is cut as `w` points at the same place would be, and integer weights sum
//! exactly in any order, so the cuts do not depend on how the points are spread.

use crate::comm::Communicator;
use crate::partition::{Bisection, Node};
use std::collections::HashMap;
use xper_math::{Real, Vector, DIM};

/// A node of the level being cut: its parts and the indices of this process's points in it.
struct Pending {
    first_part: u32,
    parts: usize,
    members: Vec<u32>,
}

/// How a node was cut (or left whole), keyed by `(first_part, parts)`.
#[derive(Clone, Copy)]
enum Decision {
    Cut { axis: usize, cut: Real },
    Whole,
}

impl Bisection {
    /// Cuts the points held by all processes of `comm` (`points` are this process's, with
    /// `weights`, or unit weights when it is empty) into `parts` regions of nearly equal
    /// weights, each cut across the longest extent once multiplied by `stretch`; collective,
    /// every process gets the same tree. Ties on a cut coordinate are not split, so weights
    /// can differ by more than the largest one where points share a coordinate.
    pub fn distributed<C: Communicator + ?Sized>(
        comm: &C,
        points: &[Vector],
        weights: &[Real],
        stretch: &Vector,
        parts: usize,
    ) -> Self {
        assert!(parts > 0, "a partition needs at least one part");
        assert!(
            weights.is_empty() || weights.len() == points.len(),
            "one weight per point"
        );
        let weight = |i: u32| weights.get(i as usize).copied().unwrap_or(1.0);
        let mut decisions: HashMap<(u32, usize), Decision> = HashMap::new();
        let mut level = vec![Pending {
            first_part: 0,
            parts,
            members: (0..points.len() as u32).collect(),
        }];
        while !level.is_empty() {
            let cuts = cut_level(comm, points, &weight, stretch, &level);
            let mut next = Vec::new();
            for (node, decision) in level.into_iter().zip(cuts) {
                decisions.insert((node.first_part, node.parts), decision);
                if let Decision::Cut { axis, cut } = decision {
                    let below_parts = node.parts / 2;
                    let (below, above): (Vec<u32>, Vec<u32>) =
                        (node.members.iter()).partition(|&&i| points[i as usize][axis] < cut);
                    for (first_part, parts, members) in [
                        (node.first_part, below_parts, below),
                        (
                            node.first_part + below_parts as u32,
                            node.parts - below_parts,
                            above,
                        ),
                    ] {
                        if parts > 1 {
                            next.push(Pending {
                                first_part,
                                parts,
                                members,
                            });
                        } else {
                            decisions.insert((first_part, parts), Decision::Whole);
                        }
                    }
                }
            }
            level = next;
        }
        Bisection::from_root(assemble(&decisions, 0, parts), parts)
    }
}

/// The decision for every node of a level, the same on every process.
fn cut_level<C: Communicator + ?Sized>(
    comm: &C,
    points: &[Vector],
    weight: &impl Fn(u32) -> Real,
    stretch: &Vector,
    level: &[Pending],
) -> Vec<Decision> {
    // Weights and boxes: sums of weights, maxima of (x, -x) per axis.
    let mut counts: Vec<f64> = (level.iter())
        .map(|n| n.members.iter().map(|&i| weight(i)).sum())
        .collect();
    let mut extremes = vec![Real::NEG_INFINITY; level.len() * 2 * DIM];
    for (node, e) in level.iter().zip(extremes.chunks_exact_mut(2 * DIM)) {
        for &i in &node.members {
            let x = points[i as usize];
            for a in 0..DIM {
                e[a] = e[a].max(x[a]);
                e[DIM + a] = e[DIM + a].max(-x[a]);
            }
        }
    }
    comm.all_reduce_sum(&mut counts);
    comm.all_reduce_max(&mut extremes);
    // Per node: the axis of longest extent and the search interval, or whole.
    let mut searches: Vec<Option<(usize, Real, Real, f64)>> = Vec::with_capacity(level.len());
    for (k, node) in level.iter().enumerate() {
        let e = &extremes[k * 2 * DIM..(k + 1) * 2 * DIM];
        let (lo, hi) = (
            Vector::from_fn(|a, _| -e[DIM + a]),
            Vector::from_fn(|a, _| e[a]),
        );
        let extent = hi - lo;
        let stretched = extent.component_mul(stretch);
        let axis = (0..DIM)
            .max_by(|&a, &b| stretched[a].total_cmp(&stretched[b]).then(b.cmp(&a)))
            .unwrap_or(0);
        let total = counts[k];
        let target = (total * (node.parts / 2) as f64 / node.parts as f64).floor();
        let splittable = total >= 2.0 && target >= 1.0 && extent[axis] > 0.0;
        searches.push(splittable.then_some((axis, lo[axis], hi[axis], target)));
    }
    // Bisection on the cut: `below(lo) < target <= below(hi)`, `below(x)` the weight of the
    // points under `x`; every process halves the same intervals, so all stop together.
    loop {
        let trials: Vec<Option<Real>> = (searches.iter())
            .map(|s| {
                s.and_then(|(_, lo, hi, _)| Some(0.5 * (lo + hi)).filter(|&m| m > lo && m < hi))
            })
            .collect();
        if trials.iter().all(Option::is_none) {
            break;
        }
        let mut below: Vec<f64> = vec![0.0; level.len()];
        for (k, node) in level.iter().enumerate() {
            if let (Some(m), Some((axis, ..))) = (trials[k], searches[k]) {
                below[k] = (node.members.iter())
                    .filter(|&&i| points[i as usize][axis] < m)
                    .map(|&i| weight(i))
                    .sum();
            }
        }
        comm.all_reduce_sum(&mut below);
        for (k, search) in searches.iter_mut().enumerate() {
            if let (Some(m), Some((_, lo, hi, target))) = (trials[k], search.as_mut()) {
                if below[k] < *target {
                    *lo = m;
                } else {
                    *hi = m;
                }
            }
        }
    }
    // `hi` leaves at least `target` points below it and the largest coordinate above it; the
    // cut goes halfway between the nearest points on either side, as the serial bisection's
    // does (the same cut when coordinates are distinct).
    let mut nearest = vec![Real::NEG_INFINITY; 2 * level.len()];
    for (k, node) in level.iter().enumerate() {
        if let Some((axis, _, hi, _)) = searches[k] {
            for &i in &node.members {
                let x = points[i as usize][axis];
                let slot = if x < hi { 2 * k } else { 2 * k + 1 };
                let value = if x < hi { x } else { -x };
                nearest[slot] = nearest[slot].max(value);
            }
        }
    }
    comm.all_reduce_max(&mut nearest);
    (searches.into_iter().enumerate())
        .map(|(k, s)| match s {
            Some((axis, ..)) => Decision::Cut {
                axis,
                cut: 0.5 * (nearest[2 * k] - nearest[2 * k + 1]),
            },
            None => Decision::Whole,
        })
        .collect()
}

/// Extents across gravity count for this fraction in the choice of a cut's axis
/// ([`across_gravity`]).
pub const ACROSS_GRAVITY: Real = 0.25;

/// The stretch of the extents for a world under `gravity`: `1 - (1 - ACROSS_GRAVITY) g_a^2 /
/// |g|^2` along axis `a` (all ones without gravity). A cut across gravity makes a bad
/// interface for a granular deposit: the contacts gather at the bottom, so the lower region
/// holds the work while the upper one waits, and the weight of everything above crosses the
/// interface, whose coupling (one exchange per sweep) then needs more sweeps. A cut along
/// gravity splits the deposit as it grows. Measured on box3d100k's first 300 steps (2
/// processes, bench-results/NOTES.md): cut across z, the longest extent, efficiency 0.51; cut
/// along x, 0.82. A domain more than `1 / ACROSS_GRAVITY` times taller than wide is still cut
/// across gravity, so that a tall column is not cut into thin slabs.
pub fn across_gravity(gravity: &Vector) -> Vector {
    let g2 = gravity.norm_squared();
    if g2 > 0.0 && g2.is_finite() {
        gravity.map(|g| 1.0 - (1.0 - ACROSS_GRAVITY) * g * g / g2)
    } else {
        Vector::repeat(1.0)
    }
}

/// The tree of the node `(first_part, parts)` from the decisions.
fn assemble(decisions: &HashMap<(u32, usize), Decision>, first_part: u32, parts: usize) -> Node {
    match decisions.get(&(first_part, parts)) {
        Some(Decision::Cut { axis, cut }) => {
            let below_parts = parts / 2;
            Node::Cut {
                axis: *axis,
                cut: *cut,
                below: Box::new(assemble(decisions, first_part, below_parts)),
                above: Box::new(assemble(
                    decisions,
                    first_part + below_parts as u32,
                    parts - below_parts,
                )),
            }
        }
        _ => Node::Part(first_part),
    }
}

// Tests of the 2D build (their scenes are planar).
#[cfg(all(test, feature = "dim2"))]
mod tests {
    use super::*;
    use crate::run_on_threads;

    /// Points with distinct coordinates dealt round-robin to the processes: every process
    /// builds the tree of the serial bisection of all the points, whose parts' sizes are
    /// within one of each other.
    #[test]
    fn every_process_gets_the_same_balanced_cuts_without_gathering_the_points() {
        let points: Vec<Vector> = (0..900)
            .map(|k| {
                let wobble = ((k * 7919) % 1009) as Real / 1009.0;
                Vector::new(
                    (k % 30) as Real * 1.7 + 0.01 * wobble,
                    (k / 30) as Real + wobble,
                )
            })
            .collect();
        for ranks in [1, 2, 3] {
            for parts in [1, 2, 5, 8] {
                let trees = run_on_threads(ranks, |comm| {
                    let mine: Vec<Vector> = (points.iter().skip(comm.rank()).step_by(ranks))
                        .copied()
                        .collect();
                    Bisection::distributed(comm, &mine, &[], &Vector::repeat(1.0), parts)
                });
                assert!(
                    trees.iter().all(|t| *t == trees[0]),
                    "{ranks} ranks disagree"
                );
                assert_eq!(
                    trees[0],
                    Bisection::new(&points, parts),
                    "not the serial cuts"
                );
                let mut count = vec![0usize; parts];
                for p in trees[0].assign(&points) {
                    count[p as usize] += 1;
                }
                let (min, max) = (count.iter().min().unwrap(), count.iter().max().unwrap());
                assert!(max - min <= 1, "{ranks} ranks, {parts} parts: {count:?}");
            }
        }
    }

    /// Integer weights: a point of weight `w` is cut as `w` unweighted copies of it would be,
    /// whatever the spread over ranks, and the parts' weights differ by at most two heavy
    /// points (ties are not split).
    #[test]
    fn a_weight_counts_as_that_many_points_at_the_same_place() {
        let points: Vec<Vector> = (0..400)
            .map(|k| {
                let wobble = ((k * 7919) % 1009) as Real / 1009.0;
                Vector::new((k % 20) as Real + 0.01 * wobble, (k / 20) as Real + wobble)
            })
            .collect();
        // Heavy points at the bottom, as contacts gather under a settling packing.
        let weights: Vec<Real> = (points.iter())
            .map(|p| if p.y < 5.0 { 11.0 } else { 1.0 })
            .collect();
        let copies: Vec<Vector> = (points.iter().zip(&weights))
            .flat_map(|(p, &w)| std::iter::repeat_n(*p, w as usize))
            .collect();
        for ranks in [1, 2, 3] {
            for parts in [2, 3, 4] {
                let trees = run_on_threads(ranks, |comm| {
                    let k = comm.rank();
                    let mine: Vec<Vector> = points.iter().skip(k).step_by(ranks).copied().collect();
                    let w: Vec<Real> = weights.iter().skip(k).step_by(ranks).copied().collect();
                    Bisection::distributed(comm, &mine, &w, &Vector::repeat(1.0), parts)
                });
                assert!(
                    trees.iter().all(|t| *t == trees[0]),
                    "{ranks} ranks disagree"
                );
                let copied = run_on_threads(1, |comm| {
                    Bisection::distributed(comm, &copies, &[], &Vector::repeat(1.0), parts)
                });
                assert_eq!(trees[0], copied[0], "not the copies' cuts");
                let mut load = vec![0.0; parts];
                for (p, w) in trees[0].assign(&points).into_iter().zip(&weights) {
                    load[p as usize] += w;
                }
                let (min, max) = load
                    .iter()
                    .fold((Real::MAX, 0.0f64), |(a, b), &l| (a.min(l), b.max(l)));
                // Unweighted, the bottom quarter's 100 points would weigh 1100 of 1400.
                assert!(
                    max - min <= 2.0 * 11.0,
                    "{ranks} ranks, {parts} parts: {load:?}"
                );
            }
        }
    }

    /// Under gravity along -y, a box 1.5 times taller than wide is cut along gravity (across
    /// x), a column 5 times taller still across it; without gravity, across the longest side.
    #[test]
    fn cuts_follow_gravity_unless_the_domain_is_a_tall_column() {
        let grid = |height: Real| -> Vec<Vector> {
            (0..600)
                .map(|k| Vector::new((k % 20) as Real / 20.0, (k / 20) as Real / 30.0 * height))
                .collect()
        };
        let axis_of = |points: &[Vector], gravity: Vector| {
            let tree = run_on_threads(1, |comm| {
                Bisection::distributed(comm, points, &[], &across_gravity(&gravity), 2)
            });
            match tree[0].root {
                Node::Cut { axis, .. } => axis,
                Node::Part(_) => panic!("not cut"),
            }
        };
        let down = Vector::new(0.0, -9.81);
        assert_eq!(axis_of(&grid(1.5), Vector::zeros()), 1);
        assert_eq!(axis_of(&grid(1.5), down), 0);
        assert_eq!(axis_of(&grid(5.0), down), 1);
    }
}
