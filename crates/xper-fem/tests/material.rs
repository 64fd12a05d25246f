//! Materials: elastic tangents, the J2 radial return against analytic solutions, the
//! consistent tangent against finite differences, unloading, incompressibility, energies.

use proptest::prelude::*;
use xper_fem::{uniaxial_stress_response, FemError, Hypothesis, Material, MaterialState};

const HYPOTHESES: [Hypothesis; 2] = [Hypothesis::PlaneStrain, Hypothesis::PlaneStress];

/// The paper's matrix material (bimaterial test): E = 99 GPa, nu = 0.325, sigma_0 = 250 MPa,
/// H = 850 MPa.
fn matrix(hardening: f64) -> Material {
    Material::J2Plastic {
        young: 99e9,
        poisson: 0.325,
        density: 7850.0,
        yield_stress: 250e6,
        hardening,
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Follows `path` (in-plane strains) from a virgin state; returns the states and the
/// plastic work of every step.
fn follow(m: &Material, h: Hypothesis, path: &[[f64; 3]]) -> Vec<(MaterialState, f64)> {
    let mut state = MaterialState::default();
    path.iter()
        .map(|&e| {
            let u = m.update(h, &state, e);
            state = u.state;
            (state, u.plastic_work)
        })
        .collect()
}

#[test]
fn validate_names_each_bad_parameter() {
    let good = matrix(850e6);
    assert_eq!(good.validate(), Ok(()));
    let bad = |m: Material| match m.validate() {
        Err(FemError::InvalidMaterial { parameter, .. }) => parameter,
        other => panic!("expected a refusal, got {other:?}"),
    };
    let j2 = |young, poisson, density, yield_stress, hardening| Material::J2Plastic {
        young,
        poisson,
        density,
        yield_stress,
        hardening,
    };
    assert_eq!(bad(j2(0.0, 0.3, 1.0, 1.0, 0.0)), "young");
    assert_eq!(bad(j2(f64::NAN, 0.3, 1.0, 1.0, 0.0)), "young");
    assert_eq!(bad(j2(1.0, 0.5, 1.0, 1.0, 0.0)), "poisson");
    assert_eq!(bad(j2(1.0, -1.0, 1.0, 1.0, 0.0)), "poisson");
    assert_eq!(bad(j2(1.0, 0.3, 0.0, 1.0, 0.0)), "density");
    assert_eq!(bad(j2(1.0, 0.3, 1.0, 0.0, 0.0)), "yield_stress");
    assert_eq!(bad(j2(1.0, 0.3, 1.0, 1.0, -1.0)), "hardening");
    assert_eq!(bad(j2(1.0, 0.3, 1.0, 1.0, f64::INFINITY)), "hardening");
    let elastic = Material::LinearElastic {
        young: 1.0,
        poisson: 0.7,
        density: 1.0,
    };
    assert_eq!(bad(elastic), "poisson");
    assert!(elastic
        .validate()
        .unwrap_err()
        .to_string()
        .contains("(-1, 0.5)"));
}

#[test]
fn elastic_tangents_are_the_textbook_ones() {
    let (e, nu) = (32e9, 0.2);
    let m = Material::LinearElastic {
        young: e,
        poisson: nu,
        density: 2200.0,
    };
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let strain = [
        [lambda + 2.0 * mu, lambda, 0.0],
        [lambda, lambda + 2.0 * mu, 0.0],
        [0.0, 0.0, mu],
    ];
    let f = e / (1.0 - nu * nu);
    let stress = [
        [f, f * nu, 0.0],
        [f * nu, f, 0.0],
        [0.0, 0.0, f * (1.0 - nu) / 2.0],
    ];
    for (h, expected) in [
        (Hypothesis::PlaneStrain, strain),
        (Hypothesis::PlaneStress, stress),
    ] {
        let d = m.elastic_tangent(h);
        for i in 0..3 {
            for j in 0..3 {
                assert!(
                    (d[i][j] - expected[i][j]).abs() <= 1e-12 * e,
                    "{h:?} {i} {j}"
                );
            }
        }
        let eps = [1e-4, -3e-4, 2e-4];
        let u = m.update(h, &MaterialState::default(), eps);
        let s = u.state.stress;
        let s_zz = match h {
            Hypothesis::PlaneStrain => nu * (s[0] + s[1]),
            Hypothesis::PlaneStress => 0.0,
        };
        assert!((s[2] - s_zz).abs() <= 1e-12 * e * 1e-4);
        // psi = s : e / 2 (the out-of-plane term vanishes in both hypotheses).
        let psi = 0.5 * (s[0] * eps[0] + s[1] * eps[1] + s[3] * eps[2]);
        assert!(rel(m.elastic_energy_density(&u.state), psi) <= 1e-12);
        assert_eq!(u.plastic_work, 0.0);
    }
}

/// Pure shear `gamma = 2 e_xy`: `tau = G gamma` up to `tau_y = sigma_0 / sqrt 3`, then
/// `gamma = tau / G + (3 tau - sqrt 3 sigma_0) / H` (the plastic shear is `sqrt 3 p`), i.e.
/// a slope `G H / (3 G + H)`. The flow direction never changes, so the radial return is
/// exact for any step size, and the work `int tau dgamma` is exactly the elastic energy
/// `tau^2 / (2 G)` plus the plastic work.
#[test]
fn pure_shear_follows_the_analytic_hardening_curve() {
    for hardening in [850e6, 0.0] {
        let m = matrix(hardening);
        let (g, s0) = (99e9 / (2.0 * 1.325), 250e6);
        let gamma_y = s0 / (3f64.sqrt() * g);
        let gammas: Vec<f64> = [0.3, 0.9, 1.7, 2.0, 5.0, 11.0, 40.0]
            .iter()
            .map(|k| k * gamma_y)
            .collect();
        let path: Vec<[f64; 3]> = gammas.iter().map(|&gm| [0.0, 0.0, gm]).collect();
        for h in HYPOTHESES {
            let mut plastic_work = 0.0;
            for ((state, work), &gamma) in follow(&m, h, &path).iter().zip(&gammas) {
                plastic_work += work;
                let tau_exact = if gamma <= gamma_y {
                    g * gamma
                } else if hardening == 0.0 {
                    s0 / 3f64.sqrt()
                } else {
                    (gamma + 3f64.sqrt() * s0 / hardening) / (1.0 / g + 3.0 / hardening)
                };
                let tau = state.stress[3];
                assert!(
                    rel(tau, tau_exact) <= 1e-10,
                    "{h:?} H {hardening}: {tau} vs {tau_exact}"
                );
                assert!(
                    state.stress[0].abs() + state.stress[1].abs() + state.stress[2].abs() <= 1e-6
                );
                let p = state.equivalent_plastic_strain;
                let ep = state.plastic_strain;
                assert!((ep[0] + ep[1] + ep[2]).abs() <= 1e-15);
                assert!((ep[3] - 3f64.sqrt() * p).abs() <= 1e-12 * p.max(1e-12));
                if gamma > gamma_y {
                    // On the yield surface: sigma_eq = sigma_0 + H p.
                    assert!(rel(state.von_mises(), s0 + hardening * p) <= 1e-10);
                    assert!(rel(gamma, tau / g + 3f64.sqrt() * p) <= 1e-10);
                } else {
                    assert_eq!(p, 0.0);
                }
                // int_0^gamma tau dgamma', piecewise: elastic triangle, then the trapezoid
                // under the straight hardening line.
                let tau_y = g * gamma_y.min(gamma);
                let work = 0.5 * tau_y * gamma_y.min(gamma)
                    + 0.5 * (tau_y + tau) * (gamma - gamma_y).max(0.0);
                let balance = m.elastic_energy_density(state) + plastic_work;
                assert!(rel(balance, work) <= 1e-10, "{h:?}: {balance} vs {work}");
            }
        }
    }
}

/// Central differences of `update` in each strain direction, against the returned tangent.
fn check_tangent(m: &Material, h: Hypothesis, previous: &MaterialState, e: [f64; 3]) {
    let d = m.update(h, previous, e).tangent;
    let scale = d.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    let step = 1e-8;
    for j in 0..3 {
        let (mut up, mut down) = (e, e);
        up[j] += step;
        down[j] -= step;
        let (su, sd) = (
            m.update(h, previous, up).state,
            m.update(h, previous, down).state,
        );
        let (su, sd) = (su.in_plane_stress(), sd.in_plane_stress());
        for i in 0..3 {
            let fd = (su[i] - sd[i]) / (2.0 * step);
            assert!(
                (fd - d[i][j]).abs() <= 1e-6 * scale,
                "{h:?} d[{i}][{j}] = {} vs {fd}",
                d[i][j]
            );
        }
    }
    for (i, row) in d.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            assert!((x - d[j][i]).abs() <= 1e-12 * scale);
        }
    }
}

