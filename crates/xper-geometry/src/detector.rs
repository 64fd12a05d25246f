//! The detector: candidate pairs kept across steps (a Verlet list), narrow phase, carry-over
//! of impulses.
//!
//! The broad phase runs with the alert distance grown by a skin `s`, and its pairs are kept as
//! candidates until the bodies have moved enough to invalidate them (L. Verlet, "Computer
//! 'experiments' on classical fluids", Phys. Rev. 159:98, 1967, for molecular dynamics): a
//! point of body `b` has moved by at most `d_b = |x_b - x_b0| + reach_b theta_b` since the
//! build (`reach_b` the largest distance from the body's position to its shape, 0 for a disk
//! or a sphere; `theta_b` the angle of the rotation from the built orientation to the
//! current one: in 2D `|theta - theta_0|` modulo 2 pi, in 3D the angle of `q_0^-1 q`; see the
//! `pose2d.rs`/`pose3d.rs` files), so its box lies in
//! its box at the build grown by `d_b`, and every pair within the alert distance is still a
//! candidate while the two largest `d_b` sum to at most `s`.
//!
//! The candidates are kept in ascending `(first body, second body)` order (compressed: the
//! second bodies in one array, where each first body's start; 4 bytes per pair and per
//! body instead of 8 per pair), and the narrow
//! phase finds exactly the contacts within the alert distance, so the contacts, their order
//! and hence the whole run do not depend on the skin or on when the list was built: a run
//! resumed from a checkpoint (which starts a new list) matches an uninterrupted one.
//!
//! The skin adapts to the motion: at each build it is set so that, at the rate the bodies
//! moved since the previous build, the list lasts [`TARGET_STEPS_PER_BUILD`] calls, within
//! `[alert, SKIN_CAP_OVER_SIZE * largest box extent]`.

use crate::broad::BroadPhase;
use crate::carry::CarryOver;
use crate::contacts::{Contact, ContactKey, ContactSet};
use crate::narrow::{collide, Manifold};
use crate::periodic::{relabel, Image, Periodic};
use crate::pose::{self, Orientation};
use crate::ContactRow;
use xper_bodies::BodySet;
use xper_math::buffer::refill;
use xper_math::{Aabb, Real, Tensor, DIM};

/// Calls a candidate list should last, at the rate the bodies moved during the previous one.
/// On box10k, 8 rather than 4 builds the list 328 times instead of 406 in 1500 steps and
/// lowers the mean detection time by about 8 ns per body (two runs each, 2026-11-22); the
/// larger skin costs the steps that keep the list no measurable time.
pub const TARGET_STEPS_PER_BUILD: Real = 8.0;

/// Largest skin, as a fraction of the largest bounding-box extent of a body that is not a
/// wall: beyond it, the candidates would reach past the nearest neighbours.
pub const SKIN_CAP_OVER_SIZE: Real = 0.25;

/// A fingerprint of the bodies' ids in order: a list is kept only for the bodies, in the
/// order, it was built for. It is the wrapping sum over the bodies of a multiplicative mix of
/// each `(index, id)` pair, so no term waits for the one before (a chained hash is one
/// multiplication's latency per body, 1.3 ns per body on box1m's detection); two different
/// id sequences share a fingerprint with a probability of about 2^-64.
fn ids_fingerprint(ids: &[u64]) -> u64 {
    const ODD: u64 = 0x9E37_79B9_7F4A_7C15;
    (ids.iter().zip(0u64..)).fold(ids.len() as u64, |sum, (&id, b)| {
        let z = (id ^ b.wrapping_mul(ODD)).wrapping_mul(ODD);
        sum.wrapping_add(z ^ z >> 29)
    })
}

/// Counters of a detector's work, for benchmarks.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DetectorStats {
    /// Calls of [`Detector::detect`].
    pub calls: u64,
    /// Candidate lists built (broad phase runs).
    pub builds: u64,
    /// Candidate pairs of the current list.
    pub candidates: usize,
    /// Current skin (m).
    pub skin: Real,
}

