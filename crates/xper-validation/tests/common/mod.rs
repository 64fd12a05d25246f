//! The assertion of validation cases shared by the engine tests.

use xper_validation::Case;

/// Prints every case of a scenario (shown with `--nocapture`), then asserts each one passed;
/// an engine failure (build or step error) fails with its message.
pub fn check(cases: Result<Vec<Case>, String>) {
    let cases = cases.unwrap_or_else(|e| panic!("{e}"));
    assert!(!cases.is_empty(), "no case");
    for case in &cases {
        println!(
            "{} | {} | {} | error {:.3e} | tolerance {:.0e} | {}",
            case.name,
            case.reference,
            case.measured,
            case.error,
            case.tolerance,
            if case.passed() { "pass" } else { "FAIL" }
        );
    }
    for case in &cases {
        assert!(case.passed(), "{case:?}");
    }
}
