//! The fluid of one block of a grid split among processes, and what a block needs from the
//! others.
//!
//! The grid is cut into horizontal blocks of whole rows (the strips of
//! [`xper_poisson::StripLayout`]). A block is stepped by the same stages as the whole grid on
//! its own [`MacGrid`] (the block's rows, its origin shifted), with [`SideCondition::Neighbour`]
//! on the sides it shares: the predictor reads one ghost row below and two above (the layout
//! of a periodic side), which [`BlockLinks::exchange_halo`] copies from the neighbours after
//! every change of the fields; each face is computed by one block (the `v` faces on a cut by
//! the block above it); sums over the grid (forces on grains, norms, energies) and the largest
//! speed go through [`BlockLinks::sum`] and [`BlockLinks::max`], and the pressure equation is
//! solved over the whole grid by [`BlockLinks::solve_pressure`].
//!
//! [`SideCondition::Neighbour`]: crate::SideCondition::Neighbour

use crate::grid::MacGrid;
use xper_math::Real;
use xper_poisson::{Multigrid, MultigridError, MultigridInfo};

/// Ghost rows a block reads below its first row.
pub const HALO_BELOW: usize = 1;
/// Ghost rows a block reads above its last row (the faces on its top side and one more).
pub const HALO_ABOVE: usize = 2;

/// What a block of the grid needs from the processes holding the other blocks. Every block
/// makes the same calls in the same order.
pub trait BlockLinks {
    /// Fills the ghost rows of every padded array of `fields` on the block's neighbour sides
    /// with the neighbours' rows (whole padded rows, ghost columns included).
    fn exchange_halo(&mut self, grid: &MacGrid, fields: &mut [&mut [Real]]);
    /// Replaces each value by its sum over the blocks.
    fn sum(&mut self, values: &mut [Real]);
    /// Replaces each value by its maximum over the blocks.
    fn max(&mut self, values: &mut [Real]);
    /// [`BlockLinks::sum`] of `sums` and [`BlockLinks::max`] of `maxima` in one reduction,
    /// where the links can (one synchronisation of the processes instead of two).
    fn sum_and_max(&mut self, sums: &mut [Real], maxima: &mut [Real]) {
        self.sum(sums);
        self.max(maxima);
    }
    /// Solves the pressure-correction equation of the whole grid; `rhs` and `phi` hold this
    /// block's cells (row-major, unpadded), `phi` the initial guess on entry.
    fn solve_pressure(
        &mut self,
        rhs: &[Real],
        phi: &mut [Real],
    ) -> Result<MultigridInfo, MultigridError>;
}

/// The whole grid on one process: no halo to exchange, reductions are the identity, the
/// pressure is solved by the serial multigrid.
pub struct WholeGrid {
    /// The pressure solver.
    pub multigrid: Multigrid,
}

impl BlockLinks for WholeGrid {
    fn exchange_halo(&mut self, _grid: &MacGrid, _fields: &mut [&mut [Real]]) {}
    fn sum(&mut self, _values: &mut [Real]) {}
    fn max(&mut self, _values: &mut [Real]) {}
    fn solve_pressure(
        &mut self,
        rhs: &[Real],
        phi: &mut [Real],
    ) -> Result<MultigridInfo, MultigridError> {
        self.multigrid.solve(rhs, phi)
    }
}
