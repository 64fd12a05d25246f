//! Siconos numerics' text format (`.dat`), as written by `frictionContact_printInFile` and
//! `globalFrictionContact_printInFile` of Siconos (<https://github.com/siconos/siconos>,
//! `numerics/src/FrictionContact`). It is not part of FCLib; Siconos' test suite uses it
//! for its 2D problems.
//!
//! # Layout
//!
//! Whitespace-separated numbers (line breaks only matter inside the CSparse dumps, which
//! have one text line):
//!
//! ```text
//! local:   d  nc  W  q[d nc]  mu[nc]
//! global:  d  nc  M  H  f[n]  w[d nc]  mu[nc]        (f is Siconos' q, w its b)
//! ```
//!
//! Each matrix is a `NumericsMatrix`: `code size0 size1`, then
//! - code `0`, dense: `size0 size1` again, then `size0 * size1` values **column by column**;
//! - code `1`, sparse-block (`SBM_write_in_file`): `nbblocks`, and if it is not 0:
//!   `blocknumber0 blocknumber1`, the cumulative sizes of the block rows and of the block
//!   columns, `filled1 filled2`, the block-row pointers (`filled1`), the block-column index
//!   of each block (`filled2`), then every block as its number followed by its values
//!   column by column;
//! - code `2`, CSparse dump (`NSM_write_in_file`): origin `1` (triplet) or `2` (CSC), a
//!   line `CSparse Version ...`, then `triplet: {m}-by-{n}, nzmax: {nzmax} nnz: {nz}` and
//!   `nz` lines `i j : x` (row, column, value), or `{m}-by-{n}, nzmax: {nzmax} nnz: {nnz},
//!   1-norm: {norm}` and, for each column `j`, `col j : locations {start} to {end}`
//!   followed by `end - start + 1` lines `i : x`. Values are printed with `%g` (6
//!   significant digits), so these matrices are only accurate to about 1e-6.
//!
//! As for FCLib files, a global `M` stored as one triangle (off-diagonal entries on one
//! side only) is read as symmetric and completed.
//!
//! Older Siconos test files end with one extra integer after `mu`; it is accepted and
//! ignored. Any other trailing data is an error.
//!
//! # Local or global
//!
//! The two layouts start alike, so [`SiconosKind::Auto`] decides from the content after
//! the first matrix `A` (`n x n`):
//! - if `n != d nc`, `A` cannot be `W`: the file is global (`A = M`);
//! - otherwise, if the next three tokens are integers `c n (d nc)` with `c` in `{0, 1, 2}`
//!   (the header of a matrix `H` of the right size), the file is global; Siconos writes
//!   the entries of `q` in `%e` notation, never as integers, so a local file never looks
//!   like this;
//! - otherwise it is local.
//!
//! A caller that knows which layout it has can say so with [`SiconosKind::Local`] or
//! [`SiconosKind::Global`]; the sizes are then checked against that layout.
//!
//! # Robustness
//!
//! Every size is checked before use: dimensions cannot exceed the number of tokens in the
//! file (each dimension is the length of a vector stored in it), indices must be in range,
//! pointers must increase, counts must match. Errors name the file, the line and token
//! index, and the reason.

mod lexer;
mod matrix;

use crate::error::{Position, ReadError, ReadErrorKind};
use crate::global::GlobalFrictionProblem;
use crate::Problem;
use lexer::Lexer;
use matrix::read_matrix;
use std::path::Path;
use xper_solver::FrictionProblem;

/// Which layout a Siconos `.dat` file has.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SiconosKind {
    /// Decide from the content (see the module docs).
    #[default]
    Auto,
    /// `d nc W q mu`.
    Local,
    /// `d nc M H f w mu`.
    Global,
}

/// Reads a Siconos `.dat` file, telling local from global problems by their content.
pub fn read_siconos(path: impl AsRef<Path>) -> Result<Problem, ReadError> {
    read_siconos_as(path, SiconosKind::Auto)
}

/// Reads a Siconos `.dat` file of the given layout.
pub fn read_siconos_as(path: impl AsRef<Path>, kind: SiconosKind) -> Result<Problem, ReadError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|e| ReadError::io(path, &e))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        ReadError::file(
            path,
            ReadErrorKind::Format,
            format!("not a text file: invalid UTF-8 at byte {}", e.valid_up_to()),
        )
    })?;
    parse_siconos(text, path, kind)
}

