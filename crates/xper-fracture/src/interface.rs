//! Interfaces between the elements of an exploded mesh: one per interior edge, two contact
//! points each (the edge's end nodes, one copy in each element), each standing for half the
//! edge. Small-displacement kinematics: the frame is the reference edge's and the two copies
//! of a node coincide in the reference configuration, so the displacement jump at a point is
//! `[u] = (u_b - u_a) . (n, t)`. In a periodic cell ([`crate::cell`]) the boundary edges of
//! opposite sides are joined the same way, their node copies one period `T` apart.

use xper_laws::cohesive::CohesiveZone;
use xper_mesh::{Mesh, Topology};

use crate::model::{region_names, BuildError, FractureSpec, Interface, InterfaceLaw, PointState};

/// Builds the interfaces of `mesh` and the distinct laws they use.
pub(crate) fn build_interfaces(
    mesh: &Mesh,
    topology: &Topology,
    spec: &FractureSpec,
) -> Result<(Vec<Interface>, Vec<InterfaceLaw>), BuildError> {
    let regions = mesh.regions.len() as u32;
    let mut laws: Vec<InterfaceLaw> = Vec::new();
    let mut table = vec![None; (regions * regions) as usize];
    for rule in &spec.interface_laws {
        let [r0, r1] = rule.regions;
        if r0 >= regions || r1 >= regions {
            return Err(BuildError(format!(
                "interface rule between regions {r0} and {r1}: only {regions} regions ({})",
                region_names(mesh)
            )));
        }
        if let InterfaceLaw::Cohesive(z) = &rule.law {
            z.validate().map_err(|e| {
                BuildError(format!(
                    "cohesive law between '{}' and '{}': {e}",
                    mesh.regions[r0 as usize].name, mesh.regions[r1 as usize].name
                ))
            })?;
        }
        if let InterfaceLaw::Contact { friction } = rule.law {
            if !(friction >= 0.0 && friction.is_finite()) {
                return Err(BuildError(format!("friction {friction} must be >= 0")));
            }
        }
        let id = laws.iter().position(|l| *l == rule.law).unwrap_or_else(|| {
            laws.push(rule.law);
            laws.len() - 1
        }) as u16;
        table[(r0 * regions + r1) as usize] = Some(id);
        table[(r1 * regions + r0) as usize] = Some(id);
    }
    let mut broken = vec![false; topology.interior.len()];
    for name in &spec.broken_edge_sets {
        let on = topology
            .interior_on_edge_set(mesh, name)
            .map_err(|e| BuildError(format!("broken edge set: {e}")))?;
        for i in on {
            broken[i] = true;
        }
    }
    let mut interfaces = Vec::with_capacity(topology.interior.len());
    for (i, edge) in topology.interior.iter().enumerate() {
        let [ra, rb] = edge.regions(mesh);
        let Some(law) = table[(ra * regions + rb) as usize] else {
            return Err(BuildError(format!(
                "no interface law between regions '{}' and '{}'",
                mesh.regions[ra as usize].name, mesh.regions[rb as usize].name
            )));
        };
        let [ta, tb] = edge.triangles.map(|t| mesh.triangles[t as usize]);
        let k = edge.local_edge[0] as usize;
        let (p, q) = (ta[k], ta[(k + 1) % 3]);
        let [xp, xq] = [p, q].map(|n| mesh.nodes[n as usize]);
        let (dx, dy) = (xq[0] - xp[0], xq[1] - xp[1]);
        let length = (dx * dx + dy * dy).sqrt();
        let normal = [dy / length, -dx / length];
        let point = initial_point(&laws[law as usize], broken[i]);
        interfaces.push(Interface {
            elements: edge.triangles,
            local_nodes: [[local(ta, p), local(tb, p)], [local(ta, q), local(tb, q)]],
            normal,
            length,
            law,
            points: [point; 2],
            period: [0.0; 2],
        });
    }
    if let Some(periodic) = &spec.periodic {
        let pairs = mesh
            .periodic_edges(&periodic.cell)
            .map_err(|e| BuildError(format!("periodic cell: {e}")))?;
        let broken_keys: std::collections::HashSet<[u32; 2]> = (spec.broken_edge_sets.iter())
            .filter_map(|name| mesh.edge_sets.get(name))
            .flatten()
            .copied()
            .collect();
        for pair in pairs {
            let [ta, tb] = pair.triangles.map(|t| mesh.triangles[t as usize]);
            let [ra, rb] = pair.triangles.map(|t| mesh.triangle_region[t as usize]);
            let Some(law) = table[(ra * regions + rb) as usize] else {
                return Err(BuildError(format!(
                    "no interface law between regions '{}' and '{}' (across the periodic sides)",
                    mesh.regions[ra as usize].name, mesh.regions[rb as usize].name
                )));
            };
            let [[p, _], [q, _]] = pair.nodes;
            let broken = broken_keys.contains(&[p.min(q), p.max(q)]);
            let point = initial_point(&laws[law as usize], broken);
            interfaces.push(Interface {
                elements: pair.triangles,
                local_nodes: pair.nodes.map(|[a, b]| [local(ta, a), local(tb, b)]),
                normal: pair.normal,
                length: pair.length,
                law,
                points: [point; 2],
                period: pair.period,
            });
        }
    }
    Ok((interfaces, laws))
}

/// The local index (0, 1, 2) of mesh node `n` in triangle `tri`.
fn local(tri: [u32; 3], n: u32) -> u8 {
    tri.iter().position(|&m| m == n).unwrap_or(0) as u8
}

/// The state of a point of a new interface of law `law`, broken (a pre-crack) or not.
fn initial_point(law: &InterfaceLaw, broken: bool) -> PointState {
    let (intensity, max_jump) = match law {
        InterfaceLaw::Cohesive(z) if broken => (0.0, z.dc()),
        InterfaceLaw::Cohesive(z) => (z.initial_damage, 0.0),
        InterfaceLaw::Contact { .. } => (0.0, 0.0),
    };
    PointState {
        intensity,
        max_jump,
        ..Default::default()
    }
}

/// The cohesive zone of a law, if it has one.
pub(crate) fn cohesive(law: &InterfaceLaw) -> Option<&CohesiveZone> {
    match law {
        InterfaceLaw::Cohesive(z) => Some(z),
        InterfaceLaw::Contact { .. } => None,
    }
}
