//! Overlapping initial bodies are reported, exactly (not by bounding boxes).

mod common;
use common::*;

fn disk(x: f64, y: f64, r: f64, tag: &str) -> String {
    format!("[[bodies]] # {tag}\nshape = \"disk\"\ncenter = [{x}, {y}]\nradius = {r}\nmaterial = \"glass\"\ngroup = \"g\"\n")
}

fn rect(x: f64, y: f64, w: f64, h: f64, angle: f64, tag: &str) -> String {
    format!("[[bodies]] # {tag}\nshape = \"rectangle\"\ncenter = [{x}, {y}]\nsize = [{w}, {h}]\nangle = {angle}\nmaterial = \"glass\"\ngroup = \"g\"\n")
}

fn wall(x0: f64, y0: f64, x1: f64, y1: f64, tag: &str) -> String {
    format!("[[walls]] # {tag}\nfrom = [{x0}, {y0}]\nto = [{x1}, {y1}]\ngroup = \"w\"\n")
}

#[test]
fn disk_disk() {
    let t = with_header(&(disk(0.0, 0.0, 0.01, "A") + &disk(0.015, 0.0, 0.01, "B")));
    let e = expect_error(
        &t,
        "bodies[1]",
        "# B",
        "body 1 (bodies[1]) overlaps body 0 (bodies[0], at test.toml:",
    );
    assert!(
        e.message
            .contains(&format!("test.toml:{}:1)", line_of(&t, "# A"))),
        "{}",
        e.message
    );
    assert!(e.message.contains("by 5.000e-3 m"), "{}", e.message);
    // Touching is fine.
    ok(&with_header(
        &(disk(0.0, 0.0, 0.01, "A") + &disk(0.02, 0.0, 0.01, "B")),
    ));
}

#[test]
fn disk_wall_and_walls_crossing() {
    let t = with_header(&(disk(0.5, 0.005, 0.01, "A") + &wall(0.0, 0.0, 1.0, 0.0, "W")));
    expect_error(&t, "walls[0]", "# W", "overlaps body 0");
    let s = ok(&with_header(
        &(disk(0.5, 0.01, 0.01, "A")
            + &wall(0.0, 0.0, 1.0, 0.0, "W")
            + &wall(0.0, -1.0, 0.0, 1.0, "V")),
    ));
    assert_eq!(s.bodies.len(), 3);
}

#[test]
fn polygon_polygon_by_separating_axes() {
    let t =
        with_header(&(rect(0.0, 0.0, 1.0, 1.0, 0.0, "A") + &rect(0.9, 0.0, 1.0, 1.0, 0.0, "B")));
    expect_error(&t, "bodies[1]", "# B", "by 1.000e-1 m");
    let d = std::f64::consts::FRAC_PI_4;
    // Rotated square: its left corner reaches x = 1.2 - 0.7071 = 0.4929 < 0.5.
    let t = with_header(&(rect(0.0, 0.0, 1.0, 1.0, 0.0, "A") + &rect(1.2, 0.0, 1.0, 1.0, d, "B")));
    expect_error(&t, "bodies[1]", "# B", "by 7.107e-3 m");
    // Bounding boxes overlap but the shapes do not.
    ok(&with_header(
        &(rect(0.0, 0.0, 1.0, 1.0, 0.0, "A") + &rect(1.3, 0.0, 1.0, 1.0, d, "B")),
    ));
    ok(&with_header(
        &(rect(0.0, 0.0, 1.0, 1.0, d, "A") + &rect(1.0, 1.0, 1.0, 1.0, d, "B")),
    ));
}

#[test]
fn polygon_disk_exact() {
    let sq = rect(0.0, 0.0, 1.0, 1.0, 0.0, "A");
    let t = with_header(&(sq.clone() + &disk(0.6, 0.6, 0.15, "B")));
    expect_error(&t, "bodies[1]", "# B", "by 8.579e-3 m");
    ok(&with_header(&(sq.clone() + &disk(0.6, 0.6, 0.14, "B"))));
    // Centre inside: depth = r + distance to the nearest side.
    let t = with_header(&(sq + &disk(0.4, 0.0, 0.05, "B")));
    expect_error(&t, "bodies[1]", "# B", "by 1.500e-1 m");
}

