//! Validation cases of the fracture engine: small runs with exact answers, each comparison a
//! [`Case`] (name, reference with its source, measured value, error, tolerance), for the
//! integration tests (which assert [`Case::passed`]) and for the rows of VALIDATION.md.
//!
//! Units: m, s, Pa (Pa/m for interface stiffnesses), J, N; plane stress, thickness 1 m.
//!
//! - [`patch_test`]: a 4 x 3 exploded grid under a uniform end traction; every element carries
//!   the traction and every bonded interface opens by `K^-1 (sigma n)`.
//! - [`mode_one`], [`mode_two`], [`unloading`], [`broken_contact`]: one cohesive interface
//!   between two stiff squares, driven quasi-statically by the far edge: the traction follows
//!   the law of BRIEF.md section 3, the energy dissipated at full separation is w x length,
//!   unloading follows the damaged secant, and a broken interface is a unilateral contact
//!   with Coulomb friction.
//! - [`bar_breaks`]: a bar pulled apart breaks at the strength and balances its energy.
//! - [`wave_speed`]: a tensile wave runs at `sqrt(E_eff / rho)`, the interfaces adding their
//!   compliance to the bulk's.
//! - [`plastic_element`]: one J2 element in uniaxial tension follows the hardening line.
//!
//! Each error is a relative deviation (normalisation in the case's reference) or, for a
//! check without a natural number, the size of the violation (0 when satisfied). A case's
//! error is NaN when the measurement is, and then the case fails.

// Index loops over the two directions and the nodes of an element read as the formulas do.
#![allow(clippy::needless_range_loop)]

mod setup;

use setup::*;
use xper_bodies::{Drive, TimeFunction};
use xper_fem::Material;
use xper_fracture::{FractureStepper, InterfaceLaw};

pub use crate::Case;

/// Every case of this module, in order.
pub fn all_cases() -> Result<Vec<Case>, String> {
    Ok([
        patch_test()?,
        mode_one()?,
        mode_two()?,
        unloading()?,
        broken_contact()?,
        bar_breaks()?,
        wave_speed()?,
        plastic_element()?,
    ]
    .concat())
}

/// Patch test of the exploded mesh: a 4 x 3 grid of 0.25 m squares (1 m x 0.75 m), E = 1e4 Pa,
/// nu = 0.3, rho = 1 kg/m^3, bonded interfaces C_N = C_T = 1e5 Pa/m (unbreakable), end forces
/// +-sigma x 0.75 m with sigma = 100 Pa, brought to rest by 200 backward Euler steps of
/// 0.01 s. The grid's interior nodes have their edges in opposite pairs, so the uniform stress
/// is exactly compatible with the interface jumps.
pub fn patch_test() -> Result<Vec<Case>, String> {
    const S: &str = "patch test, 4 x 3 exploded grid under uniform traction";
    let (young, nu, c, sigma) = (1e4, 0.3, 1e5, 100.0);
    let mesh = grid(4, 3, 0.25, 0.25, |_| 0)?;
    let law = InterfaceLaw::Cohesive(zone(c, 1e20, 1e9, 0.0));
    let mut spec = spec(vec![elastic(young, nu, 1.0)], everywhere(1, law), 0.01, 1.0);
    let force = sigma * 0.75;
    let f = |v: f64| [Drive::Force(TimeFunction::Constant(v)), Drive::Free];
    spec.loads = vec![
        load(&mesh, "left", f(-force))?,
        load(&mesh, "right", f(force))?,
    ];
    let tolerance = spec.nlgs.tolerance;
    let mut model = build(S, mesh, spec)?;
    let mut stepper = FractureStepper::new();
    let mut conv = Convergence::default();
    for _ in 0..200 {
        step(S, &mut stepper, &mut model, &mut conv)?;
    }
    let stress = model.elements.iter().fold(0.0, |acc, el| {
        let s = el.state.stress;
        [(s[0] - sigma).abs(), s[1].abs(), s[3].abs()]
            .into_iter()
            .fold(acc, worst)
    });
    let (mut jump, mut points) = (0.0, 0);
    for i in &model.interfaces {
        let [nx, ny] = i.normal;
        // Traction sigma n in the (n, t) frame, t = (-n_y, n_x): (sigma n_x^2, -sigma n_x n_y).
        let expected = [sigma * nx * nx / c, -sigma * nx * ny / c];
        for p in &i.points {
            points += 1;
            for d in 0..2 {
                jump = worst(jump, (p.jump[d] - expected[d]).abs());
            }
        }
    }
    Ok(vec![
        case(
            format!("{S}: element stresses = applied traction"),
            "analytic: sigma_xx = F / section = 100 Pa, sigma_yy = sigma_xy = 0 in every \
             element; error max |sigma - exact| / sigma"
                .into(),
            format!(
                "largest |sigma - exact| = {stress:.3e} Pa over {} elements",
                model.elements.len()
            ),
            stress / sigma,
            1e-6,
        ),
        case(
            format!("{S}: interface jumps = traction / stiffness"),
            "BRIEF.md section 3 with beta = 1: [u] = K^-1 (sigma n), ([u]_N, [u]_T) = \
             (sigma n_x^2, -sigma n_x n_y) / C, C = 1e5 Pa/m; error max |[u] - exact| / (sigma / C)"
                .into(),
            format!("largest |[u] - exact| = {jump:.3e} m over {points} interface points"),
            jump / (sigma / c),
            1e-6,
        ),
        converged(S, conv, tolerance),
    ])
}

