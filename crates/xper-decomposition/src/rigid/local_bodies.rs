//! Stage 3's bodies: the local [`BodySet`] a process steps, kept from one step to the next.
//!
//! The set holds the immovable bodies, the owned ones and the shadow copies in increasing
//! global id (the order that makes contact detection match a serial run's). Between
//! re-partitions that set rarely changes from one step to the next (a body migrates or enters
//! a halo now and then), so [`refresh`] keeps the descriptions (shapes, masses, drives) in
//! place and copies only the states from the catalogue when the ids are those of the last
//! step. Rebuilding the whole set every step cost a free-falling 100,000-disk deposit on 2
//! processes 3.7 ms per step (shape copies, a sort, allocation), a third of its step.

use xper_bodies::{BodyHandle, BodySet, Ownership};

/// The bodies a process holds, as `(global id, ownership)` in increasing id: the merge of
/// three lists each in increasing id (`immovable` with `wall_owner`, `owned`, `shadows`
/// with their owner ranks), written into `held`.
pub(crate) fn merge_held(
    immovable: &[u32],
    wall_owner: Ownership,
    owned: &[u32],
    shadows: &[(u32, u32)],
    held: &mut Vec<(u32, Ownership)>,
) {
    let movable = by_id(
        owned.iter().map(|&b| (b, Ownership::Owned)),
        (shadows.iter()).map(|&(b, owner)| (b, Ownership::Shadow { owner })),
    );
    held.clear();
    held.extend(by_id(immovable.iter().map(|&b| (b, wall_owner)), movable));
}

/// The union of two sequences in increasing id, in increasing id.
fn by_id(
    a: impl Iterator<Item = (u32, Ownership)>,
    b: impl Iterator<Item = (u32, Ownership)>,
) -> impl Iterator<Item = (u32, Ownership)> {
    let (mut a, mut b) = (a.peekable(), b.peekable());
    std::iter::from_fn(move || match (a.peek(), b.peek()) {
        (Some(x), Some(y)) if x.0 <= y.0 => a.next(),
        (Some(_), Some(_)) => b.next(),
        (Some(_), None) => a.next(),
        (None, _) => b.next(),
    })
}

/// Makes `local` hold the bodies `held` of the catalogue `all`, with `local_of[g]` the local
/// index of global body `g` (`u32::MAX` where not held) and `driven_of[g]` its entry in
/// `all.driven` (`u32::MAX`: none). States always come from `all`; descriptions are copied
/// only when the held ids differ from `local`'s.
pub(crate) fn refresh(
    all: &BodySet,
    held: &[(u32, Ownership)],
    driven_of: &[u32],
    local: &mut BodySet,
    local_of: &mut [u32],
) {
    let same = held.len() == local.id.len()
        && (held.iter().zip(&local.id)).all(|(&(g, _), &id)| g as u64 == id);
    if !same {
        for &g in &local.id {
            local_of[g as usize] = u32::MAX;
        }
        describe(all, held, driven_of, local);
        for (k, &(g, _)) in held.iter().enumerate() {
            local_of[g as usize] = k as u32;
        }
    }
    for (k, &(g, ownership)) in held.iter().enumerate() {
        // A body owned here at the last step too already holds its state (stage 3 wrote it
        // to the catalogue); the others may have moved elsewhere or arrived.
        let kept = same && ownership == Ownership::Owned && local.ownership[k] == Ownership::Owned;
        local.ownership[k] = ownership;
        if kept {
            continue;
        }
        let b = g as usize;
        local.position[k] = all.position[b];
        local.rotation[k] = all.rotation[b];
        local.velocity[k] = all.velocity[b];
        local.angular_velocity[k] = all.angular_velocity[b];
    }
}

