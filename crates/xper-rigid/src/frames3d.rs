//! VTU frames of a 3D world: spheres as points carrying their radius (for ParaView's glyphs),
//! polyhedra as closed surfaces (one polygon per face), walls as rectangles (half-spaces drawn
//! over the extent of the bodies), contacts as points and force chains as lines.

use super::contacts_grid;
use crate::run_outputs::{f64_array, i32_array};
use xper_bodies::Shape;
use xper_io::vtu::{VTK_POLYGON, VTK_VERTEX};
use xper_io::UnstructuredGrid;
use xper_math::{Real, Vector};
use xper_nscd::World;

/// The parts of a frame: `spheres`, `polyhedra`, `walls`, `contacts` and `force_chains`.
pub fn frame_parts(world: &World) -> Vec<(&'static str, UnstructuredGrid)> {
    vec![
        ("spheres", spheres_grid(world)),
        ("polyhedra", polyhedra_grid(world)),
        ("walls", walls_grid(world)),
        ("contacts", contacts_grid(world, false)),
        ("force_chains", contacts_grid(world, true)),
    ]
}

/// A point in VTK's coordinates.
pub(super) fn xyz(v: &Vector) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// The body data every part carries, for the bodies `of` (one tuple each): `id`, `group`,
/// `velocity` (m/s), `angular_velocity` (rad/s) and `orientation` (rotation vector, rad).
fn body_arrays(world: &World, of: &[usize]) -> Vec<xper_io::vtu::DataArray> {
    let b = &world.bodies;
    vec![
        i32_array("id", of.iter().map(|&k| b.id[k] as i32).collect()),
        i32_array("group", of.iter().map(|&k| b.group[k] as i32).collect()),
        f64_array(
            "velocity",
            3,
            of.iter().flat_map(|&k| xyz(&b.velocity[k])).collect(),
        ),
        f64_array(
            "angular_velocity",
            3,
            of.iter()
                .flat_map(|&k| xyz(&b.angular_velocity[k]))
                .collect(),
        ),
        f64_array(
            "orientation",
            3,
            of.iter()
                .flat_map(|&k| xyz(&b.rotation[k].scaled_axis()))
                .collect(),
        ),
    ]
}

/// Spheres: one vertex each at the centre, with point data `radius` (m) and the body data.
pub fn spheres_grid(world: &World) -> UnstructuredGrid {
    let b = &world.bodies;
    let mut g = UnstructuredGrid::default();
    let mut of = Vec::new();
    let mut radius = Vec::new();
    for k in 0..b.len() {
        if let Shape::Sphere { radius: r } = b.shape[k] {
            let first = g.points.len() as i64;
            g.points.push(xyz(&b.position[k]));
            g.add_cell(VTK_VERTEX, &[first]);
            of.push(k);
            radius.push(r);
        }
    }
    let mut data = body_arrays(world, &of);
    data.push(f64_array("radius", 1, radius));
    g.point_data = data.clone();
    g.cell_data = data;
    g
}

/// Polyhedra: one polygon per face (counter-clockwise seen from outside), each with the data
/// of its body.
pub fn polyhedra_grid(world: &World) -> UnstructuredGrid {
    let b = &world.bodies;
    let mut g = UnstructuredGrid::default();
    let mut of = Vec::new();
    for k in 0..b.len() {
        if let Shape::Polyhedron(p) = &b.shape[k] {
            let first = g.points.len() as i64;
            for v in &p.vertices {
                g.points.push(xyz(&(b.position[k] + b.rotation[k] * v)));
            }
            for face in &p.faces {
                let ids: Vec<i64> = face.iter().map(|&i| first + i as i64).collect();
                g.add_cell(VTK_POLYGON, &ids);
                of.push(k);
            }
        }
    }
    g.cell_data = body_arrays(world, &of);
    g
}

/// Walls: rectangles; a half-space (infinite extents) is drawn as a square centred on the
/// projection of the other bodies' centroid, of side twice their extent.
pub fn walls_grid(world: &World) -> UnstructuredGrid {
    let b = &world.bodies;
    let solids: Vec<usize> = (0..b.len()).filter(|&k| !b.shape[k].is_wall()).collect();
    let (lo, hi) = solids.iter().fold(
        (
            Vector::repeat(Real::INFINITY),
            Vector::repeat(-Real::INFINITY),
        ),
        |(lo, hi), &k| {
            let r = Vector::repeat(b.shape[k].size());
            (lo.inf(&(b.position[k] - r)), hi.sup(&(b.position[k] + r)))
        },
    );
    let (centre, extent) = if solids.is_empty() {
        (Vector::zeros(), 1.0)
    } else {
        ((lo + hi) / 2.0, (hi - lo).max())
    };
    let mut g = UnstructuredGrid::default();
    let mut of = Vec::new();
    for k in 0..b.len() {
        let Shape::Plane { half_extents } = b.shape[k] else {
            continue;
        };
        let (q, p) = (b.rotation[k], b.position[k]);
        let n = q * Vector::z();
        let middle = if half_extents.iter().all(|h| h.is_finite()) {
            p
        } else {
            centre - n * n.dot(&(centre - p))
        };
        let half = half_extents.map(|h| if h.is_finite() { h } else { extent });
        let first = g.points.len() as i64;
        for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let corner = middle + q * Vector::new(s * half[0], t * half[1], 0.0);
            g.points.push(xyz(&corner));
        }
        g.add_cell(VTK_POLYGON, &[first, first + 1, first + 2, first + 3]);
        of.push(k);
    }
    g.cell_data = body_arrays(world, &of);
    g
}

/// A contact's unit normal.
pub(super) fn normal3(c: &xper_geometry::Contact) -> [f64; 3] {
    c.row.normal
}

/// The magnitude of a contact's tangential impulse.
pub(super) fn tangential(c: &xper_geometry::Contact) -> f64 {
    c.impulse[1].hypot(c.impulse[2])
}

/// The arrays of contacts only 3D has: `impulse`, the world vector (N s).
pub(super) fn more_contact_arrays(world: &World) -> Vec<xper_io::vtu::DataArray> {
    let contacts = &world.contacts;
    vec![f64_array(
        "impulse",
        3,
        contacts
            .iter()
            .flat_map(|c| c.row.carry_out(c.impulse))
            .collect(),
    )]
}
