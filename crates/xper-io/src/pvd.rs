//! ParaView collection (`.pvd`) files listing one `.vtu` file per time step.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use crate::atomic::{read_text, with_path, write_atomic};
use crate::xml::{attribute, xml_escape};

/// One data set of a collection: a file shown at `time` as part `part`.
#[derive(Debug, Clone, PartialEq)]
pub struct PvdEntry {
    /// Simulation time of the data set.
    pub time: f64,
    /// Part index (several parts may share one time, e.g. bodies and contacts).
    pub part: u32,
    /// Path of the data file, relative to the `.pvd` file.
    pub file: String,
}

/// A ParaView collection: an ordered list of time-stamped data files.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PvdCollection {
    /// Entries in the order they are written.
    pub entries: Vec<PvdEntry>,
}

impl PvdCollection {
    /// Appends an entry for `file` (relative to the `.pvd`) at `time`.
    pub fn push(&mut self, time: f64, part: u32, file: impl Into<String>) {
        self.entries.push(PvdEntry {
            time,
            part,
            file: file.into(),
        });
    }

    /// Writes the collection to `path` atomically. Times are written with
    /// Rust's round-trip `{}` formatting, so reading back is exact.
    pub fn write(&self, path: &Path) -> io::Result<()> {
        let mut out = String::from("<?xml version=\"1.0\"?>\n");
        out.push_str("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
        out.push_str("  <Collection>\n");
        for e in &self.entries {
            let _ = writeln!(
                out,
                "    <DataSet timestep=\"{}\" group=\"\" part=\"{}\" file=\"{}\"/>",
                e.time,
                e.part,
                xml_escape(&e.file)
            );
        }
        out.push_str("  </Collection>\n</VTKFile>\n");
        write_atomic(path, out.as_bytes())
    }

    /// Reads a collection written by [`PvdCollection::write`].
    pub fn read(path: &Path) -> io::Result<Self> {
        let text = read_text(path)?;
        parse(&text).map_err(|e| with_path(path, e, io::ErrorKind::InvalidData))
    }

    /// Drops every entry whose time is greater than `time` (used when a run
    /// restarts from an earlier checkpoint).
    pub fn truncate_after(&mut self, time: f64) {
        self.entries.retain(|e| e.time <= time);
    }
}

/// Parses the `DataSet` elements of a collection file.
fn parse(text: &str) -> Result<PvdCollection, String> {
    if !text.contains("type=\"Collection\"") {
        return Err("not a VTK Collection file".to_string());
    }
    let mut collection = PvdCollection::default();
    let mut rest = text;
    while let Some(open) = rest.find("<DataSet") {
        let close = rest[open..].find('>').ok_or("unterminated DataSet tag")? + open;
        let tag = &rest[open..close];
        rest = &rest[close + 1..];
        let time_text = attribute(tag, "timestep").ok_or("DataSet without timestep")?;
        let time = time_text
            .parse::<f64>()
            .map_err(|e| format!("bad timestep '{time_text}': {e}"))?;
        let part = match attribute(tag, "part") {
            Some(p) => p
                .parse::<u32>()
                .map_err(|e| format!("bad part '{p}': {e}"))?,
            None => 0,
        };
        let file = attribute(tag, "file").ok_or("DataSet without file")?;
        collection.push(time, part, file);
    }
    Ok(collection)
}
