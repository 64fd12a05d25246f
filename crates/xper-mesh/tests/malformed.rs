//! Bad files give an error naming the file and the reason, never a panic.

use std::path::{Path, PathBuf};

use xper_mesh::{parse_msh, read_msh, MeshError, MeshErrorKind};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Reads `name` from `tests/data`, expects an error of `kind` whose message names the file
/// and contains `words`; returns it.
fn rejected(name: &str, kind: MeshErrorKind, words: &str) -> MeshError {
    let path = data(name);
    let err = read_msh(&path).expect_err(name);
    let text = err.to_string();
    assert_eq!(err.kind, kind, "{text}");
    assert!(text.starts_with(&path.display().to_string()), "{text}");
    assert!(text.contains(words), "`{text}` lacks `{words}`");
    err
}

/// Writes `bytes` to a fresh temporary file and parses it through `read_msh`.
fn read_bytes(tag: &str, bytes: &[u8]) -> (PathBuf, Result<xper_mesh::Mesh, MeshError>) {
    let path = std::env::temp_dir().join(format!("xper-mesh-{}-{tag}.msh", std::process::id()));
    std::fs::write(&path, bytes).unwrap();
    let result = read_msh(&path);
    std::fs::remove_file(&path).unwrap();
    (path, result)
}

#[test]
fn version_2_2_asks_for_a_conversion() {
    let err = rejected("v22.msh", MeshErrorKind::Unsupported, "gmsh -format msh41");
    assert!(err.reason.contains("2.2"), "{err}");
    assert_eq!(err.place.as_deref(), Some("line 2 ($MeshFormat)"));
}

#[test]
fn quadrangles_are_refused() {
    let err = rejected(
        "quads.msh",
        MeshErrorKind::Unsupported,
        "only 3-node triangles are supported",
    );
    assert!(err.place.unwrap().contains("element"));
}

#[test]
fn second_order_triangles_are_refused() {
    rejected(
        "second_order.msh",
        MeshErrorKind::Unsupported,
        "only 3-node triangles are supported",
    );
}

#[test]
fn non_planar_nodes_are_refused() {
    let err = rejected("nonplanar.msh", MeshErrorKind::Unsupported, "z = 1");
    assert!(err.place.unwrap().contains("node"));
}

#[test]
fn a_line_off_the_triangles_is_refused() {
    rejected(
        "stray_line.msh",
        MeshErrorKind::Invalid,
        "not a node of any triangle",
    );
}

#[test]
fn missing_and_empty_files() {
    let err = read_msh(Path::new("/nonexistent/dir/none.msh")).unwrap_err();
    assert_eq!(err.kind, MeshErrorKind::Io);
    assert!(err
        .to_string()
        .starts_with("/nonexistent/dir/none.msh: cannot read"));

    let (path, result) = read_bytes("empty", b"");
    let err = result.unwrap_err();
    assert_eq!(err.kind, MeshErrorKind::Format);
    assert_eq!(
        err.to_string(),
        format!(
            "{}: empty file (a Gmsh MSH file starts with $MeshFormat)",
            path.display()
        )
    );

    let (_, result) = read_bytes("text", b"hello\nworld\n");
    assert!(result
        .unwrap_err()
        .reason
        .contains("does not start with $MeshFormat"));
}

#[test]
fn a_file_without_triangles_is_refused() {
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    let (_, result) = read_bytes("header-only", text.as_bytes());
    assert!(result.unwrap_err().reason.contains("no triangles"));
}

#[test]
fn bad_headers_are_refused_before_parsing() {
    for (header, words) in [
        ("4.1 2 8", "file-type must be 0"),
        ("4.1 0 3", "data-size must be 4 or 8"),
        ("4.0 0 8", "version 4.0 is not supported"),
        ("4.1", "expected `version file-type data-size`"),
    ] {
        let text = format!("$MeshFormat\n{header}\n$EndMeshFormat\n");
        let err = parse_msh(text.as_bytes(), "memory").unwrap_err();
        assert!(err.to_string().starts_with("memory: line 2"), "{err}");
        assert!(err.reason.contains(words), "{err}");
    }
}

#[test]
fn truncated_files_name_the_place() {
    let bytes = std::fs::read(data("square_inclusion_ascii.msh")).unwrap();
    let (path, result) = read_bytes("half", &bytes[..bytes.len() / 2]);
    let err = result.unwrap_err();
    assert_eq!(err.kind, MeshErrorKind::Format, "{err}");
    assert!(err.to_string().starts_with(&path.display().to_string()));
    assert!(
        err.place.as_deref().unwrap_or("").starts_with("line "),
        "{err}"
    );
}

#[test]
fn corrupt_node_line_is_located() {
    let text = std::fs::read_to_string(data("square_inclusion_ascii.msh")).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    let at = lines.iter().position(|l| *l == "$Nodes").unwrap() + 4;
    lines[at] = "0 zero 0";
    let err = parse_msh(lines.join("\n").as_bytes(), "corrupt.msh").unwrap_err();
    assert_eq!(err.kind, MeshErrorKind::Format);
    assert!(err.to_string().starts_with("corrupt.msh: line"), "{err}");
    assert!(err.reason.contains("node"), "{err}");
}

#[test]
fn truncation_at_twenty_offsets_never_panics() {
    for name in ["square_inclusion_ascii.msh", "square_inclusion_binary.msh"] {
        let bytes = std::fs::read(data(name)).unwrap();
        let mut errors = 0;
        for k in 0..20 {
            let cut = bytes.len() * k / 20 + k * 7;
            match parse_msh(&bytes[..cut.min(bytes.len())], name) {
                Ok(mesh) => mesh.validate().unwrap(),
                Err(e) => {
                    assert!(e.to_string().starts_with(name), "{e}");
                    errors += 1;
                }
            }
        }
        assert!(errors >= 19, "{name}: only {errors} truncations rejected");
    }
}

#[test]
fn content_that_trips_the_parser_is_an_error() {
    // An empty $Nodes section: mshio computes `num_nodes - 1`, which overflows.
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 1 1\n$EndNodes\n";
    let err = parse_msh(text.as_bytes(), "zero.msh").unwrap_err();
    assert_eq!(err.kind, MeshErrorKind::Format);
    assert!(err.to_string().starts_with("zero.msh: "), "{err}");
}

#[test]
fn header_counts_that_disagree_with_the_blocks_are_refused() {
    let good = std::fs::read_to_string(data("square_inclusion_ascii.msh")).unwrap();
    for (from, to, words) in [
        (
            "\n18 152 1 152\n",
            "\n18 151 1 152\n",
            "the header says 151 nodes, the blocks hold 152",
        ),
        (
            "\n11 313 1 313\n",
            "\n11 300 1 313\n",
            "the header says 300 elements, the blocks hold 313",
        ),
    ] {
        assert!(good.contains(from));
        let (path, result) = read_bytes("counts", good.replacen(from, to, 1).as_bytes());
        let text = result.expect_err(to).to_string();
        assert!(text.starts_with(&path.display().to_string()), "{text}");
        assert!(text.contains(words), "`{text}` lacks `{words}`");
    }
}
