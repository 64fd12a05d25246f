//! The effective elastic tensor of a periodic cell by three static solves.
//!
//! For a macroscopic strain `E` the cell's equilibrium minimises the elastic energy
//! `W(u, E) = sum_e u_e^T K_e u_e / 2 + sum_p A_p [u~]_p^T D_p [u~]_p / 2` over the node
//! displacements `u` of the exploded mesh, with `K_e` the element stiffness (elastic tangent),
//! `D_p = beta (C_N n n^T + C_T t t^T)` the secant stiffness of each cohesive point (broken
//! points and contact laws carry nothing: cracks are taken open) and `A_p` half the edge
//! length times the thickness; the jump is `[u~] = u_b - u_a - E T` (`T` the period across
//! the cell's sides, zero inside). Hence `K u = f(E)` with `f` the forces of the periodic
//! points held at `E T`; `K` is singular by the two translations only, removed by a spring on
//! one node that carries no force since `f` is self-equilibrated. The macroscopic stress is
//! computed both ways, `(1 / V) sum_e V_e sigma_e` and the periodic points' forces
//! `(1 / V) sum sym(f_b (x) T)`: they agree at equilibrium for linear triangles, since
//! `sum_n X_n (x) grad N_n = I` on each element. The columns of `C*` are the stresses of
//! `E_xx = 1`, `E_yy = 1`, `2 E_xy = 1` (Voigt order `[xx, yy, xy]`, engineering shear, as
//! the tangents of `xper_fem`). Method: P. Suquet, "Elements of homogenization for inelastic
//! solid mechanics", in Homogenization Techniques for Composite Media, Lecture Notes in
//! Physics 272, Springer (1987) 193-278; in the exploded setting, Perales et al. (2008).

use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

use crate::interface::cohesive;
use crate::model::FractureModel;

/// The effective tensor of a cell and its checks.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Homogenized {
    /// `C*` (Pa): column `j` is the macroscopic stress `[xx, yy, xy]` of the unit strain `j`
    /// of `[E_xx, E_yy, 2 E_xy]`, as the volume average of the element stresses.
    pub tensor: [[f64; 3]; 3],
    /// The same columns from the forces across the periodic sides (Pa). With interfaces many
    /// orders stiffer than the elements these forces are large stiffnesses times small jumps,
    /// so they carry more rounding than the element stresses.
    pub tensor_boundary: [[f64; 3]; 3],
    /// Largest difference between the two, over the largest entry of `C*`.
    pub stress_difference: f64,
    /// `max |C*_ij - C*_ji| / max |C*_ij|`.
    pub asymmetry: f64,
    /// Leading principal minors of the symmetric part of `C*` (Pa, Pa^2, Pa^3): all positive
    /// for a positive definite tensor (Sylvester's criterion).
    pub minors: [f64; 3],
    /// Unknowns of the linear system (6 per element).
    pub unknowns: usize,
    /// Stored non-zeros of its matrix.
    pub nonzeros: usize,
    /// Cohesive points that carried stiffness (intact or damaged, not broken).
    pub bonded_points: usize,
}

impl Homogenized {
    /// Whether the symmetric part of `C*` is positive definite.
    pub fn positive_definite(&self) -> bool {
        self.minors.iter().all(|&m| m > 0.0)
    }

    /// The in-plane bulk modulus of the isotropic projection of `C*`,
    /// `(C11 + C22 + 2 C12) / 4` (Pa): `lambda + mu` for an isotropic tensor.
    pub fn bulk(&self) -> f64 {
        let c = &self.tensor;
        0.25 * (c[0][0] + c[1][1] + c[0][1] + c[1][0])
    }

