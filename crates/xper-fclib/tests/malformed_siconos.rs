//! Malformed Siconos `.dat` files: truncated copies of the shared files, garbage, wrong
//! sizes, out-of-range indices. Each must give an error naming the file, the position
//! (line and token) and the reason; none may panic or be accepted.

mod common;

use common::{shared_dir, TempDir};
use std::path::Path;
use xper_fclib::{
    parse_siconos, read_problem, read_siconos, Position, Problem, ReadError, ReadErrorKind,
    SiconosKind,
};

fn parse(text: &str, kind: SiconosKind) -> Result<Problem, ReadError> {
    parse_siconos(text, Path::new("test.dat"), kind)
}

/// The error of `text`, which must be at a token on `line`, of `kind`, with `words` in
/// its reason.
fn fails(
    text: &str,
    kind: SiconosKind,
    line: usize,
    err_kind: ReadErrorKind,
    words: &str,
) -> ReadError {
    let e = parse(text, kind).expect_err(text);
    assert_eq!(e.kind, err_kind, "{e}");
    match e.position {
        Position::Token { line: l, .. } => assert_eq!(l, line, "{e}"),
        ref p => panic!("{e}: position {p:?}"),
    }
    assert!(e.reason.contains(words), "'{words}' not in: {e}");
    assert!(e.to_string().starts_with("test.dat: line "), "{e}");
    e
}

/// A 2D local problem with one contact, W dense.
const LOCAL_DENSE: &str = "2\n1\n0\n2\n2\n2\t2\n4 1 1 3\n-1 0.5\n0.3\n";

#[test]
fn minimal_files_read_as_written() {
    let Problem::Local(p) = parse(LOCAL_DENSE, SiconosKind::Auto).unwrap() else {
        panic!("not local")
    };
    assert_eq!(
        (p.w.get(0, 0), p.w.get(1, 0), p.w.get(0, 1), p.w.get(1, 1)),
        (4.0, 1.0, 1.0, 3.0)
    );
    assert_eq!((p.q, p.mu), (vec![-1.0, 0.5], vec![0.3]));
    // Older Siconos files end with one integer: accepted.
    assert!(parse(&format!("{LOCAL_DENSE}1\n"), SiconosKind::Auto).is_ok());
    // A global problem whose M happens to be d nc x d nc: told apart by H's header.
    let global = "2 1  0 2 2 2 2 2 0 0 2  0 2 2 2 2 1 0 0 1  1 1  0 0  0.3";
    let Problem::Global(g) = parse(global, SiconosKind::Auto).unwrap() else {
        panic!("not global")
    };
    assert_eq!(
        (g.m.get(0, 0), g.f.clone(), g.w.clone()),
        (2.0, vec![1.0, 1.0], vec![0.0, 0.0])
    );
    assert_eq!(g.to_local().unwrap().q, vec![0.5, 0.5]);
    // Read as local it has data left over.
    fails(
        global,
        SiconosKind::Local,
        1,
        ReadErrorKind::Format,
        "unexpected data",
    );
    // CSparse triplet and CSC, and a sparse-block matrix, all giving the same W.
    let csc = "2 1 2 2 2 2\nCSparse Version 3.1.9, May 4, 2016.  Copyright (c) T. A. Davis\n\
               2-by-2, nzmax: 4 nnz: 4, 1-norm: 5\n    col 0 : locations 0 to 1\n      0 : 4\n      1 : 1\n\
               \x20   col 1 : locations 2 to 3\n      0 : 1\n      1 : 3\n-1 0.5\n0.3\n";
    let triplet = "2 1 2 2 2 1\nCSparse Version 3.1.9\ntriplet: 2-by-2, nzmax: 4 nnz: 4\n\
                   0 0 : 4\n 1 1 : 3\n 0 1 : 1\n 1 0 : 1\n-1 0.5\n0.3\n";
    let sbm = "2 1 1 2 2  1 1 1  2 2  2 1  0 1  0  0 4 1 1 3  -1 0.5 0.3";
    let reference = parse(LOCAL_DENSE, SiconosKind::Auto).unwrap();
    for text in [csc, triplet, sbm] {
        assert_eq!(parse(text, SiconosKind::Auto).unwrap(), reference, "{text}");
    }
}

