//! Edge adjacency of a mesh: which two triangles share each interior edge, and which edges
//! lie on the boundary. The fracture engine puts one cohesive interface on each interior
//! edge.

use std::collections::hash_map::Entry;
use std::collections::{HashMap, HashSet};

use serde::{Deserialize, Serialize};

use crate::error::MeshError;
use crate::mesh::{edge_key, Mesh};

/// An edge shared by two triangles.
///
/// Local edge `k` of a triangle `[n0, n1, n2]` joins its nodes `k` and `(k + 1) % 3`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct InteriorEdge {
    /// The two nodes, smaller index first.
    pub nodes: [u32; 2],
    /// The two triangles, in the order they come in `Mesh::triangles` (smaller index first).
    pub triangles: [u32; 2],
    /// The local edge index of this edge in each of the two triangles.
    pub local_edge: [u8; 2],
}

/// An edge that belongs to one triangle only.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct BoundaryEdge {
    /// The two nodes in the counter-clockwise order of the triangle, so that the outward
    /// normal points to the right of `nodes[0] -> nodes[1]`.
    pub nodes: [u32; 2],
    /// The triangle.
    pub triangle: u32,
    /// The local edge index in the triangle (see [`InteriorEdge`]).
    pub local_edge: u8,
}

/// Interior and boundary edges of a mesh, each list in the order the edges are first met
/// when walking the triangles and their local edges in order (deterministic).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Topology {
    /// Edges shared by two triangles.
    pub interior: Vec<InteriorEdge>,
    /// Edges of one triangle.
    pub boundary: Vec<BoundaryEdge>,
}

/// What the walk has found for an edge so far.
enum Slot {
    Boundary(usize),
    Interior(usize),
}

impl Mesh {
    /// The edge adjacency of the mesh, in O(number of triangles) time with a hash map keyed
    /// by the sorted node pair of each edge: the usual edge-matching construction of a
    /// doubly-connected edge list (M. de Berg, O. Cheong, M. van Kreveld, M. Overmars,
    /// "Computational Geometry: Algorithms and Applications", 3rd ed., Springer, 2008,
    /// section 2.2).
    ///
    /// Errors: a node index out of range, an edge shared by three or more triangles
    /// (non-manifold mesh).
    pub fn neighbours(&self) -> Result<Topology, MeshError> {
        let mut slots: HashMap<[u32; 2], Slot> = HashMap::with_capacity(self.triangles.len() * 2);
        let mut open: Vec<Option<BoundaryEdge>> = Vec::with_capacity(self.triangles.len() * 2);
        let mut interior = Vec::with_capacity(self.triangles.len() * 3 / 2);
        let n_nodes = self.nodes.len();
        for (t, tri) in self.triangles.iter().enumerate() {
            if let Some(&n) = tri.iter().find(|&&n| n as usize >= n_nodes) {
                return Err(MeshError::invalid(
                    format!("triangle {t}"),
                    format!("node index {n} out of range (the mesh has {n_nodes} nodes)"),
                ));
            }
            for k in 0..3u8 {
                let (a, b) = (tri[k as usize], tri[(k as usize + 1) % 3]);
                let key = edge_key(a, b);
                match slots.entry(key) {
                    Entry::Vacant(v) => {
                        v.insert(Slot::Boundary(open.len()));
                        open.push(Some(BoundaryEdge {
                            nodes: [a, b],
                            triangle: t as u32,
                            local_edge: k,
                        }));
                    }
                    Entry::Occupied(mut o) => match *o.get() {
                        Slot::Boundary(i) => {
                            let first = open[i].take().expect("a boundary slot is filled once");
                            o.insert(Slot::Interior(interior.len()));
                            interior.push(InteriorEdge {
                                nodes: key,
                                triangles: [first.triangle, t as u32],
                                local_edge: [first.local_edge, k],
                            });
                        }
                        Slot::Interior(i) => {
                            let e: &InteriorEdge = &interior[i];
                            return Err(MeshError::invalid(
                                format!("edge ({}, {})", key[0], key[1]),
                                format!(
                                    "shared by three triangles ({}, {} and {t}): non-manifold mesh",
                                    e.triangles[0], e.triangles[1]
                                ),
                            ));
                        }
                    },
                }
            }
        }
        Ok(Topology {
            interior,
            boundary: open.into_iter().flatten().collect(),
        })
    }
}

impl InteriorEdge {
    /// The region indices of the two triangles, in the order of `triangles`.
    pub fn regions(&self, mesh: &Mesh) -> [u32; 2] {
        self.triangles.map(|t| mesh.triangle_region[t as usize])
    }
}

impl Topology {
    /// Indices (into `interior`) of the interior edges that belong to the edge set `name`
    /// (e.g. the interfaces along `precrack`, which start broken). The error lists the known
    /// edge sets.
    pub fn interior_on_edge_set(&self, mesh: &Mesh, name: &str) -> Result<Vec<usize>, MeshError> {
        let set: HashSet<[u32; 2]> = mesh.edge_set(name)?.iter().copied().collect();
        Ok(self.interior_where(|e| set.contains(&e.nodes)))
    }

    /// Indices (into `boundary`) of the boundary edges that belong to the edge set `name`.
    pub fn boundary_on_edge_set(&self, mesh: &Mesh, name: &str) -> Result<Vec<usize>, MeshError> {
        let set: HashSet<[u32; 2]> = mesh.edge_set(name)?.iter().copied().collect();
        Ok((self.boundary.iter().enumerate())
            .filter(|(_, e)| set.contains(&edge_key(e.nodes[0], e.nodes[1])))
            .map(|(i, _)| i)
            .collect())
    }

    /// Indices (into `interior`) of the interior edges between a triangle of region `a` and
    /// a triangle of region `b`, in either order (`a == b` gives the edges inside one
    /// region). The error lists the known regions.
    pub fn interior_between_regions(
        &self,
        mesh: &Mesh,
        a: &str,
        b: &str,
    ) -> Result<Vec<usize>, MeshError> {
        let (ra, rb) = (mesh.region_index(a)?, mesh.region_index(b)?);
        Ok(self.interior_where(|e| {
            let [r0, r1] = e.regions(mesh);
            (r0 == ra && r1 == rb) || (r0 == rb && r1 == ra)
        }))
    }

    fn interior_where(&self, keep: impl Fn(&InteriorEdge) -> bool) -> Vec<usize> {
        (self.interior.iter().enumerate())
            .filter(|(_, e)| keep(e))
            .map(|(i, _)| i)
            .collect()
    }
}
