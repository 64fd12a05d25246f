//! Validation cases of periodic homogenization: effective tensors of periodic cells
//! ([`xper_fracture::effective_tensor`]) against exact answers (one material, laminates),
//! bounds (Hashin-Shtrikman) and the compliance of the cohesive zones; cells stepped under a
//! macroscopic strain or stress history against the static answer, the bar-and-crack curve
//! and the energy budget; a crack crossing the cell's sides. Each comparison is a [`Case`],
//! asserted by the tests of this crate and written in VALIDATION.md.
//!
//! Units: m, s, Pa (Pa/m for interface stiffnesses), J; plane strain, thickness 1 m.
//!
//! - [`one_material`], [`laminate`], [`hashin_shtrikman`], [`interface_compliance`]: the
//!   undamaged cell's tensor by three static solves;
//! - [`slow_strain`], [`mixed_loading`]: a heterogeneous cell loaded slowly in time;
//! - [`single_line`], [`reentering_crack`]: cells that break.
//!
//! Each error is a relative deviation (normalisation in the case's reference) or, for a check
//! without a natural number, the size of the violation (0 when satisfied); NaN fails.

mod breaking;
mod runs;
mod setup;

use crate::case::{case, indicator};
pub use crate::Case;
pub use breaking::{reentering_crack, single_line};
pub use runs::{mixed_loading, slow_strain};
use setup::*;
use xper_fem::Material;
use xper_fracture::{effective_tensor, FractureModel, Homogenized};
use xper_mesh::{periodic_cell, Circle, Mesh, PeriodicCellSpec, RandomCircles};

/// Every case of this module, in order.
pub fn all_cases() -> Result<Vec<Case>, String> {
    Ok([
        one_material()?,
        laminate()?,
        hashin_shtrikman()?,
        interface_compliance()?,
        slow_strain()?,
        mixed_loading()?,
        single_line()?,
        reentering_crack()?,
    ]
    .concat())
}

/// The undamaged cell of `mesh` with `materials` (`[matrix, inclusion]`) and cohesive zones of
/// stiffness `c` (Pa/m) everywhere, at zero strain: the model `effective_tensor` reads.
fn static_cell(mesh: Mesh, materials: [Material; 2], c: f64) -> Result<FractureModel, String> {
    cell_model(mesh, materials, stiff_zone(c), fixed(), 1e-6)
}

/// The effective tensor of `m`, an error naming the scenario if the solve fails.
fn tensor(scenario: &str, m: &FractureModel) -> Result<Homogenized, String> {
    effective_tensor(m).map_err(|e| format!("{scenario}: effective tensor: {e}"))
}

/// The case "the tensor is sound": symmetric, both stress measures equal (to the accuracy of
/// the solve: interfaces up to 1e8 times stiffer than the elements give a condition number
/// near 1e10, refined twice), positive definite.
fn sound(scenario: &str, c: &Homogenized) -> Case {
    let error = c
        .asymmetry
        .max(c.stress_difference)
        .max(indicator(c.positive_definite()));
    case(
        format!("{scenario}: the tensor is sound"),
        "symmetric and positive definite, boundary-force and volume-average stresses equal; \
         error max(asymmetry, stress difference) / largest entry, 1 if not positive definite"
            .into(),
        format!(
            "asymmetry {:.1e}, stress difference {:.1e}, leading minors {:.3e}, {:.3e}, {:.3e} Pa^k",
            c.asymmetry, c.stress_difference, c.minors[0], c.minors[1], c.minors[2]
        ),
        error,
        1e-6,
    )
}

/// A 1 m x 0.8 m cell with a circle of radius 0.2 m centred on the left side (wrapping
/// across it), element size `h`.
fn circle_cell(h: f64) -> PeriodicCellSpec {
    PeriodicCellSpec {
        width: 1.0,
        height: 0.8,
        circles: vec![Circle {
            center: [0.0, 0.4],
            radius: 0.2,
        }],
        rectangles: Vec::new(),
        random: None,
        element_size: h,
    }
}

/// One material (E = 100 GPa, nu = 0.3) on a 10 x 8 grid and on a generated cell whose
/// inclusion has the matrix's material, interfaces `C_N h / E = 1e8` (h = 0.1 m): C* = C.
/// The interfaces' compliance shifts C* by about 3e-8 ([`interface_compliance`]), so 1e-6
/// bounds the solve.
pub fn one_material() -> Result<Vec<Case>, String> {
    let (e, nu, h) = (100e9, 0.3, 0.1);
    let meshes = [
        ("grid 10 x 8", grid(10, 8, 1.0, 0.8, |p| p[0] < 0.5)?),
        (
            "generated cell",
            periodic_cell(&circle_cell(h)).map_err(|e| e.to_string())?,
        ),
    ];
    let mut cases = Vec::new();
    for (name, mesh) in meshes {
        let scenario = format!("periodic cell of one material, {name}");
        let m = static_cell(mesh, [elastic(e, nu); 2], 1e8 * e / h)?;
        let c = tensor(&scenario, &m)?;
        cases.push(sound(&scenario, &c));
        let err = relative_difference(&c.tensor, &tangent(e, nu));
        cases.push(case(
            format!("{scenario}: C* = C"),
            "the material's plane-strain tangent (C11 = 134.6 GPa); error max |C* - C| / max |C|"
                .into(),
            format!(
                "C11 {:.6e}, C12 {:.6e}, C33 {:.6e} Pa",
                c.tensor[0][0], c.tensor[0][1], c.tensor[2][2]
            ),
            err,
            1e-6,
        ));
    }
    Ok(cases)
}

