//! The `xper` command's own code: its arguments and `xper solve`. Running scenes is
//! [`xper_simulation`], benchmarks [`xper_bench`], validation [`xper_validation`].

pub mod solve;
