//! The distributed contact solve (NSCDD, in `xper-parallel`) and each process's share of a
//! rigid problem ([`split`]).

pub use xper_parallel::nscdd::*;
pub mod split;
