//! Direct forcing on Lagrangian markers with a regularised delta function, repeated
//! (multi-direct forcing): the `forcing = "markers"` option.
//!
//! Each grain carries `N_L` markers `X_l` evenly spaced on a circle of radius `r - c h`
//! (retracted by `c` cells into the grain; Breugem, J. Comput. Phys. 231 (2012) 4469, finds
//! `c = 0.3` makes the grain's effective radius its true one), each standing for a shell
//! element of thickness `h`: `Delta V_l = 2 pi (r - c h) h / N_L`, `N_L = ceil(2 pi (r - c h) / h)`.
//! After the momentum predictor left `u*`, the forcing (Uhlmann, J. Comput. Phys. 209 (2005)
//! 448, eqs. 12 to 15) interpolates the velocity at the markers, forces it towards the rigid
//! velocity there and spreads the force back to the faces:
//!
//! ```text
//! U_l = sum_faces u(x) delta_h(x - X_l) h^2,
//! F_l = (U_s(X_l) - U_l) / dt,
//! u  <- u + dt sum_l F_l delta_h(x - X_l) Delta V_l,
//! ```
//!
//! (with `time_scheme = "rk3"` before every stage's projection, `dt` the stage's length, as
//! Uhlmann does), repeated `iterations` times on the forced field, the forces adding up
//! (multi-direct forcing,
//! Luo, Wang, Fan and Cen, Phys. Rev. E 76 (2007) 066709; Breugem 2012 uses two), so that the
//! velocity at the markers approaches the rigid one where the kernels of neighbouring markers
//! overlap. `delta_h(x) = phi(x / h) phi(y / h) / h^2` with the three-point kernel of Roma,
//! Peskin and Berger, J. Comput. Phys. 153 (1999) 509:
//!
//! ```text
//! phi(r) = (1 + sqrt(1 - 3 r^2)) / 3                      |r| <= 1/2,
//!        = (5 - 3 |r| - sqrt(1 - 3 (1 - |r|)^2)) / 6      1/2 <= |r| <= 3/2,
//!        = 0                                               otherwise,
//! ```
//!
//! whose sum over the faces is 1 and whose first moment is 0 wherever the marker stands, so a
//! uniform flow is interpolated exactly. The fluid inside the grains is not forced (as in
//! Uhlmann 2005); its momentum enters the force on the grain as with the fraction forcing
//! ([`crate::immersed`]). The force on the grain is minus what the fluid received at the
//! faces, `- rho_f sum_faces f h^2`, and its moment about the centre.
//!
//! Interpolation and spreading use only the faces the predictor updates (the sides' faces
//! and the ghosts are left out, so a marker within 1.5 cells of a wall sees an incomplete
//! kernel). On a block of a split grid each block sums its own faces' share of every `U_l`,
//! the shares are summed over the blocks, and each block spreads onto its own faces: no halo
//! is read.

use crate::blocks::BlockLinks;
use crate::boundary::FluidBoundary;
use crate::grid::MacGrid;
use crate::immersed::{HydrodynamicForce, ImmersedDisk};
use serde::{Deserialize, Serialize};
use xper_math::{cross, Real, Vector, DIM};

/// Settings of the marker forcing (`[fluid] forcing = "markers"`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MarkerForcingParams {
    /// Forcing passes per step (multi-direct forcing), at least 1.
    pub iterations: u32,
    /// Retraction of the markers into the grain (cells), in [0, 1/2].
    pub retraction: Real,
}

impl Default for MarkerForcingParams {
    /// Breugem 2012's choice: two passes, markers 0.3 cells inside.
    fn default() -> Self {
        MarkerForcingParams {
            iterations: 2,
            retraction: 0.3,
        }
    }
}

/// The three-point regularised delta of Roma et al. (1999) at `r` cells.
#[inline]
pub fn roma_kernel(r: Real) -> Real {
    let a = r.abs();
    if a <= 0.5 {
        (1.0 + (1.0 - 3.0 * a * a).sqrt()) / 3.0
    } else if a <= 1.5 {
        let b = 1.0 - a;
        (5.0 - 3.0 * a - (1.0 - 3.0 * b * b).max(0.0).sqrt()) / 6.0
    } else {
        0.0
    }
}

