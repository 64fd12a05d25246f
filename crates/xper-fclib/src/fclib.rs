//! FCLib's HDF5 layout (Acary et al., "FCLib: a collection of discrete 3D frictional
//! contact problems", JOTA 2014; <https://github.com/FrictionalContactLibrary/fclib>,
//! `src/fclib.c`), read and written with `hdf5-metno`.
//!
//! Integers are int32, reals float64; scalars (`spacedim`, `m`, `n`, `nz`, `nzmax`) are 1-D
//! datasets of length 1.
//!
//! ```text
//! /fclib_local/spacedim                 d (2 or 3)
//! /fclib_local/W/{nzmax,m,n,nz,p,i,x}   W, m = n = d nc
//! /fclib_local/vectors/q                length d nc
//! /fclib_local/vectors/mu               length nc
//!
//! /fclib_global/spacedim
//! /fclib_global/M/...                   n x n
//! /fclib_global/H/...                   n x d nc
//! /fclib_global/vectors/{f,w,mu}        lengths n, d nc, nc
//! ```
//!
//! A matrix group stores, by the value of `nz`:
//! - `nz == -2`, CSR: `p` row pointers (`m + 1`), `i` column indices, `x` values;
//! - `nz == -1`, CSC: `p` column pointers (`n + 1`), `i` row indices, `x` values;
//! - `nz >= 0`, triplet: entry `k < nz` is at row `i[k]`, column `p[k]`, value `x[k]`
//!   (the comment in `fclib.h` says the opposite; the files follow this order).
//!
//! `i` and `x` may be longer than the entries used (`nzmax`). LMGC90's dumps store only
//! the upper triangle of the symmetric `M`: a stored `M` with off-diagonal entries on one
//! side of the diagonal only is read as symmetric and completed. The optional groups
//! (`info`, `G`, `b`, `/solution`, `/guesses`) are ignored. Every dataset length and
//! index is checked before use, and no dataset larger than 64 times the file size (in
//! elements) is read, so a corrupt header cannot trigger a huge allocation.
//!
//! The writers store matrices as CSR (`nz = -2`), the layout FCLib's own local files use,
//! and write atomically: a temporary file in the same directory is renamed over the target.

use crate::error::{Position, ReadError, ReadErrorKind};
use crate::global::GlobalFrictionProblem;
use crate::{sparse, write_atomically, Problem};
use hdf5_metno as h5;
use hdf5_metno::types::TypeDescriptor;
use std::path::Path;
use xper_solver::{CsrMatrix, FrictionProblem};

/// Reads an FCLib file: `/fclib_local` if present, else `/fclib_global`.
pub fn read_fclib(path: impl AsRef<Path>) -> Result<Problem, ReadError> {
    let path = path.as_ref();
    let (file, r) = open(path)?;
    if file.link_exists("fclib_local") {
        local(&file, &r).map(Problem::Local)
    } else if file.link_exists("fclib_global") {
        global(&file, &r).map(Problem::Global)
    } else {
        Err(ReadError::file(
            path,
            ReadErrorKind::Format,
            "neither /fclib_local nor /fclib_global is in the file",
        ))
    }
}

/// Reads the local problem `/fclib_local` of an FCLib file.
pub fn read_fclib_local(path: impl AsRef<Path>) -> Result<FrictionProblem, ReadError> {
    let (file, r) = open(path.as_ref())?;
    local(&file, &r)
}

/// Reads the global problem `/fclib_global` of an FCLib file.
pub fn read_fclib_global(path: impl AsRef<Path>) -> Result<GlobalFrictionProblem, ReadError> {
    let (file, r) = open(path.as_ref())?;
    global(&file, &r)
}

/// Writes `p` as `/fclib_local` of a new FCLib file at `path`, atomically. A problem
/// whose public fields disagree (sizes, values) is refused, so that what is written can
/// be read back.
pub fn write_fclib_local(path: impl AsRef<Path>, p: &FrictionProblem) -> Result<(), ReadError> {
    let path = path.as_ref();
    FrictionProblem::new(p.dim, p.w.clone(), p.q.clone(), p.mu.clone())
        .map_err(|e| ReadError::file(path, ReadErrorKind::Invalid, e.0))?;
    write_atomically(path, |tmp| {
        let w = Writer { path };
        let file = h5::File::create(tmp).map_err(|e| w.err("/", e))?;
        let g = w.group(&file, "/fclib_local")?;
        w.ints(&g, "/fclib_local/spacedim", &[p.dim])?;
        w.matrix(&g, "/fclib_local/W", &p.w)?;
        let v = w.group(&g, "/fclib_local/vectors")?;
        w.reals(&v, "/fclib_local/vectors/q", &p.q)?;
        w.reals(&v, "/fclib_local/vectors/mu", &p.mu)?;
        file.close().map_err(|e| w.err("/", e))
    })
}

