//! FCLib HDF5: writing then reading gives the identical problem; writes are atomic;
//! malformed files (truncated, garbage, wrong sizes, out-of-range indices, bad values)
//! give errors naming the file and the dataset.
#![cfg(feature = "hdf5")]

mod common;

use common::{shared_dir, TempDir};
use hdf5_metno as h5;
use std::path::Path;
use xper_fclib::fclib::{read_fclib_global, read_fclib_local};
use xper_fclib::{
    read_problem, write_fclib_global, write_fclib_local, CsrMatrix, FrictionProblem,
    GlobalFrictionProblem, Position, Problem, ReadError, ReadErrorKind,
};

fn small_local() -> FrictionProblem {
    let w = CsrMatrix::from_triplets(
        6,
        6,
        &[
            (0, 0, 2.0),
            (1, 1, 1.5),
            (2, 2, 1.5),
            (0, 3, -0.25),
            (3, 0, -0.25),
            (3, 3, 1.0 / 3.0),
            (4, 4, 0.7),
            (5, 5, 0.7),
            (4, 5, 1e-300),
        ],
    )
    .unwrap();
    FrictionProblem::new(
        3,
        w,
        vec![-1.0, 0.1, -0.0, 0.5, f64::MIN_POSITIVE, 3e10],
        vec![0.3, 0.0],
    )
    .unwrap()
}

#[test]
fn local_round_trip_is_identical() {
    let tmp = TempDir::new("roundtrip");
    let mut problems = vec![small_local()];
    // An empty problem and a 2D one.
    problems.push(
        FrictionProblem::new(
            3,
            CsrMatrix::from_triplets(0, 0, &[]).unwrap(),
            vec![],
            vec![],
        )
        .unwrap(),
    );
    let w2 = CsrMatrix::from_triplets(2, 2, &[(0, 0, 1.0), (1, 1, 2.0)]).unwrap();
    problems.push(FrictionProblem::new(2, w2, vec![-1.0, 0.0], vec![0.5]).unwrap());
    if let Some(shared) = shared_dir() {
        for f in [
            "Capsules-i125-1213.hdf5",
            "LMGC_100_PR_PerioBox-i00361-60-03000.hdf5",
        ] {
            let Problem::Local(p) = read_problem(shared.join("hdf5_3d_local").join(f)).unwrap()
            else {
                panic!("{f} is local")
            };
            problems.push(p);
        }
        let Problem::Local(p) =
            read_problem(shared.join("siconos_dat_2d/FrictionContactProblem00237.dat")).unwrap()
        else {
            panic!("local")
        };
        problems.push(p);
    }
    for (k, p) in problems.iter().enumerate() {
        let path = tmp.path(&format!("p{k}.hdf5"));
        write_fclib_local(&path, p).unwrap();
        let back = read_fclib_local(&path).unwrap();
        assert_eq!(&back, p, "problem {k}");
        // Bit for bit, including the sign of zeros.
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.q), bits(&p.q));
        assert_eq!(bits(&back.w.values), bits(&p.w.values));
        assert_eq!(read_problem(&path).unwrap(), Problem::Local(p.clone()));
    }
    // Only the written files are left: no temporary files.
    let mut names: Vec<String> = std::fs::read_dir(&tmp.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let expected: Vec<String> = (0..problems.len()).map(|k| format!("p{k}.hdf5")).collect();
    assert_eq!(names, expected);
}

#[test]
fn global_round_trip_is_identical_and_reduces_alike() {
    let Some(shared) = shared_dir() else { return };
    let tmp = TempDir::new("roundtrip-global");
    let sources = [
        shared.join("hdf5_3d_global/LMGC_GlobalFrictionContactProblem00046.hdf5"),
        shared.join("hdf5_3d_global/Box_Stacks-i0122-82-5.hdf5"),
        shared.join("siconos_dat_2d/gfc2d_granularflowonwall_00069_00350.dat"),
        shared.join("siconos_dat_2d/gfc2d_granularflowonwall_00000_00117.dat"),
    ];
    for (k, src) in sources.iter().enumerate() {
        let Problem::Global(p) = read_problem(src).unwrap() else {
            panic!("global")
        };
        let path = tmp.path(&format!("g{k}.h5"));
        write_fclib_global(&path, &p).unwrap();
        let back = read_fclib_global(&path).unwrap();
        assert_eq!(back, p, "{}", src.display());
        assert_eq!(back.to_local().unwrap(), p.to_local().unwrap());
    }
}

