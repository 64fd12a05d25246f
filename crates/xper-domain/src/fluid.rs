//! Distributed grains in a fluid: the grid cut into horizontal blocks of rows, one per process.
//!
//! 1. **Partition.** [`StripLayout::weighted`] cuts the rows into blocks of nearly equal work
//!    at multiples of a power of two, so that the pressure multigrid coarsens the blocks
//!    without cutting a coarse cell. The work of a row is its cells plus, for each grain whose
//!    forcing footprint crosses it, [`FORCED_CELL_WEIGHT`] per footprint cell. Each process
//!    holds its block of the fluid ([`FluidState`] on the block's [`MacGrid`]) and every grain
//!    (there are few grains and many cells: the grains' contact step is repeated by every
//!    process, which gets the same forces and so the same bits, and a grain straddling a cut
//!    needs no migration). Before every step the cuts are recomputed from the grains'
//!    positions (a weight per row: cheap; the same on every process, so every process takes
//!    the same decision); when they moved, each process receives the rows its new block needs
//!    from the processes holding them, those that change owner and its halo rows
//!    ([`DistributedFluid::recut`]), and then holds what a resume from a checkpoint would
//!    give it. The cuts are a function of the current state alone, so a run resumed from any
//!    step, on the same number of processes, continues bit for bit. (A cut that should not
//!    flip back and forth needs the current cuts in the checkpoint; they are not there yet.)
//! 2. **Step.** [`CoupledStepper::step_with`] runs the serial stages on the block, with
//!    [`BlockLinks`] for what crosses blocks: the halo rows (one below, two above) after every
//!    change of the velocity, pressure or pressure correction; the forcing and the fluid
//!    momentum inside each grain summed over blocks (each face is forced by one block, so a
//!    grain across a cut is counted once), with the norms, the energy and the largest speed
//!    (the next step's time step) in one reduction at the end of the step;
//!    the pressure solved by [`StripMultigrid`], deep ghost rows exchanged twice per level
//!    and cycle.
//! 3. **Gather** (outputs, checkpoints): rank 0 receives every block's rows and holds the whole
//!    fluid, from which a run resumes on any number of processes.

use crate::comm::Communicator;
use crate::halo::{exchange_with_neighbours, strip_neighbours, StripComm};
use crate::rigid::stepper::RankLoad;
use std::ops::Range;
use xper_bodies::Shape;
use xper_fluid::blocks::{HALO_ABOVE, HALO_BELOW};
use xper_fluid::solver::pressure_multigrid;
use xper_fluid::{
    BlockLinks, CoupledError, CoupledReport, CoupledState, CoupledStepper, FluidError, FluidParams,
    FluidState, MacGrid,
};
use xper_math::{Real, Vector};
use xper_nscd::World;
use xper_poisson::{MultigridError, MultigridInfo, StripLayout, StripMultigrid};

/// The links of one block: halo rows with the neighbours, reductions over `comm`, the pressure
/// by the strip multigrid.
struct BlockComm<'c, C: Communicator + ?Sized> {
    rows: StripComm<'c, C>,
    multigrid: StripMultigrid,
}

