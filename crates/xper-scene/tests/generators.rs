//! Generators: non-overlapping disks inside the box (brute force), determinism, walls.

mod common;
use common::*;
use xper_scene::{Scene, ShapeDesc};

fn box_of_disks(placement: &str, seed: u64) -> String {
    with_header(&format!(
        "[[generators]]\nkind = \"box_of_disks\"\ncount = 300\nradius = [0.001, 0.002]\nbox = [[0.0, 0.0], [0.1, 0.2]]\nplacement = \"{placement}\"\nseed = {seed}\nmaterial = \"glass\"\ngroup = \"grains\"\nwalls = \"box\"\nvelocity = [0.5, 0.0]\n"
    ))
}

fn disks(s: &Scene) -> Vec<([f64; 2], f64)> {
    s.bodies
        .iter()
        .filter_map(|b| match b.shape {
            ShapeDesc::Disk { radius } => Some((b.position, radius)),
            _ => None,
        })
        .collect()
}

fn check_inside_and_disjoint(s: &Scene, lo: [f64; 2], hi: [f64; 2], n: usize) {
    let d = disks(s);
    assert_eq!(d.len(), n);
    for &(c, r) in &d {
        assert!((0.001..=0.002).contains(&r), "radius {r}");
        assert!(
            c[0] - r >= lo[0] && c[1] - r >= lo[1] && c[0] + r <= hi[0] && c[1] + r <= hi[1],
            "{c:?} {r}"
        );
    }
    for i in 0..d.len() {
        for j in i + 1..d.len() {
            let (ci, ri) = d[i];
            let (cj, rj) = d[j];
            let dist = (ci[0] - cj[0]).hypot(ci[1] - cj[1]);
            assert!(dist >= ri + rj, "disks {i} and {j} overlap");
        }
    }
}

#[test]
fn box_of_disks_lattice() {
    let s = ok(&box_of_disks("lattice", 1));
    check_inside_and_disjoint(&s, [0.0, 0.0], [0.1, 0.2], 300);
    // Pitch 2 * 0.002 * 1.05 = 0.0042 m from the bottom-left, left to right then upwards.
    let p = 2.0 * 0.002 * 1.05;
    assert_eq!(s.bodies[0].position, [p / 2.0, p / 2.0]);
    assert_eq!(s.bodies[1].position, [p / 2.0 + p, p / 2.0]);
    let per_row = (0.1f64 / p).floor() as usize; // 23
    assert_eq!(s.bodies[per_row].position, [p / 2.0, p / 2.0 + p]);
    assert_eq!(s.bodies[0].velocity, [0.5, 0.0]);
    // Walls after the disks: bottom, right, top, left, in group "box".
    assert_eq!(s.bodies.len(), 304);
    assert_eq!(s.groups, vec!["grains".to_string(), "box".to_string()]);
    assert!(s.bodies[300..]
        .iter()
        .all(|w| w.group == 1 && w.mass == f64::INFINITY));
    assert_eq!(s.bodies[300].position, [0.05, 0.0]);
    assert_eq!(s.bodies[301].position, [0.1, 0.1]);
}

#[test]
fn box_of_disks_random() {
    let s = ok(&box_of_disks("random", 7));
    check_inside_and_disjoint(&s, [0.0, 0.0], [0.1, 0.2], 300);
    assert_eq!(
        s,
        ok(&box_of_disks("random", 7)),
        "deterministic for a seed"
    );
    assert_ne!(disks(&s), disks(&ok(&box_of_disks("random", 8))));
}

#[test]
fn hex_lattice_100x100_validates() {
    let t = with_header(
        "[[generators]]\nkind = \"hex_lattice\"\ncolumns = 100\nrows = 100\npitch = 4.1e-3\nradius = 1e-3\nseed = 12345\nbox = [0.41205, 0.36]\nmaterial = \"glass\"\ngroup = \"grains\"\nwalls = \"walls\"\n",
    );
    let start = std::time::Instant::now();
    let s = ok(&t);
    eprintln!(
        "100x100 hex lattice parsed and validated in {:?}",
        start.elapsed()
    );
    assert_eq!(s.bodies.len(), 10_004);
}
