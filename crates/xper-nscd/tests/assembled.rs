//! The assembled problem of a step (`assemble_problem`) against the factorised operator, and
//! the generalized Newton method in the stepper against NLGS.

use xper_bodies::{Body, BodySet, Drive, TimeFunction};
use xper_geometry::{ContactSet, Detector};
use xper_laws::{InteractionLaw, LawTable, SignoriniCoulomb};
use xper_math::{Real, Vector};
use xper_nscd::{
    assemble_problem, MoreauJean, RigidContactOperator, StepParams, VelocitySolver, World,
};
use xper_solver::{
    ContactOperator, ConvergenceNorm, ErrorScaling, NlgsParams, SolverKind, SolverParams,
};

/// SplitMix64 uniform numbers in [-1, 1).
struct Rng(xper_math::SplitMix64);

impl Rng {
    fn next(&mut self) -> Real {
        2.0 * self.0.next_f64() - 1.0
    }
}

fn laws(friction: Real) -> LawTable {
    let mut laws = LawTable::new(1);
    laws.set(
        0,
        0,
        InteractionLaw::SignoriniCoulomb(SignoriniCoulomb {
            friction,
            restitution: 0.0,
        }),
    );
    laws
}

fn params(tolerance: Real) -> StepParams {
    StepParams {
        dt: 1e-3,
        theta: 0.5,
        gravity: Vector::new(0.0, -9.81),
        alert_distance: 1e-3,
        detection: Default::default(),
        nlgs: NlgsParams {
            tolerance,
            max_iterations: 100_000,
            check_every: 1,
            relaxation: 1.0,
            norm: ConvergenceNorm::NaturalMap,
            ..Default::default()
        },
        solver: VelocitySolver::Nlgs,
        projection_tolerance: Some(1e-6),
    }
}

/// A box with a pile of disks, two square blocks (polygon-wall and polygon-polygon contacts
/// with two points between the same bodies) and a disk whose x velocity is imposed
/// (one dof of zero inverse mass).
fn mixed_world() -> World {
    let r = 0.01;
    let mut bodies = vec![
        Body::wall(Vector::new(-0.1, 0.0), Vector::new(0.2, 0.0)),
        Body::wall(Vector::new(0.0, 0.2), Vector::new(0.0, 0.0)),
    ];
    let mut rng = Rng(xper_math::SplitMix64::new(3));
    for k in 0..12 {
        let (i, j) = (k % 4, k / 4);
        let x = 0.0105 + 2.05 * r * i as Real + 0.3 * r * (j % 2) as Real;
        let y = r + 1.8 * r * j as Real + 1e-4;
        bodies.push(
            Body::disk(r * (1.0 + 0.02 * rng.next()), 1000.0, Vector::new(x, y))
                .with_velocity(Vector::new(0.05 * rng.next(), -0.05)),
        );
    }
    let square = |h: Real| {
        vec![
            Vector::new(-h, -h),
            Vector::new(h, -h),
            Vector::new(h, h),
            Vector::new(-h, h),
        ]
    };
    bodies.push(Body::polygon(
        square(0.01),
        800.0,
        Vector::new(0.12, 0.0101),
    ));
    bodies
        .push(Body::polygon(square(0.008), 800.0, Vector::new(0.1205, 0.0283)).with_rotation(0.05));
    let mut driven = Body::disk(r, 1000.0, Vector::new(0.17, r + 2e-4));
    driven.drives[0] = Drive::Velocity(TimeFunction::Constant(0.01));
    bodies.push(driven);
    let mut set = BodySet::new();
    for b in bodies {
        set.insert(b);
    }
    World::new(set, laws(0.4), params(1e-10))
}

