//! The grid broad phase finds exactly the pairs that an all-pairs search finds.

use proptest::prelude::*;
use xper_bodies::{Body, BodySet, ConvexPolygon, Drive, Shape};
use xper_geometry::{collide, BroadPhase};
use xper_math::{Real, Vector};

fn body(shape: Shape, x: Real, y: Real, angle: Real) -> Body {
    let fixed = matches!(shape, Shape::Segment { .. });
    Body {
        shape,
        position: Vector::new(x, y),
        angle,
        velocity: Vector::zeros(),
        angular_velocity: 0.0,
        mass: if fixed { Real::INFINITY } else { 1.0 },
        inertia: if fixed { Real::INFINITY } else { 1.0 },
        group: 0,
        drives: [Drive::Free, Drive::Free, Drive::Free],
    }
}

fn scene(specs: &[(u8, Real, Real, Real, Real)]) -> BodySet {
    let mut set = BodySet::new();
    for &(kind, x, y, size, angle) in specs {
        let shape = match kind % 3 {
            0 => Shape::Disk { radius: size },
            1 => Shape::Polygon(ConvexPolygon::new(vec![
                Vector::new(-size, -size / 2.0),
                Vector::new(size, -size / 2.0),
                Vector::new(0.0, size),
            ])),
            _ => Shape::Segment {
                half_length: size * 8.0,
            },
        };
        set.insert(body(shape, x, y, angle));
    }
    set
}

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
                let bi = set.shape[i].aabb(&set.position[i], set.angle[i]).loosened(alert / 2.0);
                let bj = set.shape[j].aabb(&set.position[j], set.angle[j]).loosened(alert / 2.0);
                if bi.intersects(&bj) {
                    brute.push((i as u32, j as u32));
                }
            }
        }
        prop_assert_eq!(&found, &brute);
        // Every narrow-phase contact within the alert distance comes from a reported pair.
        for i in 0..n {
            for j in i + 1..n {
                let m = collide(&set.shape[i], &set.position[i], set.angle[i], &set.shape[j], &set.position[j], set.angle[j], alert);
                if m.len > 0 {
                    prop_assert!(found.binary_search(&(i as u32, j as u32)).is_ok());
                }
            }
        }
    }
}