/// Layers normal to x (the second phase, E = 990 GPa and nu = 0.2, in 0.3 < x < 0.6 of a 1 m
/// x 0.5 m cell of the bimaterial's matrix; a contrast of 10, at which a wrong formula would
/// not pass): the exact laminate tensor (uniform sigma_xx and sigma_xy, uniform eps_yy).
pub fn laminate() -> Result<Vec<Case>, String> {
    const S: &str = "laminate, layers normal to x, contrast 10";
    const STIFF: (f64, f64) = (990e9, 0.2);
    let (x0, x1, h) = (0.3, 0.6, 0.05);
    let fraction = x1 - x0;
    let mesh = grid(20, 4, 1.0, 0.5, |p| p[0] > x0 && p[0] < x1)?;
    let materials = [elastic(MATRIX.0, MATRIX.1), elastic(STIFF.0, STIFF.1)];
    let m = static_cell(mesh, materials, 1e8 * STIFF.0 / h)?;
    let c = tensor(S, &m)?;
    let p = |(e, nu): (f64, f64)| {
        let (l, mu) = lame(e, nu);
        (l, mu, l + 2.0 * mu)
    };
    let average =
        |f: &dyn Fn((f64, f64)) -> f64| (1.0 - fraction) * f(MATRIX) + fraction * f(STIFF);
    let inv_m = average(&|q| 1.0 / p(q).2);
    let c11 = 1.0 / inv_m;
    let c12 = average(&|q| p(q).0 / p(q).2) / inv_m;
    let c22 = average(&|q| p(q).2 - p(q).0 * p(q).0 / p(q).2) + c12 * c12 / c11;
    let c33 = 1.0 / average(&|q| 1.0 / p(q).1);
    let mut cases = vec![sound(S, &c)];
    for (got, want, name, formula) in [
        (c.tensor[0][0], c11, "C1111", "<1/(lambda + 2 mu)>^-1"),
        (
            c.tensor[0][1],
            c12,
            "C1122",
            "<lambda/(lambda + 2 mu)> C1111",
        ),
        (
            c.tensor[1][1],
            c22,
            "C2222",
            "<4 mu (lambda + mu)/(lambda + 2 mu)> + C1122^2 / C1111",
        ),
        (c.tensor[2][2], c33, "C1212", "<1/mu>^-1"),
    ] {
        cases.push(case(
            format!("{S}: {name}"),
            format!("exact laminate: {name} = {formula} = {want:.6e} Pa; error relative"),
            format!("{got:.6e} Pa"),
            (got - want).abs() / want,
            1e-4,
        ));
    }
    Ok(cases)
}

/// A unit cell with random circles (radius 0.08 m, minimum spacing 0.02 m, seed 3) at an area
/// fraction of about 0.2, the bimaterial's moduli (matrix 99 GPa, inclusions 135 GPa), stiff
/// interfaces: the in-plane bulk and shear moduli of the tensor's isotropic projection lie
/// within the Hashin-Shtrikman bounds at the mesh's own fraction (h = 0.04, 0.02, 0.01 m),
/// and change less between the two finer meshes than between the two coarser.
pub fn hashin_shtrikman() -> Result<Vec<Case>, String> {
    const S: &str = "random circles at an area fraction of 0.2, bimaterial moduli";
    let mut cases = Vec::new();
    let mut moduli: Vec<(f64, f64)> = Vec::new();
    for h in [0.04, 0.02, 0.01] {
        let spec = PeriodicCellSpec {
            width: 1.0,
            height: 1.0,
            circles: Vec::new(),
            rectangles: Vec::new(),
            random: Some(RandomCircles {
                fraction: 0.2,
                radius: 0.08,
                min_spacing: 0.02,
                seed: 3,
            }),
            element_size: h,
        };
        let materials = [
            elastic(MATRIX.0, MATRIX.1),
            elastic(INCLUSION.0, INCLUSION.1),
        ];
        let mesh = periodic_cell(&spec).map_err(|e| e.to_string())?;
        let m = static_cell(mesh, materials, 1e8 * INCLUSION.0 / h)?;
        let scenario = format!("{S}, h = {h} m");
        let c = tensor(&scenario, &m)?;
        cases.push(sound(&scenario, &c));
        let areas = m.mesh.region_areas();
        let f2 = areas[1] / (areas[0] + areas[1]);
        let (kb, mb) = setup::hashin_shtrikman(f2);
        for (name, value, [lo, hi]) in [("bulk", c.bulk(), kb), ("shear", c.shear(), mb)] {
            cases.push(case(
                format!("{scenario}: {name} modulus within the Hashin-Shtrikman bounds"),
                format!(
                    "2D Hashin-Shtrikman bounds at the mesh's fraction {f2:.4}: {lo:.6e} to \
                     {hi:.6e} Pa (Torquato 2002, eqs. 21.23-21.24); error = distance outside / bound"
                ),
                format!("{value:.6e} Pa"),
                ((lo - value).max(value - hi)).max(0.0) / lo,
                0.0,
            ));
        }
        moduli.push((c.bulk(), c.shear()));
    }
    let change =
        |a: (f64, f64), b: (f64, f64)| ((b.0 - a.0) / b.0).abs().max(((b.1 - a.1) / b.1).abs());
    let changes = [change(moduli[0], moduli[1]), change(moduli[1], moduli[2])];
    cases.push(case(
        format!("{S}: the moduli converge under refinement"),
        "the change h = 0.02 -> 0.01 m smaller than h = 0.04 -> 0.02 m (error 1 if not)".into(),
        format!(
            "relative changes {:.3e} then {:.3e}",
            changes[0], changes[1]
        ),
        indicator(changes[1] < changes[0]),
        0.0,
    ));
    Ok(cases)
}