/// Writes `p` as `/fclib_global` of a new FCLib file at `path`, atomically, after
/// [`GlobalFrictionProblem::validate`].
pub fn write_fclib_global(
    path: impl AsRef<Path>,
    p: &GlobalFrictionProblem,
) -> Result<(), ReadError> {
    let path = path.as_ref();
    p.validate()
        .map_err(|e| ReadError::file(path, ReadErrorKind::Invalid, e.0))?;
    write_atomically(path, |tmp| {
        let w = Writer { path };
        let file = h5::File::create(tmp).map_err(|e| w.err("/", e))?;
        let g = w.group(&file, "/fclib_global")?;
        w.ints(&g, "/fclib_global/spacedim", &[p.dim])?;
        w.matrix(&g, "/fclib_global/M", &p.m)?;
        w.matrix(&g, "/fclib_global/H", &p.h)?;
        let v = w.group(&g, "/fclib_global/vectors")?;
        w.reals(&v, "/fclib_global/vectors/f", &p.f)?;
        w.reals(&v, "/fclib_global/vectors/w", &p.w)?;
        w.reals(&v, "/fclib_global/vectors/mu", &p.mu)?;
        file.close().map_err(|e| w.err("/", e))
    })
}

/// The file being read and the largest dataset (in elements) it may hold.
struct Reader<'a> {
    path: &'a Path,
    max_len: usize,
}

fn open(path: &Path) -> Result<(h5::File, Reader<'_>), ReadError> {
    let meta = std::fs::metadata(path).map_err(|e| ReadError::io(path, &e))?;
    let file = h5::File::open(path).map_err(|e| {
        ReadError::file(
            path,
            ReadErrorKind::Format,
            format!("not a readable HDF5 file: {e}"),
        )
    })?;
    let max_len = usize::try_from(meta.len())
        .unwrap_or(usize::MAX / 64)
        .saturating_mul(64)
        + 4096;
    Ok((file, Reader { path, max_len }))
}