const LAW: &str = "BRIEF.md section 3: R = beta C [u], beta frozen over the step, C = 1e10 Pa/m";

/// One cohesive interface (C = 1e10 Pa/m, R_max = 1e6 Pa, w = 500 J/m^2, 1 m long) opened in
/// mode I to 1.3 d_c by the far edge at constant speed over 4000 backward Euler steps of
/// 2.5e-4 s (see the specimen in `validation_setup.rs`); the traction is the far edge's
/// reaction per metre.
pub fn mode_one() -> Result<Vec<Case>, String> {
    const S: &str = "one cohesive interface, mode I";
    let z = tested(0.0);
    let (steps, dt) = (4000, 2.5e-4);
    let v = 1.3 * z.dc() / (steps as f64 * dt);
    let (vx, vy) = (TimeFunction::Constant(v), TimeFunction::Constant(0.0));
    let mut m = specimen(S, 0.0, vx, vy, dt)?;
    let (history, conv) = run(S, &mut m, steps)?;
    let (mut law, mut peak) = (0.0, 0.0);
    for s in &history {
        // Traction on the interface (Pa, positive in tension): force over 1 m.
        let traction = s.force[0] / 1.0;
        law = worst(law, (traction - s.beta * C * s.jump[0]).abs());
        peak = worst(peak, traction);
    }
    Ok(vec![
        case(
            format!("{S}: traction = beta C [u]_N at every step"),
            format!("{LAW}; error max |T - beta C [u]_N| / R_max, R_max = 1e6 Pa"),
            format!("largest |T - beta C [u]_N| = {law:.3e} Pa over {steps} steps"),
            law / STRENGTH,
            2e-3,
        ),
        case(
            format!("{S}: peak traction = strength"),
            format!(
                "BRIEF.md section 3: the traction peaks at R_max = {STRENGTH:.0e} Pa (jump d0 = \
                 {:.1e} m); error |peak - R_max| / R_max",
                z.d0()
            ),
            format!("peak {peak:.6e} Pa"),
            (peak - STRENGTH).abs() / STRENGTH,
            5e-3,
        ),
        broken(S, &m, z.dc())?,
        dissipation(S, &m),
        converged(S, conv, m.spec.nlgs.tolerance),
    ])
}