impl<C: Communicator + ?Sized> BlockLinks for BlockComm<'_, C> {
    fn exchange_halo(&mut self, grid: &MacGrid, fields: &mut [&mut [Real]]) {
        let (w, n) = (grid.width(), grid.ny);
        let row = |j: isize| ((j + 1) as usize) * w;
        let [below, above] = self.rows.neighbours;
        let pack = |fields: &[&mut [Real]], from: isize, count: usize| {
            let mut out = Vec::with_capacity(fields.len() * count * w);
            for field in fields {
                out.extend_from_slice(&field[row(from)..row(from) + count * w]);
            }
            out
        };
        let to_below = below.map(|_| pack(fields, 0, HALO_ABOVE));
        let to_above = above.map(|_| pack(fields, n as isize - HALO_BELOW as isize, HALO_BELOW));
        let [from_below, from_above] =
            exchange_with_neighbours(self.rows.comm, self.rows.neighbours, to_below, to_above);
        let unpack = |fields: &mut [&mut [Real]], data: &[Real], to: isize, count: usize| {
            for (field, part) in fields.iter_mut().zip(data.chunks_exact(count * w)) {
                field[row(to)..row(to) + count * w].copy_from_slice(part);
            }
        };
        if let Some(data) = from_below {
            unpack(fields, &data, -(HALO_BELOW as isize), HALO_BELOW);
        }
        if let Some(data) = from_above {
            unpack(fields, &data, n as isize, HALO_ABOVE);
        }
    }

    fn sum(&mut self, values: &mut [Real]) {
        self.rows.comm.all_reduce_sum(values);
    }

    fn max(&mut self, values: &mut [Real]) {
        self.rows.comm.all_reduce_max(values);
    }

    fn sum_and_max(&mut self, sums: &mut [Real], maxima: &mut [Real]) {
        self.rows.comm.all_reduce_sum_max(sums, maxima);
    }

    fn solve_pressure(
        &mut self,
        rhs: &[Real],
        phi: &mut [Real],
    ) -> Result<MultigridInfo, MultigridError> {
        self.multigrid.solve(&mut self.rows, rhs, phi)
    }
}

/// Work of a cell in a grain's forcing footprint (the cells within the radius and two cells)
/// besides its fluid work, relative to a fluid cell's: on `suspension_settling` (300 grains of
/// 16 cells across, 512 x 1024 cells, 2 processes) the block holding every grain took
/// 4.7 ms per step more than the other, 16 us per grain and 0.04 us per footprint cell,
/// against 0.08 us per fluid cell. Since the forcing is marked in runs (2026-11-26) the
/// grains' work is about half that, and this weight and equal cells (weight 0) give the same
/// step time there (10.5 s for 508 steps on 2 processes, alternated): the grains' work and
/// the projection lie in stages that each wait for their slowest process, so no cut of rows
/// balances both (`bench-results/NOTES.md`).
pub const FORCED_CELL_WEIGHT: Real = 0.5;

/// The work of each row of `domain`: its cells, plus [`FORCED_CELL_WEIGHT`] per cell of the
/// footprint of each disk of `world` that crosses it.
pub fn row_weights(domain: &MacGrid, world: &World) -> Vec<Real> {
    let h = domain.h;
    let mut weights = vec![domain.nx as Real; domain.ny];
    for (shape, centre) in world.bodies.shape.iter().zip(&world.bodies.position) {
        let Shape::Disk { radius } = shape else {
            continue;
        };
        let reach = radius + 2.0 * h;
        let row = |y: Real| (((y - domain.origin.y) / h).max(0.0) as usize).min(domain.ny);
        let (low, high) = (row(centre.y - reach), row(centre.y + reach + h));
        for weight in &mut weights[low..high] {
            *weight += FORCED_CELL_WEIGHT * 2.0 * reach / h;
        }
    }
    weights
}

/// Grains in a fluid stepped by the processes of `comm` (see the module documentation).
pub struct DistributedFluid<'c, C: Communicator + ?Sized> {
    comm: &'c C,
    layout: StripLayout,
    domain: MacGrid,
    /// The parameters of the whole grid; `params` are the block's.
    whole_params: FluidParams,
    /// Times the blocks were cut again.
    rebalances: u64,
    params: FluidParams,
    state: CoupledState,
    stepper: CoupledStepper,
    links: BlockComm<'c, C>,
}

/// The padded rows of the block of rows `rows`: its own, the ghost row below and the two above.
fn padded_rows(rows: &Range<usize>) -> Range<usize> {
    rows.start..rows.end + 3
}

/// The rows two ranges have in common (empty when none).
fn overlap(a: &Range<usize>, b: &Range<usize>) -> Range<usize> {
    a.start.max(b.start)..a.end.min(b.end).max(a.start.max(b.start))
}

