//! Periodic cells: the boundary of a mesh filling a rectangle `[x0, x0 + W] x [y0, y0 + H]`
//! matched side to side, so that each boundary edge on `x = x0` (`y = y0`) meets its image on
//! `x = x0 + W` (`y = y0 + H`) translated by the period `(W, 0)` (`(0, H)`). The fracture
//! engine joins each matched pair by a cohesive interface, as it joins neighbouring triangles
//! inside the cell (periodic homogenization: F. Perales, S. Bourgeois, A. Chrysochoos,
//! Y. Monerie, Eng. Fract. Mech. 75 (2008) 3378).

use std::collections::HashMap;

use serde::{Deserialize, Serialize};

use crate::error::MeshError;
use crate::mesh::{edge_key, Mesh};

/// A rectangular periodic cell (m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeriodicCell {
    /// Lower corner `[x0, y0]` (m).
    pub lower: [f64; 2],
    /// Side lengths `[W, H]` (m), both > 0.
    pub size: [f64; 2],
}

impl PeriodicCell {
    /// The bounding box of the nodes of `mesh`.
    pub fn bounding(mesh: &Mesh) -> PeriodicCell {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &mesh.nodes {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        PeriodicCell {
            lower: lo,
            size: [hi[0] - lo[0], hi[1] - lo[1]],
        }
    }

    /// Area of the cell `W H` (m^2).
    pub fn area(&self) -> f64 {
        self.size[0] * self.size[1]
    }

    /// The period along `axis`: `(W, 0)` or `(0, H)` (m).
    pub fn period(&self, axis: usize) -> [f64; 2] {
        let mut t = [0.0; 2];
        t[axis] = self.size[axis];
        t
    }

    /// The tolerance (m) within which two coordinates are the same point: `1e-9` of the
    /// larger side.
    pub fn tolerance(&self) -> f64 {
        1e-9 * self.size[0].max(self.size[1])
    }
}

/// A boundary edge on a lower side of the cell and its image on the opposite side: the two
/// triangles that the periodicity makes neighbours.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PeriodicEdge {
    /// Triangles `[a, b]`: `a` touches the lower side (`x = x0` or `y = y0`), `b` the upper.
    pub triangles: [u32; 2],
    /// The edge's nodes `[p, q]` in `a` (counter-clockwise in `a`) and their images `[p', q']`
    /// in `b`: `nodes[k] = [node in a, its image in b]`.
    pub nodes: [[u32; 2]; 2],
    /// Unit outward normal of the edge in `a` (pointing out of the cell).
    pub normal: [f64; 2],
    /// Edge length (m).
    pub length: f64,
    /// The period `X_b - X_a` (m): `(W, 0)` or `(0, H)`.
    pub period: [f64; 2],
}