/// One marker: its grain, position and shell volume (m^2 per m).
#[derive(Clone, Copy, Debug)]
struct Marker {
    owner: u32,
    position: Vector,
    volume: Real,
}

/// A face of a marker's kernel on this block: padded index, position and `delta_h h^2`.
#[derive(Clone, Copy, Debug)]
struct KernelFace {
    k: usize,
    position: Vector,
    weight: Real,
}

/// The markers of every grain and their kernels on this block's faces.
#[derive(Default)]
pub struct MarkerForcing {
    markers: Vec<Marker>,
    /// Per component, the kernel faces of marker `l`: `faces[d][starts[d][l]..starts[d][l + 1]]`.
    faces: [Vec<KernelFace>; DIM],
    starts: [Vec<usize>; DIM],
    /// Velocity at the markers, component after component of each marker.
    interpolated: Vec<Real>,
}

impl MarkerForcing {
    /// Places the markers of `disks`, `retraction` cells inside their surfaces, and finds
    /// their kernels on the faces of `grid` the predictor updates: once per step, before
    /// [`MarkerForcing::apply`] (which rk3 calls at every stage).
    pub fn place(
        &mut self,
        grid: &MacGrid,
        boundary: &FluidBoundary,
        disks: &[ImmersedDisk],
        retraction: Real,
    ) {
        let h = grid.h;
        self.markers.clear();
        for (p, disk) in disks.iter().enumerate() {
            let radius = (disk.radius - retraction * h).max(0.0);
            let perimeter = 2.0 * std::f64::consts::PI * radius;
            let count = (perimeter / h).ceil().max(1.0) as usize;
            let volume = perimeter * h / count as Real;
            for n in 0..count {
                let angle = 2.0 * std::f64::consts::PI * n as Real / count as Real;
                let offset = Vector::new(radius * angle.cos(), radius * angle.sin());
                self.markers.push(Marker {
                    owner: p as u32,
                    position: disk.centre + offset,
                    volume,
                });
            }
        }
        for d in 0..DIM {
            let (faces, starts) = (&mut self.faces[d], &mut self.starts[d]);
            faces.clear();
            starts.clear();
            starts.push(0);
            // Faces along axis `d`, cells along the others (offset by half a cell).
            let allowed: [std::ops::Range<isize>; DIM] = std::array::from_fn(|axis| {
                if axis == d {
                    boundary.predicted_faces(grid, d)
                } else {
                    0..grid.cells(axis) as isize
                }
            });
            let offset = |axis: usize| if axis == d { 0.0 } else { 0.5 };
            for marker in &self.markers {
                // Per axis, the indices within 1.5 cells of the marker and their weights.
                let stencil: [([isize; 4], [Real; 4], usize); DIM] = std::array::from_fn(|axis| {
                    let s = (marker.position[axis] - grid.origin[axis]) / h - offset(axis);
                    let mut at = [0; 4];
                    let mut w = [0.0; 4];
                    let mut n = 0;
                    let first = (s - 1.5).ceil() as isize;
                    for i in first..first + 4 {
                        let weight = roma_kernel(s - i as Real);
                        if weight > 0.0 && allowed[axis].contains(&i) {
                            at[n] = i;
                            w[n] = weight;
                            n += 1;
                        }
                    }
                    (at, w, n)
                });
                let (xs, wx, nx) = stencil[0];
                let (ys, wy, ny) = stencil[1];
                for b in 0..ny {
                    for a in 0..nx {
                        faces.push(KernelFace {
                            k: grid.index(xs[a], ys[b]),
                            position: grid.face_position(d, xs[a], ys[b]),
                            weight: wx[a] * wy[b],
                        });
                    }
                }
                starts.push(faces.len());
            }
        }
    }

