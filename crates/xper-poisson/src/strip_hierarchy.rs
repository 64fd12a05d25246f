//! The levels of a strip multigrid over all its processes: which strips each level has, which
//! process holds each, and how a level hands its residual to the next (Trottenberg et al.,
//! "Multigrid", section 6.3, agglomeration).
//!
//! A level coarsens into the next on the same strips while every strip stays at least
//! [`MIN_STRIP_ROWS`] rows high on the coarse level and whole coarse rows (even cuts). When it
//! cannot, and the grid is still larger than [`GATHERED_CELLS`], the level is **agglomerated**:
//! after its pre-smoothing its residual is re-cut into about half as many strips
//! ([`StripLayout::balanced`], so that they coarsen again; fewer when the grid is too low for
//! that many), held by about every other process of the level, which restrict it and continue
//! the cycle while the others wait for their rows of the correction. Strips thick enough but
//! cut at odd rows are re-cut into as many strips on the same processes. Every process
//! computes the same hierarchy from the same layout. The coarsest level (at most
//! [`GATHERED_CELLS`] cells, or a grid that does not halve) is gathered by the processes that
//! hold it and relaxed whole by each.
//!
//! Without agglomeration 48 strips of a 1024 x 1024 grid stop coarsening at 20-row strips of
//! 256 x 256 (thinner than `2 MIN_STRIP_ROWS` one level down) and every process relaxes those
//! 65,536 cells each cycle, three times its share of the fine grid; agglomerated, each stage
//! halves the processes and the grid gathered has 1,024 cells.

use crate::strip_level::{Combine, Field, StripLevel};
use crate::strips::{RowLinks, StripLayout, GATHERED_CELLS, MIN_STRIP_ROWS};
use crate::GridShape;
use std::ops::Range;

/// The strips of one level: their row cuts and the process holding each.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Strips {
    /// `strips + 1` row cuts from 0 to `ny`.
    pub starts: Vec<usize>,
    /// The process of each strip, increasing.
    pub ranks: Vec<usize>,
}

impl Strips {
    /// This process's strip, if it holds one.
    pub fn strip_of(&self, rank: usize) -> Option<usize> {
        self.ranks.binary_search(&rank).ok()
    }

    /// The rows of strip `strip`.
    pub fn rows(&self, strip: usize) -> Range<usize> {
        self.starts[strip]..self.starts[strip + 1]
    }

    /// The height of the thinnest strip.
    pub fn thinnest(&self) -> usize {
        self.starts
            .windows(2)
            .map(|w| w[1] - w[0])
            .min()
            .unwrap_or(0)
    }

    /// The processes holding the strips below and above strip `strip` (wrapping around when
    /// `periodic`), `None` on a boundary side.
    pub fn neighbours(&self, strip: usize, periodic: bool) -> [Option<usize>; 2] {
        let n = self.ranks.len();
        let below = (strip > 0 || periodic).then(|| self.ranks[(strip + n - 1) % n]);
        let above = (strip + 1 < n || periodic).then(|| self.ranks[(strip + 1) % n]);
        [below, above]
    }
}

/// How a level hands its residual to the next.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Below {
    /// The next level is this one coarsened, on the same strips.
    Coarser,
    /// The residual is re-cut into these strips (rows of this level), whose processes
    /// coarsen it into the next level.
    Agglomerated(Strips),
    /// The coarsest level: gathered by its processes and relaxed whole.
    Gathered,
}

/// One level: its grid, its strips and how it hands its residual to the next.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LevelPlan {
    pub shape: GridShape,
    pub strips: Strips,
    pub below: Below,
}

impl LevelPlan {
    /// The level's strips and those its residual is re-cut into; only for a level
    /// agglomerated below.
    pub fn agglomeration(&self) -> (&Strips, &Strips) {
        match &self.below {
            Below::Agglomerated(cut) => (&self.strips, cut),
            Below::Coarser | Below::Gathered => panic!("a level not agglomerated below"),
        }
    }
}

