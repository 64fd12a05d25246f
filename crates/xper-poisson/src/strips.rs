//! The grid cut into horizontal strips, one per process: the layout of the strips and what a
//! strip needs from the others ([`RowLinks`]). One multigrid level of a strip, with its ghost
//! rows, is the private module `strip_level`.

/// The row exchange of one strip with its neighbours on a level: what a level's smoothing,
/// residual and prolongation need ([`RowLinks`] for the strip's own neighbours, the private
/// `AgglomeratedLinks` for a level held by some of the processes).
pub trait RowExchange {
    /// Sends `to_below` to the strip below and `to_above` to the strip above (`None` where
    /// this side is the domain's boundary), runs `work` exactly once while the rows travel (it
    /// must not need what arrives), and returns what the neighbours sent here: `[from_below,
    /// from_above]`, the rows the strip below sent up and the rows the strip above sent down.
    fn exchange_rows_overlapped(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2];
    /// [`RowExchange::exchange_rows_overlapped`] with nothing to overlap.
    fn exchange_rows(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
    ) -> [Option<Vec<f64>>; 2] {
        self.exchange_rows_overlapped(to_below, to_above, &mut || {})
    }
}

/// What a strip needs from the processes holding the other strips.
///
/// Strip `s`'s neighbour below is `s - 1` (the last strip for `s = 0` when the bottom and top
/// are periodic) and its neighbour above `s + 1` (the first strip for the last one when
/// periodic). The strips of a level make the same calls in the same order: on the levels every
/// strip holds, every strip; on an agglomerated level, its strips only
/// ([`RowLinks::exchange_rows_among`], [`RowLinks::send_receive`]). The collectives (`sum`,
/// `gather`) are made by every strip.
pub trait RowLinks: RowExchange {
    /// [`RowLinks::exchange_rows_overlapped`] with the strips `neighbours` (`[below, above]`,
    /// `None` on a boundary side) instead of this strip's own: the links of an agglomerated
    /// level, whose strips are held by some of the processes only. Only the strips of that
    /// level make the call.
    fn exchange_rows_among(
        &mut self,
        neighbours: [Option<usize>; 2],
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2];
    /// Sends each `(strip, values)` of `sends` to that strip (never this one) and returns one
    /// message from each strip of `sources` (never this one), in their order: the rows that
    /// move between the processes of two agglomeration stages. Only the strips concerned
    /// make the call.
    fn send_receive(&mut self, sends: Vec<(usize, Vec<f64>)>, sources: &[usize]) -> Vec<Vec<f64>>;
    /// Replaces each value by its sum over the strips (the same bits on every strip).
    fn sum(&mut self, values: &mut [f64]);
    /// Every strip's `values` concatenated in strip order, on every strip. Every strip passes
    /// the same number of values (so one fixed-size collective can carry them).
    fn gather(&mut self, values: &[f64]) -> Vec<f64>;
}

/// The links of a grid held whole by one process: periodic sides link the strip to itself.
#[derive(Clone, Copy, Debug, Default)]
pub struct OneStrip;

impl RowExchange for OneStrip {
    fn exchange_rows_overlapped(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        work();
        [to_above.map(<[f64]>::to_vec), to_below.map(<[f64]>::to_vec)]
    }
}

impl RowLinks for OneStrip {
    fn exchange_rows_among(
        &mut self,
        _neighbours: [Option<usize>; 2],
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        self.exchange_rows_overlapped(to_below, to_above, work)
    }
    fn send_receive(&mut self, sends: Vec<(usize, Vec<f64>)>, sources: &[usize]) -> Vec<Vec<f64>> {
        assert!(
            sends.is_empty() && sources.is_empty(),
            "a grid held by one strip has no other strip to send rows to"
        );
        Vec::new()
    }
    fn sum(&mut self, _values: &mut [f64]) {}
    fn gather(&mut self, values: &[f64]) -> Vec<f64> {
        values.to_vec()
    }
}

/// [`OneStrip`] counting the calls a distributed run would turn into messages (tests and
/// `strip_bench`).
#[derive(Clone, Copy, Debug, Default)]
pub struct CountingLinks {
    /// Row exchanges.
    pub exchanges: usize,
    /// Sums over the strips.
    pub sums: usize,
    /// Gathers of the coarse grid.
    pub gathers: usize,
}

impl RowExchange for CountingLinks {
    fn exchange_rows_overlapped(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        self.exchanges += 1;
        OneStrip.exchange_rows_overlapped(to_below, to_above, work)
    }
}

impl RowLinks for CountingLinks {
    fn exchange_rows_among(
        &mut self,
        neighbours: [Option<usize>; 2],
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        self.exchanges += 1;
        OneStrip.exchange_rows_among(neighbours, to_below, to_above, work)
    }
    fn send_receive(&mut self, sends: Vec<(usize, Vec<f64>)>, sources: &[usize]) -> Vec<Vec<f64>> {
        OneStrip.send_receive(sends, sources)
    }
    fn sum(&mut self, values: &mut [f64]) {
        self.sums += 1;
        OneStrip.sum(values)
    }
    fn gather(&mut self, values: &[f64]) -> Vec<f64> {
        self.gathers += 1;
        OneStrip.gather(values)
    }
}

