//! Validation cases with exact answers (BRIEF.md section 7): each runs a small scene and
//! compares one measured number with its reference. The test suite asserts every case; `xper
//! validate` writes them all to VALIDATION.md.

use crate::{Case, RunError};
use xper_bodies::{Body, BodySet};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{MoreauJean, StepParams, VelocitySolver, World};
use xper_simulation::rigid::build::world_from_scene;
use xper_solver::{ConvergenceNorm, NlgsParams};

const G: Real = 9.81;

/// A tight solver: these cases compare with exact solutions, not with LMGC90's tolerance.
fn params(dt: Real, gravity: Vector) -> StepParams {
    StepParams {
        dt,
        theta: 0.5,
        gravity,
        alert_distance: 1e-3,
        detection: Default::default(),
        nlgs: NlgsParams {
            tolerance: 1e-14,
            max_iterations: 20_000,
            check_every: 1,
            relaxation: 1.0,
            norm: ConvergenceNorm::NaturalMap,
            ..Default::default()
        },
        solver: VelocitySolver::Nlgs,
        projection_tolerance: Some(1e-9),
    }
}

fn world(bodies: Vec<Body>, friction: Real, restitution: Real, params: StepParams) -> World {
    let mut set = BodySet::new();
    for b in bodies {
        set.insert(b);
    }
    let mut laws = LawTable::new(1);
    laws.set(
        0,
        0,
        InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
            friction,
            restitution,
        }),
    );
    World::new(set, laws, params)
}

fn run_steps(w: &mut World, steps: usize) -> Result<(), RunError> {
    let mut stepper = MoreauJean::new();
    for _ in 0..steps {
        stepper
            .step(w)
            .map_err(|e| RunError::Runtime(e.to_string()))?;
    }
    Ok(())
}

/// A 0.4 x 0.1 m block of density 1000 on an incline; returns (travel down the slope, lift, rotation).
fn slide_on_incline(slope: Real, mu: Real, steps: usize) -> Result<(Real, Real, Real), RunError> {
    let (dir, up) = (
        Vector::new(slope.cos(), slope.sin()),
        Vector::new(-slope.sin(), slope.cos()),
    );
    let (w, h) = (0.4, 0.1);
    let corners = vec![
        Vector::new(-w / 2.0, -h / 2.0),
        Vector::new(w / 2.0, -h / 2.0),
        Vector::new(w / 2.0, h / 2.0),
        Vector::new(-w / 2.0, h / 2.0),
    ];
    let block = Body::polygon(corners, 1000.0, up * (h / 2.0)).with_rotation(slope);
    let mut world = world(
        vec![block, Body::wall(-dir * 5.0, dir * 5.0)],
        mu,
        0.0,
        params(1e-3, Vector::new(0.0, -G)),
    );
    let start = world.bodies.position[0];
    run_steps(&mut world, steps)?;
    let d = world.bodies.position[0] - start;
    Ok((-d.dot(&dir), d.dot(&up), world.bodies.rotation[0] - slope))
}

fn incline_cases() -> Result<Vec<Case>, RunError> {
    let (x, lift, rot) = slide_on_incline(0.3, 0.4, 400)?;
    let stick = Case {
        name: "block on an incline, tan(0.3 rad) = 0.309 <= mu = 0.4: sticks".into(),
        reference: "no motion".into(),
        measured: format!(
            "travel {x:.3e} m, lift {lift:.3e} m, rotation {rot:.3e} rad after 0.4 s"
        ),
        error: x.abs().max(lift.abs()).max(rot.abs()),
        tolerance: 1e-12,
    };
    let (slope, mu, steps) = (0.5, 0.3, 400);
    let (x, lift, rot) = slide_on_incline(slope, mu, steps)?;
    let t = steps as Real * 1e-3;
    let exact = G * (slope.sin() - mu * slope.cos()) * t * t / 2.0;
    let slide = Case {
        name: "block on an incline, tan(0.5 rad) = 0.546 > mu = 0.3: slides".into(),
        reference: format!("x = g (sin - mu cos) t^2 / 2 = {exact:.12} m at t = {t} s"),
        measured: format!("x = {x:.12} m (lift {lift:.1e} m, rotation {rot:.1e} rad)"),
        error: ((x - exact) / exact).abs().max(lift.abs()).max(rot.abs()),
        tolerance: 1e-12,
    };
    Ok(vec![stick, slide])
}

