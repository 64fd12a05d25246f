//! The staggered Marker-And-Cell grid (Harlow and Welch, Phys. Fluids 8 (1965) 2182).
//!
//! `nx` by `ny` square cells of side `h` cover `[x0, x0 + nx h] x [y0, y0 + ny h]`. Pressure
//! lives at cell centres, the velocity component `d` on the faces normal to axis `d`: `u` at
//! `(x0 + i h, y0 + (j + 1/2) h)`, `v` at `(x0 + (i + 1/2) h, y0 + j h)`.
//!
//! Every field (pressure and each velocity component) is stored in one padded array shape of
//! `(nx + 3) x (ny + 3)` entries with one ghost layer below index 0: the entry `(i, j)` of any
//! field is at `(i + 1) + (nx + 3) (j + 1)` for `i` in `-1..=nx + 1`, `j` in `-1..=ny + 1`. One
//! shape for all fields makes neighbour offsets (`stride(d)`) the same for every component,
//! so the momentum and projection stencils are written once for all components: the cell
//! `(i, j)` lies between the faces `(i, j)` and `(i, j) + e_d` of component `d`.

use serde::{Deserialize, Serialize};
use xper_math::{Real, Vector, DIM};

/// The geometry of a uniform MAC grid.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MacGrid {
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Cell side (m).
    pub h: Real,
    /// Lower-left corner of the domain (m).
    pub origin: Vector,
}

impl MacGrid {
    /// `n x n` cells covering the square `[0, side]^2` (m).
    pub fn square(n: usize, side: Real) -> Self {
        MacGrid {
            nx: n,
            ny: n,
            h: side / n as Real,
            origin: Vector::zeros(),
        }
    }

    /// Cells along axis `d`.
    #[inline]
    pub fn cells(&self, d: usize) -> usize {
        [self.nx, self.ny][d]
    }

    /// Total number of cells.
    pub fn num_cells(&self) -> usize {
        self.nx * self.ny
    }

    /// Row length of the padded arrays.
    #[inline]
    pub fn width(&self) -> usize {
        self.nx + 3
    }

    /// Length of a padded array.
    pub fn padded_len(&self) -> usize {
        (self.nx + 3) * (self.ny + 3)
    }

    /// Offset between neighbours along axis `d` in a padded array.
    #[inline]
    pub fn stride(&self, d: usize) -> usize {
        if d == 0 {
            1
        } else {
            self.width()
        }
    }

    /// Padded index of entry `(i, j)`, `i, j >= -1`.
    #[inline]
    pub fn index(&self, i: isize, j: isize) -> usize {
        ((i + 1) as usize) + self.width() * ((j + 1) as usize)
    }

    /// Row-major index `i + nx j` of cell `(i, j)` in an unpadded cell array.
    #[inline]
    pub fn cell_index(&self, i: usize, j: usize) -> usize {
        i + self.nx * j
    }

    /// Domain size (m).
    pub fn extent(&self) -> Vector {
        Vector::new(self.nx as Real * self.h, self.ny as Real * self.h)
    }

    /// Position of the face `(i, j)` carrying component `d`.
    #[inline]
    pub fn face_position(&self, d: usize, i: isize, j: isize) -> Vector {
        let (ox, oy) = if d == 0 { (0.0, 0.5) } else { (0.5, 0.0) };
        Vector::new(
            self.origin.x + (i as Real + ox) * self.h,
            self.origin.y + (j as Real + oy) * self.h,
        )
    }

    /// Position of the centre of cell `(i, j)`.
    #[inline]
    pub fn cell_centre(&self, i: usize, j: usize) -> Vector {
        Vector::new(
            self.origin.x + (i as Real + 0.5) * self.h,
            self.origin.y + (j as Real + 0.5) * self.h,
        )
    }

    /// The padded index ranges, one contiguous run per grid row, of the entries `(i, j)` of a
    /// component-`d` array with the index along `d` in `along` and the other in `0..cells`:
    /// loops over these runs visit memory in order whatever the component.
    pub fn face_rows(
        &self,
        d: usize,
        along: std::ops::Range<isize>,
    ) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
        let (columns, rows) = if d == 0 {
            (along, 0..self.ny as isize)
        } else {
            (0..self.nx as isize, along)
        };
        rows.map(move |j| self.index(columns.start, j)..self.index(columns.end, j))
    }

    /// A zero padded array.
    pub fn zeros(&self) -> Vec<Real> {
        vec![0.0; self.padded_len()]
    }

    /// Zero padded arrays, one per velocity component.
    pub fn zero_velocity(&self) -> [Vec<Real>; DIM] {
        [self.zeros(), self.zeros()]
    }
}