#[test]
fn writing_replaces_atomically_and_failures_leave_nothing() {
    let tmp = TempDir::new("atomic");
    let path = tmp.path("dump.hdf5");
    std::fs::write(&path, b"old content").unwrap();
    write_fclib_local(&path, &small_local()).unwrap();
    assert_eq!(read_fclib_local(&path).unwrap(), small_local());
    // A missing directory: an error naming the target, and no file anywhere.
    let bad = tmp.path("no/such/dir/dump.hdf5");
    let e = write_fclib_local(&bad, &small_local()).unwrap_err();
    assert_eq!(
        (e.kind, e.path.as_path()),
        (ReadErrorKind::Io, bad.as_path())
    );
    // An inconsistent problem is refused, and the previous file stays.
    let mut broken = small_local();
    broken.mu.push(0.1);
    let e = write_fclib_local(&path, &broken).unwrap_err();
    assert_eq!(e.kind, ReadErrorKind::Invalid, "{e}");
    assert_eq!(read_fclib_local(&path).unwrap(), small_local());
    let left: Vec<_> = std::fs::read_dir(&tmp.0).unwrap().collect();
    assert_eq!(left.len(), 1);
}

/// Writes `small_local()` to `path`, then lets `edit` change the file.
fn corrupt(path: &Path, edit: impl FnOnce(&h5::File)) {
    write_fclib_local(path, &small_local()).unwrap();
    let f = h5::File::open_rw(path).unwrap();
    edit(&f);
    f.close().unwrap();
}

fn replace<T: h5::H5Type>(f: &h5::File, at: &str, data: &[T]) {
    let (group, name) = at.rsplit_once('/').unwrap();
    let g = f.group(group).unwrap();
    g.unlink(name).unwrap();
    g.new_dataset_builder()
        .with_data(data)
        .create(name)
        .unwrap();
}

/// A change made to a valid file.
type Edit = Box<dyn FnOnce(&h5::File)>;

fn expect_err(path: &Path, dataset: &str, kind: ReadErrorKind, words: &str) -> ReadError {
    let e = read_problem(path).expect_err(dataset);
    assert_eq!(e.path, path);
    assert_eq!(e.position, Position::Dataset(dataset.into()), "{e}");
    assert_eq!(e.kind, kind, "{e}");
    assert!(e.reason.contains(words), "'{words}' not in: {e}");
    assert!(
        e.to_string().contains(&format!("dataset {dataset}: ")),
        "{e}"
    );
    e
}

