//! Hand-written VTK XML `UnstructuredGrid` (`.vtu`) writer and a minimal
//! reader of exactly what the writer produces.
//!
//! Data arrays are stored inline as base64 (`format="binary"`) with
//! `header_type="UInt64"` and little-endian byte order: each payload is an
//! 8-byte little-endian byte count followed by the raw little-endian values.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use crate::atomic::{read_text, with_path, write_atomic};
use crate::base64;
use crate::xml::{attribute, xml_escape};

/// VTK cell type of a single point.
pub const VTK_VERTEX: u8 = 1;
/// VTK cell type of a two-point segment.
pub const VTK_LINE: u8 = 3;
/// VTK cell type of a triangle.
pub const VTK_TRIANGLE: u8 = 5;
/// VTK cell type of a polygon with any number of vertices.
pub const VTK_POLYGON: u8 = 7;

/// Values of a data array, stored flat (tuple after tuple).
#[derive(Debug, Clone, PartialEq)]
pub enum DataValues {
    /// Written as VTK `Float64`.
    F64(Vec<f64>),
    /// Written as VTK `Int32`.
    I32(Vec<i32>),
}

impl DataValues {
    /// Number of scalar values (tuples x components).
    pub fn len(&self) -> usize {
        match self {
            DataValues::F64(v) => v.len(),
            DataValues::I32(v) => v.len(),
        }
    }

    /// True when there are no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A named point or cell data array with `components` values per tuple.
#[derive(Debug, Clone, PartialEq)]
pub struct DataArray {
    /// Array name shown in ParaView.
    pub name: String,
    /// Values per point or cell (1 for scalars, 3 for vectors).
    pub components: usize,
    /// The flat values; length must be tuples x components.
    pub values: DataValues,
}

/// An unstructured grid: points, cells given by connectivity/offsets/types,
/// and optional point and cell data.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct UnstructuredGrid {
    /// Point coordinates (z = 0 for 2D data).
    pub points: Vec<[f64; 3]>,
    /// Point ids of all cells, concatenated.
    pub connectivity: Vec<i64>,
    /// End offset in `connectivity` of each cell.
    pub offsets: Vec<i64>,
    /// VTK cell type of each cell (`VTK_VERTEX`, `VTK_LINE`, ...).
    pub cell_types: Vec<u8>,
    /// Arrays with one tuple per point.
    pub point_data: Vec<DataArray>,
    /// Arrays with one tuple per cell.
    pub cell_data: Vec<DataArray>,
}

impl UnstructuredGrid {
    /// Appends a cell of `cell_type` made of the given point ids.
    pub fn add_cell(&mut self, cell_type: u8, point_ids: &[i64]) {
        self.connectivity.extend_from_slice(point_ids);
        self.offsets.push(self.connectivity.len() as i64);
        self.cell_types.push(cell_type);
    }

    /// Number of cells.
    pub fn num_cells(&self) -> usize {
        self.cell_types.len()
    }

