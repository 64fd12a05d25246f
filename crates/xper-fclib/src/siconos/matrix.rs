//! Siconos' `NumericsMatrix` text layout (`NM_write_in_file`): a storage code, the two
//! sizes, then the storage-specific payload. See the module docs of [`crate::siconos`].

use super::lexer::Lexer;
use crate::error::{ReadError, ReadErrorKind};
use crate::sparse;
use xper_solver::CsrMatrix;

/// Reads one matrix named `name` (for messages).
pub(crate) fn read_matrix(lx: &mut Lexer<'_>, name: &str) -> Result<CsrMatrix, ReadError> {
    let (code, code_tok) = lx.int(&format!("storage code of {name}"))?;
    if !(0..=2).contains(&code) {
        return Err(lx.error_at(
            &code_tok,
            ReadErrorKind::Format,
            format!("storage code of {name} is {code}; 0 (dense), 1 (sparse-block) or 2 (sparse) expected"),
        ));
    }
    let nrows = lx.dimension(&format!("row count of {name}"))?;
    let ncols = lx.dimension(&format!("column count of {name}"))?;
    match code {
        0 => read_dense(lx, name, nrows, ncols),
        1 => read_sparse_block(lx, name, nrows, ncols),
        _ => read_csparse(lx, name, nrows, ncols),
    }
}

/// Code 0: `size0 size1` again, then the values column by column.
fn read_dense(
    lx: &mut Lexer<'_>,
    name: &str,
    nrows: usize,
    ncols: usize,
) -> Result<CsrMatrix, ReadError> {
    for (what, expected) in [("row", nrows), ("column", ncols)] {
        let (v, t) = lx.int(&format!("dense {what} count of {name}"))?;
        if v != expected as i64 {
            return Err(lx.error_at(
                &t,
                ReadErrorKind::Format,
                format!("dense {what} count of {name} is {v} but the header said {expected}"),
            ));
        }
    }
    let count = nrows.checked_mul(ncols).filter(|&c| c <= lx.remaining());
    let Some(count) = count else {
        return Err(lx.error_here(
            ReadErrorKind::Format,
            format!(
                "dense {name} of {nrows} x {ncols} needs more values than the {} tokens left",
                lx.remaining()
            ),
        ));
    };
    let vals = lx.reals(count, name)?;
    Ok(sparse::from_dense_col_major(nrows, ncols, &vals))
}

/// Reads `n` cumulative block sizes, checking they increase and end at `total`.
fn block_sizes(
    lx: &mut Lexer<'_>,
    n: usize,
    total: usize,
    what: &str,
) -> Result<Vec<usize>, ReadError> {
    let mut ends = Vec::with_capacity(n.min(lx.remaining()));
    for k in 0..n {
        let (v, t) = lx.int(&format!("{what}[{k}]"))?;
        let prev = ends.last().copied().unwrap_or(0);
        if v <= prev as i64 || v > total as i64 {
            return Err(lx.error_at(
                &t,
                ReadErrorKind::Format,
                format!("{what}[{k}] = {v}: cumulative block sizes must increase from {prev} up to {total}"),
            ));
        }
        ends.push(v as usize);
    }
    if ends.last().copied().unwrap_or(0) != total {
        return Err(lx.error_here(
            ReadErrorKind::Format,
            format!(
                "{what} ends at {} but the matrix has {total}",
                ends.last().copied().unwrap_or(0)
            ),
        ));
    }
    Ok(ends)
}

