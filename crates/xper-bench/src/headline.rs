//! The figures BENCHMARKS.md opens with: one row per benchmark figure, xper's measurement
//! beside the other code's (or the target's) as `../shared/bench/` and the issues give them.
//! Every benchmark kind contributes its rows from its saved JSON results, so the table is
//! regenerated with the rest of the report.

use crate::fluid::FluidBench;
use crate::fracture::FractureBenchResult;
use crate::solvers::SolverBench;
use crate::BenchResult;

/// One headline figure: what is measured, xper's value and what it is compared with.
#[derive(Clone, Debug, PartialEq)]
pub struct Headline {
    /// Benchmark scene or suite.
    pub benchmark: String,
    /// What is measured, with its unit.
    pub figure: String,
    /// xper's value, as printed.
    pub xper: String,
    /// The other code's value or the target, with its source.
    pub reference: String,
    /// Whether xper's value is at least as good as the reference (`None`: not comparable).
    pub better: Option<bool>,
}

impl Headline {
    pub(crate) fn new(benchmark: &str, figure: &str, xper: String, reference: &str) -> Self {
        Headline {
            benchmark: benchmark.into(),
            figure: figure.into(),
            xper,
            reference: reference.into(),
            better: None,
        }
    }

    /// Marks the row by comparing `xper` with `reference`, smaller being better.
    pub(crate) fn smaller(mut self, xper: f64, reference: f64) -> Self {
        self.better = Some(xper <= reference);
        self
    }
}

/// LMGC90 2025.rc1 on box10k (`../shared/bench/box10k.md`; the sweep figures from the run of
/// issue 39, same tolerance, checks every 10 sweeps, at most 1000).
const LMGC90_BOX10K: [(&str, f64); 6] = [
    ("step over the run (ms)", 99.0),
    ("step once settled (ms)", 79.0),
    ("peak memory (MB)", 260.0),
    ("overlap p99 at rest (um)", 0.43),
    ("sweeps per step, median", 95.0),
    ("steps ending at the sweep cap", 40.0),
];

/// Rows of the rigid scenes: box10k (plain and Anderson) against LMGC90.
pub fn rigid(results: &[BenchResult]) -> Vec<Headline> {
    let mut rows = Vec::new();
    for r in results.iter().filter(|r| r.scene.starts_with("box10k")) {
        let xper = [
            r.median_step_ms,
            r.median_settled_step_ms,
            r.peak_memory_bytes as f64 / 1e6,
            r.overlap_p99_m * 1e6,
            r.median_sweeps,
            r.non_converged_steps as f64,
        ];
        for ((figure, lmgc), x) in LMGC90_BOX10K.iter().zip(xper) {
            let reference = format!("{lmgc} (LMGC90 2025.rc1)");
            rows.push(
                Headline::new(&r.scene, figure, format!("{x:.3}"), &reference).smaller(x, *lmgc),
            );
        }
    }
    for r in results.iter().filter(|r| !r.scene.starts_with("box10k")) {
        rows.push(Headline::new(
            &r.scene,
            "step once settled (ms), bodies",
            format!("{:.1}, {}", r.median_settled_step_ms, r.bodies),
            "none published",
        ));
    }
    rows
}

/// Akantu 5.0.7 on notched tension (`../shared/bench/notched-tension.md`): wall time with
/// cohesive elements everywhere (s), and the goal on the dissipation ratio.
const AKANTU_WALL_S: f64 = 121.0;
const DISSIPATION_GOAL: f64 = 1.1;

/// Rows of the fracture scenes: notched tension against Akantu and the goals of its spec.
pub fn fracture(results: &[FractureBenchResult]) -> Vec<Headline> {
    let mut rows = Vec::new();
    for r in results.iter().filter(|r| r.scene == "notched_tension") {
        rows.push(
            Headline::new(
                &r.scene,
                "wall time (s)",
                format!("{:.1}", r.wall_time_s),
                "121 (Akantu 5.0.7, cohesive everywhere); goal <= 60.5",
            )
            .smaller(r.wall_time_s, 0.5 * AKANTU_WALL_S),
        );
        if let Some(ratio) = r.dissipation_ratio {
            rows.push(
                Headline::new(
                    &r.scene,
                    "dissipated / (w x ligament)",
                    format!("{ratio:.3}"),
                    "1.18 to 1.40 (Akantu 5.0.7); goal < 1.1",
                )
                .smaller(ratio, DISSIPATION_GOAL),
            );
        }
    }
    rows
}