    /// Forces `u` (after the predictor) towards the rigid velocities of `disks` (placed by
    /// [`MarkerForcing::place`]) in `iterations` passes over a step `dt` and returns in
    /// `forces` minus what the fluid received on this block's faces (the caller sums it over
    /// the blocks). The shares of the marker velocities are summed over the blocks through
    /// `links`.
    #[allow(clippy::too_many_arguments)]
    pub fn apply(
        &mut self,
        grid: &MacGrid,
        disks: &[ImmersedDisk],
        iterations: u32,
        density: Real,
        dt: Real,
        u: &mut [Vec<Real>; DIM],
        forces: &mut Vec<HydrodynamicForce>,
        links: &mut dyn BlockLinks,
    ) {
        forces.clear();
        forces.resize(disks.len(), HydrodynamicForce::default());
        let cell = grid.h * grid.h;
        for _ in 0..iterations {
            self.interpolated.clear();
            self.interpolated.resize(DIM * self.markers.len(), 0.0);
            for (d, ud) in u.iter().enumerate() {
                let (faces, starts) = (&self.faces[d], &self.starts[d]);
                for l in 0..self.markers.len() {
                    self.interpolated[DIM * l + d] = faces[starts[l]..starts[l + 1]]
                        .iter()
                        .map(|f| f.weight * ud[f.k])
                        .sum();
                }
            }
            links.sum(&mut self.interpolated);
            for (d, ud) in u.iter_mut().enumerate() {
                let (faces, starts) = (&self.faces[d], &self.starts[d]);
                for (l, marker) in self.markers.iter().enumerate() {
                    let p = marker.owner as usize;
                    let disk = &disks[p];
                    let slip =
                        disk.velocity_at(&marker.position)[d] - self.interpolated[DIM * l + d];
                    let spread = slip * marker.volume / cell;
                    let force = &mut forces[p];
                    for f in &faces[starts[l]..starts[l + 1]] {
                        let change = f.weight * spread;
                        ud[f.k] += change;
                        let mut on_fluid = Vector::zeros();
                        on_fluid[d] = density * change * cell / dt;
                        force.force -= on_fluid;
                        force.torque -= cross(&(f.position - disk.centre), &on_fluid);
                    }
                }
            }
        }
    }