/// Code 1 (`SBM_write_in_file`): `nbblocks`; if non-zero, `blocknumber0 blocknumber1`,
/// the cumulative block sizes of rows and columns, `filled1 filled2`, the block-row
/// pointers (`filled1` of them) and block-column indices (`filled2`), then each block as
/// its number followed by its values column by column.
fn read_sparse_block(
    lx: &mut Lexer<'_>,
    name: &str,
    nrows: usize,
    ncols: usize,
) -> Result<CsrMatrix, ReadError> {
    let nblocks = lx.dimension(&format!("block count of {name}"))?;
    if nblocks == 0 {
        return Ok(CsrMatrix::from_triplets(nrows, ncols, &[]).expect("empty"));
    }
    let brows = lx.size(&format!("block-row count of {name}"), nrows)?;
    let bcols = lx.size(&format!("block-column count of {name}"), ncols)?;
    let row_ends = block_sizes(lx, brows, nrows, &format!("block-row sizes of {name}"))?;
    let col_ends = block_sizes(lx, bcols, ncols, &format!("block-column sizes of {name}"))?;
    let filled1 = lx.size(&format!("block-row pointer count of {name}"), brows + 1)?;
    let filled2 = lx.dimension(&format!("stored block count of {name}"))?;
    if filled1 == 0 || filled2 != nblocks {
        return Err(lx.error_here(
            ReadErrorKind::Format,
            format!("{name}: {filled1} block-row pointers and {filled2} block columns for {nblocks} blocks"),
        ));
    }
    let mut row_ptr = Vec::with_capacity(filled1);
    for k in 0..filled1 {
        let (v, t) = lx.int(&format!("block-row pointer {k} of {name}"))?;
        let prev = row_ptr.last().copied().unwrap_or(0);
        let first_ok = k > 0 || v == 0;
        if !first_ok || v < prev as i64 || v > nblocks as i64 {
            return Err(lx.error_at(
                &t,
                ReadErrorKind::Format,
                format!("block-row pointer {k} of {name} is {v}: pointers must start at 0 and increase up to {nblocks}"),
            ));
        }
        row_ptr.push(v as usize);
    }
    if row_ptr[filled1 - 1] != nblocks {
        return Err(lx.error_here(
            ReadErrorKind::Format,
            format!(
                "block-row pointers of {name} end at {} for {nblocks} blocks",
                row_ptr[filled1 - 1]
            ),
        ));
    }
    let mut block_col = Vec::with_capacity(nblocks);
    for k in 0..nblocks {
        block_col.push(lx.index(&format!("block-column index {k} of {name}"), bcols)?);
    }
    let mut entries = Vec::new();
    for br in 0..filled1 - 1 {
        let r0 = if br == 0 { 0 } else { row_ends[br - 1] };
        let nr = row_ends[br] - r0;
        for (b, &bc) in block_col
            .iter()
            .enumerate()
            .take(row_ptr[br + 1])
            .skip(row_ptr[br])
        {
            let c0 = if bc == 0 { 0 } else { col_ends[bc - 1] };
            let nc = col_ends[bc] - c0;
            let (num, t) = lx.int(&format!("number of block {b} of {name}"))?;
            if num != b as i64 {
                return Err(lx.error_at(
                    &t,
                    ReadErrorKind::Format,
                    format!("block {b} of {name} is numbered {num}"),
                ));
            }
            let vals = lx.reals(nr * nc, &format!("{name} block {b}"))?;
            for (k, &v) in vals.iter().enumerate() {
                entries.push((r0 + k % nr, c0 + k / nr, v));
            }
        }
    }
    CsrMatrix::from_triplets(nrows, ncols, &entries)
        .map_err(|e| lx.error_here(ReadErrorKind::Format, format!("{name}: {}", e.0)))
}

/// Parses CSparse's `{m}-by-{n},` size token.
fn parse_by(text: &str) -> Option<(usize, usize)> {
    let (m, n) = text.strip_suffix(',')?.split_once("-by-")?;
    Some((m.parse().ok()?, n.parse().ok()?))
}

