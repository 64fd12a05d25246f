//! Boundary conditions of the fluid, one per side of the rectangular domain.
//!
//! Velocities: the normal component lives on the boundary faces and is set there; the
//! tangential component lives half a cell inside, and its ghost value outside the side makes
//! the linear interpolation at the side equal the condition (no slip: `ghost = 2 V - interior`)
//! or its normal derivative vanish (outflow: `ghost = interior`). The pressure correction of the
//! projection sees a homogeneous Neumann condition where the normal velocity is imposed, a
//! Dirichlet condition (`p = 0`) at an outflow, and periodicity where the flow is periodic.

use crate::grid::MacGrid;
use serde::{Deserialize, Serialize};
use xper_math::{Real, DIM};
use xper_poisson::{Boundary, PoissonSide as PressureCondition};

/// Normal velocity profile of an inflow side.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum InflowProfile {
    /// The same inward speed (m/s) over the side.
    Uniform {
        /// Inward speed (m/s).
        speed: Real,
    },
    /// Poiseuille profile `4 U_max s (L - s) / L^2`, `s` along the side of length `L`.
    Parabolic {
        /// Inward speed at the middle of the side (m/s).
        max_speed: Real,
    },
    /// The part of a [`InflowProfile::Parabolic`] side held by a block of a split grid: its
    /// cells are `offset..offset + m` of the side's `cells`. Never read from a scene.
    #[serde(skip)]
    ParabolicPart {
        /// Inward speed at the middle of the whole side (m/s).
        max_speed: Real,
        /// Cells of the side before the block's.
        offset: usize,
        /// Cells of the whole side.
        cells: usize,
    },
}

impl InflowProfile {
    /// Inward speed at `s` along a side of length `length`.
    pub fn speed(&self, s: Real, length: Real) -> Real {
        match *self {
            InflowProfile::Uniform { speed } => speed,
            InflowProfile::Parabolic { max_speed }
            | InflowProfile::ParabolicPart { max_speed, .. } => {
                4.0 * max_speed * s * (length - s) / (length * length)
            }
        }
    }

    /// Inward speed on the face of cell `k` of a side of `m` cells of size `h` (for a block,
    /// the side's cells are placed within the whole side).
    pub fn speed_on_cell(&self, k: isize, m: isize, h: Real) -> Real {
        let (offset, cells) = match *self {
            InflowProfile::ParabolicPart { offset, cells, .. } => (offset as Real, cells as Real),
            _ => (0.0, m as Real),
        };
        self.speed((k as Real + 0.5 + offset) * h, cells * h)
    }
}

/// The condition on one side of the domain.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SideCondition {
    /// A fixed wall: zero velocity.
    NoSlip,
    /// A wall sliding along itself at `velocity` (m/s, along +x on the bottom and top sides,
    /// along +y on the left and right sides), e.g. the lid of a cavity.
    MovingWall {
        /// Tangential velocity (m/s).
        velocity: Real,
    },
    /// Periodic with the opposite side (both must say so).
    Periodic,
    /// Imposed inward normal velocity, zero tangential velocity.
    Inflow {
        /// The normal velocity profile.
        profile: InflowProfile,
    },
    /// Zero normal derivative of the velocity and zero pressure.
    Outflow,
    /// The side is shared with the neighbouring block of a grid split among processes: its
    /// ghost values are the neighbour's rows, copied by the halo exchange
    /// ([`crate::BlockLinks::exchange_halo`]), and the faces on it belong to the block whose
    /// low side it is. Never read from a scene.
    #[serde(skip)]
    Neighbour,
}

impl SideCondition {
    /// Whether the faces on this side, as the low side of the block, are computed by the
    /// block itself (periodic copies and a neighbour's faces are not imposed).
    #[inline]
    fn faces_are_unknowns(self) -> bool {
        matches!(self, SideCondition::Periodic | SideCondition::Neighbour)
    }
}

/// The conditions on the four sides.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FluidBoundary {
    /// Side x = x0.
    pub left: SideCondition,
    /// Side x = x0 + nx h.
    pub right: SideCondition,
    /// Side y = y0.
    pub bottom: SideCondition,
    /// Side y = y0 + ny h.
    pub top: SideCondition,
}

