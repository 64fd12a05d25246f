//! Lubrication correction for grains closer than the grid resolves.
//!
//! Two cylinders of radii `a_1`, `a_2` (per unit length) approaching each other at normal
//! speed `U` across a gap `delta` much smaller than their radii squeeze out the fluid between
//! them. Reynolds' lubrication equation with the gap `delta + x^2 / (2 a*)`,
//! `1/a* = 1/a_1 + 1/a_2`, gives the pressure `6 mu U a* / H^2` and the force
//!
//! ```text
//! F(delta) = 3 sqrt(2) pi mu U (a* / delta)^(3/2)
//! ```
//!
//! (Jeffrey and Onishi, Q. J. Mech. Appl. Math. 34 (1981) 129, for a cylinder and a plane,
//! `a* = a`; the leading term of Kromkamp, van den Ende, Kandhai, van der Sman and Boom, Chem.
//! Eng. Sci. 61 (2006) 858, for two cylinders). The resolved flow carries this force down to
//! gaps of about a cell; below the range `delta_c` the correction adds the part it misses,
//!
//! ```text
//! F_lub = -3 sqrt(2) pi mu a*^(3/2) (delta_e^(-3/2) - delta_c^(-3/2)) U_n,
//! delta_e = max(delta, delta_min),
//! ```
//!
//! zero at `delta_c`, saturated below the roughness `delta_min` (the grains touch by Signorini
//! contacts). It acts along the line of centres, against the relative normal velocity `U_n`
//! (squeezing and separating alike). Its coefficient grows without bound as the gap closes,
//! so it is implicit pair by pair (backward Euler on the relative normal velocity, stable for
//! any step): with `U_n` the relative normal velocity the grains would have at the end of the
//! step under every other force (the caller's [`LubricatedGrain::velocity`]), the force is
//! `c U_n / (1 + dt c / m*)`, `m* = (1/m_1 + 1/m_2)^-1`, the force at the end of the step.
//! A grain pressed on a wall by its weight `W` then approaches at `W / c`, the quasi-steady
//! lubrication speed, whatever the step (an explicit force, or one acting on the velocity at
//! the start of the step, would let it approach `1 + dt c / m` times too fast).

use serde::{Deserialize, Serialize};
use xper_math::{Real, Vector, DIM};

/// The lubrication correction's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Lubrication {
    /// Range `delta_c` in cells: the correction acts on gaps below `range * h`.
    pub range: Real,
    /// Roughness `delta_min` as a fraction of the smaller radius: gaps below it count as it.
    pub roughness: Real,
}

impl Default for Lubrication {
    /// One cell of range (the gap the direct forcing resolves no more), roughness 1e-3 radius.
    fn default() -> Self {
        Lubrication {
            range: 1.0,
            roughness: 1e-3,
        }
    }
}

/// One grain as the correction sees it.
#[derive(Clone, Copy, Debug)]
pub struct LubricatedGrain {
    /// Centre (m).
    pub centre: Vector,
    /// Radius (m).
    pub radius: Real,
    /// Velocity (m/s) at the end of the step under every force but this correction's.
    pub velocity: Vector,
    /// Inverse mass per unit thickness (m/kg); 0 for a grain whose translation is imposed.
    pub inverse_mass: Real,
}

/// A plane wall of the fluid domain: the points `x` with `x[axis] = at`, the fluid on the side
/// `side` (+1: above, -1: below).
#[derive(Clone, Copy, Debug)]
pub struct LubricatedWall {
    /// Normal axis.
    pub axis: usize,
    /// Position along it (m).
    pub at: Real,
    /// +1 if the fluid is on the high side, -1 on the low side.
    pub side: Real,
}

impl Lubrication {
    /// The coefficient `c` (N s/m^2 per m) at gap `delta` (m) between surfaces of reduced
    /// radius `reduced` (m), on a grid of step `h` (m), for viscosity `mu` (Pa s), and
    /// smaller radius `smaller` (m): `F = -c U_n`; zero at and beyond the range.
    pub fn coefficient(
        &self,
        mu: Real,
        reduced: Real,
        smaller: Real,
        delta: Real,
        h: Real,
    ) -> Real {
        let range = self.range * h;
        // NaN gaps give no force.
        if delta >= range || delta.is_nan() {
            return 0.0;
        }
        let effective = delta.max(self.roughness * smaller);
        let k = 3.0 * std::f64::consts::SQRT_2 * std::f64::consts::PI * mu * reduced.powf(1.5);
        k * (effective.powf(-1.5) - range.powf(-1.5)).max(0.0)
    }

