//! What the model examples share: the network they assume and how they save their figures.

/// Latency of one message (s): an InfiniBand cluster, as the rigid model of BENCHMARKS.md.
pub const ALPHA: f64 = 2e-6;
/// Bandwidth (bytes/s).
pub const BETA: f64 = 5e9;

/// The command line's cases and its `--json FILE`, if given; exits 2 with a message naming
/// `program` when `--json` has no file.
pub fn arguments(program: &str) -> (Vec<String>, Option<String>) {
    let (mut cases, mut json) = (Vec::new(), None);
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--json" {
            json = Some(args.next().unwrap_or_else(|| {
                eprintln!("{program}: --json needs a file name");
                std::process::exit(2)
            }));
        } else {
            cases.push(arg);
        }
    }
    (cases, json)
}

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
