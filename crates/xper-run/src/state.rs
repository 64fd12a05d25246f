//! A simulation's state as named arrays, for scripting (the Python module reads them into
//! NumPy and writes some back between steps). Each physics lists its arrays with their units
//! ([`ArrayInfo`]); an array is row-major with its shape ([`StateArray`]).

/// What an array holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArrayInfo {
    /// `part.quantity`, e.g. `bodies.position`.
    pub name: &'static str,
    /// Shape with `n` for the count of the part (bodies, contacts, ...), e.g. `(n, 2)`.
    pub shape: &'static str,
    /// Element type: `float64` or `int64`.
    pub dtype: &'static str,
    /// SI unit, `1` for a number without one.
    pub unit: &'static str,
    /// Whether [`crate::Simulation::set_array`] takes it between steps.
    pub writable: bool,
    /// One line on what it is.
    pub about: &'static str,
}

impl ArrayInfo {
    /// An array scripts may read and, if `writable`, write.
    pub const fn new(
        name: &'static str,
        shape: &'static str,
        dtype: &'static str,
        unit: &'static str,
        writable: bool,
        about: &'static str,
    ) -> Self {
        ArrayInfo {
            name,
            shape,
            dtype,
            unit,
            writable,
            about,
        }
    }

    /// An array scripts read only.
    pub const fn read_only(
        name: &'static str,
        shape: &'static str,
        dtype: &'static str,
        unit: &'static str,
        about: &'static str,
    ) -> Self {
        Self::new(name, shape, dtype, unit, false, about)
    }
}

/// The values of an array.
#[derive(Clone, Debug, PartialEq)]
pub enum ArrayData {
    /// Real numbers.
    F64(Vec<f64>),
    /// Integers (indices, identifiers, groups, codes).
    I64(Vec<i64>),
}

/// An array of the state, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct StateArray {
    /// Extent of each axis.
    pub shape: Vec<usize>,
    /// `shape`'s product values.
    pub data: ArrayData,
}

impl StateArray {
    /// Reals of shape `shape` (row-major).
    pub fn reals(shape: &[usize], data: Vec<f64>) -> Self {
        StateArray {
            shape: shape.to_vec(),
            data: ArrayData::F64(data),
        }
    }

    /// Integers of shape `shape` (row-major).
    pub fn integers(shape: &[usize], data: Vec<i64>) -> Self {
        StateArray {
            shape: shape.to_vec(),
            data: ArrayData::I64(data),
        }
    }
}

/// Checks that values of shape `given` fit the array `name` of shape `expected` before they are
/// written into a state: the error names the array and both shapes.
pub fn check_shape(name: &str, given: &[usize], expected: &[usize]) -> Result<(), String> {
    match given == expected {
        true => Ok(()),
        false => Err(format!(
            "{name}: an array of shape {given:?} given, the state's has shape {expected:?}"
        )),
    }
}