/// Detection with its reusable buffers: candidate pairs, narrow phase, carry-over of impulses.
///
/// Between calls it holds the candidate pairs and the poses they were built at; during a list
/// build, also the broad phase's arrays. The new contacts are written over the previous ones,
/// whose impulses they take, in the contact set's own buffers (see `carry.rs`).
#[derive(Clone, Debug, Default)]
pub struct Detector {
    /// Where each first body's candidates start in `seconds` (one entry per body and one past
    /// the end).
    first_start: Vec<u32>,
    /// The second body of each candidate pair, ascending within each first body's.
    seconds: Vec<u32>,
    /// In a periodic cell, the image of the second body of each candidate pair at the build
    /// (parallel to `seconds`); empty otherwise.
    images: Vec<Image>,
    /// In a periodic cell, each body's wrap count at the build (see [`Periodic::wraps`]).
    built_wraps: Vec<Image>,
    /// In a periodic cell, its edges and relabel count at the build.
    built_lattice: Option<(Tensor, u64)>,
    /// Each body's position at the build, in single precision (see `pose::rounded`).
    built: Vec<[f32; DIM]>,
    /// The bodies with a reach (not disks or spheres), ascending, with their orientation and
    /// reach at the build.
    built_turning: Vec<(u32, Orientation, f32)>,
    /// [`ids_fingerprint`] of the bodies at the build.
    built_ids: u64,
    /// The largest displacement bound the single-precision poses may hide (m).
    pose_rounding: Real,
    built_alert: Real,
    skin: Real,
    calls_since_build: u64,
    stats: DetectorStats,
}

impl Detector {
    /// A detector with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// What the detector has done so far.
    pub fn stats(&self) -> DetectorStats {
        DetectorStats {
            candidates: self.seconds.len(),
            skin: self.skin,
            ..self.stats
        }
    }

    /// Replaces `contacts` by the contacts of the current configuration within `alert`, in
    /// ascending `(first body, second body)` order.
    ///
    /// `law_of(group_a, group_b)` is `None` when two groups do not interact (a law table's
    /// `between`): their pairs are skipped, as are pairs of bodies that contacts cannot move
    /// (all inverse masses zero) and contacts whose normal neither body can move along
    /// (`W_NN = 0`: a body held along it against a wall). Impulses of contacts present before
    /// (same bodies and features) are kept.
    pub fn detect(
        &mut self,
        bodies: &BodySet,
        alert: Real,
        law_of: impl Fn(u16, u16) -> Option<u16>,
        contacts: &mut ContactSet,
    ) {
        self.detect_in(bodies, None, alert, law_of, contacts, &mut Vec::new());
    }