#[test]
fn polygon_segment_exact() {
    let d = std::f64::consts::FRAC_PI_4;
    let t = with_header(&(rect(0.0, 0.0, 1.0, 1.0, d, "A") + &wall(-1.0, -0.7, 1.0, -0.7, "W")));
    expect_error(&t, "walls[0]", "# W", "by 7.107e-3 m");
    ok(&with_header(
        &(rect(0.0, 0.0, 1.0, 1.0, d, "A") + &wall(-1.0, -0.72, 1.0, -0.72, "W")),
    ));
    // A diagonal wall through an axis-aligned square's corner region.
    // Line x + y = 0.9 cuts the corner (0.5, 0.5) by 0.1 / sqrt(2).
    let t = with_header(&(rect(0.0, 0.0, 1.0, 1.0, 0.0, "A") + &wall(0.1, 0.8, 0.8, 0.1, "W")));
    expect_error(&t, "walls[0]", "# W", "by 7.071e-2 m");
    ok(&with_header(
        &(rect(0.0, 0.0, 1.0, 1.0, 0.0, "A") + &wall(0.2, 0.9, 0.9, 0.2, "W")),
    ));
}

#[test]
fn generated_overlaps_name_the_generator_and_are_capped() {
    // A block covering a box of 300 generated disks: 300 overlapping pairs.
    let gen = "[[generators]]\nkind = \"box_of_disks\"\ncount = 300\nradius = [0.001, 0.002]\nbox = [[0.0, 0.0], [0.1, 0.2]]\nmaterial = \"glass\"\ngroup = \"g\"\n";
    let t = with_header(&(rect(0.05, 0.1, 0.1, 0.2, 0.0, "A") + gen));
    let e = errs(&t);
    let line = line_of(&t, "[[generators]]");
    let overlaps: Vec<_> =
        e.0.iter()
            .filter(|x| x.message.contains("overlaps"))
            .collect();
    assert_eq!(overlaps.len(), xper_scene::MAX_OVERLAP_REPORTS);
    assert!(overlaps
        .iter()
        .all(|x| x.field == "generators[0]" && x.line == line));
    assert!(
        overlaps[0].message.contains("(disk "),
        "{}",
        overlaps[0].message
    );
    assert!(
        e.0.iter()
            .any(|x| x.message.contains("more overlapping pairs")),
        "{e}"
    );
}

mod grid_vs_brute_force {
    use super::*;
    use proptest::prelude::*;
    use std::collections::BTreeSet;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// The grid finds exactly the overlapping pairs a brute-force search finds.
        #[test]
        fn same_pairs(d in prop::collection::vec((0.0f64..1.0, 0.0f64..1.0, 0.01f64..0.1), 1..40)) {
            let text: String = d.iter().map(|&(x, y, r)| disk(x, y, r, "D")).collect();
            let mut expected = BTreeSet::new();
            for i in 0..d.len() {
                for j in i + 1..d.len() {
                    let (xi, yi, ri) = d[i];
                    let (xj, yj, rj) = d[j];
                    let depth = ri + rj - (xi - xj).hypot(yi - yj);
                    let tol = 1e-9 + 1e-6 * (2.0 * ri).min(2.0 * rj);
                    if depth > tol {
                        expected.insert((i, j));
                    }
                }
            }
            let found: BTreeSet<(usize, usize)> = match parse(&with_header(&text)) {
                Ok(_) => BTreeSet::new(),
                Err(e) => e.0.iter().map(|x| {
                    let w: Vec<&str> = x.message.split_whitespace().collect();
                    let b: usize = w[1].parse().unwrap();
                    let a: usize = w[5].parse().unwrap();
                    (a, b)
                }).collect(),
            };
            prop_assume!(expected.len() <= xper_scene::MAX_OVERLAP_REPORTS);
            prop_assert_eq!(found, expected);
        }
    }
}
