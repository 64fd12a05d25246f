//! Meshes the two specimens of the paper and prints triangle counts, meshing times and
//! quality figures: `cargo run --release -p xper-mesh --example specimens [scale]`, where
//! `scale` (default 1) divides the element sizes.

use std::time::Instant;

use xper_mesh::{double_edge_notched, rectangle_with_inclusions, Mesh, NotchedSpec, RectangleSpec};

fn report(name: &str, h: f64, run: impl Fn() -> Result<Mesh, xper_mesh::MeshError>) {
    let start = Instant::now();
    let mesh = match run() {
        Ok(mesh) => mesh,
        Err(e) => {
            eprintln!("{name}: {e}");
            std::process::exit(1);
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let topology = mesh.neighbours().expect("a generated mesh is manifold");
    let adjacency = start.elapsed().as_secs_f64();
    let stats = mesh.edge_length_stats();
    // FNV-1a of the coordinates and triangles: equal across runs when meshing is deterministic.
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let words = (mesh.nodes.iter().flatten().map(|v| v.to_bits()))
        .chain(mesh.triangles.iter().flatten().map(|&n| u64::from(n)));
    for w in words {
        hash = (hash ^ w).wrapping_mul(0x100_0000_01b3);
    }
    println!(
        "{name}: h = {h:e} m, {} triangles, {} nodes, {} interfaces, meshed in {seconds:.3} s, \
         adjacency in {adjacency:.3} s, min angle {:.2} deg, edge length min/mean/max = \
         {:.3}/{:.3}/{:.3} h, checksum {hash:016x}",
        mesh.triangles.len(),
        mesh.nodes.len(),
        topology.interior.len(),
        mesh.min_angle_degrees(),
        stats.min / h,
        stats.mean / h,
        stats.max / h,
    );
}

fn main() {
    let scale: f64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0);
    let h = 2e-3 / scale;
    report("double_edge_notched", h, || {
        double_edge_notched(&NotchedSpec {
            side: 0.2,
            notch_depth: 0.025,
            notch_width: 0.005,
            element_size: h,
            point_symmetric: false,
        })
    });
    let h = 5e-7 / scale;
    report("rectangle_with_inclusions", h, || {
        rectangle_with_inclusions(&RectangleSpec {
            width: 5e-5,
            height: 5e-5,
            inclusions: vec![
                [0.5e-5, 3.0e-5, 1.5e-5, 4.0e-5],
                [2.0e-5, 2.0e-5, 3.0e-5, 3.0e-5],
                [3.5e-5, 0.8e-5, 4.5e-5, 1.8e-5],
            ],
            precrack: Some(([2.5e-5, 0.0], [2.5e-5, 0.5e-5])),
            element_size: h,
        })
    });
}
