//! Detection in a periodic cell against brute force: every pair of disks and every image of
//! the second within one cell in each direction, at each call of a sequence of random moves
//! (bodies wrapped back into the cell, their wrap counts kept as a stepper keeps them) while
//! the cell shears and is reduced (relabelled) once; the kept candidate list gives the same
//! contacts, images and gaps as the brute force.

use xper_bodies::{Body, BodySet};
use xper_geometry::{ContactSet, Detector, Image, Lattice, Periodic};
use xper_math::{Real, SplitMix64, Tensor, Vector};

fn brute_force(bodies: &BodySet, lattice: &Lattice, alert: Real) -> Vec<([u32; 2], Image, i64)> {
    let mut out = Vec::new();
    let radius = |b: usize| bodies.shape[b].size();
    for i in 0..bodies.len() {
        for j in i + 1..bodies.len() {
            for nx in -1..=1 {
                for ny in -1..=1 {
                    let n = [nx, ny];
                    let d = bodies.position[j] + lattice.shift(&n) - bodies.position[i];
                    let gap = d.norm() - radius(i) - radius(j);
                    if gap <= alert {
                        out.push(([i as u32, j as u32], n, (gap * 1e9).round() as i64));
                    }
                }
            }
        }
    }
    out.sort();
    out
}

fn detected(contacts: &ContactSet, images: &[Image]) -> Vec<([u32; 2], Image, i64)> {
    let mut out: Vec<_> = (contacts.iter().zip(images))
        .map(|(c, n)| (c.row.bodies, *n, (c.gap * 1e9).round() as i64))
        .collect();
    out.sort();
    out
}

#[test]
fn a_kept_list_in_a_shearing_cell_finds_the_contacts_of_a_brute_force_search() {
    let mut rng = SplitMix64::new(5);
    let mut lattice = Lattice {
        origin: Vector::new(-0.5, 0.2),
        edges: Tensor::new(2.0, 0.3, 0.0, 1.5),
        periodic: [true, true],
        relabels: 0,
    };
    let mut bodies = BodySet::new();
    for _ in 0..150 {
        let s = Vector::new(rng.next_f64(), rng.next_f64());
        let p = lattice.origin + lattice.edges * s;
        bodies.insert(Body::disk(0.04 + 0.03 * rng.next_f64(), 1000.0, p));
    }
    let mut wraps: Vec<Image> = vec![[0, 0]; bodies.len()];
    let alert = 0.01;
    let law = |_: u16, _: u16| Some(0u16);
    let (mut kept, mut contacts, mut images) = (Detector::new(), ContactSet::default(), vec![]);
    let mut across = 0;
    for call in 0..200 {
        let periodic = Periodic {
            lattice: &lattice,
            wraps: &wraps,
        };
        kept.detect_in(
            &bodies,
            Some(periodic),
            alert,
            law,
            &mut contacts,
            &mut images,
        );
        let expected = brute_force(&bodies, &lattice, alert);
        assert_eq!(detected(&contacts, &images), expected, "call {call}");
        across += expected.iter().filter(|c| c.1 != [0, 0]).count();
        // Move, shear (once past half an edge: reduced), wrap.
        for b in 0..bodies.len() {
            let jump = if rng.next_f64() > 0.999 { 20.0 } else { 1.0 };
            let d = Vector::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5) * (0.002 * jump);
            bodies.position[b] += d;
        }
        lattice.edges[(0, 1)] += 0.004;
        if lattice.edges[(0, 1)] > 1.0 {
            lattice.edges[(0, 1)] -= 2.0;
            lattice.relabels += 1;
        }
        let inverse = lattice.inverse().unwrap();
        for (b, w) in wraps.iter_mut().enumerate() {
            let n = lattice.wrap_of(&inverse, &bodies.position[b]);
            bodies.position[b] -= lattice.shift(&n);
            w[0] += n[0];
            w[1] += n[1];
        }
    }
    assert!(across > 500, "only {across} contacts across the sides");
    assert_eq!(lattice.relabels, 1);
    assert!(kept.stats().builds < 100, "{:?}", kept.stats());
}
