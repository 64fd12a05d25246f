//! Round trips of the PVD collection, CSV series and atomic JSON writers.

mod common;

use xper_io::{write_atomic, write_json_atomic, PvdCollection, SeriesTable};

#[test]
fn pvd_round_trip_and_truncate() {
    let dir = common::test_dir("pvd");
    let path = dir.join("run.pvd");
    let mut pvd = PvdCollection::default();
    let times = [0.0, 0.1 + 0.2, 1e-300, 123456.789012345, 2.0 / 3.0];
    for (i, &t) in times.iter().enumerate() {
        pvd.push(t, 0, format!("vtu/bodies_{i:05}.vtu"));
        pvd.push(t, 1, format!("vtu/contacts_{i:05}.vtu"));
    }
    pvd.push(5.0, 2, "odd & <name>.vtu");
    pvd.write(&path).unwrap();
    assert!(!dir.join("run.pvd.tmp").exists());
    let back = PvdCollection::read(&path).unwrap();
    assert_eq!(back, pvd);
    for (a, b) in back.entries.iter().zip(&pvd.entries) {
        assert_eq!(a.time.to_bits(), b.time.to_bits());
    }
    let mut cut = back.clone();
    cut.truncate_after(0.5);
    let kept: Vec<f64> = cut.entries.iter().map(|e| e.time).collect();
    assert_eq!(kept, vec![0.0, 0.0, 0.1 + 0.2, 0.1 + 0.2, 1e-300, 1e-300]);

    std::fs::write(
        &path,
        "<VTKFile type=\"Collection\"><DataSet timestep=\"x\" file=\"a\"/>",
    )
    .unwrap();
    let err = PvdCollection::read(&path).unwrap_err();
    assert!(err.to_string().contains("run.pvd"), "{err}");
}

#[test]
fn series_round_trip_is_bit_exact() {
    let dir = common::test_dir("series");
    let path = dir.join("series.csv");
    let mut table = SeriesTable::new(&["time", "energy", "count"]);
    let specials = [
        0.1 + 0.2,
        -0.0,
        f64::MIN_POSITIVE,
        5e-324,
        f64::MAX,
        -1.0 / 3.0,
        f64::INFINITY,
        1e21,
    ];
    for (i, &v) in specials.iter().enumerate() {
        table.push(vec![i as f64 * 0.01, v, (i * i) as f64]);
    }
    table.write_csv(&path).unwrap();
    assert!(!dir.join("series.csv.tmp").exists());
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("time,energy,count\n"));
    let back = SeriesTable::read_csv(&path).unwrap();
    assert_eq!(back.columns, table.columns);
    assert_eq!(back.rows.len(), table.rows.len());
    for (a, b) in back.rows.iter().flatten().zip(table.rows.iter().flatten()) {
        assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
    }
    assert_eq!(back.column("count").unwrap()[3], 9.0);
    assert!(back.column("missing").is_none());

    let mut cut = back;
    cut.truncate_rows_where_first_column_greater_than(0.025);
    assert_eq!(cut.column("time").unwrap(), vec![0.0, 0.01, 0.02]);
}

#[test]
fn corrupted_csv_names_path_and_line() {
    let dir = common::test_dir("series_bad");
    let path = dir.join("bad.csv");
    std::fs::write(&path, "a,b\n1,2\n3,4\n5,oops\n").unwrap();
    let err = SeriesTable::read_csv(&path).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("bad.csv:4"), "{msg}");
    assert!(msg.contains("oops"), "{msg}");
    std::fs::write(&path, "a,b\n1,2,3\n").unwrap();
    let msg = SeriesTable::read_csv(&path).unwrap_err().to_string();
    assert!(msg.contains("bad.csv:2"), "{msg}");
    let mut t = SeriesTable::new(&["a,b"]);
    t.rows.push(vec![1.0]);
    assert!(t.write_csv(&path).is_err());
}

#[test]
fn atomic_writes_replace_and_report_path() {
    let dir = common::test_dir("atomic");
    let path = dir.join("data.bin");
    write_atomic(&path, b"first").unwrap();
    write_atomic(&path, b"second").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"second");
    assert!(!dir.join("data.bin.tmp").exists());

    let json = dir.join("summary.json");
    let value = serde_json::json!({"steps": 10, "ratio": 0.1 + 0.2, "name": "test"});
    write_json_atomic(&json, &value).unwrap();
    let text = std::fs::read_to_string(&json).unwrap();
    assert!(text.contains("\n  \"steps\": 10"), "{text}");
    let back: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(back, value);

    let bad = dir.join("no_such_dir").join("x.json");
    let err = write_json_atomic(&bad, &value).unwrap_err();
    assert!(err.to_string().contains("no_such_dir"), "{err}");
}
