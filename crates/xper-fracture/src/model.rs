//! The fracture model: an exploded mesh (one deformable body per triangle), the interfaces
//! between neighbouring triangles, loads, and the state that evolves during a run.

use serde::{Deserialize, Serialize};
use xper_bodies::Drive;
use xper_fem::{MaterialState, Triangle3};
use xper_mesh::{Mesh, Topology};

use crate::cell::CellState;
use crate::dense::{add_scaled, Mat6};
pub use crate::spec::{
    BuildError, FractureSpec, InterfaceLaw, InterfaceRule, MassMatrix, NodeLoad, PlasticStiffness,
};

/// One triangle as a deformable body (6 degrees of freedom: x and y of its three nodes).
#[derive(Clone, Debug, PartialEq)]
pub struct ElementBody {
    /// Mesh nodes of the triangle (counter-clockwise); the body has its own copy of each.
    pub mesh_nodes: [u32; 3],
    /// Region index.
    pub region: u32,
    /// Reference geometry.
    pub triangle: Triangle3,
    /// Nodal displacements `[u1x, u1y, u2x, u2y, u3x, u3y]` (m).
    pub displacement: [f64; 6],
    /// Nodal velocities (m/s).
    pub velocity: [f64; 6],
    /// Material state (one point: the strain of a linear triangle is constant).
    pub state: MaterialState,
    /// Mass matrix (kg).
    pub mass: Mat6,
    /// Tangent stiffness (N/m).
    pub stiffness: Mat6,
    /// Internal force `A t B^T sigma` at the current displacement (N).
    pub internal_force: [f64; 6],
    /// Load index of each degree of freedom (`u16::MAX`: none).
    pub load: [u16; 6],
    /// Share of its load's force carried by each node copy: half the length of the boundary
    /// edges of this element whose two nodes are in the load's set, over the total of the
    /// set (a uniform traction); an equal share per copy when the set has no such edge.
    pub load_share: [f64; 3],
}

/// State of one of the two contact points of an interface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PointState {
    /// Displacement jump `[u_N, u_T]` (m), body b minus body a in the interface frame.
    pub jump: [f64; 2],
    /// Largest jump norm reached (m), the memory of the cohesive law.
    pub max_jump: f64,
    /// Adhesion intensity beta (1 sound, 0 broken).
    pub intensity: f64,
    /// Total impulse of the last step (N s), adhesive part included: the warm start.
    pub impulse: [f64; 2],
    /// Adhesive part of that impulse (N s).
    pub adhesive_impulse: [f64; 2],
}

/// The interface between two neighbouring elements, with two contact points (the edge's
/// end nodes, one copy in each element), each standing for half the edge.
#[derive(Clone, Debug, PartialEq)]
pub struct Interface {
    /// Elements `[a, b]`; the normal points from a to b.
    pub elements: [u32; 2],
    /// For each point, the local node in a and in b.
    pub local_nodes: [[u8; 2]; 2],
    /// Unit normal of the reference edge, outward from a (the frame `(n, t)`, `t = (-n_y, n_x)`).
    pub normal: [f64; 2],
    /// Reference edge length (m).
    pub length: f64,
    /// Index of the law in `FractureModel::laws`.
    pub law: u16,
    /// The two points.
    pub points: [PointState; 2],
    /// `X_b - X_a` (m): the period of an interface across the sides of a periodic cell, zero
    /// for one inside the mesh.
    pub period: [f64; 2],
}

/// Energies (J), accumulated since the start of the run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FractureEnergy {
    /// Kinetic energy now.
    pub kinetic: f64,
    /// Elastic energy stored in the elements now.
    pub elastic: f64,
    /// Plastic work dissipated in the elements.
    pub plastic: f64,
    /// Elastic energy stored in the cohesive interfaces now.
    pub cohesive_stored: f64,
    /// Energy dissipated by interface damage (fracture energy spent).
    pub cohesive_dissipated: f64,
    /// Energy dissipated by the contact part of the interfaces (friction, inelastic closure).
    pub contact_dissipated: f64,
    /// Work of the loads (imposed velocities and forces) and of gravity.
    pub external_work: f64,
    /// Initial total (kinetic + elastic + stored).
    pub initial: f64,
}

impl FractureEnergy {
    /// The energy in play: every term of the budget in absolute value (J).
    pub fn in_play(&self) -> f64 {
        [
            self.kinetic,
            self.elastic,
            self.plastic,
            self.cohesive_stored,
            self.cohesive_dissipated,
            self.contact_dissipated,
            self.external_work,
            self.initial,
        ]
        .iter()
        .map(|v| v.abs())
        .sum()
    }