    /// Adds the correction over a step `dt` to `forces` (one per grain, N/m) for the pairs of
    /// `grains` and each grain with each of `walls`, in viscosity `mu`, grid step `h`. Pairs
    /// are found by sorting along x: `O(n log n)` plus the pairs within reach.
    pub fn add_forces(
        &self,
        mu: Real,
        h: Real,
        dt: Real,
        grains: &[LubricatedGrain],
        walls: &[LubricatedWall],
        forces: &mut [Vector],
    ) {
        let reach = self.range * h;
        let mut order: Vec<usize> = (0..grains.len()).collect();
        order.sort_by(|&p, &q| {
            let left = |p: usize| grains[p].centre.x - grains[p].radius;
            left(p).total_cmp(&left(q)).then(p.cmp(&q))
        });
        for (n, &p) in order.iter().enumerate() {
            let a = &grains[p];
            let right = a.centre.x + a.radius + reach;
            for &q in &order[n + 1..] {
                let b = &grains[q];
                if b.centre.x - b.radius > right {
                    break;
                }
                let between = b.centre - a.centre;
                let distance = between.norm();
                let delta = distance - a.radius - b.radius;
                if delta >= reach || delta.is_nan() || distance == 0.0 {
                    continue;
                }
                let normal = between / distance;
                let reduced = a.radius * b.radius / (a.radius + b.radius);
                let c = self.coefficient(mu, reduced, a.radius.min(b.radius), delta, h);
                let mobility = a.inverse_mass + b.inverse_mass;
                let approach = (b.velocity - a.velocity).dot(&normal) / (1.0 + dt * c * mobility);
                let on_a = normal * (c * approach);
                forces[p] += on_a;
                forces[q] -= on_a;
            }
            for wall in walls {
                let delta = wall.side * (a.centre[wall.axis] - wall.at) - a.radius;
                if delta >= reach || delta.is_nan() {
                    continue;
                }
                let c = self.coefficient(mu, a.radius, a.radius, delta, h);
                // The normal from the grain to the wall, and the wall at rest along it.
                let mut normal = Vector::zeros();
                normal[wall.axis] = -wall.side;
                let approach = -a.velocity.dot(&normal) / (1.0 + dt * c * a.inverse_mass);
                forces[p] += normal * (c * approach);
            }
        }
        debug_assert!(walls.iter().all(|w| w.axis < DIM));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MU: Real = 1e-3;

    /// Below the range the force is the lubrication formula minus its value at the range; zero
    /// beyond; saturated below the roughness.
    #[test]
    fn coefficient_is_the_lubrication_formula_cut_at_the_range() {
        let lub = Lubrication::default();
        let (a, h): (Real, Real) = (1e-3, 1e-4);
        let formula = |d: Real| 3.0 * 2f64.sqrt() * std::f64::consts::PI * MU * (a / d).powf(1.5);
        for delta in [1e-6, 1e-5, 5e-5, 9.9e-5] {
            let c = lub.coefficient(MU, a, a, delta, h);
            let expected = formula(delta) - formula(h);
            assert!(
                (c - expected).abs() <= 1e-12 * expected,
                "{delta}: {c} vs {expected}"
            );
        }
        assert_eq!(lub.coefficient(MU, a, a, 1e-4, h), 0.0);
        assert_eq!(lub.coefficient(MU, a, a, 2e-4, h), 0.0);
        assert_eq!(
            lub.coefficient(MU, a, a, 1e-9, h),
            lub.coefficient(MU, a, a, 1e-6, h)
        );
        // Two equal cylinders: reduced radius a/2, (3 pi / 2) mu (a / delta)^(3/2).
        let pair = lub.coefficient(MU, 0.5 * a, a, 1e-6, 1.0) + formula(1.0) / 2f64.powf(1.5);
        let expected = 1.5 * std::f64::consts::PI * MU * (a / 1e-6).powf(1.5);
        assert!((pair - expected).abs() <= 1e-9 * expected);
    }

    /// A disk driven towards a wall by the correction alone stops at the gap where the
    /// lubrication impulse has absorbed its momentum:
    /// `m U_0 = int_delta_stop^delta_0 c(delta) d delta`, with `c = K (delta^-3/2 - delta_c^-3/2)`,
    /// i.e. `m U_0 = 2 K (delta_s^-1/2 - delta_0^-1/2) - K delta_c^-3/2 (delta_0 - delta_s)`,
    /// solved by bisection; the stepped disk's closest gap matches it within 1 %.
    #[test]
    fn a_disk_thrown_at_a_wall_stops_where_the_lubrication_impulse_says() {
        let lub = Lubrication {
            range: 1.0,
            roughness: 1e-6,
        };
        let (a, h, m): (Real, Real, Real) = (1e-3, 1e-4, 3e-3);
        let (delta0, u0): (Real, Real) = (0.9e-4, 0.05);
        let k = 3.0 * 2f64.sqrt() * std::f64::consts::PI * MU * a.powf(1.5);
        let impulse = |ds: Real| {
            2.0 * k * (ds.powf(-0.5) - delta0.powf(-0.5)) - k * h.powf(-1.5) * (delta0 - ds)
        };
        let (mut lo, mut hi) = (1e-12, delta0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if impulse(mid) > m * u0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let stop = 0.5 * (lo + hi);
        assert!(stop > 1e-7 && stop < 0.5 * delta0, "{stop}");
        let wall = LubricatedWall {
            axis: 1,
            at: 0.0,
            side: 1.0,
        };
        let mut grain = LubricatedGrain {
            centre: Vector::new(0.0, a + delta0),
            radius: a,
            velocity: Vector::new(0.0, -u0),
            inverse_mass: 1.0 / m,
        };
        let dt = 1e-6;
        let mut closest = delta0;
        for _ in 0..200_000 {
            let mut force = [Vector::zeros()];
            lub.add_forces(MU, h, dt, &[grain], &[wall], &mut force);
            grain.velocity += force[0] * (dt / m);
            grain.centre += grain.velocity * dt;
            closest = closest.min(grain.centre.y - a);
        }
        assert!(
            (closest - stop).abs() <= 0.01 * stop,
            "closest gap {closest:e} m, expected {stop:e} m"
        );
    }

    /// Equal and opposite forces on a pair, along the line of centres, resisting both the
    /// approach and the separation; none beyond the range.
    #[test]
    fn pair_forces_are_equal_opposite_and_resist_the_relative_motion() {
        let lub = Lubrication::default();
        let h = 1e-4;
        let grain = |x: Real, y: Real, vx: Real| LubricatedGrain {
            centre: Vector::new(x, y),
            radius: 1e-3,
            velocity: Vector::new(vx, 0.3),
            inverse_mass: 1e3,
        };
        for (gap, v, sign) in [(2e-5, 0.01, -1.0), (2e-5, -0.01, 1.0), (2e-4, 0.01, 0.0)] {
            let grains = [grain(0.0, 0.5, v), grain(2e-3 + gap, 0.5, -v)];
            let mut forces = [Vector::zeros(); 2];
            lub.add_forces(MU, h, 1e-4, &grains, &[], &mut forces);
            assert_eq!(forces[0], -forces[1]);
            assert_eq!(forces[0].y, 0.0);
            assert_eq!(
                forces[0].x.signum() * (forces[0].x != 0.0) as u8 as Real,
                sign
            );
        }
    }
}

#[cfg(test)]
mod weight_tests {
    use super::*;

    /// A grain pressed on a wall by a weight `W` (a force outside the correction) settles at
    /// the quasi-steady speed `W / c(delta)` whatever the step: with the correction acting on
    /// the velocity the grain would reach under the weight alone, a step 100 times the
    /// grain's relaxation time `m / c` gives the same speed as a small one.
    #[test]
    fn a_weighted_grain_approaches_at_the_quasi_steady_speed_for_any_step() {
        let lub = Lubrication::default();
        let (a, h, m, mu, weight): (Real, Real, Real, Real, Real) =
            (1e-3, 1e-4, 4.7e-3, 1e-2, 0.0154);
        let delta = 2e-5;
        let wall = LubricatedWall {
            axis: 1,
            at: 0.0,
            side: 1.0,
        };
        let c = lub.coefficient(mu, a, a, delta, h);
        let quasi_steady = weight / c;
        for dt in [1e-7, 1e-5, 1e-2] {
            let mut v: Real = 0.0;
            // At least 20 relaxation times.
            let steps = (20.0 * m / (c * dt)).ceil().max(50.0) as usize;
            for _ in 0..steps {
                // The step as the coupling takes it: predicted under the weight, corrected.
                let predicted = v - weight / m * dt;
                let grain = LubricatedGrain {
                    centre: Vector::new(0.0, a + delta),
                    radius: a,
                    velocity: Vector::new(0.0, predicted),
                    inverse_mass: 1.0 / m,
                };
                let mut force = [Vector::zeros()];
                lub.add_forces(mu, h, dt, &[grain], &[wall], &mut force);
                v += (force[0].y - weight) / m * dt;
            }
            assert!(
                (v.abs() - quasi_steady).abs() <= 1e-3 * quasi_steady,
                "dt {dt}: speed {} against {quasi_steady}",
                v.abs()
            );
        }
    }
}
