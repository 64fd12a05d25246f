//! Frictional cohesive zone law between two elements (LMGC90's `MP3_CZM`).
//!
//! Sources: F. Perales, F. Dubois, Y. Monerie, B. Piar, L. Stainier, "A NonSmooth Contact
//! Dynamics-based multi-domain solver: code coupling (Xper) and application to fracture",
//! European Journal of Computational Mechanics 19 (2010) 389-417; Y. Monerie, V. Acary,
//! "Formulation dynamique d'un modele de zone cohesive tridimensionnel couplant endommagement
//! et frottement", Revue Europeenne des Elements Finis 10 (2001) 489-503; the `MP3_CZM` law of
//! LMGC90 (parameter `smax` is the strength `R_max` below).
//!
//! # The law
//! The interface carries an adhesion intensity `beta` (1 sound, 0 broken) and an elastic
//! adhesive reaction `K(beta) [u]`, `K(beta) = beta diag(C_N, C_T)`:
//!
//! ```text
//! g(x) = beta0                                          x <= d0
//!        beta0 (d0 / x) (1 - ((x - d0) / (dc - d0))^2)  d0 < x < dc
//!        0                                              x >= dc
//! d0 = (R_max / 2) (1 / C_N + 1 / C_T),   dc = (3 / 2) (w / R_max + d0 / 6)
//! beta = min(g(|[u]|), g(|[u]|_max)) = g(max(|[u]|, |[u]|_max))   (g is non-increasing)
//! |[u]| = sqrt(max(u_N, 0)^2 + u_T^2)                                (only opening counts)
//! ```
//!
//! `beta` is frozen while the contact problem of a step is solved and updated once per step
//! ([`CohesiveZone::update_intensity`]); `|[u]|_max` makes the damage irreversible. With
//! `beta0 = 1` and `C_N = C_T = C`, the traction of a monotonic opening rises linearly to
//! `R_max` at `d0`, falls to 0 at `dc`, and the work to full separation is exactly `w`.
//!
//! # Sign convention
//! `[u] = [u_N, u_T]` is the displacement jump in the local frame of the interface
//! (metres): `u_N > 0` is an opening (separation), `u_N < 0` an interpenetration. Reactions
//! use the contact convention of the rest of xper: a positive normal reaction pushes the two
//! sides apart. The cohesive reaction is therefore `-K(beta) [u]` ([`CohesiveZone::traction`]):
//! an opening gets a negative (attractive) normal traction, and the total reaction is
//! `R = R_contact + traction`. (The brief writes `R_contact + K(beta)[u]` with the jump
//! measured the other way; the physics is the same.)
//!
//! # Compression
//! The normal cohesive part uses the full normal jump, as in LMGC90: for `u_N < 0` it is
//! repulsive (`-beta C_N u_N > 0`). In xper the contact part enforces non-penetration, so in
//! a solved state `u_N < 0` only comes from the solver tolerance and this term is tiny; using
//! the full jump keeps traction, stored energy and dissipation consistent (the traction is
//! `-d/d[u]` of [`CohesiveZone::stored_energy_per_area`]). Only the opening part enters the
//! damage measure `|[u]|`, so compression alone never damages the interface.
//!
//! # Friction
//! After failure (`beta = 0`) the interface is an ordinary unilateral contact with Coulomb
//! friction of coefficient [`CohesiveZone::friction`], applied by the contact solver to the
//! contact part of the reaction.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Parameters of the frictional cohesive zone law (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CohesiveZone {
    /// Normal stiffness `C_N` of the interface (Pa/m), > 0.
    pub normal_stiffness: f64,
    /// Tangential stiffness `C_T` of the interface (Pa/m), > 0.
    pub tangential_stiffness: f64,
    /// Fracture energy `w` (J/m^2): the work to separate a unit area in pure mode with
    /// `beta0 = 1` and `C_N = C_T`, > 0.
    pub fracture_energy: f64,
    /// Strength `R_max` (Pa): the peak traction with `beta0 = 1` and `C_N = C_T`, > 0
    /// (LMGC90's `smax`).
    pub strength: f64,
    /// Initial adhesion intensity `beta0` in (0, 1] (dimensionless; 1 is a sound interface,
    /// 0 a broken one).
    pub initial_damage: f64,
    /// Coulomb friction coefficient `mu` of the contact after failure (dimensionless, >= 0).
    pub friction: f64,
}