#[test]
fn malformed_datasets_are_named_in_the_error() {
    let tmp = TempDir::new("malformed");
    let cases: Vec<(&str, Edit, &str, ReadErrorKind, &str)> = vec![
        (
            "index",
            Box::new(|f| replace(f, "fclib_local/W/i", &[0i32, 1, 2, 3, 0, 4, 5, 9, 5])),
            "/fclib_local/W",
            ReadErrorKind::Format,
            "outside 0..6",
        ),
        (
            "negative-index",
            Box::new(|f| replace(f, "fclib_local/W/i", &[0i32, 1, 2, 3, 0, 4, 5, -1, 5])),
            "/fclib_local/W",
            ReadErrorKind::Format,
            "= -1",
        ),
        (
            "pointers",
            Box::new(|f| replace(f, "fclib_local/W/p", &[0i32, 2, 3, 4, 6, 8])),
            "/fclib_local/W",
            ReadErrorKind::Format,
            "6 + 1 expected",
        ),
        (
            "decreasing",
            Box::new(|f| replace(f, "fclib_local/W/p", &[0i32, 2, 3, 2, 6, 8, 9])),
            "/fclib_local/W",
            ReadErrorKind::Format,
            "decrease",
        ),
        (
            "nz",
            Box::new(|f| replace(f, "fclib_local/W/nz", &[-3i32])),
            "/fclib_local/W/nz",
            ReadErrorKind::Format,
            "nz = -3",
        ),
        (
            "rows",
            Box::new(|f| replace(f, "fclib_local/W/m", &[7i32])),
            "/fclib_local/W",
            ReadErrorKind::Invalid,
            "7 x 6",
        ),
        (
            "q-length",
            Box::new(|f| replace(f, "fclib_local/vectors/q", &[1.0f64; 7])),
            "/fclib_local/vectors/q",
            ReadErrorKind::Invalid,
            "not a multiple",
        ),
        (
            "mu-length",
            Box::new(|f| replace(f, "fclib_local/vectors/mu", &[0.1f64; 3])),
            "/fclib_local/vectors/mu",
            ReadErrorKind::Invalid,
            "3 entries; 2 expected",
        ),
        (
            "mu-negative",
            Box::new(|f| replace(f, "fclib_local/vectors/mu", &[0.1f64, -0.2])),
            "/fclib_local/vectors/mu",
            ReadErrorKind::Invalid,
            "mu[1] = -0.2",
        ),
        (
            "mu-nan",
            Box::new(|f| replace(f, "fclib_local/vectors/mu", &[f64::NAN, 0.2])),
            "/fclib_local/vectors/mu",
            ReadErrorKind::Invalid,
            "not finite",
        ),
        (
            "x-inf",
            Box::new(|f| {
                replace(
                    f,
                    "fclib_local/W/x",
                    &[1.0f64, 1.0, 1.0, f64::INFINITY, 1.0, 1.0, 1.0, 1.0, 1.0],
                )
            }),
            "/fclib_local/W/x",
            ReadErrorKind::Invalid,
            "entry 3 = inf",
        ),
        (
            "spacedim",
            Box::new(|f| replace(f, "fclib_local/spacedim", &[4i32])),
            "/fclib_local/spacedim",
            ReadErrorKind::Invalid,
            "spacedim = 4",
        ),
        (
            "scalar",
            Box::new(|f| replace(f, "fclib_local/spacedim", &[3i32, 3])),
            "/fclib_local/spacedim",
            ReadErrorKind::Format,
            "2 values; one expected",
        ),
        (
            "float-index",
            Box::new(|f| replace(f, "fclib_local/W/i", &[0.0f64; 9])),
            "/fclib_local/W/i",
            ReadErrorKind::Format,
            "integers expected",
        ),
        (
            "missing",
            Box::new(|f| f.group("fclib_local/vectors").unwrap().unlink("q").unwrap()),
            "/fclib_local/vectors/q",
            ReadErrorKind::Format,
            "missing dataset",
        ),
    ];
    for (name, edit, dataset, kind, words) in cases {
        let path = tmp.path(&format!("{name}.hdf5"));
        corrupt(&path, edit);
        expect_err(&path, dataset, kind, words);
    }
    // A triplet matrix with a column out of range, in a global file.
    let path = tmp.path("triplet.hdf5");
    let m = CsrMatrix::from_triplets(2, 2, &[(0, 0, 1.0), (1, 1, 1.0)]).unwrap();
    let h = CsrMatrix::from_triplets(2, 3, &[(0, 0, 1.0), (1, 2, 1.0)]).unwrap();
    let g = GlobalFrictionProblem::new(3, m, h, vec![1.0, 2.0], vec![0.0; 3], vec![0.5]).unwrap();
    write_fclib_global(&path, &g).unwrap();
    let f = h5::File::open_rw(&path).unwrap();
    replace(&f, "fclib_global/H/nz", &[2i32]);
    replace(&f, "fclib_global/H/i", &[0i32, 1]);
    replace(&f, "fclib_global/H/p", &[0i32, 3]);
    replace(&f, "fclib_global/H/x", &[1.0f64, 1.0]);
    f.close().unwrap();
    expect_err(
        &path,
        "/fclib_global/H",
        ReadErrorKind::Format,
        "column index[1] = 3 is outside 0..3",
    );
}

#[test]
fn truncated_and_garbage_files_are_errors() {
    let tmp = TempDir::new("truncated-h5");
    let mut sources = vec![];
    let written = tmp.path("written.hdf5");
    write_fclib_local(&written, &small_local()).unwrap();
    sources.push(written);
    if let Some(shared) = shared_dir() {
        sources.push(shared.join("hdf5_3d_local/BoxesStack_local_problem_test.hdf5"));
        sources.push(shared.join("hdf5_3d_global/LMGC_CubeH8.hdf5"));
    }
    for src in &sources {
        let bytes = std::fs::read(src).unwrap();
        for frac in [0.0, 0.01, 0.2, 0.5, 0.8, 0.99] {
            let cut = (bytes.len() as f64 * frac) as usize;
            let path = tmp.path(&format!("cut-{cut}.hdf5"));
            std::fs::write(&path, &bytes[..cut]).unwrap();
            let e = read_problem(&path).expect_err(&format!("{} cut at {cut}", src.display()));
            assert_eq!(e.path, path);
            assert!(matches!(e.kind, ReadErrorKind::Format), "{e}");
        }
    }
    let garbage = tmp.path("garbage.h5");
    std::fs::write(&garbage, b"\x89HDF\r\n\x1a\nnot really an HDF5 file at all").unwrap();
    let e = read_problem(&garbage).unwrap_err();
    assert_eq!(
        (e.kind, &e.position),
        (ReadErrorKind::Format, &Position::File)
    );
    assert!(e.reason.contains("not a readable HDF5 file"), "{e}");
    // A valid HDF5 file without FCLib groups.
    let empty = tmp.path("empty.hdf5");
    h5::File::create(&empty).unwrap().close().unwrap();
    let e = read_problem(&empty).unwrap_err();
    assert!(
        e.reason.contains("neither /fclib_local nor /fclib_global"),
        "{e}"
    );
}