/// The grid of the block of rows `rows` of `domain`.
fn block_grid(domain: &MacGrid, rows: &Range<usize>) -> MacGrid {
    MacGrid {
        ny: rows.len(),
        origin: domain.origin + Vector::new(0.0, rows.start as Real * domain.h),
        ..*domain
    }
}

/// The block of rows `rows` of `whole`, with every grain.
fn block_of(whole: &CoupledState, rows: &Range<usize>) -> CoupledState {
    let fluid = &whole.fluid;
    let (w, nx) = (fluid.grid.width(), fluid.grid.nx);
    let padded = padded_rows(rows);
    let block = |field: &[Real]| field[padded.start * w..padded.end * w].to_vec();
    CoupledState {
        fluid: FluidState {
            grid: block_grid(&fluid.grid, rows),
            velocity: [block(&fluid.velocity[0]), block(&fluid.velocity[1])],
            pressure: block(&fluid.pressure),
            increment: fluid.increment[rows.start * nx..rows.end * nx].to_vec(),
            time: fluid.time,
            step: fluid.step,
            inner: fluid.inner.clone(),
        },
        world: whole.world.clone(),
    }
}

/// Checks that every block of `layout` holds the rows a halo exchange needs.
fn check_layout(layout: &StripLayout, domain: &MacGrid) -> Result<(), FluidError> {
    let strips = layout.starts.len() - 1;
    if (0..strips).any(|s| layout.rows(s).len() < HALO_ABOVE) {
        return Err(FluidError::Setup(format!(
            "{} rows are too few for {strips} processes: every block needs at least {HALO_ABOVE} rows",
            domain.ny
        )));
    }
    Ok(())
}

impl<'c, C: Communicator + ?Sized> DistributedFluid<'c, C> {
    /// Cuts `whole` (the same state on every process, fresh or from a checkpoint) into blocks
    /// of rows of nearly equal work and keeps this process's. Collective.
    pub fn new(
        comm: &'c C,
        params: &FluidParams,
        whole: &CoupledState,
    ) -> Result<Self, FluidError> {
        let domain = whole.fluid.grid;
        let weights = row_weights(&domain, &whole.world);
        let layout = StripLayout::weighted(domain.nx, domain.ny, comm.size(), &weights)
            .map_err(|why| FluidError::Setup(format!("{why} (one block per process)")))?;
        check_layout(&layout, &domain)?;
        let state = block_of(whole, &layout.rows(comm.rank()));
        Self::with_layout(comm, params, domain, state, layout)
    }

    /// [`DistributedFluid::new`] with the blocks of `layout`, this process's being `state`.
    fn with_layout(
        comm: &'c C,
        params: &FluidParams,
        domain: MacGrid,
        state: CoupledState,
        layout: StripLayout,
    ) -> Result<Self, FluidError> {
        let (me, size) = (comm.rank(), comm.size());
        let rows = layout.rows(me);
        let mut block_params = params.clone();
        block_params.boundary = params.boundary.block(rows.clone(), domain.ny, size);
        let stepper = CoupledStepper::new_block(&block_params, &state, domain, &params.boundary)?;
        let (shape, boundary, multigrid_params) = pressure_multigrid(&domain, params);
        let multigrid = StripMultigrid::new(shape, boundary, multigrid_params, layout.clone(), me)
            .map_err(|e| FluidError::Setup(e.to_string()))?;
        let neighbours = strip_neighbours(me, size, params.boundary.is_periodic(1));
        Ok(DistributedFluid {
            comm,
            layout,
            domain,
            whole_params: params.clone(),
            rebalances: 0,
            params: block_params,
            state,
            stepper,
            links: BlockComm {
                rows: StripComm { comm, neighbours },
                multigrid,
            },
        })
    }

