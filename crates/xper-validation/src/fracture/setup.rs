//! Meshes, specs, run loops and the case builders shared by the validation cases (units: m,
//! s, Pa, Pa/m for interface stiffnesses, J, N).

use super::Case;
pub(super) use crate::case::{case, indicator};
use xper_bodies::{Drive, TimeFunction};
use xper_fem::{Hypothesis, Material};
use xper_fracture::{
    FractureModel, FractureSpec, FractureStepReport, FractureStepper, InterfaceLaw, InterfaceRule,
    MassMatrix, NodeLoad,
};
use xper_laws::cohesive::CohesiveZone;
use xper_mesh::{Mesh, Region};
use xper_solver::{ConvergenceNorm, NlgsParams};

/// The larger of `a` and `b`, NaN if either is (`f64::max` would hide a NaN measurement).
pub(super) fn worst(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// `nx x ny` rectangles of `dx x dy` (m), each split along the diagonal from its lower-left to
/// its upper-right corner (every interior node then has opposite edges in pairs). Region of
/// the squares with column `i`: `region(i)`. Edge sets left, right, bottom, top.
pub(super) fn grid(
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    region: impl Fn(usize) -> u32,
) -> Result<Mesh, String> {
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            nodes.push([i as f64 * dx, j as f64 * dy]);
        }
    }
    let (mut tris, mut regions) = (Vec::new(), Vec::new());
    for j in 0..ny {
        for i in 0..nx {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            regions.extend([region(i); 2]);
        }
    }
    let count = regions.iter().copied().max().unwrap_or(0) + 1;
    let regs = (0..count)
        .map(|r| Region {
            name: format!("r{r}"),
            tag: r as i32 + 1,
        })
        .collect();
    let left: Vec<[u32; 2]> = (0..ny).map(|j| [id(0, j), id(0, j + 1)]).collect();
    let right: Vec<[u32; 2]> = (0..ny).map(|j| [id(nx, j), id(nx, j + 1)]).collect();
    let bottom: Vec<[u32; 2]> = (0..nx).map(|i| [id(i, 0), id(i + 1, 0)]).collect();
    let top: Vec<[u32; 2]> = (0..nx).map(|i| [id(i, ny), id(i + 1, ny)]).collect();
    Mesh::new(nodes, tris, regions, regs)
        .and_then(|m| m.with_edge_set("left", &left))
        .and_then(|m| m.with_edge_set("right", &right))
        .and_then(|m| m.with_edge_set("bottom", &bottom))
        .and_then(|m| m.with_edge_set("top", &top))
        .map_err(|e| format!("grid mesh {nx} x {ny}: {e}"))
}

/// A linear elastic material: Young's modulus (Pa), Poisson's ratio, density (kg/m^3).
pub(super) fn elastic(young: f64, poisson: f64, density: f64) -> Material {
    Material::LinearElastic {
        young,
        poisson,
        density,
    }
}

/// A cohesive zone with `C_N = C_T = c` (Pa/m), fracture energy `w` (J/m^2), strength
/// `R_max` (Pa), Coulomb friction after failure, initially sound (beta0 = 1).
pub(super) fn zone(c: f64, w: f64, strength: f64, friction: f64) -> CohesiveZone {
    CohesiveZone {
        normal_stiffness: c,
        tangential_stiffness: c,
        fracture_energy: w,
        strength,
        initial_damage: 1.0,
        friction,
    }
}

/// The same law between every pair of `regions` regions.
pub(super) fn everywhere(regions: u32, law: InterfaceLaw) -> Vec<InterfaceRule> {
    let mut rules = Vec::new();
    for a in 0..regions {
        for b in a..regions {
            rules.push(InterfaceRule {
                regions: [a, b],
                law,
            });
        }
    }
    rules
}

/// A load on the node set `set` of `mesh`.
pub(super) fn load(mesh: &Mesh, set: &str, drives: [Drive; 2]) -> Result<NodeLoad, String> {
    Ok(NodeLoad {
        name: set.into(),
        nodes: mesh
            .node_set(set)
            .map_err(|e| format!("node set {set}: {e}"))?
            .to_vec(),
        drives,
    })
}

/// An imposed constant velocity (m/s).
pub(super) fn velocity(v: f64) -> Drive {
    Drive::Velocity(TimeFunction::Constant(v))
}

/// A plane stress spec of unit thickness (m) with a consistent mass, no gravity and tight
/// NLGS settings (tolerance 1e-10 in the quadratic norm); time step `dt` (s).
pub(super) fn spec(
    materials: Vec<Material>,
    laws: Vec<InterfaceRule>,
    dt: f64,
    theta: f64,
) -> FractureSpec {
    FractureSpec {
        thickness: 1.0,
        hypothesis: Hypothesis::PlaneStress,
        materials,
        interface_laws: laws,
        broken_edge_sets: Vec::new(),
        loads: Vec::new(),
        gravity: [0.0, 0.0],
        mass: MassMatrix::Consistent,
        dt,
        theta,
        nlgs: NlgsParams {
            tolerance: 1e-10,
            max_iterations: 200_000,
            check_every: 10,
            relaxation: 1.0,
            norm: ConvergenceNorm::Quad,
            ..Default::default()
        },
        periodic: None,
        plastic_stiffness: Default::default(),
    }
}