    /// [`Detector::detect`], in a periodic cell when `periodic` is given: contacts are also
    /// found between a body and the images of the others, and `images` receives, per contact
    /// in order, the image of its second body it is with (cleared first; left empty without a
    /// cell).
    pub fn detect_in(
        &mut self,
        bodies: &BodySet,
        periodic: Option<Periodic>,
        alert: Real,
        law_of: impl Fn(u16, u16) -> Option<u16>,
        contacts: &mut ContactSet,
        images: &mut Vec<Image>,
    ) {
        self.stats.calls += 1;
        images.clear();
        // The list first, then the contacts: a build's arrays are gone before the merge.
        let moved = self.moved_since_build(bodies, periodic, alert);
        if moved.is_none_or(|m| m > self.skin) {
            self.build(bodies, periodic, alert, moved);
        }
        self.calls_since_build += 1;
        let mut merge = CarryOver::new(contacts);
        let immobile = |b: usize| !bodies.is_movable(b);
        // A body whose translations are free and whose mass is finite moves along any normal.
        let pushed = |b: usize| {
            bodies.imposed[b] & TRANSLATIONS == 0 && bodies.is_dynamic(b) && bodies.mass[b] > 0.0
        };
        let built_wraps = &self.built_wraps;
        let mut pair = |i: u32, j: u32, built_image: Option<&Image>| {
            let (a, b) = (i as usize, j as usize);
            let (shape_a, shape_b) = (&bodies.shape[a], &bodies.shape[b]);
            let pa = &bodies.position[a];
            let image = match (periodic, built_image) {
                (Some(p), Some(n)) => Some(relabel(
                    n,
                    [&p.wraps[a], &p.wraps[b]],
                    [&built_wraps[a], &built_wraps[b]],
                )),
                _ => None,
            };
            let shifted;
            let pb = match (periodic, &image) {
                (Some(p), Some(n)) if n.iter().any(|&x| x != 0) => {
                    shifted = bodies.position[b] + p.lattice.shift(n);
                    &shifted
                }
                _ => &bodies.position[b],
            };
            // Pairs of disks (spheres), the common case, without the general dispatch.
            let disks = match pose::round_pair(shape_a, shape_b, pa, pb, alert) {
                Some(Some(p)) => Manifold::one(p),
                Some(None) => return,
                None => Manifold::EMPTY,
            };
            if law_of(bodies.group[a], bodies.group[b]).is_none() || immobile(a) && immobile(b) {
                return;
            }
            let m = if disks.len > 0 {
                disks
            } else {
                let (angle_a, angle_b) = (bodies.rotation[a], bodies.rotation[b]);
                collide(shape_a, pa, angle_a, shape_b, pb, angle_b, alert)
            };
            if m.as_slice().is_empty() {
                return;
            }
            let (previous, count) = merge.previous_of([i, j]);
            let probe = !pushed(a) && !pushed(b);
            for p in m.as_slice() {
                let row = ContactRow::new([i, j], &p.point, &p.normal, pa, pb);
                if probe && !moves_along_normal(&row, bodies) {
                    continue;
                }
                let impulse = (previous[..count].iter())
                    .find(|c| c.0 == p.feature)
                    .map_or([0.0; DIM], |c| row.carry_in(c.1));
                merge.push(Contact {
                    row,
                    key: ContactKey { feature: p.feature },
                    gap: p.gap,
                    impulse,
                });
                if let Some(n) = image {
                    images.push(n);
                }
            }
        };
        for (i, range) in (0u32..).zip(self.first_start.windows(2)) {
            let (from, to) = (range[0] as usize, range[1] as usize);
            if self.images.is_empty() {
                for &j in &self.seconds[from..to] {
                    pair(i, j, None);
                }
            } else {
                for (&j, n) in self.seconds[from..to].iter().zip(&self.images[from..to]) {
                    pair(i, j, Some(n));
                }
            }
        }
    }

