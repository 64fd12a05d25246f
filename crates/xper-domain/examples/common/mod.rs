//! What the model examples share: the network they assume and how they save their figures.

/// Latency of one message (s): an InfiniBand cluster, as the rigid model of BENCHMARKS.md.
pub const ALPHA: f64 = 2e-6;
/// Bandwidth (bytes/s).
pub const BETA: f64 = 5e9;

/// Writes `figures` as JSON to `path` atomically (a temporary file renamed); on failure,
/// prints the reason with the file and exits 1.
pub fn write_json(program: &str, path: &str, figures: &[serde_json::Value]) {
    let text = serde_json::to_string_pretty(figures).expect("plain numbers");
    let temporary = format!("{path}.tmp");
    let written = std::fs::write(&temporary, text).and_then(|_| std::fs::rename(&temporary, path));
    if let Err(e) = written {
        eprintln!("{program}: {path}: {e}");
        std::process::exit(1)
    }
}
