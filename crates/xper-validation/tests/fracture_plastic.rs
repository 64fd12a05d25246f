//! Uniaxial tension of one J2 elastoplastic element with linear isotropic hardening (plane
//! stress, i.e. the 3D uniaxial state): the axial stress follows `sigma_0 + H p` once
//! yielded, `p` the accumulated plastic strain, and the elastic slope E before. The scenario
//! and its parameters: [`xper_validation::fracture::plastic_element`].

mod common;

#[test]
fn one_element_in_tension_follows_the_hardening_line() {
    common::check(xper_validation::fracture::plastic_element());
}
