//! The linear triangle: kinematics, stiffness, mass, refusals.

use nalgebra::{SMatrix, SymmetricEigen};
use proptest::prelude::*;
use xper_fem::{FemError, Hypothesis, Material, MaterialState, Triangle3};

const NODES: [[f64; 2]; 3] = [[0.1, 0.2], [1.3, 0.4], [0.5, 1.1]];

fn steel() -> Material {
    Material::LinearElastic {
        young: 200e9,
        poisson: 0.3,
        density: 7850.0,
    }
}

/// Nodal displacements of the field `u(x) = c + G x`.
fn linear_field(nodes: &[[f64; 2]; 3], c: [f64; 2], g: [[f64; 2]; 2]) -> [f64; 6] {
    let mut u = [0.0; 6];
    for (a, p) in nodes.iter().enumerate() {
        for i in 0..2 {
            u[2 * a + i] = c[i] + g[i][0] * p[0] + g[i][1] * p[1];
        }
    }
    u
}

fn mat6(k: &[[f64; 6]; 6]) -> SMatrix<f64, 6, 6> {
    SMatrix::from_fn(|i, j| k[i][j])
}

#[test]
fn area_is_the_shoelace_area() {
    let t = Triangle3::new([[0.0, 0.0], [2.0, 0.0], [0.0, 3.0]], 0.5).unwrap();
    assert_eq!(t.area(), 3.0);
    assert_eq!(t.volume(), 1.5);
    assert_eq!(t.thickness(), 0.5);
}

#[test]
fn rigid_motions_give_zero_strain_and_linear_fields_their_exact_strain() {
    let t = Triangle3::new(NODES, 0.01).unwrap();
    let theta = 1e-3;
    let rigid = [
        linear_field(&NODES, [1.0, 0.0], [[0.0; 2]; 2]),
        linear_field(&NODES, [0.0, 1.0], [[0.0; 2]; 2]),
        linear_field(&NODES, [0.0, 0.0], [[0.0, -theta], [theta, 0.0]]),
    ];
    for u in rigid {
        for e in t.strain(&u) {
            assert!(e.abs() <= 1e-15, "{e}");
        }
    }
    let g = [[2e-3, -7e-4], [5e-4, -1e-3]];
    let e = t.strain(&linear_field(&NODES, [0.3, -0.2], g));
    let exact = [g[0][0], g[1][1], g[0][1] + g[1][0]];
    for i in 0..3 {
        assert!(
            (e[i] - exact[i]).abs() <= 1e-15,
            "{i}: {} vs {}",
            e[i],
            exact[i]
        );
    }
}

#[test]
fn stiffness_is_symmetric_with_exactly_three_rigid_modes() {
    let t = Triangle3::new(NODES, 0.01).unwrap();
    for hypothesis in [Hypothesis::PlaneStrain, Hypothesis::PlaneStress] {
        let k = t.stiffness(&steel().elastic_tangent(hypothesis));
        let scale = k.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let kt = mat6(&k).transpose();
        assert!((mat6(&k) - kt).amax() <= 1e-12 * scale);
        let mut eigen: Vec<f64> = SymmetricEigen::new(mat6(&k))
            .eigenvalues
            .iter()
            .copied()
            .collect();
        eigen.sort_by(f64::total_cmp);
        let largest = eigen[5];
        for &l in &eigen[..3] {
            assert!(l.abs() <= 1e-12 * largest, "rigid mode eigenvalue {l}");
        }
        for &l in &eigen[3..] {
            assert!(l > 1e-3 * largest, "deformation mode eigenvalue {l}");
        }
    }
}

#[test]
fn internal_force_of_the_elastic_stress_is_k_times_u() {
    let t = Triangle3::new(NODES, 0.02).unwrap();
    let u = [1e-4, -2e-4, 3e-4, 0.5e-4, -1e-4, 2.5e-4];
    let update = steel().update(
        Hypothesis::PlaneStrain,
        &MaterialState::default(),
        t.strain(&u),
    );
    let f = t.internal_force(&update.state.in_plane_stress());
    let k = t.stiffness(&update.tangent);
    let ku: Vec<f64> = k
        .iter()
        .map(|row| (0..6).map(|j| row[j] * u[j]).sum())
        .collect();
    let scale = ku.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for i in 0..6 {
        assert!((f[i] - ku[i]).abs() <= 1e-12 * scale);
    }
    // The elastic energy of the element is u.K.u / 2.
    let energy = t.elastic_energy(&steel(), &update.state);
    let half_uku = 0.5 * (0..6).map(|i| u[i] * ku[i]).sum::<f64>();
    assert!((energy - half_uku).abs() <= 1e-12 * half_uku);
}

