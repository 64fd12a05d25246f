//! The record of one validation comparison, shared by every physics' cases and the
//! VALIDATION.md tables.

/// One comparison of a measured value with its reference.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Case {
    /// What is tested.
    pub name: String,
    /// The reference value and where it comes from (formula, source).
    pub reference: String,
    /// The measured value, as printed.
    pub measured: String,
    /// The deviation compared with the tolerance (NaN fails).
    pub error: f64,
    /// Largest acceptable error.
    pub tolerance: f64,
}

impl Case {
    /// Whether the error is within the tolerance (false when the error is NaN).
    pub fn passed(&self) -> bool {
        self.error <= self.tolerance
    }
}