    /// One coupled step of the whole grid (collective); the report's forces, norms and energy
    /// are the whole grid's, the grains' report is every process's own (identical) one.
    /// The fluid's total time (`times[3]`) includes a re-cut of the blocks before the step.
    pub fn step(&mut self) -> Result<CoupledReport, CoupledError> {
        let started = std::time::Instant::now();
        self.rebalance().map_err(CoupledError::Fluid)?;
        let recut = started.elapsed().as_secs_f64();
        let mut report =
            (self.stepper).step_with(&self.params, &mut self.state, &mut self.links)?;
        report.fluid.times[3] += recut;
        Ok(report)
    }

    /// This process's block and grains.
    pub fn state(&self) -> &CoupledState {
        &self.state
    }

    /// The rows of each process.
    pub fn layout(&self) -> &StripLayout {
        &self.layout
    }

    /// Times the blocks were cut again since this run (or its resume) started.
    pub fn rebalances(&self) -> u64 {
        self.rebalances
    }

    /// Cuts the blocks again if the grains have moved work across a cut (see the module
    /// documentation). Collective; every process decides alike.
    fn rebalance(&mut self) -> Result<(), FluidError> {
        let weights = row_weights(&self.domain, &self.state.world);
        let (nx, ny) = (self.domain.nx, self.domain.ny);
        let layout =
            StripLayout::weighted(nx, ny, self.comm.size(), &weights).map_err(FluidError::Setup)?;
        if layout == self.layout {
            return Ok(());
        }
        self.recut(layout)
    }

    /// Cuts the blocks as `layout` says (the same on every process). Collective.
    pub fn recut(&mut self, layout: StripLayout) -> Result<(), FluidError> {
        if layout.starts.len() != self.comm.size() + 1
            || layout.starts.first() != Some(&0)
            || layout.starts.last() != Some(&self.domain.ny)
        {
            return Err(FluidError::Setup(format!(
                "block boundaries {:?} for {} processes and {} rows (one more boundary than \
                 processes, from 0 to the number of rows)",
                layout.starts,
                self.comm.size(),
                self.domain.ny
            )));
        }
        check_layout(&layout, &self.domain)?;
        let state = self.moved_to(&layout);
        let rebalances = self.rebalances + 1;
        *self = Self::with_layout(self.comm, &self.whole_params, self.domain, state, layout)?;
        self.rebalances = rebalances;
        Ok(())
    }

    /// This process's block under `layout`, the rows it needs (those that change owner and
    /// its new halo rows) received from the processes that hold them under the current one;
    /// nothing else travels. The same block as [`block_of`] the gathered whole. Collective.
    fn moved_to(&self, layout: &StripLayout) -> CoupledState {
        let (me, size) = (self.comm.rank(), self.comm.size());
        let (w, nx) = (self.domain.width(), self.domain.nx);
        // What process `from` holds now of what process `to` needs under `layout`.
        let pieces = |from: usize, to: usize| {
            (
                overlap(&self.held_rows(from), &padded_rows(&layout.rows(to))),
                overlap(&self.layout.rows(from), &layout.rows(to)),
            )
        };
        let current = &self.state.fluid;
        let old_start = self.layout.rows(me).start;
        let moves = |(rows, increment): &(Range<usize>, Range<usize>)| {
            !rows.is_empty() || !increment.is_empty()
        };
        let sends: Vec<(usize, Vec<Real>)> = (0..size)
            .filter(|&s| s != me && moves(&pieces(me, s)))
            .map(|s| {
                let (rows, increment) = pieces(me, s);
                (s, pack_rows(current, old_start, &rows, &increment))
            })
            .collect();
        let sources: Vec<usize> = (0..size)
            .filter(|&s| s != me && moves(&pieces(s, me)))
            .collect();
        let received = self.comm.exchange(&sends, &sources);
        let rows = layout.rows(me);
        let padded = padded_rows(&rows);
        let mut block = FluidState {
            grid: block_grid(&self.domain, &rows),
            velocity: [vec![0.0; padded.len() * w], vec![0.0; padded.len() * w]],
            pressure: vec![0.0; padded.len() * w],
            increment: vec![0.0; rows.len() * nx],
            time: current.time,
            step: current.step,
            inner: current.inner.clone(),
        };
        let (own_rows, own_increment) = pieces(me, me);
        let own = pack_rows(current, old_start, &own_rows, &own_increment);
        for (s, data) in sources.iter().zip(&received).chain([(&me, &own)]) {
            let (piece_rows, piece_increment) = pieces(*s, me);
            unpack_rows(&mut block, rows.start, data, &piece_rows, &piece_increment);
        }
        CoupledState {
            fluid: block,
            world: self.state.world.clone(),
        }
    }

