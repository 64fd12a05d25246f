//! Periodic cells for the tests: structured and generated meshes, a model builder, and the
//! isotropic plane-strain tangent the exact answers are written in.

#![allow(dead_code)]

use xper_bodies::TimeFunction;
use xper_fem::{Hypothesis, Material};
use xper_fracture::{
    FractureModel, FractureSpec, InterfaceLaw, InterfaceRule, MacroDrive, MassMatrix, PeriodicSpec,
};
use xper_laws::cohesive::CohesiveZone;
use xper_mesh::{Mesh, PeriodicCell, Region};
use xper_solver::NlgsParams;

/// A `nx x ny` grid of squares on `[0, w] x [0, h]`, each cut into two triangles along
/// alternating diagonals; region 1 where `second(centroid)`, else 0.
pub fn grid(nx: usize, ny: usize, w: f64, h: f64, second: impl Fn([f64; 2]) -> bool) -> Mesh {
    let node = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let x = if i == nx { w } else { w * i as f64 / nx as f64 };
            let y = if j == ny { h } else { h * j as f64 / ny as f64 };
            nodes.push([x, y]);
        }
    }
    let (mut triangles, mut regions) = (Vec::new(), Vec::new());
    for j in 0..ny {
        for i in 0..nx {
            let [a, b, c, d] = [
                node(i, j),
                node(i + 1, j),
                node(i + 1, j + 1),
                node(i, j + 1),
            ];
            let pair = if (i + j) % 2 == 0 {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            for t in pair {
                let p = t.map(|n| nodes[n as usize]);
                let centroid = [
                    (p[0][0] + p[1][0] + p[2][0]) / 3.0,
                    (p[0][1] + p[1][1] + p[2][1]) / 3.0,
                ];
                regions.push(u32::from(second(centroid)));
                triangles.push(t);
            }
        }
    }
    let names = ["matrix", "inclusion"].map(|n| Region {
        name: n.into(),
        tag: 1,
    });
    Mesh::new(nodes, triangles, regions, names.to_vec()).unwrap()
}

/// A cohesive zone of stiffness `c` (Pa/m) both ways that does not damage below a jump of
/// 1 mm.
pub fn stiff_zone(c: f64) -> CohesiveZone {
    CohesiveZone {
        normal_stiffness: c,
        tangential_stiffness: c,
        fracture_energy: c * 1e-6,
        strength: c * 1e-3,
        initial_damage: 1.0,
        friction: 0.0,
    }
}

/// An elastic material.
pub fn elastic(young: f64, poisson: f64) -> Material {
    Material::LinearElastic {
        young,
        poisson,
        density: 7850.0,
    }
}

/// The model of `mesh` as a periodic cell (its bounding box) with materials `[matrix,
/// inclusion]`, one cohesive zone of stiffness `c` everywhere, and `drives`.
pub fn cell_model(
    mesh: Mesh,
    materials: [Material; 2],
    zone: CohesiveZone,
    drives: [MacroDrive; 3],
    dt: f64,
) -> FractureModel {
    let rules = [[0, 0], [0, 1], [1, 1]].map(|regions| InterfaceRule {
        regions,
        law: InterfaceLaw::Cohesive(zone),
    });
    cell_model_with(mesh, materials.to_vec(), rules.to_vec(), drives, dt)
}

/// The model of `mesh` as a periodic cell (its bounding box) with a material per region and
/// these interface rules.
pub fn cell_model_with(
    mesh: Mesh,
    materials: Vec<Material>,
    rules: Vec<InterfaceRule>,
    drives: [MacroDrive; 3],
    dt: f64,
) -> FractureModel {
    let cell = PeriodicCell::bounding(&mesh);
    let spec = FractureSpec {
        thickness: 1.0,
        hypothesis: Hypothesis::PlaneStrain,
        materials,
        interface_laws: rules,
        broken_edge_sets: Vec::new(),
        loads: Vec::new(),
        gravity: [0.0, 0.0],
        mass: MassMatrix::Consistent,
        dt,
        theta: 0.5,
        nlgs: NlgsParams {
            tolerance: 1e-8,
            max_iterations: 100_000,
            acceleration: xper_solver::Acceleration::ANDERSON,
            ..Default::default()
        },
        periodic: Some(PeriodicSpec { cell, drives }),
        plastic_stiffness: Default::default(),
    };
    FractureModel::new(mesh, spec).unwrap()
}

/// Every component at zero strain.
pub fn fixed() -> [MacroDrive; 3] {
    std::array::from_fn(|_| MacroDrive::Strain(TimeFunction::Constant(0.0)))
}

/// Lame's `(lambda, mu)` of `E` (Pa) and `nu`.
pub fn lame(young: f64, poisson: f64) -> (f64, f64) {
    let mu = young / (2.0 * (1.0 + poisson));
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    (lambda, mu)
}

/// The plane-strain tangent of an isotropic material, Voigt `[xx, yy, xy]`, engineering shear.
pub fn tangent(young: f64, poisson: f64) -> [[f64; 3]; 3] {
    let (l, m) = lame(young, poisson);
    [[l + 2.0 * m, l, 0.0], [l, l + 2.0 * m, 0.0], [0.0, 0.0, m]]
}

/// Largest entry difference over the largest entry.
pub fn relative_difference(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> f64 {
    let scale = b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut d = 0.0f64;
    for r in 0..3 {
        for c in 0..3 {
            d = d.max((a[r][c] - b[r][c]).abs());
        }
    }
    d / scale
}