    /// How far two bodies may have moved towards each other since the list was built: the
    /// sum of the two largest displacement bounds `d_b`; `None` when the list is no use (none
    /// yet, another alert distance, bodies added, removed or renumbered).
    fn moved_since_build(
        &self,
        bodies: &BodySet,
        periodic: Option<Periodic>,
        alert: Real,
    ) -> Option<Real> {
        if self.built.len() != bodies.len()
            || self.built_alert != alert
            || ids_fingerprint(&bodies.id) != self.built_ids
        {
            return None;
        }
        // In a periodic cell: each body's displacement counts its wraps since the build, and
        // the images moved with the cell's edges by at most the sum of the edges' changes.
        let mut drift = 0.0;
        match (periodic, &self.built_lattice) {
            (None, None) => {}
            (Some(p), Some((edges, relabels))) => {
                if p.lattice.relabels != *relabels || p.wraps.len() != bodies.len() {
                    return None;
                }
                let change = p.lattice.edges - edges;
                drift = (0..DIM)
                    .filter(|&k| p.lattice.periodic[k])
                    .map(|k| change.column(k).norm())
                    .sum();
            }
            _ => return None,
        }
        // The two largest squared bounds: the square root is taken of these two only (for a
        // disk, `d_b^2` is the squared displacement itself).
        let (mut first, mut second): (Real, Real) = (0.0, 0.0);
        let mut turning = self.built_turning.iter().peekable();
        for (b, built) in self.built.iter().enumerate() {
            let mut p = bodies.position[b];
            if let Some(periodic) = periodic {
                let (now, then) = (&periodic.wraps[b], &self.built_wraps[b]);
                if now != then {
                    let n: Image = std::array::from_fn(|k| now[k] - then[k]);
                    p += periodic.lattice.shift(&n);
                }
            }
            let d: [Real; DIM] = std::array::from_fn(|k| p[k] - built[k] as Real);
            let mut squared = d[0] * d[0];
            for x in &d[1..] {
                squared += x * x;
            }
            if let Some((_, orientation, reach)) = turning.next_if(|t| t.0 as usize == b) {
                let turned = pose::turned(bodies.rotation[b], orientation);
                let d = squared.sqrt() + *reach as Real * turned;
                squared = d * d;
            }
            second = second.max(squared.min(first));
            first = first.max(squared);
        }
        Some(first.sqrt() + second.sqrt() + 2.0 * self.pose_rounding + drift)
    }

    /// Runs the broad phase with the alert distance grown by a new skin, and records the
    /// poses it was built at; `moved` is [`Self::moved_since_build`] for the list that ends.
    fn build(
        &mut self,
        bodies: &BodySet,
        periodic: Option<Periodic>,
        alert: Real,
        moved: Option<Real>,
    ) {
        self.skin = self.next_skin(bodies, alert, moved);
        self.built_alert = alert;
        self.calls_since_build = 0;
        self.stats.builds += 1;
        self.built_ids = ids_fingerprint(&bodies.id);
        let mut rounding: Real = 0.0;
        self.built_turning.clear();
        refill(
            &mut self.built,
            (0..bodies.len()).map(|b| {
                let reach = pose::reach(&bodies.shape[b]);
                let p = bodies.position[b];
                let (pose, hidden) = pose::rounded(&p, bodies.rotation[b], reach);
                rounding = rounding.max(hidden);
                if pose.reach > 0.0 {
                    self.built_turning
                        .push((b as u32, pose.orientation, pose.reach));
                }
                pose.position
            }),
        );
        self.built_turning.shrink_to_fit();
        self.pose_rounding = rounding;
        let previous = self.seconds.len();
        self.seconds = Vec::new();
        self.images = Vec::new();
        if let Some(periodic) = periodic {
            self.build_periodic(bodies, periodic, alert + self.skin);
            return;
        }
        self.built_lattice = None;
        self.built_wraps = Vec::new();
        // What serves only this build is held only during it, and never all at once: the list
        // that ends (dropped first), the broad phase's arrays (dropped once the pairs are
        // found), the unsorted pairs (dropped once sorted). Between builds the detector holds
        // the list and the poses alone; at a build its peak is the broad phase's arrays and
        // the unsorted pairs.
        let mut unsorted = Vec::with_capacity(previous + previous / 16 + 16);
        let mut broad = BroadPhase::new();
        broad.find_pairs(bodies, alert + self.skin, &mut unsorted);
        drop(broad);
        sort_pairs(
            &unsorted,
            bodies.len(),
            &mut self.first_start,
            &mut self.seconds,
            false,
        );
    }

