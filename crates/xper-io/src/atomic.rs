//! Atomic file writes: data goes to `<path>.tmp` in the same directory, is
//! flushed to disk, then renamed over the destination, so readers never see a
//! half-written file.

use std::ffi::OsString;
use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Wraps an I/O error so that its message names `path`.
pub(crate) fn with_path(path: &Path, e: impl std::fmt::Display, kind: io::ErrorKind) -> io::Error {
    io::Error::new(kind, format!("{}: {}", path.display(), e))
}

/// Adds `path` to the message of an existing I/O error, keeping its kind.
pub(crate) fn annotate(path: &Path, e: io::Error) -> io::Error {
    with_path(path, &e, e.kind())
}

/// The temporary sibling `<path>.tmp` used while writing `path`.
fn tmp_path(path: &Path) -> PathBuf {
    let mut name: OsString = path.as_os_str().to_owned();
    name.push(".tmp");
    PathBuf::from(name)
}

/// Writes `bytes` to `path` atomically (temp file, flush, sync, rename).
///
/// Errors name the path that failed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let tmp = tmp_path(path);
    let result = (|| {
        let mut file = File::create(&tmp).map_err(|e| annotate(&tmp, e))?;
        file.write_all(bytes).map_err(|e| annotate(&tmp, e))?;
        file.flush().map_err(|e| annotate(&tmp, e))?;
        file.sync_all().map_err(|e| annotate(&tmp, e))?;
        drop(file);
        std::fs::rename(&tmp, path).map_err(|e| annotate(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Serialises `value` as pretty-printed JSON (with a trailing newline) and
/// writes it to `path` atomically.
pub fn write_json_atomic<T: serde::Serialize>(path: &Path, value: &T) -> io::Result<()> {
    let mut text = serde_json::to_string_pretty(value)
        .map_err(|e| with_path(path, e, io::ErrorKind::InvalidData))?;
    text.push('\n');
    write_atomic(path, text.as_bytes())
}

/// Reads a whole file as UTF-8 text, naming the path on error.
pub(crate) fn read_text(path: &Path) -> io::Result<String> {
    std::fs::read_to_string(path).map_err(|e| annotate(path, e))
}