#[test]
fn mass_matrices_carry_the_element_mass() {
    let t = Triangle3::new(NODES, 0.02).unwrap();
    let rho = 7850.0;
    let total = rho * t.area() * t.thickness();
    let m = t.consistent_mass(rho);
    for d in 0..2 {
        let same: f64 = (0..3)
            .flat_map(|a| (0..3).map(move |b| (a, b)))
            .map(|(a, b)| m[2 * a + d][2 * b + d])
            .sum();
        assert!((same - total).abs() <= 1e-14 * total);
        let cross: f64 = (0..3)
            .flat_map(|a| (0..3).map(move |b| (a, b)))
            .map(|(a, b)| m[2 * a + d][2 * b + 1 - d].abs())
            .sum();
        assert_eq!(cross, 0.0);
    }
    assert!((m[0][0] - total / 6.0).abs() <= 1e-14 * total);
    assert!((m[0][2] - total / 12.0).abs() <= 1e-14 * total);
    let lumped = t.lumped_mass(rho);
    for (i, row) in m.iter().enumerate() {
        let row_sum: f64 = row.iter().sum();
        assert!((lumped[i] - row_sum).abs() <= 1e-14 * total);
    }
    assert!((lumped.iter().sum::<f64>() - 2.0 * total).abs() <= 1e-14 * total);
    let eigen = SymmetricEigen::new(mat6(&m)).eigenvalues;
    assert!(
        eigen.iter().all(|&l| l > 0.0),
        "consistent mass is positive definite"
    );
}

#[test]
fn bad_triangles_are_refused_with_a_reason() {
    let clockwise = [NODES[0], NODES[2], NODES[1]];
    assert!(
        matches!(Triangle3::new(clockwise, 0.01), Err(FemError::ClockwiseTriangle { area }) if area < 0.0)
    );
    let flat = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]];
    assert!(matches!(
        Triangle3::new(flat, 0.01),
        Err(FemError::DegenerateTriangle { .. })
    ));
    let sliver = [[0.0, 0.0], [1.0, 0.0], [0.5, 1e-14]];
    assert!(matches!(
        Triangle3::new(sliver, 0.01),
        Err(FemError::DegenerateTriangle { .. })
    ));
    let mut nan = NODES;
    nan[1][1] = f64::NAN;
    assert_eq!(
        Triangle3::new(nan, 0.01),
        Err(FemError::NonFiniteNode { node: 1 })
    );
    for thickness in [0.0, -1.0, f64::INFINITY, f64::NAN] {
        let e = Triangle3::new(NODES, thickness).unwrap_err();
        assert!(matches!(e, FemError::InvalidThickness { .. }));
        assert!(e.to_string().contains("thickness"));
    }
    // A tiny but well-shaped triangle is fine: the test is relative to its size.
    let tiny = NODES.map(|p| [1e-9 * p[0], 1e-9 * p[1]]);
    assert!(Triangle3::new(tiny, 1e-9).is_ok());
}

proptest! {
    #[test]
    fn any_valid_triangle_passes_the_element_checks(
        coords in prop::array::uniform6(-1.0f64..1.0),
        g in prop::array::uniform4(-1e-3f64..1e-3),
    ) {
        let nodes = [[coords[0], coords[1]], [coords[2], coords[3]], [coords[4], coords[5]]];
        let t = match Triangle3::new(nodes, 0.1) {
            Ok(t) => t,
            Err(FemError::ClockwiseTriangle { .. }) => {
                Triangle3::new([nodes[0], nodes[2], nodes[1]], 0.1).unwrap()
            }
            Err(_) => return Ok(()),
        };
        prop_assume!(t.area() > 1e-3);
        let nodes = t.nodes();
        let gradient = [[g[0], g[1]], [g[2], g[3]]];
        let e = t.strain(&linear_field(&nodes, [0.1, 0.2], gradient));
        let exact = [g[0], g[3], g[1] + g[2]];
        for i in 0..3 {
            prop_assert!((e[i] - exact[i]).abs() <= 1e-10 * 1e-3);
        }
        let k = t.stiffness(&steel().elastic_tangent(Hypothesis::PlaneStrain));
        let scale = k.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let rotation = linear_field(&nodes, [0.3, -0.1], [[0.0, -1.0], [1.0, 0.0]]);
        for row in &k {
            let f: f64 = (0..6).map(|j| row[j] * rotation[j]).sum();
            prop_assert!(f.abs() <= 1e-10 * scale);
        }
    }
}
