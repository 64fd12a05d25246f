//! A rigid world as named arrays ([`xper_run::state`]): bodies and contacts, read by scripts
//! and, for velocities and gravity, written between steps. Spatial columns follow the
//! dimension (`DIM`, `ANGULAR_DIM`, `ROTATION_COORDS` of `xper-math`).

use crate::frames::status;
use xper_bodies::{Drive, TimeFunction};
use xper_laws::InteractionLaw;
use xper_math::{angular_coords, angular_from_coords, rotation_coords, Vector};
use xper_math::{ANGULAR_DIM, DIM, DOFS, ROTATION_COORDS};
use xper_nscd::World;
use xper_run::state::{check_shape, ArrayInfo, StateArray, StateView};

#[cfg(feature = "dim2")]
mod shapes {
    pub const VECTOR: &str = "(n, 2)";
    pub const ANGULAR: &str = "(n, 1)";
    pub const ROTATION: &str = "(n, 1)";
    pub const ROTATION_ABOUT: &str = "orientation: the angle, counter-clockwise";
    pub const ROTATION_UNIT: &str = "rad";
    pub const TANGENTIAL: &str = "(n, 1)";
    pub const GRAVITY: &str = "(2,)";
    pub const DOFS: &str = "(n, 3)";
    pub const TENSOR: &str = "(2, 2)";
}
#[cfg(feature = "dim3")]
mod shapes {
    pub const VECTOR: &str = "(n, 3)";
    pub const ANGULAR: &str = "(n, 3)";
    pub const ROTATION: &str = "(n, 4)";
    pub const ROTATION_ABOUT: &str = "orientation: the unit quaternion (w, x, y, z)";
    pub const ROTATION_UNIT: &str = "1";
    pub const TANGENTIAL: &str = "(n, 2)";
    pub const GRAVITY: &str = "(3,)";
    pub const DOFS: &str = "(n, 6)";
    pub const TENSOR: &str = "(3, 3)";
}
use shapes::*;

/// The arrays of a rigid world.
pub const ARRAYS: [ArrayInfo; 23] = [
    ArrayInfo::new(
        "bodies.id",
        "(n,)",
        "int64",
        "1",
        false,
        "the body's identifier in the scene",
    ),
    ArrayInfo::new(
        "bodies.group",
        "(n,)",
        "int64",
        "1",
        false,
        "the body's group (index)",
    ),
    ArrayInfo::new(
        "bodies.position",
        VECTOR,
        "float64",
        "m",
        false,
        "centre of mass",
    ),
    ArrayInfo::new(
        "bodies.orientation",
        ROTATION,
        "float64",
        ROTATION_UNIT,
        false,
        ROTATION_ABOUT,
    ),
    ArrayInfo::new(
        "bodies.velocity",
        VECTOR,
        "float64",
        "m/s",
        true,
        "velocity of the centre of mass",
    ),
    ArrayInfo::new(
        "bodies.angular_velocity",
        ANGULAR,
        "float64",
        "rad/s",
        true,
        "angular velocity",
    ),
    ArrayInfo::new(
        "bodies.radius",
        "(n,)",
        "float64",
        "m",
        false,
        "bounding radius (a wall's half-length; inf for a half-space)",
    ),
    ArrayInfo::new(
        "bodies.mass",
        "(n,)",
        "float64",
        "kg",
        false,
        "mass (per m of thickness in 2D; inf for a fixed or driven body)",
    ),
    ArrayInfo::new(
        "contacts.bodies",
        "(n, 2)",
        "int64",
        "1",
        false,
        "the two bodies (indices into the bodies' arrays)",
    ),
    ArrayInfo::new(
        "contacts.point",
        VECTOR,
        "float64",
        "m",
        false,
        "contact point, carried with the first body",
    ),
    ArrayInfo::new(
        "contacts.normal",
        VECTOR,
        "float64",
        "1",
        false,
        "unit normal, from the first body to the second",
    ),
    ArrayInfo::new(
        "contacts.normal_impulse",
        "(n,)",
        "float64",
        "N s",
        false,
        "normal impulse of the last step (per m of thickness in 2D)",
    ),
    ArrayInfo::new(
        "contacts.tangential_impulse",
        TANGENTIAL,
        "float64",
        "N s",
        false,
        "tangential impulse of the last step, in the contact's frame (2D: along n turned by +90 degrees)",
    ),
    ArrayInfo::new("contacts.impulse", VECTOR, "float64", "N s", false, "impulse of the last step on the second body, world frame (2D: r_n n + r_t t with t = n turned by +90 degrees)"),
    ArrayInfo::new(
        "contacts.gap",
        "(n,)",
        "float64",
        "m",
        false,
        "gap at the end of the last step (linearised)",
    ),
    ArrayInfo::new(
        "contacts.status",
        "(n,)",
        "int64",
        "1",
        false,
        "0 open, 1 sticking, 2 sliding",
    ),
    ArrayInfo::new("bodies.imposed_velocity", shapes::DOFS, "float64", "m/s, rad/s", true, "velocity imposed on each degree of freedom (translations, then rotations) at the current time; NaN where not imposed (writing NaN frees an imposed one)"),
    ArrayInfo::new("bodies.force", shapes::DOFS, "float64", "N, N m", true, "external force or torque on each degree of freedom at the current time (per m of thickness in 2D), gravity aside (a pressure drive: its force at the current positions; writing another value makes it a constant force); NaN where the velocity is imposed (writing NaN leaves it)"),
    ArrayInfo::new("laws.groups", "(n, 2)", "int64", "1", false, "the two groups of each law (indices into the group names)"),
    ArrayInfo::new("laws.friction", "(n,)", "float64", "1", true, "Coulomb friction coefficient (>= 0)"),
    ArrayInfo::new("laws.restitution", "(n,)", "float64", "1", true, "Newton restitution coefficient (in [0, 1])"),
    ArrayInfo::new(
        "world.gravity",
        GRAVITY,
        "float64",
        "m/s^2",
        true,
        "gravity",
    ),
    ArrayInfo::new(
        "world.time",
        "(1,)",
        "float64",
        "s",
        false,
        "simulated time",
    ),
];

