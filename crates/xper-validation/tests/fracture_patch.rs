//! Patch test of the exploded mesh: under a uniform uniaxial traction, every element carries
//! the same stress and every bonded cohesive interface opens by the jump its compliance
//! gives, `[u] = K^-1 (sigma n)` in the interface frame (C_N, C_T in Pa/m). The scenario and
//! its parameters: [`xper_validation::fracture::patch_test`].

mod common;

#[test]
fn uniform_traction_gives_uniform_stress_and_the_compliance_jumps() {
    common::check(xper_validation::fracture::patch_test());
}