impl Reader<'_> {
    fn err(&self, at: &str, kind: ReadErrorKind, reason: impl Into<String>) -> ReadError {
        ReadError::new(self.path, Position::Dataset(at.to_string()), kind, reason)
    }

    fn group(&self, parent: &h5::Group, at: &str) -> Result<h5::Group, ReadError> {
        let name = at.rsplit('/').next().unwrap_or(at);
        parent
            .group(name)
            .map_err(|e| self.err(at, ReadErrorKind::Format, format!("missing group: {e}")))
    }

    /// A 1-D (or scalar) dataset, with its element type checked.
    fn dataset(&self, g: &h5::Group, at: &str, integer: bool) -> Result<h5::Dataset, ReadError> {
        let name = at.rsplit('/').next().unwrap_or(at);
        let ds = g
            .dataset(name)
            .map_err(|e| self.err(at, ReadErrorKind::Format, format!("missing dataset: {e}")))?;
        if ds.ndim() > 1 {
            return Err(self.err(
                at,
                ReadErrorKind::Format,
                format!("{}-dimensional; 1-D expected", ds.ndim()),
            ));
        }
        if ds.size() > self.max_len {
            return Err(self.err(
                at,
                ReadErrorKind::Format,
                format!("{} elements: more than the file can hold", ds.size()),
            ));
        }
        let dtype = ds
            .dtype()
            .and_then(|t| t.to_descriptor())
            .map_err(|e| self.err(at, ReadErrorKind::Format, format!("unreadable type: {e}")))?;
        let ok = match dtype {
            TypeDescriptor::Integer(_) | TypeDescriptor::Unsigned(_) => true,
            TypeDescriptor::Float(_) => !integer,
            _ => false,
        };
        if !ok {
            let want = if integer { "integers" } else { "reals" };
            return Err(self.err(
                at,
                ReadErrorKind::Format,
                format!("holds {dtype}; {want} expected"),
            ));
        }
        Ok(ds)
    }

    fn ints(&self, g: &h5::Group, at: &str) -> Result<Vec<i64>, ReadError> {
        let ds = self.dataset(g, at, true)?;
        ds.read_raw::<i64>()
            .map_err(|e| self.err(at, ReadErrorKind::Format, format!("cannot read: {e}")))
    }

    fn reals(&self, g: &h5::Group, at: &str) -> Result<Vec<f64>, ReadError> {
        let ds = self.dataset(g, at, false)?;
        let v = ds
            .read_raw::<f64>()
            .map_err(|e| self.err(at, ReadErrorKind::Format, format!("cannot read: {e}")))?;
        if let Some(k) = v.iter().position(|x| !x.is_finite()) {
            return Err(self.err(
                at,
                ReadErrorKind::Invalid,
                format!("entry {k} = {} is not finite", v[k]),
            ));
        }
        Ok(v)
    }

    fn scalar(&self, g: &h5::Group, at: &str) -> Result<i64, ReadError> {
        match self.ints(g, at)?.as_slice() {
            [v] => Ok(*v),
            v => Err(self.err(
                at,
                ReadErrorKind::Format,
                format!("{} values; one expected", v.len()),
            )),
        }
    }

    /// A vector of exactly `len` reals (when given).
    fn vector(&self, g: &h5::Group, at: &str, len: Option<usize>) -> Result<Vec<f64>, ReadError> {
        let v = self.reals(g, at)?;
        match len {
            Some(n) if v.len() != n => Err(self.err(
                at,
                ReadErrorKind::Invalid,
                format!("{} entries; {n} expected", v.len()),
            )),
            _ => Ok(v),
        }
    }

    fn dim(&self, g: &h5::Group, at: &str) -> Result<usize, ReadError> {
        match self.scalar(g, at)? {
            d @ (2 | 3) => Ok(d as usize),
            d => Err(self.err(
                at,
                ReadErrorKind::Invalid,
                format!("spacedim = {d} is not 2 or 3"),
            )),
        }
    }

    fn mu(&self, g: &h5::Group, at: &str, nc: usize) -> Result<Vec<f64>, ReadError> {
        let mu = self.vector(g, at, Some(nc))?;
        if let Some(a) = mu.iter().position(|v| *v < 0.0) {
            return Err(self.err(
                at,
                ReadErrorKind::Invalid,
                format!("mu[{a}] = {} is negative", mu[a]),
            ));
        }
        Ok(mu)
    }

    /// The matrix group `at`, which must be `nrows x ncols`.
    fn matrix(
        &self,
        parent: &h5::Group,
        at: &str,
        nrows: usize,
        ncols: usize,
    ) -> Result<CsrMatrix, ReadError> {
        let g = self.group(parent, at)?;
        let (m, n) = (
            self.scalar(&g, &format!("{at}/m"))?,
            self.scalar(&g, &format!("{at}/n"))?,
        );
        if (m, n) != (nrows as i64, ncols as i64) {
            return Err(self.err(
                at,
                ReadErrorKind::Invalid,
                format!("matrix is {m} x {n}; the vectors make it {nrows} x {ncols}"),
            ));
        }
        let nz = self.scalar(&g, &format!("{at}/nz"))?;
        let p = self.ints(&g, &format!("{at}/p"))?;
        let i = self.ints(&g, &format!("{at}/i"))?;
        let x = self.reals(&g, &format!("{at}/x"))?;
        let built = match nz {
            -2 => sparse::from_compressed(nrows, ncols, &p, &i, &x, true),
            -1 => sparse::from_compressed(nrows, ncols, &p, &i, &x, false),
            nz if nz >= 0 => {
                let nz = nz as usize;
                if p.len() < nz || i.len() < nz || x.len() < nz {
                    return Err(self.err(
                        at,
                        ReadErrorKind::Format,
                        format!(
                            "triplet with nz = {nz} but p, i, x have {}, {}, {} entries",
                            p.len(),
                            i.len(),
                            x.len()
                        ),
                    ));
                }
                sparse::from_triplets(nrows, ncols, &i[..nz], &p[..nz], &x[..nz])
            }
            nz => {
                return Err(self.err(
                    &format!("{at}/nz"),
                    ReadErrorKind::Format,
                    format!("nz = {nz}: -2 (CSR), -1 (CSC) or a count expected"),
                ))
            }
        };
        built.map_err(|reason| self.err(at, ReadErrorKind::Format, reason))
    }
}