/// The arrays of a periodic cell (`[cell]`), in a world that has one.
pub const CELL_ARRAYS: [ArrayInfo; 4] = [
    ArrayInfo::read_only("cell.origin", GRAVITY, "float64", "m", "the cell's lower corner"),
    ArrayInfo::read_only(
        "cell.edges",
        TENSOR,
        "float64",
        "m",
        "the edges H (upper triangular): column l is edge l, the cell is origin + H s, s in [0, 1)^d",
    ),
    ArrayInfo::read_only(
        "cell.gradient",
        TENSOR,
        "float64",
        "1/s",
        "the velocity gradient L of the last step, L[k, l] = dv_k/dx_l (imposed or under stress)",
    ),
    ArrayInfo::read_only(
        "cell.wraps",
        VECTOR,
        "int64",
        "1",
        "per body, how many of each edge it was moved back by on leaving the cell (with fixed edges, its unwrapped position is position + H wraps)",
    ),
];

/// The arrays of `world`: [`ARRAYS`], and [`CELL_ARRAYS`] when it has a periodic cell.
pub fn arrays(world: &World) -> Vec<ArrayInfo> {
    let cell = world.cell.as_ref().map_or(&[][..], |_| &CELL_ARRAYS[..]);
    ARRAYS.iter().chain(cell).copied().collect()
}

/// A tensor's components row by row.
fn row_major(t: &xper_math::Tensor) -> Vec<f64> {
    (0..DIM)
        .flat_map(|k| (0..DIM).map(move |l| t[(k, l)]))
        .collect()
}

