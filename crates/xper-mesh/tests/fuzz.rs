//! The MSH reader never panics on damaged files: random byte edits (changes, insertions,
//! deletions) and truncations of the valid ASCII and binary meshes of `tests/data`. A file
//! that still reads gives a mesh whose triangles name existing nodes.

use proptest::prelude::*;
use xper_mesh::parse_msh;

const FILES: [&[u8]; 2] = [
    include_bytes!("data/square_inclusion_ascii.msh"),
    include_bytes!("data/square_inclusion_binary.msh"),
];

/// `bytes` with each `(position, value, operation)` applied (0: change, 1: insert, 2: delete;
/// positions wrap around the current length), then cut to `keep` of its length.
fn damaged(bytes: &[u8], edits: &[(u32, u8, u8)], keep: f64) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for &(at, value, op) in edits {
        let at = at as usize % b.len().max(1);
        match op {
            0 if !b.is_empty() => b[at] = value,
            1 => b.insert(at, value),
            _ if !b.is_empty() => {
                b.remove(at);
            }
            _ => {}
        }
    }
    b.truncate((b.len() as f64 * keep).ceil() as usize);
    b
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn damaged_meshes_are_refused_or_read_whole(
        file in 0usize..2,
        edits in prop::collection::vec((any::<u32>(), any::<u8>(), 0u8..3), 1..6),
        keep in prop_oneof![Just(1.0), 0.0f64..1.0],
    ) {
        let bytes = damaged(FILES[file], &edits, keep);
        if let Ok(mesh) = parse_msh(&bytes, "fuzz.msh") {
            let n = mesh.nodes.len();
            for t in &mesh.triangles {
                prop_assert!(t.iter().all(|&v| (v as usize) < n), "triangle {t:?} of {n} nodes");
            }
        }
    }

    #[test]
    fn ascii_meshes_with_a_number_replaced_are_refused_or_read_whole(
        line in any::<u32>(),
        value in prop_oneof![
            Just("-1".to_string()),
            Just("0".to_string()),
            Just("4294967296".to_string()),
            Just("99999999999999999999".to_string()),
            Just("1e308".to_string()),
            Just("nan".to_string()),
            "[0-9]{1,12}",
        ],
    ) {
        let text = String::from_utf8_lossy(FILES[0]).into_owned();
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let k = line as usize % lines.len();
        let mut words: Vec<String> = lines[k].split(' ').map(str::to_string).collect();
        let w = (line as usize / lines.len()) % words.len();
        words[w] = value;
        lines[k] = words.join(" ");
        if let Ok(mesh) = parse_msh(lines.join("\n").as_bytes(), "fuzz.msh") {
            let n = mesh.nodes.len();
            for t in &mesh.triangles {
                prop_assert!(t.iter().all(|&v| (v as usize) < n), "triangle {t:?} of {n} nodes");
            }
        }
    }
}
