//! Periodic homogenization (m, s, Pa, J): the effective tensor of periodic cells against exact
//! answers, the Hashin-Shtrikman bounds and the series estimate of the interfaces'
//! compliance; cells stepped under macroscopic strain or stress histories against the static
//! answer, the bar-and-crack curve and the energy budget; a crack crossing the sides.
//!
//! The scenarios and their parameters: [`xper_validation::periodic`].

mod common;

use xper_validation::periodic as validation;

#[test]
fn one_material_gives_the_material_tensor() {
    common::check(validation::one_material());
}

#[test]
fn a_laminate_matches_the_exact_tensor() {
    common::check(validation::laminate());
}

#[test]
fn random_inclusions_lie_within_hashin_shtrikman_and_converge() {
    common::check(validation::hashin_shtrikman());
}

#[test]
fn compliant_interfaces_follow_the_series_estimate() {
    common::check(validation::interface_compliance());
}

#[test]
fn a_slow_strain_gives_the_static_stress() {
    common::check(validation::slow_strain());
}

#[test]
fn mixed_loading_reaches_uniaxial_stress() {
    common::check(validation::mixed_loading());
}

#[test]
fn a_single_cohesive_line_follows_the_bar_and_crack_curve() {
    common::check(validation::single_line());
}

#[test]
fn a_crack_leaving_a_side_reenters_on_the_opposite_side() {
    common::check(validation::reentering_crack());
}
