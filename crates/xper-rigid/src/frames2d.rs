//! VTU frames of a 2D world: disks and polygons as polygons, walls as lines.

use super::contacts_grid;
use crate::run_outputs::{f64_array, i32_array};
use xper_bodies::Shape;
use xper_io::vtu::{VTK_LINE, VTK_POLYGON};
use xper_io::UnstructuredGrid;
use xper_math::{rotate, Vector};
use xper_nscd::World;

/// The parts of a frame: `bodies`, `contacts` and `force_chains`.
pub fn frame_parts(world: &World) -> Vec<(&'static str, UnstructuredGrid)> {
    vec![
        ("bodies", bodies_grid(world)),
        ("contacts", contacts_grid(world, false)),
        ("force_chains", contacts_grid(world, true)),
    ]
}

/// Sides of the polygon drawn for a disk.
const DISK_SIDES: usize = 16;

/// Bodies: disks as 16-sided polygons, polygons as polygons, walls as lines; cell data
/// `id`, `group`, `shape` (0 disk, 1 polygon, 2 wall), `velocity`, `angular_velocity`, `angle`.
pub fn bodies_grid(world: &World) -> UnstructuredGrid {
    let b = &world.bodies;
    let mut g = UnstructuredGrid::default();
    let mut kind = Vec::with_capacity(b.len());
    for k in 0..b.len() {
        let (p, angle) = (b.position[k], b.rotation[k]);
        let first = g.points.len() as i64;
        let (cell_type, count, shape_kind) = match &b.shape[k] {
            Shape::Disk { radius } => {
                for s in 0..DISK_SIDES {
                    let phi = angle + 2.0 * std::f64::consts::PI * s as f64 / DISK_SIDES as f64;
                    g.points
                        .push([p.x + radius * phi.cos(), p.y + radius * phi.sin(), 0.0]);
                }
                (VTK_POLYGON, DISK_SIDES, 0)
            }
            Shape::Polygon(poly) => {
                for v in &poly.vertices {
                    let w = p + rotate(v, angle);
                    g.points.push([w.x, w.y, 0.0]);
                }
                (VTK_POLYGON, poly.vertices.len(), 1)
            }
            Shape::Segment { half_length } => {
                let d = rotate(&Vector::new(*half_length, 0.0), angle);
                for w in [p - d, p + d] {
                    g.points.push([w.x, w.y, 0.0]);
                }
                (VTK_LINE, 2, 2)
            }
        };
        let ids: Vec<i64> = (first..first + count as i64).collect();
        g.add_cell(cell_type, &ids);
        kind.push(shape_kind);
    }
    let n = b.len();
    g.cell_data = vec![
        i32_array("id", b.id.iter().map(|&i| i as i32).collect()),
        i32_array("group", b.group.iter().map(|&i| i as i32).collect()),
        i32_array("shape", kind),
        f64_array(
            "velocity",
            3,
            (0..n)
                .flat_map(|k| [b.velocity[k].x, b.velocity[k].y, 0.0])
                .collect(),
        ),
        f64_array("angular_velocity", 1, b.angular_velocity.clone()),
        f64_array("angle", 1, b.rotation.clone()),
    ];
    g
}

/// A point of the plane in VTK's three coordinates.
pub(super) fn xyz(v: &Vector) -> [f64; 3] {
    [v.x, v.y, 0.0]
}

/// A contact's unit normal in three coordinates.
pub(super) fn normal3(c: &xper_geometry::Contact) -> [f64; 3] {
    [c.row.normal[0], c.row.normal[1], 0.0]
}

/// A contact's tangential impulse (signed: along the tangent, the normal turned by +90 degrees).
pub(super) fn tangential(c: &xper_geometry::Contact) -> f64 {
    c.impulse[1]
}

/// The arrays of contacts only this dimension has: none in 2D.
pub(super) fn more_contact_arrays(_world: &World) -> Vec<xper_io::vtu::DataArray> {
    Vec::new()
}
