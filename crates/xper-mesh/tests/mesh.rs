//! The mesh type: constructors and their checks, quality figures, adjacency, selectors.

use std::collections::BTreeSet;
use std::path::Path;

use xper_mesh::{
    read_msh, rectangle_with_inclusions, Mesh, MeshErrorKind, NodeSelector, RectangleSpec, Region,
};

fn one_region() -> Vec<Region> {
    vec![Region {
        name: "all".into(),
        tag: 1,
    }]
}

/// The unit square split along its diagonal, the second triangle given clockwise.
fn square() -> Mesh {
    let nodes = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    Mesh::new(nodes, vec![[0, 1, 2], [0, 3, 2]], vec![0, 0], one_region()).unwrap()
}

fn invalid(result: Result<Mesh, xper_mesh::MeshError>, words: &str) {
    let Err(err) = result else {
        panic!("accepted a mesh that should fail with `{words}`");
    };
    assert_eq!(err.kind, MeshErrorKind::Invalid, "{err}");
    assert!(err.to_string().contains(words), "`{err}` lacks `{words}`");
}

#[test]
fn clockwise_triangles_are_turned() {
    let mesh = square();
    assert_eq!(mesh.triangles[1], [0, 2, 3]);
    assert_eq!(mesh.triangle_area(0), 0.5);
    assert_eq!(mesh.triangle_area(1), 0.5);
    assert_eq!(mesh.area(), 1.0);
    assert_eq!(mesh.min_angle_degrees(), 45.0);
    let stats = mesh.edge_length_stats();
    assert_eq!(stats.count, 5);
    assert_eq!(stats.min, 1.0);
    assert_eq!(stats.max, 2f64.sqrt());
    assert!((stats.mean - (4.0 + 2f64.sqrt()) / 5.0).abs() < 1e-15);
}

#[test]
fn broken_meshes_are_refused() {
    let nodes = || vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let m = |nodes: Vec<[f64; 2]>, tris: Vec<[u32; 3]>| {
        let n = tris.len();
        Mesh::new(nodes, tris, vec![0; n], one_region())
    };
    invalid(m(nodes(), vec![[0, 1, 7]]), "node index 7 out of range");
    invalid(m(nodes(), vec![[0, 1, 1]]), "repeated");
    invalid(
        m(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], vec![[0, 1, 2]]),
        "degenerate",
    );
    invalid(
        m(
            vec![[0.0, 0.0], [1.0, f64::NAN], [2.0, 0.0]],
            vec![[0, 1, 2]],
        ),
        "non-finite",
    );
    let mut fan = nodes();
    fan.push([0.5, -1.0]);
    invalid(
        m(fan, vec![[0, 1, 2], [0, 1, 3], [0, 1, 4]]),
        "shared by three triangles",
    );
    invalid(
        Mesh::new(nodes(), vec![[0, 1, 2]], vec![3], one_region()),
        "region index 3 out of range",
    );
    invalid(
        Mesh::new(nodes(), vec![[0, 1, 2]], vec![], one_region()),
        "0 region indices for 1 triangles",
    );
}

#[test]
fn sets_are_checked_and_merged() {
    let mesh = square().with_edge_set("bottom", &[[1, 0]]).unwrap();
    assert_eq!(mesh.edge_set("bottom").unwrap(), &[[0, 1]]);
    assert_eq!(mesh.node_set("bottom").unwrap(), &[0, 1]);
    let mesh = mesh.with_node_set("bottom", &[3, 0]).unwrap();
    assert_eq!(mesh.node_set("bottom").unwrap(), &[0, 1, 3]);
    invalid(
        square().with_edge_set("x", &[[1, 3]]),
        "not the ends of an edge",
    );
    invalid(square().with_node_set("x", &[4]), "node 4 out of range");
    invalid(square().with_edge_set("", &[]), "non-empty name");
    invalid(mesh.clone().with_edge_set("bottom", &[]), "already exists");
    let err = mesh.edge_set("left").unwrap_err();
    assert_eq!(err.kind, MeshErrorKind::Selection);
    assert!(
        err.to_string()
            .contains("unknown edge set `left` (known: bottom)"),
        "{err}"
    );
}

