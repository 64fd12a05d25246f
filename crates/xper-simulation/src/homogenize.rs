//! `xper homogenize`: the effective elastic tensor of a fracture scene's periodic cell
//! (`xper_fracture::effective_tensor`), printed with its checks and optionally written as
//! JSON.

use std::path::Path;

use crate::fracture::build::load_model;
use crate::RunError;
use xper_fracture::Homogenized;

/// What `--json` writes: the scene, the cell and the tensor with its checks.
#[derive(serde::Serialize)]
struct Report<'a> {
    scene: &'a str,
    scene_file: String,
    cell_size: [f64; 2],
    elements: usize,
    interfaces: usize,
    periodic_interfaces: usize,
    bulk_modulus: f64,
    shear_modulus: f64,
    positive_definite: bool,
    wall_time_s: f64,
    #[serde(flatten)]
    result: &'a Homogenized,
}

/// Computes and prints the effective tensor of the periodic cell of the scene at `path`;
/// with `json`, also writes it there (atomically). A scene without `[periodic]` is bad input.
pub fn homogenize(path: &Path, json: Option<&Path>) -> Result<(), RunError> {
    let (scene, model) = load_model(path)?;
    let Some(periodic) = &model.spec.periodic else {
        return Err(RunError::BadInput(format!(
            "{}: no [periodic] section: `xper homogenize` needs a periodic cell",
            path.display()
        )));
    };
    let start = std::time::Instant::now();
    let result = xper_fracture::effective_tensor(&model)
        .map_err(|e| RunError::BadInput(format!("{}: {e}", path.display())))?;
    let wall = start.elapsed().as_secs_f64();
    let periodic_interfaces = model
        .interfaces
        .iter()
        .filter(|i| i.period != [0.0; 2])
        .count();
    let [w, h] = periodic.cell.size;
    println!(
        "{}: periodic cell {w:e} x {h:e} m, {} elements, {} interfaces ({periodic_interfaces} \
         across the sides), {} bonded points; {} unknowns solved in {wall:.2} s",
        path.display(),
        model.elements.len(),
        model.interfaces.len(),
        result.bonded_points,
        result.unknowns
    );
    println!("effective tensor C* (GPa), rows and columns [xx, yy, xy], engineering shear strain:");
    for row in &result.tensor {
        println!(
            "  [{:>12.6} {:>12.6} {:>12.6}]",
            row[0] / 1e9,
            row[1] / 1e9,
            row[2] / 1e9
        );
    }
    println!(
        "boundary-force formula against the volume average: largest difference {:.2e} of max |C*|",
        result.stress_difference
    );
    println!(
        "symmetry: max |C*_ij - C*_ji| = {:.2e} of max |C*|",
        result.asymmetry
    );
    let m = result.minors;
    println!(
        "positive definite: {} (leading minors of the symmetric part {:.4e} Pa, {:.4e} Pa^2, {:.4e} Pa^3)",
        if result.positive_definite() { "yes" } else { "NO" },
        m[0],
        m[1],
        m[2]
    );
    println!(
        "isotropic projection: in-plane bulk modulus (lambda + mu) {:.6} GPa, shear modulus {:.6} GPa",
        result.bulk() / 1e9,
        result.shear() / 1e9
    );
    if let Some(out) = json {
        let report = Report {
            scene: &scene.name,
            scene_file: path.display().to_string(),
            cell_size: periodic.cell.size,
            elements: model.elements.len(),
            interfaces: model.interfaces.len(),
            periodic_interfaces,
            bulk_modulus: result.bulk(),
            shear_modulus: result.shear(),
            positive_definite: result.positive_definite(),
            wall_time_s: wall,
            result: &result,
        };
        xper_io::write_json_atomic(out, &report)
            .map_err(|e| RunError::Runtime(format!("{}: {e}", out.display())))?;
    }
    Ok(())
}