/// The levels of the strip multigrid of `layout` (strip `s` on process `s`) over `shape`.
pub(crate) fn plan_levels(shape: GridShape, layout: &StripLayout) -> Vec<LevelPlan> {
    let mut levels = Vec::new();
    let mut shape = shape;
    let mut strips = Strips {
        starts: layout.starts.clone(),
        ranks: (0..layout.strips()).collect(),
    };
    loop {
        let (nx, ny) = (shape.nx, shape.ny);
        let halves = nx % 2 == 0 && nx >= 4 && ny % 2 == 0 && nx * ny > GATHERED_CELLS;
        let thick = strips.thinnest() >= 2 * MIN_STRIP_ROWS;
        let even = strips.starts.iter().all(|s| s % 2 == 0);
        let count = strips.ranks.len();
        let below = if halves && thick && even {
            Below::Coarser
        } else if halves && count > 1 {
            // Strips of at least 2 MIN_STRIP_ROWS rows cut at even rows coarsen at least once;
            // strips thick enough but cut at odd rows are only re-cut, on the same processes.
            let fewer = if thick { count } else { count.div_ceil(2) };
            let fewer = fewer.min(ny / (2 * MIN_STRIP_ROWS)).max(1);
            Below::Agglomerated(Strips {
                starts: StripLayout::balanced(nx, ny, fewer)
                    .expect("ny / (2 MIN_STRIP_ROWS) strips fit a grid of ny rows")
                    .starts,
                ranks: (0..fewer)
                    .map(|t| strips.ranks[t * count / fewer])
                    .collect(),
            })
        } else {
            levels.push(LevelPlan {
                shape,
                strips,
                below: Below::Gathered,
            });
            return levels;
        };
        let next = match &below {
            Below::Agglomerated(cut) => cut,
            _ => &strips,
        };
        let next = Strips {
            starts: next.starts.iter().map(|s| s / 2).collect(),
            ranks: next.ranks.clone(),
        };
        levels.push(LevelPlan {
            shape,
            strips,
            below,
        });
        shape = GridShape {
            nx: nx / 2,
            ny: ny / 2,
            hx: 2.0 * shape.hx,
            hy: 2.0 * shape.hy,
        };
        strips = next;
    }
}

/// The rows of `rows` that each strip of `starts` holds, as `(strip, rows)`, in order.
pub(crate) fn overlaps(starts: &[usize], rows: Range<usize>) -> Vec<(usize, Range<usize>)> {
    starts
        .windows(2)
        .enumerate()
        .filter_map(|(s, w)| {
            let common = w[0].max(rows.start)..w[1].min(rows.end);
            (common.start < common.end).then_some((s, common))
        })
        .collect()
}

