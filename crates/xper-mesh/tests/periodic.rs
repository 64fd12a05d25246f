//! Periodic cells: the generator against the exact geometry of its inclusions and the matching
//! of opposite sides, and the errors of a mesh whose sides do not match.

use xper_mesh::{
    periodic_cell, Circle, Mesh, MeshErrorKind, PeriodicCell, PeriodicCellSpec, RandomCircles,
    Region,
};

fn spec(h: f64) -> PeriodicCellSpec {
    PeriodicCellSpec {
        width: 1.0,
        height: 0.8,
        circles: Vec::new(),
        rectangles: Vec::new(),
        random: None,
        element_size: h,
    }
}

fn unit_cell(mesh: &Mesh) -> PeriodicCell {
    PeriodicCell {
        lower: [0.0, 0.0],
        size: [mesh.nodes.iter().map(|p| p[0]).fold(0.0, f64::max), 0.8],
    }
}

/// Every side edge is matched once, images are the same points shifted by the period, and
/// the matched edges cover the four sides.
fn check_matching(mesh: &Mesh) {
    let cell = unit_cell(mesh);
    let pairs = mesh.periodic_edges(&cell).unwrap();
    let mut covered = [0.0; 2];
    for p in &pairs {
        for [a, b] in p.nodes {
            let (xa, xb) = (mesh.nodes[a as usize], mesh.nodes[b as usize]);
            assert_eq!(xb[0] - xa[0], p.period[0]);
            assert_eq!(xb[1] - xa[1], p.period[1]);
        }
        let axis = usize::from(p.period[1] != 0.0);
        covered[axis] += p.length;
        assert_eq!(p.normal[axis], -1.0);
    }
    assert!((covered[0] - cell.size[1]).abs() < 1e-12, "{covered:?}");
    assert!((covered[1] - cell.size[0]).abs() < 1e-12, "{covered:?}");
    let left = mesh.edge_set("left").unwrap().len();
    let bottom = mesh.edge_set("bottom").unwrap().len();
    assert_eq!(pairs.len(), left + bottom);
}

#[test]
fn plain_cell_matches_its_sides() {
    let mesh = periodic_cell(&spec(0.1)).unwrap();
    mesh.validate().unwrap();
    check_matching(&mesh);
    assert!((mesh.area() - 0.8).abs() < 1e-12);
    assert!(
        mesh.min_angle_degrees() > 20.0,
        "{}",
        mesh.min_angle_degrees()
    );
}

/// A circle centred on the left side and one on a corner wrap across the sides: the
/// inclusion's area is that of the two inscribed polygons, as if each were whole.
#[test]
fn circles_wrap_across_sides() {
    let h = 0.04;
    let mut s = spec(h);
    s.circles = vec![
        Circle {
            center: [0.0, 0.4],
            radius: 0.15,
        },
        Circle {
            center: [1.0, 0.8],
            radius: 0.12,
        },
    ];
    let mesh = periodic_cell(&s).unwrap();
    check_matching(&mesh);
    let polygon_area = |r: f64| {
        let n = ((std::f64::consts::TAU * r / h).ceil() as usize).max(16) as f64;
        0.5 * n * r * r * (std::f64::consts::TAU / n).sin()
    };
    let expected = polygon_area(0.15) + polygon_area(0.12);
    let areas = mesh.region_areas();
    assert!(
        (areas[1] - expected).abs() < 1e-12 * expected.max(1.0),
        "{} vs {expected}",
        areas[1]
    );
    assert!((areas[0] + areas[1] - 0.8).abs() < 1e-12);
    let near = |x: f64, y: f64| {
        (0..mesh.triangles.len()).any(|t| {
            let c = mesh.triangles[t].map(|n| mesh.nodes[n as usize]);
            let cx = (c[0][0] + c[1][0] + c[2][0]) / 3.0;
            let cy = (c[0][1] + c[1][1] + c[2][1]) / 3.0;
            mesh.triangle_region[t] == 1 && (cx - x).abs() < 0.05 && (cy - y).abs() < 0.05
        })
    };
    for (x, y) in [
        (0.02, 0.4),
        (0.98, 0.4),
        (0.02, 0.02),
        (0.98, 0.78),
        (0.02, 0.78),
    ] {
        assert!(near(x, y), "no inclusion triangle near ({x}, {y})");
    }
}

