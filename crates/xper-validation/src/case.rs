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

/// A case (shorthand for the struct literal).
pub(crate) fn case(
    name: String,
    reference: String,
    measured: String,
    error: f64,
    tolerance: f64,
) -> Case {
    Case {
        name,
        reference,
        measured,
        error,
        tolerance,
    }
}

/// 0 when `ok`, else 1: the error of a check without a natural number.
pub(crate) fn indicator(ok: bool) -> f64 {
    if ok {
        0.0
    } else {
        1.0
    }
}

/// Appends the rows of `cases` to a validation table; returns how many failed.
pub(crate) fn push_cases(md: &mut String, cases: &[Case]) -> usize {
    for c in cases {
        push_case_row(md, &c.name, &c.reference, &c.measured, c.error, c.tolerance);
    }
    cases.iter().filter(|c| !c.passed()).count()
}

/// Appends one case to a validation table and prints its verdict (pass when
/// `error <= tolerance`, so a NaN error fails).
pub(crate) fn push_case_row(
    md: &mut String,
    name: &str,
    reference: &str,
    measured: &str,
    error: f64,
    tolerance: f64,
) {
    let verdict = if error <= tolerance { "pass" } else { "FAIL" };
    println!("{verdict}: {name} ({error:.2e} <= {tolerance:.0e})");
    md.push_str(&format!(
        "| {name} | {reference} | {measured} | {error:.2e} | {tolerance:.0e} | {verdict} |\n"
    ));
}
