//! VTU frames of a fracture run: the exploded elements as triangles (each with its own three
//! points, so that cracks open visibly) and the interfaces as lines.

use crate::outputs::{f64_array, i32_array};
use xper_fracture::{FractureModel, Interface, InterfaceLaw};
use xper_io::vtu::{VTK_LINE, VTK_TRIANGLE};
use xper_io::UnstructuredGrid;

/// Current position (m) of local node `j` of element `e`: reference plus displacement.
pub fn node_position(m: &FractureModel, e: usize, j: usize) -> [f64; 2] {
    let el = &m.elements[e];
    let x = m.mesh.nodes[el.mesh_nodes[j] as usize];
    [
        x[0] + el.displacement[2 * j],
        x[1] + el.displacement[2 * j + 1],
    ]
}

/// The elements: one VTK triangle per element at its displaced nodes. Point data
/// `displacement` (m); cell data `stress_xx`, `stress_yy`, `stress_xy`, `stress_zz` (Pa),
/// `von_mises` (Pa), `strain_xx`, `strain_yy`, `strain_xy` (tensor components, the shear
/// being half the engineering shear), `equivalent_plastic_strain`, `velocity` (m/s, mean of
/// the three nodes), `region` (index into the mesh's regions) and `element` (index).
pub fn elements_grid(m: &FractureModel) -> UnstructuredGrid {
    let n = m.elements.len();
    let mut g = UnstructuredGrid::default();
    g.points.reserve(3 * n);
    let mut displacement = Vec::with_capacity(9 * n);
    let mut columns: [Vec<f64>; 9] = std::array::from_fn(|_| Vec::with_capacity(n));
    let mut velocity = Vec::with_capacity(3 * n);
    for (e, el) in m.elements.iter().enumerate() {
        let first = g.points.len() as i64;
        for j in 0..3 {
            let p = node_position(m, e, j);
            g.points.push([p[0], p[1], 0.0]);
            displacement.extend([el.displacement[2 * j], el.displacement[2 * j + 1], 0.0]);
        }
        g.add_cell(VTK_TRIANGLE, &[first, first + 1, first + 2]);
        let s = el.state.stress;
        let strain = el.triangle.strain(&el.displacement);
        let values = [
            s[0],
            s[1],
            s[3],
            s[2],
            el.state.von_mises(),
            strain[0],
            strain[1],
            0.5 * strain[2],
            el.state.equivalent_plastic_strain,
        ];
        for (c, v) in columns.iter_mut().zip(values) {
            c.push(v);
        }
        let v = &el.velocity;
        velocity.extend([(v[0] + v[2] + v[4]) / 3.0, (v[1] + v[3] + v[5]) / 3.0, 0.0]);
    }
    g.point_data = vec![f64_array("displacement", 3, displacement)];
    let names = [
        "stress_xx",
        "stress_yy",
        "stress_xy",
        "stress_zz",
        "von_mises",
        "strain_xx",
        "strain_yy",
        "strain_xy",
        "equivalent_plastic_strain",
    ];
    g.cell_data = (names.iter().zip(columns))
        .map(|(name, values)| f64_array(name, 1, values))
        .collect();
    g.cell_data.push(f64_array("velocity", 3, velocity));
    g.cell_data.push(i32_array(
        "region",
        m.elements.iter().map(|e| e.region as i32).collect(),
    ));
    g.cell_data
        .push(i32_array("element", (0..n as i32).collect::<Vec<i32>>()));
    g
}

/// Position (m) of point `k` of an interface: the mean of its two copies. The copy in `b` of
/// an interface across the sides of a periodic cell is brought back by the deformed period
/// `(I + E) T`, so that the point sits on the lower side (`x = x0` or `y = y0`).
pub fn point_position(m: &FractureModel, i: &Interface, k: usize) -> [f64; 2] {
    let [a, b] = i.elements.map(|e| e as usize);
    let [la, lb] = i.local_nodes[k].map(usize::from);
    let (pa, pb) = (node_position(m, a, la), node_position(m, b, lb));
    let shift = deformed_period(m, i);
    [
        0.5 * (pa[0] + (pb[0] - shift[0])),
        0.5 * (pa[1] + (pb[1] - shift[1])),
    ]
}

/// `(I + E) T` (m) of an interface across the sides of a periodic cell, zero otherwise.
pub fn deformed_period(m: &FractureModel, i: &Interface) -> [f64; 2] {
    let strain = m.cell.map_or([0.0; 3], |c| c.strain);
    let et = xper_fracture::strain_times(&strain, i.period);
    [i.period[0] + et[0], i.period[1] + et[1]]
}

/// Whether a cohesive interface has lost some adhesion without being fully broken.
pub fn is_damaged(m: &FractureModel, i: &Interface) -> bool {
    match m.laws[i.law as usize] {
        InterfaceLaw::Cohesive(z) => {
            !m.is_broken(i) && i.points.iter().any(|p| p.intensity < z.initial_damage)
        }
        InterfaceLaw::Contact { .. } => false,
    }
}

/// The interfaces: one VTK line per interface, from point 0 to point 1 (each at the mean of
/// its two copies; an interface across the sides of a periodic cell on the lower side). Cell data: `beta` (mean intensity of the two points) and `beta_min`,
/// `opening` and `sliding` (mean normal and tangential jumps, m), `normal_traction` and
/// `tangential_traction` (mean of impulse / (dt length/2 thickness), Pa; the normal one is
/// positive when it pushes the sides apart, negative when cohesion holds them together),
/// `broken` (1 for a fully broken cohesive interface), `law` (index of the law).
pub fn interfaces_grid(m: &FractureModel) -> UnstructuredGrid {
    let n = m.interfaces.len();
    let mut g = UnstructuredGrid::default();
    g.points.reserve(2 * n);
    let mut columns: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(n));
    let (mut broken, mut law) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in &m.interfaces {
        let first = g.points.len() as i64;
        for k in 0..2 {
            let p = point_position(m, i, k);
            g.points.push([p[0], p[1], 0.0]);
        }
        g.add_cell(VTK_LINE, &[first, first + 1]);
        let area = 0.5 * i.length * m.spec.thickness;
        let mean = |f: &dyn Fn(&xper_fracture::PointState) -> f64| {
            0.5 * (f(&i.points[0]) + f(&i.points[1]))
        };
        let to_traction = 1.0 / (m.spec.dt * area);
        let values = [
            mean(&|p| p.intensity),
            i.points[0].intensity.min(i.points[1].intensity),
            mean(&|p| p.jump[0]),
            mean(&|p| p.jump[1]),
            mean(&|p| p.impulse[0]) * to_traction,
            mean(&|p| p.impulse[1]) * to_traction,
        ];
        for (c, v) in columns.iter_mut().zip(values) {
            c.push(v);
        }
        broken.push(i32::from(m.is_broken(i)));
        law.push(i32::from(i.law));
    }
    let names = [
        "beta",
        "beta_min",
        "opening",
        "sliding",
        "normal_traction",
        "tangential_traction",
    ];
    g.cell_data = (names.iter().zip(columns))
        .map(|(name, values)| f64_array(name, 1, values))
        .collect();
    g.cell_data.push(i32_array("broken", broken));
    g.cell_data.push(i32_array("law", law));
    g
}