/// The same interface sheared in mode II (far edge along y) to 1.3 d_c.
pub fn mode_two() -> Result<Vec<Case>, String> {
    const S: &str = "one cohesive interface, mode II";
    let z = tested(0.0);
    let (steps, dt) = (4000, 2.5e-4);
    let v = 1.3 * z.dc() / (steps as f64 * dt);
    let (vx, vy) = (TimeFunction::Constant(0.0), TimeFunction::Constant(v));
    let mut m = specimen(S, 0.0, vx, vy, dt)?;
    let (history, conv) = run(S, &mut m, steps)?;
    // The interface's tangent is (0, 1) in the frame of the left element: the traction on the
    // right square is -force_y per metre; compared in absolute value.
    let law = history.iter().fold(0.0, |acc, s| {
        worst(
            acc,
            (s.force[1].abs() - (s.beta * C * s.jump[1]).abs()).abs(),
        )
    });
    Ok(vec![
        case(
            format!("{S}: traction = beta C [u]_T at every step"),
            format!("{LAW}; error max ||T| - |beta C [u]_T|| / R_max, R_max = 1e6 Pa"),
            format!("largest ||T| - |beta C [u]_T|| = {law:.3e} Pa over {steps} steps"),
            law / STRENGTH,
            2e-3,
        ),
        dissipation(S, &m),
        converged(S, conv, m.spec.nlgs.tolerance),
    ])
}

/// The same interface opened in mode I to `x1 = (d0 + dc) / 2` over 1000 steps, closed back to
/// `x1 / 2`, then reopened to `x1` (steps of 2.5e-4 s).
pub fn unloading() -> Result<Vec<Case>, String> {
    const S: &str = "one cohesive interface, unloading and reloading";
    let z = tested(0.0);
    let dt = 2.5e-4;
    let x1 = 0.5 * (z.d0() + z.dc());
    let t1 = 1000.0 * dt;
    let v = x1 / t1;
    let vx = TimeFunction::Table(vec![
        (0.0, v),
        (t1, v),
        (t1 + 1e-9, -v),
        (1.5 * t1, -v),
        (1.5 * t1 + 1e-9, v),
    ]);
    let mut m = specimen(S, 0.0, vx, TimeFunction::Constant(0.0), dt)?;
    let (history, conv) = run(S, &mut m, 2000)?;
    let beta1 = history[1005].beta;
    let (mut change, mut secant) = (0.0, 0.0);
    for s in &history[1005..1990] {
        change = worst(change, (s.beta - beta1).abs());
        secant = worst(secant, (s.force[0] - beta1 * C * s.jump[0]).abs());
    }
    Ok(vec![
        case(
            format!("{S}: partly damaged at the largest jump"),
            "BRIEF.md section 3: d0 < x1 = (d0 + d_c) / 2 < d_c, so 0 < beta(x1) < 1 \
             (error 1 if not)"
                .into(),
            format!("beta = {beta1:.6}"),
            indicator(beta1 > 0.0 && beta1 < 1.0),
            0.0,
        ),
        case(
            format!("{S}: no new damage below the largest jump"),
            "BRIEF.md section 3: beta = min(g(|[u]|), g(|[u]|_max)) stays at beta(x1) while \
             |[u]| <= x1 (steps 1006 to 1990); error max |beta - beta(x1)|"
                .into(),
            format!("largest change of beta {change:.3e}"),
            change,
            0.0,
        ),
        case(
            format!("{S}: traction on the damaged secant"),
            format!(
                "BRIEF.md section 3: T = beta(x1) C [u]_N while unloading and reloading, C = \
                 1e10 Pa/m; error max |T - beta(x1) C [u]_N| / R_max, R_max = {STRENGTH:.0e} Pa"
            ),
            format!("largest |T - beta(x1) C [u]_N| = {secant:.3e} Pa"),
            secant / STRENGTH,
            2e-3,
        ),
        converged(S, conv, m.spec.nlgs.tolerance),
    ])
}