/// Why a [`CohesiveZone`] (or a helper's argument) is invalid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CohesiveError {
    /// A parameter is NaN or infinite.
    NonFinite {
        /// Name of the parameter.
        parameter: &'static str,
        /// Its value.
        value: f64,
    },
    /// A parameter that must be strictly positive is not.
    NotPositive {
        /// Name of the parameter.
        parameter: &'static str,
        /// Its value.
        value: f64,
    },
    /// `initial_damage` (beta0) is outside (0, 1].
    InitialDamageOutOfRange {
        /// Its value.
        value: f64,
    },
    /// `friction` is negative.
    NegativeFriction {
        /// Its value.
        value: f64,
    },
    /// The softening branch is empty: `dc <= d0`, i.e. the strength is too high for the
    /// fracture energy (`w` must exceed `R_max d0 / 2`, the elastic energy stored at the peak).
    NoSoftening {
        /// Jump at the peak `d0` (m).
        d0: f64,
        /// Jump at failure `dc` (m).
        dc: f64,
    },
    /// A Poisson ratio outside the range a helper accepts.
    PoissonOutOfRange {
        /// Its value.
        value: f64,
        /// Lower bound (exclusive).
        min: f64,
        /// Upper bound (exclusive).
        max: f64,
    },
}

impl fmt::Display for CohesiveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use CohesiveError::*;
        f.write_str("cohesive zone: ")?;
        match *self {
            NonFinite { parameter, value } => write!(f, "{parameter} = {value} is not finite"),
            NotPositive { parameter, value } => write!(f, "{parameter} = {value} must be > 0"),
            InitialDamageOutOfRange { value } => write!(
                f,
                "initial_damage (beta0) = {value} must be in (0, 1] (1 sound, 0 broken)"
            ),
            NegativeFriction { value } => write!(f, "friction = {value} must be >= 0"),
            NoSoftening { d0, dc } => write!(
                f,
                "strength too high for the fracture energy: the failure jump dc = {dc:.6e} m \
                 does not exceed the peak jump d0 = {d0:.6e} m (need w > R_max d0 / 2)"
            ),
            PoissonOutOfRange { value, min, max } => {
                write!(f, "Poisson ratio {value} must be in ({min}, {max})")
            }
        }
    }
}

impl std::error::Error for CohesiveError {}

fn finite(parameter: &'static str, value: f64) -> Result<f64, CohesiveError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(CohesiveError::NonFinite { parameter, value })
    }
}

fn positive(parameter: &'static str, value: f64) -> Result<f64, CohesiveError> {
    if finite(parameter, value)? > 0.0 {
        Ok(value)
    } else {
        Err(CohesiveError::NotPositive { parameter, value })
    }
}

impl CohesiveZone {
    /// Checks every parameter: all finite, stiffnesses, fracture energy and strength > 0,
    /// `beta0` in (0, 1], `mu >= 0`, and a non-empty softening branch (`dc > d0`).
    pub fn validate(&self) -> Result<(), CohesiveError> {
        positive("normal_stiffness", self.normal_stiffness)?;
        positive("tangential_stiffness", self.tangential_stiffness)?;
        positive("fracture_energy", self.fracture_energy)?;
        positive("strength", self.strength)?;
        let beta0 = finite("initial_damage", self.initial_damage)?;
        if !(beta0 > 0.0 && beta0 <= 1.0) {
            return Err(CohesiveError::InitialDamageOutOfRange { value: beta0 });
        }
        if finite("friction", self.friction)? < 0.0 {
            return Err(CohesiveError::NegativeFriction {
                value: self.friction,
            });
        }
        let (d0, dc) = (self.d0(), self.dc());
        if dc <= d0 {
            return Err(CohesiveError::NoSoftening { d0, dc });
        }
        Ok(())
    }

    /// Jump at the peak traction, `d0 = (R_max / 2)(1 / C_N + 1 / C_T)` (m).
    pub fn d0(&self) -> f64 {
        0.5 * self.strength * (1.0 / self.normal_stiffness + 1.0 / self.tangential_stiffness)
    }

    /// Jump at complete failure, `dc = (3 / 2)(w / R_max + d0 / 6)` (m).
    pub fn dc(&self) -> f64 {
        1.5 * (self.fracture_energy / self.strength + self.d0() / 6.0)
    }

