//! Every shared problem file loads, with the sizes, values and structure documented in
//! `shared/fclib/SOURCES.md`; global problems reduce to the same W and q as an
//! independent dense (or diagonal) computation. Run with `--nocapture` for the table.

mod common;

use common::{dense, dense_reduction, files, max_diff, norm, shared_dir};
use std::path::Path;
use xper_fclib::{read_problem, CsrMatrix, FrictionProblem, GlobalFrictionProblem, Problem};

/// What SOURCES.md says about a file, and nnz(W) of its local form (regression value).
struct Expect {
    file: &'static str,
    global: bool,
    dim: usize,
    contacts: usize,
    /// Number of global unknowns (global files only).
    dofs: usize,
    nnz_w: usize,
    /// The friction coefficients that occur.
    mu: &'static [f64],
    /// |q| is about 0 (documented trivial problems).
    trivial: bool,
}

const fn e(
    file: &'static str,
    global: bool,
    dim: usize,
    contacts: usize,
    dofs: usize,
    nnz_w: usize,
    mu: &'static [f64],
) -> Expect {
    Expect {
        file,
        global,
        dim,
        contacts,
        dofs,
        nnz_w,
        mu,
        trivial: false,
    }
}

const SICONOS: &[Expect] = &[
    e(
        "FC2D_SliderCrankLagrangian00000.dat",
        false,
        2,
        2,
        0,
        16,
        &[0.01],
    ),
    e(
        "FC2D_SliderCrankLagrangian00001.dat",
        false,
        2,
        2,
        0,
        16,
        &[0.01],
    ),
    e(
        "FrictionContactProblem00031.dat",
        false,
        2,
        11,
        0,
        60,
        &[0.9],
    ),
    e(
        "FrictionContactProblem00071.dat",
        false,
        2,
        89,
        0,
        1148,
        &[0.9],
    ),
    e(
        "FrictionContactProblem00237.dat",
        false,
        2,
        376,
        0,
        6624,
        &[0.9],
    ),
    e(
        "FrictionContactProblem00374.dat",
        false,
        2,
        28,
        0,
        76,
        &[0.9],
    ),
    Expect {
        trivial: true,
        ..e(
            "FrictionContactProblem00394.dat",
            false,
            2,
            6,
            0,
            24,
            &[0.9],
        )
    },
    e(
        "FrictionContactProblem00727.dat",
        false,
        2,
        367,
        0,
        6356,
        &[0.9],
    ),
    Expect {
        trivial: true,
        ..e(
            "fc2d_granularflowonwall_00667_00000.dat",
            false,
            2,
            667,
            0,
            3822,
            &[0.5],
        )
    },
    e(
        "fc2d_granularflowonwall_02020_00213.dat",
        false,
        2,
        2020,
        0,
        20616,
        &[0.5],
    ),
    e(
        "fc2d_granularflowonwall_07002_00801.dat",
        false,
        2,
        7002,
        0,
        125806,
        &[0.5],
    ),
    Expect {
        trivial: true,
        ..e(
            "gfc2d_granularflowonwall_00000_00117.dat",
            true,
            2,
            0,
            900,
            0,
            &[],
        )
    },
    e(
        "gfc2d_granularflowonwall_00069_00350.dat",
        true,
        2,
        69,
        900,
        508,
        &[0.5],
    ),
    e(
        "gfc2d_granularflowonwall_00230_00206.dat",
        true,
        2,
        230,
        9000,
        1056,
        &[0.5],
    ),
];

const HDF5_LOCAL: &[Expect] = &[
    e(
        "BoxesStack_local_problem_test.hdf5",
        false,
        3,
        48,
        0,
        4896,
        &[0.7],
    ),
    e("Capsules-i125-1213.hdf5", false, 3, 286, 0, 11772, &[0.7]),
    e(
        "LMGC_100_PR_PerioBox-i00361-60-03000.hdf5",
        false,
        3,
        60,
        0,
        9576,
        &[0.3, 0.5],
    ),
];

const HDF5_GLOBAL: &[Expect] = &[
    e("Box_Stacks-i0122-82-5.hdf5", true, 3, 82, 450, 2016, &[0.3]),
    e("LMGC_CubeH8.hdf5", true, 3, 1, 162, 9, &[0.3]),
    e(
        "LMGC_GlobalFrictionContactProblem00046.hdf5",
        true,
        3,
        9,
        162,
        729,
        &[0.3],
    ),
    e(
        "Spheres-i099-356-679.hdf5",
        true,
        3,
        356,
        12000,
        7344,
        &[0.7],
    ),
    e(
        "spheres-in-a-box-98-i10000-256-10.hdf5",
        true,
        3,
        256,
        588,
        17424,
        &[0.1],
    ),
];