/// Builds the model of the scenario `scenario`.
pub(super) fn build(
    scenario: &str,
    mesh: Mesh,
    spec: FractureSpec,
) -> Result<FractureModel, String> {
    FractureModel::new(mesh, spec).map_err(|e| format!("{scenario}: build: {e}"))
}

/// NLGS convergence over a run: steps done, steps that did not converge, largest final
/// residual of those.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Convergence {
    pub steps: usize,
    pub failed: usize,
    pub worst_residual: f64,
}

/// One step of the scenario `scenario`, its convergence recorded in `conv`.
pub(super) fn step(
    scenario: &str,
    stepper: &mut FractureStepper,
    m: &mut FractureModel,
    conv: &mut Convergence,
) -> Result<FractureStepReport, String> {
    let n = m.step + 1;
    let r = stepper
        .step(m)
        .map_err(|e| format!("{scenario}: step {n}: {e}"))?;
    conv.steps += 1;
    if !r.converged {
        conv.failed += 1;
        conv.worst_residual = worst(conv.worst_residual, r.residual);
    }
    Ok(r)
}

/// Stiffness of the tested interface of [`specimen`] (Pa/m).
pub(super) const C: f64 = 1e10;
/// Strength of the tested interface (Pa).
pub(super) const STRENGTH: f64 = 1e6;
/// Fracture energy of the tested interface (J/m^2); its length is 1 m.
pub(super) const W: f64 = 500.0;

/// The tested interface's law with Coulomb friction `friction` after failure.
pub(super) fn tested(friction: f64) -> CohesiveZone {
    zone(C, W, STRENGTH, friction)
}

/// Two unit squares (regions 0 and 1, one square of two elements each); the tested interface
/// is the edge x = 1. The far edge (x = 2) follows the velocity tables `vx`, `vy` (m/s); the
/// near edge (x = 0) is fixed. Bulk E = 1e12 Pa, nu = 0.2, rho = 100 kg/m^3, and the bonding
/// interfaces inside each square (C = 1e12 Pa/m, unbreakable) are 100 times stiffer than the
/// tested interface, so its jump is the imposed displacement to about 2 %. Backward Euler
/// (theta = 1), NLGS tolerance 1e-7.
pub(super) fn specimen(
    scenario: &str,
    friction: f64,
    vx: TimeFunction,
    vy: TimeFunction,
    dt: f64,
) -> Result<FractureModel, String> {
    let mesh = grid(2, 1, 1.0, 1.0, |i| i as u32)?;
    let bond = InterfaceLaw::Cohesive(zone(1e12, 1e20, 1e12, 0.0));
    let rules = vec![
        InterfaceRule {
            regions: [0, 0],
            law: bond,
        },
        InterfaceRule {
            regions: [1, 1],
            law: bond,
        },
        InterfaceRule {
            regions: [0, 1],
            law: InterfaceLaw::Cohesive(tested(friction)),
        },
    ];
    let stiff = elastic(1e12, 0.2, 100.0);
    let mut spec = spec(vec![stiff, stiff], rules, dt, 1.0);
    spec.nlgs.tolerance = 1e-7;
    spec.loads = vec![
        load(&mesh, "left", [velocity(0.0), velocity(0.0)])?,
        load(&mesh, "right", [Drive::Velocity(vx), Drive::Velocity(vy)])?,
    ];
    build(scenario, mesh, spec)
}

/// The tested interface of [`specimen`] (the one between the two regions).
pub(super) fn tested_interface(scenario: &str, m: &FractureModel) -> Result<usize, String> {
    m.interfaces
        .iter()
        .position(|i| {
            m.mesh.triangle_region[i.elements[0] as usize]
                != m.mesh.triangle_region[i.elements[1] as usize]
        })
        .ok_or_else(|| format!("{scenario}: no interface between the two squares"))
}

/// One step of [`run`]: mean jump of the tested interface [N, T] (m), force on the far edge
/// [x, y] (N), intensity beta of its first point before the step.
#[derive(Clone, Copy, Debug)]
pub(super) struct Sample {
    pub jump: [f64; 2],
    pub force: [f64; 2],
    pub beta: f64,
}

/// Runs `steps` steps of a [`specimen`].
pub(super) fn run(
    scenario: &str,
    m: &mut FractureModel,
    steps: usize,
) -> Result<(Vec<Sample>, Convergence), String> {
    let k = tested_interface(scenario, m)?;
    let mut stepper = FractureStepper::new();
    let mut conv = Convergence::default();
    let mut out = Vec::with_capacity(steps);
    for _ in 0..steps {
        let beta = m.interfaces[k].points[0].intensity;
        let r = step(scenario, &mut stepper, m, &mut conv)?;
        let p = &m.interfaces[k].points;
        let jump = [
            0.5 * (p[0].jump[0] + p[1].jump[0]),
            0.5 * (p[0].jump[1] + p[1].jump[1]),
        ];
        let force = r
            .loads
            .get(1)
            .ok_or_else(|| format!("{scenario}: no reading of the far-edge load"))?
            .force;
        out.push(Sample { jump, force, beta });
    }
    Ok((out, conv))
}