#[test]
fn validate_sees_edits_of_the_public_fields() {
    let mut mesh = square();
    mesh.validate().unwrap();
    mesh.triangles[0] = [0, 2, 1];
    invalid(mesh.validate().map(|_| square()), "clockwise");
    let mut mesh = square().with_edge_set("bottom", &[[0, 1]]).unwrap();
    mesh.node_sets.insert("bottom".into(), vec![0]);
    invalid(mesh.validate().map(|_| square()), "node 1 missing");
}

/// Interior edges as (nodes, triangles, local edges).
type Interior = BTreeSet<([u32; 2], [u32; 2], [u8; 2])>;
/// Boundary edges as (nodes, triangle, local edge).
type Boundary = BTreeSet<([u32; 2], u32, u8)>;

/// All interior and boundary edges by comparing every pair of triangle edges: O(n^2).
fn brute_force(mesh: &Mesh) -> (Interior, Boundary) {
    let mut interior = BTreeSet::new();
    let mut boundary = BTreeSet::new();
    let edge = |t: usize, k: usize| {
        let tri = mesh.triangles[t];
        [tri[k], tri[(k + 1) % 3]]
    };
    for t in 0..mesh.triangles.len() {
        for k in 0..3 {
            let [a, b] = edge(t, k);
            let mut partner = None;
            for u in 0..mesh.triangles.len() {
                for l in 0..3 {
                    let [c, d] = edge(u, l);
                    if u != t && c == b && d == a {
                        partner = Some((u, l));
                    }
                }
            }
            match partner {
                Some((u, l)) if t < u => {
                    interior.insert((
                        [a.min(b), a.max(b)],
                        [t as u32, u as u32],
                        [k as u8, l as u8],
                    ));
                }
                Some(_) => {}
                None => {
                    boundary.insert(([a, b], t as u32, k as u8));
                }
            }
        }
    }
    (interior, boundary)
}

#[test]
fn neighbours_agree_with_brute_force() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let read = read_msh(&data.join("square_inclusion_ascii.msh")).unwrap();
    let generated = rectangle_with_inclusions(&RectangleSpec {
        width: 1.0,
        height: 0.5,
        inclusions: vec![[0.2, 0.1, 0.4, 0.3]],
        precrack: Some(([0.7, 0.0], [0.7, 0.2])),
        element_size: 0.08,
    })
    .unwrap();
    for mesh in [square(), read, generated] {
        let topo = mesh.neighbours().unwrap();
        let (interior, boundary) = brute_force(&mesh);
        let fast: BTreeSet<_> = topo
            .interior
            .iter()
            .map(|e| (e.nodes, e.triangles, e.local_edge))
            .collect();
        assert_eq!(fast.len(), topo.interior.len());
        assert_eq!(fast, interior);
        let fast: BTreeSet<_> = topo
            .boundary
            .iter()
            .map(|e| (e.nodes, e.triangle, e.local_edge))
            .collect();
        assert_eq!(fast.len(), topo.boundary.len());
        assert_eq!(fast, boundary);
        assert_eq!(mesh.neighbours().unwrap(), topo, "not deterministic");
    }
}

