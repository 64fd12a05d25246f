//! The grid broad phase finds exactly the pairs that an all-pairs search finds.

mod common;

use common::scene;
use proptest::prelude::*;
use xper_geometry::{collide, BroadPhase, OuterBox};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn grid_pairs_equal_brute_force_pairs(
        specs in prop::collection::vec((0u8..3, 0.0..10.0f64, 0.0..10.0f64, 0.05..0.6f64, 0.0..6.3f64), 1..250),
        alert in 0.0..0.3f64,
    ) {
        let set = scene(&specs);
        let mut pairs = Vec::new();
        BroadPhase::new().find_pairs(&set, alert, &mut pairs);
        let mut found: Vec<(u32, u32)> = pairs.clone();
        found.sort_unstable();
        let before = found.len();
        found.dedup();
        prop_assert_eq!(before, found.len(), "a pair was reported twice");
        let n = set.len();
        let mut brute = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let bi = set.shape[i].aabb(&set.position[i], set.rotation[i]).loosened(alert / 2.0);
                let bj = set.shape[j].aabb(&set.position[j], set.rotation[j]).loosened(alert / 2.0);
                // The grid's boxes are the exact ones rounded outwards to single precision:
                // the same pairs, and at least every pair of the exact boxes.
                if OuterBox::around(&bi).intersects(&OuterBox::around(&bj)) {
                    brute.push((i as u32, j as u32));
                }
                if bi.intersects(&bj) {
                    prop_assert!(found.binary_search(&(i as u32, j as u32)).is_ok());
                }
            }
        }
        prop_assert_eq!(&found, &brute);
        // Every narrow-phase contact within the alert distance comes from a reported pair.
        for i in 0..n {
            for j in i + 1..n {
                let m = collide(&set.shape[i], &set.position[i], set.rotation[i], &set.shape[j], &set.position[j], set.rotation[j], alert);
                if m.len > 0 {
                    prop_assert!(found.binary_search(&(i as u32, j as u32)).is_ok());
                }
            }
        }
    }
}
