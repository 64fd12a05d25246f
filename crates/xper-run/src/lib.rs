//! The run machinery every physics and every dimension shares: a simulation is anything that
//! implements [`Simulation`], and [`drive`] is its one time loop.
//!
//! * [`simulation`]: the trait (step, sync, frame, checkpoint, tables, summary), the run's
//!   options and facts;
//! * [`driver`]: the time loop with its schedule of series, frames and checkpoints, resume,
//!   failures, summary, progress and the comparison with a serial run;
//! * [`checkpoint`]: the sealed envelope of `checkpoint.bin` and its payload;
//!   [`resume`]: which edits of a scene a resume takes;
//! * [`outputs`], [`lock`]: the output directory, atomic tables, one run per directory;
//! * [`state`]: the state as named arrays with units, for scripts;
//! * [`comparison`], [`ranks`]: a distributed run against the serial one, each process's
//!   share.
//!
//! Which scene becomes which simulation is `xper-simulation`'s; this crate knows no physics.

pub mod bench;
pub mod checkpoint;
pub mod comparison;
pub mod driver;
pub mod lock;
pub mod outputs;
pub mod ranks;
pub mod resume;
pub mod simulation;
pub mod state;

pub use driver::{drive, Run, SceneFile};
pub use simulation::{OutputSchedule, RunFacts, RunOptions, Simulation, StepFailure};

/// A failure with the exit code it maps to.
#[derive(Debug)]
pub enum RunError {
    /// Bad scene, command line or checkpoint: exit code 2.
    BadInput(String),
    /// The run could not complete: exit code 1.
    Runtime(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::BadInput(m) | RunError::Runtime(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for RunError {}
