//! `[solver] kind` (nlgs, newton, proximal_newton) and `[output] dump_problems`.

mod common;
use common::*;
use xper_scene::{Acceleration, ConvergenceNorm, SolverSettings, VelocitySolverKind};

const DISK: &str = r#"[[bodies]]
shape = "disk"
center = [0.0, 0.0]
radius = 0.01
material = "glass"
group = "grains"
"#;

fn scene(rest: &str) -> String {
    with_header(&format!("{rest}\n{DISK}"))
}

#[test]
fn solver_kinds_and_their_defaults() {
    let s = ok(&scene("")).solver;
    assert_eq!(s, SolverSettings::default());
    assert_eq!((s.kind, s.max_iterations), (VelocitySolverKind::Nlgs, 1000));
    let s = ok(&scene("[solver]\nkind = \"newton\"\ntolerance = 1e-9\n")).solver;
    assert_eq!(
        (s.kind, s.tolerance, s.max_iterations, s.norm),
        (
            VelocitySolverKind::Newton,
            1e-9,
            200,
            ConvergenceNorm::NaturalMap
        )
    );
    let s = ok(&scene(
        "[solver]\nmax_iterations = 7\nkind = \"proximal_newton\"\ncheck_every = 2\n",
    ))
    .solver;
    assert_eq!(
        (s.kind, s.max_iterations, s.check_every),
        (VelocitySolverKind::ProximalNewton, 7, 2)
    );
    let s = ok(&scene("[solver]\nkind = \"nlgs\"\nnorm = \"maxm\"\n")).solver;
    assert_eq!(
        (s.kind, s.norm),
        (VelocitySolverKind::Nlgs, ConvergenceNorm::Maxm)
    );
}

#[test]
fn solver_kind_errors() {
    let t = scene("[solver]\nkind = \"Newton\"\n");
    let e = expect_error(
        &t,
        "solver.kind",
        "kind = \"Newton\"",
        "unknown solver kind `Newton` (known: nlgs, newton, proximal_newton)",
    );
    assert_eq!(e.column, 8);
    assert_eq!(
        e.to_string(),
        format!(
            "test.toml:{}:8: solver.kind: unknown solver kind `Newton` (known: nlgs, newton, proximal_newton)",
            e.line
        )
    );
    let t = scene("[solver]\nkind = 3\n");
    expect_error(&t, "solver.kind", "kind = 3", "expected a string");
    let t = scene("[solver]\nkind = \"newton\"\nnorm = \"quad\"\n");
    expect_error(
        &t,
        "solver.norm",
        "norm =",
        "applies to kind = \"nlgs\" only",
    );
}

#[test]
fn anderson_acceleration_and_its_parameters() {
    assert_eq!(ok(&scene("")).solver.acceleration, Acceleration::None);
    let s = ok(&scene("[solver]\nacceleration = \"anderson\"\n")).solver;
    assert_eq!(
        s.acceleration,
        Acceleration::Anderson {
            depth: 3,
            period: 3
        }
    );
    let s = ok(&scene(
        "[solver]\nacceleration = \"anderson\"\nanderson_depth = 5\nanderson_period = 1\n",
    ))
    .solver;
    assert_eq!(
        s.acceleration,
        Acceleration::Anderson {
            depth: 5,
            period: 1
        }
    );
    let s = ok(&scene("[solver]\nacceleration = \"none\"\n")).solver;
    assert_eq!(s.acceleration, Acceleration::None);
    let t = scene("[solver]\nacceleration = \"andersen\"\n");
    expect_error(
        &t,
        "solver.acceleration",
        "acceleration =",
        "unknown acceleration `andersen` (known: none, anderson)",
    );
    let t = scene("[solver]\nacceleration = \"anderson\"\nanderson_depth = 9\n");
    expect_error(
        &t,
        "solver.anderson_depth",
        "anderson_depth",
        "must be in [1, 8], got 9",
    );
    let t = scene("[solver]\nacceleration = \"anderson\"\nanderson_period = 0\n");
    expect_error(
        &t,
        "solver.anderson_period",
        "anderson_period",
        "must be in [1, 4294967295], got 0",
    );
    let t = scene("[solver]\nanderson_depth = 2\n");
    expect_error(
        &t,
        "solver.anderson_depth",
        "anderson_depth",
        "needs acceleration = \"anderson\"",
    );
    let t = scene("[solver]\nkind = \"newton\"\nacceleration = \"anderson\"\n");
    expect_error(
        &t,
        "solver.acceleration",
        "acceleration =",
        "applies to kind = \"nlgs\" only",
    );
    let t = scene("[solver]\nkind = \"newton\"\nanderson_depth = 2\n");
    expect_error(
        &t,
        "solver.anderson_depth",
        "anderson_depth",
        "applies to kind = \"nlgs\" only",
    );
    // A misspelt acceleration is one error, not also one per parameter.
    let t = scene("[solver]\nacceleration = \"andersen\"\nanderson_depth = 2\n");
    let e = errs(&t);
    assert_eq!(e.0.len(), 1, "{e}");
}

#[test]
fn dump_problems_are_validated_step_numbers() {
    let t = with_header(&format!("[output]\ndump_problems = [7, 1, 10]\n\n{DISK}"));
    assert_eq!(ok(&t).output.dump_problems, vec![1, 7, 10]);
    assert!(ok(&scene("")).output.dump_problems.is_empty());
    assert!(ok(&with_header(&format!(
        "[output]\ndump_problems = []\n{DISK}"
    )))
    .output
    .dump_problems
    .is_empty());
    let bad = |list: &str, field: &str, needle: &str| {
        let t = with_header(&format!(
            "[output]\ndump_problems = {list} # here\n\n{DISK}"
        ));
        expect_error(&t, field, "# here", needle);
    };
    bad("[0]", "output.dump_problems[0]", "must be >= 1, got 0");
    bad("[3, -2]", "output.dump_problems[1]", "must be >= 1, got -2");
    bad(
        "[11]",
        "output.dump_problems[0]",
        "step 11 is after the last step of the run (10)",
    );
    bad(
        "[2, 5, 2]",
        "output.dump_problems[2]",
        "step 2 is listed twice",
    );
    bad(
        "[1.5]",
        "output.dump_problems[0]",
        "expected a step number (integer >= 1), found",
    );
    bad(
        "[\"3\"]",
        "output.dump_problems[0]",
        "expected a step number",
    );
    bad(
        "5",
        "output.dump_problems",
        "expected an array of step numbers",
    );
    // Every bad entry is reported, not only the first.
    let t = with_header(&format!("[output]\ndump_problems = [0, 99]\n\n{DISK}"));
    let e = errs(&t);
    assert!(e.has_field("output.dump_problems[0]") && e.has_field("output.dump_problems[1]"));
}
