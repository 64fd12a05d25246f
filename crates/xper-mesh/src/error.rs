//! The error type of the crate: every failure names its origin (a file path, a generator or
//! `mesh`), the place inside it when known, and the reason.

use std::fmt;

/// What kind of failure a [`MeshError`] reports, for callers that branch on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshErrorKind {
    /// The file could not be read from disk.
    Io,
    /// The file is not a well-formed Gmsh MSH 4.1 file (truncated, wrong version, corrupt).
    Format,
    /// The file is well formed but holds something this crate does not support
    /// (quadrangles, second-order elements, 3D elements, non-planar nodes).
    Unsupported,
    /// The mesh breaks an invariant: degenerate triangle, index out of range, non-finite
    /// coordinate, edge shared by three triangles, inconsistent set.
    Invalid,
    /// A generator was given a specification it cannot mesh (negative size, inclusion
    /// outside the domain, overlapping inclusions).
    Spec,
    /// A name (region, edge set, node set) or a selector is unknown or malformed.
    Selection,
}

/// An error of reading, generating, validating or querying a mesh.
///
/// Its [`Display`](fmt::Display) is `origin: place: reason` (the place is left out when
/// unknown), e.g. `tests/data/bad.msh: element 12: only 3-node triangles are supported`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeshError {
    /// What failed: a file path, a generator name (`rectangle_with_inclusions`) or `mesh`.
    pub origin: String,
    /// Where inside the origin: a section, an element or node tag, a line, a field name.
    pub place: Option<String>,
    /// Why it failed, in words.
    pub reason: String,
    /// The family of the failure.
    pub kind: MeshErrorKind,
}

impl MeshError {
    /// A new error without a place.
    pub fn new(kind: MeshErrorKind, origin: impl Into<String>, reason: impl Into<String>) -> Self {
        MeshError {
            origin: origin.into(),
            place: None,
            reason: reason.into(),
            kind,
        }
    }

    /// The same error with its place set.
    pub fn at(mut self, place: impl Into<String>) -> Self {
        self.place = Some(place.into());
        self
    }

    /// The same error with its origin replaced (a mesh checked after reading a file takes
    /// the file's path as origin).
    pub fn from_origin(mut self, origin: impl Into<String>) -> Self {
        self.origin = origin.into();
        self
    }

    /// An [`MeshErrorKind::Invalid`] error about the mesh itself.
    pub(crate) fn invalid(place: impl Into<String>, reason: impl Into<String>) -> Self {
        MeshError::new(MeshErrorKind::Invalid, "mesh", reason).at(place)
    }

    /// An [`MeshErrorKind::Selection`] error for an unknown name, listing the known ones.
    pub(crate) fn unknown_name<'a>(
        what: &str,
        name: &str,
        known: impl Iterator<Item = &'a str>,
    ) -> Self {
        let known: Vec<&str> = known.collect();
        let list = if known.is_empty() {
            "none".to_string()
        } else {
            known.join(", ")
        };
        MeshError::new(
            MeshErrorKind::Selection,
            "mesh",
            format!("unknown {what} `{name}` (known: {list})"),
        )
    }
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.place {
            Some(place) => write!(f, "{}: {}: {}", self.origin, place, self.reason),
            None => write!(f, "{}: {}", self.origin, self.reason),
        }
    }
}

impl std::error::Error for MeshError {}
