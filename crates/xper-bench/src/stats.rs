//! Statistics of the measured series.

pub use xper_simulation::rigid::bench::median;
