//! Uniaxial tension of one J2 elastoplastic element with linear isotropic hardening (plane
//! stress, i.e. the 3D uniaxial state): the axial stress follows `sigma_0 + H p` once
//! yielded, `p` the accumulated plastic strain, and the elastic slope E before.
//!
//! One triangle (0,0), (1,0), (0,1) m: node (0,0) fixed, node (0,1) held in x, node (1,0)
//! pulled in x; the two free components (y of the last two nodes) leave `sigma_yy` and
//! `sigma_xy` free to vanish. Quasi-static: backward Euler steps much longer than the
//! element's period.

use xper_bodies::{Drive, TimeFunction};
use xper_fem::{Hypothesis, Material};
use xper_fracture::{FractureModel, FractureSpec, FractureStepper, MassMatrix, NodeLoad};
use xper_mesh::{Mesh, Region};
use xper_solver::NlgsParams;

#[test]
fn one_element_in_tension_follows_the_hardening_line() {
    let (young, sigma0, hardening) = (200e9, 250e6, 850e6);
    let mesh = Mesh::new(
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        vec![[0, 1, 2]],
        vec![0],
        vec![Region {
            name: "steel".into(),
            tag: 1,
        }],
    )
    .unwrap();
    let fixed = |v: f64| Drive::Velocity(TimeFunction::Constant(v));
    let (steps, dt) = (400, 1e-3);
    let strain_rate = 5.0 * sigma0 / young / (steps as f64 * dt);
    let spec = FractureSpec {
        thickness: 1.0,
        hypothesis: Hypothesis::PlaneStress,
        materials: vec![Material::J2Plastic {
            young,
            poisson: 0.3,
            density: 1e-3,
            yield_stress: sigma0,
            hardening,
        }],
        interface_laws: vec![],
        broken_edge_sets: vec![],
        loads: vec![
            NodeLoad {
                name: "corner".into(),
                nodes: vec![0],
                drives: [fixed(0.0), fixed(0.0)],
            },
            NodeLoad {
                name: "pulled".into(),
                nodes: vec![1],
                drives: [fixed(strain_rate), Drive::Free],
            },
            NodeLoad {
                name: "held".into(),
                nodes: vec![2],
                drives: [fixed(0.0), Drive::Free],
            },
        ],
        gravity: [0.0, 0.0],
        mass: MassMatrix::Consistent,
        dt,
        theta: 1.0,
        nlgs: NlgsParams::default(),
    };
    let mut model = FractureModel::new(mesh, spec).unwrap();
    let mut stepper = FractureStepper::new();
    let mut plastic_steps = 0;
    for _ in 0..steps {
        stepper.step(&mut model).unwrap();
        let el = &model.elements[0];
        let s = el.state.stress;
        let p = el.state.equivalent_plastic_strain;
        let eps = el.triangle.strain(&el.displacement)[0];
        assert!(
            s[1].abs() < 1e-6 * sigma0 && s[3].abs() < 1e-6 * sigma0,
            "{s:?}"
        );
        if p > 0.0 {
            plastic_steps += 1;
            let line = sigma0 + hardening * p;
            assert!(
                (s[0] - line).abs() < 1e-8 * sigma0,
                "sigma {} vs {line}",
                s[0]
            );
        } else {
            assert!(
                (s[0] - young * eps).abs() < 1e-8 * sigma0,
                "elastic: {} vs {}",
                s[0],
                young * eps
            );
        }
    }
    assert!(plastic_steps > steps / 2, "{plastic_steps} plastic steps");
    let e = &model.energy;
    assert!(e.plastic > 0.0);
    // The step uses the internal force linearised at its start (one Newton iteration per
    // step, as LMGC90), so the work of the reaction over the step where the element yields
    // is computed with the elastic tangent: 1.4e-3 of the work with 400 steps.
    assert!(e.error().abs() < 3e-3 * e.external_work, "{e:?}");
}