/// The same interface with friction mu = 0.4 after failure: opened beyond d_c (to 1.2 d_c) in
/// 1000 steps, closed back by 1.01 times as much (the far edge then presses on the near one
/// through the broken interface), then slid along y (steps of 2.5e-4 s, 3000 in all).
pub fn broken_contact() -> Result<Vec<Case>, String> {
    const S: &str = "one broken interface, closed then slid (mu = 0.4)";
    let mu = 0.4;
    let z = tested(mu);
    let dt = 2.5e-4;
    let t1 = 1000.0 * dt;
    let v = 1.2 * z.dc() / t1;
    let vx = TimeFunction::Table(vec![
        (0.0, v),
        (t1, v),
        (t1 + 1e-9, -v),
        (2.01 * t1, -v),
        (2.01 * t1 + 1e-9, 0.0),
    ]);
    let vy = TimeFunction::Table(vec![(0.0, 0.0), (2.1 * t1, 0.0), (2.1 * t1 + 1e-9, v)]);
    let mut m = specimen(S, mu, vx, vy, dt)?;
    let (history, conv) = run(S, &mut m, 3000)?;
    let (mut penetration, mut pull, mut largest_fx) = (0.0, 0, f64::NEG_INFINITY);
    for s in &history[2020..] {
        penetration = worst(penetration, -s.jump[0] / z.dc());
        if s.force[0] >= 0.0 || s.force[0].is_nan() {
            pull += 1;
        }
        largest_fx = worst(largest_fx, s.force[0]);
    }
    let (mut slip, mut low, mut high) = (0.0, f64::INFINITY, f64::NEG_INFINITY);
    for s in &history[2400..] {
        let ratio = s.force[1].abs() / s.force[0].abs();
        slip = worst(slip, (ratio - mu).abs());
        (low, high) = (low.min(ratio), high.max(ratio));
    }
    Ok(vec![
        broken(S, &m, z.dc())?,
        case(
            format!("{S}: no interpenetration"),
            "BRIEF.md section 3: a broken interface is a unilateral contact, [u]_N >= 0 (steps \
             2021 to 3000); error max(-[u]_N) / d_c"
                .into(),
            format!(
                "smallest [u]_N = {:.3e} m",
                history[2020..]
                    .iter()
                    .fold(f64::INFINITY, |acc, s| acc.min(s.jump[0]))
            ),
            penetration,
            1e-3,
        ),
        case(
            format!("{S}: the closed interface is in compression"),
            "unilateral contact pressed shut: far-edge force F_x < 0 at steps 2021 to 3000; \
             error = the steps without"
                .into(),
            format!("largest F_x = {largest_fx:.4e} N"),
            pull as f64,
            0.0,
        ),
        case(
            format!("{S}: sliding at the Coulomb bound"),
            "BRIEF.md section 3: Coulomb friction, |F_T| = mu |F_N| while sliding (steps 2401 \
             to 3000), mu = 0.4; error max ||F_T| / |F_N| - mu|"
                .into(),
            format!("|F_T| / |F_N| in [{low:.9}, {high:.9}]"),
            slip,
            1e-6,
        ),
        converged(S, conv, m.spec.nlgs.tolerance),
    ])
}