/// The array `name` of `world`.
pub fn array(world: &World, name: &str) -> Option<StateArray> {
    if let Some(part) = name.strip_prefix("cell.") {
        let cell = world.cell.as_ref()?;
        return Some(match part {
            "origin" => StateArray::reals(&[DIM], cell.lattice.origin.iter().copied().collect()),
            "edges" => StateArray::reals(&[DIM, DIM], row_major(&cell.lattice.edges)),
            "gradient" => StateArray::reals(&[DIM, DIM], row_major(&cell.gradient)),
            "wraps" => {
                // Bodies added since the last step have not left the cell yet.
                let n = world.bodies.len();
                let row = |b: usize| cell.wraps.get(b).copied().unwrap_or([0; DIM]);
                let values = (0..n).flat_map(|b| row(b).map(i64::from)).collect();
                StateArray::integers(&[n, DIM], values)
            }
            _ => return None,
        });
    }
    let b = &world.bodies;
    let n = b.len();
    let c = &world.contacts;
    let m = c.len();
    let vectors = |v: &[Vector]| v.iter().flat_map(|x| x.iter().copied()).collect();
    Some(match name {
        "bodies.id" => StateArray::integers(&[n], b.id.iter().map(|&i| i as i64).collect()),
        "bodies.group" => StateArray::integers(&[n], b.group.iter().map(|&g| g as i64).collect()),
        "bodies.position" => StateArray::reals(&[n, DIM], vectors(&b.position)),
        "bodies.orientation" => StateArray::reals(
            &[n, ROTATION_COORDS],
            b.rotation.iter().flat_map(rotation_coords).collect(),
        ),
        "bodies.velocity" => StateArray::reals(&[n, DIM], vectors(&b.velocity)),
        "bodies.angular_velocity" => StateArray::reals(
            &[n, ANGULAR_DIM],
            b.angular_velocity.iter().flat_map(angular_coords).collect(),
        ),
        "bodies.radius" => StateArray::reals(&[n], b.shape.iter().map(|s| s.size()).collect()),
        "bodies.mass" => StateArray::reals(&[n], b.mass.clone()),
        "contacts.bodies" => StateArray::integers(
            &[m, 2],
            c.rows
                .iter()
                .flat_map(|r| r.bodies.map(i64::from))
                .collect(),
        ),
        "contacts.point" => StateArray::reals(
            &[m, DIM],
            (c.rows.iter())
                .flat_map(|r| {
                    let p = r.point(&b.position[r.bodies[0] as usize]);
                    p.iter().copied().collect::<Vec<_>>()
                })
                .collect(),
        ),
        "contacts.normal" => {
            StateArray::reals(&[m, DIM], c.rows.iter().flat_map(|r| r.normal).collect())
        }
        "contacts.normal_impulse" => {
            StateArray::reals(&[m], c.impulses.iter().map(|i| i[0]).collect())
        }
        "contacts.tangential_impulse" => StateArray::reals(
            &[m, DIM - 1],
            c.impulses.iter().flat_map(|i| i[1..].to_vec()).collect(),
        ),
        "contacts.gap" => StateArray::reals(&[m], c.gaps.clone()),
        "contacts.impulse" => StateArray::reals(
            &[m, DIM],
            (c.rows.iter().zip(&c.impulses))
                .flat_map(|(r, i)| r.world_impulse(*i).iter().copied().collect::<Vec<_>>())
                .collect(),
        ),
        "contacts.status" => {
            StateArray::integers(&[m], c.iter().map(|k| status(world, &k) as i64).collect())
        }
        "world.gravity" => {
            StateArray::reals(&[DIM], world.params.gravity.iter().copied().collect())
        }
        "world.time" => StateArray::reals(&[1], vec![world.time]),
        "bodies.imposed_velocity" | "bodies.force" => {
            let force = name == "bodies.force";
            let values = (0..n).flat_map(|k| {
                b.drives(k).map(|d| match (d, force) {
                    (Drive::Velocity(f), false) => f.eval(world.time),
                    (Drive::Force(f), true) => f.eval(world.time),
                    (Drive::Pressure(p), true) => p.force(p.pressure.eval(world.time), &b.position),
                    (Drive::Velocity(_), true) | (_, false) => f64::NAN,
                    (Drive::Free, true) => 0.0,
                })
            });
            StateArray::reals(&[n, DOFS], values.collect())
        }
        "laws.groups" => {
            let laws = &world.laws;
            let groups = (0..laws.len()).flat_map(|k| laws.groups_of(k as u16).map(|g| g as i64));
            StateArray::integers(&[laws.len(), 2], groups.collect())
        }
        "laws.friction" | "laws.restitution" => {
            let laws = &world.laws;
            let values = (0..laws.len()).map(|k| match laws.law(k as u16) {
                InteractionLaw::SignoriniCoulomb(l) if name == "laws.friction" => l.friction,
                InteractionLaw::SignoriniCoulomb(l) => l.restitution,
            });
            StateArray::reals(&[laws.len()], values.collect())
        }
        _ => return None,
    })
}

/// The array `name` of `world` read in place, for the bodies' reals kept as rows of
/// `f64`s: position, velocity, angular velocity, mass, and in 2D the angle (a 3D quaternion is
/// kept as (x, y, z, w), not the array's (w, x, y, z)). Contacts are rebuilt every step, and
/// the other arrays are computed or of another type: those are copied by [`array`].
pub fn view(world: &World, name: &str) -> Option<StateView> {
    let b = &world.bodies;
    let n = b.len();
    // SAFETY: `Vector` and `AngVector` are nalgebra vectors of f64 (or f64 itself in 2D),
    // `Real` is f64: each is made of f64s without padding.
    unsafe {
        match name {
            "bodies.position" => StateView::of(&[n, DIM], &b.position),
            "bodies.velocity" => StateView::of(&[n, DIM], &b.velocity),
            "bodies.angular_velocity" => StateView::of(&[n, ANGULAR_DIM], &b.angular_velocity),
            "bodies.mass" => StateView::of(&[n], &b.mass),
            #[cfg(feature = "dim2")]
            "bodies.orientation" => StateView::of(&[n, ROTATION_COORDS], &b.rotation),
            _ => None,
        }
    }
}

/// Writes `values` into the writable array `name` of `world`. What this changes of the
/// kinetic and potential energy (velocities, gravity) is counted as external work, so that the
/// energy budget stays closed.
pub fn set_array(
    world: &mut World,
    name: &str,
    shape: &[usize],
    values: &[f64],
) -> Result<(), String> {
    let mechanical =
        |w: &World| w.bodies.kinetic_energy() + w.bodies.potential_energy(&w.params.gravity);
    let before = mechanical(world);
    write_array(world, name, shape, values)?;
    world.energy.external_work += mechanical(world) - before;
    Ok(())
}