    /// The immersed bodies (as [`CoupledStepper::immersed`]).
    pub fn immersed(&self) -> &[usize] {
        self.stepper.immersed()
    }

    /// Cells of the pressure multigrid's coarsest grid that this process gathers and relaxes
    /// whole in each cycle, 0 when an agglomeration leaves it out before
    /// ([`StripMultigrid::gathered_cells`]).
    pub fn pressure_gathered_cells(&self) -> usize {
        self.links.multigrid.gathered_cells()
    }

    /// This process's share: the cells of its block; every process holds every grain.
    pub fn load(&self) -> RankLoad {
        RankLoad {
            bodies: self.state.world.bodies.len(),
            cells: self.state.fluid.grid.num_cells(),
            contacts: self.state.world.contacts.len(),
            recuts: self.rebalances,
            ..RankLoad::default()
        }
    }

    /// Gathers the whole fluid and the grains into `whole` on rank 0 (other ranks leave it
    /// unchanged). Collective.
    pub fn gather(&self, whole: &mut CoupledState) {
        if self.comm.rank() != 0 {
            self.comm.exchange(&[(0, self.pack())], &[]);
            return;
        }
        let sources: Vec<usize> = (1..self.comm.size()).collect();
        let mut strips = vec![self.pack()];
        strips.extend(self.comm.exchange(&[], &sources));
        self.unpack_all(&strips, whole);
    }

    /// The padded rows of the whole grid process `s` holds and sends: its own rows, plus the
    /// ghost row below for the first block and the two above for the last. They partition the
    /// whole grid's padded rows.
    fn held_rows(&self, s: usize) -> Range<usize> {
        let rows = self.layout.rows(s);
        let low = if s == 0 { 0 } else { rows.start + 1 };
        let high = if s + 1 == self.comm.size() {
            rows.end + 3
        } else {
            rows.end + 1
        };
        low..high
    }

    /// This process's rows of the velocity, pressure and pressure increment.
    fn pack(&self) -> Vec<Real> {
        let (me, rows) = (self.comm.rank(), self.layout.rows(self.comm.rank()));
        pack_rows(&self.state.fluid, rows.start, &self.held_rows(me), &rows)
    }

    /// Writes every process's [`Self::pack`] (in rank order) into `whole`, with this process's
    /// time, step, inner momenta and grains.
    fn unpack_all(&self, strips: &[Vec<Real>], whole: &mut CoupledState) {
        for (s, data) in strips.iter().enumerate() {
            unpack_rows(
                &mut whole.fluid,
                0,
                data,
                &self.held_rows(s),
                &self.layout.rows(s),
            );
        }
        let fluid = &mut whole.fluid;
        fluid.time = self.state.fluid.time;
        fluid.step = self.state.fluid.step;
        fluid.inner.clone_from(&self.state.fluid.inner);
        whole.world.clone_from(&self.state.world);
    }
}