    /// Why the budget shows a blow-up, if it does: a balance error that is not finite or
    /// exceeds half the energy in play means the run diverged even though every step solved
    /// (a sound run keeps it many orders of magnitude smaller).
    pub fn divergence(&self) -> Option<String> {
        let (error, in_play) = (self.error(), self.in_play());
        (!error.is_finite() || error.abs() > 0.5 * in_play).then(|| {
            format!(
                "diverging: the energy balance error {error:.3e} J exceeds half the energy in \
                 play ({in_play:.3e} J); reduce dt"
            )
        })
    }

    /// `kinetic + elastic + stored + dissipated - initial - external work`: zero for an exact
    /// budget.
    pub fn error(&self) -> f64 {
        self.kinetic
            + self.elastic
            + self.plastic
            + self.cohesive_stored
            + self.cohesive_dissipated
            + self.contact_dissipated
            - self.initial
            - self.external_work
    }
}

/// An exploded mesh in motion.
#[derive(Clone, Debug)]
pub struct FractureModel {
    /// The mesh it was built from.
    pub mesh: Mesh,
    /// The build parameters.
    pub spec: FractureSpec,
    /// One body per triangle.
    pub elements: Vec<ElementBody>,
    /// Interfaces between neighbouring triangles.
    pub interfaces: Vec<Interface>,
    /// Distinct interface laws.
    pub laws: Vec<InterfaceLaw>,
    /// Current time (s).
    pub time: f64,
    /// Steps done.
    pub step: u64,
    /// Energy budget.
    pub energy: FractureEnergy,
    /// Elements that are copies of another process's (a part of a distributed run, see
    /// [`FractureModel::part`]): stepped like the others but left out of the energies and
    /// loads, which their owner counts. Empty for a whole model.
    pub shadow: Vec<bool>,
    /// The macroscopic state of a periodic cell (`None` without `spec.periodic`).
    pub cell: Option<CellState>,
    /// The cell's free strain components are a copy of another process's (a part of a
    /// distributed run): their kinetic energy and the work of the imposed stresses are
    /// counted by that process. False for a whole model.
    pub cell_copy: bool,
}

const NO_LOAD: u16 = u16::MAX;

impl FractureModel {
    /// Explodes `mesh` into element bodies and interfaces as `spec` says.
    ///
    /// The triangles are renumbered along a Morton (Z-order) curve of their centroids, so that
    /// neighbouring elements sit close in memory and a sweep over the interfaces walks the
    /// element data nearly in order.
    pub fn new(mesh: Mesh, spec: FractureSpec) -> Result<Self, BuildError> {
        let mesh = spatially_sorted(mesh);
        let err = |s: String| Err(BuildError(s));
        if !(spec.thickness > 0.0 && spec.thickness.is_finite()) {
            return err(format!("thickness {} m must be positive", spec.thickness));
        }
        if !(spec.dt > 0.0 && spec.dt.is_finite()) {
            return err(format!("dt {} s must be positive", spec.dt));
        }
        if !(0.5..=1.0).contains(&spec.theta) {
            return err(format!("theta {} must be in [0.5, 1]", spec.theta));
        }
        if let Some(load) =
            (spec.loads.iter()).find(|l| l.drives.iter().any(|d| matches!(d, Drive::Pressure(_))))
        {
            return err(format!(
                "load `{}`: a pressure drives a wall of a rigid scene, not mesh nodes; use `force`",
                load.name
            ));
        }
        if spec.materials.len() != mesh.regions.len() {
            return err(format!(
                "{} materials for {} regions ({})",
                spec.materials.len(),
                mesh.regions.len(),
                region_names(&mesh)
            ));
        }
        for (m, r) in spec.materials.iter().zip(&mesh.regions) {
            m.validate()
                .map_err(|e| BuildError(format!("material of region '{}': {e}", r.name)))?;
        }
        if spec.loads.len() >= NO_LOAD as usize {
            return err(format!(
                "{} loads: at most {}",
                spec.loads.len(),
                NO_LOAD - 1
            ));
        }
        let mut node_load = vec![[NO_LOAD; 2]; mesh.nodes.len()];
        for (l, load) in spec.loads.iter().enumerate() {
            if load.nodes.is_empty() {
                return err(format!("load '{}' selects no node", load.name));
            }
            for &n in &load.nodes {
                let Some(slot) = node_load.get_mut(n as usize) else {
                    return err(format!("load '{}': node {n} is not in the mesh", load.name));
                };
                for d in 0..2 {
                    if matches!(load.drives[d], Drive::Free) {
                        continue;
                    }
                    if slot[d] != NO_LOAD {
                        return err(format!(
                            "node {n} component {d} is driven by both '{}' and '{}'",
                            spec.loads[slot[d] as usize].name, load.name
                        ));
                    }
                    slot[d] = l as u16;
                }
            }
        }
        let mut elements = Vec::with_capacity(mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let region = mesh.triangle_region[t];
            let material = &spec.materials[region as usize];
            let nodes = tri.map(|n| mesh.nodes[n as usize]);
            let triangle = Triangle3::new(nodes, spec.thickness)
                .map_err(|e| BuildError(format!("triangle {t}: {e}")))?;
            let mass = match spec.mass {
                MassMatrix::Consistent => triangle.consistent_mass(material.density()),
                MassMatrix::Lumped => {
                    let d = triangle.lumped_mass(material.density());
                    let mut m = [[0.0; 6]; 6];
                    for i in 0..6 {
                        m[i][i] = d[i];
                    }
                    m
                }
            };
            let stiffness = triangle.stiffness(&material.elastic_tangent(spec.hypothesis));
            let mut load = [NO_LOAD; 6];
            for (j, &n) in tri.iter().enumerate() {
                load[2 * j] = node_load[n as usize][0];
                load[2 * j + 1] = node_load[n as usize][1];
            }
            elements.push(ElementBody {
                mesh_nodes: *tri,
                region,
                triangle,
                displacement: [0.0; 6],
                velocity: [0.0; 6],
                state: MaterialState::default(),
                mass,
                stiffness,
                internal_force: [0.0; 6],
                load,
                load_share: [0.0; 3],
            });
        }
        let topology = mesh
            .neighbours()
            .map_err(|e| BuildError(format!("mesh adjacency: {e}")))?;
        load_shares(&mesh, &topology, &spec, &node_load, &mut elements);
        let (interfaces, laws) = crate::interface::build_interfaces(&mesh, &topology, &spec)?;
        let cell = match &spec.periodic {
            Some(p) => Some(crate::cell::initial_cell(p, spec.dt, &mut elements)?),
            None => None,
        };
        Ok(FractureModel {
            mesh,
            spec,
            elements,
            interfaces,
            laws,
            time: 0.0,
            step: 0,
            energy: FractureEnergy::default(),
            shadow: Vec::new(),
            cell,
            cell_copy: false,
        })
    }

