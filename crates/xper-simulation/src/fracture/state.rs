//! A fracture model as named arrays ([`xper_run::state`]): the mesh's nodes, the elements (each
//! a body with its own copy of its three nodes) and the cohesive interfaces between them.

use super::frames::{is_damaged, point_position};
use xper_fracture::FractureModel;
use xper_run::state::{ArrayInfo, StateArray};

/// The arrays of a fracture model.
pub const ARRAYS: [ArrayInfo; 16] = [
    ArrayInfo::read_only(
        "nodes.position",
        "(n, 2)",
        "float64",
        "m",
        "the mesh's nodes, unloaded",
    ),
    ArrayInfo::read_only(
        "nodes.displacement",
        "(n, 2)",
        "float64",
        "m",
        "nodal displacement: the mean of the node's copies in its elements",
    ),
    ArrayInfo::read_only(
        "elements.nodes",
        "(n, 3)",
        "int64",
        "1",
        "the triangle's mesh nodes, counter-clockwise",
    ),
    ArrayInfo::read_only(
        "elements.region",
        "(n,)",
        "int64",
        "1",
        "the element's region (material)",
    ),
    ArrayInfo::read_only(
        "elements.displacement",
        "(n, 3, 2)",
        "float64",
        "m",
        "displacement of the element's own copy of each node",
    ),
    ArrayInfo::read_only(
        "elements.velocity",
        "(n, 3, 2)",
        "float64",
        "m/s",
        "velocity of each node copy",
    ),
    ArrayInfo::read_only(
        "elements.stress",
        "(n, 4)",
        "float64",
        "Pa",
        "stress xx, yy, zz, xy (constant over the triangle)",
    ),
    ArrayInfo::read_only(
        "elements.von_mises",
        "(n,)",
        "float64",
        "Pa",
        "von Mises equivalent stress",
    ),
    ArrayInfo::read_only(
        "elements.plastic_strain",
        "(n,)",
        "float64",
        "1",
        "equivalent plastic strain (J2 materials; 0 otherwise)",
    ),
    ArrayInfo::read_only(
        "interfaces.elements",
        "(n, 2)",
        "int64",
        "1",
        "the two elements the interface joins",
    ),
    ArrayInfo::read_only(
        "interfaces.point",
        "(n, 2, 2)",
        "float64",
        "m",
        "the interface's two points (mean of the copies on either side)",
    ),
    ArrayInfo::read_only("interfaces.length", "(n,)", "float64", "m", "edge length"),
    ArrayInfo::read_only(
        "interfaces.intensity",
        "(n, 2)",
        "float64",
        "1",
        "adhesion intensity beta at each point: 1 sound, 0 broken (damage is 1 - beta)",
    ),
    ArrayInfo::read_only(
        "interfaces.jump",
        "(n, 2, 2)",
        "float64",
        "m",
        "displacement jump (normal, tangential) at each point",
    ),
    ArrayInfo::read_only(
        "interfaces.status",
        "(n,)",
        "int64",
        "1",
        "0 sound, 1 damaged, 2 broken",
    ),
    ArrayInfo::read_only("world.time", "(1,)", "float64", "s", "simulated time"),
];

/// The array `name` of `m`.
pub fn array(m: &FractureModel, name: &str) -> Option<StateArray> {
    let (els, ifs) = (&m.elements, &m.interfaces);
    let (ne, ni, nn) = (els.len(), ifs.len(), m.mesh.nodes.len());
    Some(match name {
        "nodes.position" => StateArray::reals(
            &[nn, 2],
            m.mesh.nodes.iter().flat_map(|x| [x[0], x[1]]).collect(),
        ),
        "nodes.displacement" => {
            let mut sum = vec![0.0; 2 * nn];
            let mut count = vec![0u32; nn];
            for el in els {
                for (j, &node) in el.mesh_nodes.iter().enumerate() {
                    let k = node as usize;
                    sum[2 * k] += el.displacement[2 * j];
                    sum[2 * k + 1] += el.displacement[2 * j + 1];
                    count[k] += 1;
                }
            }
            for (k, c) in count.iter().enumerate().filter(|(_, &c)| c > 0) {
                sum[2 * k] /= *c as f64;
                sum[2 * k + 1] /= *c as f64;
            }
            StateArray::reals(&[nn, 2], sum)
        }
        "elements.nodes" => StateArray::integers(
            &[ne, 3],
            els.iter()
                .flat_map(|e| e.mesh_nodes.map(i64::from))
                .collect(),
        ),
        "elements.region" => {
            StateArray::integers(&[ne], els.iter().map(|e| e.region as i64).collect())
        }
        "elements.displacement" => StateArray::reals(
            &[ne, 3, 2],
            els.iter().flat_map(|e| e.displacement).collect(),
        ),
        "elements.velocity" => {
            StateArray::reals(&[ne, 3, 2], els.iter().flat_map(|e| e.velocity).collect())
        }
        "elements.stress" => StateArray::reals(
            &[ne, 4],
            els.iter()
                .flat_map(|e| {
                    let s = e.state.stress;
                    [s[0], s[1], s[2], s[3]]
                })
                .collect(),
        ),
        "elements.von_mises" => {
            StateArray::reals(&[ne], els.iter().map(|e| e.state.von_mises()).collect())
        }
        "elements.plastic_strain" => StateArray::reals(
            &[ne],
            els.iter()
                .map(|e| e.state.equivalent_plastic_strain)
                .collect(),
        ),
        "interfaces.elements" => StateArray::integers(
            &[ni, 2],
            ifs.iter().flat_map(|i| i.elements.map(i64::from)).collect(),
        ),
        "interfaces.point" => StateArray::reals(
            &[ni, 2, 2],
            ifs.iter()
                .flat_map(|i| [point_position(m, i, 0), point_position(m, i, 1)].concat())
                .collect(),
        ),
        "interfaces.length" => StateArray::reals(&[ni], ifs.iter().map(|i| i.length).collect()),
        "interfaces.intensity" => StateArray::reals(
            &[ni, 2],
            ifs.iter()
                .flat_map(|i| i.points.map(|p| p.intensity))
                .collect(),
        ),
        "interfaces.jump" => StateArray::reals(
            &[ni, 2, 2],
            ifs.iter()
                .flat_map(|i| i.points.iter().flat_map(|p| p.jump).collect::<Vec<_>>())
                .collect(),
        ),
        "interfaces.status" => StateArray::integers(
            &[ni],
            ifs.iter()
                .map(|i| match (m.is_broken(i), is_damaged(m, i)) {
                    (true, _) => 2,
                    (false, true) => 1,
                    _ => 0,
                })
                .collect(),
        ),
        "world.time" => StateArray::reals(&[1], vec![m.time]),
        _ => return None,
    })
}