/// `W = H^T M^-1 H`, `q = H^T M^-1 f + w` computed independently: directly when `M` is
/// diagonal, by dense elimination otherwise (small `M` only).
fn reference(p: &GlobalFrictionProblem) -> (Vec<Vec<f64>>, Vec<f64>) {
    let m = dense_diagonal(&p.m);
    let Some(d) = m else {
        assert!(
            p.dof_count() <= 500,
            "no dense reference for a large coupled M"
        );
        return dense_reduction(&p.m, &p.h, &p.f, &p.w);
    };
    let k = p.h.ncols;
    let hd = dense(&p.h.transpose()); // k x n
    let mut w = vec![vec![0.0; k]; k];
    let mut q = p.w.clone();
    for i in 0..k {
        for r in (0..p.dof_count()).filter(|&r| hd[i][r] != 0.0) {
            q[i] += hd[i][r] * p.f[r] / d[r];
            for j in 0..k {
                w[i][j] += hd[i][r] * hd[j][r] / d[r];
            }
        }
    }
    (w, q)
}

/// The diagonal of `m` if `m` is diagonal.
fn dense_diagonal(m: &CsrMatrix) -> Option<Vec<f64>> {
    (0..m.nrows)
        .map(|i| match &m.col_idx[m.row_ptr[i]..m.row_ptr[i + 1]] {
            [j] if *j == i => Some(m.values[m.row_ptr[i]]),
            _ => None,
        })
        .collect()
}

/// Checks one file against its expectations and returns its local form.
fn check(path: &Path, ex: &Expect) -> FrictionProblem {
    let name = ex.file;
    let p = read_problem(path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(matches!(p, Problem::Global(_)), ex.global, "{name}: form");
    assert_eq!(
        (p.dim(), p.contact_count()),
        (ex.dim, ex.contacts),
        "{name}: dim, contacts"
    );
    let local = match &p {
        Problem::Local(l) => l.clone(),
        Problem::Global(g) => {
            assert_eq!(g.dof_count(), ex.dofs, "{name}: unknowns");
            assert_eq!(
                (g.m.nrows, g.h.nrows, g.h.ncols),
                (ex.dofs, ex.dofs, ex.dim * ex.contacts)
            );
            let l = g.to_local().unwrap_or_else(|e| panic!("{name}: {e}"));
            if ex.contacts > 0 {
                let (wd, qd) = reference(g);
                let scale = wd.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
                let dw = max_diff(&l.w, &wd);
                assert!(
                    dw <= 1e-10 * scale,
                    "{name}: W off by {dw:e} (max |W| {scale:e})"
                );
                let dq =
                    l.q.iter()
                        .zip(&qd)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max);
                assert!(dq <= 1e-10 * norm(&qd), "{name}: q off by {dq:e}");
            }
            l
        }
    };
    let k = ex.dim * ex.contacts;
    assert_eq!(
        (local.w.nrows, local.w.ncols, local.q.len()),
        (k, k, k),
        "{name}: sizes"
    );
    assert!(local.w.is_finite(), "{name}: W finite");
    assert_eq!(local.w.nnz(), ex.nnz_w, "{name}: nnz(W)");
    for a in 0..ex.contacts {
        let wnn = local.w.get(ex.dim * a, ex.dim * a);
        assert!(wnn > 0.0, "{name}: W_nn of contact {a} is {wnn}");
    }
    for mu in &local.mu {
        assert!(ex.mu.contains(mu), "{name}: unexpected mu {mu}");
    }
    let q = norm(&local.q);
    if ex.trivial {
        assert!(q < 1e-14, "{name}: |q| = {q:e}, documented as about 0");
    } else {
        assert!(q > 1e-6, "{name}: |q| = {q:e}");
    }
    local
}

fn check_all(sub: &str, expected: &[Expect]) -> Vec<(String, FrictionProblem)> {
    let Some(shared) = shared_dir() else {
        return Vec::new();
    };
    let found = files(&shared, sub);
    let names: Vec<String> = found
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into())
        .collect();
    let listed: Vec<&str> = expected.iter().map(|e| e.file).collect();
    assert_eq!(names, listed, "{sub}: files on disk vs. the expectations");
    found
        .iter()
        .zip(expected)
        .map(|(p, ex)| (ex.file.to_string(), check(p, ex)))
        .collect()
}

#[test]
fn siconos_files_load_with_documented_sizes() {
    check_all("siconos_dat_2d", SICONOS);
}

#[cfg(feature = "hdf5")]
#[test]
fn fclib_local_files_load_with_documented_sizes() {
    check_all("hdf5_3d_local", HDF5_LOCAL);
}

#[cfg(feature = "hdf5")]
#[test]
fn fclib_global_files_load_and_reduce_like_a_dense_computation() {
    check_all("hdf5_3d_global", HDF5_GLOBAL);
}

fn load(sub: &str, file: &str) -> Option<Problem> {
    let shared = shared_dir()?;
    Some(read_problem(shared.join(sub).join(file)).unwrap())
}