/// Parses the text of a Siconos `.dat` file; `path` only names it in errors.
pub fn parse_siconos(text: &str, path: &Path, kind: SiconosKind) -> Result<Problem, ReadError> {
    let mut lx = Lexer::new(text, path);
    let (d, t) = lx.int("dimension d")?;
    if d != 2 && d != 3 {
        return Err(lx.error_at(
            &t,
            ReadErrorKind::Invalid,
            format!("dimension d = {d} is not 2 or 3"),
        ));
    }
    let d = d as usize;
    let nc = lx.dimension("contact count nc")?;
    let k = d * nc;
    let first_header = lx.peek(2).get(1).copied();
    let first = read_matrix(&mut lx, "W or M")?;
    let n = first.nrows;
    if first.ncols != n {
        return Err(size_error(
            &lx,
            first_header,
            format!(
                "the first matrix is {} x {}; W and M are square",
                n, first.ncols
            ),
        ));
    }
    let global = match kind {
        SiconosKind::Local => false,
        SiconosKind::Global => true,
        SiconosKind::Auto => n != k || looks_like_matrix_header(&lx, n, k),
    };
    if !global {
        if n != k {
            return Err(size_error(
                &lx,
                first_header,
                format!("W is {n} x {n} but {nc} contacts in {d}D need {k} x {k} (is this a global problem?)"),
            ));
        }
        let q = lx.reals(k, "q")?;
        let mu = read_mu(&mut lx, nc)?;
        check_end(&lx)?;
        let p = FrictionProblem::new(d, first, q, mu).map_err(|e| invalid(path, e.0))?;
        return Ok(Problem::Local(p));
    }
    let why = if kind == SiconosKind::Auto {
        if n != k {
            format!(" (read as global: the first matrix is {n} x {n} while d nc = {k})")
        } else {
            " (read as global: a matrix header follows the first matrix)".to_string()
        }
    } else {
        String::new()
    };
    let body = |lx: &mut Lexer<'_>| -> Result<Problem, ReadError> {
        let h_header = lx.peek(2).get(1).copied();
        let h = read_matrix(lx, "H")?;
        if h.nrows != n || h.ncols != k {
            return Err(size_error(
                lx,
                h_header,
                format!(
                    "H is {} x {} but M is {n} x {n} and {nc} contacts in {d}D need {n} x {k}",
                    h.nrows, h.ncols
                ),
            ));
        }
        let f = lx.reals(n, "f (Siconos' q)")?;
        let w = lx.reals(k, "w (Siconos' b)")?;
        let mu = read_mu(lx, nc)?;
        check_end(lx)?;
        let m = crate::sparse::complete_symmetric_triangle(first.clone());
        let p = GlobalFrictionProblem::new(d, m, h, f, w, mu).map_err(|e| invalid(path, e.0))?;
        Ok(Problem::Global(p))
    };
    body(&mut lx).map_err(|mut e| {
        e.reason.push_str(&why);
        e
    })
}

/// A size error, at the row count of the matrix header `header` when known.
fn size_error(lx: &Lexer<'_>, header: Option<lexer::Tok<'_>>, reason: String) -> ReadError {
    match header {
        Some(t) => lx.error_at(&t, ReadErrorKind::Invalid, reason),
        None => lx.error_here(ReadErrorKind::Invalid, reason),
    }
}

fn invalid(path: &Path, reason: String) -> ReadError {
    ReadError::new(path, Position::File, ReadErrorKind::Invalid, reason)
}

/// Whether the next tokens are `code n k` with `code` a storage code: the header of `H`.
fn looks_like_matrix_header(lx: &Lexer<'_>, n: usize, k: usize) -> bool {
    let t = lx.peek(3);
    let int = |i: usize| t.get(i).and_then(|t| t.text.parse::<i64>().ok());
    matches!(int(0), Some(0..=2)) && int(1) == Some(n as i64) && int(2) == Some(k as i64)
}

/// `nc` friction coefficients, each finite and non-negative.
fn read_mu(lx: &mut Lexer<'_>, nc: usize) -> Result<Vec<f64>, ReadError> {
    if nc > lx.remaining() {
        return Err(lx.error_here(
            ReadErrorKind::Format,
            format!(
                "mu needs {nc} values but only {} tokens are left in the file",
                lx.remaining()
            ),
        ));
    }
    let mut mu = Vec::with_capacity(nc);
    for a in 0..nc {
        let here = lx.peek(1);
        let v = lx.real(&format!("mu[{a}]"))?;
        if !(v.is_finite() && v >= 0.0) {
            return Err(lx.error_at(
                &here[0],
                ReadErrorKind::Invalid,
                format!("mu[{a}] = {v} is not a finite non-negative number"),
            ));
        }
        mu.push(v);
    }
    Ok(mu)
}

/// Nothing may follow but one integer (older Siconos files end with one).
fn check_end(lx: &Lexer<'_>) -> Result<(), ReadError> {
    let rest = lx.peek(2);
    let ok = match rest.as_slice() {
        [] => true,
        [t] => t.text.parse::<i64>().is_ok(),
        _ => false,
    };
    if ok {
        Ok(())
    } else {
        Err(lx.error_at(
            &rest[0],
            ReadErrorKind::Format,
            format!("unexpected data after the problem: \"{}\"", rest[0].text),
        ))
    }
}