/// A bar of 10 x 2 squares of 0.1 m (1 m x 0.2 m), E = 1e10 Pa, nu = 0.2, rho = 1000 kg/m^3,
/// interfaces C = 1e12 Pa/m, w = 10 J/m^2, R_max = 1e6 Pa, pulled at both ends by
/// velocities ramped over 1 ms to 0.01 m/s in opposite directions; 1500 steps of 1e-5 s,
/// theta = 0.5, NLGS tolerance 1e-8.
pub fn bar_breaks() -> Result<Vec<Case>, String> {
    const S: &str = "bar of 10 x 2 cells pulled apart";
    let (strength, height, w) = (1e6, 0.2, 10.0);
    let mesh = grid(10, 2, 0.1, 0.1, |_| 0)?;
    let law = InterfaceLaw::Cohesive(zone(1e12, w, strength, 0.0));
    let mut spec = spec(
        vec![elastic(1e10, 0.2, 1000.0)],
        everywhere(1, law),
        1e-5,
        0.5,
    );
    spec.nlgs.tolerance = 1e-8;
    let ramp = |v: f64| Drive::Velocity(TimeFunction::Table(vec![(0.0, 0.0), (1e-3, v)]));
    spec.loads = vec![
        load(&mesh, "left", [ramp(-0.01), Drive::Free])?,
        load(&mesh, "right", [ramp(0.01), Drive::Free])?,
    ];
    let mut model = build(S, mesh, spec)?;
    let mut stepper = FractureStepper::new();
    let mut conv = Convergence::default();
    let (mut peak, mut max_work, mut balance) = (0.0, 0.0, 0.0);
    let mut after_break = Vec::new();
    for _ in 0..1500 {
        let r = step(S, &mut stepper, &mut model, &mut conv)?;
        let force = r
            .loads
            .get(1)
            .ok_or_else(|| format!("{S}: no reading of the right load"))?
            .force[0];
        peak = worst(peak, force);
        if r.step > 1000 {
            after_break.push(force);
        }
        max_work = worst(max_work, model.energy.external_work.abs());
        balance = worst(balance, model.energy.error().abs());
    }
    let expected = strength * height;
    let broken = model.broken_points();
    // After the break each half vibrates freely: the force on the pulled end averages to 0.
    let mean_after = after_break.iter().sum::<f64>() / after_break.len() as f64;
    let e = model.energy;
    let least = w * height;
    Ok(vec![
        case(
            format!("{S}: peak force = strength x section"),
            format!(
                "BRIEF.md section 3: R_max x section = {strength:.0e} Pa x {height} m = \
                 {expected:.0e} N (slow loading, uniform traction); error |peak - R_max h| / \
                 (R_max h)"
            ),
            format!("peak {peak:.5e} N"),
            (peak - expected).abs() / expected,
            0.03,
        ),
        case(
            format!("{S}: separated (at least 6 broken interface points)"),
            "broken interface points >= 6 (the bound of the integration test); error = the \
             points missing"
                .into(),
            format!("{broken} broken points"),
            6usize.saturating_sub(broken) as f64,
            0.0,
        ),
        case(
            format!("{S}: mean end force after the break = 0"),
            "free vibration of the two halves: the force on the pulled end averages to 0 over \
             steps 1001 to 1500; error |mean| / (R_max h)"
                .into(),
            format!("mean {mean_after:.4e} N"),
            mean_after.abs() / expected,
            0.03,
        ),
        case(
            format!("{S}: dissipated energy >= w x section"),
            format!(
                "BRIEF.md section 3: breaking the section spends at least w h = {w} J/m^2 x \
                 {height} m = {least} J; error max(w h - D, 0) / (w h)"
            ),
            format!("D = {:.5} J", e.cohesive_dissipated),
            (least - e.cohesive_dissipated).max(0.0) / least,
            0.0,
        ),
        case(
            format!("{S}: the loads do positive work"),
            "work of the imposed velocities > 0 (error 1 if not)".into(),
            format!("work {:.5} J", e.external_work),
            indicator(e.external_work > 0.0),
            0.0,
        ),
        case(
            format!("{S}: energy balance"),
            "conservation: kinetic + elastic + cohesive stored + dissipated = work of the loads \
             at every step; error max |balance error| / max |work|"
                .into(),
            format!("largest |balance error| {balance:.3e} J, largest |work| {max_work:.4e} J"),
            balance / max_work,
            1e-4,
        ),
        converged(S, conv, model.spec.nlgs.tolerance),
    ])
}