fn drop_cases() -> Result<Vec<Case>, RunError> {
    let (r, height) = (0.05, 0.5);
    let disk = Body::disk(r, 1000.0, Vector::new(0.0, r + height));
    let floor = Body::wall(Vector::new(-1.0, 0.0), Vector::new(1.0, 0.0));
    let mut w = world(
        vec![disk, floor],
        0.3,
        0.0,
        params(1e-3, Vector::new(0.0, -G)),
    );
    let (m, e0) = (w.bodies.mass[0], w.kinetic_energy() + w.potential_energy());
    let mut stepper = MoreauJean::new();
    let (mut landed, mut rebound): (bool, Real) = (false, 0.0);
    for _ in 0..1000 {
        stepper
            .step(&mut w)
            .map_err(|e| RunError::Runtime(e.to_string()))?;
        let vy = w.bodies.velocity[0].y;
        if landed {
            rebound = rebound.max(vy.abs());
        }
        landed |= w.bodies.position[0].y - r < 1e-3 && vy.abs() < 1e-12;
    }
    let lost = e0 - (w.kinetic_energy() + w.potential_energy());
    let exact = m * G * height;
    Ok(vec![
        Case {
            name: "disk dropped from 0.5 m on a wall, e = 0: no rebound".into(),
            reference: "vertical velocity 0 after landing".into(),
            measured: format!("landed: {landed}, largest |v_y| after landing {rebound:.2e} m/s"),
            error: if landed { rebound } else { Real::INFINITY },
            tolerance: 1e-12,
        },
        Case {
            name: "disk dropped from 0.5 m on a wall, e = 0: energy lost".into(),
            reference: format!("m g H = {exact:.9} J/m"),
            measured: format!(
                "{lost:.9} J/m (energy balance error {:.1e} J/m)",
                w.energy_error()
            ),
            error: ((lost - exact) / exact)
                .abs()
                .max(w.energy_error().abs() / exact),
            tolerance: 1e-7,
        },
    ])
}

fn cradle(gap: Real) -> Result<[Real; 3], RunError> {
    let (r, v0) = (0.1, 1.0);
    let bodies = (0..3)
        .map(|k| {
            let b = Body::disk(r, 1000.0, Vector::new(k as Real * (2.0 * r + gap), 0.0));
            if k == 0 {
                b.with_velocity(Vector::new(v0, 0.0))
            } else {
                b
            }
        })
        .collect();
    let mut w = world(bodies, 0.0, 1.0, params(1e-3, Vector::zeros()));
    run_steps(&mut w, 200)?;
    Ok([0, 1, 2].map(|k| w.bodies.velocity[k].x / v0))
}

fn cradle_cases() -> Result<Vec<Case>, RunError> {
    let mut cases = Vec::new();
    for (gap, exact, name) in [
        (
            0.0,
            [-1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0],
            "Newton's cradle, e = 1, three touching disks (simultaneous impact)",
        ),
        (
            1e-4,
            [0.0, 0.0, 1.0],
            "Newton's cradle, e = 1, gaps of 1e-4 m (successive impacts)",
        ),
    ] {
        let v = cradle(gap)?;
        cases.push(Case {
            name: name.into(),
            reference: format!(
                "v / v0 = ({:.6}, {:.6}, {:.6})",
                exact[0], exact[1], exact[2]
            ),
            measured: format!("({:.12}, {:.12}, {:.12})", v[0], v[1], v[2]),
            error: (0..3).map(|k| (v[k] - exact[k]).abs()).fold(0.0, Real::max),
            tolerance: 1e-10,
        });
    }
    Ok(cases)
}

fn column_case() -> Result<Case, RunError> {
    let (r, n, dt) = (0.01, 10, 1e-3);
    let mut bodies: Vec<Body> = (0..n)
        .map(|k| Body::disk(r, 2000.0, Vector::new(0.0, r + 2.0 * r * k as Real)))
        .collect();
    bodies.push(Body::wall(Vector::new(-1.0, 0.0), Vector::new(1.0, 0.0)));
    let mut w = world(bodies, 0.3, 0.0, params(dt, Vector::new(0.0, -G)));
    let m = w.bodies.mass[0];
    run_steps(&mut w, 20)?;
    let mut error: Real = if w.contacts.len() == n {
        0.0
    } else {
        Real::INFINITY
    };
    for c in w.contacts.iter() {
        let [a, b] = c.row.bodies;
        let below = if b as usize == n {
            a as usize
        } else {
            b as usize
        };
        let exact = (n - below) as Real * m * G;
        error = error
            .max(((c.impulse[0] / dt - exact) / exact).abs())
            .max(c.impulse[1].abs());
    }
    Ok(Case {
        name: "column of 10 disks at rest on a wall".into(),
        reference: "force below the k-th disk from the top = k m g".into(),
        measured: format!(
            "{} contacts, largest relative force error {error:.1e}",
            w.contacts.len()
        ),
        error,
        tolerance: 1e-9,
    })
}

