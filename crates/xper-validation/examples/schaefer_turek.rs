//! Prints the Schaefer-Turek 2D-1 coefficients for a cell size and end time given on the
//! command line, with `markers` for the marker forcing:
//! `cargo run --release -p xper-validation --example schaefer_turek -- 0.005 8 [markers]`.
fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (h, end) = (
        args.first().copied().unwrap_or(0.005),
        args.get(1).copied().unwrap_or(8.0),
    );
    let forcing = if std::env::args().any(|a| a == "markers") {
        xper_fluid::Forcing::Markers(Default::default())
    } else {
        xper_fluid::Forcing::Fraction
    };
    match xper_validation::fluid::schaefer_turek(h, end, forcing) {
        Ok(case) => println!("{}: {} (error {:.3})", case.name, case.measured, case.error),
        Err(e) => eprintln!("{e}"),
    }
}
