//! Frictional contact problems from (and to) files, for testing xper's solvers on problems
//! written by other codes.
//!
//! Two formats are read:
//! - **FCLib** HDF5 files (Acary, Cadoux, Lamarque, Kaufman, Bremond, Vaillant,
//!   "FCLib: a collection of discrete 3D frictional contact problems", JOTA 160(3), 2014;
//!   <https://github.com/FrictionalContactLibrary/fclib>): `/fclib_local` (W, q, mu) and
//!   `/fclib_global` (M, H, f, w, mu), behind the `hdf5` cargo feature, which needs the
//!   system HDF5 library. The `fclib` module (present with the feature) documents the
//!   layout; its `write_fclib_local` and `write_fclib_global` write it atomically.
//! - **Siconos** numerics text files (`.dat`), local and global, 2D or 3D, with dense,
//!   sparse-block or CSparse matrices; see [`siconos`] for the layout and for how local and
//!   global files are told apart.
//!
//! Both give a [`Problem`]: the local form is xper's [`FrictionProblem`]
//! (`u = W r + q`, unknowns `[normal, tangent(s)]` per contact), the global form a
//! [`GlobalFrictionProblem`] (`M v = H r + f`, `u = H^T v + w`) that
//! [`GlobalFrictionProblem::to_local`] reduces to `W = H^T M^-1 H`, `q = H^T M^-1 f + w`.
//!
//! [`read_problem`] picks the reader from the file extension. Every reader returns a
//! [`ReadError`] naming the file, the position (line and token for text, dataset path for
//! HDF5) and the reason for malformed, truncated or inconsistent files; none panics on
//! file data. The writers report their failures with the same type.

#![warn(missing_docs)]

mod error;
#[cfg(feature = "hdf5")]
pub mod fclib;
mod global;
pub mod siconos;
mod sparse;

pub use error::{Position, ReadError, ReadErrorKind};
#[cfg(feature = "hdf5")]
pub use fclib::{
    read_fclib, read_fclib_global, read_fclib_local, write_fclib_global, write_fclib_local,
};
pub use global::{Factorization, GlobalFrictionProblem, Reduction};
pub use siconos::{parse_siconos, read_siconos, read_siconos_as, SiconosKind};
pub use xper_solver::{CsrMatrix, FrictionProblem, ProblemError};

use std::path::Path;

/// A problem read from a file, in the form the file stores it.
#[derive(Clone, Debug, PartialEq)]
pub enum Problem {
    /// `u = W r + q`.
    Local(FrictionProblem),
    /// `M v = H r + f`, `u = H^T v + w`.
    Global(GlobalFrictionProblem),
}

impl Problem {
    /// Local dimension, 2 or 3.
    pub fn dim(&self) -> usize {
        match self {
            Problem::Local(p) => p.dim,
            Problem::Global(p) => p.dim,
        }
    }

    /// Number of contacts.
    pub fn contact_count(&self) -> usize {
        match self {
            Problem::Local(p) => p.contact_count(),
            Problem::Global(p) => p.contact_count(),
        }
    }

    /// The local form: the problem itself, or the reduction of a global one.
    pub fn into_local(self) -> Result<FrictionProblem, ProblemError> {
        match self {
            Problem::Local(p) => Ok(p),
            Problem::Global(p) => p.to_local(),
        }
    }
}

/// How a problem file is read by [`read_local`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadAs {
    /// As the file says (by extension and content, see [`read_problem`]).
    Auto,
    /// A Siconos `.dat` read as a local problem.
    Local,
    /// A Siconos `.dat` read as a global problem.
    Global,
}

/// Reads a problem file and reduces it to the local form; returns it with the form the file
/// stored (`"local"` or `"global"`). The error names the file and the reason.
pub fn read_local(path: &Path, how: ReadAs) -> Result<(FrictionProblem, &'static str), String> {
    let problem = match how {
        ReadAs::Auto => read_problem(path),
        ReadAs::Local => read_siconos_as(path, SiconosKind::Local),
        ReadAs::Global => read_siconos_as(path, SiconosKind::Global),
    }
    .map_err(|e| e.to_string())?;
    let form = match problem {
        Problem::Local(_) => "local",
        Problem::Global(_) => "global",
    };
    let local = problem
        .into_local()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((local, form))
}

/// Reads a problem, choosing the format by extension: `.hdf5`/`.h5` for FCLib (needs the
/// `hdf5` feature), `.dat` for Siconos text (local or global told apart by content).
pub fn read_problem(path: impl AsRef<Path>) -> Result<Problem, ReadError> {
    let path = path.as_ref();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("hdf5" | "h5") => read_hdf5(path),
        Some("dat") => read_siconos(path),
        _ => Err(ReadError::file(
            path,
            ReadErrorKind::Unsupported,
            "unknown extension: .hdf5 or .h5 (FCLib) or .dat (Siconos) expected",
        )),
    }
}

#[cfg(feature = "hdf5")]
fn read_hdf5(path: &Path) -> Result<Problem, ReadError> {
    read_fclib(path)
}

#[cfg(not(feature = "hdf5"))]
fn read_hdf5(path: &Path) -> Result<Problem, ReadError> {
    Err(ReadError::file(
        path,
        ReadErrorKind::Unsupported,
        "built without HDF5 support: rebuild with --features hdf5",
    ))
}

/// Writes `bytes`-producing output atomically: `write` fills a temporary file next to
/// `path`, which then replaces `path` by a rename, so readers never see a partial file.
#[cfg_attr(not(feature = "hdf5"), allow(dead_code))]
pub(crate) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), ReadError>,
) -> Result<(), ReadError> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| ReadError::file(path, ReadErrorKind::Io, "not a file path"))?;
    let tmp = path.with_file_name(format!(
        ".{}.tmp-{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let result =
        write(&tmp).and_then(|()| std::fs::rename(&tmp, path).map_err(|e| ReadError::io(path, &e)));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
