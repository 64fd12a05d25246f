//! Output writers for the xper simulator: atomic file writes, VTK XML
//! unstructured grids (`.vtu`) and ParaView collections (`.pvd`), CSV time
//! series, PNG line plots and segment drawings, and peak memory measurement.
//!
//! This crate knows nothing about physics; it only formats and writes data.

#![warn(missing_docs)]

pub mod atomic;
mod base64;
pub mod memory;
pub mod plot;
pub mod pvd;
pub mod segments;
pub mod series;
pub mod vti;
pub mod vtu;
mod xml;

pub use atomic::{write_atomic, write_json_atomic};
pub use memory::{current_heap_bytes, peak_heap_bytes, peak_memory_bytes, CountingAllocator};
pub use plot::{plot_panels, Curve, Panel};
pub use pvd::{PvdCollection, PvdEntry};
pub use segments::{plot_segments, SegmentLayer};
pub use series::{is_timing_column, without_timing_columns, SeriesTable};
pub use vti::{write_vti, ImageGrid};
pub use vtu::{read_vtu, write_vtu, DataArray, DataValues, UnstructuredGrid};
