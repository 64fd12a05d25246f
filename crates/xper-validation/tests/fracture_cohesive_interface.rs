//! One cohesive interface between two squares of stiff elastic elements, opened quasi-
//! statically in mode I and in mode II by imposed velocities on the far edge (the near edge
//! fixed): the traction follows the law (BRIEF.md section 3), the energy dissipated at full
//! separation is w x length, unloading follows the damaged secant, and a broken interface is
//! a unilateral contact with Coulomb friction. The scenarios and their parameters (m, s, Pa,
//! J): [`xper_validation::fracture`].

mod common;

use xper_validation::fracture as validation;

#[test]
fn mode_one_follows_the_law_and_dissipates_w_times_length() {
    common::check(validation::mode_one());
}

#[test]
fn mode_two_follows_the_law_and_dissipates_w_times_length() {
    common::check(validation::mode_two());
}

#[test]
fn unloading_follows_the_damaged_secant() {
    common::check(validation::unloading());
}

#[test]
fn a_broken_interface_is_a_frictional_contact() {
    common::check(validation::broken_contact());
}