/// The padded rows `padded` (of the whole grid) of both velocity components and the pressure,
/// then the rows `increment` of the pressure increment, of `fluid`, a block whose first row is
/// row `first` of the whole grid (0 for the whole grid).
fn pack_rows(
    fluid: &FluidState,
    first: usize,
    padded: &Range<usize>,
    increment: &Range<usize>,
) -> Vec<Real> {
    let (w, nx) = (fluid.grid.width(), fluid.grid.nx);
    let mut out = Vec::with_capacity(3 * padded.len() * w + increment.len() * nx);
    if !padded.is_empty() {
        let (from, to) = ((padded.start - first) * w, (padded.end - first) * w);
        for field in [&fluid.velocity[0], &fluid.velocity[1], &fluid.pressure] {
            out.extend_from_slice(&field[from..to]);
        }
    }
    if !increment.is_empty() {
        let from = (increment.start - first) * nx;
        out.extend_from_slice(&fluid.increment[from..from + increment.len() * nx]);
    }
    out
}

/// Writes `data`, packed by [`pack_rows`] with the same rows, into `fluid`, a block whose first
/// row is row `first` of the whole grid.
fn unpack_rows(
    fluid: &mut FluidState,
    first: usize,
    data: &[Real],
    padded: &Range<usize>,
    increment: &Range<usize>,
) {
    let (w, nx) = (fluid.grid.width(), fluid.grid.nx);
    let span = padded.len() * w;
    if span > 0 {
        let at = (padded.start - first) * w;
        let [u0, u1] = &mut fluid.velocity;
        for (field, part) in [u0, u1, &mut fluid.pressure]
            .into_iter()
            .zip(data.chunks(span))
        {
            field[at..at + span].copy_from_slice(part);
        }
    }
    if !increment.is_empty() {
        let at = (increment.start - first) * nx;
        fluid.increment[at..at + increment.len() * nx].copy_from_slice(&data[3 * span..]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run_on_threads;

    /// A grain falling across the cut of a 16 x 64 box on 2 blocks.
    fn falling_grain() -> (FluidParams, CoupledState) {
        let h = 1e-4;
        let grid = MacGrid {
            nx: 16,
            ny: 64,
            h,
            origin: Vector::zeros(),
        };
        let grain = (4.0 * h, Vector::new(8.0 * h, 32.0 * h));
        crate::fixtures::grains_in_a_box(grid, &[grain], 1e-8)
    }

    /// Zeroes the halo rows of the block's velocity and pressure on its linked sides.
    fn spoil_halos<C: Communicator + ?Sized>(run: &mut DistributedFluid<'_, C>) {
        let fluid = &mut run.state.fluid;
        let (w, ny) = (fluid.grid.width(), fluid.grid.ny);
        let [below, above] = run.links.rows.neighbours;
        let [u0, u1] = &mut fluid.velocity;
        for field in [u0, u1, &mut fluid.pressure] {
            if below.is_some() {
                field[..HALO_BELOW * w].fill(0.0);
            }
            if above.is_some() {
                field[(ny + HALO_BELOW) * w..(ny + HALO_BELOW + HALO_ABOVE) * w].fill(0.0);
            }
        }
    }

    /// A step starts from the halos the last one exchanged, unless the stepper is told that
    /// the fields changed: then it exchanges them again and gives the bits of a run whose
    /// halos were never touched; untold, stale halos change the step.
    #[test]
    fn a_step_after_fields_changed_exchanges_the_halos_again() {
        let (params, start) = falling_grain();
        let velocities = run_on_threads(2, |comm| {
            let mut outcomes = Vec::new();
            for (spoil, tell) in [(false, false), (true, true), (true, false)] {
                let mut run = DistributedFluid::new(comm, &params, &start).unwrap();
                for step in 0..3 {
                    if step == 2 && spoil {
                        spoil_halos(&mut run);
                        if tell {
                            run.stepper.fields_changed();
                        }
                    }
                    run.step().unwrap();
                }
                outcomes.push(run.state.fluid.velocity.clone());
            }
            outcomes
        });
        for (rank, outcomes) in velocities.iter().enumerate() {
            assert!(
                outcomes[0] == outcomes[1],
                "rank {rank}: told, the step differs"
            );
            assert!(
                outcomes[0] != outcomes[2],
                "rank {rank}: untold, stale halos unseen"
            );
        }
    }
}