#[test]
fn consistent_tangent_matches_finite_differences() {
    let m = matrix(850e6);
    for h in HYPOTHESES {
        let virgin = MaterialState::default();
        check_tangent(&m, h, &virgin, [1e-4, -0.5e-4, 0.8e-4]);
        check_tangent(&m, h, &virgin, [6e-3, -1e-3, 4e-3]);
        // After plastic flow in shear, load in tension: the flow direction turns.
        let first = m.update(h, &virgin, [0.0, 0.0, 8e-3]).state;
        assert!(first.equivalent_plastic_strain > 0.0);
        check_tangent(&m, h, &first, [7e-3, -2e-3, 9e-3]);
        check_tangent(&m, h, &first, [0.0, 0.0, 7.9e-3]);
    }
    check_tangent(
        &matrix(0.0),
        Hypothesis::PlaneStrain,
        &MaterialState::default(),
        [6e-3, -1e-3, 4e-3],
    );
}

#[test]
fn unloading_is_elastic_with_the_elastic_slope() {
    let m = matrix(850e6);
    for h in HYPOTHESES {
        let loaded = m.update(h, &MaterialState::default(), [8e-3, -2e-3, 5e-3]);
        assert!(loaded.state.equivalent_plastic_strain > 0.0);
        let d = m.elastic_tangent(h);
        for back in [1e-5, 1e-3, 2e-3] {
            let de = [-back, 0.3 * back, -0.5 * back];
            let e = [8e-3 + de[0], -2e-3 + de[1], 5e-3 + de[2]];
            let unloaded = m.update(h, &loaded.state, e);
            assert_eq!(
                unloaded.state.equivalent_plastic_strain,
                loaded.state.equivalent_plastic_strain
            );
            assert_eq!(unloaded.plastic_work, 0.0);
            let (s0, s1) = (
                loaded.state.in_plane_stress(),
                unloaded.state.in_plane_stress(),
            );
            for i in 0..3 {
                let expected = (0..3).map(|j| d[i][j] * de[j]).sum::<f64>();
                assert!(
                    (s1[i] - s0[i] - expected).abs() <= 1e-9 * 250e6,
                    "{h:?} {i}"
                );
            }
            assert_eq!(unloaded.tangent, d);
        }
    }
}

