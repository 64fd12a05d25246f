//! Micromechanical measures of a packing: granular stress, fabric, coordination, solid
//! fraction and the normal-force network, from the contact forces of the last step.
//!
//! Grains are the bodies of finite mass with no driven degree of freedom; every other body
//! (walls, servo walls, imposed bodies) is the boundary. With `f = r / h` the mean force of a
//! contact over the step (its impulse over the time step) that body `i` exerts on body `j`,
//! and `r_i`, `r_j` the lever arms from the bodies' centres to the contact point:
//!
//! ```text
//! sigma = (1/V) sum_c f (x) l_c      compression positive (Love-Weber; e.g. F. Radjai,
//!                                     F. Dubois, "Discrete-element modeling of granular
//!                                     materials", Wiley 2011, ch. 8)
//! l_c   = r_i - r_j                  between two grains (the branch vector x_j - x_i)
//!       = r_i  (j boundary)  or  -r_j  (i boundary) for a grain against the boundary
//! F     = (1/N_c) sum_c n (x) n      over force-bearing contacts between grains
//!                                     (M. Satake, 1982), anisotropy from `fabric_anisotropy`
//! z     = sum_grains c_g / N_g       c_g force-bearing contacts of grain g (boundary included)
//! z*    = the same without rattlers: grains left with fewer than 2 force-bearing contacts
//!         are removed, and their contacts with them, until none is left
//!         (as in e.g. Radjai and Dubois 2011, ch. 8)
//! phi   = sum_grains V_g / V
//! ```
//!
//! Per grain and contact, `sigma` is the static average `-(1/V) sum_g sum_c f_on_g (x) r_g`,
//! which equals the boundary forces times the boundary positions over `V` when the grains are
//! in equilibrium without body forces: two independent measures of the same stress.
//!
//! `V` is the box spanned by the boundary bodies' positions (the centre lines or planes of the
//! walls of a box, each wall along the axis it faces: [`VolumeSource::Walls`]) or the
//! bounding box of the grains ([`VolumeSource::Grains`]).

use crate::World;
use xper_math::{
    fabric_anisotropy, principal_values, stress_invariants, Real, Tensor, Vector, AXIS_NAMES,
};

/// How the volume `V` of the measures is taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VolumeSource {
    /// The box spanned by the positions of the boundary bodies (a box's walls). A wall (a
    /// segment in 2D, a plane in 3D) bounds only the axes its bounding box is flat along, the
    /// one it faces when it lies along the axes: its position along the others (the midpoint
    /// of a segment, the point given for a plane) says nothing of the box. A wall tilted off
    /// the axes bounds none.
    Walls,
    /// The bounding box of the grains.
    Grains,
    /// The periodic cell (its edges' diagonal components as the extents, their product, the
    /// cell's volume for upper-triangular edges, as `V`).
    Cell,
}

/// The measures of one state ([`measure`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Micro {
    /// Volume `V` (m^2 per m of thickness in 2D, m^3 in 3D).
    pub volume: Real,
    /// The extents of the box `V` is the volume of, along each axis (m).
    pub extent: Vector,
    /// Solid fraction.
    pub solid_fraction: Real,
    /// Granular stress tensor (Pa), compression positive; not symmetrised.
    pub stress: Tensor,
    /// Mean stress `p` of its symmetric part (Pa), see `xper_math::stress_invariants`.
    pub pressure: Real,
    /// Deviator `q` (Pa).
    pub deviator: Real,
    /// Fabric tensor (unit trace; zero without force-bearing contacts).
    pub fabric: Tensor,
    /// Fabric anisotropy `a`.
    pub anisotropy: Real,
    /// Grains.
    pub grains: usize,
    /// Force-bearing contacts between two grains.
    pub grain_contacts: usize,
    /// Force-bearing contacts between a grain and the boundary.
    pub boundary_contacts: usize,
    /// Coordination number `z`.
    pub coordination: Real,
    /// Coordination number `z*` without rattlers.
    pub coordination_without_rattlers: Real,
    /// Fraction of grains that are rattlers.
    pub rattler_fraction: Real,
    /// Mean normal force `<f_n>` over force-bearing grain contacts (N per m in 2D, N in 3D).
    pub mean_normal_force: Real,
    /// Fraction of those contacts in the strong network (`f_n > <f_n>`).
    pub strong_fraction: Real,
    /// Share of `tr(sigma)` carried by the strong network.
    pub strong_share: Real,
}

/// Why the measures cannot be taken.
#[derive(Clone, Debug, PartialEq)]
pub enum MicroError {
    /// `V` is not positive: the boundary (or the grains) span no volume along `axis`.
    NoVolume {
        /// The source of `V`.
        source: VolumeSource,
        /// The first axis of zero extent.
        axis: usize,
    },
    /// `V` is the periodic cell's, and there is none.
    NoCell,
}

