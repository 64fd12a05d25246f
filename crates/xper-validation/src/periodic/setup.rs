//! Periodic cells for the validation cases: structured meshes, a model builder, the isotropic
//! plane-strain tangent the exact answers are written in, the Hashin-Shtrikman bounds and the
//! series estimate of the interfaces' compliance (units: m, Pa, Pa/m, J).

use xper_bodies::TimeFunction;
use xper_fem::{Hypothesis, Material};
use xper_fracture::{
    FractureModel, FractureSpec, InterfaceLaw, InterfaceRule, MacroDrive, MassMatrix, PeriodicSpec,
};
use xper_laws::cohesive::CohesiveZone;
use xper_mesh::{Mesh, PeriodicCell, Region};
use xper_solver::NlgsParams;

/// The paper's bimaterial (BRIEF.md section 6): matrix and inclusion `(E (Pa), nu)`.
pub(super) const MATRIX: (f64, f64) = (99e9, 0.325);
pub(super) const INCLUSION: (f64, f64) = (135e9, 0.32);

/// A `nx x ny` grid of squares on `[0, w] x [0, h]`, each cut into two triangles along
/// alternating diagonals; region 1 where `second(centroid)`, else 0.
pub(super) fn grid(
    nx: usize,
    ny: usize,
    w: f64,
    h: f64,
    second: impl Fn([f64; 2]) -> bool,
) -> Result<Mesh, String> {
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
    Mesh::new(nodes, triangles, regions, names.to_vec())
        .map_err(|e| format!("grid {nx} x {ny}: {e}"))
}

/// A cohesive zone of stiffness `c` (Pa/m) both ways that does not damage below a jump of
/// 1 mm.
pub(super) fn stiff_zone(c: f64) -> CohesiveZone {
    weak_zone(c, c * 1e-3, c * 1e-6)
}

/// A cohesive zone that breaks: stiffness `c` (Pa/m) both ways, strength `r` (Pa), fracture
/// energy `w` (J/m^2), no friction.
pub(super) fn weak_zone(c: f64, r: f64, w: f64) -> CohesiveZone {
    CohesiveZone {
        normal_stiffness: c,
        tangential_stiffness: c,
        fracture_energy: w,
        strength: r,
        initial_damage: 1.0,
        friction: 0.0,
    }
}

/// An elastic material of density 7850 kg/m^3.
pub(super) fn elastic(young: f64, poisson: f64) -> Material {
    Material::LinearElastic {
        young,
        poisson,
        density: 7850.0,
    }
}

/// The model of `mesh` as a periodic cell (its bounding box) with materials `[matrix,
/// inclusion]`, one cohesive zone everywhere, and `drives`.
pub(super) fn cell_model(
    mesh: Mesh,
    materials: [Material; 2],
    zone: CohesiveZone,
    drives: [MacroDrive; 3],
    dt: f64,
) -> Result<FractureModel, String> {
    let rules = [[0, 0], [0, 1], [1, 1]].map(|regions| InterfaceRule {
        regions,
        law: InterfaceLaw::Cohesive(zone),
    });
    cell_model_with(mesh, materials.to_vec(), rules.to_vec(), drives, dt)
}

/// The model of `mesh` as a periodic cell (its bounding box) with a material per region and
/// these interface rules; plane strain, thickness 1 m, theta = 1/2, Anderson-accelerated NLGS
/// at a tolerance of 1e-8.
pub(super) fn cell_model_with(
    mesh: Mesh,
    materials: Vec<Material>,
    rules: Vec<InterfaceRule>,
    drives: [MacroDrive; 3],
    dt: f64,
) -> Result<FractureModel, String> {
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
    FractureModel::new(mesh, spec).map_err(|e| format!("periodic cell: {e}"))
}

/// Every component at zero strain.
pub(super) fn fixed() -> [MacroDrive; 3] {
    std::array::from_fn(|_| MacroDrive::Strain(TimeFunction::Constant(0.0)))
}

/// Lame's `(lambda, mu)` of `E` (Pa) and `nu`.
pub(super) fn lame(young: f64, poisson: f64) -> (f64, f64) {
    let mu = young / (2.0 * (1.0 + poisson));
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    (lambda, mu)
}

