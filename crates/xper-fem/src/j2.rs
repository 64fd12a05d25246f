//! Three-dimensional J2 (von Mises) radial return with linear isotropic hardening and its
//! consistent tangent; the plane hypotheses restrict it (see [`crate::material`]).
//!
//! Source: J.C. Simo, T.J.R. Hughes, "Computational Inelasticity", Springer 1998, boxes 3.1
//! (radial return) and 3.2 (consistent elastoplastic tangent moduli), written here with the
//! equivalent plastic strain `p` (`p' = sqrt(2/3 e_p' : e_p')`, so that `p` is the axial
//! plastic strain of a uniaxial test) and the yield stress `sigma_y = sigma_0 + H p`:
//!
//! ```text
//! s_tr = 2 G dev(e - e_p,n),  q_tr = sqrt(3/2 s_tr : s_tr),  f = q_tr - (sigma_0 + H p_n)
//! f <= 0: elastic;  otherwise  dp = f / (3 G + H),  s = (1 - 3 G dp / q_tr) s_tr,
//!         e_p = e_p,n + dp (3/2) s_tr / q_tr,  p = p_n + dp
//! C = K 1(x)1 + 2 G theta I_dev - 2 G theta_bar n(x)n,  n = s_tr / |s_tr|,
//!     theta = 1 - 3 G dp / q_tr,  theta_bar = 3 G / (3 G + H) - 3 G dp / q_tr
//! ```
//!
//! Strains (total and plastic) use engineering Voigt components
//! `[e_xx, e_yy, e_zz, 2 e_xy, 2 e_yz, 2 e_zx]`; stresses tensor components
//! `[s_xx, s_yy, s_zz, s_xy, s_yz, s_zx]` (Pa); the tangent maps the first to the second.

/// Elastic and hardening constants of a J2 material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct J2 {
    /// Shear modulus `G` (Pa).
    pub shear: f64,
    /// Bulk modulus `K` (Pa).
    pub bulk: f64,
    /// Initial yield stress `sigma_0` (Pa).
    pub yield_stress: f64,
    /// Linear isotropic hardening modulus `H` (Pa).
    pub hardening: f64,
}

/// The outcome of one radial return.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Return3 {
    /// Stress, tensor components (Pa).
    pub stress: [f64; 6],
    /// Plastic strain, engineering Voigt components.
    pub plastic_strain: [f64; 6],
    /// Equivalent plastic strain `p` after the step.
    pub equivalent_plastic_strain: f64,
    /// Consistent tangent (Pa), engineering strain to tensor stress.
    pub tangent: [[f64; 6]; 6],
    /// Plastic work of the step per unit volume (J/m^3), `dp (sigma_0 + H (p_n + p) / 2)`.
    pub plastic_work: f64,
}

/// `a : b` for tensor components.
fn contract(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5])
}

/// The deviatoric part of tensor components.
fn deviator(t: &[f64; 6]) -> [f64; 6] {
    let mean = (t[0] + t[1] + t[2]) / 3.0;
    [t[0] - mean, t[1] - mean, t[2] - mean, t[3], t[4], t[5]]
}

/// Engineering Voigt strain to tensor components.
fn to_tensor(e: &[f64; 6]) -> [f64; 6] {
    [e[0], e[1], e[2], 0.5 * e[3], 0.5 * e[4], 0.5 * e[5]]
}

/// The von Mises equivalent `sqrt(3/2 s : s)` of a stress (Pa, tensor components).
pub(crate) fn von_mises(stress: &[f64; 6]) -> f64 {
    let s = deviator(stress);
    (1.5 * contract(&s, &s)).sqrt()
}

impl J2 {
    /// The isotropic elastic tangent (Pa), engineering strain to tensor stress.
    pub fn elastic_tangent(&self) -> [[f64; 6]; 6] {
        self.tangent(1.0, 0.0, &[0.0; 6])
    }

