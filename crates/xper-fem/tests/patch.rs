//! The patch test (B.M. Irons, A. Razzaque, 1972; O.C. Zienkiewicz, R.L. Taylor, "The Finite
//! Element Method", vol. 1, chapter 10): a patch of elements whose boundary follows a
//! constant-strain field must reproduce that field exactly inside.

use nalgebra::{DMatrix, DVector};
use xper_fem::{Hypothesis, Material, MaterialState, Triangle3};

/// 2 x 2 squares on [0, 2]^2 split into 8 triangles, the centre node moved off the grid.
/// Node `3 r + c` is at column `c`, row `r`; node 4 is the interior one.
fn patch(centre: [f64; 2], crossed: bool) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let mut nodes: Vec<[f64; 2]> = (0..9).map(|n| [(n % 3) as f64, (n / 3) as f64]).collect();
    nodes[4] = centre;
    let mut triangles = Vec::new();
    for r in 0..2 {
        for c in 0..2 {
            let (a, b, d, e) = (3 * r + c, 3 * r + c + 1, 3 * r + c + 4, 3 * r + c + 3);
            // Split along a-d, or along b-e, alternating when `crossed`.
            if crossed && (r + c) % 2 == 1 {
                triangles.push([a, b, e]);
                triangles.push([b, d, e]);
            } else {
                triangles.push([a, b, d]);
                triangles.push([a, d, e]);
            }
        }
    }
    (nodes, triangles)
}

fn run_patch_test(material: &Material, hypothesis: Hypothesis, centre: [f64; 2], crossed: bool) {
    let (nodes, triangles) = patch(centre, crossed);
    let elements: Vec<Triangle3> = triangles
        .iter()
        .map(|t| Triangle3::new(t.map(|n| nodes[n]), 0.05).unwrap())
        .collect();
    let tangent = material.elastic_tangent(hypothesis);
    let n = 2 * nodes.len();
    let mut k = DMatrix::<f64>::zeros(n, n);
    for (element, t) in elements.iter().zip(&triangles) {
        let ke = element.stiffness(&tangent);
        for a in 0..6 {
            for b in 0..6 {
                k[(2 * t[a / 2] + a % 2, 2 * t[b / 2] + b % 2)] += ke[a][b];
            }
        }
    }
    // u(x) = c + G x with a constant strain [g00, g11, g01 + g10].
    let g = [[1.2e-3, -4e-4], [7e-4, -9e-4]];
    let exact = |p: [f64; 2]| {
        [
            0.01 + g[0][0] * p[0] + g[0][1] * p[1],
            -0.02 + g[1][0] * p[0] + g[1][1] * p[1],
        ]
    };
    let strain = [g[0][0], g[1][1], g[0][1] + g[1][0]];
    let interior = [8, 9];
    let boundary: Vec<usize> = (0..n).filter(|d| !interior.contains(d)).collect();
    let prescribed = DVector::from_iterator(
        boundary.len(),
        boundary.iter().map(|&d| exact(nodes[d / 2])[d % 2]),
    );
    let k_ii = k.select_rows(&interior).select_columns(&interior);
    let k_ib = k.select_rows(&interior).select_columns(&boundary);
    let u_i = k_ii
        .lu()
        .solve(&(-(k_ib * &prescribed)))
        .expect("K_ii is regular");
    let mut u = vec![0.0; n];
    for (d, value) in boundary.iter().zip(prescribed.iter()) {
        u[*d] = *value;
    }
    u[8] = u_i[0];
    u[9] = u_i[1];
    let centre_exact = exact(nodes[4]);
    for i in 0..2 {
        assert!((u[8 + i] - centre_exact[i]).abs() <= 1e-12 * centre_exact[i].abs().max(1e-3));
    }
    // Every element recovers the exact strain, and the interior node is in equilibrium.
    let mut interior_force = [0.0; 2];
    for (element, t) in elements.iter().zip(&triangles) {
        let ue: [f64; 6] = std::array::from_fn(|a| u[2 * t[a / 2] + a % 2]);
        let e = element.strain(&ue);
        for i in 0..3 {
            assert!(
                (e[i] - strain[i]).abs() <= 1e-12 * 1.2e-3,
                "{hypothesis:?} {e:?}"
            );
        }
        let update = material.update(hypothesis, &MaterialState::default(), e);
        let f = element.internal_force(&update.state.in_plane_stress());
        for (a, &node) in t.iter().enumerate() {
            if node == 4 {
                interior_force[0] += f[2 * a];
                interior_force[1] += f[2 * a + 1];
            }
        }
    }
    let stress_scale = material.young() * 1.2e-3 * 0.05;
    for f in interior_force {
        assert!(
            f.abs() <= 1e-11 * stress_scale,
            "unbalanced interior force {f}"
        );
    }
}

#[test]
fn a_constant_strain_field_is_reproduced_exactly_on_distorted_patches() {
    let materials = [
        Material::LinearElastic {
            young: 32e9,
            poisson: 0.2,
            density: 2200.0,
        },
        Material::J2Plastic {
            young: 99e9,
            poisson: 0.325,
            density: 7850.0,
            yield_stress: 250e6,
            hardening: 850e6,
        },
    ];
    for material in &materials {
        for hypothesis in [Hypothesis::PlaneStrain, Hypothesis::PlaneStress] {
            for crossed in [false, true] {
                run_patch_test(material, hypothesis, [1.0, 1.0], crossed);
                run_patch_test(material, hypothesis, [1.13, 0.91], crossed);
            }
        }
    }
}