    /// Whether element `e` is a copy of another process's element.
    pub fn is_shadow(&self, e: usize) -> bool {
        self.shadow.get(e).copied().unwrap_or(false)
    }

    /// Whether degree of freedom `d` of element `e` has an imposed velocity.
    pub fn is_imposed(&self, e: usize, d: usize) -> bool {
        let l = self.elements[e].load[d];
        l != NO_LOAD && self.spec.loads[l as usize].drives[d % 2].is_imposed_velocity()
    }

    /// Kinetic energy `v^T M v / 2` summed over the elements, shadows excepted, plus that of
    /// the free components of a periodic cell's strain, `M_k E'_k^2 / 2` (J).
    pub fn kinetic_energy(&self) -> f64 {
        self.cell_kinetic_energy()
            + self
                .elements
                .iter()
                .enumerate()
                .filter(|(k, _)| !self.is_shadow(*k))
                .map(|(_, e)| {
                    let mv = crate::dense::mul_vec(&e.mass, &e.velocity);
                    0.5 * mv.iter().zip(&e.velocity).map(|(a, b)| a * b).sum::<f64>()
                })
                .sum::<f64>()
    }

    /// Effective mass `M + h^2 theta^2 K` of an element.
    pub fn effective_mass(&self, e: usize) -> Mat6 {
        let (h, th) = (self.spec.dt, self.spec.theta);
        let el = &self.elements[e];
        add_scaled(&el.mass, h * h * th * th, &el.stiffness)
    }

    /// Number of broken interface points (intensity 0).
    pub fn broken_points(&self) -> usize {
        self.interfaces
            .iter()
            .flat_map(|i| i.points.iter())
            .filter(|p| p.intensity == 0.0)
            .count()
    }

    /// Whether an interface is fully broken: a cohesive interface whose two points have lost
    /// all adhesion (pre-cracks included). Contact-law interfaces never count as broken.
    pub fn is_broken(&self, i: &Interface) -> bool {
        matches!(self.laws[i.law as usize], InterfaceLaw::Cohesive(_))
            && i.points.iter().all(|p| p.intensity == 0.0)
    }

    /// Largest difference of a nodal displacement component between this model and `other`,
    /// element by element (m): how far two runs of the same model ended apart.
    pub fn largest_displacement_difference(&self, other: &FractureModel) -> f64 {
        (self.elements.iter().zip(&other.elements))
            .flat_map(|(a, b)| (0..6).map(|d| (a.displacement[d] - b.displacement[d]).abs()))
            .fold(0.0, f64::max)
    }

