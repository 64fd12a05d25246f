//! Imposed velocities and forces on a body's degrees of freedom, as functions of time.

use serde::{Deserialize, Serialize};
use xper_math::Real;

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
}