#[test]
fn edge_set_queries() {
    let mesh = rectangle_with_inclusions(&RectangleSpec {
        width: 1.0,
        height: 1.0,
        inclusions: vec![],
        precrack: Some(([0.5, 0.0], [0.5, 0.3])),
        element_size: 0.1,
    })
    .unwrap();
    let topo = mesh.neighbours().unwrap();
    let crack = topo.interior_on_edge_set(&mesh, "precrack").unwrap();
    assert_eq!(crack.len(), mesh.edge_set("precrack").unwrap().len());
    for &i in &crack {
        let e = topo.interior[i];
        assert!(e.nodes.iter().all(|&n| mesh.nodes[n as usize][0] == 0.5));
        assert_eq!(e.regions(&mesh), [0, 0]);
    }
    let bottom = topo.boundary_on_edge_set(&mesh, "bottom").unwrap();
    assert_eq!(bottom.len(), mesh.edge_set("bottom").unwrap().len());
    for &i in &bottom {
        let [a, b] = topo.boundary[i].nodes.map(|n| mesh.nodes[n as usize]);
        assert!(
            a[1] == 0.0 && b[1] == 0.0 && a[0] < b[0],
            "counter-clockwise along y = 0"
        );
    }
    assert!(topo
        .interior_on_edge_set(&mesh, "bottom")
        .unwrap()
        .is_empty());
    let err = topo.interior_on_edge_set(&mesh, "crack").unwrap_err();
    assert!(
        err.to_string()
            .contains("known: bottom, inclusion_boundary, left, precrack, right, top"),
        "{err}"
    );
    let inside = topo
        .interior_between_regions(&mesh, "matrix", "matrix")
        .unwrap();
    assert_eq!(inside.len(), topo.interior.len());
    assert!(topo
        .interior_between_regions(&mesh, "matrix", "inclusion")
        .unwrap()
        .is_empty());
    assert!(topo
        .interior_between_regions(&mesh, "matrix", "steel")
        .is_err());
}

#[test]
fn selectors() {
    let mesh = square().with_edge_set("left", &[[0, 3]]).unwrap();
    let set = |name: &str| NodeSelector::Set(name.into());
    assert_eq!(mesh.select_nodes(&set("left")).unwrap(), vec![0, 3]);
    let err = mesh.select_nodes(&set("right")).unwrap_err();
    assert_eq!(err.kind, MeshErrorKind::Selection);
    assert!(
        err.to_string()
            .contains("unknown node set `right` (known: left)"),
        "{err}"
    );
    let segment = |from, to, tolerance| NodeSelector::Segment {
        from,
        to,
        tolerance,
    };
    assert_eq!(
        mesh.select_nodes(&segment([1.0, 0.0], [1.0, 1.0], 0.0))
            .unwrap(),
        vec![1, 2]
    );
    assert_eq!(
        mesh.select_nodes(&segment([0.0, 0.0], [1.0, 1.0], 1e-12))
            .unwrap(),
        vec![0, 2]
    );
    assert_eq!(
        mesh.select_nodes(&segment([0.0, 0.5], [0.0, 0.6], 0.39))
            .unwrap(),
        vec![]
    );
    assert_eq!(
        mesh.select_nodes(&segment([0.0, 0.5], [0.0, 0.6], 0.45))
            .unwrap(),
        vec![3]
    );
    assert_eq!(
        mesh.select_nodes(&segment([0.0, 0.5], [0.0, 0.6], 0.5))
            .unwrap(),
        vec![0, 3]
    );
    assert!(mesh
        .select_nodes(&segment([0.0, 0.0], [1.0, 0.0], -1.0))
        .is_err());
    assert!(mesh
        .select_nodes(&segment([0.0, f64::NAN], [1.0, 0.0], 1.0))
        .is_err());
    let boxed = |min, max| NodeSelector::Box { min, max };
    assert_eq!(
        mesh.select_nodes(&boxed([0.5, -1.0], [2.0, 2.0])).unwrap(),
        vec![1, 2]
    );
    assert_eq!(
        mesh.select_nodes(&boxed([0.0, 0.0], [0.0, 0.0])).unwrap(),
        vec![0]
    );
    assert_eq!(
        mesh.select_nodes(&boxed([2.0, 2.0], [3.0, 3.0])).unwrap(),
        vec![]
    );
    let err = mesh
        .select_nodes(&boxed([1.0, 0.0], [0.0, 1.0]))
        .unwrap_err();
    assert!(err.to_string().contains("exceeds"), "{err}");
}
