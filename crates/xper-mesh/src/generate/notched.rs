//! The double-edge-notched square of Nooru-Mohamed (M. B. Nooru-Mohamed, "Mixed-mode
//! fracture of concrete: an experimental approach", PhD thesis, Delft University of
//! Technology, 1992): a 200 mm square with two 25 mm deep, 5 mm wide notches at mid-height.

use serde::{Deserialize, Serialize};

use super::symmetric::point_symmetric;
use super::{check_count, finish_mesh, positive, triangulate, Line, Pslg};
use crate::error::{MeshError, MeshErrorKind};
use crate::mesh::{Mesh, Region};

const ORIGIN: &str = "double_edge_notched";

/// The square `[0, side]^2` with a rectangular notch cut into the middle of its left and
/// right edges.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NotchedSpec {
    /// Side of the square (m); 0.2 in the experiment.
    pub side: f64,
    /// Depth of each notch, along x (m), less than half the side; 0.025 in the experiment.
    pub notch_depth: f64,
    /// Width of each notch, along y (m), less than the side; 0.005 in the experiment.
    pub notch_width: f64,
    /// Target element size `h` (m): no boundary piece is longer than `h`.
    pub element_size: f64,
    /// Make the mesh invariant under the half-turn about the square's centre (see
    /// [`super::symmetric`]), as the specimen and a point-symmetric loading are; off by
    /// default.
    #[serde(default)]
    pub point_symmetric: bool,
}

/// Meshes the notched square of `spec`; no triangle lies in a notch.
///
/// Region: `concrete` (tag 1). Edge sets (each with its node set): `bottom`, `top`,
/// `left_lower` and `left_upper` (the left edge below and above the notch), `right_lower`,
/// `right_upper`, `notch_left` and `notch_right` (the three faces of each notch).
///
/// Errors (kind [`MeshErrorKind::Spec`]): a non-positive or non-finite size, notches that would
/// meet or cut the square apart, an element size giving more than
/// [`MAX_TRIANGLES`](super::MAX_TRIANGLES).
pub fn double_edge_notched(spec: &NotchedSpec) -> Result<Mesh, MeshError> {
    let (s, d, nw, h) = (
        spec.side,
        spec.notch_depth,
        spec.notch_width,
        spec.element_size,
    );
    positive(ORIGIN, "side", s)?;
    positive(ORIGIN, "notch_depth", d)?;
    positive(ORIGIN, "notch_width", nw)?;
    positive(ORIGIN, "element_size", h)?;
    if 2.0 * d >= s {
        return Err(MeshError::new(
            MeshErrorKind::Spec,
            ORIGIN,
            format!("two notches {d} m deep would meet in a square of side {s} m"),
        )
        .at("notch_depth"));
    }
    if nw >= s {
        return Err(MeshError::new(
            MeshErrorKind::Spec,
            ORIGIN,
            format!("a notch {nw} m wide would cut the square of side {s} m"),
        )
        .at("notch_width"));
    }
    check_count(ORIGIN, s * s, h)?;
    let (lo, hi) = (0.5 * (s - nw), 0.5 * (s + nw));
    let (xl, xr) = (d, s - d);
    let lines = vec![
        Line {
            a: [0.0, 0.0],
            b: [s, 0.0],
            set: "bottom",
        },
        Line {
            a: [s, 0.0],
            b: [s, lo],
            set: "right_lower",
        },
        Line {
            a: [s, lo],
            b: [xr, lo],
            set: "notch_right",
        },
        Line {
            a: [xr, lo],
            b: [xr, hi],
            set: "notch_right",
        },
        Line {
            a: [xr, hi],
            b: [s, hi],
            set: "notch_right",
        },
        Line {
            a: [s, hi],
            b: [s, s],
            set: "right_upper",
        },
        Line {
            a: [s, s],
            b: [0.0, s],
            set: "top",
        },
        Line {
            a: [0.0, s],
            b: [0.0, hi],
            set: "left_upper",
        },
        Line {
            a: [0.0, hi],
            b: [xl, hi],
            set: "notch_left",
        },
        Line {
            a: [xl, hi],
            b: [xl, lo],
            set: "notch_left",
        },
        Line {
            a: [xl, lo],
            b: [0.0, lo],
            set: "notch_left",
        },
        Line {
            a: [0.0, lo],
            b: [0.0, 0.0],
            set: "left_lower",
        },
    ];
    let mut pslg = Pslg::default();
    for line in &lines {
        pslg.add_line(line.a, line.b, &[], h);
    }
    let in_notch = |p: [f64; 2]| p[1] > lo && p[1] < hi && (p[0] < xl || p[0] > xr);
    let mut raw = triangulate(
        ORIGIN,
        pslg,
        h,
        super::Refine {
            exclude_outer: true,
            keep_lines: false,
        },
        |p| !in_notch(p),
        &lines,
    )?;
    if spec.point_symmetric {
        let centre = [0.5 * s, 0.5 * s];
        raw = point_symmetric(ORIGIN, &raw, centre, 0.0, h, &lines, |p| !in_notch(p))?;
    }
    let n = raw.triangles.len();
    let regions = vec![Region {
        name: "concrete".into(),
        tag: 1,
    }];
    let sets = [
        "bottom",
        "top",
        "left_lower",
        "left_upper",
        "right_lower",
        "right_upper",
        "notch_left",
        "notch_right",
    ];
    finish_mesh(ORIGIN, raw, vec![0; n], regions, &lines, h, &sets)
}