    /// The candidate pairs in a periodic cell, within `reach` (the alert distance and the
    /// skin): the broad phase over the bodies and the images of those within reach of a side
    /// (walls have no images); a pair of a body and an image is kept as the pair of the two
    /// bodies with the image of the second, sorted by bodies then image, each once.
    fn build_periodic(&mut self, bodies: &BodySet, periodic: Periodic, reach: Real) {
        let lattice = periodic.lattice;
        self.built_lattice = Some((lattice.edges, lattice.relabels));
        refill(&mut self.built_wraps, periodic.wraps.iter().copied());
        let Some(inverse) = lattice.inverse() else {
            refill(
                &mut self.first_start,
                std::iter::repeat_n(0, bodies.len() + 1),
            );
            return;
        };
        let n = bodies.len();
        let boxes: Vec<Aabb> = (0..n)
            .map(|b| bodies.shape[b].aabb(&bodies.position[b], bodies.rotation[b]))
            .collect();
        let half_diagonal = |b: &Aabb| (b.max - b.min).norm() / 2.0;
        let largest = (0..n)
            .filter(|&b| !bodies.shape[b].is_wall())
            .map(|b| half_diagonal(&boxes[b]))
            .fold(0.0, Real::max);
        let mut proxies: Vec<(u32, Image)> = Vec::new();
        let mut near = Vec::new();
        for (b, bb) in boxes.iter().enumerate() {
            if bodies.shape[b].is_wall() {
                continue;
            }
            near.clear();
            let centre = (bb.min + bb.max) / 2.0;
            let within = half_diagonal(bb) + largest + reach;
            lattice.images_near(&inverse, &centre, within, &mut near);
            proxies.extend(near.iter().map(|&m| (b as u32, m)));
        }
        let mut found = Vec::new();
        BroadPhase::new().find_pairs_of(
            n + proxies.len(),
            |k| match k.checked_sub(n) {
                None => (boxes[k], bodies.shape[k].is_wall()),
                Some(p) => (
                    lattice.shifted(&boxes[proxies[p].0 as usize], &proxies[p].1),
                    false,
                ),
            },
            reach,
            &mut found,
        );
        let mut pairs: Vec<(u32, (u32, Image))> = Vec::with_capacity(found.len());
        for (a, b) in found {
            let (a, b) = (a as usize, b as usize);
            match (a.checked_sub(n), b.checked_sub(n)) {
                (None, None) => pairs.push((a as u32, (b as u32, [0; DIM]))),
                // Walls meet bodies, never their images (a wall is not repeated).
                (None, Some(p)) | (Some(p), None) if !bodies.shape[a.min(b)].is_wall() => {
                    let real = a.min(b) as u32;
                    let (body, m) = proxies[p];
                    if body > real {
                        pairs.push((real, (body, m)));
                    } else if body < real {
                        pairs.push((body, (real, m.map(|x| -x))));
                    }
                }
                _ => {}
            }
        }
        // A pair of bodies near two sides is found twice (each body with the other's image).
        let mut sorted = Vec::new();
        sort_pairs(&pairs, n, &mut self.first_start, &mut sorted, true);
        drop(pairs);
        self.seconds = sorted.iter().map(|p| p.0).collect();
        self.images = sorted.iter().map(|p| p.1).collect();
    }

    /// The skin of a new list: what lasts [`TARGET_STEPS_PER_BUILD`] calls at the rate the
    /// bodies moved during the list that ends (`moved` over its calls), clamped; the alert
    /// distance when there is no such list.
    fn next_skin(&self, bodies: &BodySet, alert: Real, moved: Option<Real>) -> Real {
        let Some(moved) = moved.filter(|_| self.calls_since_build > 0) else {
            return alert;
        };
        let size = (bodies.shape.iter())
            .filter(|s| !s.is_wall())
            .map(|s| 2.0 * s.size())
            .fold(0.0, Real::max);
        let cap = (SKIN_CAP_OVER_SIZE * size).max(alert);
        let rate = moved / self.calls_since_build as Real;
        (TARGET_STEPS_PER_BUILD * rate).clamp(alert, cap)
    }
}

/// The bits of [`BodySet::imposed`] of the translations.
const TRANSLATIONS: u8 = (1 << DIM) - 1;