    /// The stiffness the law is calibrated on, `C_h = 2 / (1 / C_N + 1 / C_T)` (Pa/m), the
    /// harmonic mean of `C_N` and `C_T`: `d0 = R_max / C_h`. A proportional opening path with
    /// stiffness `C_h` peaks at `beta0 R_max` and dissipates `beta0 w`.
    pub fn calibration_stiffness(&self) -> f64 {
        2.0 / (1.0 / self.normal_stiffness + 1.0 / self.tangential_stiffness)
    }

    /// The intensity function `g(x)` of the module documentation (dimensionless), for a jump
    /// norm `x >= 0` (m); non-increasing, `beta0` up to `d0`, 0 from `dc` on.
    pub fn intensity(&self, x: f64) -> f64 {
        let (d0, dc) = (self.d0(), self.dc());
        if x <= d0 {
            self.initial_damage
        } else if x < dc {
            let s = (x - d0) / (dc - d0);
            self.initial_damage * (d0 / x) * (1.0 - s * s)
        } else {
            0.0
        }
    }

    /// The damage measure `|[u]| = sqrt(max(u_N, 0)^2 + u_T^2)` (m) of a jump `[u_N, u_T]` (m):
    /// only the opening part of the normal jump counts.
    pub fn jump_norm(jump: [f64; 2]) -> f64 {
        let opening = jump[0].max(0.0);
        (opening * opening + jump[1] * jump[1]).sqrt()
    }

    /// Once-per-step damage update: given the largest jump norm reached so far (m) and the
    /// current jump (m), returns `(beta, new_max_jump)` with
    /// `new_max_jump = max(previous_max_jump, |[u]|)` and
    /// `beta = min(g(|[u]|), g(new_max_jump))`, which is `g(new_max_jump)` since `g` is
    /// non-increasing. Irreversible: `beta` never increases along a sequence of updates.
    pub fn update_intensity(&self, previous_max_jump: f64, jump: [f64; 2]) -> (f64, f64) {
        let x = Self::jump_norm(jump);
        let new_max = previous_max_jump.max(x);
        let beta = self.intensity(x).min(self.intensity(new_max));
        (beta, new_max)
    }

    /// Diagonal of the interface stiffness `K(beta) = beta diag(C_N, C_T)` (Pa/m).
    pub fn stiffness(&self, beta: f64) -> [f64; 2] {
        [
            beta * self.normal_stiffness,
            beta * self.tangential_stiffness,
        ]
    }

    /// Cohesive reaction per unit area `[t_N, t_T] = -beta [C_N u_N, C_T u_T]` (Pa) for a jump
    /// `[u_N, u_T]` (m) and an intensity `beta`, in the contact convention (positive normal
    /// = repulsive): an opening gets a negative (attractive) normal traction. The full normal
    /// jump is used (see "Compression" in the module documentation).
    pub fn traction(&self, jump: [f64; 2], beta: f64) -> [f64; 2] {
        let k = self.stiffness(beta);
        [-k[0] * jump[0], -k[1] * jump[1]]
    }

    /// Elastic energy stored per unit area, `beta (C_N u_N^2 + C_T u_T^2) / 2` (J/m^2); the
    /// traction is minus its gradient with respect to the jump.
    pub fn stored_energy_per_area(&self, jump: [f64; 2], beta: f64) -> f64 {
        0.5 * beta * self.quadratic_form(jump)
    }

    /// Energy per unit area (J/m^2) dissipated when the intensity drops from `beta_before`
    /// to `beta_after` at a fixed jump (m): the stored energy released,
    /// `(beta_before - beta_after)(C_N u_N^2 + C_T u_T^2) / 2`. With `beta` frozen during a
    /// step and updated at its end, the work of the cohesive reaction over a run is exactly
    /// the final stored energy plus the sum of these increments.
    pub fn damage_dissipation_per_area(
        &self,
        jump: [f64; 2],
        beta_before: f64,
        beta_after: f64,
    ) -> f64 {
        0.5 * (beta_before - beta_after) * self.quadratic_form(jump)
    }