impl Mesh {
    /// The boundary edges of the sides of `cell` matched to their images on the opposite
    /// sides, left-right pairs first, each list in the order of the boundary walk of
    /// [`Mesh::neighbours`] (deterministic).
    ///
    /// Errors (kind [`Invalid`](crate::MeshErrorKind::Invalid)): the mesh does not fill the cell
    /// (its bounding box differs from it by more than [`PeriodicCell::tolerance`]); a node on
    /// a side without a node at the same place on the opposite side (the first few are named
    /// with their coordinates); a boundary edge on a side whose image is not an edge of the
    /// mesh (the sides are cut differently).
    pub fn periodic_edges(&self, cell: &PeriodicCell) -> Result<Vec<PeriodicEdge>, MeshError> {
        let tol = cell.tolerance();
        if !(cell.size[0] > 0.0 && cell.size[1] > 0.0) {
            return Err(MeshError::invalid(
                "periodic cell",
                format!("sides {:?} m must be positive", cell.size),
            ));
        }
        let bbox = PeriodicCell::bounding(self);
        for d in 0..2 {
            let (lo, hi) = (bbox.lower[d], bbox.lower[d] + bbox.size[d]);
            let (clo, chi) = (cell.lower[d], cell.lower[d] + cell.size[d]);
            if (lo - clo).abs() > tol || (hi - chi).abs() > tol {
                return Err(MeshError::invalid(
                    "periodic cell",
                    format!(
                        "the mesh spans [{lo}, {hi}] m along {} but the cell is [{clo}, {chi}] m",
                        ["x", "y"][d]
                    ),
                ));
            }
        }
        let topology = self.neighbours()?;
        let boundary: HashMap<[u32; 2], usize> = (topology.boundary.iter().enumerate())
            .map(|(i, e)| (edge_key(e.nodes[0], e.nodes[1]), i))
            .collect();
        let mut pairs = Vec::new();
        for axis in 0..2 {
            let on = |n: u32, value: f64| (self.nodes[n as usize][axis] - value).abs() <= tol;
            let (lower, upper) = (cell.lower[axis], cell.lower[axis] + cell.size[axis]);
            let side_nodes = |value: f64| {
                let mut nodes: Vec<u32> = (topology.boundary.iter())
                    .filter(|e| on(e.nodes[0], value) && on(e.nodes[1], value))
                    .flat_map(|e| e.nodes)
                    .collect();
                nodes.sort_unstable();
                nodes.dedup();
                nodes
            };
            let (low_nodes, up_nodes) = (side_nodes(lower), side_nodes(upper));
            let image = self.match_side(axis, lower, upper, &low_nodes, &up_nodes, tol)?;
            let other = 1 - axis;
            for e in &topology.boundary {
                let [p, q] = e.nodes;
                if !(on(p, lower) && on(q, lower)) {
                    continue;
                }
                let [ip, iq] = [p, q].map(|n| image[&n]);
                let Some(&j) = boundary.get(&edge_key(ip, iq)) else {
                    return Err(MeshError::invalid(
                        format!("periodic cell, edge {p}-{q}"),
                        format!(
                            "the edge on {} = {lower} has no image edge {ip}-{iq} on {} = \
                             {upper}: the two sides are cut differently",
                            ["x", "y"][axis],
                            ["x", "y"][axis]
                        ),
                    ));
                };
                let [xp, xq] = [p, q].map(|n| self.nodes[n as usize]);
                let length = (xq[other] - xp[other]).abs();
                let mut normal = [0.0; 2];
                normal[axis] = -1.0;
                pairs.push(PeriodicEdge {
                    triangles: [e.triangle, topology.boundary[j].triangle],
                    nodes: [[p, ip], [q, iq]],
                    normal,
                    length,
                    period: cell.period(axis),
                });
            }
        }
        Ok(pairs)
    }

    /// The image on the upper side of each node of the lower side, checking that the two
    /// sides carry the same nodes.
    fn match_side(
        &self,
        axis: usize,
        lower: f64,
        upper: f64,
        low_nodes: &[u32],
        up_nodes: &[u32],
        tol: f64,
    ) -> Result<HashMap<u32, u32>, MeshError> {
        let other = 1 - axis;
        let along = |n: u32| self.nodes[n as usize][other];
        let sorted = |nodes: &[u32]| {
            let mut v: Vec<(f64, u32)> = nodes.iter().map(|&n| (along(n), n)).collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
        let (low, up) = (sorted(low_nodes), sorted(up_nodes));
        let find = |list: &[(f64, u32)], x: f64| {
            let i = list.partition_point(|e| e.0 < x - tol);
            list.get(i).filter(|e| (e.0 - x).abs() <= tol).map(|e| e.1)
        };
        let name = ["x", "y"][axis];
        let mut missing = Vec::new();
        for (from, to, value, target) in [(&low, &up, lower, upper), (&up, &low, upper, lower)] {
            for &(x, n) in from.iter() {
                if find(to, x).is_none() {
                    let p = self.nodes[n as usize];
                    missing.push(format!(
                        "node {n} at ({}, {}) on {name} = {value} has no image on {name} = {target}",
                        p[0], p[1]
                    ));
                }
            }
        }
        if !missing.is_empty() {
            let count = missing.len();
            missing.truncate(5);
            return Err(MeshError::invalid(
                "periodic cell",
                format!(
                    "{count} unmatched boundary node(s): {}{}",
                    missing.join("; "),
                    if count > 5 { "; ..." } else { "" }
                ),
            ));
        }
        Ok(low
            .iter()
            .map(|&(x, n)| (n, find(&up, x).expect("matched above")))
            .collect())
    }
}
