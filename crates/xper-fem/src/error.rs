//! The error every constructor and driver of this crate returns.

use std::fmt;

/// Why an element, a material or a driven strain path is refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FemError {
    /// A node coordinate is NaN or infinite.
    NonFiniteNode {
        /// Local node index (0, 1 or 2).
        node: usize,
    },
    /// The triangle's area is zero or negligible compared with its longest edge squared.
    DegenerateTriangle {
        /// Signed area (m^2).
        area: f64,
    },
    /// The nodes are ordered clockwise (negative signed area); elements must be
    /// counter-clockwise.
    ClockwiseTriangle {
        /// Signed area (m^2).
        area: f64,
    },
    /// The thickness is not a finite positive number.
    InvalidThickness {
        /// Its value (m).
        value: f64,
    },
    /// A material parameter is out of its admissible range.
    InvalidMaterial {
        /// Name of the parameter.
        parameter: &'static str,
        /// Its value.
        value: f64,
        /// The admissible range, in words.
        expected: &'static str,
    },
    /// A strain driver was given a NaN or infinite strain.
    NonFiniteStrain {
        /// Index of the step of the strain path.
        step: usize,
    },
    /// A strain driver could not enforce its stress condition.
    NotConverged {
        /// Index of the step of the strain path.
        step: usize,
        /// The stress residual left (Pa).
        residual: f64,
    },
}

impl fmt::Display for FemError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            FemError::NonFiniteNode { node } => {
                write!(f, "triangle: node {node} has a non-finite coordinate")
            }
            FemError::DegenerateTriangle { area } => {
                write!(f, "triangle: degenerate (area {area:.3e} m^2)")
            }
            FemError::ClockwiseTriangle { area } => write!(
                f,
                "triangle: nodes are clockwise (signed area {area:.3e} m^2); \
                 give them counter-clockwise"
            ),
            FemError::InvalidThickness { value } => {
                write!(f, "triangle: thickness {value} m must be finite and > 0")
            }
            FemError::InvalidMaterial {
                parameter,
                value,
                expected,
            } => write!(f, "material: {parameter} = {value} must be {expected}"),
            FemError::NonFiniteStrain { step } => {
                write!(f, "strain driver: step {step} has a non-finite strain")
            }
            FemError::NotConverged { step, residual } => write!(
                f,
                "strain driver: step {step} did not converge (stress residual {residual:.3e} Pa)"
            ),
        }
    }
}

impl std::error::Error for FemError {}