    /// Energy per unit area (J/m^2) dissipated once the largest jump norm reached is
    /// `max_jump` (m), for an interface of stiffness `C_h` ([`Self::calibration_stiffness`]):
    /// the area under the envelope `g(x) C_h x` up to `max_jump` minus the elastic energy
    /// still stored on the damaged secant, `g(max_jump) C_h max_jump^2 / 2`. Closed form,
    /// with `y = x - d0` and `L = dc - d0`: 0 up to `d0`;
    /// `beta0 C_h (d0^2 / 2 + d0 (y - y^3 / (3 L^2))) - g(x) C_h x^2 / 2` in the softening
    /// branch; `beta0 C_h d0 (d0 / 2 + 2 L / 3) = beta0 w` from `dc` on.
    ///
    /// When `C_N = C_T` this is the dissipation of any path whose normal jump stays >= 0
    /// (it then depends on the largest jump norm only). When `C_N != C_T` the dissipation
    /// depends on the mode mix; see [`Self::proportional_dissipation_per_area`].
    pub fn dissipated_energy_per_area(&self, max_jump: f64) -> f64 {
        self.calibration_stiffness() * self.dissipation_shape(max_jump)
    }

    /// Energy per unit area (J/m^2) dissipated along the proportional (radial) path from 0 to
    /// the jump `[u_N, u_T]` (m) with `u_N >= 0`: `C_e D(x) / C_h` with `x = |[u]|`,
    /// `D` = [`Self::dissipated_energy_per_area`] and `C_e = (C_N u_N^2 + C_T u_T^2) / x^2`
    /// the stiffness of the path. Full separation in mode I thus costs
    /// `beta0 w (1 + C_N / C_T) / 2`, in mode II `beta0 w (1 + C_T / C_N) / 2`.
    pub fn proportional_dissipation_per_area(&self, jump: [f64; 2]) -> f64 {
        let x = Self::jump_norm(jump);
        if x == 0.0 {
            return 0.0;
        }
        let opened = [jump[0].max(0.0), jump[1]];
        self.quadratic_form(opened) / (x * x) * self.dissipation_shape(x)
    }

    /// LMGC90's rule of thumb for the interface stiffnesses of a mesh of size `mesh_size` (m)
    /// in a bulk of Young modulus `young` (Pa) and Poisson ratio `poisson`:
    /// `C_N = 23 E / (L (1 - 2 nu))`, `C_T = 2 (1 - 2 nu) / (1 + 3 nu) C_N` (Pa/m). It comes
    /// from the LMGC90 cohesive examples and only keeps the added interface compliance
    /// small compared with the bulk's; it is not a derived result. Needs `E > 0`, `L > 0`
    /// and `-1/3 < nu < 1/2` (both stiffnesses positive).
    pub fn stiffness_rule_of_thumb(
        young: f64,
        poisson: f64,
        mesh_size: f64,
    ) -> Result<(f64, f64), CohesiveError> {
        positive("young", young)?;
        positive("mesh_size", mesh_size)?;
        let nu = finite("poisson", poisson)?;
        let (min, max) = (-1.0 / 3.0, 0.5);
        if !(nu > min && nu < max) {
            return Err(CohesiveError::PoissonOutOfRange {
                value: nu,
                min,
                max,
            });
        }
        let c_n = 23.0 * young / (mesh_size * (1.0 - 2.0 * nu));
        let c_t = 2.0 * (1.0 - 2.0 * nu) / (1.0 + 3.0 * nu) * c_n;
        Ok((c_n, c_t))
    }

    /// `C_N u_N^2 + C_T u_T^2` (Pa m).
    fn quadratic_form(&self, jump: [f64; 2]) -> f64 {
        self.normal_stiffness * jump[0] * jump[0] + self.tangential_stiffness * jump[1] * jump[1]
    }

    /// `int_0^x g(s) s ds - g(x) x^2 / 2` (m^2): the dissipation per unit stiffness of a
    /// proportional path whose largest jump norm is `x`.
    fn dissipation_shape(&self, x: f64) -> f64 {
        let (d0, dc, beta0) = (self.d0(), self.dc(), self.initial_damage);
        if x <= d0 {
            return 0.0;
        }
        let l = dc - d0;
        let y = x.min(dc) - d0;
        // int_0^x g(s) s ds: beta0 d0^2 / 2 on [0, d0], then beta0 d0 (1 - ((s - d0)/L)^2).
        let envelope = beta0 * (0.5 * d0 * d0 + d0 * (y - y * y * y / (3.0 * l * l)));
        envelope - 0.5 * self.intensity(x) * x * x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A law with a visible softening branch: with `C_N = C_T = 100`, d0 = 0.01, dc = 0.0775 m.
    fn law(c_n: f64, c_t: f64, beta0: f64) -> CohesiveZone {
        CohesiveZone {
            normal_stiffness: c_n,
            tangential_stiffness: c_t,
            fracture_energy: 0.05,
            strength: 1.0,
            initial_damage: beta0,
            friction: 0.3,
        }
    }

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
    }