    /// `K 1(x)1 + 2 G theta I_dev - 2 G theta_bar n(x)n` in Voigt form.
    fn tangent(&self, theta: f64, theta_bar: f64, n: &[f64; 6]) -> [[f64; 6]; 6] {
        let mut c = [[0.0; 6]; 6];
        for (i, row) in c.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                let volumetric = if i < 3 && j < 3 { 1.0 } else { 0.0 };
                let identity = match (i == j, i < 3) {
                    (true, true) => 1.0,
                    (true, false) => 0.5,
                    _ => 0.0,
                };
                *x = self.bulk * volumetric
                    + 2.0 * self.shear * theta * (identity - volumetric / 3.0)
                    - 2.0 * self.shear * theta_bar * n[i] * n[j];
            }
        }
        c
    }

    /// The radial return from the plastic strain `plastic_strain` and equivalent plastic
    /// strain `p` of the previous step to the total strain `strain` (engineering Voigt).
    pub fn radial_return(&self, plastic_strain: &[f64; 6], p: f64, strain: &[f64; 6]) -> Return3 {
        let (g, k) = (self.shear, self.bulk);
        let elastic: [f64; 6] = std::array::from_fn(|i| strain[i] - plastic_strain[i]);
        let e = to_tensor(&elastic);
        let pressure_part = k * (e[0] + e[1] + e[2]);
        let s_trial = deviator(&e).map(|x| 2.0 * g * x);
        let q_trial = (1.5 * contract(&s_trial, &s_trial)).sqrt();
        let yield_now = self.yield_stress + self.hardening * p;
        let f = q_trial - yield_now;
        let with_pressure = |s: [f64; 6]| {
            let mut stress = s;
            for x in &mut stress[..3] {
                *x += pressure_part;
            }
            stress
        };
        if f <= 0.0 {
            return Return3 {
                stress: with_pressure(s_trial),
                plastic_strain: *plastic_strain,
                equivalent_plastic_strain: p,
                tangent: self.elastic_tangent(),
                plastic_work: 0.0,
            };
        }
        let dp = f / (3.0 * g + self.hardening);
        let ratio = 3.0 * g * dp / q_trial;
        let stress = with_pressure(s_trial.map(|x| (1.0 - ratio) * x));
        let mut new_plastic = *plastic_strain;
        for i in 0..6 {
            // Engineering shear components carry twice the tensor flow direction.
            let engineering = if i < 3 { 1.0 } else { 2.0 };
            new_plastic[i] += engineering * dp * 1.5 * s_trial[i] / q_trial;
        }
        let norm = contract(&s_trial, &s_trial).sqrt();
        let n = s_trial.map(|x| x / norm);
        let theta = 1.0 - ratio;
        let theta_bar = 3.0 * g / (3.0 * g + self.hardening) - ratio;
        Return3 {
            stress,
            plastic_strain: new_plastic,
            equivalent_plastic_strain: p + dp,
            tangent: self.tangent(theta, theta_bar, &n),
            plastic_work: dp * (self.yield_stress + self.hardening * (p + 0.5 * dp)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::root::solve_increasing;

    fn steel() -> (J2, f64) {
        let (young, poisson) = (200e9, 0.3);
        let j2 = J2 {
            shear: young / (2.0 * (1.0 + poisson)),
            bulk: young / (3.0 * (1.0 - 2.0 * poisson)),
            yield_stress: 250e6,
            hardening: 2e9,
        };
        (j2, young)
    }

    /// Uniaxial stress in 3D: drive e_xx, solve the lateral strain e_yy = e_zz so that
    /// s_yy = s_zz = 0. Then sigma_xx = sigma_0 + H p, p = e_p,xx and, on the plastic branch,
    /// sigma = (e + sigma_0 / H) E H / (E + H) (from e = sigma / E + (sigma - sigma_0) / H).
    #[test]
    fn uniaxial_stress_follows_linear_hardening_exactly() {
        let (j2, young) = steel();
        let (mut plastic, mut p, mut lateral) = ([0.0; 6], 0.0, 0.0);
        let h = j2.hardening;
        for step in 1..=60 {
            let axial = 1e-4 * step as f64;
            let solve = |x: f64| {
                let r = j2.radial_return(&plastic, p, &[axial, x, x, 0.0, 0.0, 0.0]);
                (r.stress[1], r.tangent[1][1] + r.tangent[1][2])
            };
            lateral = solve_increasing(solve, lateral, 1e-6).expect("lateral strain");
            let r = j2.radial_return(&plastic, p, &[axial, lateral, lateral, 0.0, 0.0, 0.0]);
            (plastic, p) = (r.plastic_strain, r.equivalent_plastic_strain);
            let sigma = r.stress[0];
            assert!(r.stress[1].abs() < 1e-6 && (r.stress[2] - r.stress[1]).abs() < 1e-6);
            let expected = if young * axial <= j2.yield_stress {
                young * axial
            } else {
                (axial + j2.yield_stress / h) * young * h / (young + h)
            };
            assert!((sigma - expected).abs() <= 1e-10 * expected, "step {step}");
            if p > 0.0 {
                assert!((sigma - (j2.yield_stress + h * p)).abs() <= 1e-10 * sigma);
                assert!((p - plastic[0]).abs() <= 1e-10 * p);
                assert!((plastic[1] + 0.5 * plastic[0]).abs() <= 1e-10 * p);
            }
        }
        assert!(p > 0.0, "the path must reach the plastic branch");
    }

    #[test]
    fn tangent_is_symmetric_and_elastic_tangent_is_isotropic() {
        let (j2, young) = steel();
        let c = j2.elastic_tangent();
        let nu = (3.0 * j2.bulk - 2.0 * j2.shear) / (2.0 * (3.0 * j2.bulk + j2.shear));
        let lambda = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        assert!((c[0][0] - (lambda + 2.0 * j2.shear)).abs() < 1e-4);
        assert!((c[0][1] - lambda).abs() < 1e-4);
        assert!((c[3][3] - j2.shear).abs() < 1e-4);
        let r = j2.radial_return(&[0.0; 6], 0.0, &[3e-3, -1e-3, 0.5e-3, 2e-3, 1e-3, -1e-3]);
        assert!(r.equivalent_plastic_strain > 0.0);
        for i in 0..6 {
            for j in 0..6 {
                assert!((r.tangent[i][j] - r.tangent[j][i]).abs() <= 1e-12 * young);
            }
        }
    }
}