    /// The shear modulus of the isotropic projection of `C*` (Pa): the mean of its two
    /// shear moduli `(C11 + C22 - 2 C12) / 4` (strain `[1, -1, 0]`) and `C33` (strain
    /// `[0, 0, 1]`); `mu` for an isotropic tensor.
    pub fn shear(&self) -> f64 {
        let c = &self.tensor;
        0.5 * (0.25 * (c[0][0] + c[1][1] - c[0][1] - c[1][0]) + c[2][2])
    }
}

/// Why the tensor cannot be computed.
#[derive(Clone, Debug, PartialEq)]
pub struct HomogenizeError(pub String);

impl std::fmt::Display for HomogenizeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for HomogenizeError {}

/// Steps of iterative refinement of the direct solve.
const REFINEMENTS: usize = 2;

/// One spring of the assembly: two unknown pairs, the 2x2 stiffness `A D` (N/m) and the
/// period.
struct Spring {
    dofs: [usize; 2],
    d: [f64; 4],
    period: [f64; 2],
}

/// The effective tensor of the periodic cell `m` in its current state (the elastic tangent of
/// each material, the secant stiffness of each cohesive point).
pub fn effective_tensor(m: &FractureModel) -> Result<Homogenized, HomogenizeError> {
    let Some(periodic) = &m.spec.periodic else {
        return Err(HomogenizeError(
            "the scene has no [periodic] cell: the effective tensor is that of a periodic cell"
                .into(),
        ));
    };
    let n = 6 * m.elements.len();
    let mut triplets: Vec<Triplet<usize, usize, f64>> = Vec::new();
    let mut tangents = Vec::with_capacity(m.elements.len());
    let mut largest = 0.0f64;
    for (e, el) in m.elements.iter().enumerate() {
        let c = m.spec.materials[el.region as usize].elastic_tangent(m.spec.hypothesis);
        let k = el.triangle.stiffness(&c);
        for i in 0..6 {
            largest = largest.max(k[i][i]);
            for j in 0..6 {
                if k[i][j] != 0.0 {
                    triplets.push(Triplet::new(6 * e + i, 6 * e + j, k[i][j]));
                }
            }
        }
        tangents.push(c);
    }
    let mut springs = Vec::new();
    for i in &m.interfaces {
        let Some(z) = cohesive(&m.laws[i.law as usize]) else {
            continue;
        };
        let area = 0.5 * i.length * m.spec.thickness;
        let [nx, ny] = i.normal;
        for (k, p) in i.points.iter().enumerate() {
            if p.intensity <= 0.0 {
                continue;
            }
            let [cn, ct] = z.stiffness(p.intensity).map(|c| c * area);
            let d = [
                cn * nx * nx + ct * ny * ny,
                (cn - ct) * nx * ny,
                (cn - ct) * nx * ny,
                cn * ny * ny + ct * nx * nx,
            ];
            let dofs =
                [0, 1].map(|s| 6 * i.elements[s] as usize + 2 * i.local_nodes[k][s] as usize);
            springs.push(Spring {
                dofs,
                d,
                period: i.period,
            });
        }
    }
    for s in &springs {
        for (a, sa) in [(0, -1.0), (1, 1.0)] {
            for (b, sb) in [(0, -1.0), (1, 1.0)] {
                for r in 0..2 {
                    for c in 0..2 {
                        let v = sa * sb * s.d[2 * r + c];
                        if v != 0.0 {
                            triplets.push(Triplet::new(s.dofs[a] + r, s.dofs[b] + c, v));
                        }
                    }
                }
            }
        }
    }
    for d in 0..2 {
        triplets.push(Triplet::new(d, d, largest));
    }
    let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
        .map_err(|e| HomogenizeError(format!("cannot assemble the cell's stiffness: {e:?}")))?;
    let nonzeros = matrix.compute_nnz();
    let llt = matrix.sp_cholesky(Side::Lower).map_err(|e| {
        HomogenizeError(format!(
            "the cell's stiffness is singular ({e:?}): a part of the cell is held by no \
             cohesive interface (broken or contact-only interfaces carry nothing here)"
        ))
    })?;
    let strains = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.5]];
    let mut rhs = Mat::<f64>::zeros(n, 3);
    for (case, e) in strains.iter().enumerate() {
        for s in springs.iter().filter(|s| s.period != [0.0; 2]) {
            let et = crate::cell::strain_times(e, s.period);
            let f = [
                s.d[0] * et[0] + s.d[1] * et[1],
                s.d[2] * et[0] + s.d[3] * et[1],
            ];
            for r in 0..2 {
                rhs[(s.dofs[1] + r, case)] += f[r];
                rhs[(s.dofs[0] + r, case)] -= f[r];
            }
        }
    }
    // Two steps of iterative refinement (the residual from the assembled triplets): the
    // springs are many orders stiffer than the elements, and each step divides the error
    // of the direct solve by about the condition number times the rounding unit.
    let mut u = llt.solve(&rhs);
    for _ in 0..REFINEMENTS {
        let mut residual = rhs.clone();
        for t in &triplets {
            for case in 0..3 {
                residual[(t.row, case)] -= t.val * u[(t.col, case)];
            }
        }
        u += llt.solve(&residual);
    }
    let volume = periodic.cell.area() * m.spec.thickness;
    let (mut tensor, mut tensor_boundary) = ([[0.0; 3]; 3], [[0.0; 3]; 3]);
    for (case, e) in strains.iter().enumerate() {
        let mut boundary = [0.0; 3];
        for s in springs.iter().filter(|s| s.period != [0.0; 2]) {
            let et = crate::cell::strain_times(e, s.period);
            let jump: [f64; 2] = std::array::from_fn(|r| {
                u[(s.dofs[1] + r, case)] - u[(s.dofs[0] + r, case)] - et[r]
            });
            let force = [
                -(s.d[0] * jump[0] + s.d[1] * jump[1]),
                -(s.d[2] * jump[0] + s.d[3] * jump[1]),
            ];
            let w = crate::cell::tensor_weights(force, s.period);
            boundary[0] += w[0];
            boundary[1] += w[1];
            boundary[2] += 0.5 * w[2];
        }
        let mut average = [0.0; 3];
        for (k, el) in m.elements.iter().enumerate() {
            let ue: [f64; 6] = std::array::from_fn(|d| u[(6 * k + d, case)]);
            let strain = el.triangle.strain(&ue);
            for r in 0..3 {
                let sigma: f64 = (0..3).map(|c| tangents[k][r][c] * strain[c]).sum();
                average[r] += el.triangle.volume() * sigma;
            }
        }
        for r in 0..3 {
            tensor_boundary[r][case] = boundary[r] / volume;
            tensor[r][case] = average[r] / volume;
        }
    }
    let scale = tensor.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut stress_difference = 0.0f64;
    let mut asymmetry = 0.0f64;
    for r in 0..3 {
        for c in 0..3 {
            stress_difference = stress_difference.max((tensor[r][c] - tensor_boundary[r][c]).abs());
            asymmetry = asymmetry.max((tensor[r][c] - tensor[c][r]).abs());
        }
    }
    let s: [[f64; 3]; 3] =
        std::array::from_fn(|r| std::array::from_fn(|c| 0.5 * (tensor[r][c] + tensor[c][r])));
    let minors = [
        s[0][0],
        s[0][0] * s[1][1] - s[0][1] * s[1][0],
        s[0][0] * (s[1][1] * s[2][2] - s[1][2] * s[2][1])
            - s[0][1] * (s[1][0] * s[2][2] - s[1][2] * s[2][0])
            + s[0][2] * (s[1][0] * s[2][1] - s[1][1] * s[2][0]),
    ];
    Ok(Homogenized {
        tensor,
        tensor_boundary,
        stress_difference: stress_difference / scale,
        asymmetry: asymmetry / scale,
        minors,
        unknowns: n,
        nonzeros,
        bonded_points: springs.len(),
    })
}