    /// Checks that offsets, connectivity and data array lengths are
    /// consistent with the number of points and cells.
    pub fn validate(&self) -> Result<(), String> {
        let n_points = self.points.len();
        let n_cells = self.num_cells();
        if self.offsets.len() != n_cells {
            return Err(format!(
                "{} offsets for {} cell types",
                self.offsets.len(),
                n_cells
            ));
        }
        let mut prev = 0i64;
        for (i, &o) in self.offsets.iter().enumerate() {
            if o < prev {
                return Err(format!("offset {i} ({o}) is smaller than the previous one"));
            }
            prev = o;
        }
        if prev as usize != self.connectivity.len() {
            return Err(format!(
                "last offset {} does not match connectivity length {}",
                prev,
                self.connectivity.len()
            ));
        }
        if let Some(&id) = self
            .connectivity
            .iter()
            .find(|&&id| id < 0 || id as usize >= n_points)
        {
            return Err(format!("point id {id} out of range 0..{n_points}"));
        }
        for (kind, arrays, n) in [
            ("point", &self.point_data, n_points),
            ("cell", &self.cell_data, n_cells),
        ] {
            for a in arrays {
                if a.components == 0 {
                    return Err(format!("{kind} data '{}' has 0 components", a.name));
                }
                if a.values.len() != n * a.components {
                    return Err(format!(
                        "{kind} data '{}' has {} values, expected {} x {}",
                        a.name,
                        a.values.len(),
                        n,
                        a.components
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Base64 payload: 8-byte little-endian byte count, then the raw bytes.
fn payload(raw: &[u8]) -> String {
    let mut bytes = Vec::with_capacity(raw.len() + 8);
    bytes.extend_from_slice(&(raw.len() as u64).to_le_bytes());
    bytes.extend_from_slice(raw);
    base64::encode(&bytes)
}

/// Appends one `<DataArray>` element.
pub(crate) fn push_array(
    out: &mut String,
    indent: &str,
    vtk_type: &str,
    name: Option<&str>,
    comps: usize,
    raw: &[u8],
) {
    let _ = write!(out, "{indent}<DataArray type=\"{vtk_type}\"");
    if let Some(name) = name {
        let _ = write!(out, " Name=\"{}\"", xml_escape(name));
    }
    let _ = writeln!(
        out,
        " NumberOfComponents=\"{comps}\" format=\"binary\">\n{indent}  {}\n{indent}</DataArray>",
        payload(raw)
    );
}

pub(crate) fn f64_bytes(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn i64_bytes(v: &[i64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn push_data(out: &mut String, tag: &str, arrays: &[DataArray]) {
    let _ = writeln!(out, "      <{tag}>");
    for a in arrays {
        let (ty, raw) = match &a.values {
            DataValues::F64(v) => ("Float64", f64_bytes(v)),
            DataValues::I32(v) => ("Int32", v.iter().flat_map(|x| x.to_le_bytes()).collect()),
        };
        push_array(out, "        ", ty, Some(&a.name), a.components, &raw);
    }
    let _ = writeln!(out, "      </{tag}>");
}

/// Renders `grid` as the text of a `.vtu` file (no validation).
fn render(grid: &UnstructuredGrid) -> String {
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\"?>\n");
    out.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    out.push_str("  <UnstructuredGrid>\n");
    let _ = writeln!(
        out,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        grid.points.len(),
        grid.num_cells()
    );
    push_data(&mut out, "PointData", &grid.point_data);
    push_data(&mut out, "CellData", &grid.cell_data);
    out.push_str("      <Points>\n");
    let coords: Vec<f64> = grid.points.iter().flatten().copied().collect();
    push_array(
        &mut out,
        "        ",
        "Float64",
        Some("Points"),
        3,
        &f64_bytes(&coords),
    );
    out.push_str("      </Points>\n      <Cells>\n");
    let ind = "        ";
    push_array(
        &mut out,
        ind,
        "Int64",
        Some("connectivity"),
        1,
        &i64_bytes(&grid.connectivity),
    );
    push_array(
        &mut out,
        ind,
        "Int64",
        Some("offsets"),
        1,
        &i64_bytes(&grid.offsets),
    );
    push_array(&mut out, ind, "UInt8", Some("types"), 1, &grid.cell_types);
    out.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    out
}

/// Validates `grid` and writes it to `path` atomically as a VTK XML
/// unstructured grid with inline base64 binary data.
pub fn write_vtu(path: &Path, grid: &UnstructuredGrid) -> io::Result<()> {
    grid.validate().map_err(|e| {
        with_path(
            path,
            format!("invalid grid: {e}"),
            io::ErrorKind::InvalidInput,
        )
    })?;
    write_atomic(path, render(grid).as_bytes())
}

/// A data array as read back from a file, before it is put in place.
struct RawArray {
    vtk_type: String,
    name: String,
    components: usize,
    bytes: Vec<u8>,
}

/// Splits the decoded payload after its 8-byte length header.
fn strip_header(decoded: Vec<u8>) -> Result<Vec<u8>, String> {
    if decoded.len() < 8 {
        return Err("binary payload shorter than its header".to_string());
    }
    let mut len = [0u8; 8];
    len.copy_from_slice(&decoded[..8]);
    let n = u64::from_le_bytes(len) as usize;
    if decoded.len() - 8 != n {
        return Err(format!(
            "header says {n} bytes, payload has {}",
            decoded.len() - 8
        ));
    }
    Ok(decoded[8..].to_vec())
}

/// Converts little-endian bytes to values of size `N` with `f`.
fn from_le<T, const N: usize>(bytes: &[u8], f: fn([u8; N]) -> T) -> Result<Vec<T>, String> {
    if bytes.len() % N != 0 {
        return Err(format!("{} bytes is not a multiple of {N}", bytes.len()));
    }
    Ok(bytes
        .chunks_exact(N)
        .map(|c| {
            let mut a = [0u8; N];
            a.copy_from_slice(c);
            f(a)
        })
        .collect())
}

fn to_values(a: &RawArray) -> Result<DataValues, String> {
    match a.vtk_type.as_str() {
        "Float64" => Ok(DataValues::F64(from_le(&a.bytes, f64::from_le_bytes)?)),
        "Int32" => Ok(DataValues::I32(from_le(&a.bytes, i32::from_le_bytes)?)),
        t => Err(format!("unsupported data type {t} for array '{}'", a.name)),
    }
}

/// Parses the text written by [`render`].
fn parse(text: &str) -> Result<UnstructuredGrid, String> {
    if !text.contains("type=\"UnstructuredGrid\"") || !text.contains("header_type=\"UInt64\"") {
        return Err("not a UInt64-header UnstructuredGrid VTK file".to_string());
    }
    let mut grid = UnstructuredGrid::default();
    let mut section = String::new();
    let mut rest = text;
    let mut n_points = None;
    while let Some(open) = rest.find('<') {
        let close = rest[open..].find('>').ok_or("unterminated tag")? + open;
        let tag = &rest[open + 1..close];
        rest = &rest[close + 1..];
        let tag_name = tag.split_whitespace().next().unwrap_or("");
        match tag_name {
            "PointData" | "CellData" | "Points" | "Cells" => section = tag_name.to_string(),
            "Piece" => {
                let np = attribute(tag, "NumberOfPoints").ok_or("Piece without NumberOfPoints")?;
                n_points = Some(
                    np.parse::<usize>()
                        .map_err(|e| format!("NumberOfPoints: {e}"))?,
                );
            }
            "DataArray" => {
                let end = rest.find("</DataArray>").ok_or("unterminated DataArray")?;
                let content = &rest[..end];
                rest = &rest[end + "</DataArray>".len()..];
                if attribute(tag, "format").as_deref() != Some("binary") {
                    return Err("only format=\"binary\" arrays are supported".to_string());
                }
                let components = match attribute(tag, "NumberOfComponents") {
                    Some(c) => c
                        .parse::<usize>()
                        .map_err(|e| format!("NumberOfComponents: {e}"))?,
                    None => 1,
                };
                let raw = RawArray {
                    vtk_type: attribute(tag, "type").ok_or("DataArray without type")?,
                    name: attribute(tag, "Name").unwrap_or_default(),
                    components,
                    bytes: strip_header(base64::decode(content)?)?,
                };
                place(&mut grid, &section, raw)?;
            }
            _ => {}
        }
    }
    if n_points != Some(grid.points.len()) {
        return Err(format!(
            "NumberOfPoints {:?} does not match {} points read",
            n_points,
            grid.points.len()
        ));
    }
    grid.validate()?;
    Ok(grid)
}

/// Stores a parsed array in the part of `grid` named by `section`.
fn place(grid: &mut UnstructuredGrid, section: &str, a: RawArray) -> Result<(), String> {
    let expect = |t: &str| {
        if a.vtk_type == t {
            Ok(())
        } else {
            Err(format!(
                "array '{}' has type {}, expected {t}",
                a.name, a.vtk_type
            ))
        }
    };
    match section {
        "Points" => {
            expect("Float64")?;
            if a.components != 3 {
                return Err("points must have 3 components".to_string());
            }
            let v = from_le(&a.bytes, f64::from_le_bytes)?;
            grid.points = v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        }
        "Cells" => match a.name.as_str() {
            "connectivity" | "offsets" => {
                expect("Int64")?;
                let v = from_le(&a.bytes, i64::from_le_bytes)?;
                if a.name == "connectivity" {
                    grid.connectivity = v;
                } else {
                    grid.offsets = v;
                }
            }
            "types" => {
                expect("UInt8")?;
                grid.cell_types = a.bytes;
            }
            other => return Err(format!("unknown Cells array '{other}'")),
        },
        "PointData" | "CellData" => {
            let array = DataArray {
                values: to_values(&a)?,
                name: a.name,
                components: a.components,
            };
            if section == "PointData" {
                grid.point_data.push(array);
            } else {
                grid.cell_data.push(array);
            }
        }
        _ => return Err(format!("DataArray '{}' outside a known section", a.name)),
    }
    Ok(())
}

/// Reads a `.vtu` file written by [`write_vtu`] (inline base64 binary,
/// UInt64 headers, little-endian). Other VTK files are not supported.
pub fn read_vtu(path: &Path) -> io::Result<UnstructuredGrid> {
    let text = read_text(path)?;
    parse(&text).map_err(|e| with_path(path, e, io::ErrorKind::InvalidData))
}
