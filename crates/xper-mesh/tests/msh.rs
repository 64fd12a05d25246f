//! Reading the committed Gmsh files of `tests/data` (written by `tools/make_test_meshes.py`):
//! the unit square with the inclusion [0.3, 0.6] x [0.3, 0.5].

use std::path::{Path, PathBuf};
use std::process::Command;

use xper_mesh::{read_msh, Mesh};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

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

/// Checks everything the geometry fixes exactly, for the given names.
fn check_square(mesh: &Mesh, regions: [&str; 2], sides: [&str; 5], origin: &str) {
    mesh.validate().unwrap();
    assert_eq!(mesh.regions.len(), 2);
    assert_eq!(mesh.regions[0].name, regions[0]);
    assert_eq!(mesh.regions[0].tag, 1);
    assert_eq!(mesh.regions[1].name, regions[1]);
    assert_eq!(mesh.regions[1].tag, 2);
    let areas = mesh.region_areas();
    assert!((areas[0] - 0.94).abs() < 1e-12, "matrix area {}", areas[0]);
    assert!(
        (areas[1] - 0.06).abs() < 1e-12,
        "inclusion area {}",
        areas[1]
    );
    assert!((mesh.area() - 1.0).abs() < 1e-12);
    for t in 0..mesh.triangles.len() {
        assert!(
            mesh.triangle_area(t) > 0.0,
            "triangle {t} is not counter-clockwise"
        );
    }
    let [left, right, bottom, top, inclusion] = sides;
    let on = |name: &str, test: &dyn Fn([f64; 2]) -> bool| {
        let nodes = mesh.node_set(name).unwrap();
        assert!(!nodes.is_empty(), "{name} is empty");
        for &n in nodes {
            assert!(test(mesh.nodes[n as usize]), "node {n} of {name} misplaced");
        }
    };
    on(left, &|p| p[0] == 0.0);
    on(right, &|p| p[0] == 1.0);
    on(bottom, &|p| p[1] == 0.0);
    on(top, &|p| p[1] == 1.0);
    on(inclusion, &|p| {
        let on_x = (p[0] - 0.3).abs() < 1e-15 || (p[0] - 0.6).abs() < 1e-15;
        let on_y = (p[1] - 0.3).abs() < 1e-15 || (p[1] - 0.5).abs() < 1e-15;
        (on_x && p[1] >= 0.3 - 1e-15 && p[1] <= 0.5 + 1e-15)
            || (on_y && p[0] >= 0.3 - 1e-15 && p[0] <= 0.6 + 1e-15)
    });
    for side in [left, right, bottom, top] {
        assert!((set_length(mesh, side) - 1.0).abs() < 1e-12, "{side}");
    }
    assert!((set_length(mesh, inclusion) - 1.0).abs() < 1e-12);
    let corner = mesh.node_set(origin).unwrap();
    assert_eq!(corner.len(), 1);
    assert_eq!(mesh.nodes[corner[0] as usize], [0.0, 0.0]);

    // The inclusion outline is exactly the set of interfaces between the two regions.
    let topo = mesh.neighbours().unwrap();
    let mut between = topo
        .interior_between_regions(mesh, regions[0], regions[1])
        .unwrap();
    let mut on_outline = topo.interior_on_edge_set(mesh, inclusion).unwrap();
    between.sort_unstable();
    on_outline.sort_unstable();
    assert!(!between.is_empty());
    assert_eq!(between, on_outline);
    let perimeter: f64 = topo.boundary.iter().map(|e| length(mesh, e.nodes)).sum();
    assert!((perimeter - 4.0).abs() < 1e-12);
}

const NAMED: ([&str; 2], [&str; 5], &str) = (
    ["matrix", "inclusion"],
    ["left", "right", "bottom", "top", "inclusion_boundary"],
    "origin",
);

#[test]
fn ascii_file_has_named_regions_sets_and_areas() {
    let mesh = read_msh(&data("square_inclusion_ascii.msh")).unwrap();
    let (r, s, o) = NAMED;
    check_square(&mesh, r, s, o);
}

#[test]
fn binary_file_gives_the_ascii_mesh() {
    let ascii = read_msh(&data("square_inclusion_ascii.msh")).unwrap();
    let binary = read_msh(&data("square_inclusion_binary.msh")).unwrap();
    let (r, s, o) = NAMED;
    check_square(&binary, r, s, o);
    assert_eq!(ascii.triangles, binary.triangles);
    assert_eq!(ascii.triangle_region, binary.triangle_region);
    assert_eq!(ascii.regions, binary.regions);
    assert_eq!(ascii.edge_sets, binary.edge_sets);
    assert_eq!(ascii.node_sets, binary.node_sets);
    assert_eq!(ascii.nodes.len(), binary.nodes.len());
    // Gmsh prints 16 significant digits in ASCII files: equal to 1e-15 relative.
    for (a, b) in ascii.nodes.iter().zip(&binary.nodes) {
        assert!((a[0] - b[0]).abs() <= 1e-15 && (a[1] - b[1]).abs() <= 1e-15);
    }
}

#[test]
fn unnamed_groups_take_their_tags() {
    let mesh = read_msh(&data("unnamed_groups.msh")).unwrap();
    check_square(
        &mesh,
        ["region_1", "region_2"],
        ["line_11", "line_12", "line_13", "line_14", "line_15"],
        "point_21",
    );
}

#[test]
fn file_without_groups_is_one_domain() {
    let mesh = read_msh(&data("no_groups.msh")).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.regions.len(), 1);
    assert_eq!(mesh.regions[0].name, "domain");
    assert!(mesh.edge_sets.is_empty());
    assert!(mesh.node_sets.is_empty());
    assert!((mesh.area() - 1.0).abs() < 1e-12);
    let named = read_msh(&data("square_inclusion_ascii.msh")).unwrap();
    assert_eq!(mesh.triangles.len(), named.triangles.len());
}

#[test]
fn a_fresh_gmsh_run_reads_the_same_when_gmsh_is_installed() {
    let has_gmsh = Command::new("python3")
        .args(["-c", "import gmsh"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !has_gmsh {
        eprintln!("skipped: the gmsh Python package is not installed");
        return;
    }
    let out = std::env::temp_dir().join(format!("xper-mesh-gmsh-{}", std::process::id()));
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tools/make_test_meshes.py");
    let status = Command::new("python3")
        .arg(&script)
        .arg("--out")
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success(), "{} failed", script.display());
    for name in ["square_inclusion_ascii.msh", "square_inclusion_binary.msh"] {
        let mesh = read_msh(&out.join(name)).unwrap();
        let (r, s, o) = NAMED;
        check_square(&mesh, r, s, o);
    }
    std::fs::remove_dir_all(&out).unwrap();
}
