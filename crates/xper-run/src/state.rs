//! A simulation's state as named arrays, for scripting (the Python module reads them into
//! NumPy and writes some back between steps). Each physics lists its arrays with their units
//! ([`ArrayInfo`]); an array is row-major with its shape ([`StateArray`]). Some arrays can
//! also be read in place, without a copy ([`StateView`]).

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

/// A state array read in place ([`crate::Simulation::view`]): the address of reals the
/// simulation itself keeps, contiguous and row-major, with their shape. Its values change with
/// every step and write; its address holds until the simulation grows the storage (adding
/// bodies) or is dropped, which the holder of a view must prevent.
#[derive(Clone, Debug, PartialEq)]
pub struct StateView {
    /// Extent of each axis.
    pub shape: Vec<usize>,
    /// The first of `shape`'s product reals.
    pub data: *const f64,
}

impl StateView {
    /// The view of shape `shape` of the reals of `values`, or `None` when their count is not
    /// `shape`'s product. The pointer comes from [`Vec::as_ptr`], which creates no reference
    /// to the elements, so it stays valid while the vector is later written in place.
    ///
    /// # Safety
    /// `T` must be made of `f64`s only, without padding (`f64`, nalgebra's `SVector<f64, D>`).
    pub unsafe fn of<T>(shape: &[usize], values: &Vec<T>) -> Option<Self> {
        let reals = std::mem::size_of_val(values.as_slice()) / std::mem::size_of::<f64>();
        let fits = std::mem::align_of::<T>() == std::mem::align_of::<f64>()
            && shape.iter().product::<usize>() == reals;
        fits.then(|| StateView {
            shape: shape.to_vec(),
            data: values.as_ptr().cast(),
        })
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_view_reads_the_vector_in_place_and_checks_its_shape() {
        let mut values = vec![[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]];
        // SAFETY: [f64; 2] is made of f64s.
        let view = unsafe { StateView::of(&[3, 2], &values) }.unwrap();
        assert_eq!(view.shape, [3, 2]);
        values[1][0] = 30.0;
        // SAFETY: `values` is alive and was not reallocated.
        let read = unsafe { std::slice::from_raw_parts(view.data, 6) };
        assert_eq!(read, [1.0, 2.0, 30.0, 4.0, 5.0, 6.0]);
        assert!(unsafe { StateView::of(&[2, 2], &values) }.is_none());
        assert!(unsafe { StateView::of(&[6], &[1u8; 48].to_vec()) }.is_none());
    }
}
