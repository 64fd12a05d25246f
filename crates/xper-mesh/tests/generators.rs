//! The specimen generators against the exact geometry of their domains.
//!
//! Bounds checked: min angle >= MIN_ANGLE_DEGREES - 0.5 degree; longest edge <= 1.5 h.

use xper_mesh::{
    double_edge_notched, rectangle_with_inclusions, Mesh, MeshErrorKind, NotchedSpec,
    RectangleSpec, MIN_ANGLE_DEGREES,
};

const ANGLE_MARGIN: f64 = 0.5;
const MAX_EDGE_OVER_H: f64 = 1.5;
/// Smallest angle of a point-symmetric mesh (degrees): the seam's triangles are not refined.
const SYMMETRIC_MIN_ANGLE: f64 = 15.0;

fn length(mesh: &Mesh, e: [u32; 2]) -> f64 {
    let (a, b) = (mesh.nodes[e[0] as usize], mesh.nodes[e[1] as usize]);
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

fn set_length(mesh: &Mesh, name: &str) -> f64 {
    mesh.edge_set(name)
        .unwrap()
        .iter()
        .map(|&e| length(mesh, e))
        .sum()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}

/// Quality, Euler's formula (no hole) and manifoldness; returns the topology.
fn check_common(mesh: &Mesh, h: f64) -> xper_mesh::Topology {
    check_common_with(mesh, h, MIN_ANGLE_DEGREES - ANGLE_MARGIN)
}

/// [`check_common`] with another smallest angle (degrees).
fn check_common_with(mesh: &Mesh, h: f64, min_angle: f64) -> xper_mesh::Topology {
    mesh.validate().unwrap();
    let angle = mesh.min_angle_degrees();
    assert!(angle >= min_angle, "min angle {angle}");
    let stats = mesh.edge_length_stats();
    assert!(
        stats.max <= MAX_EDGE_OVER_H * h,
        "longest edge {} h",
        stats.max / h
    );
    let topo = mesh.neighbours().unwrap();
    for e in &topo.interior {
        for (side, &t) in e.triangles.iter().enumerate() {
            let tri = mesh.triangles[t as usize];
            let k = e.local_edge[side] as usize;
            let mut nodes = [tri[k], tri[(k + 1) % 3]];
            nodes.sort_unstable();
            assert_eq!(nodes, e.nodes);
        }
    }
    let (v, f) = (mesh.nodes.len() as i64, mesh.triangles.len() as i64);
    let edges = (topo.interior.len() + topo.boundary.len()) as i64;
    assert_eq!(
        v - edges + f,
        1,
        "Euler characteristic of a disk without holes"
    );
    assert_eq!(stats.count as i64, edges);
    topo
}

/// Every boundary edge lies in exactly one of `sets`, and the sets hold only boundary edges.
fn check_boundary_partition(mesh: &Mesh, topo: &xper_mesh::Topology, sets: &[&str]) {
    let mut from_sets: Vec<[u32; 2]> = sets
        .iter()
        .flat_map(|s| mesh.edge_set(s).unwrap().iter().copied())
        .collect();
    from_sets.sort_unstable();
    let mut boundary: Vec<[u32; 2]> = topo
        .boundary
        .iter()
        .map(|e| [e.nodes[0].min(e.nodes[1]), e.nodes[0].max(e.nodes[1])])
        .collect();
    boundary.sort_unstable();
    assert_eq!(from_sets, boundary);
}

fn notched(h: f64) -> NotchedSpec {
    NotchedSpec {
        side: 0.2,
        notch_depth: 0.025,
        notch_width: 0.005,
        element_size: h,
        point_symmetric: false,
    }
}

fn check_notched(spec: &NotchedSpec) -> Mesh {
    let mesh = double_edge_notched(spec).unwrap();
    let (s, d, w, h) = (
        spec.side,
        spec.notch_depth,
        spec.notch_width,
        spec.element_size,
    );
    let min_angle = if spec.point_symmetric {
        SYMMETRIC_MIN_ANGLE
    } else {
        MIN_ANGLE_DEGREES - ANGLE_MARGIN
    };
    let topo = check_common_with(&mesh, h, min_angle);
    assert!(
        close(mesh.area(), s * s - 2.0 * d * w, 1e-12),
        "area {}",
        mesh.area()
    );
    assert_eq!(mesh.regions.len(), 1);
    assert_eq!(mesh.regions[0].name, "concrete");
    let (lo, hi) = ((s - w) / 2.0, (s + w) / 2.0);
    for p in &mesh.nodes {
        let in_notch = p[1] > lo && p[1] < hi && (p[0] < d || p[0] > s - d);
        assert!(!in_notch, "node {p:?} inside a notch");
    }
    let on = |name: &str, len: f64, test: &dyn Fn([f64; 2]) -> bool| {
        assert!(close(set_length(&mesh, name), len, 1e-12), "{name}");
        for &n in mesh.node_set(name).unwrap() {
            assert!(
                test(mesh.nodes[n as usize]),
                "{name}: {:?}",
                mesh.nodes[n as usize]
            );
        }
    };
    on("bottom", s, &|p| p[1] == 0.0);
    on("top", s, &|p| p[1] == s);
    on("left_lower", lo, &|p| p[0] == 0.0 && p[1] <= lo);
    on("left_upper", s - hi, &|p| p[0] == 0.0 && p[1] >= hi);
    on("right_lower", lo, &|p| p[0] == s && p[1] <= lo);
    on("right_upper", s - hi, &|p| p[0] == s && p[1] >= hi);
    let face = |x_mouth: f64, x_tip: f64| {
        move |p: [f64; 2]| {
            let (x0, x1) = (x_mouth.min(x_tip), x_mouth.max(x_tip));
            ((p[1] == lo || p[1] == hi) && p[0] >= x0 && p[0] <= x1)
                || (p[0] == x_tip && p[1] >= lo && p[1] <= hi)
        }
    };
    on("notch_left", 2.0 * d + w, &face(0.0, d));
    on("notch_right", 2.0 * d + w, &face(s, s - d));
    check_boundary_partition(
        &mesh,
        &topo,
        &[
            "bottom",
            "top",
            "left_lower",
            "left_upper",
            "right_lower",
            "right_upper",
            "notch_left",
            "notch_right",
        ],
    );
    mesh
}

fn bimaterial(h: f64) -> RectangleSpec {
    RectangleSpec {
        width: 5e-5,
        height: 5e-5,
        inclusions: vec![
            [0.5e-5, 3.0e-5, 1.5e-5, 4.0e-5],
            [2.0e-5, 2.0e-5, 3.0e-5, 3.0e-5],
            [3.5e-5, 0.8e-5, 4.5e-5, 1.8e-5],
        ],
        precrack: Some(([2.5e-5, 0.0], [2.5e-5, 0.5e-5])),
        element_size: h,
    }
}

fn check_rectangle(spec: &RectangleSpec) -> Mesh {
    let mesh = rectangle_with_inclusions(spec).unwrap();
    let (w, ht, h) = (spec.width, spec.height, spec.element_size);
    let topo = check_common(&mesh, h);
    assert!(close(mesh.area(), w * ht, 1e-12));
    let inclusions: f64 = spec
        .inclusions
        .iter()
        .map(|r| (r[2] - r[0]) * (r[3] - r[1]))
        .sum();
    let perimeters: f64 = spec
        .inclusions
        .iter()
        .map(|r| 2.0 * (r[2] - r[0] + r[3] - r[1]))
        .sum();
    let areas = mesh.region_areas();
    assert_eq!(mesh.region_index("matrix").unwrap(), 0);
    assert_eq!(mesh.region_index("inclusion").unwrap(), 1);
    assert!(
        close(areas[1], inclusions, 1e-12),
        "{} vs {inclusions}",
        areas[1]
    );
    assert!(close(areas[0], w * ht - inclusions, 1e-12));
    let on = |name: &str, len: f64, test: &dyn Fn([f64; 2]) -> bool| {
        assert!(close(set_length(&mesh, name), len, 1e-12), "{name}");
        for &n in mesh.node_set(name).unwrap() {
            assert!(
                test(mesh.nodes[n as usize]),
                "{name}: {:?}",
                mesh.nodes[n as usize]
            );
        }
    };
    on("left", ht, &|p| p[0] == 0.0);
    on("right", ht, &|p| p[0] == w);
    on("bottom", w, &|p| p[1] == 0.0);
    on("top", w, &|p| p[1] == ht);
    on("inclusion_boundary", perimeters, &|p| {
        spec.inclusions.iter().any(|r| {
            ((p[0] == r[0] || p[0] == r[2]) && p[1] >= r[1] && p[1] <= r[3])
                || ((p[1] == r[1] || p[1] == r[3]) && p[0] >= r[0] && p[0] <= r[2])
        })
    });
    check_boundary_partition(&mesh, &topo, &["left", "right", "bottom", "top"]);
    let mut between = topo
        .interior_between_regions(&mesh, "matrix", "inclusion")
        .unwrap();
    let mut outline = topo
        .interior_on_edge_set(&mesh, "inclusion_boundary")
        .unwrap();
    between.sort_unstable();
    outline.sort_unstable();
    assert_eq!(between, outline);
    assert_eq!(
        outline.len(),
        mesh.edge_set("inclusion_boundary").unwrap().len()
    );
    let crack = topo.interior_on_edge_set(&mesh, "precrack").unwrap();
    assert_eq!(crack.len(), mesh.edge_set("precrack").unwrap().len());
    mesh
}

#[test]
fn notched_specimen_is_exact() {
    let spec = notched(5e-3);
    let mesh = check_notched(&spec);
    assert!(
        mesh.triangles.len() > 4000,
        "{} triangles",
        mesh.triangles.len()
    );
    assert_eq!(
        mesh,
        double_edge_notched(&spec).unwrap(),
        "not deterministic"
    );
}

#[test]
fn bimaterial_specimen_is_exact() {
    let spec = bimaterial(1e-6);
    let mesh = check_rectangle(&spec);
    let (a, b) = spec.precrack.unwrap();
    let length = b[1] - a[1];
    assert!(close(set_length(&mesh, "precrack"), length, 1e-12));
    for &n in mesh.node_set("precrack").unwrap() {
        let p = mesh.nodes[n as usize];
        assert!(p[0] == a[0] && p[1] >= a[1] && p[1] <= b[1], "{p:?}");
    }
    assert_eq!(
        mesh,
        rectangle_with_inclusions(&spec).unwrap(),
        "not deterministic"
    );
}

#[test]
fn slanted_precrack_and_no_inclusion() {
    let spec = RectangleSpec {
        width: 2.0,
        height: 1.0,
        inclusions: vec![],
        precrack: Some(([0.5, 0.0], [0.8, 0.4])),
        element_size: 0.05,
    };
    let mesh = check_rectangle(&spec);
    assert_eq!(mesh.region_areas()[1], 0.0);
    assert!(mesh.edge_set("inclusion_boundary").unwrap().is_empty());
    assert!(close(set_length(&mesh, "precrack"), 0.5, 1e-9));
    for &n in mesh.node_set("precrack").unwrap() {
        let p = mesh.nodes[n as usize];
        let cross = (p[0] - 0.5) * 0.4 - p[1] * 0.3;
        assert!(cross.abs() < 1e-12 && p[1] >= 0.0 && p[1] <= 0.4, "{p:?}");
    }
}

#[test]
fn paper_sizes() {
    let mesh = check_notched(&notched(2e-3));
    eprintln!(
        "double_edge_notched h = 2 mm: {} triangles, min angle {:.2}",
        mesh.triangles.len(),
        mesh.min_angle_degrees()
    );
    let mesh = check_rectangle(&bimaterial(5e-7));
    eprintln!(
        "rectangle_with_inclusions h = 5e-7 m: {} triangles, min angle {:.2}",
        mesh.triangles.len(),
        mesh.min_angle_degrees()
    );
}

fn spec_error(result: Result<Mesh, xper_mesh::MeshError>, origin: &str, words: &str) {
    let Err(err) = result else {
        panic!("accepted a spec that should fail with `{words}`");
    };
    assert_eq!(err.kind, MeshErrorKind::Spec, "{err}");
    let text = err.to_string();
    assert!(text.starts_with(origin), "{text}");
    assert!(text.contains(words), "`{text}` lacks `{words}`");
}

#[test]
fn bad_rectangle_specs_are_refused() {
    let origin = "rectangle_with_inclusions";
    let with = |f: &dyn Fn(&mut RectangleSpec)| {
        let mut spec = bimaterial(2e-6);
        f(&mut spec);
        rectangle_with_inclusions(&spec)
    };
    spec_error(
        with(&|s| s.width = -1.0),
        origin,
        "width: must be finite and positive",
    );
    spec_error(with(&|s| s.element_size = f64::NAN), origin, "element_size");
    spec_error(with(&|s| s.element_size = 1e-12), origin, "check the units");
    spec_error(
        with(&|s| s.inclusions.push([4e-5, 4e-5, 6e-5, 4.5e-5])),
        origin,
        "strictly inside",
    );
    spec_error(
        with(&|s| s.inclusions.push([0.0, 1e-6, 1e-6, 2e-6])),
        origin,
        "strictly inside",
    );
    spec_error(
        with(&|s| s.inclusions.push([1e-5, 1e-6, 0.5e-5, 2e-6])),
        origin,
        "xmin < xmax",
    );
    spec_error(
        with(&|s| s.inclusions.push([2.5e-5, 2.5e-5, 3.2e-5, 3.2e-5])),
        origin,
        "inclusions[3] = [2.5e-5, 2.5e-5, 3.2e-5, 3.2e-5]: overlaps or touches inclusions[1]",
    );
    spec_error(
        with(&|s| s.inclusions.push([3.6e-5, 1.7e-5, 3.8e-5, 1.9e-5])),
        origin,
        "inclusions[3] = [3.6e-5, 1.7e-5, 3.8e-5, 1.9e-5]: overlaps or touches inclusions[2]",
    );
    spec_error(
        with(&|s| s.precrack = Some(([2.5e-5, 0.0], [2.5e-5, 2.2e-5]))),
        origin,
        "meets inclusions[1]",
    );
    spec_error(
        with(&|s| s.precrack = Some(([0.0, 0.0], [0.0, 1e-5]))),
        origin,
        "along a side",
    );
    spec_error(
        with(&|s| s.precrack = Some(([1e-5, -1e-6], [1e-5, 1e-5]))),
        origin,
        "inside",
    );
    spec_error(
        with(&|s| s.precrack = Some(([1e-5, 0.0], [1e-5, 0.0]))),
        origin,
        "distinct",
    );
}

#[test]
fn touching_inclusions_are_refused() {
    let mut spec = bimaterial(2e-6);
    spec.inclusions = vec![[1e-5, 1e-5, 2e-5, 2e-5], [2e-5, 1e-5, 3e-5, 2e-5]];
    spec_error(
        rectangle_with_inclusions(&spec),
        "rectangle_with_inclusions",
        "touches",
    );
}

#[test]
fn bad_notched_specs_are_refused() {
    let origin = "double_edge_notched";
    let with = |f: &dyn Fn(&mut NotchedSpec)| {
        let mut spec = notched(1e-2);
        f(&mut spec);
        double_edge_notched(&spec)
    };
    spec_error(with(&|s| s.side = 0.0), origin, "side");
    spec_error(with(&|s| s.notch_depth = 0.1), origin, "would meet");
    spec_error(with(&|s| s.notch_width = 0.3), origin, "would cut");
    spec_error(
        with(&|s| s.element_size = f64::INFINITY),
        origin,
        "element_size",
    );
}

/// Regression (Nooru-Mohamed's anti-symmetric cracks came out lopsided on a mesh without
/// symmetry): the point-symmetric mesh of the notched square maps onto itself under the
/// half-turn about the centre, node for node and triangle for triangle, and keeps the exact
/// geometry of the plain mesh.
#[test]
fn point_symmetric_notched_square_is_its_own_half_turn() {
    for h in [8e-3, 4e-3] {
        let spec = NotchedSpec {
            point_symmetric: true,
            ..notched(h)
        };
        let mesh = check_notched(&spec);
        let s = spec.side;
        let image_of = |p: [f64; 2]| {
            let q = [s - p[0], s - p[1]];
            (mesh.nodes.iter())
                .position(|n| (n[0] - q[0]).abs() <= 1e-12 && (n[1] - q[1]).abs() <= 1e-12)
                .unwrap_or_else(|| panic!("h = {h}: node {p:?} has no image"))
        };
        let image: Vec<usize> = mesh.nodes.iter().map(|&p| image_of(p)).collect();
        let sorted = |t: [u32; 3]| {
            let mut k = t.map(|i| i as usize);
            k.sort_unstable();
            k
        };
        let triangles: std::collections::HashSet<[usize; 3]> =
            mesh.triangles.iter().map(|&t| sorted(t)).collect();
        for t in &mesh.triangles {
            let mut k = sorted(*t).map(|i| image[i]);
            k.sort_unstable();
            assert!(
                triangles.contains(&k),
                "h = {h}: triangle {t:?} has no image"
            );
        }
    }
}