impl std::fmt::Display for MicroError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MicroError::NoVolume { source, axis } => write!(
                f,
                "the {} span no volume along {}: the measures need a box of walls around the \
                 grains (`walls`), or use `grains`",
                match source {
                    VolumeSource::Walls => "walls (the bodies that are not free grains)",
                    VolumeSource::Grains => "grains",
                    VolumeSource::Cell => "periodic cell's edges",
                },
                AXIS_NAMES[*axis]
            ),
            MicroError::NoCell => write!(
                f,
                "the measures' volume is the periodic cell's (`cell`), and the scene has no cell"
            ),
        }
    }
}

impl std::error::Error for MicroError {}

impl Micro {
    /// `q / p` (0 without stress).
    pub fn stress_ratio(&self) -> Real {
        if self.pressure != 0.0 {
            self.deviator / self.pressure
        } else {
            0.0
        }
    }
}

/// Whether body `b` is a grain: finite mass, nothing driven.
pub fn is_grain(world: &World, b: usize) -> bool {
    world.bodies.is_dynamic(b)
        && (world.bodies.driven)
            .binary_search_by_key(&(b as u32), |(h, _)| h.0)
            .is_err()
}

/// Which bodies are grains ([`is_grain`]).
fn grain_flags(world: &World) -> Vec<bool> {
    (0..world.bodies.len())
        .map(|b| is_grain(world, b))
        .collect()
}

/// The thickness of a wall's bounding box, relative to its size, below which the wall faces
/// that axis: an orientation that went through a rotation vector leaves about 1e-16 where the
/// rotation matrix has zeros.
const FLAT: Real = 1e-12;

/// The extents of the box whose volume is `V` (m).
pub fn volume_box(
    world: &World,
    grain: &[bool],
    source: VolumeSource,
) -> Result<Vector, MicroError> {
    if source == VolumeSource::Cell {
        let cell = world.cell.as_ref().ok_or(MicroError::NoCell)?;
        let extent = cell.lattice.edges.diagonal();
        return match extent.iter().position(|e| !(*e > 0.0 && e.is_finite())) {
            Some(axis) => Err(MicroError::NoVolume { source, axis }),
            None => Ok(extent),
        };
    }
    let b = &world.bodies;
    let (mut lo, mut hi) = (
        Vector::repeat(Real::INFINITY),
        Vector::repeat(-Real::INFINITY),
    );
    for k in (0..b.len()).filter(|&k| grain[k] == (source == VolumeSource::Grains)) {
        let (min, max) = match source {
            VolumeSource::Walls if b.shape[k].is_wall() => {
                let bb = b.shape[k].aabb(&b.position[k], b.rotation[k]);
                // A half-space's bounding box is exactly flat along the axis it faces.
                let size = b.shape[k].size();
                let thin = if size.is_finite() { FLAT * size } else { 0.0 };
                let flat = (bb.max - bb.min).map(|e| e <= thin);
                let p = b.position[k];
                let lo = Vector::from_fn(|a, _| if flat[a] { p[a] } else { Real::INFINITY });
                let hi = Vector::from_fn(|a, _| if flat[a] { p[a] } else { -Real::INFINITY });
                (lo, hi)
            }
            VolumeSource::Walls => (b.position[k], b.position[k]),
            VolumeSource::Grains | VolumeSource::Cell => {
                let bb = b.shape[k].aabb(&b.position[k], b.rotation[k]);
                (bb.min, bb.max)
            }
        };
        lo = lo.inf(&min);
        hi = hi.sup(&max);
    }
    let extent = hi - lo;
    match extent.iter().position(|e| !(*e > 0.0 && e.is_finite())) {
        Some(axis) => Err(MicroError::NoVolume { source, axis }),
        None => Ok(extent),
    }
}

/// The mean force the contacts exerted on body `b` over the last step (N per m in 2D, N in
/// 3D): the sum of their impulses on it over the time step, e.g. the load a wall bears.
pub fn contact_force(world: &World, b: usize) -> Vector {
    let c = &world.contacts;
    let mut f = Vector::zeros();
    for (row, impulse) in c.rows.iter().zip(&c.impulses) {
        let r = row.world_impulse(*impulse) / world.params.dt;
        if row.bodies[1] as usize == b {
            f += r;
        } else if row.bodies[0] as usize == b {
            f -= r;
        }
    }
    f
}

/// A force-bearing contact touching a grain: its bodies, whether each is a grain, its force
/// on the second body (N per m in 2D, N in 3D), normal force and branch vector `l`.
struct Bearing {
    bodies: [usize; 2],
    grains: [bool; 2],
    force: Vector,
    normal_force: Real,
    normal: Vector,
    branch: Vector,
}

