//! Measures of a crack pattern, to compare a run with the paper's pictures: where the broken
//! interfaces are (left or right of the mid-line, between which regions), how long the cracks
//! are, how far they leave a straight line, and whether the pattern has the point symmetry
//! (a half-turn about the centre) or the mirror symmetry of its specimen.
//!
//! Positions are those of the reference (undeformed) mesh; interfaces of the edge sets that
//! start broken (pre-cracks) are left out.

use std::collections::{BTreeMap, HashMap, HashSet};

use serde::Serialize;
use xper_fracture::{FractureModel, InterfaceLaw};

/// Measures of the broken interfaces of a model (lengths in m).
#[derive(Clone, Debug, Default, Serialize, serde::Deserialize)]
pub struct CrackMetrics {
    /// Interfaces broken during the run (every point at intensity 0).
    pub broken_interfaces: usize,
    /// Their total length (m).
    pub broken_length_m: f64,
    /// Cohesive interfaces damaged but not broken (some point with 0 < intensity < 1).
    pub damaged_interfaces: usize,
    /// Broken length per pair of regions, `"a/b"` with the names in order (m).
    pub broken_length_by_regions: BTreeMap<String, f64>,
    /// Broken length left and right of the vertical mid-line of the mesh (m).
    pub broken_length_left_right_m: [f64; 2],
    /// Height (y extent) of the broken interfaces left and right of the mid-line (m).
    pub height_left_right_m: [f64; 2],
    /// Fraction of the broken length whose image by a half-turn about the mesh centre lies
    /// within 1.5 edge lengths of a broken interface (1: point-symmetric pattern).
    pub point_symmetry: f64,
    /// The same for the mirror image about the vertical mid-line.
    pub mirror_symmetry: f64,
    /// Median interface length (m), the resolution of the measures.
    pub edge_length_m: f64,
}

/// Midpoint of an interface in the reference mesh.
pub fn midpoint(m: &FractureModel, i: &xper_fracture::Interface) -> [f64; 2] {
    let e = &m.elements[i.elements[0] as usize];
    let p: Vec<[f64; 2]> = (i.local_nodes[0].iter())
        .map(|&j| m.mesh.nodes[e.mesh_nodes[j as usize] as usize])
        .collect();
    [0.5 * (p[0][0] + p[1][0]), 0.5 * (p[0][1] + p[1][1])]
}

/// Centre of the bounding box of the reference mesh.
pub fn mesh_centre(m: &FractureModel) -> [f64; 2] {
    let (lo, hi) = m.mesh.nodes.iter().fold(
        ([f64::MAX, f64::MAX], [f64::MIN, f64::MIN]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    );
    [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]
}

/// Mesh-node pairs of the edge sets that start broken.
fn precrack_edges(m: &FractureModel) -> HashSet<[u32; 2]> {
    let mut set = HashSet::new();
    for name in &m.spec.broken_edge_sets {
        for e in m.mesh.edge_sets.get(name).into_iter().flatten() {
            set.insert([e[0].min(e[1]), e[0].max(e[1])]);
        }
    }
    set
}

/// Points within a radius of a query, by a uniform grid of cell `cell`.
struct PointGrid {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<[f64; 2]>>,
}

impl PointGrid {
    fn new(cell: f64, points: &[[f64; 2]]) -> Self {
        let mut cells: HashMap<(i64, i64), Vec<[f64; 2]>> = HashMap::new();
        for p in points {
            cells.entry(Self::key(cell, p)).or_default().push(*p);
        }
        PointGrid { cell, cells }
    }

    fn key(cell: f64, p: &[f64; 2]) -> (i64, i64) {
        ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64)
    }

    /// Whether a point lies within `cell` of `q`.
    fn near(&self, q: &[f64; 2]) -> bool {
        let (kx, ky) = Self::key(self.cell, q);
        (kx - 1..=kx + 1).any(|x| {
            (ky - 1..=ky + 1).any(|y| {
                self.cells.get(&(x, y)).is_some_and(|ps| {
                    ps.iter()
                        .any(|p| (p[0] - q[0]).hypot(p[1] - q[1]) <= self.cell)
                })
            })
        })
    }
}