    /// Number of points of cohesive interfaces.
    pub fn cohesive_points(&self) -> usize {
        (self.interfaces.iter())
            .filter(|i| matches!(self.laws[i.law as usize], InterfaceLaw::Cohesive(_)))
            .count()
            * 2
    }

    /// Number of points of cohesive interfaces that have lost adhesion (intensity below the
    /// law's initial one; broken points included).
    pub fn damaged_points(&self) -> usize {
        self.interfaces
            .iter()
            .filter_map(|i| match self.laws[i.law as usize] {
                InterfaceLaw::Cohesive(z) => Some((i, z.initial_damage)),
                InterfaceLaw::Contact { .. } => None,
            })
            .map(|(i, beta0)| i.points.iter().filter(|p| p.intensity < beta0).count())
            .sum()
    }

    /// Number of fully broken interfaces ([`FractureModel::is_broken`]).
    pub fn broken_interfaces(&self) -> usize {
        self.interfaces.iter().filter(|i| self.is_broken(i)).count()
    }
}

/// `a, b, c` list of the region names, for messages.
pub(crate) fn region_names(mesh: &Mesh) -> String {
    mesh.regions
        .iter()
        .map(|r| format!("'{}'", r.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Fills `ElementBody::load_share` (see there).
fn load_shares(
    mesh: &Mesh,
    topology: &Topology,
    spec: &FractureSpec,
    node_load: &[[u16; 2]],
    elements: &mut [ElementBody],
) {
    let loaded = |n: u32| {
        node_load[n as usize]
            .iter()
            .find(|&&l| l != NO_LOAD)
            .copied()
    };
    let mut total = vec![0.0; spec.loads.len()];
    for edge in &topology.boundary {
        let [p, q] = edge.nodes;
        let (Some(lp), Some(lq)) = (loaded(p), loaded(q)) else {
            continue;
        };
        if lp != lq {
            continue;
        }
        let [xp, xq] = [p, q].map(|n| mesh.nodes[n as usize]);
        let half = 0.5 * ((xq[0] - xp[0]).powi(2) + (xq[1] - xp[1]).powi(2)).sqrt();
        let el = &mut elements[edge.triangle as usize];
        for n in [p, q] {
            if let Some(j) = el.mesh_nodes.iter().position(|&m| m == n) {
                el.load_share[j] += half;
            }
        }
        total[lp as usize] += 2.0 * half;
    }
    let mut copies = vec![0usize; spec.loads.len()];
    for el in elements.iter() {
        for &n in &el.mesh_nodes {
            if let Some(l) = loaded(n) {
                copies[l as usize] += 1;
            }
        }
    }
    for el in elements.iter_mut() {
        for j in 0..3 {
            if let Some(l) = loaded(el.mesh_nodes[j]) {
                let l = l as usize;
                el.load_share[j] = if total[l] > 0.0 {
                    el.load_share[j] / total[l]
                } else {
                    1.0 / copies[l] as f64
                };
            }
        }
    }
}

/// `mesh` with its triangles in Morton order of their centroids (the nodes keep their
/// numbers, so node and edge sets are unchanged).
fn spatially_sorted(mut mesh: Mesh) -> Mesh {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &mesh.nodes {
        for d in 0..2 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    let scale = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
    let spread = |x: u64| {
        let mut x = x & 0xFFFF_FFFF;
        x = (x | (x << 16)) & 0x0000_FFFF_0000_FFFF;
        x = (x | (x << 8)) & 0x00FF_00FF_00FF_00FF;
        x = (x | (x << 4)) & 0x0F0F_0F0F_0F0F_0F0F;
        x = (x | (x << 2)) & 0x3333_3333_3333_3333;
        (x | (x << 1)) & 0x5555_5555_5555_5555
    };
    let key = |t: &[u32; 3]| {
        let c = |d: usize| t.iter().map(|&n| mesh.nodes[n as usize][d]).sum::<f64>() / 3.0;
        let q = |d: usize| (((c(d) - lo[d]) / scale) * 4_294_967_295.0) as u64;
        spread(q(0)) | (spread(q(1)) << 1)
    };
    let mut order: Vec<usize> = (0..mesh.triangles.len()).collect();
    let keys: Vec<u64> = mesh.triangles.iter().map(key).collect();
    order.sort_by_key(|&t| (keys[t], t));
    mesh.triangles = order.iter().map(|&t| mesh.triangles[t]).collect();
    mesh.triangle_region = order.iter().map(|&t| mesh.triangle_region[t]).collect();
    mesh
}
