//! A box of a few hundred disks deposits under gravity without interpenetration beyond the
//! projection tolerance (1e-4 x the smallest radius), and its kinetic energy decays.

mod common;
use common::{deposit_scene, temp_dir, xper};
use xper_io::SeriesTable;

#[test]
fn box_of_disks_deposits_and_comes_to_rest() {
    let dir = temp_dir("deposit");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, deposit_scene(300, 3000)).unwrap();
    let out = dir.join("out");
    let run = xper(&["run", scene.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let series = SeriesTable::read_csv(&out.join("series.csv")).unwrap();
    let ke = series.column("kinetic_energy").unwrap();
    let overlap = series.column("max_overlap").unwrap();
    let projected = series.column("projection_iterations").unwrap();
    let peak = ke.iter().copied().fold(0.0, f64::max);
    let last = *ke.last().unwrap();
    assert!(peak > 0.0 && last < 1e-3 * peak, "kinetic energy {last} vs peak {peak}");
    // Overlaps after the last projection: the step's overlap before projection is below
    // the tolerance whenever no projection ran.
    let tolerance = 1e-4 * 0.002;
    let settled: Vec<(f64, f64)> = overlap.iter().copied().zip(projected.iter().copied()).skip(2500).collect();
    for (o, p) in &settled {
        assert!(*p > 0.0 || *o <= tolerance, "overlap {o} m left without projection");
    }
    let max_settled = settled.iter().map(|s| s.0).fold(0.0, f64::max);
    assert!(max_settled < 10.0 * tolerance, "settled overlap {max_settled} m");
    let non_converged = series.column("converged").unwrap().iter().filter(|&&c| c == 0.0).count();
    // NLGS may hit its sweep cap on a few steps of the collapse; it is reported, and rare.
    assert!(non_converged * 100 <= 3 * ke.len(), "{non_converged} non-converged steps");
    let energy_error = series.column("energy_error").unwrap();
    let dissipated = *series.column("dissipated_energy").unwrap().last().unwrap();
    assert!(energy_error.iter().all(|e| e.abs() < 1e-6 * dissipated), "energy balance");
}