#[test]
fn assembled_w_applies_impulses_like_the_operator() {
    let mut world = mixed_world();
    let mut stepper = MoreauJean::new();
    for _ in 0..40 {
        stepper.step(&mut world).unwrap();
    }
    let mut contacts = ContactSet::default();
    Detector::new().detect(
        &world.bodies,
        world.params.alert_distance,
        |a, b| world.laws.between(a, b),
        &mut contacts,
    );
    let n = contacts.len();
    assert!(n >= 20, "only {n} contacts");
    let mut op = RigidContactOperator::default();
    op.load_bodies(&world.bodies, |_| [0.0; 3]);
    op.rows = contacts.rows.clone();
    op.refresh_blocks();
    let mut rng = Rng(xper_math::SplitMix64::new(11));
    let mu: Vec<Real> = (0..n).map(|_| 0.5 + 0.5 * rng.next()).collect();
    let shift: Vec<Real> = (0..n).map(|_| rng.next()).collect();
    let p = assemble_problem(&op, &mu, &shift).unwrap();
    assert_eq!(
        (p.dim, p.w.nrows, p.w.ncols, p.mu.clone()),
        (2, 2 * n, 2 * n, mu)
    );
    // At zero velocities q is the shift alone.
    let q0: Vec<Real> = shift.iter().flat_map(|&s| [s, 0.0]).collect();
    assert_eq!(p.q, q0);
    assert_eq!(p.w, p.w.transpose(), "W is exactly symmetric");

    for trial in 0..5 {
        let r: Vec<Real> = (0..2 * n).map(|_| rng.next()).collect();
        let mut wr = vec![0.0; 2 * n];
        p.w.mul_add(&r, &mut wr);
        // Independent path: impulses applied to body velocities, local velocities read back.
        for b in &mut op.bodies {
            b.velocity = [0.0; 3];
        }
        for a in 0..n {
            op.apply_impulse(a, [r[2 * a], r[2 * a + 1]]);
        }
        let scale = wr.iter().fold(0.0, |m: Real, x| m.max(x.abs()));
        let mut worst: Real = 0.0;
        for a in 0..n {
            let u = op.local_velocity(a);
            worst = worst
                .max((u[0] - wr[2 * a]).abs())
                .max((u[1] - wr[2 * a + 1]).abs());
        }
        assert!(
            worst <= 1e-12 * scale,
            "trial {trial}: |W r - H^T M^-1 H r| = {worst:.3e}, |W r| = {scale:.3e}"
        );
    }
    // Diagonal blocks agree with the operator's own W_aa (a different formula).
    for (a, row) in op.rows.iter().enumerate() {
        let b = row.full_block();
        for (k, l, v) in [(0, 0, b[0]), (0, 1, b[1]), (1, 0, b[2]), (1, 1, b[3])] {
            let got = p.w.get(2 * a + k, 2 * a + l);
            assert!((got - v).abs() <= 1e-12 * b[0], "contact {a}: {got} vs {v}");
        }
    }
    // Walls do not couple: two contacts sharing only a wall have no block.
    let wall_pairs: Vec<(usize, usize)> = (0..n)
        .flat_map(|a| (0..n).map(move |c| (a, c)))
        .filter(|&(a, c)| {
            let (ba, bc) = (contacts.rows[a].bodies, contacts.rows[c].bodies);
            a != c && ba[0] == 0 && bc[0] == 0 && ba[1] != bc[1]
        })
        .collect();
    assert!(!wall_pairs.is_empty());
    for (a, c) in wall_pairs {
        let stored = p.w.col_idx[p.w.row_ptr[2 * a]..p.w.row_ptr[2 * a + 1]].contains(&(2 * c));
        assert!(!stored, "contacts {a} and {c} share only the floor");
    }
    // Bad input is an error, not a panic.
    assert!(assemble_problem(&op, &[0.3], &shift).is_err());
    op.rows[0].bodies[1] = 1_000;
    assert!(assemble_problem(&op, &vec![0.3; n], &shift).is_err());
}

/// Two layers of disks on a floor (3 below, 2 resting in the hollows), one sliding, one
/// dropped on top: every contact frame independent, so `W` is positive definite.
fn small_deposit(solver: VelocitySolver, tolerance: Real) -> World {
    let r = 0.01;
    let mut bodies = vec![Body::wall(Vector::new(-0.1, 0.0), Vector::new(0.2, 0.0))];
    for i in 0..3 {
        let x = 2.2 * r * i as Real;
        let v = if i == 2 { 0.1 } else { 0.0 };
        bodies.push(
            Body::disk(r, 1000.0, Vector::new(x, r + 2e-5)).with_velocity(Vector::new(v, 0.0)),
        );
    }
    let dy = ((2.0 * r) * (2.0 * r) - (1.1 * r) * (1.1 * r)).sqrt();
    for i in 0..2 {
        let x = 1.1 * r + 2.2 * r * i as Real;
        bodies.push(Body::disk(r, 1000.0, Vector::new(x, r + dy + 5e-5)));
    }
    bodies.push(
        Body::disk(0.6 * r, 1000.0, Vector::new(2.2 * r, r + 2.0 * dy + 0.7e-3))
            .with_velocity(Vector::new(0.0, -0.3)),
    );
    let mut set = BodySet::new();
    for b in bodies {
        set.insert(b);
    }
    let mut world = World::new(set, laws(0.3), params(tolerance));
    world.params.solver = solver;
    world
}