/// The crack measures of `m` in its current state.
pub fn crack_metrics(m: &FractureModel) -> CrackMetrics {
    let precrack = precrack_edges(m);
    let centre = mesh_centre(m);
    let mut lengths: Vec<f64> = m.interfaces.iter().map(|i| i.length).collect();
    lengths.sort_by(f64::total_cmp);
    let edge = lengths.get(lengths.len() / 2).copied().unwrap_or(0.0);
    let mut out = CrackMetrics {
        edge_length_m: edge,
        ..CrackMetrics::default()
    };
    let mut broken: Vec<([f64; 2], f64)> = vec![];
    let mut y_range = [[f64::MAX, f64::MIN]; 2];
    for i in &m.interfaces {
        if !matches!(m.laws[i.law as usize], InterfaceLaw::Cohesive(_)) {
            continue;
        }
        let e = &m.elements[i.elements[0] as usize];
        let nodes = i.local_nodes[0].map(|j| e.mesh_nodes[j as usize]);
        if precrack.contains(&[nodes[0].min(nodes[1]), nodes[0].max(nodes[1])]) {
            continue;
        }
        if i.points.iter().all(|p| p.intensity == 0.0) {
            let p = midpoint(m, i);
            let side = usize::from(p[0] > centre[0]);
            out.broken_interfaces += 1;
            out.broken_length_m += i.length;
            out.broken_length_left_right_m[side] += i.length;
            y_range[side] = [y_range[side][0].min(p[1]), y_range[side][1].max(p[1])];
            let mut names = i.elements.map(|el| {
                let r = m.elements[el as usize].region as usize;
                m.mesh.regions[r].name.clone()
            });
            names.sort();
            *(out.broken_length_by_regions)
                .entry(format!("{}/{}", names[0], names[1]))
                .or_default() += i.length;
            broken.push((p, i.length));
        } else if i.points.iter().any(|p| p.intensity < 1.0) {
            out.damaged_interfaces += 1;
        }
    }
    out.height_left_right_m = y_range.map(|[a, b]| if b >= a { b - a } else { 0.0 });
    if out.broken_length_m > 0.0 && edge > 0.0 {
        let points: Vec<[f64; 2]> = broken.iter().map(|b| b.0).collect();
        let grid = PointGrid::new(1.5 * edge, &points);
        let matched = |image: &dyn Fn([f64; 2]) -> [f64; 2]| {
            broken
                .iter()
                .filter(|(p, _)| grid.near(&image(*p)))
                .map(|b| b.1)
                .sum::<f64>()
                / out.broken_length_m
        };
        out.point_symmetry = matched(&|p| [2.0 * centre[0] - p[0], 2.0 * centre[1] - p[1]]);
        out.mirror_symmetry = matched(&|p| [2.0 * centre[0] - p[0], p[1]]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The coarse Nooru-Mohamed model (1491 elements), no interface damaged.
    fn model() -> FractureModel {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes/nooru_mohamed_small/scene.toml");
        crate::fracture::build::load_model(&path).unwrap().1
    }

    /// Breaks the interfaces whose reference midpoint satisfies `select`; returns their
    /// total length, computed here independently of `crack_metrics`.
    fn break_where(m: &mut FractureModel, select: impl Fn([f64; 2]) -> bool) -> f64 {
        let chosen: Vec<usize> = (0..m.interfaces.len())
            .filter(|&k| select(midpoint(m, &m.interfaces[k])))
            .collect();
        let mut length = 0.0;
        for k in chosen {
            let i = &mut m.interfaces[k];
            for p in &mut i.points {
                p.intensity = 0.0;
            }
            length += i.length;
        }
        length
    }

    #[test]
    fn a_sound_specimen_has_no_crack() {
        let c = crack_metrics(&model());
        assert_eq!((c.broken_interfaces, c.damaged_interfaces), (0, 0));
        assert_eq!((c.broken_length_m, c.point_symmetry), (0.0, 0.0));
        assert!(
            c.edge_length_m > 0.005 && c.edge_length_m < 0.015,
            "{}",
            c.edge_length_m
        );
    }

    #[test]
    fn a_band_across_the_centre_is_symmetric_and_a_band_on_one_side_is_not() {
        let mut m = model();
        let (centre, edge) = (mesh_centre(&m), crack_metrics(&m).edge_length_m);
        let length = break_where(&mut m, |p| (p[1] - centre[1]).abs() < 0.5 * edge);
        let c = crack_metrics(&m);
        assert!((c.broken_length_m - length).abs() <= 1e-12 * length);
        let [left, right] = c.broken_length_left_right_m;
        assert!((left + right - length).abs() <= 1e-12 * length);
        assert!(
            left > 0.3 * length && right > 0.3 * length,
            "{left} / {right}"
        );
        assert!(
            c.height_left_right_m.iter().all(|&h| h < edge),
            "{:?}",
            c.height_left_right_m
        );
        assert!(c.mirror_symmetry > 0.95 && c.point_symmetry > 0.95, "{c:?}");
        assert_eq!(c.broken_length_by_regions.len(), 1);

        let mut m = model();
        let length = break_where(&mut m, |p| {
            (p[1] - centre[1]).abs() < 0.5 * edge && p[0] < centre[0] - 3.0 * edge
        });
        let c = crack_metrics(&m);
        assert_eq!(c.broken_length_left_right_m, [c.broken_length_m, 0.0]);
        assert!((c.broken_length_m - length).abs() <= 1e-12 * length);
        assert_eq!((c.mirror_symmetry, c.point_symmetry), (0.0, 0.0));
    }

    #[test]
    fn partly_damaged_interfaces_are_counted_apart_from_broken_ones() {
        let mut m = model();
        for (k, i) in m.interfaces.iter_mut().take(10).enumerate() {
            i.points[0].intensity = if k < 4 { 0.5 } else { 0.0 };
            i.points[1].intensity = if k < 7 { 0.5 } else { 0.0 };
        }
        let c = crack_metrics(&m);
        assert_eq!((c.broken_interfaces, c.damaged_interfaces), (3, 7));
    }
}
