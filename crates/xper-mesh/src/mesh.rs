//! The triangle mesh: nodes, counter-clockwise triangles, regions, named edge and node sets;
//! its constructors and invariant checks, and its quality figures.

use std::collections::{BTreeMap, HashSet};

use serde::{Deserialize, Serialize};

use crate::error::MeshError;

/// A triangle whose doubled area is at most this factor times the square of its longest edge
/// is degenerate (its smallest angle is then below about 1e-14 rad).
const DEGENERACY: f64 = 1e-14;

/// A named part of the domain (a material): every triangle belongs to exactly one region.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Region {
    /// Name of the region (a Gmsh physical name, or a generator's name such as `matrix`).
    pub name: String,
    /// Numeric tag (the Gmsh physical tag; generators number regions from 1).
    pub tag: i32,
}

/// A 2D mesh of 3-node triangles.
///
/// Invariants (checked by [`Mesh::new`], [`Mesh::with_edge_set`], [`Mesh::with_node_set`] and
/// [`Mesh::validate`]): coordinates are finite; every triangle has three distinct nodes in
/// range, is counter-clockwise and has a positive area; no edge is shared by more than two
/// triangles; `triangle_region` has one valid region index per triangle; every edge of an
/// edge set is an edge of a triangle, stored with its nodes ascending, the list sorted and
/// unique; every node set is sorted and unique and contains the nodes of the edge set of the
/// same name, if any.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Mesh {
    /// Node coordinates `[x, y]` (m).
    pub nodes: Vec<[f64; 2]>,
    /// Triangles as node indices, counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
    /// Region index (into `regions`) of each triangle.
    pub triangle_region: Vec<u32>,
    /// The regions.
    pub regions: Vec<Region>,
    /// Named lines of the mesh (boundary parts, interfaces, pre-cracks): edges as node pairs.
    pub edge_sets: BTreeMap<String, Vec<[u32; 2]>>,
    /// Named node sets (sorted, unique).
    pub node_sets: BTreeMap<String, Vec<u32>>,
}

/// Minimum, mean and maximum length of the distinct edges of a mesh (m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgeLengthStats {
    /// Shortest edge (m).
    pub min: f64,
    /// Mean edge length (m).
    pub mean: f64,
    /// Longest edge (m).
    pub max: f64,
    /// Number of distinct edges.
    pub count: usize,
}

/// The edge key of two nodes: the pair with the smaller index first.
pub(crate) fn edge_key(a: u32, b: u32) -> [u32; 2] {
    if a < b {
        [a, b]
    } else {
        [b, a]
    }
}

/// Twice the signed area of the triangle `a, b, c` (m^2): positive when counter-clockwise.
pub(crate) fn doubled_signed_area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether the triangle `a, b, c` has a (near) zero area: its doubled area is at most
/// `DEGENERACY` times the square of its longest edge, in either orientation.
pub(crate) fn is_degenerate(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let longest2 = dist2(a, b).max(dist2(b, c)).max(dist2(c, a));
    doubled_signed_area(a, b, c).abs() <= DEGENERACY * longest2
}

fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

impl Mesh {
    /// Builds a mesh from nodes (m), triangles, their region indices and the regions, with no
    /// edge or node set. Clockwise triangles are turned counter-clockwise (two nodes swapped).
    ///
    /// Errors (kind [`MeshErrorKind::Invalid`](crate::MeshErrorKind::Invalid), origin `mesh`): a
    /// non-finite coordinate, a node index out of range, a triangle with a repeated node or a
    /// (near) zero area, a region index out of range, a length mismatch between `triangles`
    /// and `triangle_region`, an edge shared by more than two triangles.
    pub fn new(
        nodes: Vec<[f64; 2]>,
        mut triangles: Vec<[u32; 3]>,
        triangle_region: Vec<u32>,
        regions: Vec<Region>,
    ) -> Result<Mesh, MeshError> {
        check_nodes(&nodes)?;
        for (t, tri) in triangles.iter_mut().enumerate() {
            check_triangle_indices(t, tri, nodes.len())?;
            let [a, b, c] = tri.map(|n| nodes[n as usize]);
            if doubled_signed_area(a, b, c) < 0.0 {
                tri.swap(1, 2);
            }
        }
        let mesh = Mesh {
            nodes,
            triangles,
            triangle_region,
            regions,
            edge_sets: BTreeMap::new(),
            node_sets: BTreeMap::new(),
        };
        mesh.validate()?;
        Ok(mesh)
    }

