use std::path::Path;
use std::time::Instant;
fn main() {
    let refs = Path::new("../shared/validation_refs/Ghia1982");
    let t = Instant::now();
    for c in xper_fluid::validation::lid_driven_cavity(1000, 128, refs, 0.05).unwrap() {
        println!("{c:?}");
    }
    println!("cavity Re1000 128: {:.1} s", t.elapsed().as_secs_f64());
    let t = Instant::now();
    println!(
        "{:?}",
        xper_fluid::validation::schaefer_turek(0.00125, 3.0).unwrap()
    );
    println!("ST 80/D: {:.1} s", t.elapsed().as_secs_f64());
}