/// The plane-strain tangent of an isotropic material, Voigt `[xx, yy, xy]`, engineering shear.
pub(super) fn tangent(young: f64, poisson: f64) -> [[f64; 3]; 3] {
    let (l, m) = lame(young, poisson);
    [[l + 2.0 * m, l, 0.0], [l, l + 2.0 * m, 0.0], [0.0, 0.0, m]]
}

/// Largest entry difference over the largest entry.
pub(super) fn relative_difference(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> f64 {
    let scale = b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let d = (0..9).fold(0.0f64, |d, k| {
        d.max((a[k / 3][k % 3] - b[k / 3][k % 3]).abs())
    });
    d / scale
}

/// 3x3 inverse.
pub(super) fn inverse(c: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1])
        - c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0])
        + c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0]);
    let cof = |r: usize, k: usize| {
        let (r0, r1) = ((r + 1) % 3, (r + 2) % 3);
        let (k0, k1) = ((k + 1) % 3, (k + 2) % 3);
        c[r0][k0] * c[r1][k1] - c[r0][k1] * c[r1][k0]
    };
    std::array::from_fn(|i| std::array::from_fn(|j| cof(j, i) / det))
}

/// The two-dimensional Hashin-Shtrikman bounds `(lower, upper)` of the in-plane bulk modulus
/// `lambda + mu` and of the shear modulus for the inclusion at area fraction `f2` in the
/// matrix (well ordered, the inclusion stiffer): S. Torquato, Random Heterogeneous Materials,
/// Springer (2002), eqs. 21.23-21.24 with d = 2 (Z. Hashin, J. Mech. Phys. Solids 13 (1965)
/// 119).
pub(super) fn hashin_shtrikman(f2: f64) -> ([f64; 2], [f64; 2]) {
    let k = |(e, nu): (f64, f64)| {
        let (l, m) = lame(e, nu);
        (l + m, m)
    };
    let (k1, m1) = k(MATRIX);
    let (k2, m2) = k(INCLUSION);
    let f1 = 1.0 - f2;
    let bulk =
        |ka: f64, ma: f64, kb: f64, fa: f64, fb: f64| ka + fb / (1.0 / (kb - ka) + fa / (ka + ma));
    let shear = |ka: f64, ma: f64, mb: f64, fa: f64, fb: f64| {
        ma + fb / (1.0 / (mb - ma) + fa * (ka + 2.0 * ma) / (2.0 * ma * (ka + ma)))
    };
    (
        [bulk(k1, m1, k2, f1, f2), bulk(k2, m2, k1, f2, f1)],
        [shear(k1, m1, m2, f1, f2), shear(k2, m2, m1, f2, f1)],
    )
}

/// The compliance `S_est = S + sum_p (A_p / V) N_p^T diag(1 / C_N, 1 / C_T) N_p` of a cell of
/// one material in which every interface point carries the traction of the uniform stress
/// (`N_p` maps the stress to the point's normal and tangential traction): the series
/// estimate. A uniform stress with these point forces is statically admissible, so by the
/// principle of minimum complementary energy the estimate bounds the compliance from above;
/// it is not exact to first order in `1 / C`, because the forces of the springs around a
/// node may also circulate (the ring is statically indeterminate) and the cell takes the
/// cheapest distribution.
pub(super) fn series_compliance(m: &FractureModel, young: f64, poisson: f64) -> [[f64; 3]; 3] {
    let mut s = inverse(&tangent(young, poisson));
    let volume = m.spec.periodic.as_ref().map_or(1.0, |p| p.cell.area()) * m.spec.thickness;
    for i in &m.interfaces {
        let InterfaceLaw::Cohesive(z) = m.laws[i.law as usize] else {
            continue;
        };
        let [nx, ny] = i.normal;
        let rows = [
            [nx * nx, ny * ny, 2.0 * nx * ny],
            [-nx * ny, nx * ny, nx * nx - ny * ny],
        ];
        let weight = i.length * m.spec.thickness / volume;
        let inv = [1.0 / z.normal_stiffness, 1.0 / z.tangential_stiffness];
        for (a, row) in s.iter_mut().enumerate() {
            for (b, entry) in row.iter_mut().enumerate() {
                *entry += weight
                    * (0..2)
                        .map(|k| inv[k] * rows[k][a] * rows[k][b])
                        .sum::<f64>();
            }
        }
    }
    s
}
