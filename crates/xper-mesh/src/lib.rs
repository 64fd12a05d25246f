//! Triangle meshes in 2D for the fracture engine of xper, where every triangle becomes its
//! own deformable body and a cohesive interface joins each pair of neighbouring triangles.
//!
//! - [`Mesh`]: nodes (m), counter-clockwise 3-node triangles, regions (materials), named
//!   edge sets (boundaries, interfaces, pre-cracks) and node sets; invariant checks
//!   ([`Mesh::validate`]) and quality figures ([`Mesh::min_angle_degrees`],
//!   [`Mesh::edge_length_stats`], [`Mesh::area`]).
//! - [`Mesh::neighbours`]: the interior edges with their two triangles and the boundary
//!   edges ([`Topology`]), and queries by edge set or by pair of regions.
//! - [`Mesh::select_nodes`]: nodes by set name, near a segment, or in a box
//!   ([`NodeSelector`]).
//! - [`read_msh`]: Gmsh MSH 4.1 files, ASCII and binary, with physical groups.
//! - [`rectangle_with_inclusions`] and [`double_edge_notched`]: the two specimens of the
//!   paper, meshed by constrained Delaunay refinement (spade); [`periodic_cell`]: a periodic
//!   cell with circular inclusions (placed or random) that wrap across its sides.
//! - [`Mesh::periodic_edges`]: the boundary edges of a periodic cell matched to their images.
//!
//! Every failure is a [`MeshError`] naming the origin (file path or generator), the place
//! and the reason.

#![warn(missing_docs)]

mod error;
mod generate;
mod mesh;
mod msh;
mod periodic;
mod select;
mod topology;

pub use error::{MeshError, MeshErrorKind};
pub use generate::{
    double_edge_notched, estimated_triangles, periodic_cell, rectangle_with_inclusions, Circle,
    NotchedSpec, PeriodicCellSpec, RandomCircles, RectangleSpec, MAX_AREA_FACTOR, MAX_TRIANGLES,
    MIN_ANGLE_DEGREES,
};
pub use mesh::{EdgeLengthStats, Mesh, Region};
pub use msh::{parse_msh, read_msh};
pub use periodic::{PeriodicCell, PeriodicEdge};
pub use select::NodeSelector;
pub use topology::{BoundaryEdge, InteriorEdge, Topology};