/// Rewrites every column of `local` for the bodies `held` (states included), reusing its
/// allocations.
fn describe(all: &BodySet, held: &[(u32, Ownership)], driven_of: &[u32], local: &mut BodySet) {
    let ids = || held.iter().map(|&(g, _)| g as usize);
    fn fill<T: Clone>(column: &mut Vec<T>, values: impl Iterator<Item = T>) {
        column.clear();
        column.extend(values);
    }
    fill(&mut local.position, ids().map(|b| all.position[b]));
    fill(&mut local.rotation, ids().map(|b| all.rotation[b]));
    fill(&mut local.velocity, ids().map(|b| all.velocity[b]));
    fill(
        &mut local.angular_velocity,
        ids().map(|b| all.angular_velocity[b]),
    );
    fill(&mut local.mass, ids().map(|b| all.mass[b]));
    fill(&mut local.inertia, ids().map(|b| all.inertia[b]));
    fill(&mut local.imposed, ids().map(|b| all.imposed[b]));
    fill(&mut local.shape, ids().map(|b| all.shape[b].clone()));
    fill(&mut local.group, ids().map(|b| all.group[b]));
    fill(&mut local.id, ids().map(|b| b as u64));
    fill(&mut local.ownership, held.iter().map(|&(_, o)| o));
    local.driven.clear();
    for (k, b) in ids().enumerate() {
        if let Some((_, drives)) = all.driven.get(driven_of[b] as usize) {
            local.driven.push((BodyHandle(k as u32), drives.clone()));
        }
    }
}

// Tests of the 2D build (their scenes are planar).
#[cfg(all(test, feature = "dim2"))]
mod tests {
    use super::*;
    use xper_bodies::Body;
    use xper_math::Vector;

    fn catalogue(n: usize) -> BodySet {
        let mut all = BodySet::new();
        for k in 0..n {
            all.insert(Body::disk(
                0.1,
                1000.0 + k as f64,
                Vector::new(k as f64, 0.0),
            ));
        }
        all
    }

    #[test]
    fn merged_bodies_are_in_increasing_id_with_their_ownership() {
        let mut held = Vec::new();
        let wall = Ownership::Shadow { owner: 0 };
        merge_held(&[0, 9], wall, &[2, 3, 7], &[(1, 4), (8, 2)], &mut held);
        let ids: Vec<u32> = held.iter().map(|h| h.0).collect();
        assert_eq!(ids, [0, 1, 2, 3, 7, 8, 9]);
        assert_eq!(held[1].1, Ownership::Shadow { owner: 4 });
        assert_eq!(held[4].1, Ownership::Owned);
        assert_eq!(held[6].1, wall);
    }

    /// The kept set must equal a set described from scratch, whatever the previous step held
    /// and owned: between refreshes the owned bodies move here (and are stored back into the
    /// catalogue), the others elsewhere.
    #[test]
    fn a_refreshed_set_equals_one_described_from_scratch() {
        let mut all = catalogue(12);
        let driven_of = vec![u32::MAX; 12];
        let (mut local, mut local_of) = (BodySet::new(), vec![u32::MAX; 12]);
        let steps: [&[u32]; 5] = [
            &[1, 4, 5],
            &[1, 4, 5],
            &[1, 4, 5],
            &[0, 4, 5, 11],
            &[0, 4, 5, 11],
        ];
        for (step, ids) in steps.iter().enumerate() {
            let owned = |g: u32| (g as usize + step / 2).is_multiple_of(2);
            for (b, &k) in local_of.iter().enumerate() {
                let owned_here = k != u32::MAX && local.ownership[k as usize] == Ownership::Owned;
                if !owned_here {
                    all.velocity[b] = Vector::new(step as f64, b as f64);
                }
            }
            let held: Vec<(u32, Ownership)> = (ids.iter())
                .map(|&g| match owned(g) {
                    true => (g, Ownership::Owned),
                    false => (g, Ownership::Shadow { owner: 1 }),
                })
                .collect();
            refresh(&all, &held, &driven_of, &mut local, &mut local_of);
            let mut fresh = BodySet::new();
            describe(&all, &held, &driven_of, &mut fresh);
            assert_eq!(local, fresh, "step {step}");
            for (k, &g) in ids.iter().enumerate() {
                assert_eq!(local_of[g as usize], k as u32);
            }
            let held_count = local_of.iter().filter(|&&k| k != u32::MAX).count();
            assert_eq!(held_count, ids.len());
            for (k, &g) in ids.iter().enumerate() {
                local.velocity[k].x += 10.0;
                if owned(g) {
                    all.velocity[g as usize] = local.velocity[k];
                }
            }
        }
    }
}
