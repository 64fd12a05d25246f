//! The document builder against an independent TOML reader (the `toml` crate, built on
//! `toml_edit`): the same values for every shipped scene and for generated documents, the
//! same refusals, the same tree however the text is cut into runs, and no panic on damaged text.

use super::*;
use proptest::prelude::*;

fn value_of(node: &Node) -> toml::Value {
    match &node.kind {
        Kind::Str(s) => toml::Value::String(s.clone()),
        Kind::Int(i) => toml::Value::Integer(*i),
        Kind::Float(f) => toml::Value::Float(*f),
        Kind::Bool(b) => toml::Value::Boolean(*b),
        Kind::Datetime(d) => toml::Value::Datetime(d.parse().expect("a valid date-time")),
        Kind::Array(items) => toml::Value::Array(items.iter().map(value_of).collect()),
        Kind::Table(entries) => toml::Value::Table(
            (entries.iter())
                .map(|e| (e.key.clone(), value_of(&e.value)))
                .collect(),
        ),
    }
}

/// Equality with NaN equal to itself (`nan` is a TOML float).
fn same(a: &toml::Value, b: &toml::Value) -> bool {
    use toml::Value as V;
    match (a, b) {
        (V::Float(x), V::Float(y)) => x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()),
        (V::Array(x), V::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(x, y)| same(x, y))
        }
        (V::Table(x), V::Table(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

fn ours(text: &str) -> Result<toml::Value, SyntaxError> {
    let idx = LineIndex::new(text);
    parse(text, &idx).map(|n| value_of(&n))
}

fn reference(text: &str) -> Option<toml::Value> {
    text.parse::<toml::Table>().ok().map(toml::Value::Table)
}

fn scene_files() -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut files: Vec<_> = std::fs::read_dir(&root)
        .expect("the scenes folder")
        .filter_map(|e| e.ok().map(|e| e.path().join("scene.toml")))
        .filter(|p| p.exists())
        .collect();
    files.sort();
    files
}

#[test]
fn every_shipped_scene_reads_as_the_toml_crate_reads_it() {
    let files = scene_files();
    assert!(files.len() >= 10, "found only {} scenes", files.len());
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let expected = reference(&text).expect("shipped scenes are valid TOML");
        let got = ours(&text).unwrap_or_else(|e| panic!("{}: {e:?}", file.display()));
        assert!(same(&got, &expected), "{}", file.display());
    }
}

#[test]
fn the_tree_is_the_same_however_the_text_is_cut_into_runs() {
    for file in scene_files() {
        let text = std::fs::read_to_string(&file).unwrap();
        let idx = LineIndex::new(&text);
        let whole = format!("{:?}", parse_in_runs(&text, &idx, usize::MAX).unwrap());
        for run in [1, 2, 3, 7, 50] {
            let cut = format!("{:?}", parse_in_runs(&text, &idx, run).unwrap());
            assert_eq!(cut, whole, "{} in runs of {run} tokens", file.display());
        }
    }
}

const REFUSED: &[(&str, &str)] = &[
    ("a = 1\na = 2\n", "duplicate key `a`"),
    ("[t]\nx = 1\n[t]\ny = 2\n", "table `t` is defined twice"),
    ("a.b = 1\n[a]\n", "table `a` is defined twice"),
    ("[a.b.c]\nz = 9\n[a]\nb.c.t = 1\n", "already defined"),
    ("a = [1]\n[[a]]\n", "not as an array of tables"),
    ("[[a]]\n[a]\n", "array of tables"),
    ("a = 1\n[a.b]\n", "is a value, not a table"),
    ("a = {x = 1}\n[a]\n", "defined twice"),
    ("a = {x = 1}\na.y = 2\n", "already defined"),
    ("a = {x = 1, x = 2}\n", "duplicate key `x`"),
    ("a = 99999999999999999999\n", "64-bit"),
    ("a = 1e999\n", "64 bits"),
    ("a = \n", ""),
    ("a = [1, 2\n", ""),
    ("[a\n", ""),
    ("a = \"unterminated\n", ""),
    ("a = 1979-13-45\n", ""),
];

