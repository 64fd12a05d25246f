//! The error every reader and writer returns: which file, where in it, and why.

use std::fmt;
use std::path::{Path, PathBuf};

/// Where in a file a problem was found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Position {
    /// The file as a whole (it cannot be opened, it has an unknown extension, ...).
    File,
    /// A whitespace-separated token of a text file: its 1-based index among all tokens and
    /// the 1-based line it is on. A token past the end of the file (truncation) has the
    /// index it would have had and the last line of the file.
    Token {
        /// 1-based index of the token in the file.
        index: usize,
        /// 1-based line number.
        line: usize,
    },
    /// An HDF5 object, by its absolute path in the file (`/fclib_local/W/p`).
    Dataset(String),
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Position::File => Ok(()),
            Position::Token { index, line } => write!(f, "line {line}, token {index}"),
            Position::Dataset(path) => write!(f, "dataset {path}"),
        }
    }
}

/// What kind of failure a [`ReadError`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadErrorKind {
    /// The operating system refused to read or write the file.
    Io,
    /// The content does not follow the format: missing, malformed or out-of-range data.
    Format,
    /// The content is well-formed but the problem it describes is invalid (sizes that do
    /// not match, a negative or NaN friction coefficient, ...).
    Invalid,
    /// The file needs a capability this build does not have (HDF5 without the `hdf5`
    /// feature) or a format variant this crate does not read.
    Unsupported,
}

/// A file could not be read or written: the file, the position in it and the reason.
/// The writers use it too (with [`ReadErrorKind::Io`] or [`ReadErrorKind::Unsupported`]).
///
/// Its `Display` reads like `path/to/file.dat: line 12, token 57: expected an integer, found "x"`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    /// The file concerned.
    pub path: PathBuf,
    /// Where in the file.
    pub position: Position,
    /// What went wrong.
    pub kind: ReadErrorKind,
    /// Why, in words.
    pub reason: String,
}

impl ReadError {
    /// A new error.
    pub fn new(
        path: &Path,
        position: Position,
        kind: ReadErrorKind,
        reason: impl Into<String>,
    ) -> Self {
        ReadError {
            path: path.to_path_buf(),
            position,
            kind,
            reason: reason.into(),
        }
    }

    /// An error about the file as a whole.
    pub fn file(path: &Path, kind: ReadErrorKind, reason: impl Into<String>) -> Self {
        Self::new(path, Position::File, kind, reason)
    }

    /// An input/output error.
    pub fn io(path: &Path, err: &std::io::Error) -> Self {
        Self::file(path, ReadErrorKind::Io, err.to_string())
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.position {
            Position::File => write!(f, "{}: {}", self.path.display(), self.reason),
            _ => write!(
                f,
                "{}: {}: {}",
                self.path.display(),
                self.position,
                self.reason
            ),
        }
    }
}

impl std::error::Error for ReadError {}
