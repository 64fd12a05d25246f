//! The distributed contact solve over MPI: `mpirun` on 1, 2 and 4 processes (oversubscribed
//! on a 2-core machine) agrees with the undivided solve on every rank, and a failure injected
//! on one rank ends the job with a non-zero code within seconds. Every mpirun is under
//! `timeout`, so a hang fails the test instead of the CI job.
#![cfg(feature = "mpi")]

use std::process::Command;
use std::time::{Duration, Instant};

fn mpirun(ranks: usize, extra: &[&str]) -> (Option<i32>, String, Duration) {
    let start = Instant::now();
    let output = Command::new("timeout")
        .args(["120", "mpirun", "-np", &ranks.to_string()])
        .arg(env!("CARGO_BIN_EXE_xper-domain-mpi-check"))
        .args(extra)
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .env("OMPI_MCA_rmaps_base_oversubscribe", "1")
        .env("OMPI_MCA_mpi_yield_when_idle", "1")
        .output()
        .expect("mpirun could not be started (is openmpi-bin installed?)");
    let text = String::from_utf8_lossy(&output.stdout).to_string()
        + &String::from_utf8_lossy(&output.stderr);
    (output.status.code(), text, start.elapsed())
}

#[test]
fn one_two_and_four_processes_agree_with_the_undivided_solve() {
    for ranks in [1, 2, 4] {
        let (code, text, _) = mpirun(ranks, &["--tolerance", "1e-5"]);
        assert_eq!(code, Some(0), "{ranks} processes:\n{text}");
        assert_eq!(
            text.matches(": ok").count(),
            ranks,
            "{ranks} processes:\n{text}"
        );
    }
}

#[test]
fn anderson_accelerated_solves_on_two_and_four_processes_agree_with_the_undivided_one() {
    for ranks in [2, 4] {
        let (code, text, _) = mpirun(ranks, &["--tolerance", "1e-5", "--anderson"]);
        assert_eq!(code, Some(0), "{ranks} processes:\n{text}");
        assert_eq!(
            text.matches(": ok").count(),
            ranks,
            "{ranks} processes:\n{text}"
        );
    }
}

/// The agglomerated pressure multigrid over MPI (4 processes, its strips re-cut into 2 and
/// gathered by ranks 0 and 2) gives the one-strip solve's bits on every rank.
#[test]
fn the_agglomerated_pressure_multigrid_over_mpi_gives_the_one_strip_bits() {
    let (code, text, _) = mpirun(4, &["--pressure"]);
    assert_eq!(code, Some(0), "{text}");
    assert_eq!(text.matches(": ok").count(), 4, "{text}");
    assert_eq!(text.matches("gathered grid 512 cells").count(), 2, "{text}");
}

#[test]
fn a_failure_on_one_rank_ends_the_job_promptly() {
    let (code, text, elapsed) = mpirun(2, &["--tolerance", "1e-5", "--fail-on-rank", "1"]);
    assert!(
        code.is_some_and(|c| c != 0 && c != 124),
        "exit {code:?} (124: killed by timeout):\n{text}"
    );
    assert!(text.contains("failure injected on rank 1"), "{text}");
    assert!(elapsed < Duration::from_secs(60), "took {elapsed:?}");
}