// The literals are copied from the files: the reader must give their nearest doubles.
#[allow(clippy::excessive_precision)]
#[test]
fn siconos_values_land_where_the_storage_codes_say() {
    let Some(Problem::Local(p)) = load("siconos_dat_2d", "FC2D_SliderCrankLagrangian00000.dat")
    else {
        return;
    };
    // Dense, column by column: the second value of the first line is W(1, 0).
    assert_eq!(p.w.get(0, 0), 9.365610022253570150496671e+02);
    assert_eq!(p.w.get(1, 0), -4.642665883420582986218506e+02);
    assert_eq!(p.w.get(0, 1), -4.642662921766745967033785e+02);
    assert_eq!(p.w.get(3, 2), 4.616593375838677957290201e+02);
    assert_eq!(p.q[1], -8.407368208001527065675873e+00);
    assert_eq!(p.mu, vec![0.01, 0.01]);

    // Sparse-block: block 7 sits at block row 6, block column 10, column by column.
    let Some(Problem::Local(p)) = load("siconos_dat_2d", "FrictionContactProblem00031.dat") else {
        return;
    };
    assert_eq!(p.w.get(12, 20), -1.921399e-01);
    assert_eq!(p.w.get(13, 20), -1.180736e-01);
    assert_eq!(p.w.get(12, 21), 1.180736e-01);
    assert_eq!(p.w.get(21, 13), 2.588994e-01);
    assert_eq!(p.w.get(1, 0), 1.084202e-18);
    assert_eq!(p.w.get(0, 1), -1.084202e-18);
    assert_eq!(p.w.get(0, 20), 0.0);

    // CSparse CSC: "col 0" lists rows 0 and 649.
    let Some(Problem::Local(p)) = load("siconos_dat_2d", "fc2d_granularflowonwall_00667_00000.dat")
    else {
        return;
    };
    assert_eq!(
        (p.w.get(0, 0), p.w.get(649, 0), p.w.get(648, 1)),
        (856.713, -454.43, 454.43)
    );

    // Global: M triplet (diagonal), H CSC.
    let Some(Problem::Global(g)) =
        load("siconos_dat_2d", "gfc2d_granularflowonwall_00069_00350.dat")
    else {
        return;
    };
    assert_eq!(
        (g.m.get(0, 0), g.m.get(2, 2), g.m.nnz()),
        (0.00150187, 1.46527e-10, 900)
    );
    assert_eq!((g.h.get(343, 0), g.h.get(344, 0)), (-1.0, -1.40662e-05));
    assert_eq!(g.w[0], 6.872251259351841445877085e-02);
}

#[cfg(feature = "hdf5")]
#[test]
fn fclib_values_land_where_the_layouts_say() {
    // CSR W.
    let Some(Problem::Local(p)) = load("hdf5_3d_local", "Capsules-i125-1213.hdf5") else {
        return;
    };
    assert_eq!(p.w.get(0, 0), 1.8960848564937047);
    assert_eq!(p.q[0], -0.004904999995580751);
    // Triplet H (i = row, p = column) and diagonal M.
    let Some(Problem::Global(g)) = load("hdf5_3d_global", "Box_Stacks-i0122-82-5.hdf5") else {
        return;
    };
    assert_eq!(g.h.get(2, 0), 1.0);
    assert_eq!(g.m.get(449, 449), 0.180266659456);
    // LMGC90 stores the upper triangle of its symmetric M: it is read in full.
    let Some(Problem::Global(g)) = load("hdf5_3d_global", "LMGC_CubeH8.hdf5") else {
        return;
    };
    assert_eq!(g.m.get(0, 0), 256126234.56790134);
    assert_eq!(g.m.get(0, 1), 5.165436921296297);
    assert_eq!(g.m.get(1, 0), g.m.get(0, 1));
    let l = g.to_local().unwrap();
    for i in 0..3 {
        for j in 0..3 {
            assert!((l.w.get(i, j) - l.w.get(j, i)).abs() <= 1e-12 * l.w.get(0, 0));
        }
    }
}

#[cfg(feature = "hdf5")]
fn hdf5_rows() -> Vec<(String, FrictionProblem)> {
    let mut rows = check_all("hdf5_3d_local", HDF5_LOCAL);
    rows.extend(check_all("hdf5_3d_global", HDF5_GLOBAL));
    rows
}

#[cfg(not(feature = "hdf5"))]
fn hdf5_rows() -> Vec<(String, FrictionProblem)> {
    Vec::new()
}

/// The table in README.md.
#[test]
fn print_table_of_shared_files() {
    let rows: Vec<_> = check_all("siconos_dat_2d", SICONOS)
        .into_iter()
        .chain(hdf5_rows())
        .collect();
    if rows.is_empty() {
        return;
    }
    println!("| file | form | dim | contacts | nnz(W) | abs(q) |");
    println!("|---|---|---|---|---|---|");
    let all: Vec<&Expect> = SICONOS
        .iter()
        .chain(HDF5_LOCAL)
        .chain(HDF5_GLOBAL)
        .collect();
    for (name, p) in &rows {
        let ex = all.iter().find(|e| e.file == name).unwrap();
        let form = if ex.global { "global" } else { "local" };
        println!(
            "| {name} | {form} | {} | {} | {} | {:.3e} |",
            p.dim,
            p.contact_count(),
            p.w.nnz(),
            norm(&p.q)
        );
    }
    #[cfg(not(feature = "hdf5"))]
    println!("(HDF5 files left out: built without the hdf5 feature)");
}
