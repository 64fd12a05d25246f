//! Round trips and external validation of the VTU writer.

mod common;

use std::process::Command;

use xper_io::vtu::{VTK_LINE, VTK_POLYGON, VTK_TRIANGLE, VTK_VERTEX};
use xper_io::{read_vtu, write_vtu, DataArray, DataValues, UnstructuredGrid};

fn sample_grid() -> UnstructuredGrid {
    let mut g = UnstructuredGrid {
        points: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.5, 0.8, 0.0],
            [0.5, 1.2, 0.0],
            [-0.3, 0.7, 0.0],
            [2.0, 2.0, 0.0],
            [0.1 + 0.2, -1e-300, f64::MAX],
        ],
        ..Default::default()
    };
    g.add_cell(VTK_POLYGON, &[0, 1, 2, 3, 4]);
    g.add_cell(VTK_LINE, &[2, 5]);
    g.add_cell(VTK_VERTEX, &[6]);
    g.add_cell(VTK_TRIANGLE, &[0, 1, 5]);
    g.point_data.push(DataArray {
        name: "velocity".into(),
        components: 3,
        values: DataValues::F64((0..21).map(|i| i as f64 * 0.1 - 1.0).collect()),
    });
    g.point_data.push(DataArray {
        name: "body<id> & \"tag\"".into(),
        components: 1,
        values: DataValues::I32(vec![0, 0, 0, 0, 0, -7, i32::MAX]),
    });
    g.cell_data.push(DataArray {
        name: "force".into(),
        components: 1,
        values: DataValues::F64(vec![1.5, -2.25, f64::MIN_POSITIVE, 3.0]),
    });
    g.cell_data.push(DataArray {
        name: "kind".into(),
        components: 2,
        values: DataValues::I32(vec![1, 2, 3, 4, 5, 6, 7, i32::MIN]),
    });
    g
}

#[test]
fn round_trip_is_exact() {
    let dir = common::test_dir("vtu_round_trip");
    let path = dir.join("grid.vtu");
    let grid = sample_grid();
    assert_eq!(grid.num_cells(), 4);
    assert_eq!(grid.offsets, vec![5, 7, 8, 11]);
    write_vtu(&path, &grid).unwrap();
    assert!(!dir.join("grid.vtu.tmp").exists());
    let back = read_vtu(&path).unwrap();
    assert_eq!(back, grid);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("header_type=\"UInt64\""));
    assert!(text.contains("NumberOfPoints=\"7\" NumberOfCells=\"4\""));
}

#[test]
fn empty_grid_round_trips() {
    let dir = common::test_dir("vtu_empty");
    let path = dir.join("empty.vtu");
    write_vtu(&path, &UnstructuredGrid::default()).unwrap();
    let back = read_vtu(&path).unwrap();
    assert_eq!(back, UnstructuredGrid::default());
}

#[test]
fn payload_has_byte_count_header() {
    let dir = common::test_dir("vtu_payload");
    let path = dir.join("one.vtu");
    let mut g = UnstructuredGrid {
        points: vec![[1.0, 2.0, 3.0]],
        ..Default::default()
    };
    g.add_cell(VTK_VERTEX, &[0]);
    write_vtu(&path, &g).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    // types array: u64 length 1 then byte 0x01 -> base64 "AQAAAAAAAAAB".
    assert!(text.contains("AQAAAAAAAAAB"), "{text}");
}

#[test]
fn invalid_grid_is_rejected_with_path() {
    let dir = common::test_dir("vtu_invalid");
    let path = dir.join("bad.vtu");
    let mut g = sample_grid();
    g.cell_data[0].values = DataValues::F64(vec![1.0]);
    assert!(g.validate().is_err());
    let err = write_vtu(&path, &g).unwrap_err();
    assert!(err.to_string().contains("bad.vtu"), "{err}");
    assert!(!path.exists());
    let mut g = sample_grid();
    g.connectivity[0] = 99;
    assert!(g.validate().unwrap_err().contains("99"));
}

#[test]
fn reading_garbage_names_path() {
    let dir = common::test_dir("vtu_garbage");
    let path = dir.join("garbage.vtu");
    std::fs::write(&path, "hello").unwrap();
    let err = read_vtu(&path).unwrap_err();
    assert!(err.to_string().contains("garbage.vtu"), "{err}");
    let err = read_vtu(&dir.join("missing.vtu")).unwrap_err();
    assert!(err.to_string().contains("missing.vtu"), "{err}");
}

const VTK_CHECK: &str = r#"
import sys, vtk
r = vtk.vtkXMLUnstructuredGridReader()
r.SetFileName(sys.argv[1])
r.Update()
if r.GetErrorCode() != 0:
    sys.exit("reader error %d" % r.GetErrorCode())
g = r.GetOutput()
pd, cd = g.GetPointData(), g.GetCellData()
v = pd.GetArray("velocity")
print(g.GetNumberOfPoints(), g.GetNumberOfCells(), pd.GetNumberOfArrays(), cd.GetNumberOfArrays(),
      g.GetCellType(0), g.GetCell(0).GetNumberOfPoints(), g.GetCellType(1), g.GetCellType(2),
      v.GetNumberOfComponents(), repr(v.GetTuple3(1)[0]), cd.GetArray("kind").GetValue(7))
"#;

#[test]
fn python_vtk_reads_the_file() {
    let python = ["python3", "/usr/bin/python3"].into_iter().find(|py| {
        Command::new(py)
            .args(["-c", "import vtk"])
            .output()
            .is_ok_and(|o| o.status.success())
    });
    let Some(python) = python else {
        println!("skipped: python vtk module not installed");
        return;
    };
    let dir = common::test_dir("vtu_python");
    let path = dir.join("grid.vtu");
    write_vtu(&path, &sample_grid()).unwrap();
    let out = Command::new(python)
        .args(["-c", VTK_CHECK])
        .arg(&path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(stdout.trim(), "7 4 2 2 7 5 3 1 3 -0.7 -2147483648");

    let empty = dir.join("empty.vtu");
    write_vtu(&empty, &UnstructuredGrid::default()).unwrap();
    let out = Command::new(python)
        .args(["-c", "import sys, vtk\nr = vtk.vtkXMLUnstructuredGridReader()\nr.SetFileName(sys.argv[1])\nr.Update()\nassert r.GetErrorCode() == 0\nprint(r.GetOutput().GetNumberOfPoints(), r.GetOutput().GetNumberOfCells())"])
        .arg(&empty)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "0 0");
}