/// Code 2 (`NSM_write_in_file` + `CSparseMatrix_print_in_file`): the origin (1 triplet,
/// 2 CSC), a `CSparse Version ...` line, then either
/// `triplet: {m}-by-{n}, nzmax: {nzmax} nnz: {nz}` and `nz` lines `i j : x`, or
/// `{m}-by-{n}, nzmax: {nzmax} nnz: {nnz}, 1-norm: {norm}` and, per column `j`,
/// `col j : locations {start} to {end}` followed by lines `i : x`.
fn read_csparse(
    lx: &mut Lexer<'_>,
    name: &str,
    nrows: usize,
    ncols: usize,
) -> Result<CsrMatrix, ReadError> {
    let (origin, origin_tok) = lx.int(&format!("sparse origin of {name}"))?;
    if origin != 1 && origin != 2 {
        return Err(lx.error_at(
            &origin_tok,
            if origin == 3 {
                ReadErrorKind::Unsupported
            } else {
                ReadErrorKind::Format
            },
            format!("sparse origin of {name} is {origin}; 1 (triplet) or 2 (CSC) expected"),
        ));
    }
    let t = lx.expect(&format!("the CSparse header of {name}"))?;
    if t.text != "CSparse" {
        return Err(lx.error_at(
            &t,
            ReadErrorKind::Format,
            format!(
                "expected the \"CSparse Version ...\" line of {name}, found \"{}\"",
                t.text
            ),
        ));
    }
    lx.skip_line();
    let first = lx.expect(&format!("the size line of {name}"))?;
    let triplet = first.text == "triplet:";
    if triplet != (origin == 1) {
        return Err(lx.error_at(
            &first,
            ReadErrorKind::Format,
            format!(
                "sparse origin {origin} of {name} does not match its layout (\"{}\")",
                first.text
            ),
        ));
    }
    let by = if triplet {
        lx.expect(&format!("the size of {name}"))?
    } else {
        first
    };
    let (m, n) = parse_by(by.text).ok_or_else(|| {
        lx.error_at(
            &by,
            ReadErrorKind::Format,
            format!(
                "expected \"{{m}}-by-{{n}},\" for {name}, found \"{}\"",
                by.text
            ),
        )
    })?;
    if (m, n) != (nrows, ncols) {
        return Err(lx.error_at(
            &by,
            ReadErrorKind::Format,
            format!("{name} is {m} x {n} here but {nrows} x {ncols} in its header"),
        ));
    }
    lx.literal("nzmax:", name)?;
    lx.dimension(&format!("nzmax of {name}"))?;
    lx.literal("nnz:", name)?;
    if triplet {
        let nz = lx.dimension(&format!("entry count of {name}"))?;
        let mut entries = Vec::with_capacity(nz.min(lx.remaining() / 4));
        for k in 0..nz {
            let i = lx.index(&format!("row of entry {k} of {name}"), nrows)?;
            let j = lx.index(&format!("column of entry {k} of {name}"), ncols)?;
            lx.literal(":", name)?;
            entries.push((i, j, lx.real(&format!("value of entry {k} of {name}"))?));
        }
        return Ok(CsrMatrix::from_triplets(nrows, ncols, &entries).expect("indices checked"));
    }
    let t = lx.expect(&format!("nnz of {name}"))?;
    let nnz = t
        .text
        .strip_suffix(',')
        .and_then(|s| s.parse::<usize>().ok());
    let nnz = nnz.filter(|&v| v <= lx.total()).ok_or_else(|| {
        lx.error_at(
            &t,
            ReadErrorKind::Format,
            format!("expected \"{{nnz}},\" for {name}, found \"{}\"", t.text),
        )
    })?;
    lx.literal("1-norm:", name)?;
    lx.expect(&format!("1-norm of {name}"))?;
    let mut entries = Vec::with_capacity(nnz);
    for j in 0..ncols {
        lx.literal("col", name)?;
        let (cj, t) = lx.int(&format!("column number of {name}"))?;
        if cj != j as i64 {
            return Err(lx.error_at(
                &t,
                ReadErrorKind::Format,
                format!("column {cj} of {name} where {j} was expected"),
            ));
        }
        lx.literal(":", name)?;
        lx.literal("locations", name)?;
        let (start, t) = lx.int(&format!("first location of column {j} of {name}"))?;
        if start != entries.len() as i64 {
            return Err(lx.error_at(
                &t,
                ReadErrorKind::Format,
                format!(
                    "column {j} of {name} starts at {start}, not {}",
                    entries.len()
                ),
            ));
        }
        lx.literal("to", name)?;
        let (end, t) = lx.int(&format!("last location of column {j} of {name}"))?;
        if end < start - 1 || end >= nnz as i64 {
            return Err(lx.error_at(
                &t,
                ReadErrorKind::Format,
                format!(
                    "column {j} of {name} ends at {end}: outside {}..{nnz}",
                    start - 1
                ),
            ));
        }
        for _ in start..=end {
            let i = lx.index(&format!("row index in column {j} of {name}"), nrows)?;
            lx.literal(":", name)?;
            entries.push((i, j, lx.real(&format!("value at ({i}, {j}) of {name}"))?));
        }
    }
    if entries.len() != nnz {
        return Err(lx.error_here(
            ReadErrorKind::Format,
            format!("{name} has {} entries but announced {nnz}", entries.len()),
        ));
    }
    Ok(CsrMatrix::from_triplets(nrows, ncols, &entries).expect("indices checked"))
}
