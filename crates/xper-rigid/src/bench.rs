//! `xper bench` of a rigid scene: the figures of ../shared/bench/box10k.md (box3d10k.md in
//! 3D), measured on the engine alone, without outputs.

use crate::build::{release_body_descriptions, world_from_scene, RigidScene};
use crate::RunError;
use std::path::Path;
use xper_geometry::{ContactSet, Detector};
use xper_nscd::MoreauJean;
pub use xper_run::bench::BenchResult;

/// Median of a sample (the upper one for an even count); NaN when empty.
pub fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// Runs one scene, loaded from `path`, in this process, on `machine` (a description).
pub fn bench_one(
    mut scene: RigidScene,
    path: &Path,
    steps: Option<u64>,
    settled: usize,
    machine: String,
) -> Result<BenchResult, RunError> {
    let mut world = world_from_scene(&scene);
    release_body_descriptions(&mut scene);
    let steps = steps.map_or(scene.steps, |s| s.min(scene.steps));
    let mut stepper = MoreauJean::new();
    // Sized for the run: grown by doubling, these figures would weigh on the heap peak.
    let series = || Vec::with_capacity(steps as usize);
    let (mut total, mut sweeps, mut contacts, mut ns_update, mut detect) =
        (series(), series(), series(), series(), series());
    let mut non_converged = 0;
    let started = std::time::Instant::now();
    for _ in 0..steps {
        let r = stepper
            .step(&mut world)
            .map_err(|e| RunError::Runtime(format!("{}: {e}", path.display())))?;
        total.push(r.times.total * 1e3);
        sweeps.push(r.iterations as f64);
        contacts.push(r.contacts as f64);
        detect.push(r.times.detect * 1e3);
        if r.iterations > 0 && r.active > 0 {
            ns_update.push(r.times.solve * 1e9 / (r.active as f64 * r.iterations as f64));
        }
        non_converged += (!r.converged) as usize;
    }
    let wall_time_s = started.elapsed().as_secs_f64();
    // Read before the overlap measurement below, whose detector is the benchmark's, not the run's.
    let peak = xper_io::peak_memory_bytes().unwrap_or(0);
    let peak_heap = xper_io::peak_heap_bytes();
    let mut final_contacts = ContactSet::default();
    Detector::new().detect(
        &world.bodies,
        world.params.alert_distance,
        |a, b| world.laws.between(a, b),
        &mut final_contacts,
    );
    let mut overlaps: Vec<f64> = (final_contacts.gaps.iter())
        .filter(|&&gap| gap < 0.0)
        .map(|&gap| -gap)
        .collect();
    overlaps.sort_by(f64::total_cmp);
    let tail = |v: &[f64]| v[v.len().saturating_sub(settled)..].to_vec();
    let bodies = world.bodies.len();
    Ok(BenchResult {
        scene: scene.name.clone(),
        dimension: Some(xper_math::DIM as u8),
        bodies,
        steps,
        machine,
        median_step_ms: median(total.clone()),
        median_settled_step_ms: median(tail(&total)),
        median_sweeps: median(sweeps.clone()),
        median_settled_sweeps: median(tail(&sweeps)),
        median_contacts: median(contacts.clone()),
        median_settled_contacts: median(tail(&contacts)),
        median_ns_per_contact_update: median(ns_update),
        median_detect_ms: median(detect.clone()),
        mean_detect_ns_per_body: Some(
            detect.iter().sum::<f64>() / detect.len().max(1) as f64 * 1e6 / bodies as f64,
        ),
        median_detect_ns_per_body: median(detect) * 1e6 / bodies as f64,
        candidate_list_builds: Some(stepper.detector_stats().builds),
        non_converged_steps: non_converged,
        peak_memory_bytes: peak,
        peak_memory_bytes_per_body: peak as f64 / bodies as f64,
        peak_heap_bytes: peak_heap,
        overlap_median_m: percentile(&overlaps, 0.5),
        overlap_p99_m: percentile(&overlaps, 0.99),
        overlap_max_m: overlaps.last().copied().unwrap_or(0.0),
        overlapping_contacts: overlaps.len(),
        wall_time_s,
    })
}