/// Rows of the contact-problem suite: problems solved, and speed where a time is published.
pub fn solvers(bench: &SolverBench) -> Vec<Headline> {
    let mut problems: Vec<&str> = bench.rows.iter().map(|r| r.problem.as_str()).collect();
    problems.dedup();
    let solved = (problems.iter())
        .filter(|p| bench.rows.iter().any(|r| r.problem == **p && r.converged))
        .count();
    let mut rows = vec![Headline::new(
        "contact-problem suite",
        "problems solved to tolerance",
        format!("{solved} of {}", problems.len()),
        "all (target)",
    )];
    rows[0].better = Some(solved == problems.len());
    for p in problems {
        let of = |r: &&crate::solvers::SolverBenchRow| r.problem == p && r.converged;
        let fastest = (bench.rows.iter().filter(of)).min_by(|a, b| a.time_s.total_cmp(&b.time_s));
        if let Some(f) = fastest.filter(|f| f.published_fastest_s.is_some()) {
            let published = f.published_fastest_s.unwrap_or(f64::NAN);
            rows.push(
                Headline::new(
                    p,
                    "fastest solve (s)",
                    format!("{:.4} ({})", f.time_s, f.solver),
                    &format!("{published} (Acary, Bremond, Huber 2018, their machine)"),
                )
                .smaller(f.time_s, published),
            );
        }
    }
    rows
}

/// Rows of the fluid: the multigrid and the whole step against the targets of issue 5.
pub fn fluid(bench: &FluidBench) -> Vec<Headline> {
    let mut rows = Vec::new();
    let smoother = (bench.multigrid.iter())
        .map(|(_, f)| f.smoother_cells_per_second)
        .fold(f64::INFINITY, f64::min);
    let work = (bench.multigrid.iter())
        .map(|(_, f)| f.work_units_per_decade)
        .fold(0.0, f64::max);
    if !bench.multigrid.is_empty() {
        rows.push(
            Headline::new(
                "pressure multigrid",
                "smoother, slowest grid (cells/s)",
                format!("{smoother:.2e}"),
                ">= 3e8 (target)",
            )
            .smaller(-smoother, -3e8),
        );
        rows.push(
            Headline::new(
                "pressure multigrid",
                "work units per decade, largest",
                format!("{work:.2}"),
                "<= 6 (target)",
            )
            .smaller(work, 6.0),
        );
    }
    if let Some(slowest) =
        (bench.steps.iter()).min_by(|a, b| a.cells_per_second.total_cmp(&b.cells_per_second))
    {
        rows.push(
            Headline::new(
                "fluid step",
                "cells per second, slowest case",
                format!("{:.2e}", slowest.cells_per_second),
                ">= 1e7 (target)",
            )
            .smaller(-slowest.cells_per_second, -1e7),
        );
    }
    rows
}

/// Rows of scene reading: the largest file of each layout against issue 38's "a 50 MB scene
/// is checked in seconds" (read as at most 10 s), and linear growth.
pub fn reading(bench: &crate::reading::ReadingBench) -> Vec<Headline> {
    let mut rows = Vec::new();
    if let Some(largest) = (bench.files.iter()).max_by_key(|f| f.bytes) {
        rows.push(
            Headline::new(
                "reading scenes",
                &format!("check of a {:.0} MB scene (s)", largest.bytes as f64 / 1e6),
                format!("{:.1}", largest.seconds),
                "<= 10 s (target: \"in seconds\")",
            )
            .smaller(largest.seconds, 10.0),
        );
    }
    let worst = (bench.files.iter())
        .filter_map(|f| crate::reading::growth(bench, &f.layout))
        .fold(None, |w: Option<f64>, g| Some(w.map_or(g, |w| w.max(g))));
    if let Some(worst) = worst {
        rows.push(
            Headline::new(
                "reading scenes",
                "time per MB, largest over second size, worst layout",
                format!("{worst:.2}"),
                "<= 2 (1 linear, 10 quadratic)",
            )
            .smaller(worst, 2.0),
        );
    }
    rows
}

/// The Markdown table of `rows`.
pub fn markdown(rows: &[Headline]) -> String {
    let mut md = String::from(
        "## At a glance\n\nxper's figures beside the other codes' (or the targets), from the results below.\n\n\
         | benchmark | figure | xper | reference | xper at least as good |\n|---|---|---|---|---|\n",
    );
    for r in rows {
        let verdict = match r.better {
            Some(true) => "yes",
            Some(false) => "no",
            None => "-",
        };
        md.push_str(&format!(
            "| {} | {} | {} | {} | {verdict} |\n",
            r.benchmark, r.figure, r.xper, r.reference
        ));
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_is_better_only_when_it_does_not_exceed_the_reference() {
        let row = |x| Headline::new("b", "f", String::new(), "r").smaller(x, 2.0);
        assert_eq!(row(1.0).better, Some(true));
        assert_eq!(row(2.0).better, Some(true));
        assert_eq!(row(3.0).better, Some(false));
        assert_eq!(row(f64::NAN).better, Some(false));
    }

    #[test]
    fn the_table_has_one_line_per_row_and_says_when_no_comparison_exists() {
        let rows = [
            Headline::new("a", "f", "1".into(), "2").smaller(1.0, 2.0),
            Headline::new("b", "g", "1".into(), "none"),
        ];
        let md = markdown(&rows);
        assert!(md.contains("| a | f | 1 | 2 | yes |"));
        assert!(md.contains("| b | g | 1 | none | - |"));
        assert_eq!(
            md.lines()
                .filter(|l| l.starts_with("| a |") || l.starts_with("| b |"))
                .count(),
            2
        );
    }
}