/// Moves the cells of `field` from the strips `from` to the strips `to` of the same level:
/// process `me` sends the rows of its strip of `from` (held by `source`, if it holds one) that
/// other processes' strips of `to` hold, and writes into its strip of `to` (held by `target`)
/// the rows it receives and the rows it holds in both, as `combine` says.
#[allow(clippy::too_many_arguments)]
pub(crate) fn move_rows(
    links: &mut dyn RowLinks,
    me: usize,
    from: &Strips,
    source: Option<&StripLevel>,
    to: &Strips,
    target: Option<&mut StripLevel>,
    field: Field,
    combine: Combine,
) {
    let rows_of = |level: &StripLevel| level.first_row..level.first_row + level.rows;
    let mut sends = Vec::new();
    let mut kept = None;
    if let Some(source) = source {
        for (t, rows) in overlaps(&to.starts, rows_of(source)) {
            let cells = source.copy_rows(field, rows.clone());
            if to.ranks[t] == me {
                kept = Some((rows.start, cells));
            } else {
                sends.push((to.ranks[t], cells));
            }
        }
    }
    let mut sources = Vec::new();
    let mut places = Vec::new();
    if let Some(target) = &target {
        for (s, rows) in overlaps(&from.starts, rows_of(target)) {
            if from.ranks[s] != me {
                sources.push(from.ranks[s]);
                places.push(rows);
            }
        }
    }
    let received = if sends.is_empty() && sources.is_empty() {
        Vec::new()
    } else {
        links.send_receive(sends, &sources)
    };
    if let Some(target) = target {
        if let Some((first, cells)) = kept {
            target.write_rows(field, first, &cells, combine);
        }
        for (rows, cells) in places.into_iter().zip(received) {
            assert_eq!(
                cells.len(),
                target.nx * rows.len(),
                "agglomerated rows {rows:?}: not the rows asked for"
            );
            target.write_rows(field, rows.start, &cells, combine);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(nx: usize, ny: usize) -> GridShape {
        GridShape {
            nx,
            ny,
            hx: 1.0,
            hy: 1.0,
        }
    }

    /// Every level's strips cover its grid, nest (a process holding a strip held one on the
    /// level above), are at least `MIN_STRIP_ROWS` high, and the coarsest grid is at most
    /// `GATHERED_CELLS` cells whenever the grid halves that far.
    #[test]
    fn agglomerated_levels_nest_and_end_at_a_small_gathered_grid() {
        for (nx, ny, strips, gathered_rank_count) in [
            (160, 640, 2, 2),
            (1024, 1024, 48, 6),
            (4096, 4096, 48, 6),
            (4096, 4096, 1024, 8),
            (256, 64, 8, 4),
        ] {
            let layout = StripLayout::balanced(nx, ny, strips).unwrap();
            let levels = plan_levels(square(nx, ny), &layout);
            for pair in levels.windows(2) {
                let (upper, lower) = (&pair[0].strips, &pair[1].strips);
                assert!(lower.ranks.iter().all(|r| upper.ranks.contains(r)));
                assert_eq!(pair[1].shape.nx * 2, pair[0].shape.nx);
            }
            for level in &levels {
                let strips = &level.strips;
                assert_eq!(strips.starts.first(), Some(&0));
                assert_eq!(strips.starts.last(), Some(&level.shape.ny));
                assert_eq!(strips.starts.len(), strips.ranks.len() + 1);
                assert!(strips.thinnest() >= MIN_STRIP_ROWS);
            }
            let bottom = levels.last().unwrap();
            assert!(bottom.shape.nx * bottom.shape.ny <= GATHERED_CELLS);
            assert_eq!(
                bottom.strips.strip_of(0),
                Some(0),
                "process 0 holds every level"
            );
            assert_eq!(
                bottom.strips.ranks.len(),
                gathered_rank_count,
                "{nx} x {ny} on {strips}"
            );
        }
    }

    /// Thick strips cut at an odd row are re-cut at even rows on the same processes, not
    /// halved.
    #[test]
    fn thick_strips_cut_at_odd_rows_keep_their_processes() {
        let layout = StripLayout {
            starts: vec![0, 80, 161, 240],
        };
        let levels = plan_levels(square(64, 240), &layout);
        let Below::Agglomerated(cut) = &levels[0].below else {
            panic!("{:?}", levels[0].below);
        };
        assert_eq!(cut.ranks, vec![0, 1, 2]);
        assert!(cut.starts.iter().all(|s| s % 2 == 0), "{:?}", cut.starts);
        assert_eq!(levels[1].strips.ranks, vec![0, 1, 2]);
    }

    #[test]
    fn overlaps_cut_a_range_at_the_strips() {
        assert_eq!(
            overlaps(&[0, 4, 10, 16], 3..12),
            vec![(0, 3..4), (1, 4..10), (2, 10..12)]
        );
        assert_eq!(overlaps(&[0, 4, 10], 4..10), vec![(1, 4..10)]);
    }
}