    /// The largest difference between the velocity at a marker and the grain's rigid
    /// velocity there, as interpolated before the last forcing pass (m/s).
    pub fn last_slip(&self, disks: &[ImmersedDisk]) -> Real {
        let mut largest: Real = 0.0;
        for (l, marker) in self.markers.iter().enumerate() {
            let rigid = disks[marker.owner as usize].velocity_at(&marker.position);
            for d in 0..DIM {
                largest = largest.max((rigid[d] - self.interpolated[DIM * l + d]).abs());
            }
        }
        largest
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::blocks::WholeGrid;
    use xper_poisson::{GridShape, Multigrid, MultigridParams};

    fn whole(grid: &MacGrid) -> WholeGrid {
        let shape = GridShape {
            nx: grid.nx,
            ny: grid.ny,
            hx: grid.h,
            hy: grid.h,
        };
        let boundary = FluidBoundary::closed_box().pressure_boundary();
        WholeGrid {
            multigrid: Multigrid::new(shape, boundary, MultigridParams::default()).unwrap(),
        }
    }

    const DENSITY: Real = 1000.0;

    /// One forcing of `u` on a whole closed box: the forcing (for its slip) and the forces.
    fn force(
        grid: &MacGrid,
        disks: &[ImmersedDisk],
        params: MarkerForcingParams,
        dt: Real,
        u: &mut [Vec<Real>; DIM],
    ) -> (MarkerForcing, Vec<HydrodynamicForce>) {
        let mut forcing = MarkerForcing::default();
        let mut forces = Vec::new();
        forcing.place(grid, &FluidBoundary::closed_box(), disks, params.retraction);
        forcing.apply(
            grid,
            disks,
            params.iterations,
            DENSITY,
            dt,
            u,
            &mut forces,
            &mut whole(grid),
        );
        (forcing, forces)
    }

    /// Roma et al.'s kernel is a partition of unity with zero first moment and sum of squares
    /// 1/2 wherever the marker stands (the conditions it was built from).
    #[test]
    fn kernel_moments() {
        for n in 0..=100 {
            let s = 3.0 + n as Real / 100.0;
            let sums = (0..8).fold([0.0; 3], |acc, i| {
                let r = s - i as Real;
                let w = roma_kernel(r);
                [acc[0] + w, acc[1] + r * w, acc[2] + w * w]
            });
            assert!((sums[0] - 1.0).abs() < 1e-14, "s {s}: sum {}", sums[0]);
            assert!(sums[1].abs() < 1e-14, "s {s}: first moment {}", sums[1]);
            assert!((sums[2] - 0.5).abs() < 1e-14, "s {s}: squares {}", sums[2]);
        }
    }

    fn uniform(grid: &MacGrid, velocity: Vector) -> [Vec<Real>; DIM] {
        let mut u = grid.zero_velocity();
        for (d, ud) in u.iter_mut().enumerate() {
            ud.iter_mut().for_each(|x| *x = velocity[d]);
        }
        u
    }

    fn disk(grid: &MacGrid, velocity: Vector, angular_velocity: Real) -> ImmersedDisk {
        ImmersedDisk {
            centre: grid.origin + Vector::new(16.3 * grid.h, 15.8 * grid.h),
            radius: 6.0 * grid.h,
            velocity,
            angular_velocity,
        }
    }

    /// A grain moving with the flow around it is left alone: the interpolated velocity is the
    /// rigid one at every marker, so nothing changes and the force is zero.
    #[test]
    fn a_grain_moving_with_a_uniform_flow_feels_nothing() {
        let grid = MacGrid::square(32, 1.0);
        let v = Vector::new(0.3, -0.7);
        let mut u = uniform(&grid, v);
        let before = u.clone();
        let disks = [disk(&grid, v, 0.0)];
        let (_, forces) = force(&grid, &disks, MarkerForcingParams::default(), 1e-3, &mut u);
        for d in 0..DIM {
            let change = u[d]
                .iter()
                .zip(&before[d])
                .fold(0.0, |m: Real, (a, b)| m.max((a - b).abs()));
            assert!(change < 1e-14, "component {d} changed by {change}");
        }
        assert!(forces[0].force.norm() < 1e-9 && forces[0].torque.abs() < 1e-12);
    }

    /// A grain at rest in a uniform flow: every pass reduces the slip at the markers (the
    /// multi-direct forcing converges), the force on the grain is along the flow, and the
    /// fluid's change of momentum is exactly minus the force (what the faces received).
    #[test]
    fn passes_reduce_the_slip_and_the_force_balances_the_fluid() {
        let grid = MacGrid::square(32, 1.0);
        let flow = Vector::new(1.0, 0.0);
        let disks = [disk(&grid, Vector::zeros(), 0.0)];
        let (density, dt) = (DENSITY, 1e-3);
        let mut slips = Vec::new();
        for iterations in 1..=6 {
            let mut u = uniform(&grid, flow);
            let params = MarkerForcingParams {
                iterations,
                retraction: 0.3,
            };
            let (forcing, forces) = force(&grid, &disks, params, dt, &mut u);
            slips.push(forcing.last_slip(&disks));
            let mut momentum = Vector::zeros();
            for d in 0..DIM {
                for j in 0..grid.ny as isize {
                    for i in 0..grid.nx as isize {
                        let k = grid.index(i, j);
                        momentum[d] += density * (u[d][k] - flow[d]) * grid.h * grid.h;
                    }
                }
            }
            let force = forces[0].force;
            assert!(force.x > 0.0 && force.y.abs() < 1e-9 * force.x, "{force:?}");
            assert!(
                (momentum / dt + force).norm() < 1e-9 * force.norm(),
                "fluid {:?} against grain {force:?}",
                momentum / dt
            );
        }
        assert!(
            (slips[0] - 1.0).abs() < 1e-12,
            "first pass sees the whole flow"
        );
        for pair in slips.windows(2) {
            assert!(pair[1] < 0.9 * pair[0], "slips {slips:?}");
        }
    }
}
