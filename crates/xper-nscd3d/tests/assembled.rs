//! The assembled 3D problem of a step (`assemble_problem`, FCLib's local form with `dim = 3`)
//! against the factorised operator, and the generalized Newton method on it against NLGS.

mod common;

use common::*;
use xper_bodies::{Body, BodySet, Drive, TimeFunction};
use xper_geometry::{ContactSet, Detector};
use xper_math::{Real, Rotation, SplitMix64, Vector};
use xper_nscd3d::{assemble_problem, MoreauJean, RigidContactOperator, VelocitySolver, World};
use xper_solver::{ContactOperator, ErrorScaling, SolverKind, SolverParams};

fn uniform(rng: &mut SplitMix64) -> Real {
    2.0 * rng.next_f64() - 1.0
}

/// A floor and a side wall, a heap of spheres, two boxes (face contacts with up to four points
/// between the same bodies) and a sphere whose x velocity is imposed (one dof of zero inverse
/// mass), stepped until they touch.
fn mixed_world() -> World {
    let r = 0.01;
    let mut set = BodySet::new();
    set.insert(floor());
    set.insert(Body::plane(Vector::zeros(), Vector::x(), [0.2, 0.2]));
    let mut rng = SplitMix64::new(5);
    for k in 0..18 {
        let (i, j, l) = (k % 3, k / 3 % 3, k / 9);
        let centre = Vector::new(
            0.0105 + 2.05 * r * i as Real + 0.3 * r * l as Real,
            2.05 * r * j as Real + 0.3 * r * l as Real,
            r + 1.9 * r * l as Real + 1e-4,
        );
        set.insert(
            Body::sphere(r * (1.0 + 0.02 * uniform(&mut rng)), 1000.0, centre)
                .with_velocity(Vector::new(0.05 * uniform(&mut rng), 0.0, -0.05)),
        );
    }
    set.insert(cube(0.01, Vector::new(0.1, 0.0, 0.0101)));
    let turned = cuboid(
        Vector::new(0.008, 0.006, 0.005),
        Vector::new(0.1, 0.0, 0.0255),
    );
    let rotation = turned.rotation * Rotation::from_scaled_axis(Vector::new(0.0, 0.0, 0.3));
    set.insert(turned.with_rotation(rotation));
    let mut driven = Body::sphere(r, 1000.0, Vector::new(0.15, 0.0, r + 2e-4));
    driven.drives[0] = Drive::Velocity(TimeFunction::Constant(0.01));
    set.insert(driven);
    let mut w = world(set, 0.4, 0.0, Vector::new(0.0, 0.0, -G), 1e-3);
    w.params.nlgs.tolerance = 1e-10;
    w
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
    assert!(n >= 30, "only {n} contacts");
    let mut op = RigidContactOperator::default();
    op.load_bodies(&world.bodies, |_| [0.0; 6]);
    op.rows = contacts.rows.clone();
    op.refresh_blocks();
    let mut rng = SplitMix64::new(11);
    let mu: Vec<Real> = (0..n).map(|_| 0.5 + 0.5 * uniform(&mut rng)).collect();
    let shift: Vec<Real> = (0..n).map(|_| uniform(&mut rng)).collect();
    let p = assemble_problem(&op, &mu, &shift).unwrap();
    assert_eq!((p.dim, p.w.nrows, p.w.ncols), (3, 3 * n, 3 * n));
    let q0: Vec<Real> = shift.iter().flat_map(|&s| [s, 0.0, 0.0]).collect();
    assert_eq!(p.q, q0, "at zero velocities q is the shift alone");
    assert_eq!(p.w, p.w.transpose(), "W is exactly symmetric");
    for trial in 0..5 {
        let r: Vec<Real> = (0..3 * n).map(|_| uniform(&mut rng)).collect();
        let mut wr = vec![0.0; 3 * n];
        p.w.mul_add(&r, &mut wr);
        // Independent path: impulses applied to the bodies, local velocities read back.
        for b in &mut op.bodies {
            b.velocity = [0.0; 6];
        }
        for a in 0..n {
            op.apply_impulse(a, [r[3 * a], r[3 * a + 1], r[3 * a + 2]]);
        }
        let scale = wr.iter().fold(0.0, |m: Real, x| m.max(x.abs()));
        let worst = (0..n)
            .flat_map(|a| {
                let u = op.local_velocity(a);
                (0..3).map(move |k| (u[k], 3 * a + k))
            })
            .fold(0.0, |m: Real, (u, i)| m.max((u - wr[i]).abs()));
        assert!(
            worst <= 1e-12 * scale,
            "trial {trial}: {worst:e} vs {scale:e}"
        );
    }
    // The diagonal blocks are the rows' own (another formula).
    for (a, row) in op.rows.iter().enumerate() {
        let b = row.full_block();
        for k in 0..3 {
            for l in 0..3 {
                let got = p.w.get(3 * a + k, 3 * a + l);
                assert!((got - b[3 * k + l]).abs() <= 1e-12 * b[0], "contact {a}");
            }
        }
    }
    // The imposed x velocity: W has no x-coupling through that sphere, so its contacts with
    // the floor see only its other degrees of freedom (checked through W's action above).
    assert!(op.bodies.iter().any(|b| !b.is_free(0) && b.is_free(1)));
}