fn write_array(
    world: &mut World,
    name: &str,
    shape: &[usize],
    values: &[f64],
) -> Result<(), String> {
    let nan_allowed = matches!(name, "bodies.imposed_velocity" | "bodies.force");
    if values
        .iter()
        .any(|v| v.is_infinite() || v.is_nan() && !nan_allowed)
    {
        return Err(format!("{name}: values must be finite"));
    }
    let n = world.bodies.len();
    match name {
        "bodies.velocity" => {
            check_shape(name, shape, &[n, DIM])?;
            let b = &mut world.bodies;
            for (v, new) in b.velocity.iter_mut().zip(values.chunks_exact(DIM)) {
                *v = Vector::from_column_slice(new);
            }
        }
        "bodies.angular_velocity" => {
            check_shape(name, shape, &[n, ANGULAR_DIM])?;
            let b = &mut world.bodies;
            for (w, new) in (b.angular_velocity.iter_mut()).zip(values.chunks_exact(ANGULAR_DIM)) {
                *w = angular_from_coords(new);
            }
        }
        "bodies.imposed_velocity" | "bodies.force" => {
            check_shape(name, shape, &[n, DOFS])?;
            set_drives(world, name == "bodies.force", values)?;
        }
        "laws.friction" | "laws.restitution" => {
            check_shape(name, shape, &[world.laws.len()])?;
            set_laws(world, name == "laws.friction", values)?;
        }
        "world.gravity" => {
            check_shape(name, shape, &[DIM])?;
            world.params.gravity = Vector::from_column_slice(values);
        }
        _ => {
            return Err(match arrays(world).iter().find(|a| a.name == name) {
                Some(_) => {
                    let writable: Vec<&str> = (ARRAYS.iter().filter(|a| a.writable))
                        .map(|a| a.name)
                        .collect();
                    format!("{name}: read-only (writable: {})", writable.join(", "))
                }
                None => format!("{name}: no such array of a rigid simulation"),
            })
        }
    }
    Ok(())
}

/// Imposed velocities or forces: a value equal to the current one keeps its drive (and its
/// function of time, or its pressure); another becomes a constant drive; NaN frees an imposed velocity
/// (`force = false`) or leaves a degree of freedom as it is (`force = true`).
fn set_drives(world: &mut World, force: bool, values: &[f64]) -> Result<(), String> {
    let name = if force {
        "bodies.force"
    } else {
        "bodies.imposed_velocity"
    };
    let t = world.time;
    let b = &mut world.bodies;
    // Every change is checked before any is made: a refused write leaves the world as it was.
    let mut changes = Vec::new();
    for (k, row) in values.chunks_exact(DOFS).enumerate() {
        let drives = b.drives(k);
        for (d, (&v, now)) in row.iter().zip(drives).enumerate() {
            let new = match (force, now, v.is_nan()) {
                (false, Drive::Velocity(_), true) => Drive::Free,
                (_, _, true) => continue,
                (false, Drive::Velocity(f), false) | (true, Drive::Force(f), false)
                    if f.eval(t) == v =>
                {
                    continue
                }
                (true, Drive::Pressure(p), false)
                    if p.force(p.pressure.eval(t), &b.position) == v =>
                {
                    continue
                }
                (true, Drive::Free, false) if v == 0.0 => continue,
                (false, _, false) => Drive::Velocity(TimeFunction::Constant(v)),
                (true, _, false) if !b.is_dynamic(k) => {
                    return Err(format!(
                        "{name}: body {k} has an infinite mass (a wall or a fixed body): a force \
                         cannot move it; impose its velocity instead"
                    ))
                }
                (true, _, false) => Drive::Force(TimeFunction::Constant(v)),
            };
            changes.push((k, d, new));
        }
    }
    for (k, d, new) in changes {
        b.set_drive(k, d, new);
    }
    Ok(())
}

/// Friction (`friction = true`) or restitution coefficients of the laws, checked as a scene's.
/// Every value is checked before any is written.
fn set_laws(world: &mut World, friction: bool, values: &[f64]) -> Result<(), String> {
    for (k, &v) in values.iter().enumerate() {
        if friction && v < 0.0 {
            return Err(format!("laws.friction[{k}]: must be >= 0, got {v}"));
        }
        if !friction && !(0.0..=1.0).contains(&v) {
            return Err(format!("laws.restitution[{k}]: must be in [0, 1], got {v}"));
        }
    }
    for (k, &v) in values.iter().enumerate() {
        let InteractionLaw::SignoriniCoulomb(law) = world.laws.law_mut(k as u16);
        match friction {
            true => law.friction = v,
            false => law.restitution = v,
        }
    }
    Ok(())
}