    /// Adds the edge set `name` (its edges as node pairs, in any order and orientation;
    /// duplicates are merged) and adds its nodes to the node set of the same name.
    ///
    /// Errors: an empty name, a node index out of range, an edge that is not an edge of a
    /// triangle, an existing edge set of that name.
    pub fn with_edge_set(mut self, name: &str, edges: &[[u32; 2]]) -> Result<Mesh, MeshError> {
        let place = format!("edge set `{name}`");
        if name.is_empty() {
            return Err(MeshError::invalid(
                place,
                "an edge set needs a non-empty name",
            ));
        }
        if self.edge_sets.contains_key(name) {
            return Err(MeshError::invalid(
                place,
                "an edge set of that name already exists",
            ));
        }
        let mesh_edges = self.edge_keys();
        let mut keys = Vec::with_capacity(edges.len());
        for &[a, b] in edges {
            let key = edge_key(a, b);
            if !mesh_edges.contains(&key) {
                return Err(MeshError::invalid(
                    place,
                    format!("nodes {a} and {b} are not the ends of an edge of a triangle"),
                ));
            }
            keys.push(key);
        }
        keys.sort_unstable();
        keys.dedup();
        let nodes: Vec<u32> = keys.iter().flatten().copied().collect();
        self.edge_sets.insert(name.to_string(), keys);
        self.with_node_set(name, &nodes)
    }

    /// Adds the nodes to the node set `name` (created if absent; kept sorted and unique).
    ///
    /// Errors: an empty name, a node index out of range.
    pub fn with_node_set(mut self, name: &str, nodes: &[u32]) -> Result<Mesh, MeshError> {
        let place = format!("node set `{name}`");
        if name.is_empty() {
            return Err(MeshError::invalid(
                place,
                "a node set needs a non-empty name",
            ));
        }
        if let Some(&n) = nodes.iter().find(|&&n| n as usize >= self.nodes.len()) {
            return Err(MeshError::invalid(
                place,
                format!(
                    "node {n} out of range (the mesh has {} nodes)",
                    self.nodes.len()
                ),
            ));
        }
        let set = self.node_sets.entry(name.to_string()).or_default();
        set.extend_from_slice(nodes);
        set.sort_unstable();
        set.dedup();
        Ok(self)
    }

    /// Checks every invariant listed on [`Mesh`]; the first violation is the error.
    pub fn validate(&self) -> Result<(), MeshError> {
        check_nodes(&self.nodes)?;
        if self.triangle_region.len() != self.triangles.len() {
            return Err(MeshError::invalid(
                "triangle_region",
                format!(
                    "{} region indices for {} triangles",
                    self.triangle_region.len(),
                    self.triangles.len()
                ),
            ));
        }
        for (t, tri) in self.triangles.iter().enumerate() {
            check_triangle_indices(t, tri, self.nodes.len())?;
            let [a, b, c] = tri.map(|n| self.nodes[n as usize]);
            if doubled_signed_area(a, b, c) <= 0.0 || is_degenerate(a, b, c) {
                return Err(MeshError::invalid(
                    format!("triangle {t} (nodes {} {} {})", tri[0], tri[1], tri[2]),
                    "degenerate or clockwise triangle (area not positive)",
                ));
            }
        }
        if let Some((t, r)) = (self.triangle_region.iter().enumerate())
            .find(|(_, &r)| r as usize >= self.regions.len())
        {
            return Err(MeshError::invalid(
                format!("triangle {t}"),
                format!(
                    "region index {r} out of range ({} regions)",
                    self.regions.len()
                ),
            ));
        }
        self.neighbours()?;
        let mesh_edges = self.edge_keys();
        for (name, edges) in &self.edge_sets {
            let place = format!("edge set `{name}`");
            if edges.windows(2).any(|w| w[0] >= w[1]) {
                return Err(MeshError::invalid(place, "edges not sorted and unique"));
            }
            if let Some(e) = edges
                .iter()
                .find(|e| e[0] >= e[1] || !mesh_edges.contains(*e))
            {
                return Err(MeshError::invalid(
                    place,
                    format!(
                        "[{}, {}] is not an edge of a triangle (nodes ascending)",
                        e[0], e[1]
                    ),
                ));
            }
            let Some(set) = self.node_sets.get(name) else {
                return Err(MeshError::invalid(place, "no node set of the same name"));
            };
            if let Some(n) = edges
                .iter()
                .flatten()
                .find(|n| set.binary_search(n).is_err())
            {
                return Err(MeshError::invalid(
                    place,
                    format!("node {n} missing from the node set of the same name"),
                ));
            }
        }
        for (name, set) in &self.node_sets {
            let place = format!("node set `{name}`");
            if set.windows(2).any(|w| w[0] >= w[1]) {
                return Err(MeshError::invalid(place, "nodes not sorted and unique"));
            }
            if let Some(n) = set.iter().find(|&&n| n as usize >= self.nodes.len()) {
                return Err(MeshError::invalid(place, format!("node {n} out of range")));
            }
        }
        Ok(())
    }