/// The row exchange of an agglomerated level: with the strips `neighbours` of that level
/// ([`RowLinks::exchange_rows_among`]). It has no collective: only some processes hold the
/// level.
pub(crate) struct AgglomeratedLinks<'a> {
    pub links: &'a mut dyn RowLinks,
    pub neighbours: [Option<usize>; 2],
}

impl RowExchange for AgglomeratedLinks<'_> {
    fn exchange_rows_overlapped(
        &mut self,
        to_below: Option<&[f64]>,
        to_above: Option<&[f64]>,
        work: &mut dyn FnMut(),
    ) -> [Option<Vec<f64>>; 2] {
        (self.links).exchange_rows_among(self.neighbours, to_below, to_above, work)
    }
}

/// The rows of each strip: strip `s` holds `starts[s]..starts[s + 1]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StripLayout {
    /// `strips + 1` increasing row boundaries from 0 to `ny`.
    pub starts: Vec<usize>,
}

/// Coarse grids at most this large are gathered and relaxed whole by the processes holding
/// their strips (every process unless an agglomeration left some out).
pub const GATHERED_CELLS: usize = 1024;

impl StripLayout {
    /// `strips` strips of nearly equal height over an `nx x ny` grid, cut at multiples of the
    /// largest power of two `2^k` that divides `nx` and `ny`, leaves every strip at least
    /// [`MIN_STRIP_ROWS`] blocks of `2^k` rows, and is not beyond what brings the grid down to
    /// [`GATHERED_CELLS`]: the strips then coarsen `k` times without cutting a coarse cell.
    pub fn balanced(nx: usize, ny: usize, strips: usize) -> Result<Self, String> {
        let unit = Self::unit_rows(nx, ny, strips)?;
        let blocks = ny / unit;
        let starts = (0..=strips).map(|s| unit * (blocks * s / strips)).collect();
        Ok(StripLayout { starts })
    }

    /// `strips` strips over an `nx x ny` grid cut where [`StripLayout::balanced`] may cut, so
    /// that the strips carry nearly equal sums of `row_weight` (one non-negative weight per
    /// row: the work of the row), each keeping at least [`MIN_STRIP_ROWS`] blocks. Each cut is
    /// the block boundary nearest to its share of the total weight, so the shares are equal
    /// to within half a block's weight. Weights all zero give the balanced strips.
    pub fn weighted(
        nx: usize,
        ny: usize,
        strips: usize,
        row_weight: &[f64],
    ) -> Result<Self, String> {
        if row_weight.len() != ny || !row_weight.iter().all(|w| *w >= 0.0 && w.is_finite()) {
            return Err(format!(
                "{} row weights for {ny} rows, or a weight negative or not finite",
                row_weight.len()
            ));
        }
        let unit = Self::unit_rows(nx, ny, strips)?;
        let blocks = ny / unit;
        // before[b]: the weight of blocks 0..b.
        let mut before = vec![0.0; blocks + 1];
        for b in 0..blocks {
            before[b + 1] = before[b] + row_weight[b * unit..(b + 1) * unit].iter().sum::<f64>();
        }
        let total = before[blocks];
        if total == 0.0 {
            return Self::balanced(nx, ny, strips);
        }
        let mut starts = vec![0; strips + 1];
        let mut cut = 0;
        for (s, start) in starts.iter_mut().enumerate().take(strips).skip(1) {
            let share = total * s as f64 / strips as f64;
            let mut b = before.partition_point(|&w| w < share).min(blocks);
            if b > 0 && share - before[b - 1] < before[b] - share {
                b -= 1;
            }
            let lowest = cut + MIN_STRIP_ROWS;
            let highest = blocks - (strips - s) * MIN_STRIP_ROWS;
            cut = b.clamp(lowest, highest);
            *start = unit * cut;
        }
        starts[strips] = ny;
        Ok(StripLayout { starts })
    }

    /// The rows of the blocks strips are cut in: the largest power of two `2^k` dividing `nx`
    /// and `ny` that leaves every strip at least [`MIN_STRIP_ROWS`] blocks and does not coarsen
    /// beyond [`GATHERED_CELLS`].
    fn unit_rows(nx: usize, ny: usize, strips: usize) -> Result<usize, String> {
        if strips == 0 || ny < MIN_STRIP_ROWS * strips {
            return Err(format!(
                "{ny} rows cannot be shared among {strips} strips (at least {MIN_STRIP_ROWS} rows each)"
            ));
        }
        let mut unit = 1;
        while nx.is_multiple_of(2 * unit)
            && ny.is_multiple_of(2 * unit)
            && ny / (2 * unit) >= MIN_STRIP_ROWS * strips
            && (nx / unit) * (ny / unit) > GATHERED_CELLS
        {
            unit *= 2;
        }
        Ok(unit)
    }

    /// Number of strips.
    pub fn strips(&self) -> usize {
        self.starts.len() - 1
    }

    /// The global rows of strip `s`.
    pub fn rows(&self, s: usize) -> std::ops::Range<usize> {
        self.starts[s]..self.starts[s + 1]
    }
}

/// Strips at least this many rows high on every strip level: a level smoothed between two
/// exchanges needs `2 s + 1` ghost rows for `s` sweeps, all from the neighbouring strip, so a
/// smoothed level (whose strips coarsen to this many rows) holds the 5 of the default V(2,1)
/// and at least the 3 of one sweep.
pub const MIN_STRIP_ROWS: usize = 3;
