use xper_bodies::{Drive, TimeFunction};
use xper_fem::{Hypothesis, Material};
use xper_fracture::*;
use xper_laws::cohesive::CohesiveZone;
use xper_mesh::{double_edge_notched, NotchedSpec};
use xper_solver::NlgsParams;
fn main() {
    let h: f64 = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(2e-3);
    let dt: f64 = std::env::args()
        .nth(2)
        .map(|s| s.parse().unwrap())
        .unwrap_or(1e-7);
    let steps: usize = std::env::args()
        .nth(3)
        .map(|s| s.parse().unwrap())
        .unwrap_or(20);
    let t0 = std::time::Instant::now();
    let mesh = double_edge_notched(&NotchedSpec {
        side: 0.2,
        notch_depth: 0.025,
        notch_width: 0.005,
        element_size: h,
    })
    .unwrap();
    let v = |x: f64| Drive::Velocity(TimeFunction::Constant(x));
    let set = |n: &str| mesh.node_set(n).unwrap().to_vec();
    let loads = vec![
        NodeLoad {
            name: "top".into(),
            nodes: set("top"),
            drives: [Drive::Free, v(0.1)],
        },
        NodeLoad {
            name: "bottom".into(),
            nodes: set("bottom"),
            drives: [Drive::Free, v(-0.1)],
        },
        NodeLoad {
            name: "left_upper".into(),
            nodes: set("left_upper")
                .into_iter()
                .filter(|n| !set("top").contains(n))
                .collect(),
            drives: [
                v(0.1),
                if std::env::var("FULL").is_ok() {
                    v(0.0)
                } else {
                    Drive::Free
                },
            ],
        },
        NodeLoad {
            name: "right_lower".into(),
            nodes: set("right_lower")
                .into_iter()
                .filter(|n| !set("bottom").contains(n))
                .collect(),
            drives: [
                v(-0.1),
                if std::env::var("FULL").is_ok() {
                    v(0.0)
                } else {
                    Drive::Free
                },
            ],
        },
    ];
    let loads: Vec<NodeLoad> = if std::env::var("TONLY").is_ok() {
        loads.into_iter().take(2).collect()
    } else if std::env::var("CONLY").is_ok() {
        loads.into_iter().skip(2).collect()
    } else {
        loads
    };
    let z = CohesiveZone {
        normal_stiffness: 2e14,
        tangential_stiffness: 2e14,
        fracture_energy: 110.0,
        strength: 3e6,
        initial_damage: 1.0,
        friction: 0.0,
    };
    let spec = FractureSpec {
        thickness: 0.05,
        hypothesis: Hypothesis::PlaneStrain,
        materials: vec![Material::LinearElastic {
            young: 32e9,
            poisson: 0.2,
            density: 2200.0,
        }],
        interface_laws: vec![InterfaceRule {
            regions: [0, 0],
            law: InterfaceLaw::Cohesive(z),
        }],
        broken_edge_sets: vec![],
        loads,
        gravity: [0.0, 0.0],
        mass: if std::env::var("LUMP").is_ok() {
            MassMatrix::Lumped
        } else {
            MassMatrix::Consistent
        },
        dt,
        theta: 0.5,
        nlgs: NlgsParams {
            norm: if std::env::var("NMAP").is_ok() {
                xper_solver::ConvergenceNorm::NaturalMap
            } else {
                xper_solver::ConvergenceNorm::Quad
            },
            tolerance: std::env::var("TOL")
                .ok()
                .map(|s| s.parse().unwrap())
                .unwrap_or(1.666e-4),
            max_iterations: std::env::args()
                .nth(4)
                .map(|s| s.parse().unwrap())
                .unwrap_or(1000),
            ..NlgsParams::default()
        },
    };
    let mut m = FractureModel::new(mesh, spec).unwrap();
    println!(
        "elements {} interfaces {} build {:.2} s",
        m.elements.len(),
        m.interfaces.len(),
        t0.elapsed().as_secs_f64()
    );
    if std::env::var("DIFF").is_ok() {
        let mut st = FractureStepper::new();
        st.step(&mut m).unwrap();
        diff_probe(&m);
        return;
    }
    let mut st = FractureStepper::new();
    let (mut tsolve, mut twall, mut upd) = (0.0, 0.0, 0.0);
    for _ in 0..steps {
        let r = st.step(&mut m).unwrap();
        tsolve += r.solve_time;
        twall += r.wall_time;
        upd += (r.contacts as f64) * r.iterations as f64;
        if r.step % 10 == 0 || r.step < 5 {
            println!(
                "step {} it {} res {:.3e} conv {} broken {} wall {:.1} ms f0 {:?}",
                r.step,
                r.iterations,
                r.residual,
                r.converged,
                r.broken_points,
                r.wall_time * 1e3,
                r.loads[0].force
            );
        }
    }
    println!(
        "wall/step {:.2} ms solve/step {:.2} ms ns/update {:.1} energy err {:.3e} work {:.3e}",
        twall * 1e3 / steps as f64,
        tsolve * 1e3 / steps as f64,
        tsolve * 1e9 / upd,
        m.energy.error(),
        m.energy.external_work
    );
}
#[allow(dead_code)]
pub fn diff_probe(m: &FractureModel) {
    let mut a = m.clone();
    let mut b = m.clone();
    a.spec.nlgs.max_iterations = 200;
    b.spec.nlgs.max_iterations = 201;
    FractureStepper::new().step(&mut a).unwrap();
    FractureStepper::new().step(&mut b).unwrap();
    let mut d: Vec<(f64, usize, usize)> = Vec::new();
    for (i, (ia, ib)) in a.interfaces.iter().zip(&b.interfaces).enumerate() {
        for k in 0..2 {
            let (ra, rb) = (ia.points[k].impulse, ib.points[k].impulse);
            d.push(((ra[0] - rb[0]).abs() + (ra[1] - rb[1]).abs(), i, k));
        }
    }
    d.sort_by(|x, y| y.0.partial_cmp(&x.0).unwrap());
    for &(v, i, k) in d.iter().take(8) {
        let it = &a.interfaces[i];
        let [ea, eb] = it.elements;
        let na = a.elements[ea as usize].mesh_nodes[it.local_nodes[k][0] as usize];
        println!(
            "diff {v:.3e} iface {i} pt {k} normal {:?} node {} at {:?} R {:?} loads a {:?} b {:?}",
            it.normal,
            na,
            a.mesh.nodes[na as usize],
            it.points[k].impulse,
            a.elements[ea as usize].load,
            a.elements[eb as usize].load
        );
    }
}