/// Random circles: the count the fraction asks for, no two closer than the spacing
/// (periodically), the same cell for the same seed and another for another seed.
#[test]
fn random_circles_reach_the_fraction() {
    let mut s = spec(0.02);
    let r = 0.06;
    s.random = Some(RandomCircles {
        fraction: 0.2,
        radius: r,
        min_spacing: 0.01,
        seed: 7,
    });
    let mesh = periodic_cell(&s).unwrap();
    check_matching(&mesh);
    let n = (0.2 * 0.8 / (std::f64::consts::PI * r * r)).round();
    let poly = {
        let m = ((std::f64::consts::TAU * r / 0.02).ceil() as usize).max(16) as f64;
        0.5 * m * r * r * (std::f64::consts::TAU / m).sin()
    };
    let areas = mesh.region_areas();
    assert!(
        (areas[1] - n * poly).abs() < 1e-10,
        "{} vs {}",
        areas[1],
        n * poly
    );
    assert_eq!(periodic_cell(&s).unwrap(), mesh);
    s.random.as_mut().unwrap().seed = 8;
    assert_ne!(periodic_cell(&s).unwrap().nodes, mesh.nodes);
}

#[test]
fn bad_specs_are_refused() {
    let mut s = spec(0.05);
    s.circles = vec![Circle {
        center: [0.5, 0.4],
        radius: 0.45,
    }];
    let e = periodic_cell(&s).unwrap_err();
    assert_eq!(e.kind, MeshErrorKind::Spec);
    assert!(e.to_string().contains("circles[0]"), "{e}");
    s.circles = vec![Circle {
        center: [0.1, 0.4],
        radius: 0.1 + 0.01,
    }];
    let e = periodic_cell(&s).unwrap_err();
    assert!(e.to_string().contains("within h/2"), "{e}");
    s.circles = vec![
        Circle {
            center: [0.05, 0.4],
            radius: 0.2,
        },
        Circle {
            center: [0.75, 0.4],
            radius: 0.2,
        },
    ];
    let e = periodic_cell(&s).unwrap_err();
    assert!(e.to_string().contains("overlaps"), "{e}");
    s.circles.clear();
    s.random = Some(RandomCircles {
        fraction: 0.55,
        radius: 0.2,
        min_spacing: 0.1,
        seed: 1,
    });
    let e = periodic_cell(&s).unwrap_err();
    assert!(e.to_string().contains("attempts"), "{e}");
}

/// Two triangles whose left and right sides carry different nodes: the error names the
/// unmatched node and its place.
#[test]
fn unmatched_nodes_are_named() {
    let nodes = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.4]];
    let triangles = vec![[0, 1, 4], [0, 4, 2], [0, 2, 3]];
    let regions = vec![Region {
        name: "all".into(),
        tag: 1,
    }];
    let mesh = Mesh::new(nodes, triangles, vec![0; 3], regions).unwrap();
    let cell = PeriodicCell {
        lower: [0.0, 0.0],
        size: [1.0, 1.0],
    };
    let e = mesh.periodic_edges(&cell).unwrap_err();
    assert_eq!(e.kind, MeshErrorKind::Invalid);
    assert!(e.to_string().contains("node 4 at (1, 0.4)"), "{e}");
    let wrong = PeriodicCell {
        lower: [0.0, 0.0],
        size: [1.0, 2.0],
    };
    let e = mesh.periodic_edges(&wrong).unwrap_err();
    assert!(e.to_string().contains("spans"), "{e}");
}

fn data(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Gmsh files: a grid whose sides match is a periodic cell (2 + 2 edge pairs), and so is the
/// unit square with an inclusion (its sides are cut alike); moving one node of its right side
/// by 1e-3 breaks the match, and the error names that node.
#[test]
fn gmsh_meshes_are_checked() {
    let grid = xper_mesh::read_msh(&data("periodic_grid.msh")).unwrap();
    let pairs = grid.periodic_edges(&PeriodicCell::bounding(&grid)).unwrap();
    assert_eq!(pairs.len(), 4);
    assert_eq!(pairs.iter().filter(|p| p.period == [1.0, 0.0]).count(), 2);
    let mut square = xper_mesh::read_msh(&data("square_inclusion_ascii.msh")).unwrap();
    let cell = PeriodicCell::bounding(&square);
    let pairs = square.periodic_edges(&cell).unwrap();
    let sides = ["left", "bottom"].map(|s| square.edge_set(s).unwrap().len());
    assert_eq!(pairs.len(), sides[0] + sides[1]);
    let moved = (0..square.nodes.len())
        .find(|&n| {
            square.nodes[n][0] == 1.0 && square.nodes[n][1] > 0.2 && square.nodes[n][1] < 0.8
        })
        .unwrap();
    square.nodes[moved][1] += 1e-3;
    let e = square.periodic_edges(&cell).unwrap_err();
    assert_eq!(e.kind, MeshErrorKind::Invalid);
    assert!(
        e.to_string().contains(&format!("node {moved} at (1, ")),
        "{e}"
    );
}