/// One material (E = 100 GPa, nu = 0.3) on the cell of [`one_material`], interfaces of
/// stiffness `C_N = C_T = r E / h` for r = 1 to 1e5: the modulus rises monotonically to the
/// bulk value as C_N grows; the added compliance stays below the series estimate (an upper
/// bound by minimum complementary energy) and within 3 % of it; once the interfaces are
/// stiff, the drop of the modulus is linear in E / (C_N h): tenfold for a tenfold C_N.
pub fn interface_compliance() -> Result<Vec<Case>, String> {
    const S: &str = "compliant cohesive zones, one material";
    let (e, nu, h) = (100e9, 0.3, 0.1);
    let s_bulk = inverse(&tangent(e, nu));
    let (mut monotone, mut last) = (true, 0.0);
    let (mut lowest, mut highest) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut drops = Vec::new();
    let mut cases = Vec::new();
    for ratio in [1.0, 10.0, 100.0, 1e3, 1e4, 1e5] {
        let mesh = periodic_cell(&circle_cell(h)).map_err(|e| e.to_string())?;
        let m = static_cell(mesh, [elastic(e, nu); 2], ratio * e / h)?;
        let c = tensor(S, &m)?;
        if ratio == 1.0 {
            cases.push(sound(&format!("{S}, C_N h / E = 1"), &c));
        }
        let s = inverse(&c.tensor);
        let estimate = series_compliance(&m, e, nu);
        let modulus = 1.0 / s[0][0];
        monotone &= modulus > last && modulus < 1.0 / s_bulk[0][0];
        last = modulus;
        for k in 0..3 {
            let share = (s[k][k] - s_bulk[k][k]) / (estimate[k][k] - s_bulk[k][k]);
            lowest = lowest.min(share);
            highest = highest.max(share);
        }
        drops.push(1.0 - modulus * s_bulk[0][0]);
    }
    let n = drops.len();
    let tenfold: Vec<f64> = drops[n - 3..].windows(2).map(|w| w[0] / w[1]).collect();
    cases.extend([
        case(
            format!("{S}: the modulus rises monotonically to the bulk value"),
            "1 / S*_1111 increasing with C_N h / E = 1, 10, ..., 1e5 and below 1 / S_1111 \
             (error 1 if not)"
                .into(),
            format!(
                "modulus drop 1 - E*/E' from {:.3e} to {:.3e}",
                drops[0],
                drops[n - 1]
            ),
            indicator(monotone),
            0.0,
        ),
        case(
            format!("{S}: added compliance below the series estimate"),
            "minimum complementary energy: S*_kk - S_kk <= the series estimate, error = the \
             largest ratio - 1"
                .into(),
            format!("largest ratio {highest:.6}"),
            (highest - 1.0).max(0.0),
            1e-9,
        ),
        case(
            format!("{S}: added compliance near the series estimate"),
            "the series estimate (every point carrying the uniform stress's traction); error = \
             1 - the smallest ratio"
                .into(),
            format!("smallest ratio {lowest:.4}"),
            1.0 - lowest,
            3e-2,
        ),
        case(
            format!("{S}: drop linear in E / (C_N h) for stiff interfaces"),
            "the drop falls tenfold when C_N grows tenfold from 1e3 E / h on; error \
             max |ratio / 10 - 1|"
                .into(),
            format!("ratios {:.4} and {:.4}", tenfold[0], tenfold[1]),
            tenfold
                .iter()
                .fold(0.0f64, |a, r| a.max((r / 10.0 - 1.0).abs())),
            5e-3,
        ),
    ]);
    Ok(cases)
}