/// The largest difference over 40 steps between the velocities NLGS reaches and those of one
/// step solved from the same state by the generalized Newton method on the assembled problem,
/// both to `tolerance` in the natural-map error, relative to the largest velocity (rims
/// included).
fn one_step_difference(tolerance: Real) -> Real {
    let r = 0.01;
    let mut set = BodySet::new();
    set.insert(floor());
    for (x, y, z) in [(0.0, 0.0, r), (2.1 * r, 0.0, r), (1.05 * r, 1.9 * r, r)] {
        set.insert(Body::sphere(r, 1000.0, Vector::new(x, y, z + 2e-5)));
    }
    set.insert(
        Body::sphere(r, 1000.0, Vector::new(1.05 * r, 0.63 * r, 2.7 * r))
            .with_velocity(Vector::new(0.02, 0.0, -0.1)),
    );
    let mut nlgs = world(set, 0.3, 0.0, Vector::new(0.0, 0.0, -G), 1e-3);
    nlgs.params.nlgs.tolerance = tolerance;
    nlgs.params.nlgs.norm = xper_solver::ConvergenceNorm::NaturalMap;
    let newton = VelocitySolver::Assembled(SolverParams {
        tolerance,
        scaling: ErrorScaling::RelativeMax,
        ..SolverParams::with_kind(SolverKind::Newton)
    });
    let (mut sa, mut sb) = (MoreauJean::new(), MoreauJean::new());
    let (mut worst, mut contacts): (Real, usize) = (0.0, 0);
    for step in 1..=40 {
        let mut one = nlgs.clone();
        one.params.solver = newton;
        let rb = sb.step(&mut one).unwrap();
        let ra = sa.step(&mut nlgs).unwrap();
        assert!(ra.converged && rb.converged, "step {step}: {ra:?} {rb:?}");
        assert_eq!(ra.active, rb.active);
        contacts = contacts.max(ra.active);
        let speed = |w: &World, b: usize| (w.bodies.velocity[b], w.bodies.angular_velocity[b] * r);
        let vmax = (1..nlgs.bodies.len())
            .map(|b| speed(&nlgs, b).0.norm() + speed(&nlgs, b).1.norm())
            .fold(0.0, Real::max);
        for b in 1..nlgs.bodies.len() {
            let ((va, wa), (vb, wb)) = (speed(&nlgs, b), speed(&one, b));
            worst = worst.max(((va - vb).norm() + (wa - wb).norm()) / vmax);
        }
    }
    assert!(contacts >= 6, "{contacts} contacts");
    worst
}

/// Spheres in a heap on a floor (the top one thrown on the others): NLGS on the operator and
/// the generalized Newton method on the assembled problem solve the same problem, so their
/// velocities differ by an amount proportional to the tolerance: a hundred times tighter
/// divides it by at least 20. (The factor between difference and tolerance, about 1e3 here,
/// is the problem's conditioning times the ratio of `max(|q|, |u|, |r|)` to the bodies'
/// speeds once the heap has settled.)
#[test]
fn newton_and_nlgs_agree_in_the_stepper() {
    let (loose, tight) = (one_step_difference(1e-10), one_step_difference(1e-12));
    assert!(loose < 1e-6, "{loose:e}");
    assert!(tight < loose / 20.0, "{loose:e} then {tight:e}");
}