impl FluidBoundary {
    /// No-slip walls all around.
    pub fn closed_box() -> Self {
        FluidBoundary {
            left: SideCondition::NoSlip,
            right: SideCondition::NoSlip,
            bottom: SideCondition::NoSlip,
            top: SideCondition::NoSlip,
        }
    }

    /// The lid-driven cavity: no-slip walls, the top sliding at `speed` (m/s) along +x.
    pub fn lid_driven(speed: Real) -> Self {
        FluidBoundary {
            top: SideCondition::MovingWall { velocity: speed },
            ..Self::closed_box()
        }
    }

    /// Periodic in both directions.
    pub fn periodic() -> Self {
        FluidBoundary {
            left: SideCondition::Periodic,
            right: SideCondition::Periodic,
            bottom: SideCondition::Periodic,
            top: SideCondition::Periodic,
        }
    }

    /// The low and high side along axis `d`.
    #[inline]
    pub fn sides(&self, d: usize) -> [SideCondition; 2] {
        if d == 0 {
            [self.left, self.right]
        } else {
            [self.bottom, self.top]
        }
    }

    /// Whether axis `d` is periodic.
    #[inline]
    pub fn is_periodic(&self, d: usize) -> bool {
        self.sides(d)[0] == SideCondition::Periodic
    }

    /// The conditions of a block of rows `rows` of a grid of `ny` rows split among processes:
    /// the sides towards another block (or, for periodic bottom and top, across them when
    /// there are several blocks) become [`SideCondition::Neighbour`].
    pub fn block(&self, rows: std::ops::Range<usize>, ny: usize, blocks: usize) -> Self {
        let periodic = self.is_periodic(1) && blocks > 1;
        let mut block = *self;
        for side in [&mut block.left, &mut block.right] {
            if let SideCondition::Inflow {
                profile: InflowProfile::Parabolic { max_speed },
            } = *side
            {
                *side = SideCondition::Inflow {
                    profile: InflowProfile::ParabolicPart {
                        max_speed,
                        offset: rows.start,
                        cells: ny,
                    },
                };
            }
        }
        if rows.start > 0 || periodic {
            block.bottom = SideCondition::Neighbour;
        }
        if rows.end < ny || periodic {
            block.top = SideCondition::Neighbour;
        }
        block
    }

    /// Checks that periodic sides come in pairs.
    pub fn validate(&self) -> Result<(), String> {
        for (d, name) in ["left/right", "bottom/top"].iter().enumerate() {
            let [lo, hi] = self.sides(d);
            if (lo == SideCondition::Periodic) != (hi == SideCondition::Periodic) {
                return Err(format!(
                    "the {name} sides: one is periodic and the other is not"
                ));
            }
        }
        Ok(())
    }

    /// The homogeneous condition of the pressure correction on each side.
    pub fn pressure_boundary(&self) -> Boundary {
        let map = |c: SideCondition| match c {
            SideCondition::Periodic => PressureCondition::Periodic,
            SideCondition::Outflow => PressureCondition::Dirichlet,
            // A block's pressure is solved over the whole grid, with the whole grid's sides.
            SideCondition::Neighbour => PressureCondition::Periodic,
            _ => PressureCondition::Neumann,
        };
        Boundary {
            left: map(self.left),
            right: map(self.right),
            bottom: map(self.bottom),
            top: map(self.top),
        }
    }

    /// Faces of component `d` (index along axis `d`) updated by the momentum predictor:
    /// every face not on a side where the normal velocity is imposed or extrapolated.
    pub fn predicted_faces(&self, grid: &MacGrid, d: usize) -> std::ops::Range<isize> {
        let n = grid.cells(d) as isize;
        if self.sides(d)[0].faces_are_unknowns() {
            0..n
        } else {
            1..n
        }
    }

    /// Faces of component `d` corrected by the projection: the predicted ones and the outflow
    /// faces.
    pub fn projected_faces(&self, grid: &MacGrid, d: usize) -> std::ops::Range<isize> {
        let n = grid.cells(d) as isize;
        if self.is_periodic(d) {
            return 0..n;
        }
        let [lo, hi] = self.sides(d);
        let start = if lo == SideCondition::Outflow || lo.faces_are_unknowns() {
            0
        } else {
            1
        };
        let end = if hi == SideCondition::Outflow {
            n + 1
        } else {
            n
        };
        start..end
    }

