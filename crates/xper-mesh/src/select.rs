//! Node selectors: how a scene names the nodes it loads or holds.

use serde::{Deserialize, Serialize};

use crate::error::{MeshError, MeshErrorKind};
use crate::mesh::Mesh;

/// A way to pick nodes of a mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum NodeSelector {
    /// The node set of that name.
    Set(String),
    /// The nodes at distance at most `tolerance` (m) from the segment `from`-`to` (m).
    Segment {
        /// First end of the segment (m).
        from: [f64; 2],
        /// Second end of the segment (m).
        to: [f64; 2],
        /// Largest distance from the segment (m), non-negative.
        tolerance: f64,
    },
    /// The nodes inside the closed axis-aligned box `min`-`max` (m).
    Box {
        /// Lower-left corner (m).
        min: [f64; 2],
        /// Upper-right corner (m).
        max: [f64; 2],
    },
}

fn selector_error(reason: String) -> MeshError {
    MeshError::new(MeshErrorKind::Selection, "node selector", reason)
}

fn finite(p: &[f64]) -> bool {
    p.iter().all(|v| v.is_finite())
}

/// Distance (m) from `p` to the segment `a`-`b` (a point when `a == b`).
pub(crate) fn distance_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let s = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (a[0] + s * dx, a[1] + s * dy);
    ((p[0] - qx).powi(2) + (p[1] - qy).powi(2)).sqrt()
}

impl Mesh {
    /// The nodes picked by `selector`, sorted and unique. An empty selection is `Ok(vec![])`:
    /// the caller decides whether that is an error.
    ///
    /// Errors: an unknown set name (the message lists the known node sets), a non-finite
    /// coordinate, a negative or non-finite tolerance, a box whose `min` exceeds its `max`.
    pub fn select_nodes(&self, selector: &NodeSelector) -> Result<Vec<u32>, MeshError> {
        let pick = |keep: &dyn Fn([f64; 2]) -> bool| -> Vec<u32> {
            (self.nodes.iter().enumerate())
                .filter(|(_, &p)| keep(p))
                .map(|(i, _)| i as u32)
                .collect()
        };
        match selector {
            NodeSelector::Set(name) => self
                .node_set(name)
                .map(<[u32]>::to_vec)
                .map_err(|e| e.from_origin("node selector")),
            NodeSelector::Segment {
                from,
                to,
                tolerance,
            } => {
                if !finite(from) || !finite(to) {
                    return Err(selector_error(format!(
                        "segment ends {from:?} {to:?} must be finite"
                    )));
                }
                if !(tolerance.is_finite() && *tolerance >= 0.0) {
                    return Err(selector_error(format!(
                        "segment tolerance {tolerance} must be finite and non-negative"
                    )));
                }
                Ok(pick(&|p| distance_to_segment(p, *from, *to) <= *tolerance))
            }
            NodeSelector::Box { min, max } => {
                if !finite(min) || !finite(max) {
                    return Err(selector_error(format!(
                        "box corners {min:?} {max:?} must be finite"
                    )));
                }
                if min[0] > max[0] || min[1] > max[1] {
                    return Err(selector_error(format!(
                        "box min {min:?} exceeds max {max:?}"
                    )));
                }
                Ok(pick(&|p| {
                    p[0] >= min[0] && p[0] <= max[0] && p[1] >= min[1] && p[1] <= max[1]
                }))
            }
        }
    }
}
