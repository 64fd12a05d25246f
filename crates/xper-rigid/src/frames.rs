//! VTU frames: bodies per dimension (`frames2d.rs`: disks, polygons and wall segments;
//! `frames3d.rs`: spheres, polyhedra and planes), contacts as points and force chains as lines.

#[cfg(feature = "dim2")]
#[path = "frames2d.rs"]
mod dimension;
#[cfg(feature = "dim3")]
#[path = "frames3d.rs"]
mod dimension;

pub use dimension::*;
use dimension::{more_contact_arrays, normal3, tangential, xyz};

use crate::run_outputs::{f64_array, i32_array};
use xper_io::vtu::{VTK_LINE, VTK_VERTEX};
use xper_io::UnstructuredGrid;
use xper_laws::InteractionLaw;
use xper_nscd::World;

/// Contact status for output: 0 open (no impulse), 1 sticking, 2 sliding.
pub(crate) fn status(world: &World, c: &xper_geometry::Contact) -> i32 {
    let friction = match world.contact_law(c.row.bodies) {
        Some(InteractionLaw::SignoriniCoulomb(law)) => law.friction,
        None => 0.0,
    };
    let rn = c.impulse[0];
    if rn <= 0.0 {
        0
    } else if tangential(c).abs() < friction * rn * (1.0 - 1e-9) {
        1
    } else {
        2
    }
}

/// Contacts as points (`normal`; `normal_impulse` and `tangential_impulse` (2D: signed, N s per
/// m of thickness; 3D: its magnitude, N s); `status`; `gap`, the linearised gap at the end of
/// the step, m; in 3D also `impulse`, the world vector) and, when `chains` is set, as lines
/// between the two body centres (walls: the contact point) with the same cell data, to draw
/// force chains. A contact point is the one detected at the beginning of the step, carried
/// with its first body to that body's current position (its lever arm is what a contact
/// keeps).
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
                g.points.push(xyz(&end));
            }
            g.add_cell(VTK_LINE, &[first, first + 1]);
        } else {
            g.points.push(xyz(&point));
            g.add_cell(VTK_VERTEX, &[first]);
        }
    }
    g.cell_data = vec![
        f64_array(
            "normal",
            3,
            contacts.iter().flat_map(|c| normal3(&c)).collect(),
        ),
        f64_array(
            "normal_impulse",
            1,
            contacts.iter().map(|c| c.impulse[0]).collect(),
        ),
        f64_array(
            "tangential_impulse",
            1,
            contacts.iter().map(|c| tangential(&c)).collect(),
        ),
        i32_array(
            "status",
            contacts.iter().map(|c| status(world, &c)).collect(),
        ),
        f64_array("gap", 1, contacts.iter().map(|c| c.gap).collect()),
    ];
    g.cell_data.extend(more_contact_arrays(world));
    g
}