    /// Work done against the cohesive reaction along `path(s)`, `s` in [0, 1], with the
    /// intensity updated at every point (trapezoid rule on `n` intervals).
    fn work_along(z: &CohesiveZone, n: usize, path: impl Fn(f64) -> [f64; 2]) -> f64 {
        let (mut max, mut work) = (0.0, 0.0);
        let mut prev = (path(0.0), z.traction(path(0.0), z.initial_damage));
        for k in 1..=n {
            let u = path(k as f64 / n as f64);
            let (beta, m) = z.update_intensity(max, u);
            max = m;
            let t = z.traction(u, beta);
            work -= (0..2)
                .map(|i| 0.5 * (t[i] + prev.1[i]) * (u[i] - prev.0[i]))
                .sum::<f64>();
            prev = (u, t);
        }
        work
    }

    #[test]
    fn envelope_rises_linearly_to_strength_then_falls_to_zero_at_dc() {
        let c = 100.0;
        for beta0 in [1.0, 0.6] {
            let z = law(c, c, beta0);
            z.validate().unwrap();
            let (d0, dc, r) = (z.d0(), z.dc(), beta0 * z.strength);
            assert!(rel(d0, z.strength / c) < 1e-15);
            let mut previous = (0.0, 0.0);
            for k in 0..=3000 {
                let x = 1.5 * dc * k as f64 / 3000.0;
                let (beta, _) = z.update_intensity(0.0, [x, 0.0]);
                let t = -z.traction([x, 0.0], beta)[0];
                let s = (x - d0) / (dc - d0);
                let expected = match x {
                    x if x <= d0 => beta0 * c * x,
                    x if x < dc => r * (1.0 - s * s),
                    _ => 0.0,
                };
                assert!(
                    (t - expected).abs() <= 1e-12 * r,
                    "x {x}: {t} vs {expected}"
                );
                if previous.0 > d0 {
                    assert!(t <= previous.1 + 1e-12, "softening must decrease");
                }
                previous = (x, t);
            }
            assert!(rel(-z.traction([d0, 0.0], z.intensity(d0))[0], r) < 1e-12);
            assert!(rel(-z.traction([0.0, d0], z.intensity(d0))[1], r) < 1e-12);
            assert_eq!(z.intensity(dc), 0.0);
        }
    }

    #[test]
    fn work_to_separation_is_the_fracture_energy_in_each_pure_mode() {
        // (C_N, C_T, beta0): the work is beta0 w (1 + C_N / C_T) / 2 in mode I, beta0 w
        // (1 + C_T / C_N) / 2 in mode II, so exactly w for a sound interface with C_N = C_T.
        for (c_n, c_t, beta0) in [
            (100.0, 100.0, 1.0),
            (100.0, 100.0, 0.6),
            (300.0, 100.0, 1.0),
        ] {
            let z = law(c_n, c_t, beta0);
            z.validate().unwrap();
            let end = 2.0 * z.dc();
            let w = beta0 * z.fracture_energy;
            let mode1 = work_along(&z, 200_000, |s| [s * end, 0.0]);
            let mode2 = work_along(&z, 200_000, |s| [0.0, -s * end]);
            assert!(rel(mode1, w * (1.0 + c_n / c_t) / 2.0) < 1e-6, "{mode1}");
            assert!(rel(mode2, w * (1.0 + c_t / c_n) / 2.0) < 1e-6, "{mode2}");
            assert!(rel(z.proportional_dissipation_per_area([end, 0.0]), mode1) < 1e-6);
            assert!(rel(z.proportional_dissipation_per_area([0.0, end]), mode2) < 1e-6);
            assert!(rel(z.dissipated_energy_per_area(z.dc()), w) < 1e-12);
            assert!(rel(z.dissipated_energy_per_area(end), w) < 1e-12);
            if c_n == c_t {
                assert!(rel(mode1, z.dissipated_energy_per_area(z.dc())) < 1e-6);
            }
        }
    }

