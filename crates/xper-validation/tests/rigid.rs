//! Every validation case passes (the same code that writes VALIDATION.md).

#[test]
fn every_validation_case_passes() {
    let cases = xper_validation::rigid::all_cases(300, 3000).expect("cases run");
    for c in &cases {
        assert!(
            c.passed(),
            "{}: error {:e} > tolerance {:e} ({})",
            c.name,
            c.error,
            c.tolerance,
            c.measured
        );
    }
    assert_eq!(cases.len(), 11);
}