    /// The index of the region called `name`; the error lists the known names.
    pub fn region_index(&self, name: &str) -> Result<u32, MeshError> {
        match self.regions.iter().position(|r| r.name == name) {
            Some(i) => Ok(i as u32),
            None => Err(MeshError::unknown_name(
                "region",
                name,
                self.regions.iter().map(|r| r.name.as_str()),
            )),
        }
    }

    /// The edge set called `name`; the error lists the known names.
    pub fn edge_set(&self, name: &str) -> Result<&[[u32; 2]], MeshError> {
        match self.edge_sets.get(name) {
            Some(edges) => Ok(edges),
            None => Err(MeshError::unknown_name(
                "edge set",
                name,
                self.edge_sets.keys().map(String::as_str),
            )),
        }
    }

    /// The node set called `name`; the error lists the known names.
    pub fn node_set(&self, name: &str) -> Result<&[u32], MeshError> {
        match self.node_sets.get(name) {
            Some(nodes) => Ok(nodes),
            None => Err(MeshError::unknown_name(
                "node set",
                name,
                self.node_sets.keys().map(String::as_str),
            )),
        }
    }

    /// Area of triangle `t` (m^2), signed: positive for a counter-clockwise triangle.
    pub fn triangle_area(&self, t: usize) -> f64 {
        let [a, b, c] = self.triangles[t].map(|n| self.nodes[n as usize]);
        0.5 * doubled_signed_area(a, b, c)
    }

    /// Total area of the triangles (m^2).
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| self.triangle_area(t))
            .sum()
    }

    /// Area of each region (m^2), indexed like `regions`.
    pub fn region_areas(&self) -> Vec<f64> {
        let mut areas = vec![0.0; self.regions.len()];
        for (t, &r) in self.triangle_region.iter().enumerate() {
            areas[r as usize] += self.triangle_area(t);
        }
        areas
    }

    /// The smallest interior angle over all triangles (degrees); 180 for an empty mesh.
    pub fn min_angle_degrees(&self) -> f64 {
        let mut min = std::f64::consts::PI;
        for tri in &self.triangles {
            let p = tri.map(|n| self.nodes[n as usize]);
            for k in 0..3 {
                let (o, u, v) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
                let (ux, uy) = (u[0] - o[0], u[1] - o[1]);
                let (vx, vy) = (v[0] - o[0], v[1] - o[1]);
                let angle = (ux * vy - uy * vx).abs().atan2(ux * vx + uy * vy);
                min = min.min(angle);
            }
        }
        min.to_degrees()
    }

    /// Lengths of the distinct edges (m); all zero for an empty mesh.
    pub fn edge_length_stats(&self) -> EdgeLengthStats {
        let edges = self.edge_keys();
        let (mut min, mut max, mut sum) = (f64::INFINITY, 0.0f64, 0.0);
        for &[a, b] in &edges {
            let l = dist2(self.nodes[a as usize], self.nodes[b as usize]).sqrt();
            min = min.min(l);
            max = max.max(l);
            sum += l;
        }
        if edges.is_empty() {
            min = 0.0;
        }
        EdgeLengthStats {
            min,
            mean: sum / edges.len().max(1) as f64,
            max,
            count: edges.len(),
        }
    }

    /// The set of edge keys (nodes ascending) of all triangles.
    pub(crate) fn edge_keys(&self) -> HashSet<[u32; 2]> {
        let mut keys = HashSet::with_capacity(self.triangles.len() * 2);
        for t in &self.triangles {
            for k in 0..3 {
                keys.insert(edge_key(t[k], t[(k + 1) % 3]));
            }
        }
        keys
    }
}

fn check_nodes(nodes: &[[f64; 2]]) -> Result<(), MeshError> {
    match nodes
        .iter()
        .position(|p| !p[0].is_finite() || !p[1].is_finite())
    {
        Some(i) => Err(MeshError::invalid(
            format!("node {i}"),
            format!("non-finite coordinate {:?}", nodes[i]),
        )),
        None => Ok(()),
    }
}

fn check_triangle_indices(t: usize, tri: &[u32; 3], n_nodes: usize) -> Result<(), MeshError> {
    let place = || format!("triangle {t} (nodes {} {} {})", tri[0], tri[1], tri[2]);
    if let Some(&n) = tri.iter().find(|&&n| n as usize >= n_nodes) {
        return Err(MeshError::invalid(
            place(),
            format!("node index {n} out of range (the mesh has {n_nodes} nodes)"),
        ));
    }
    if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
        return Err(MeshError::invalid(
            place(),
            "a node is repeated (degenerate triangle)",
        ));
    }
    Ok(())
}
