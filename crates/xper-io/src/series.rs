//! Tables of per-step numbers written as CSV.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use crate::atomic::{read_text, with_path, write_atomic};

/// Whether a column of a series holds wall-clock figures (`wall_time`, `solve_time`,
/// `fluid_time`, ..., `*_seconds`), which differ between two runs of the same scene; the
/// simulated `time` does not.
pub fn is_timing_column(name: &str) -> bool {
    name.ends_with("_time") && name != "time" || name.ends_with("_seconds")
}

/// The text of a CSV table without its wall-clock columns ([`is_timing_column`], named on the
/// first line): what two runs of the same scene must agree on byte for byte.
pub fn without_timing_columns(csv: &str) -> String {
    let mut lines = csv.lines();
    let keep: Vec<bool> = (lines.next().unwrap_or("").split(','))
        .map(|c| !is_timing_column(c))
        .collect();
    let mut kept = String::with_capacity(csv.len());
    for line in csv.lines() {
        let fields: Vec<&str> = (line.split(',').zip(&keep))
            .filter(|(_, k)| **k)
            .map(|(f, _)| f)
            .collect();
        kept.push_str(&fields.join(","));
        kept.push('\n');
    }
    kept
}

/// A table of `f64` values with named columns, one row per recorded step.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SeriesTable {
    /// Column names, written as the CSV header line.
    pub columns: Vec<String>,
    /// Rows; each has one value per column.
    pub rows: Vec<Vec<f64>>,
}

impl SeriesTable {
    /// An empty table with the given column names.
    pub fn new(columns: &[&str]) -> Self {
        Self {
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row; it must have one value per column.
    pub fn push(&mut self, row: Vec<f64>) {
        debug_assert_eq!(row.len(), self.columns.len(), "row length != column count");
        self.rows.push(row);
    }

    /// All values of the column called `name`, or `None` if there is none.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let i = self.columns.iter().position(|c| c == name)?;
        Some(
            self.rows
                .iter()
                .map(|r| r.get(i).copied().unwrap_or(f64::NAN))
                .collect(),
        )
    }

    /// Writes the table to `path` atomically: a header line of column names,
    /// then one line per row. Values use Rust's `{}` formatting, which reads
    /// back bit-exactly.
    pub fn write_csv(&self, path: &Path) -> io::Result<()> {
        let invalid = |msg: String| with_path(path, msg, io::ErrorKind::InvalidInput);
        if let Some(c) = self
            .columns
            .iter()
            .find(|c| c.contains([',', '"', '\n', '\r']) || c.trim() != c.as_str())
        {
            return Err(invalid(format!("unsupported column name {c:?}")));
        }
        let mut out = self.columns.join(",");
        out.push('\n');
        for (i, row) in self.rows.iter().enumerate() {
            if row.len() != self.columns.len() {
                return Err(invalid(format!(
                    "row {i} has {} values for {} columns",
                    row.len(),
                    self.columns.len()
                )));
            }
            for (j, v) in row.iter().enumerate() {
                if j > 0 {
                    out.push(',');
                }
                let _ = write!(out, "{v}");
            }
            out.push('\n');
        }
        write_atomic(path, out.as_bytes())
    }

    /// Reads a CSV file written by [`SeriesTable::write_csv`]. Errors name
    /// the path and the 1-based line of a malformed row or number.
    pub fn read_csv(path: &Path) -> io::Result<Self> {
        let text = read_text(path)?;
        let bad = |line: usize, msg: String| {
            io::Error::new(
                io::ErrorKind::InvalidData,
                format!("{}:{}: {}", path.display(), line, msg),
            )
        };
        let mut lines = text.lines().enumerate();
        let header = match lines.next() {
            Some((_, h)) if !h.trim().is_empty() => h,
            _ => return Err(bad(1, "missing header line".to_string())),
        };
        let columns: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
        let mut rows = Vec::new();
        for (index, line) in lines {
            let line_no = index + 1;
            if line.trim().is_empty() {
                continue;
            }
            let fields: Vec<&str> = line.split(',').collect();
            if fields.len() != columns.len() {
                return Err(bad(
                    line_no,
                    format!("{} fields, expected {}", fields.len(), columns.len()),
                ));
            }
            let row = fields
                .iter()
                .zip(&columns)
                .map(|(f, c)| {
                    f.trim().parse::<f64>().map_err(|e| {
                        bad(
                            line_no,
                            format!("bad number {:?} in column '{c}': {e}", f.trim()),
                        )
                    })
                })
                .collect::<io::Result<Vec<f64>>>()?;
            rows.push(row);
        }
        Ok(Self { columns, rows })
    }

    /// Drops every row whose first value is greater than `value` (used when a
    /// run restarts from an earlier checkpoint). Rows with a NaN first value
    /// are kept.
    pub fn truncate_rows_where_first_column_greater_than(&mut self, value: f64) {
        self.rows
            .retain(|r| !matches!(r.first(), Some(&v) if v > value));
    }
}
