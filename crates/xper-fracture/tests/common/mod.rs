//! Structured meshes and specs shared by the engine tests.
#![allow(dead_code)]

use xper_bodies::{Drive, TimeFunction};
use xper_fem::{Hypothesis, Material};
use xper_fracture::{FractureSpec, InterfaceLaw, InterfaceRule, MassMatrix, NodeLoad};
use xper_laws::cohesive::CohesiveZone;
use xper_mesh::{Mesh, Region};
use xper_solver::{ConvergenceNorm, NlgsParams};

/// `nx x ny` rectangles of `dx x dy`, each split along the diagonal from its lower-left to its
/// upper-right corner (every interior node then has opposite edges in pairs). Region of the
/// squares with column `i`: `region(i)`. Edge sets left, right, bottom, top.
pub fn grid(nx: usize, ny: usize, dx: f64, dy: f64, region: impl Fn(usize) -> u32) -> Mesh {
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
        .expect("grid mesh")
}

/// An elastic material.
pub fn elastic(young: f64, poisson: f64, density: f64) -> Material {
    Material::LinearElastic {
        young,
        poisson,
        density,
    }
}

/// A cohesive zone with `C_N = C_T = c`.
pub fn zone(c: f64, w: f64, strength: f64, friction: f64) -> CohesiveZone {
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
pub fn everywhere(regions: u32, law: InterfaceLaw) -> Vec<InterfaceRule> {
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
pub fn load(mesh: &Mesh, set: &str, drives: [Drive; 2]) -> NodeLoad {
    NodeLoad {
        name: set.into(),
        nodes: mesh.node_set(set).expect("node set").to_vec(),
        drives,
    }
}

/// An imposed constant velocity.
pub fn velocity(v: f64) -> Drive {
    Drive::Velocity(TimeFunction::Constant(v))
}

/// A spec with tight NLGS settings.
pub fn spec(
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
        },
    }
}