    #[test]
    fn dissipation_closed_form_matches_the_integral_at_every_max_jump() {
        let z = law(100.0, 100.0, 1.0);
        for x in [0.5, 1.0, 1.3, 2.0, 4.0, 7.0, 7.7] {
            let x = x * z.d0();
            let work = work_along(&z, 100_000, |s| [0.6 * s * x, 0.8 * s * x]);
            let stored = z.stored_energy_per_area([0.6 * x, 0.8 * x], z.intensity(x));
            let closed = z.dissipated_energy_per_area(x);
            assert!(
                (work - stored - closed).abs() <= 1e-6 * z.fracture_energy,
                "x {x}"
            );
        }
        assert_eq!(z.dissipated_energy_per_area(0.9 * z.d0()), 0.0);
    }

    #[test]
    fn unloading_follows_the_secant_and_reloading_retraces_it() {
        let c = 100.0;
        let z = law(c, c, 1.0);
        let x1 = 0.5 * (z.d0() + z.dc());
        let mut max = 0.0;
        for k in 0..=100 {
            (_, max) = z.update_intensity(max, [x1 * k as f64 / 100.0, 0.0]);
        }
        let beta1 = z.intensity(x1);
        assert!(beta1 > 0.0 && beta1 < 1.0);
        for k in (0..=100).rev().chain(0..=100) {
            let x = x1 * k as f64 / 100.0;
            let (beta, m) = z.update_intensity(max, [x, 0.0]);
            max = m;
            assert_eq!(beta, beta1);
            assert!((z.traction([x, 0.0], beta)[0] + beta1 * c * x).abs() < 1e-14);
        }
        assert_eq!(max, x1);
        let (beta2, max2) = z.update_intensity(max, [1.1 * x1, 0.0]);
        assert_eq!((beta2, max2), (z.intensity(1.1 * x1), 1.1 * x1));
        assert!(beta2 < beta1);
    }

    #[test]
    fn mixed_mode_path_balances_work_storage_and_dissipation() {
        let z = law(100.0, 100.0, 1.0);
        let (d0, dc) = (z.d0(), z.dc());
        // Open to 0.5 d0, shear to 3 d0, close the normal jump, shear back, open past dc.
        let corners = [
            [0.0, 0.0],
            [0.5 * d0, 0.0],
            [0.5 * d0, 3.0 * d0],
            [0.0, 3.0 * d0],
            [0.0, -d0],
            [1.2 * dc, -d0],
        ];
        let (mut max, mut beta, mut u) = (0.0, z.initial_damage, corners[0]);
        let (mut work, mut dissipated, mut max_before_last_leg) = (0.0, 0.0, 0.0);
        let n = 20_000;
        for (leg, pair) in corners.windows(2).enumerate() {
            if leg == corners.len() - 2 {
                max_before_last_leg = max;
            }
            for k in 1..=n {
                let s = k as f64 / n as f64;
                let next = [0, 1].map(|i| pair[0][i] + s * (pair[1][i] - pair[0][i]));
                // The reaction is linear in the jump with beta frozen: the trapezoid is exact.
                let (t0, t1) = (z.traction(u, beta), z.traction(next, beta));
                work -= (0..2)
                    .map(|i| 0.5 * (t0[i] + t1[i]) * (next[i] - u[i]))
                    .sum::<f64>();
                let (b, m) = z.update_intensity(max, next);
                dissipated += z.damage_dissipation_per_area(next, beta, b);
                (u, beta, max) = (next, b, m);
            }
        }
        let stored = z.stored_energy_per_area(u, beta);
        assert!((work - stored - dissipated).abs() < 1e-12 * z.fracture_energy);
        assert_eq!(beta, 0.0);
        assert!(rel(max_before_last_leg, 0.5f64.hypot(3.0) * d0) < 1e-12);
        assert!(rel(dissipated, z.fracture_energy) < 1e-4, "{dissipated}");
    }

    #[test]
    fn compression_alone_never_damages_and_pushes_back() {
        let z = law(100.0, 100.0, 1.0);
        let u = [-10.0 * z.dc(), 0.0];
        assert_eq!(z.update_intensity(0.0, u), (1.0, 0.0));
        assert!(z.traction(u, 1.0)[0] > 0.0);
        assert_eq!(CohesiveZone::jump_norm([-3.0, 4.0]), 4.0);
        assert_eq!(CohesiveZone::jump_norm([3.0, -4.0]), 5.0);
    }