#[test]
fn documents_the_toml_crate_refuses_are_refused_with_the_reason() {
    for (text, reason) in REFUSED {
        assert!(reference(text).is_none(), "the reference accepts {text:?}");
        match ours(text) {
            Ok(v) => panic!("{text:?} accepted as {v:?}"),
            Err(e) => assert!(
                e.message.contains(reason) && e.offset <= text.len(),
                "{text:?}: {e:?}, expected {reason:?}"
            ),
        }
    }
}

#[test]
fn headers_dotted_keys_and_arrays_of_tables_combine_as_toml_says() {
    let text = "top = 1\n[fruit]\napple.color = \"red\"\napple.taste.sweet = true\n\
                [fruit.apple.texture]\nsmooth = true\n[[x.y]]\nn = 1\n[[x.y]]\nn = 2\n\
                [x.y.z]\nm = 3\n[a.b]\n[a]\nc = 'lit'\nd = [{e = 1}, {f.g = 2}]\n";
    let expected = reference(text).unwrap();
    assert!(same(&ours(text).unwrap(), &expected), "{:?}", ours(text));
}

#[test]
fn positions_are_those_of_keys_values_and_headers() {
    let text = "[scene]\nname = \"s\"\n\n[[bodies]]\nradius = 0.5\n[[bodies]]\n  radius = 2\n";
    let idx = LineIndex::new(text);
    let root = parse(text, &idx).unwrap();
    let Kind::Table(entries) = &root.kind else {
        panic!()
    };
    let bodies = entries.iter().find(|e| e.key == "bodies").unwrap();
    assert_eq!(bodies.key_pos, Pos { line: 4, column: 3 });
    let Kind::Array(list) = &bodies.value.kind else {
        panic!()
    };
    assert_eq!(list[1].pos, Pos { line: 6, column: 1 });
    let Kind::Table(second) = &list[1].kind else {
        panic!()
    };
    assert_eq!(second[0].key_pos, Pos { line: 7, column: 3 });
    assert_eq!(
        second[0].value.pos,
        Pos {
            line: 7,
            column: 12
        }
    );
}

#[test]
fn a_large_table_is_read_in_linear_time() {
    // 200k keys in one table: the hash index keeps each lookup constant.
    let text: String = (0..200_000).map(|i| format!("k{i} = {i}\n")).collect();
    let got = ours(&text).unwrap();
    assert_eq!(got.as_table().map(|t| t.len()), Some(200_000));
    assert_eq!(
        got.get("k199999").and_then(|v| v.as_integer()),
        Some(199_999)
    );
}

fn toml_value() -> impl Strategy<Value = toml::Value> {
    let leaf = prop_oneof![
        any::<i64>().prop_map(toml::Value::Integer),
        (-1e300f64..1e300).prop_map(toml::Value::Float),
        any::<bool>().prop_map(toml::Value::Boolean),
        "[ -~é\\n\\t\"']{0,12}".prop_map(toml::Value::String),
    ];
    leaf.prop_recursive(4, 48, 6, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..5).prop_map(toml::Value::Array),
            prop::collection::btree_map("[a-z_][a-z0-9_ .-]{0,6}", inner, 0..5)
                .prop_map(|m| toml::Value::Table(m.into_iter().collect())),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn generated_documents_read_as_written(
        table in prop::collection::btree_map("[a-z][a-z0-9_]{0,5}", toml_value(), 0..6)
    ) {
        let value = toml::Value::Table(table.into_iter().collect());
        let text = toml::to_string(&value).unwrap();
        let got = ours(&text).map_err(|e| TestCaseError::fail(format!("{text}\n{e:?}")))?;
        prop_assert!(same(&got, &value), "{}\n{:?}", text, got);
    }

    #[test]
    fn damaged_scenes_never_panic_and_agree_with_the_reference_when_it_accepts(
        which in 0usize..64, at in any::<prop::sample::Index>(), len in 0usize..8,
        byte in prop::sample::select(b"[]{}=,.\"'#\n \\abz0-+".to_vec())
    ) {
        let files = scene_files();
        let text = std::fs::read_to_string(&files[which % files.len()]).unwrap();
        let mut bytes = text.into_bytes();
        let at = at.index(bytes.len());
        let end = (at + len).min(bytes.len());
        bytes.splice(at..end, [byte]);
        let Ok(text) = String::from_utf8(bytes) else { return Ok(()) };
        let got = ours(&text);
        if let Some(expected) = reference(&text) {
            let got = got.map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            prop_assert!(same(&got, &expected));
        }
    }
}
