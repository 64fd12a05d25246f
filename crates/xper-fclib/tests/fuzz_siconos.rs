//! The Siconos `.dat` reader never panics on damaged files: tokens of the shared problem files
//! replaced by wrong numbers or garbage, lines deleted or repeated, files cut: each is read or
//! refused with an error, never a panic (nor an allocation abort: sizes are checked against
//! the file before anything is allocated).

mod common;

use common::shared_dir;
use proptest::prelude::*;
use std::path::Path;
use xper_fclib::{parse_siconos, SiconosKind};

/// Small shared files, local and global.
const FILES: [&str; 4] = [
    "siconos_dat_2d/FrictionContactProblem00031.dat",
    "siconos_dat_2d/FrictionContactProblem00394.dat",
    "siconos_dat_2d/FC2D_SliderCrankLagrangian00000.dat",
    "siconos_dat_2d/gfc2d_granularflowonwall_00069_00350.dat",
];

fn texts() -> Option<Vec<String>> {
    let dir = shared_dir()?;
    Some(
        FILES
            .iter()
            .map(|f| std::fs::read_to_string(dir.join(f)).unwrap())
            .collect(),
    )
}

#[derive(Clone, Debug)]
enum Edit {
    Replace(u32, String),
    DeleteLine(u32),
    RepeatLine(u32),
    Cut(u32),
}

fn edit() -> impl Strategy<Value = Edit> {
    let value = prop_oneof![
        Just("-1".to_string()),
        Just("0".to_string()),
        Just("3".to_string()),
        Just("4294967297".to_string()),
        Just("1e308".to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        "[0-9]{1,10}",
        "[a-z.+-]{1,4}",
    ];
    prop_oneof![
        (any::<u32>(), value).prop_map(|(at, v)| Edit::Replace(at, v)),
        any::<u32>().prop_map(Edit::DeleteLine),
        any::<u32>().prop_map(Edit::RepeatLine),
        any::<u32>().prop_map(Edit::Cut),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for e in edits {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match e {
            Edit::Replace(at, v) => {
                let k = *at as usize % n;
                let mut words: Vec<&str> = lines[k].split_whitespace().collect();
                if !words.is_empty() {
                    let w = (*at as usize / n) % words.len();
                    words[w] = v;
                }
                lines[k] = words.join(" ");
            }
            Edit::DeleteLine(at) => {
                lines.remove(*at as usize % n);
            }
            Edit::RepeatLine(at) => {
                let k = *at as usize % n;
                let line = lines[k].clone();
                lines.insert(k, line);
            }
            Edit::Cut(at) => lines.truncate(*at as usize % n),
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn damaged_siconos_files_are_read_or_refused_never_panic(
        file in 0usize..FILES.len(),
        edits in prop::collection::vec(edit(), 1..5),
        kind in prop_oneof![Just(SiconosKind::Auto), Just(SiconosKind::Local), Just(SiconosKind::Global)],
    ) {
        let Some(texts) = texts() else { return Ok(()) };
        let text = apply(&texts[file], &edits);
        let _ = parse_siconos(&text, Path::new("fuzz.dat"), kind);
    }
}
