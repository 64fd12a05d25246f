//! Dynamic tests on bars of exploded elements (m, s, Pa, J):
//! - a bar pulled apart slowly breaks when the traction reaches the strength `R_max`, and the
//!   energy budget (kinetic + elastic + cohesive stored + dissipated = work of the loads)
//!   balances over the run;
//! - a longitudinal wave runs through an exploded bar at `sqrt(E_eff / rho)`, where the
//!   interfaces add their compliance to the bulk's:
//!   `1 / E_eff = 1 / E + (1 + 1 / sqrt 2) / (C d)` in tension.
//!
//! The scenarios and their parameters: [`xper_validation::fracture`].

mod common;

use xper_validation::fracture as validation;

#[test]
fn a_bar_pulled_apart_breaks_at_the_strength_and_balances_its_energy() {
    common::check(validation::bar_breaks());
}

#[test]
fn waves_run_at_the_speed_of_the_bulk_plus_interface_compliance() {
    common::check(validation::wave_speed());
}