/// Largest difference of the velocities of the centres and rims (m/s) between two worlds,
/// relative to the largest of them in `a`.
fn velocity_difference(a: &World, b: &World) -> Real {
    let v = |w: &World, k: usize| {
        let [vx, vy, om] = w.bodies.generalized_velocity(k);
        [vx, vy, om * w.bodies.shape[k].size() / 2.0]
    };
    let disks = 1..a.bodies.len();
    let vmax = disks
        .clone()
        .flat_map(|k| v(a, k))
        .fold(0.0, |m: Real, x| m.max(x.abs()));
    disks
        .flat_map(|k| (0..3).map(move |d| (k, d)))
        .map(|(k, d)| (v(a, k)[d] - v(b, k)[d]).abs() / vmax)
        .fold(0.0, Real::max)
}

#[test]
fn newton_and_nlgs_agree_in_the_stepper() {
    let tolerance = 1e-10;
    let newton = VelocitySolver::Assembled(SolverParams {
        tolerance,
        scaling: ErrorScaling::RelativeMax,
        ..SolverParams::with_kind(SolverKind::Newton)
    });
    let mut a = small_deposit(VelocitySolver::Nlgs, tolerance);
    let mut b = small_deposit(newton, tolerance);
    let (mut sa, mut sb, mut s1) = (MoreauJean::new(), MoreauJean::new(), MoreauJean::new());
    let (mut per_step, mut newton_iterations): (Real, u32) = (0.0, 0);
    for step in 1..=30 {
        // One Newton step from the state NLGS reached: the difference of one solve.
        let mut one = a.clone();
        one.params.solver = newton;
        let r1 = s1.step(&mut one).unwrap();
        let (ra, rb) = (sa.step(&mut a).unwrap(), sb.step(&mut b).unwrap());
        for r in [&ra, &rb, &r1] {
            assert!(r.converged && r.residual < tolerance, "step {step}: {r:?}");
        }
        assert_eq!(
            (ra.active, ra.active),
            (rb.active, r1.active),
            "step {step}"
        );
        newton_iterations = newton_iterations.max(rb.iterations);
        per_step = per_step.max(velocity_difference(&a, &one));
    }
    let trajectory = velocity_difference(&a, &b);
    println!(
        "velocity differences / max |v|: one step {per_step:.3e}, after 30 steps {trajectory:.3e}; \
         at most {newton_iterations} Newton iterations per step"
    );
    // Both solve the same u = W r + q to a natural-map error below the tolerance times
    // max(|q|, |u|, |r|). W is positive definite here (independent contact frames), so the
    // solution is unique and an iterate's distance to it is at most the error times a
    // modest factor (the conditioning of W, and max(|q|, |u|, |r|) / max |v|, here <= 5):
    // one solve differs by a small multiple of the tolerance. Along a trajectory the
    // differences are carried from step to step by the velocities and positions, and the
    // impact of the top disk (step 15) amplifies them, so the bound is looser.
    assert!(per_step < 20.0 * tolerance, "{per_step:.3e}");
    assert!(trajectory < 100.0 * tolerance, "{trajectory:.3e}");
    assert!(newton_iterations <= 10, "{newton_iterations}");
    assert!(a.contacts.len() >= 7);
}

#[test]
fn captured_problem_is_the_one_solved() {
    let mut world = small_deposit(VelocitySolver::Nlgs, 1e-10);
    let mut stepper = MoreauJean::new();
    for _ in 0..5 {
        stepper.step(&mut world).unwrap();
    }
    assert!(stepper.take_problem().is_none());
    let expected = stepper.next_problem(&world).unwrap();
    let before = world.clone();
    // next_problem leaves the world and the next step untouched.
    let mut twin = world.clone();
    let mut twin_stepper = MoreauJean::new();
    assert_eq!(world, before);
    stepper.capture_next_problem();
    stepper.step(&mut world).unwrap();
    twin_stepper.step(&mut twin).unwrap();
    assert_eq!(world, twin);
    let got = stepper.take_problem().expect("captured");
    assert_eq!(got, expected);
    assert!(stepper.take_problem().is_none());
    assert!(got.contact_count() >= 7);
    // The impulses the step found solve the captured problem.
    let r: Vec<Real> = world.contacts.impulses.iter().flatten().copied().collect();
    assert!(got.error(&r).relative_max < 1e-9, "{:?}", got.error(&r));
}