fn bearing_contacts(world: &World, grain: &[bool]) -> Vec<Bearing> {
    let h = world.params.dt;
    let c = &world.contacts;
    let mut out = Vec::new();
    for (row, impulse) in c.rows.iter().zip(&c.impulses) {
        let bodies = row.bodies.map(|b| b as usize);
        let grains = bodies.map(|b| grain[b]);
        if impulse[0] <= 0.0 || !(grains[0] || grains[1]) {
            continue;
        }
        let [ri, rj] = row.arm_vectors();
        let branch = match grains {
            [true, true] => ri - rj,
            [true, false] => ri,
            _ => -rj,
        };
        out.push(Bearing {
            bodies,
            grains,
            force: row.world_impulse(*impulse) / h,
            normal_force: impulse[0] / h,
            normal: row.normal(),
            branch,
        });
    }
    out
}

/// The measures of `world` with its last step's contact impulses.
pub fn measure(world: &World, source: VolumeSource) -> Result<Micro, MicroError> {
    let n = world.bodies.len();
    let grain = grain_flags(world);
    let extent = volume_box(world, &grain, source)?;
    let volume = extent.product();
    let contacts = bearing_contacts(world, &grain);
    let grains = grain.iter().filter(|&&g| g).count();

    let mut stress = Tensor::zeros();
    let mut fabric = Tensor::zeros();
    let mut grain_contacts = 0;
    let mut count = vec![0u32; n];
    for c in &contacts {
        stress += c.force * c.branch.transpose();
        if c.grains == [true, true] {
            fabric += c.normal * c.normal.transpose();
            grain_contacts += 1;
        }
        for (&b, &g) in c.bodies.iter().zip(&c.grains) {
            count[b] += g as u32;
        }
    }
    stress /= volume;
    if grain_contacts > 0 {
        fabric /= grain_contacts as Real;
    }
    let (pressure, deviator) = stress_invariants(principal_values(&stress));
    let sum_counts: u32 = count.iter().sum();
    let (kept, kept_counts) = without_rattlers(&contacts, &grain, count);

    let mean_normal_force = match contacts.len() {
        0 => 0.0,
        m => contacts.iter().map(|c| c.normal_force).sum::<Real>() / m as Real,
    };
    let strong: Vec<&Bearing> = (contacts.iter())
        .filter(|c| c.normal_force > mean_normal_force)
        .collect();
    let trace = |cs: &mut dyn Iterator<Item = &Bearing>| -> Real {
        cs.map(|c| c.force.dot(&c.branch)).sum()
    };
    let total = trace(&mut contacts.iter());
    let ratio = |a: Real, b: Real| if b != 0.0 { a / b } else { 0.0 };
    let solid: Real = (0..n)
        .filter(|&b| grain[b])
        .map(|b| world.bodies.shape[b].mass_properties(1.0).0)
        .sum();
    Ok(Micro {
        volume,
        extent,
        solid_fraction: solid / volume,
        pressure,
        deviator,
        anisotropy: fabric_anisotropy(principal_values(&fabric)),
        stress,
        fabric,
        grains,
        grain_contacts,
        boundary_contacts: contacts.len() - grain_contacts,
        coordination: ratio(sum_counts as Real, grains as Real),
        coordination_without_rattlers: ratio(kept_counts as Real, kept as Real),
        rattler_fraction: ratio((grains - kept) as Real, grains as Real),
        mean_normal_force,
        strong_fraction: ratio(strong.len() as Real, contacts.len() as Real),
        strong_share: ratio(trace(&mut strong.iter().copied()), total),
    })
}

/// Removes grains with fewer than 2 force-bearing contacts, and their contacts, until none
/// is left; returns the grains kept and the sum of their contact counts.
fn without_rattlers(contacts: &[Bearing], grain: &[bool], mut count: Vec<u32>) -> (usize, u32) {
    let n = grain.len();
    let mut touching: Vec<Vec<usize>> = vec![Vec::new(); n];
    for c in contacts.iter().filter(|c| c.grains == [true, true]) {
        touching[c.bodies[0]].push(c.bodies[1]);
        touching[c.bodies[1]].push(c.bodies[0]);
    }
    let mut removed = vec![false; n];
    let mut queue: Vec<usize> = (0..n).filter(|&b| grain[b] && count[b] < 2).collect();
    while let Some(b) = queue.pop() {
        if removed[b] {
            continue;
        }
        removed[b] = true;
        for &other in &touching[b] {
            if !removed[other] {
                count[other] -= 1;
                if count[other] < 2 {
                    queue.push(other);
                }
            }
        }
    }
    let kept: Vec<usize> = (0..n).filter(|&b| grain[b] && !removed[b]).collect();
    (kept.len(), kept.iter().map(|&b| count[b]).sum())
}

