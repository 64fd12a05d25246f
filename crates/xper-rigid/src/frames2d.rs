//! VTU frames: bodies as cells, contacts as points, force chains as lines.

use crate::run_outputs::{f64_array, i32_array};
use xper_bodies::Shape;
use xper_io::vtu::{VTK_LINE, VTK_POLYGON, VTK_VERTEX};
use xper_io::UnstructuredGrid;
use xper_laws::InteractionLaw;
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

/// Contact status for output: 0 open (no impulse), 1 sticking, 2 sliding.
fn status(world: &World, c: &xper_geometry::Contact) -> i32 {
    let friction = match world.contact_law(c.row.bodies) {
        Some(InteractionLaw::SignoriniCoulomb(law)) => law.friction,
        None => 0.0,
    };
    let [rn, rt] = c.impulse;
    if rn <= 0.0 {
        0
    } else if rt.abs() < friction * rn * (1.0 - 1e-9) {
        1
    } else {
        2
    }
}

/// Contacts as points (`normal`, `normal_impulse`, `tangential_impulse` in N s/m, `status`,
/// `gap`: the linearised gap at the end of the step, m) and, when `chains` is set, as lines between the two body centres (walls: the contact
/// point) with the same cell data, to draw force chains. A contact point is the one detected
/// at the beginning of the step, carried with its first body to that body's current position
/// (its lever arm is what a contact keeps).
pub fn contacts_grid(world: &World, chains: bool) -> UnstructuredGrid {
    let mut g = UnstructuredGrid::default();
    let contacts = &world.contacts;
    for c in contacts.iter() {
        let first = g.points.len() as i64;
        let point = c
            .row
            .point(&world.bodies.position[c.row.bodies[0] as usize]);
        if chains {
            for &body in &c.row.bodies {
                let b = body as usize;
                let end = if world.bodies.is_dynamic(b) {
                    world.bodies.position[b]
                } else {
                    point
                };
                g.points.push([end.x, end.y, 0.0]);
            }
            g.add_cell(VTK_LINE, &[first, first + 1]);
        } else {
            g.points.push([point.x, point.y, 0.0]);
            g.add_cell(VTK_VERTEX, &[first]);
        }
    }
    g.cell_data = vec![
        f64_array(
            "normal",
            3,
            contacts
                .iter()
                .flat_map(|c| [c.row.normal[0], c.row.normal[1], 0.0])
                .collect(),
        ),
        f64_array(
            "normal_impulse",
            1,
            contacts.iter().map(|c| c.impulse[0]).collect(),
        ),
        f64_array(
            "tangential_impulse",
            1,
            contacts.iter().map(|c| c.impulse[1]).collect(),
        ),
        i32_array(
            "status",
            contacts.iter().map(|c| status(world, &c)).collect(),
        ),
        f64_array("gap", 1, contacts.iter().map(|c| c.gap).collect()),
    ];
    g
}