    #[test]
    fn validate_names_each_bad_parameter() {
        use CohesiveError::*;
        let good = law(100.0, 100.0, 1.0);
        assert_eq!(good.validate(), Ok(()));
        let with = |f: &dyn Fn(&mut CohesiveZone)| {
            let mut z = good;
            f(&mut z);
            z.validate().unwrap_err()
        };
        let name = |e: CohesiveError| match e {
            NotPositive { parameter, .. } | NonFinite { parameter, .. } => parameter,
            other => panic!("unexpected {other}"),
        };
        assert_eq!(
            name(with(&|z| z.normal_stiffness = 0.0)),
            "normal_stiffness"
        );
        assert_eq!(
            name(with(&|z| z.tangential_stiffness = -1.0)),
            "tangential_stiffness"
        );
        assert_eq!(name(with(&|z| z.fracture_energy = 0.0)), "fracture_energy");
        assert_eq!(name(with(&|z| z.strength = -2.0)), "strength");
        assert_eq!(name(with(&|z| z.strength = f64::NAN)), "strength");
        assert_eq!(name(with(&|z| z.friction = f64::INFINITY)), "friction");
        for value in [0.0, -0.1, 1.01] {
            let e = with(&|z| z.initial_damage = value);
            assert_eq!(e, InitialDamageOutOfRange { value });
        }
        assert_eq!(
            with(&|z| z.friction = -0.1),
            NegativeFriction { value: -0.1 }
        );
        // w must exceed R_max d0 / 2 = R_max^2 / (2 C): with R_max = 1, C = 100, w > 0.005.
        let e = with(&|z| z.fracture_energy = 0.004);
        assert!(matches!(e, NoSoftening { .. }) && e.to_string().contains("strength too high"));
        let mut z = good;
        z.fracture_energy = 0.0051;
        assert_eq!(z.validate(), Ok(()));
    }

    #[test]
    fn stiffness_rule_of_thumb_follows_the_lmgc90_formula() {
        let (e, nu, l) = (32e9, 0.2, 2e-3);
        let (c_n, c_t) = CohesiveZone::stiffness_rule_of_thumb(e, nu, l).unwrap();
        assert!(rel(c_n * l * (1.0 - 2.0 * nu), 23.0 * e) < 1e-15);
        assert!(rel(c_t * (1.0 + 3.0 * nu), 2.0 * (1.0 - 2.0 * nu) * c_n) < 1e-15);
        let bad = [
            (0.0, 0.2, 1.0),
            (1.0, 0.5, 1.0),
            (1.0, -0.34, 1.0),
            (1.0, 0.2, 0.0),
        ];
        for (e, nu, l) in bad {
            assert!(CohesiveZone::stiffness_rule_of_thumb(e, nu, l).is_err());
        }
        assert!(CohesiveZone::stiffness_rule_of_thumb(1.0, f64::NAN, 1.0).is_err());
    }

    proptest! {
        #[test]
        fn intensity_never_increases_and_traction_derives_from_the_energy(
            jumps in prop::collection::vec((-0.1f64..0.1, -0.1f64..0.1), 1..40),
            c_t in 20.0f64..500.0,
        ) {
            let z = law(100.0, c_t, 0.9);
            prop_assume!(z.validate().is_ok());
            let (mut beta, mut max) = (z.initial_damage, 0.0);
            for (u_n, u_t) in jumps {
                let (b, m) = z.update_intensity(max, [u_n, u_t]);
                prop_assert!(b <= beta && b >= 0.0 && m >= max);
                (beta, max) = (b, m);
                let t = z.traction([u_n, u_t], beta);
                let h = 1e-6;
                for i in 0..2 {
                    let (mut up, mut down) = ([u_n, u_t], [u_n, u_t]);
                    up[i] += h;
                    down[i] -= h;
                    let slope = (z.stored_energy_per_area(up, beta)
                        - z.stored_energy_per_area(down, beta)) / (2.0 * h);
                    prop_assert!((slope + t[i]).abs() <= 1e-6 * (1.0 + t[i].abs()));
                }
            }
        }
    }
}