/// The largest intensity left on the tested interface (0 when every point is broken).
pub(super) fn largest_intensity(scenario: &str, m: &FractureModel) -> Result<f64, String> {
    let k = tested_interface(scenario, m)?;
    Ok(m.interfaces[k]
        .points
        .iter()
        .fold(0.0, |acc, p| worst(acc, p.intensity.abs())))
}

/// Mean x velocity (m/s) of the element copies of the mesh nodes `nodes`.
pub(super) fn mean_vx(m: &FractureModel, nodes: &[u32]) -> f64 {
    let (mut sum, mut count) = (0.0, 0);
    for el in &m.elements {
        for (j, n) in el.mesh_nodes.iter().enumerate() {
            if nodes.contains(n) {
                sum += el.velocity[2 * j];
                count += 1;
            }
        }
    }
    sum / count as f64
}

/// The nodes of `mesh` on the line x = `x` (m).
pub(super) fn nodes_at_x(mesh: &Mesh, x: f64) -> Vec<u32> {
    (0..mesh.nodes.len() as u32)
        .filter(|&n| (mesh.nodes[n as usize][0] - x).abs() < 1e-9)
        .collect()
}

/// One triangle (0,0), (1,0), (0,1) m of `material`, plane stress, unit thickness: node
/// (0,0) fixed, node (0,1) held in x, node (1,0) pulled in x at `strain_rate` (1/s, the
/// side being 1 m long); the two free components (y of the last two nodes) leave
/// `sigma_yy` and `sigma_xy` free to vanish. Backward Euler steps of `dt` (s), NLGS defaults.
pub(super) fn one_triangle(
    scenario: &str,
    material: Material,
    strain_rate: f64,
    dt: f64,
) -> Result<(Mesh, FractureSpec), String> {
    let mesh = Mesh::new(
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        vec![[0, 1, 2]],
        vec![0],
        vec![Region {
            name: "steel".into(),
            tag: 1,
        }],
    )
    .map_err(|e| format!("{scenario}: mesh: {e}"))?;
    let node_load = |name: &str, node: u32, drives: [Drive; 2]| NodeLoad {
        name: name.into(),
        nodes: vec![node],
        drives,
    };
    let spec = FractureSpec {
        thickness: 1.0,
        hypothesis: Hypothesis::PlaneStress,
        materials: vec![material],
        interface_laws: vec![],
        broken_edge_sets: vec![],
        loads: vec![
            node_load("corner", 0, [velocity(0.0), velocity(0.0)]),
            node_load("pulled", 1, [velocity(strain_rate), Drive::Free]),
            node_load("held", 2, [velocity(0.0), Drive::Free]),
        ],
        gravity: [0.0, 0.0],
        mass: MassMatrix::Consistent,
        dt,
        theta: 1.0,
        nlgs: NlgsParams::default(),
        periodic: None,
        plastic_stiffness: Default::default(),
    };
    Ok((mesh, spec))
}

/// The case "NLGS converged at every step" of a run: error = the steps that did not converge.
pub(super) fn converged(scenario: &str, conv: Convergence, tolerance: f64) -> Case {
    let measured = if conv.failed == 0 {
        format!("all {} steps converged", conv.steps)
    } else {
        format!(
            "{} of {} steps not converged (largest final residual {:.2e})",
            conv.failed, conv.steps, conv.worst_residual
        )
    };
    case(
        format!("{scenario}: NLGS converged at every step"),
        format!("NLGS residual below {tolerance:.0e} (quadratic norm) at every step"),
        measured,
        conv.failed as f64,
        0.0,
    )
}

/// The dissipation case of a full separation of the 1 m tested interface.
pub(super) fn dissipation(scenario: &str, m: &FractureModel) -> Case {
    let d = m.energy.cohesive_dissipated;
    case(
        format!("{scenario}: dissipated energy = w x length"),
        format!(
            "BRIEF.md section 3 law, analytic: work to full separation = w x length = {W} J/m^2 x \
             1 m = {W} J; error |D - w L| / (w L)"
        ),
        format!("D = {d:.6} J"),
        (d - W).abs() / W,
        1e-3,
    )
}

/// The case "every point of the tested interface is broken".
pub(super) fn broken(scenario: &str, m: &FractureModel, dc: f64) -> Result<Case, String> {
    let beta = largest_intensity(scenario, m)?;
    Ok(case(
        format!("{scenario}: every interface point broken"),
        format!("BRIEF.md section 3: g(x) = 0 for x >= d_c = {dc:.4e} m, so beta = 0"),
        format!("largest beta left {beta:.3e}"),
        beta,
        0.0,
    ))
}