/// A box of `count` disks falling under gravity, run with the LMGC90 tolerance; the box is
/// 0.15 m high and 0.1 m wide per 300 disks.
pub fn deposit_scene(count: usize, steps: usize) -> String {
    let width = 0.1 * count as Real / 300.0;
    format!(
        "[scene]\nname = \"deposit\"\ndt = 2e-4\nsteps = {steps}\nalert_distance = 5e-4\n\n\
         [[materials]]\nname = \"glass\"\ndensity = 2500.0\n\n\
         [[laws]]\nbetween = [\"grains\", \"grains\"]\nkind = \"signorini_coulomb\"\nfriction = 0.3\n\n\
         [[laws]]\nbetween = [\"grains\", \"walls\"]\nkind = \"signorini_coulomb\"\nfriction = 0.5\n\n\
         [[generators]]\nkind = \"box_of_disks\"\ncount = {count}\nradius = [0.002, 0.003]\n\
         box = [[0.0, 0.0], [{width}, 0.15]]\nplacement = \"random\"\nseed = 7\nmaterial = \"glass\"\n\
         group = \"grains\"\nwalls = \"walls\"\n"
    )
}

/// The deposit's cases, its NLGS sweeps plain or Anderson-accelerated (`accelerated`).
fn deposit_case(count: usize, steps: usize, accelerated: bool) -> Result<Vec<Case>, RunError> {
    let mut text = deposit_scene(count, steps);
    if accelerated {
        text.push_str("\n[solver]\nacceleration = \"anderson\"\n");
    }
    let scene = xper_scene::parse_scene(&text, std::path::Path::new("deposit.toml"))
        .map_err(|e| RunError::Runtime(e.to_string()))?;
    let mut w = world_from_scene(&scene);
    let tolerance = w.params.projection_tolerance.unwrap_or(0.0);
    let mut stepper = MoreauJean::new();
    let (mut peak, mut non_converged, mut total_sweeps): (Real, usize, u64) = (0.0, 0, 0);
    for _ in 0..steps {
        let r = stepper
            .step(&mut w)
            .map_err(|e| RunError::Runtime(e.to_string()))?;
        peak = peak.max(r.kinetic);
        non_converged += (!r.converged) as usize;
        total_sweeps += u64::from(r.iterations);
    }
    let mut contacts = xper_geometry::ContactSet::default();
    xper_geometry::Detector::new().detect(
        &w.bodies,
        w.params.alert_distance,
        |a, b| w.laws.between(a, b),
        &mut contacts,
    );
    let overlap = contacts.gaps.iter().map(|&gap| -gap).fold(0.0, Real::max);
    let ke = w.kinetic_energy();
    let (overlaps, decays, sweeps) = if accelerated {
        (
            "box of disks deposited under gravity, Anderson-accelerated NLGS: overlaps at rest",
            "box of disks deposited under gravity, Anderson-accelerated NLGS: kinetic energy decays",
            "Anderson-accelerated sweeps",
        )
    } else {
        (
            "box of disks deposited under gravity: overlaps at rest",
            "box of disks deposited under gravity: kinetic energy decays",
            "plain sweeps",
        )
    };
    Ok(vec![
        Case {
            name: overlaps.into(),
            reference: format!("no overlap beyond the projection tolerance {tolerance:.1e} m"),
            measured: format!("{count} disks, {steps} steps, {sweeps}: largest overlap {overlap:.2e} m; {non_converged} non-converged steps; {total_sweeps} sweeps in all"),
            error: overlap,
            tolerance,
        },
        Case {
            name: decays.into(),
            reference: "final kinetic energy below 1e-3 of its peak".into(),
            measured: format!("{:.2e} of the peak {peak:.3e} J/m", ke / peak),
            error: ke / peak,
            tolerance: 1e-3,
        },
    ])
}

/// Every case, with the deposit of `deposit_disks` disks.
pub fn all_cases(deposit_disks: usize, deposit_steps: usize) -> Result<Vec<Case>, RunError> {
    let mut cases = incline_cases()?;
    cases.extend(drop_cases()?);
    cases.extend(cradle_cases()?);
    cases.push(column_case()?);
    cases.extend(deposit_case(deposit_disks, deposit_steps, false)?);
    cases.extend(deposit_case(deposit_disks, deposit_steps, true)?);
    Ok(cases)
}
