//! The parts of a MSH 4.1 file that are read here rather than by mshio: the `$MeshFormat`
//! header (checked first, so that unsupported versions and sizes give a clear message), the
//! `$PhysicalNames` section (which mshio skips), and the translation of mshio's errors.
//!
//! Format reference: Gmsh reference manual, section "MSH file format" (version 4.1),
//! <https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format>.

use std::collections::HashMap;

use crate::error::{MeshError, MeshErrorKind};

/// What the `$MeshFormat` header says.
pub(crate) struct Header {
    /// `true` for a binary file (file-type 1).
    pub binary: bool,
}

fn format_error(origin: &str, place: impl Into<String>, reason: impl Into<String>) -> MeshError {
    MeshError::new(MeshErrorKind::Format, origin, reason).at(place)
}

/// The 1-based line of byte `offset` in `bytes`.
pub(crate) fn line_of(bytes: &[u8], offset: usize) -> usize {
    bytes[..offset.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The place of byte `offset`: a line for an ASCII file, a byte offset for a binary one.
pub(crate) fn place_of(bytes: &[u8], offset: usize, binary: bool) -> String {
    if binary {
        format!("byte {offset}")
    } else {
        format!("line {}", line_of(bytes, offset))
    }
}

/// The lines of `bytes` with the byte offset where each starts.
fn lines_with_offsets(bytes: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    let mut start = 0;
    bytes.split(|&b| b == b'\n').map(move |line| {
        let at = start;
        start += line.len() + 1;
        (at, line)
    })
}

fn trim(line: &[u8]) -> &[u8] {
    line.trim_ascii()
}

/// Checks the `$MeshFormat` header: version 4.1, file-type 0 or 1, data-size 4 or 8.
pub(crate) fn check_header(bytes: &[u8], origin: &str) -> Result<Header, MeshError> {
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(MeshError::new(
            MeshErrorKind::Format,
            origin,
            "empty file (a Gmsh MSH file starts with $MeshFormat)",
        ));
    }
    let mut lines = lines_with_offsets(bytes).filter(|(_, l)| !trim(l).is_empty());
    let (first_at, first) = lines.next().unwrap_or((0, &[]));
    if trim(first) != b"$MeshFormat" {
        return Err(format_error(
            origin,
            format!("line {}", line_of(bytes, first_at)),
            "not a Gmsh MSH file: it does not start with $MeshFormat",
        ));
    }
    let (at, line) = lines.next().unwrap_or((bytes.len(), &[]));
    let place = format!("line {} ($MeshFormat)", line_of(bytes, at));
    let text = String::from_utf8_lossy(trim(line)).into_owned();
    let fields: Vec<&str> = text.split_ascii_whitespace().collect();
    if fields.len() < 3 {
        return Err(format_error(
            origin,
            place,
            format!("expected `version file-type data-size`, found `{text}`"),
        ));
    }
    if fields[0] != "4.1" {
        let hint = if fields[0].starts_with('2') || fields[0].starts_with('4') {
            ": convert with gmsh -format msh41 (e.g. `gmsh old.msh -0 -format msh41 -o new.msh`)"
        } else {
            ""
        };
        return Err(MeshError::new(
            MeshErrorKind::Unsupported,
            origin,
            format!(
                "MSH format version {} is not supported, only 4.1{hint}",
                fields[0]
            ),
        )
        .at(place));
    }
    let binary = match fields[1] {
        "0" => false,
        "1" => true,
        other => {
            return Err(format_error(
                origin,
                place,
                format!("file-type must be 0 (ASCII) or 1 (binary), found {other}"),
            ))
        }
    };
    if fields[2] != "4" && fields[2] != "8" {
        return Err(format_error(
            origin,
            place,
            format!("data-size must be 4 or 8, found {}", fields[2]),
        ));
    }
    Ok(Header { binary })
}

/// The names of the `$PhysicalNames` section, keyed by `(dimension, physical tag)`; empty
/// when the file has no such section.
pub(crate) fn physical_names(
    bytes: &[u8],
    origin: &str,
) -> Result<HashMap<(i32, i32), String>, MeshError> {
    let mut names = HashMap::new();
    let mut lines = lines_with_offsets(bytes).skip_while(|(_, l)| trim(l) != b"$PhysicalNames");
    let Some((start, _)) = lines.next() else {
        return Ok(names);
    };
    let place = |at: usize| format!("line {} ($PhysicalNames)", line_of(bytes, at));
    let (at, count_line) = lines.next().unwrap_or((bytes.len(), &[]));
    let count: usize = std::str::from_utf8(trim(count_line))
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format_error(origin, place(at), "expected the number of names"))?;
    for _ in 0..count {
        let Some((at, line)) = lines.next() else {
            return Err(format_error(
                origin,
                place(start),
                format!("the file ends before the {count} physical names"),
            ));
        };
        let text = String::from_utf8_lossy(trim(line)).into_owned();
        let parsed = (|| {
            let mut it = text.splitn(3, char::is_whitespace);
            let dim: i32 = it.next()?.parse().ok()?;
            let tag: i32 = it.next()?.parse().ok()?;
            let name = it.next()?.trim();
            let name = name.strip_prefix('"')?.strip_suffix('"')?;
            Some((dim, tag, name.to_string()))
        })();
        let Some((dim, tag, name)) = parsed else {
            return Err(format_error(
                origin,
                place(at),
                format!("expected `dimension tag \"name\"`, found `{text}`"),
            ));
        };
        names.insert((dim, tag), name);
    }
    match lines.next() {
        Some((_, l)) if trim(l) == b"$EndPhysicalNames" => Ok(names),
        Some((at, _)) => Err(format_error(
            origin,
            place(at),
            "expected $EndPhysicalNames",
        )),
        None => Err(format_error(
            origin,
            place(bytes.len()),
            "the file ends before $EndPhysicalNames",
        )),
    }
}
