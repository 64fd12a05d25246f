//! The linear 3-node triangle (constant strain triangle) for plane problems.
//!
//! Source: O.C. Zienkiewicz, R.L. Taylor, J.Z. Zhu, "The Finite Element Method: its Basis
//! and Fundamentals", 7th ed., Butterworth-Heinemann 2013, section 6.2 (the CST); T.J.R.
//! Hughes, "The Finite Element Method", Dover 2000, section 3.6 (mass matrices).
//!
//! Degrees of freedom are ordered `[u1x, u1y, u2x, u2y, u3x, u3y]` (m); strains use Voigt
//! notation with engineering shear `[e_xx, e_yy, 2 e_xy]`; in-plane stresses are
//! `[s_xx, s_yy, s_xy]` (Pa). The thickness `t` (m) is the real thickness in plane stress
//! and the out-of-plane depth in plane strain (1 m gives quantities per metre).

use crate::error::FemError;
use crate::material::{Material, MaterialState};

/// Areas below this fraction of the longest edge squared are degenerate.
const DEGENERATE_RATIO: f64 = 1e-12;

/// A linear triangle with its constant strain-displacement matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle3 {
    nodes: [[f64; 2]; 3],
    thickness: f64,
    area: f64,
    b: [[f64; 6]; 3],
}

impl Triangle3 {
    /// A triangle from its three node coordinates `[x, y]` (m), counter-clockwise, and its
    /// thickness (m). Refuses non-finite coordinates, degenerate or clockwise triangles and a
    /// thickness that is not finite and positive.
    pub fn new(nodes: [[f64; 2]; 3], thickness: f64) -> Result<Self, FemError> {
        if let Some(node) = nodes
            .iter()
            .position(|p| !p[0].is_finite() || !p[1].is_finite())
        {
            return Err(FemError::NonFiniteNode { node });
        }
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(FemError::InvalidThickness { value: thickness });
        }
        let [p1, p2, p3] = nodes;
        let twice_area = (p2[0] - p1[0]) * (p3[1] - p1[1]) - (p3[0] - p1[0]) * (p2[1] - p1[1]);
        let longest2 = (0..3)
            .map(|i| {
                let (a, b) = (nodes[i], nodes[(i + 1) % 3]);
                (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
            })
            .fold(0.0, f64::max);
        let area = 0.5 * twice_area;
        if twice_area.abs() <= DEGENERATE_RATIO * longest2 {
            return Err(FemError::DegenerateTriangle { area });
        }
        if twice_area < 0.0 {
            return Err(FemError::ClockwiseTriangle { area });
        }
        // dN_i/dx = (y_j - y_k) / 2A, dN_i/dy = (x_k - x_j) / 2A, (i, j, k) cyclic.
        let mut b = [[0.0; 6]; 3];
        for i in 0..3 {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let dx = (nodes[j][1] - nodes[k][1]) / twice_area;
            let dy = (nodes[k][0] - nodes[j][0]) / twice_area;
            b[0][2 * i] = dx;
            b[1][2 * i + 1] = dy;
            b[2][2 * i] = dy;
            b[2][2 * i + 1] = dx;
        }
        Ok(Triangle3 {
            nodes,
            thickness,
            area,
            b,
        })
    }

    /// The node coordinates (m).
    pub fn nodes(&self) -> [[f64; 2]; 3] {
        self.nodes
    }

    /// The thickness (m).
    pub fn thickness(&self) -> f64 {
        self.thickness
    }

    /// The area `A` (m^2), positive.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The volume `A t` (m^3).
    pub fn volume(&self) -> f64 {
        self.area * self.thickness
    }

    /// The strain-displacement matrix `B` (3x6, 1/m): `[e_xx, e_yy, 2 e_xy] = B u`.
    pub fn b_matrix(&self) -> [[f64; 6]; 3] {
        self.b
    }

    /// The (constant) strain `B u` of nodal displacements `u` (m).
    pub fn strain(&self, displacements: &[f64; 6]) -> [f64; 3] {
        self.b
            .map(|row| (0..6).map(|j| row[j] * displacements[j]).sum())
    }

    /// The stiffness `A t B^T D B` (N/m) for an in-plane tangent `D` (3x3, Pa) mapping
    /// `[e_xx, e_yy, 2 e_xy]` to `[s_xx, s_yy, s_xy]`.
    pub fn stiffness(&self, tangent: &[[f64; 3]; 3]) -> [[f64; 6]; 6] {
        let v = self.volume();
        let mut db = [[0.0; 6]; 3];
        for (i, row) in db.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = (0..3).map(|k| tangent[i][k] * self.b[k][j]).sum();
            }
        }
        let mut k = [[0.0; 6]; 6];
        for (i, row) in k.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = v * (0..3).map(|m| self.b[m][i] * db[m][j]).sum::<f64>();
            }
        }
        k
    }

    /// The internal nodal forces `A t B^T s` (N) of the in-plane stress `[s_xx, s_yy, s_xy]`
    /// (Pa); see [`MaterialState::in_plane_stress`].
    pub fn internal_force(&self, stress: &[f64; 3]) -> [f64; 6] {
        let v = self.volume();
        std::array::from_fn(|j| v * (0..3).map(|m| self.b[m][j] * stress[m]).sum::<f64>())
    }

    /// The consistent mass matrix `rho A t / 12 [2 1 1; 1 2 1; 1 1 2] (x) I2` (kg) for a
    /// density `rho` (kg/m^3).
    pub fn consistent_mass(&self, density: f64) -> [[f64; 6]; 6] {
        let m = density * self.volume() / 12.0;
        let mut mass = [[0.0; 6]; 6];
        for a in 0..3 {
            for b in 0..3 {
                let value = if a == b { 2.0 * m } else { m };
                mass[2 * a][2 * b] = value;
                mass[2 * a + 1][2 * b + 1] = value;
            }
        }
        mass
    }

    /// The lumped (row-sum) mass `rho A t / 3` on every degree of freedom (kg).
    pub fn lumped_mass(&self, density: f64) -> [f64; 6] {
        [density * self.volume() / 3.0; 6]
    }

    /// The elastic strain energy `A t psi_e` (J) of the element in a material state, with
    /// `psi_e` = [`Material::elastic_energy_density`].
    pub fn elastic_energy(&self, material: &Material, state: &MaterialState) -> f64 {
        self.volume() * material.elastic_energy_density(state)
    }
}
