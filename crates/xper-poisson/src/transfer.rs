//! Grid transfers between a level and the next coarser one, as tensor products of 1D maps.
//!
//! Along one axis the fine grid has `nf` cells and the coarse grid `nc = nf`, `nf / 2` or
//! `ceil(nf / 2)` uniform cells over the same length `L`. Lengths are measured in units of
//! `L / (nf nc)`, so fine cell `i` is `[i nc, (i + 1) nc]`, coarse cell `I` is
//! `[I nf, (I + 1) nf]`, and all weights below are exact ratios of integers.
//!
//! - restriction: coarse value = average of the fine values over the coarse cell, i.e. each
//!   fine cell gives `overlap / nf` of its value to the (at most two) coarse cells it
//!   overlaps;
//! - prolongation: linear interpolation between the two coarse centres around each fine
//!   centre; beyond the first or last coarse centre the ghost value (mirror for Neumann,
//!   negated mirror for Dirichlet, opposite cell for periodic) is folded into the weights.

use crate::level::Level;
use crate::PoissonSide;

/// How a fine axis maps to the coarse one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Not coarsened.
    Identity,
    /// Two fine cells per coarse cell (vectorised fast paths).
    Halve,
    /// Any other ratio (odd `nf`).
    General,
}

/// Two (coarse index, weight) pairs.
type Pair = [(usize, f64); 2];

/// The 1D restriction and prolongation weights of one axis.
struct AxisMap {
    kind: Kind,
    coarse: usize,
    sides: [PoissonSide; 2],
    /// Per fine cell, where its value goes (restriction).
    restrict: Vec<Pair>,
    /// Per fine cell, where its value comes from (prolongation).
    prolong: Vec<Pair>,
}

impl AxisMap {
    fn new(nf: usize, nc: usize, sides: [PoissonSide; 2]) -> Self {
        let kind = if nc == nf {
            Kind::Identity
        } else if nf == 2 * nc {
            Kind::Halve
        } else {
            Kind::General
        };
        let restrict = (0..nf)
            .map(|i| {
                let (start, end) = (i * nc, (i + 1) * nc);
                let a = start / nf;
                let in_a = end.min((a + 1) * nf) - start;
                let b = if in_a < nc { a + 1 } else { a };
                [
                    (a, in_a as f64 / nf as f64),
                    (b, (nc - in_a) as f64 / nf as f64),
                ]
            })
            .collect();
        let fold = |index: isize, weight: f64| -> (usize, f64) {
            let last = nc as isize - 1;
            let (side, mirror, wrap) = if index < 0 {
                (sides[0], 0, last)
            } else if index > last {
                (sides[1], last, 0)
            } else {
                return (index as usize, weight);
            };
            match side {
                PoissonSide::Neumann => (mirror as usize, weight),
                PoissonSide::Dirichlet => (mirror as usize, -weight),
                PoissonSide::Periodic => (wrap as usize, weight),
            }
        };
        let prolong = (0..nf)
            .map(|i| {
                // Fine centre in coarse-centre coordinates, times 2 nf.
                let s = ((2 * i + 1) * nc) as isize - nf as isize;
                let span = 2 * nf as isize;
                let (a, rem) = (s.div_euclid(span), s.rem_euclid(span));
                let t = rem as f64 / span as f64;
                [fold(a, 1.0 - t), fold(a + 1, t)]
            })
            .collect();
        AxisMap {
            kind,
            coarse: nc,
            sides,
            restrict,
            prolong,
        }
    }
}

/// The transfers between one level and the next coarser one.
pub(crate) struct Transfer {
    x: AxisMap,
    y: AxisMap,
    /// A coarse row interpolated in y, with a ghost at each end (`nc + 2`).
    line: Vec<f64>,
}

impl Transfer {
    pub fn new(
        fine: &Level,
        coarse: &Level,
        x_sides: [PoissonSide; 2],
        y_sides: [PoissonSide; 2],
    ) -> Self {
        Transfer {
            x: AxisMap::new(fine.nx, coarse.nx, x_sides),
            y: AxisMap::new(fine.ny, coarse.ny, y_sides),
            line: vec![0.0; coarse.nx + 2],
        }
    }

    /// Adds the restriction of the residual `r` of fine row `j` to the coarse rhs.
    pub fn restrict_row(&self, j: usize, r: &[f64], coarse: &mut Level) {
        let nc = self.x.coarse;
        let stride = coarse.stride();
        let row = &mut coarse.row;
        let src: &[f64] = match self.x.kind {
            Kind::Identity => r,
            Kind::Halve => {
                for (c, pair) in row.iter_mut().zip(r.chunks_exact(2)) {
                    *c = 0.5 * (pair[0] + pair[1]);
                }
                row
            }
            Kind::General => {
                row.fill(0.0);
                for (&v, weights) in r.iter().zip(&self.x.restrict) {
                    for &(c, w) in weights {
                        row[c] += w * v;
                    }
                }
                row
            }
        };
        for &(c, w) in &self.y.restrict[j] {
            if w != 0.0 {
                let start = 1 + stride * (c + 1);
                for (f, &v) in coarse.f[start..start + nc].iter_mut().zip(src) {
                    *f += w * v;
                }
            }
        }
    }

    /// Adds the interpolated coarse correction `coarse.u` to `fine.u`.
    pub fn prolong(&mut self, coarse: &Level, fine: &mut Level) {
        let nc = self.x.coarse;
        let stride = coarse.stride();
        for j in 0..fine.ny {
            let [(ja, wa), (jb, wb)] = self.y.prolong[j];
            let a = &coarse.u[1 + stride * (ja + 1)..][..nc];
            let b = &coarse.u[1 + stride * (jb + 1)..][..nc];
            let line = &mut self.line;
            for ((l, &va), &vb) in line[1..nc + 1].iter_mut().zip(a).zip(b) {
                *l = wa * va + wb * vb;
            }
            let start = fine.row_start(j);
            let out = &mut fine.u[start..start + fine.nx];
            match self.x.kind {
                Kind::Identity => {
                    for (o, &l) in out.iter_mut().zip(&line[1..]) {
                        *o += l;
                    }
                }
                Kind::Halve => {
                    let ghost = |side, inside: f64, opposite: f64| match side {
                        PoissonSide::Neumann => inside,
                        PoissonSide::Dirichlet => -inside,
                        PoissonSide::Periodic => opposite,
                    };
                    line[0] = ghost(self.x.sides[0], line[1], line[nc]);
                    line[nc + 1] = ghost(self.x.sides[1], line[nc], line[1]);
                    for (pair, l) in out.chunks_exact_mut(2).zip(line.windows(3)) {
                        pair[0] += 0.75 * l[1] + 0.25 * l[0];
                        pair[1] += 0.75 * l[1] + 0.25 * l[2];
                    }
                }
                Kind::General => {
                    for (o, weights) in out.iter_mut().zip(&self.x.prolong) {
                        let [(a, wa), (b, wb)] = *weights;
                        *o += wa * line[a + 1] + wb * line[b + 1];
                    }
                }
            }
        }
    }
}