/// Whether an impulse along the normal of `row` moves one of its bodies (`W_NN > 0`). A
/// contact between two bodies that cannot move along its normal (a body whose motion is
/// imposed, against a wall or another such body) is left out by the detection, as LMGC90
/// leaves it out: no impulse of it could change a velocity, and its local problem has no
/// solution once it closes.
fn moves_along_normal(row: &ContactRow, bodies: &BodySet) -> bool {
    let mut probe = *row;
    probe.refresh_block(|b| bodies.inv_mass(b));
    probe.full_block()[0] > 0.0
}

/// `pairs` (each `(i, j)` with `i < j`, `j` a second body, or a second body and its image)
/// in ascending order, compressed: `seconds` the second bodies, `start[i]..start[i + 1]` those
/// of first body `i`. A counting sort by first body, then the few second bodies of each first
/// body sorted in place; with `dedup`, each group's repeated entries are then kept once.
fn sort_pairs<T: Copy + Ord + Default>(
    pairs: &[(u32, T)],
    n_bodies: usize,
    start: &mut Vec<u32>,
    seconds: &mut Vec<T>,
    dedup: bool,
) {
    refill(start, std::iter::repeat_n(0, n_bodies + 1));
    for &(i, _) in pairs {
        start[i as usize + 1] += 1;
    }
    for b in 0..n_bodies {
        start[b + 1] += start[b];
    }
    refill(seconds, std::iter::repeat_n(T::default(), pairs.len()));
    // `start[i]` serves as the cursor of group `i`, then moves back to its beginning.
    for &(i, j) in pairs {
        let slot = &mut start[i as usize];
        seconds[*slot as usize] = j;
        *slot += 1;
    }
    for b in (0..n_bodies).rev() {
        start[b + 1] = start[b];
    }
    start[0] = 0;
    for b in 0..n_bodies {
        seconds[start[b] as usize..start[b + 1] as usize].sort_unstable();
    }
    if dedup {
        // Groups move down over the entries dropped before them.
        let mut kept = 0;
        for b in 0..n_bodies {
            let (from, to) = (start[b] as usize, start[b + 1] as usize);
            start[b] = kept as u32;
            for k in from..to {
                if k == from || seconds[k] != seconds[k - 1] {
                    seconds[kept] = seconds[k];
                    kept += 1;
                }
            }
        }
        start[n_bodies] = kept as u32;
        seconds.truncate(kept);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ids_fingerprint_changes_when_bodies_are_renumbered_added_or_removed() {
        let ids: Vec<u64> = (0..100).collect();
        let mut swapped = ids.clone();
        swapped.swap(10, 11);
        let fingerprints = [
            ids_fingerprint(&ids),
            ids_fingerprint(&swapped),
            ids_fingerprint(&ids[..99]),
            ids_fingerprint(&[ids.as_slice(), &[100]].concat()),
        ];
        for a in 0..fingerprints.len() {
            for b in a + 1..fingerprints.len() {
                assert_ne!(fingerprints[a], fingerprints[b], "{a} and {b}");
            }
        }
    }
}

/// The 3D detector's kept candidate list against a detection from scratch at every call of
/// a sequence of random moves and rotations (some larger than the skin): the same contacts in
/// the same order; bodies at rest never rebuild the list.
#[cfg(all(test, feature = "dim3"))]
mod tests_3d {
    use super::*;
    use xper_bodies::Body;
    use xper_math::{Rotation, SplitMix64, Vector};

    /// Three spheres touching a floor: free; held along the floor's normal (no impulse could
    /// move it: `W_NN = 0`); held along the floor only (free along the normal). The held one
    /// makes no contact, the other two do; so do the held one and a free sphere on it.
    #[test]
    fn a_body_held_along_the_normal_makes_no_contact_with_a_wall() {
        use xper_bodies::{Drive, TimeFunction};
        let held = |dofs: &[usize], at: Vector| {
            let mut b = Body::sphere(0.1, 1000.0, at);
            for &k in dofs {
                b.drives[k] = Drive::Velocity(TimeFunction::Constant(0.0));
            }
            b
        };
        let mut set = BodySet::new();
        set.insert(Body::plane(Vector::zeros(), Vector::z(), [4.0, 4.0]));
        set.insert(held(&[], Vector::new(0.0, 0.0, 0.1)));
        set.insert(held(&[2, 3, 4, 5], Vector::new(1.0, 0.0, 0.1)));
        set.insert(held(&[0, 1, 3, 4, 5], Vector::new(2.0, 0.0, 0.1)));
        set.insert(held(&[], Vector::new(1.0, 0.0, 0.3)));
        let mut contacts = ContactSet::default();
        Detector::new().detect(&set, 0.01, |_, _| Some(0), &mut contacts);
        let pairs: Vec<[u32; 2]> = contacts.rows.iter().map(|r| r.bodies).collect();
        assert_eq!(pairs, vec![[0, 1], [0, 3], [2, 4]]);
    }

    #[test]
    fn kept_candidates_give_the_contacts_of_a_fresh_detection_in_3d() {
        let mut rng = SplitMix64::new(29);
        for case in 0..6 {
            let mut set = BodySet::new();
            set.insert(Body::plane(Vector::zeros(), Vector::z(), [4.0, 4.0]));
            for k in 0..120 {
                let p = Vector::new(
                    3.0 * rng.next_f64(),
                    3.0 * rng.next_f64(),
                    2.0 * rng.next_f64(),
                );
                let r = 0.1 + 0.2 * rng.next_f64();
                let body = if k % 3 == 0 {
                    let points: Vec<Vector> = (0..8)
                        .map(|_| {
                            p + Vector::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * r
                        })
                        .collect();
                    Body::polyhedron(&points, 1000.0).unwrap()
                } else {
                    Body::sphere(r, 1000.0, p)
                };
                set.insert(body);
            }
            let (step, spin) = if case == 0 { (0.0, 0.0) } else { (0.02, 0.05) };
            let alert = 0.02;
            let law = |_: u16, _: u16| Some(0u16);
            let mut kept = Detector::new();
            let mut kept_contacts = ContactSet::default();
            for call in 0..20 {
                kept.detect(&set, alert, law, &mut kept_contacts);
                let mut fresh = ContactSet::default();
                Detector::new().detect(&set, alert, law, &mut fresh);
                let strip = |c: &ContactSet| -> Vec<_> {
                    c.iter().map(|c| (c.row, c.key, c.gap.to_bits())).collect()
                };
                let (k, f) = (strip(&kept_contacts), strip(&fresh));
                let only_k: Vec<_> = k
                    .iter()
                    .filter(|x| !f.contains(x))
                    .map(|x| (x.0.bodies, x.1))
                    .collect();
                let only_f: Vec<_> = f
                    .iter()
                    .filter(|x| !k.contains(x))
                    .map(|x| (x.0.bodies, x.1))
                    .collect();
                assert!(
                    k == f,
                    "case {case} call {call}: kept only {only_k:?}, fresh only {only_f:?}, {:?}",
                    kept.stats()
                );
                assert!(fresh.len() > 20, "case {case}: {} contacts", fresh.len());
                for b in 1..set.len() {
                    let jump = if rng.next_f64() > 0.98 { 10.0 } else { 1.0 };
                    let d = Vector::new(rng.next_f64(), rng.next_f64(), rng.next_f64())
                        - Vector::repeat(0.5);
                    set.position[b] += d * (2.0 * jump * step);
                    let w = Vector::new(rng.next_f64(), rng.next_f64(), rng.next_f64());
                    set.rotation[b] = Rotation::from_scaled_axis(w * spin) * set.rotation[b];
                }
            }
            if case == 0 {
                assert_eq!(kept.stats().builds, 1);
            }
        }
    }
}
