//! `read_problem` picks the reader by extension.

use xper_fclib::{read_problem, Position, ReadErrorKind};

#[test]
fn unknown_extensions_are_refused() {
    for name in ["problem.txt", "problem", "problem.hdf"] {
        let e = read_problem(name).unwrap_err();
        assert_eq!(
            (e.kind, &e.position),
            (ReadErrorKind::Unsupported, &Position::File),
            "{e}"
        );
        assert!(
            e.to_string()
                .starts_with(&format!("{name}: unknown extension")),
            "{e}"
        );
    }
}

#[cfg(not(feature = "hdf5"))]
#[test]
fn hdf5_files_need_the_feature() {
    for name in ["dump.hdf5", "dump.H5"] {
        let e = read_problem(name).unwrap_err();
        assert_eq!(e.kind, ReadErrorKind::Unsupported);
        assert_eq!(
            e.to_string(),
            format!("{name}: built without HDF5 support: rebuild with --features hdf5")
        );
    }
}

#[cfg(feature = "hdf5")]
#[test]
fn hdf5_files_go_to_the_fclib_reader() {
    let e = read_problem("no-such-dump.H5").unwrap_err();
    assert_eq!(e.kind, ReadErrorKind::Io, "{e}");
}

#[test]
fn dat_files_go_to_the_siconos_reader() {
    let e = read_problem("no-such-problem.DAT").unwrap_err();
    assert_eq!(e.kind, ReadErrorKind::Io, "{e}");
}
