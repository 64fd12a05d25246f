//! The detector's candidate list (kept across calls while bodies move less than its skin)
//! gives exactly the contacts of a detection from scratch, in the same order, at every call
//! of a sequence of random moves and rotations, including moves larger than the skin.

mod common;

use common::scene;
use proptest::prelude::*;
use xper_bodies::Shape;
use xper_geometry::{ContactSet, Detector};
use xper_math::Real;

/// A pseudo-random number in [-1, 1) from a counter (splitmix64).
fn noise(k: u64) -> Real {
    let mut z = k.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as Real * (2.0 / (1u64 << 53) as Real) - 1.0
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn kept_candidates_give_the_contacts_of_a_fresh_detection(
        specs in prop::collection::vec((0u8..3, 0.0..6.0f64, 0.0..6.0f64, 0.1..0.5f64, 0.0..6.3f64), 2..120),
        alert in 0.005..0.1f64,
        step in prop_oneof![Just(0.0), 0.0..0.08f64],
        spin in prop_oneof![Just(0.0), 0.0..0.1f64],
        seed in 0u64..1000,
    ) {
        let mut set = scene(&specs);
        let law = |_: u16, _: u16| Some(0u16);
        let mut kept = Detector::new();
        let mut kept_contacts = ContactSet::default();
        let mut set_impulses: Vec<([u32; 2], u32, [Real; 2])> = Vec::new();
        for call in 0..25u64 {
            kept.detect(&set, alert, law, &mut kept_contacts);
            for c in kept_contacts.iter() {
                let (bodies, feature) = (c.row.bodies, c.key.feature);
                let before = (set_impulses.iter())
                    .find(|(b, f, _)| *b == bodies && *f == feature)
                    .map_or([0.0, 0.0], |e| e.2);
                prop_assert_eq!(c.impulse, before, "call {}: impulse of {:?}", call, bodies);
            }
            let mut fresh_contacts = ContactSet::default();
            Detector::new().detect(&set, alert, law, &mut fresh_contacts);
            let strip = |c: &ContactSet| -> Vec<_> {
                c.iter().map(|c| (c.row, c.key, c.gap.to_bits())).collect()
            };
            prop_assert_eq!(strip(&kept_contacts), strip(&fresh_contacts), "call {}", call);
            // Every contact carries a non-zero impulse into the next call.
            for (k, r) in kept_contacts.impulses.iter_mut().enumerate() {
                *r = [1.0 + k as Real, 0.0];
            }
            set_impulses = (kept_contacts.iter())
                .map(|c| (c.row.bodies, c.key.feature, c.impulse))
                .collect();
            // Move and turn every movable body; now and then one jumps far.
            for b in 0..set.len() {
                if matches!(set.shape[b], Shape::Segment { .. }) {
                    continue;
                }
                let k = seed * 1_000_003 + call * 1009 + b as u64;
                let jump = if noise(3 * k + 2) > 0.97 { 10.0 } else { 1.0 };
                set.position[b].x += jump * step * noise(3 * k);
                set.position[b].y += jump * step * noise(3 * k + 1);
                set.rotation[b] += spin * noise(3 * k + 2);
            }
        }
        // Bodies at rest never invalidate the first list.
        if step == 0.0 && spin == 0.0 {
            prop_assert_eq!(kept.stats().builds, 1);
        }
    }
}