/// A tensile wave in a bar of 200 x 1 squares of d = 0.01 m (2 m x 0.01 m), E = 1e10 Pa,
/// nu = 0, rho = 1000 kg/m^3, interfaces C_N = C_T = 1.7e12 Pa/m (unbreakable), the left
/// end pulled at 1e-3 m/s from t = 0; theta = 0.5, dt = d / (10 c); the front (mean x velocity
/// above half the imposed one) timed at x = 0.6 m and x = 1.2 m. In compression the contact
/// part would keep the normal jumps at zero, hence a tensile wave.
pub fn wave_speed() -> Result<Vec<Case>, String> {
    const S: &str = "tensile wave in an exploded bar";
    let (young, rho, d, c) = (1e10, 1000.0, 0.01, 1.7e12);
    let e_eff = 1.0 / (1.0 / young + (1.0 + 0.5f64.sqrt()) / (c * d));
    let speed = (e_eff / rho).sqrt();
    let mesh = grid(200, 1, d, d, |_| 0)?;
    let law = InterfaceLaw::Cohesive(zone(c, 1e20, 1e12, 0.0));
    let dt = 0.1 * d / speed;
    let mut spec = spec(vec![elastic(young, 0.0, rho)], everywhere(1, law), dt, 0.5);
    spec.nlgs.tolerance = 1e-8;
    let v0 = 1e-3;
    spec.loads = vec![load(&mesh, "left", [velocity(-v0), velocity(0.0)])?];
    let probes = [0.6, 1.2];
    let nodes = probes.map(|x| nodes_at_x(&mesh, x));
    let mut model = build(S, mesh, spec)?;
    let mut stepper = FractureStepper::new();
    let mut conv = Convergence::default();
    let mut arrival = [f64::NAN; 2];
    let steps = (1.6 / speed / dt) as usize;
    for _ in 0..steps {
        step(S, &mut stepper, &mut model, &mut conv)?;
        for (k, probe) in nodes.iter().enumerate() {
            if arrival[k].is_nan() && -mean_vx(&model, probe) > 0.5 * v0 {
                arrival[k] = model.time;
            }
        }
    }
    let measured = (probes[1] - probes[0]) / (arrival[1] - arrival[0]);
    let bulk = (young / rho).sqrt();
    Ok(vec![case(
        format!("{S}: front speed = sqrt(E_eff / rho)"),
        format!(
            "analytic (average-strain theorem, uniform stress, jumps sigma n / C): 1 / E_eff = \
             1 / E + (1 + 1 / sqrt 2) / (C d), c = sqrt(E_eff / rho) = {speed:.2} m/s (bulk \
             alone {bulk:.2} m/s); error |c_measured - c| / c"
        ),
        format!(
            "{measured:.2} m/s (front at 0.6 m at {:.4e} s, at 1.2 m at {:.4e} s)",
            arrival[0], arrival[1]
        ),
        (measured - speed).abs() / speed,
        2e-2,
    )])
}