/// The normal forces of the force-bearing contacts touching a grain, each over their mean
/// (empty without such contacts).
pub fn normalised_normal_forces(world: &World) -> Vec<Real> {
    let forces: Vec<Real> = (bearing_contacts(world, &grain_flags(world)).iter())
        .map(|c| c.normal_force)
        .collect();
    let mean = forces.iter().sum::<Real>() / forces.len().max(1) as Real;
    forces.iter().map(|f| f / mean).collect()
}

#[cfg(all(test, feature = "dim2"))]
mod tests {
    use super::*;
    use crate::StepParams;
    use xper_bodies::{Body, BodySet};
    use xper_geometry::{Contact, ContactKey, ContactRow};
    use xper_laws::LawTable;

    /// Walls at x = 0 and x = 4 with grains A (x = 1) and B (x = 3) of radius 1 between them,
    /// a pair C (x = 10), D (x = 12) touching only each other and a lone grain E (x = 6); every
    /// contact carries a normal force of 1 N per m along +x.
    fn chain() -> World {
        let mut bodies = BodySet::new();
        let at = |x: Real| Vector::new(x, 0.0);
        let wall = |x: Real| Body::wall(Vector::new(x, -1.0), Vector::new(x, 1.0));
        bodies.insert(wall(0.0));
        for x in [1.0, 3.0, 10.0, 12.0, 6.0] {
            bodies.insert(Body::disk(1.0, 1.0, at(x)));
        }
        bodies.insert(wall(4.0));
        let params = StepParams::for_tests(0.01);
        let mut world = World::new(bodies, LawTable::new(1), params);
        for (pair, point) in [([0, 1], 0.0), ([1, 2], 2.0), ([2, 6], 4.0), ([3, 4], 11.0)] {
            let x = |b: u32| world.bodies.position[b as usize];
            let row = ContactRow::new(
                pair,
                &at(point),
                &at(1.0).normalize(),
                &x(pair[0]),
                &x(pair[1]),
            );
            world.contacts.push(Contact {
                row,
                key: ContactKey { feature: 0 },
                gap: 0.0,
                impulse: [0.01, 0.0],
            });
        }
        world
    }

    #[test]
    fn chain_measures_match_the_hand_count() {
        let world = chain();
        assert_eq!(
            measure(&world, VolumeSource::Walls),
            Err(MicroError::NoVolume {
                source: VolumeSource::Walls,
                axis: 1
            })
        );
        let m = measure(&world, VolumeSource::Grains).unwrap();
        // Grains span x in [0, 13], y in [-1, 1].
        assert!((m.volume - 26.0).abs() < 1e-12);
        // sum f l_x: wall-A 1, A-B 2, B-wall 1, C-D 2.
        assert!(
            (m.stress[(0, 0)] - 6.0 / 26.0).abs() < 1e-12,
            "{}",
            m.stress
        );
        assert!(m.stress[(1, 1)].abs() < 1e-12 && m.stress[(0, 1)].abs() < 1e-12);
        assert!((m.pressure - 3.0 / 26.0).abs() < 1e-12 && (m.deviator - 3.0 / 26.0).abs() < 1e-12);
        assert_eq!((m.grains, m.grain_contacts, m.boundary_contacts), (5, 2, 2));
        // Contacts per grain A 2, B 2, C 1, D 1, E 0; E, C, D are rattlers.
        assert!((m.coordination - 6.0 / 5.0).abs() < 1e-12);
        assert!((m.coordination_without_rattlers - 2.0).abs() < 1e-12);
        assert!((m.rattler_fraction - 0.6).abs() < 1e-12);
        assert!((m.fabric[(0, 0)] - 1.0).abs() < 1e-12 && (m.anisotropy - 2.0).abs() < 1e-12);
        assert!((m.mean_normal_force - 1.0).abs() < 1e-12 && m.strong_fraction == 0.0);
        let phi = 5.0 * std::f64::consts::PI / 26.0;
        assert!((m.solid_fraction - phi).abs() < 1e-12);
    }

    #[test]
    fn rattlers_cascade() {
        // B's contact with the right wall removed: B keeps only A, so B goes, then A.
        let mut world = chain();
        world.contacts.impulses[2] = [0.0, 0.0];
        let m = measure(&world, VolumeSource::Grains).unwrap();
        assert_eq!(m.coordination_without_rattlers, 0.0);
        assert!((m.rattler_fraction - 1.0).abs() < 1e-12);
        // A 2, B 1, C 1, D 1, E 0.
        assert!((m.coordination - 1.0).abs() < 1e-12);
    }
}