fn local(file: &h5::File, r: &Reader<'_>) -> Result<FrictionProblem, ReadError> {
    let g = r.group(file, "/fclib_local")?;
    let d = r.dim(&g, "/fclib_local/spacedim")?;
    let v = r.group(&g, "/fclib_local/vectors")?;
    let q = r.vector(&v, "/fclib_local/vectors/q", None)?;
    if q.len() % d != 0 {
        return Err(r.err(
            "/fclib_local/vectors/q",
            ReadErrorKind::Invalid,
            format!("{} entries: not a multiple of spacedim {d}", q.len()),
        ));
    }
    let mu = r.mu(&v, "/fclib_local/vectors/mu", q.len() / d)?;
    let w = r.matrix(&g, "/fclib_local/W", q.len(), q.len())?;
    FrictionProblem::new(d, w, q, mu)
        .map_err(|e| r.err("/fclib_local", ReadErrorKind::Invalid, e.0))
}

fn global(file: &h5::File, r: &Reader<'_>) -> Result<GlobalFrictionProblem, ReadError> {
    let g = r.group(file, "/fclib_global")?;
    let d = r.dim(&g, "/fclib_global/spacedim")?;
    let v = r.group(&g, "/fclib_global/vectors")?;
    let f = r.vector(&v, "/fclib_global/vectors/f", None)?;
    let w = r.vector(&v, "/fclib_global/vectors/w", None)?;
    if w.len() % d != 0 {
        return Err(r.err(
            "/fclib_global/vectors/w",
            ReadErrorKind::Invalid,
            format!("{} entries: not a multiple of spacedim {d}", w.len()),
        ));
    }
    let mu = r.mu(&v, "/fclib_global/vectors/mu", w.len() / d)?;
    let m = r.matrix(&g, "/fclib_global/M", f.len(), f.len())?;
    let m = sparse::complete_symmetric_triangle(m);
    let h = r.matrix(&g, "/fclib_global/H", f.len(), w.len())?;
    GlobalFrictionProblem::new(d, m, h, f, w, mu)
        .map_err(|e| r.err("/fclib_global", ReadErrorKind::Invalid, e.0))
}

/// Writes datasets, naming the target file (not the temporary one) in errors.
struct Writer<'a> {
    path: &'a Path,
}

impl Writer<'_> {
    fn err(&self, at: &str, e: impl std::fmt::Display) -> ReadError {
        ReadError::new(
            self.path,
            Position::Dataset(at.to_string()),
            ReadErrorKind::Io,
            e.to_string(),
        )
    }

    fn group(&self, parent: &h5::Group, at: &str) -> Result<h5::Group, ReadError> {
        let name = at.rsplit('/').next().unwrap_or(at);
        parent.create_group(name).map_err(|e| self.err(at, e))
    }

    fn ints(&self, g: &h5::Group, at: &str, v: &[usize]) -> Result<(), ReadError> {
        let v: Vec<i32> = v
            .iter()
            .map(|&x| i32::try_from(x))
            .collect::<Result<_, _>>()
            .map_err(|_| {
                ReadError::new(
                    self.path,
                    Position::Dataset(at.to_string()),
                    ReadErrorKind::Unsupported,
                    "a value exceeds FCLib's int32 range",
                )
            })?;
        self.data(g, at, v.as_slice())
    }

    fn reals(&self, g: &h5::Group, at: &str, v: &[f64]) -> Result<(), ReadError> {
        self.data(g, at, v)
    }

    fn data<T: h5::H5Type>(&self, g: &h5::Group, at: &str, v: &[T]) -> Result<(), ReadError> {
        let name = at.rsplit('/').next().unwrap_or(at);
        g.new_dataset_builder()
            .with_data(v)
            .create(name)
            .map(|_| ())
            .map_err(|e| self.err(at, e))
    }

    /// `a` as a CSR group (`nz = -2`).
    fn matrix(&self, parent: &h5::Group, at: &str, a: &CsrMatrix) -> Result<(), ReadError> {
        let g = self.group(parent, at)?;
        self.ints(&g, &format!("{at}/m"), &[a.nrows])?;
        self.ints(&g, &format!("{at}/n"), &[a.ncols])?;
        self.ints(&g, &format!("{at}/nzmax"), &[a.nnz()])?;
        self.data(&g, &format!("{at}/nz"), &[-2i32])?;
        self.ints(&g, &format!("{at}/p"), &a.row_ptr)?;
        self.ints(&g, &format!("{at}/i"), &a.col_idx)?;
        self.reals(&g, &format!("{at}/x"), &a.values)
    }
}