#[test]
fn truncated_copies_of_the_shared_files_are_errors_at_the_end() {
    let Some(shared) = shared_dir() else { return };
    let tmp = TempDir::new("truncated");
    let sources = [
        "FC2D_SliderCrankLagrangian00000.dat",      // dense
        "FrictionContactProblem00031.dat",          // sparse-block
        "fc2d_granularflowonwall_00667_00000.dat",  // CSparse CSC
        "gfc2d_granularflowonwall_00069_00350.dat", // global: triplet M, CSC H
    ];
    let mut checked = 0;
    for name in sources {
        let bytes = std::fs::read(shared.join("siconos_dat_2d").join(name)).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        let full_tokens = text.split_ascii_whitespace().count();
        // Cut anywhere before the line of mu (cutting inside its last number could leave
        // a shorter but valid number).
        let mu_line = text.trim_end().rfind('\n').unwrap();
        for frac in [0.0, 0.001, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999] {
            let cut = (mu_line as f64 * frac) as usize;
            let path = tmp.path(&format!("cut-{cut}-{name}"));
            std::fs::write(&path, &bytes[..cut]).unwrap();
            let e = read_siconos(&path).expect_err(&format!("{name} cut at {cut} accepted"));
            assert_eq!(e.path, path);
            assert_eq!(e.kind, ReadErrorKind::Format, "{e}");
            let Position::Token { index, line } = e.position else {
                panic!("{e}")
            };
            let kept = text[..cut].split_ascii_whitespace().count();
            assert!(
                index <= kept + 1 && index < full_tokens,
                "{e}: {kept} tokens kept"
            );
            assert!(
                line >= 1 && line <= text[..cut].lines().count().max(1),
                "{e}"
            );
            assert!(
                e.to_string()
                    .contains(&format!("cut-{cut}-{name}: line {line}")),
                "{e}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 32);
}

#[test]
fn garbage_is_rejected_with_a_reason() {
    let tmp = TempDir::new("garbage");
    let bin = tmp.path("binary.dat");
    std::fs::write(&bin, [0x89u8, b'H', b'D', b'F', 0xff, 0xfe, 0]).unwrap();
    let e = read_siconos(&bin).unwrap_err();
    assert_eq!(
        (e.kind, &e.position),
        (ReadErrorKind::Format, &Position::File)
    );
    assert!(e.reason.contains("not a text file"), "{e}");
    let e = read_problem(tmp.path("missing.dat")).unwrap_err();
    assert_eq!(e.kind, ReadErrorKind::Io, "{e}");
    fails(
        "",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Format,
        "ends early",
    );
    fails(
        "hello world",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Format,
        "expected an integer (dimension d)",
    );
    fails(
        "2\n1\n0\n2\n2\n2 2\n4 x 1 3\n-1 0.5\n0.3\n",
        SiconosKind::Auto,
        7,
        ReadErrorKind::Format,
        "\"x\"",
    );
    fails(
        &format!("{LOCAL_DENSE}1 2\n"),
        SiconosKind::Auto,
        10,
        ReadErrorKind::Format,
        "unexpected data",
    );
    fails(
        &format!("{LOCAL_DENSE}end\n"),
        SiconosKind::Auto,
        10,
        ReadErrorKind::Format,
        "\"end\"",
    );
}

#[test]
fn wrong_sizes_are_rejected() {
    fails(
        "4 1 0 2 2",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Invalid,
        "not 2 or 3",
    );
    // Huge counts are refused before any allocation.
    fails(
        "2 99999999999 0 2 2",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Format,
        "outside 0..=",
    );
    fails(
        "2 1 0 2 99999999999",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Format,
        "outside 0..=",
    );
    // Dense size line disagreeing with the header.
    fails(
        "2\n1\n0\n2\n2\n2\t3\n4 1 1 3\n",
        SiconosKind::Auto,
        6,
        ReadErrorKind::Format,
        "dense column count",
    );
    // Non-square first matrix.
    fails(
        "2 1 0 2 1 2 1 4 1  -1 0.5 0.3",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Invalid,
        "square",
    );
    // W of 2 x 2 for 2 contacts: as local, a size error; by content, read as global.
    let text = "2\n2\n0\n2\n2\n2 2\n4 1 1 3\n-1 0.5\n0.3\n";
    fails(
        text,
        SiconosKind::Local,
        4,
        ReadErrorKind::Invalid,
        "need 4 x 4",
    );
    let e = fails(
        text,
        SiconosKind::Auto,
        8,
        ReadErrorKind::Format,
        "storage code of H",
    );
    assert!(
        e.reason
            .contains("read as global: the first matrix is 2 x 2 while d nc = 4"),
        "{e}"
    );
    // q too short.
    fails(
        "2 1 0 2 2 2 2 4 1 1 3 -1",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Format,
        "q needs 2 values",
    );
    // H of the wrong size in a global file.
    let global = "2 1  0 2 2 2 2 2 0 0 2  0 2 1 2 1 1 0  1 1  0 0  0.3";
    fails(
        global,
        SiconosKind::Global,
        1,
        ReadErrorKind::Invalid,
        "H is 2 x 1",
    );
}

#[test]
fn bad_values_are_rejected_at_their_token() {
    fails(
        "2 1 0 2 2 2 2 4 1 1 3\n-1 0.5\n-0.3\n",
        SiconosKind::Auto,
        3,
        ReadErrorKind::Invalid,
        "mu[0] = -0.3",
    );
    fails(
        "2 1 0 2 2 2 2 4 1 1 3\n-1 0.5\nnan\n",
        SiconosKind::Auto,
        3,
        ReadErrorKind::Invalid,
        "mu[0] = NaN",
    );
    fails(
        "2 1 0 2 2 2 2 4 1 1 3\n-1 inf\n0.3\n",
        SiconosKind::Auto,
        2,
        ReadErrorKind::Invalid,
        "q[1] = inf",
    );
    fails(
        "2 1 0 2 2 2 2 4 NaN 1 3\n-1 0\n0.3\n",
        SiconosKind::Auto,
        1,
        ReadErrorKind::Invalid,
        "not finite",
    );
}

#[test]
fn sparse_block_structure_is_checked() {
    // Valid: "2 1 1 2 2  1 1 1  2 2  2 1  0 1  0  0 4 1 1 3  -1 0.5 0.3".
    let bad = [
        (
            "2 1 1 2 2  1 1 1  3 2  2 1  0 1  0  0 4 1 1 3  -1 0.5 0.3",
            "block-row sizes",
        ),
        (
            "2 1 1 2 2  1 1 1  2 2  2 1  0 2  0  0 4 1 1 3  -1 0.5 0.3",
            "block-row pointer 1",
        ),
        (
            "2 1 1 2 2  1 1 1  2 2  2 1  0 1  1  0 4 1 1 3  -1 0.5 0.3",
            "block-column index 0",
        ),
        (
            "2 1 1 2 2  1 1 1  2 2  2 1  0 1  0  5 4 1 1 3  -1 0.5 0.3",
            "numbered 5",
        ),
        (
            "2 1 1 2 2  1 1 1  2 2  2 2  0 1  0  0 4 1 1 3  -1 0.5 0.3",
            "block columns for 1 blocks",
        ),
        (
            "2 1 1 2 2  1 1 1  2 2  2 1  1 1  0  0 4 1 1 3  -1 0.5 0.3",
            "must start at 0",
        ),
    ];
    for (text, words) in bad {
        fails(text, SiconosKind::Local, 1, ReadErrorKind::Format, words);
    }
}

#[test]
fn csparse_indices_and_counts_are_checked() {
    let head = "2 1 2 2 2 2\nCSparse Version 3.1.9\n2-by-2, nzmax: 4 nnz: 4, 1-norm: 5\n";
    let tail = "-1 0.5\n0.3\n";
    let col1 = "col 1 : locations 2 to 3\n 0 : 1\n 1 : 3\n";
    let cases = [
        (format!("{head}col 0 : locations 0 to 1\n 0 : 4\n 2 : 1\n{col1}{tail}"), 6, "row index in column 0"),
        (format!("{head}col 1 : locations 0 to 1\n 0 : 4\n 1 : 1\n{col1}{tail}"), 4, "column 1 of W or M where 0"),
        (format!("{head}col 0 : locations 1 to 1\n 0 : 4\n{col1}{tail}"), 4, "starts at 1, not 0"),
        (format!("{head}col 0 : locations 0 to 7\n 0 : 4\n 1 : 1\n{col1}{tail}"), 4, "ends at 7"),
        (format!("{head}col 0 : locations 0 to 1\n 0 : 4\n 1 : 1\ncol 1 : locations 2 to 2\n 0 : 1\n{tail}"), 9, "3 entries but announced 4"),
        (head.replace("2-by-2", "3-by-2") + tail, 3, "3 x 2 here but 2 x 2"),
        (head.replace("2 1 2 2 2 2", "2 1 2 2 2 3"), 1, "sparse origin of W or M is 3"),
        (head.replace("CSparse Version 3.1.9", "(null)"), 2, "CSparse Version"),
        (head.replace("2 1 2 2 2 2", "2 1 2 2 2 1"), 3, "does not match its layout"),
    ];
    for (text, line, words) in &cases {
        let kind = if words.contains("origin") {
            ReadErrorKind::Unsupported
        } else {
            ReadErrorKind::Format
        };
        fails(text, SiconosKind::Local, *line, kind, words);
    }
    let triplet = "2 1 2 2 2 1\nCSparse Version 3.1.9\ntriplet: 2-by-2, nzmax: 4 nnz: 2\n0 0 : 4\n1 2 : 3\n-1 0.5\n0.3\n";
    fails(
        triplet,
        SiconosKind::Local,
        5,
        ReadErrorKind::Format,
        "column of entry 1",
    );
}