/// One J2 elastoplastic triangle (0,0), (1,0), (0,1) m with linear isotropic hardening, plane
/// stress (the 3D uniaxial state): E = 200e9 Pa, nu = 0.3, rho = 1e-3 kg/m^3,
/// sigma_0 = 250e6 Pa, H = 850e6 Pa. Node (0,0) fixed, node (0,1) held in x, node (1,0)
/// pulled in x to a strain of 5 sigma_0 / E over 400 backward Euler steps of 1e-3 s (much
/// longer than the element's period: quasi-static); NLGS defaults.
pub fn plastic_element() -> Result<Vec<Case>, String> {
    const S: &str = "one J2 element in uniaxial tension";
    let (young, sigma0, hardening) = (200e9, 250e6, 850e6);
    let (steps, dt) = (400usize, 1e-3);
    let strain_rate = 5.0 * sigma0 / young / (steps as f64 * dt);
    let steel = Material::J2Plastic {
        young,
        poisson: 0.3,
        density: 1e-3,
        yield_stress: sigma0,
        hardening,
    };
    let (mesh, spec) = one_triangle(S, steel, strain_rate, dt)?;
    let mut model = build(S, mesh, spec)?;
    let mut stepper = FractureStepper::new();
    let mut conv = Convergence::default();
    let (mut free, mut line, mut slope, mut plastic_steps) = (0.0, 0.0, 0.0, 0);
    for _ in 0..steps {
        step(S, &mut stepper, &mut model, &mut conv)?;
        let el = &model.elements[0];
        let s = el.state.stress;
        let p = el.state.equivalent_plastic_strain;
        let eps = el.triangle.strain(&el.displacement)[0];
        free = worst(free, worst(s[1].abs(), s[3].abs()));
        if p > 0.0 {
            plastic_steps += 1;
            line = worst(line, (s[0] - (sigma0 + hardening * p)).abs());
        } else {
            slope = worst(slope, (s[0] - young * eps).abs());
        }
    }
    let e = model.energy;
    Ok(vec![
        case(
            format!("{S}: sigma_yy = sigma_xy = 0"),
            "analytic, uniaxial stress: the free y components leave sigma_yy = sigma_xy = 0; \
             error max(|sigma_yy|, |sigma_xy|) / sigma_0"
                .into(),
            format!("largest |sigma_yy|, |sigma_xy| = {free:.3e} Pa"),
            free / sigma0,
            1e-6,
        ),
        case(
            format!("{S}: elastic slope before yield"),
            "Hooke, uniaxial stress: sigma_xx = E eps_xx while p = 0, E = 200 GPa; error max \
             |sigma_xx - E eps_xx| / sigma_0"
                .into(),
            format!("largest |sigma_xx - E eps_xx| = {slope:.3e} Pa"),
            slope / sigma0,
            1e-8,
        ),
        case(
            format!("{S}: hardening line after yield"),
            "J2 radial return, linear isotropic hardening (BRIEF.md section 3): sigma_xx = \
             sigma_0 + H p, sigma_0 = 250 MPa, H = 850 MPa; error max |sigma_xx - sigma_0 - H p| \
             / sigma_0"
                .into(),
            format!(
                "largest |sigma_xx - sigma_0 - H p| = {line:.3e} Pa over {plastic_steps} steps"
            ),
            line / sigma0,
            1e-8,
        ),
        case(
            format!("{S}: plastic in more than half of the steps"),
            "strained to 5 sigma_0 / E, it yields at sigma_0 / E: more than 200 of the 400 \
             steps plastic; error = the steps missing"
                .into(),
            format!("{plastic_steps} plastic steps of {steps}"),
            (steps / 2 + 1).saturating_sub(plastic_steps) as f64,
            0.0,
        ),
        case(
            format!("{S}: positive plastic dissipation"),
            "plastic work > 0 once yielded (error 1 if not)".into(),
            format!("plastic work {:.5e} J", e.plastic),
            indicator(e.plastic > 0.0),
            0.0,
        ),
        case(
            format!("{S}: energy balance"),
            "conservation: kinetic + elastic + plastic = work of the loads; the step linearises \
             the internal force at its start (one Newton iteration, as LMGC90), which costs \
             1.4e-3 of the work over the yielding step; error |balance error| / work"
                .into(),
            format!(
                "balance error {:.4e} J, work {:.5e} J",
                e.error(),
                e.external_work
            ),
            // A work that is not positive fails (infinite or NaN error).
            e.error().abs() / e.external_work.max(0.0),
            3e-3,
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::Case;

    #[test]
    fn a_nan_error_fails() {
        let case = |error| Case {
            name: "n".into(),
            reference: "r".into(),
            measured: "m".into(),
            error,
            tolerance: 1e-3,
        };
        assert!(case(1e-3).passed() && !case(2e-3).passed() && !case(f64::NAN).passed());
    }
}