#[test]
fn uniaxial_tension_of_an_elastoplastic_element_follows_linear_hardening() {
    let (e, nu, s0, hardening) = (99e9, 0.325, 250e6, 850e6);
    let m = matrix(hardening);
    let path: Vec<f64> = (1..=80).map(|k| 1e-4 * k as f64).collect();
    // Plane strain: s_yy = 0, e_zz = 0, so elastically s_xx = E e / (1 - nu^2), s_zz = nu s_xx.
    let points = uniaxial_stress_response(&m, Hypothesis::PlaneStrain, &path).unwrap();
    let mut plastic_steps = 0;
    for point in &points {
        let s = point.state.stress;
        assert!(s[1].abs() <= 1e-12 * s[0].abs() + 1e-3);
        let p = point.state.equivalent_plastic_strain;
        let ep = point.state.plastic_strain;
        assert!((ep[0] + ep[1] + ep[2]).abs() <= 1e-15);
        if p == 0.0 {
            assert!(rel(s[0], e * point.axial_strain / (1.0 - nu * nu)) <= 1e-10);
            assert!(rel(s[2], nu * s[0]) <= 1e-10);
            assert!(point.state.von_mises() <= s0);
        } else {
            plastic_steps += 1;
            assert!(rel(point.state.von_mises(), s0 + hardening * p) <= 1e-8);
        }
    }
    // Yield when sigma_eq = s_xx sqrt(1 - nu + nu^2) reaches sigma_0.
    let yield_strain = s0 * (1.0 - nu * nu) / (e * (1.0 - nu + nu * nu).sqrt());
    let elastic_steps = path.iter().filter(|&&x| x <= yield_strain).count();
    assert_eq!(plastic_steps, path.len() - elastic_steps);
    assert!(
        plastic_steps > 40,
        "the path must go well into the plastic range"
    );
    // Plane stress is the 3D uniaxial test: s = (e + s0 / H) E H / (E + H) and p = e_p,xx.
    let points = uniaxial_stress_response(&m, Hypothesis::PlaneStress, &path).unwrap();
    for point in &points {
        let s = point.state.stress;
        let p = point.state.equivalent_plastic_strain;
        let exact = if e * point.axial_strain <= s0 {
            e * point.axial_strain
        } else {
            (point.axial_strain + s0 / hardening) * e * hardening / (e + hardening)
        };
        assert!(rel(s[0], exact) <= 1e-10, "{} vs {exact}", s[0]);
        assert!(s[1].abs() <= 1e-3 && s[2] == 0.0);
        if p > 0.0 {
            assert!(rel(s[0], s0 + hardening * p) <= 1e-10);
            assert!(rel(point.state.plastic_strain[0], p) <= 1e-10);
        }
    }
    let bad = Material::LinearElastic {
        young: -1.0,
        poisson: 0.3,
        density: 1.0,
    };
    assert!(uniaxial_stress_response(&bad, Hypothesis::PlaneStrain, &path).is_err());
    let nan = [1e-4, f64::NAN];
    let e = uniaxial_stress_response(&m, Hypothesis::PlaneStrain, &nan).unwrap_err();
    assert_eq!(e, FemError::NonFiniteStrain { step: 1 });
}

proptest! {
    #[test]
    fn random_paths_stay_admissible_and_plastically_incompressible(
        path in prop::collection::vec(prop::array::uniform3(-6e-3f64..6e-3), 1..25),
        plane_stress in any::<bool>(),
    ) {
        let (s0, hardening) = (250e6, 850e6);
        let m = matrix(hardening);
        let h = if plane_stress { Hypothesis::PlaneStress } else { Hypothesis::PlaneStrain };
        let mut previous_p = 0.0;
        for (state, work) in follow(&m, h, &path) {
            let p = state.equivalent_plastic_strain;
            let ep = state.plastic_strain;
            prop_assert!(p >= previous_p && work >= 0.0);
            prop_assert!((ep[0] + ep[1] + ep[2]).abs() <= 1e-14);
            let yield_stress = s0 + hardening * p;
            prop_assert!(state.von_mises() <= yield_stress * (1.0 + 1e-10));
            if p > previous_p {
                prop_assert!(rel(state.von_mises(), yield_stress) <= 1e-10);
            }
            if plane_stress {
                prop_assert!(state.stress[2] == 0.0);
            }
            previous_p = p;
        }
    }
}