    /// Sets the normal velocity on the boundary faces (outflow faces are left to the
    /// projection; see [`FluidBoundary::extrapolate_outflow`]) and fills the ghost values of the tangential components and of periodic
    /// copies. Axis 0 first, then axis 1 over the whole padded range, so corners are consistent.
    pub fn fill_velocity(&self, grid: &MacGrid, u: &mut [Vec<Real>; DIM]) {
        for a in 0..DIM {
            let n = grid.cells(a) as isize;
            let e = 1 - a;
            let m = grid.cells(e) as isize;
            let at = |along_a: isize, along_e: isize| {
                if a == 0 {
                    grid.index(along_a, along_e)
                } else {
                    grid.index(along_e, along_a)
                }
            };
            for (side, condition) in self.sides(a).into_iter().enumerate() {
                let (face, inside, ghost, inward) = if side == 0 {
                    (0, 0, -1, 1.0)
                } else {
                    (n, n - 1, n, -1.0)
                };
                for k in -1..=m + 1 {
                    let normal = &mut u[a];
                    match condition {
                        SideCondition::Periodic => {
                            if side == 1 {
                                normal[at(n, k)] = normal[at(0, k)];
                                normal[at(n + 1, k)] = normal[at(1, k)];
                                normal[at(-1, k)] = normal[at(n - 1, k)];
                            }
                        }
                        SideCondition::NoSlip | SideCondition::MovingWall { .. } => {
                            normal[at(face, k)] = 0.0
                        }
                        SideCondition::Inflow { profile } => {
                            let inside_side = (0..m).contains(&k);
                            normal[at(face, k)] = if inside_side {
                                inward * profile.speed_on_cell(k, m, grid.h)
                            } else {
                                0.0
                            };
                        }
                        SideCondition::Outflow => {}
                        SideCondition::Neighbour => continue,
                    }
                    let tangential = &mut u[e];
                    let value = match condition {
                        SideCondition::Periodic => {
                            if side == 1 {
                                tangential[at(-1, k)] = tangential[at(n - 1, k)];
                                tangential[at(n, k)] = tangential[at(0, k)];
                            }
                            continue;
                        }
                        SideCondition::NoSlip | SideCondition::Inflow { .. } => {
                            -tangential[at(inside, k)]
                        }
                        SideCondition::MovingWall { velocity } => {
                            2.0 * velocity - tangential[at(inside, k)]
                        }
                        SideCondition::Outflow => tangential[at(inside, k)],
                        SideCondition::Neighbour => unreachable!("skipped above"),
                    };
                    tangential[at(ghost, k)] = value;
                }
            }
        }
    }

    /// Gives each outflow face the value of the face next inside (zero normal derivative), the
    /// predicted value that the projection then corrects.
    pub fn extrapolate_outflow(&self, grid: &MacGrid, u: &mut [Vec<Real>; DIM]) {
        for (a, normal) in u.iter_mut().enumerate() {
            let n = grid.cells(a) as isize;
            let m = grid.cells(1 - a) as isize;
            for (side, condition) in self.sides(a).into_iter().enumerate() {
                if condition != SideCondition::Outflow {
                    continue;
                }
                let (face, next) = if side == 0 { (0, 1) } else { (n, n - 1) };
                for k in 0..m {
                    let (f, x) = if a == 0 {
                        (grid.index(face, k), grid.index(next, k))
                    } else {
                        (grid.index(k, face), grid.index(k, next))
                    };
                    normal[f] = normal[x];
                }
            }
        }
    }

    /// Copies pressure values into the ghost cells of periodic sides (the only ghosts the
    /// momentum predictor reads).
    pub fn fill_pressure(&self, grid: &MacGrid, p: &mut [Real]) {
        for a in 0..DIM {
            if !self.is_periodic(a) {
                continue;
            }
            let n = grid.cells(a) as isize;
            let m = grid.cells(1 - a) as isize;
            for k in -1..=m + 1 {
                let at = |along: isize| {
                    if a == 0 {
                        grid.index(along, k)
                    } else {
                        grid.index(k, along)
                    }
                };
                p[at(-1)] = p[at(n - 1)];
                p[at(n)] = p[at(0)];
            }
        }
    }
}
