//! Imposed velocities and forces on a body's degrees of freedom, as functions of time.

use serde::{Deserialize, Serialize};
use xper_math::{Real, Vector};

/// A scalar function of time (s).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum TimeFunction {
    /// The same value at all times.
    Constant(Real),
    /// Piecewise linear through `(t, value)` points with strictly increasing `t`, constant
    /// beyond both ends.
    Table(Vec<(Real, Real)>),
    /// `offset + amplitude * sin(2 pi frequency t + phase)` (frequency in Hz, phase in rad).
    Sine {
        /// Amplitude, in the unit of the driven quantity.
        amplitude: Real,
        /// Frequency (Hz).
        frequency: Real,
        /// Phase (rad).
        phase: Real,
        /// Constant offset.
        offset: Real,
    },
}

impl TimeFunction {
    /// Value at time `t`.
    pub fn eval(&self, t: Real) -> Real {
        match self {
            TimeFunction::Constant(v) => *v,
            TimeFunction::Table(points) => {
                let Some(first) = points.first() else {
                    return 0.0;
                };
                if t <= first.0 {
                    return first.1;
                }
                for w in points.windows(2) {
                    let ((t0, v0), (t1, v1)) = (w[0], w[1]);
                    if t <= t1 {
                        return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
                    }
                }
                points[points.len() - 1].1
            }
            TimeFunction::Sine {
                amplitude,
                frequency,
                phase,
                offset,
            } => offset + amplitude * (2.0 * std::f64::consts::PI * frequency * t + phase).sin(),
        }
    }
}

/// What drives one degree of freedom of a body.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum Drive {
    /// Moves under gravity and contact forces.
    #[default]
    Free,
    /// Velocity (m/s or rad/s) imposed: contacts cannot change it.
    Velocity(TimeFunction),
    /// An external force (N per unit thickness) or torque added to gravity.
    Force(TimeFunction),
    /// A pressure on a wall, applied as the force `p A n_d` on this translational degree of
    /// freedom, with `A` the loaded length (2D, m) or area (3D, m^2) measured at the
    /// beginning of each step: a servo wall holding a confining pressure.
    Pressure(PressureDrive),
}

/// A pressure (Pa) on a wall and the extent it acts on ([`Drive::Pressure`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PressureDrive {
    /// The pressure (Pa) as a function of time; positive pushes along `direction`.
    pub pressure: TimeFunction,
    /// `n_d`: the component along this degree of freedom of the unit direction the pressure
    /// pushes the wall (its normal, towards the sample).
    pub direction: Real,
    /// The loaded extent `A`: the product of these factors (one per direction along the wall).
    pub extent: Vec<ExtentFactor>,
}

/// One factor of a loaded extent.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum ExtentFactor {
    /// A fixed length (m).
    Fixed(Real),
    /// The distance between two bodies along a unit `axis`: `|(x_b - x_a) . axis|` (m), e.g.
    /// the height of a sample between its top and bottom walls.
    Between {
        /// The two bodies `[a, b]` (indices in the body set).
        bodies: [u32; 2],
        /// The unit axis.
        axis: Vector,
    },
}

impl PressureDrive {
    /// The force (N per unit thickness in 2D, N in 3D) at pressure `p` (Pa) with the bodies at
    /// `positions` (indexed by body).
    pub fn force(&self, p: Real, positions: &[Vector]) -> Real {
        let extent: Real = (self.extent.iter())
            .map(|f| match f {
                ExtentFactor::Fixed(l) => *l,
                ExtentFactor::Between { bodies, axis } => {
                    let [a, b] = bodies.map(|k| positions[k as usize]);
                    (b - a).dot(axis).abs()
                }
            })
            .product();
        p * extent * self.direction
    }
}

impl Drive {
    /// Whether the velocity of this degree of freedom is imposed.
    pub fn is_imposed_velocity(&self) -> bool {
        matches!(self, Drive::Velocity(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_interpolates_and_clamps() {
        let f = TimeFunction::Table(vec![(0.0, 0.0), (1.0, 2.0), (3.0, -2.0)]);
        assert_eq!(f.eval(-1.0), 0.0);
        assert_eq!(f.eval(0.5), 1.0);
        assert_eq!(f.eval(2.0), 0.0);
        assert_eq!(f.eval(10.0), -2.0);
    }

    #[test]
    fn sine_matches_formula() {
        let f = TimeFunction::Sine {
            amplitude: 2.0,
            frequency: 0.25,
            phase: 0.0,
            offset: 1.0,
        };
        assert!((f.eval(1.0) - 3.0).abs() < 1e-15);
    }

    #[test]
    fn pressure_force_is_pressure_times_the_followed_extent() {
        let drive = PressureDrive {
            pressure: TimeFunction::Constant(1e5),
            direction: -1.0,
            extent: vec![
                ExtentFactor::Between {
                    bodies: [0, 1],
                    axis: Vector::from_fn(|k, _| (k == 1) as u8 as Real),
                },
                ExtentFactor::Fixed(0.5),
            ],
        };
        let at = |y: Real| Vector::from_fn(|k, _| if k == 1 { y } else { 7.0 });
        let f = drive.force(1e5, &[at(0.25), at(0.05)]);
        assert!((f - (-1e5 * 0.2 * 0.5)).abs() < 1e-9, "{f}");
    }
}
