//! Hand-written VTK XML `ImageData` (`.vti`) writer for uniform grids with cell data (a fluid
//! on its MAC grid: velocity and pressure interpolated to cell centres), inline base64 binary
//! in the same encoding as the `.vtu` writer.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use crate::atomic::{with_path, write_atomic};
use crate::vtu::{f64_bytes, push_array};

/// A uniform grid of `cells[0] x cells[1]` square cells with per-cell arrays.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ImageGrid {
    /// Cells along x and y.
    pub cells: [usize; 2],
    /// Lower-left corner (m).
    pub origin: [f64; 2],
    /// Cell side (m).
    pub spacing: f64,
    /// Per-cell arrays: name, components, values (row-major, x fastest).
    pub cell_data: Vec<(String, usize, Vec<f64>)>,
}

/// Writes `grid` to `path` atomically; every array must hold cells x components values.
pub fn write_vti(path: &Path, grid: &ImageGrid) -> io::Result<()> {
    let n = grid.cells[0] * grid.cells[1];
    for (name, comps, values) in &grid.cell_data {
        if values.len() != n * comps {
            return Err(with_path(
                path,
                format!(
                    "cell data '{name}' has {} values, expected {n} x {comps}",
                    values.len()
                ),
                io::ErrorKind::InvalidInput,
            ));
        }
    }
    let [nx, ny] = grid.cells;
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
    let _ = writeln!(
        out,
        "  <ImageData WholeExtent=\"0 {nx} 0 {ny} 0 0\" Origin=\"{:e} {:e} 0\" Spacing=\"{:e} {:e} 1\">",
        grid.origin[0], grid.origin[1], grid.spacing, grid.spacing
    );
    let _ = writeln!(
        out,
        "    <Piece Extent=\"0 {nx} 0 {ny} 0 0\">\n      <CellData>"
    );
    for (name, comps, values) in &grid.cell_data {
        push_array(
            &mut out,
            "        ",
            "Float64",
            Some(name),
            *comps,
            &f64_bytes(values),
        );
    }
    out.push_str("      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n");
    write_atomic(path, out.as_bytes())
}
