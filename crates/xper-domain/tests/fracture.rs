//! The distributed fracture run against the serial one, on the coarse Nooru-Mohamed scene
//! (`scenes/nooru_mohamed_small`: 1491 elements, 2177 cohesive interfaces, cracks growing from
//! both notches).
//!
//! The measure of agreement: the largest difference of a nodal displacement between the two
//! runs, against the serial run's own error, measured as the difference between the serial
//! run at the scene's tolerance and at a hundredth of it. NLGS stops at the tolerance, not at
//! the solution, so a distributed run (a different sweep order, the shared elements glued
//! after each sweep) may differ by a multiple of that error; it must also shrink with the
//! tolerance.

use std::path::Path;

use xper_domain::{run_on_threads, DistributedFracture, RankLoad};
use xper_fracture::{FractureModel, FractureStepReport, FractureStepper};

const STEPS: u64 = 800;

fn scene_model(tolerance: f64) -> FractureModel {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/nooru_mohamed_small/scene.toml");
    let scene = match xper_scene::load_any_scene(&path).unwrap() {
        xper_scene::AnyScene::Fracture(s) => s,
        xper_scene::AnyScene::Rigid(_) | xper_scene::AnyScene::Rigid3(_) => {
            panic!("not a fracture scene")
        }
    };
    let setup = scene.build().unwrap();
    let mut model = FractureModel::new(setup.mesh, setup.spec).unwrap();
    model.spec.nlgs.tolerance = tolerance;
    model
}

fn serial(mut model: FractureModel, steps: u64) -> (FractureModel, Vec<FractureStepReport>) {
    let mut stepper = FractureStepper::new();
    let reports = (0..steps)
        .map(|_| stepper.step(&mut model).unwrap())
        .collect();
    (model, reports)
}

/// The run of `model` on `ranks` thread processes: the gathered model, the reports of rank 0
/// and each rank's load.
fn distributed(
    model: &FractureModel,
    ranks: usize,
    steps: u64,
) -> (FractureModel, Vec<FractureStepReport>, Vec<RankLoad>) {
    let out = run_on_threads(ranks, |comm| {
        let mut run = DistributedFracture::new(comm, model);
        let reports: Vec<_> = (0..steps).map(|_| run.step().unwrap()).collect();
        let mut whole = model.clone();
        run.gather(&mut whole);
        (whole, reports, run.load())
    });
    let loads = out.iter().map(|o| o.2).collect();
    let (whole, reports, _) = out.into_iter().next().unwrap();
    (whole, reports, loads)
}

fn largest_displacement(a: &FractureModel) -> f64 {
    (a.elements.iter())
        .flat_map(|x| x.displacement.map(f64::abs))
        .fold(0.0, f64::max)
}

#[test]
fn one_process_is_the_serial_run_bit_for_bit() {
    let model = scene_model(1.666e-4);
    let (serial, serial_reports) = serial(model.clone(), 60);
    let (whole, reports, loads) = distributed(&model, 1, 60);
    assert_eq!(serial.largest_displacement_difference(&whole), 0.0);
    for (a, b) in serial_reports.iter().zip(&reports) {
        assert_eq!(
            (a.iterations, a.energy, &a.loads),
            (b.iterations, b.energy, &b.loads)
        );
    }
    assert_eq!(loads[0].shadows, 0);
    assert!((serial.interfaces.iter().zip(&whole.interfaces)).all(|(a, b)| a.points == b.points));
}

#[test]
fn two_and_four_processes_agree_with_the_serial_run_within_its_own_error() {
    let tolerance = 1.666e-4;
    let model = scene_model(tolerance);
    let (reference, reference_reports) = serial(model.clone(), STEPS);
    let (tight, _) = serial(scene_model(tolerance / 100.0), STEPS);
    let serial_error = reference.largest_displacement_difference(&tight);
    let scale = largest_displacement(&reference);
    let broken = reference.broken_points();
    println!("serial error {serial_error:.3e} m of {scale:.3e} m; {broken} broken points");
    assert!(broken > 0, "the run must break interfaces");
    for ranks in [2, 4] {
        let (whole, reports, loads) = distributed(&model, ranks, STEPS);
        let difference = reference.largest_displacement_difference(&whole);
        let shared: usize = loads.iter().map(|l| l.interface_bodies).sum();
        let force = |r: &[FractureStepReport]| r.last().unwrap().loads[0].force[1];
        println!(
            "{ranks} processes: {difference:.3e} m, shared elements {shared}, top force {:.4e} \
             N (serial {:.4e} N), energy error {:.2e} J",
            force(&reports),
            force(&reference_reports),
            reports.last().unwrap().energy.error()
        );
        assert!(shared > 0);
        assert_eq!(reports.last().unwrap().broken_points, broken);
        assert_eq!(
            loads.iter().map(|l| l.bodies).sum::<usize>(),
            model.elements.len()
        );
        assert!(
            difference <= 10.0 * serial_error,
            "{ranks} processes: {difference:e} m from the serial run, its own error {serial_error:e} m"
        );
        let energy = reports.last().unwrap().energy;
        assert!(energy.error().abs() <= 1e-6 * energy.in_play());
    }
}

#[test]
fn the_difference_shrinks_with_the_tolerance() {
    let differences: Vec<f64> = [1.666e-4, 1.666e-6]
        .iter()
        .map(|&tolerance| {
            let model = scene_model(tolerance);
            let (reference, _) = serial(model.clone(), 300);
            let (whole, _, _) = distributed(&model, 3, 300);
            reference.largest_displacement_difference(&whole)
        })
        .collect();
    println!(
        "3 processes, 300 steps: {:.3e} m and {:.3e} m at tolerances 1.666e-4 and 1.666e-6",
        differences[0], differences[1]
    );
    assert!(differences[1] < 0.1 * differences[0]);
}

#[test]
fn a_run_resumed_on_another_process_count_continues_the_uninterrupted_run() {
    let tolerance = 1.666e-4;
    let model = scene_model(tolerance);
    let (reference, _) = serial(model.clone(), 400);
    let (tight, _) = serial(scene_model(tolerance / 100.0), 400);
    let serial_error = reference.largest_displacement_difference(&tight);
    let (halfway, _, _) = distributed(&model, 2, 200);
    assert_eq!(halfway.step, 200);
    let (resumed, _, _) = distributed(&halfway, 3, 200);
    assert_eq!(resumed.step, 400);
    let difference = reference.largest_displacement_difference(&resumed);
    println!("2 then 3 processes: {difference:.3e} m (serial error {serial_error:.3e} m)");
    assert!(difference <= 10.0 * serial_error);
    let (same, _, _) = distributed(&halfway, 2, 200);
    let (straight, _, _) = distributed(&model, 2, 400);
    assert_eq!(
        same.largest_displacement_difference(&straight),
        0.0,
        "resume on the same count"
    );
}

/// The periodic bimaterial cell (`scenes/periodic_bimaterial_small`, J2 matrix, random
/// inclusions crossing the sides), E_xx ramped to 3e-3 in 1e-7 s, with `drives` for E_yy and
/// E_xy, and NLGS's tolerance.
fn periodic_model(drives: [xper_fracture::MacroDrive; 2], tolerance: f64) -> FractureModel {
    use xper_bodies::TimeFunction;
    use xper_fracture::MacroDrive;
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes/periodic_bimaterial_small/scene.toml");
    let scene = match xper_scene::load_any_scene(&path).unwrap() {
        xper_scene::AnyScene::Fracture(s) => s,
        xper_scene::AnyScene::Rigid(_) | xper_scene::AnyScene::Rigid3(_) => {
            panic!("not a fracture scene")
        }
    };
    let mut setup = scene.build().unwrap();
    let [yy, xy] = drives;
    setup.spec.periodic.as_mut().unwrap().drives = [
        MacroDrive::Strain(TimeFunction::Table(vec![(0.0, 0.0), (1e-7, 3e-3)])),
        yy,
        xy,
    ];
    let mut m = FractureModel::new(setup.mesh, setup.spec).unwrap();
    m.spec.nlgs.tolerance = tolerance;
    m
}

/// The periodic cell of [`periodic_model`] on 2 and 3 processes, whose parts are joined by
/// the interfaces across the cell's sides as well as by the inner ones: the run agrees with
/// the serial one within 10 times the serial run's own error, and so do the macroscopic
/// stresses and strains (within 10 times their own serial error), at the end (after the
/// cell broke) and at step 100 (before any interface broke, when the runs are smooth and
/// their errors small). Returns the serial run.
fn periodic_cell_agrees(drives: impl Fn() -> [xper_fracture::MacroDrive; 2]) -> FractureModel {
    let steps = 250;
    let (reference, before) = serial(periodic_model(drives(), 1.666e-4), steps);
    let (tight, tight_before) = serial(periodic_model(drives(), 1.666e-6), steps);
    let early = |reports: &[FractureStepReport]| {
        let r = &reports[99];
        assert_eq!(r.broken_points, 0, "step 100 must come before any break");
        r.cell.unwrap().strain
    };
    let early_difference =
        |a: [f64; 3], b: [f64; 3]| (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max);
    let early_error = early_difference(early(&before), early(&tight_before));
    let serial_error = reference.largest_displacement_difference(&tight);
    let cell = |m: &FractureModel| {
        let c = m.cell.unwrap();
        [c.stress_volume, c.strain]
    };
    let difference = |a: &FractureModel, b: &FractureModel, what: usize| {
        (0..3)
            .map(|k| (cell(a)[what][k] - cell(b)[what][k]).abs())
            .fold(0.0, f64::max)
    };
    let stress_error = difference(&reference, &tight, 0);
    let strain_error = difference(&reference, &tight, 1);
    let work_error = (reference.energy.external_work - tight.energy.external_work).abs();
    assert!(
        reference.broken_points() > 0,
        "the run must break interfaces"
    );
    for ranks in [2, 3] {
        let (whole, reports, loads) =
            distributed(&periodic_model(drives(), 1.666e-4), ranks, steps);
        let early_strain = early_difference(early(&reports), early(&before));
        assert!(loads.iter().map(|l| l.interface_bodies).sum::<usize>() > 0);
        let displacement = reference.largest_displacement_difference(&whole);
        let (stress, strain) = (
            difference(&reference, &whole, 0),
            difference(&reference, &whole, 1),
        );
        let work = (whole.energy.external_work - reference.energy.external_work).abs();
        println!(
            "{ranks} processes: {displacement:.3e} m (serial error {serial_error:.3e} m), stress \
             {stress:.3e} Pa (serial error {stress_error:.3e} Pa), strain {strain:.3e} (serial \
             error {strain_error:.3e}), work {work:.3e} J (serial error {work_error:.3e} J); \
             at step 100: strain {early_strain:.3e} (serial error {early_error:.3e})"
        );
        let e_xx = early(&before)[0];
        assert!(early_strain <= 10.0 * early_error.max(1e-9 * e_xx));
        assert!(displacement <= 10.0 * serial_error);
        assert!(stress <= 10.0 * stress_error.max(1e-9 * cell(&reference)[0][0].abs()));
        assert!(strain <= 10.0 * strain_error.max(1e-12 * cell(&reference)[1][0].abs()));
        assert!(work <= 10.0 * work_error.max(1e-9 * reference.energy.external_work.abs()));
    }
    reference
}

/// Imposed strain E_xx, E_yy = E_xy = 0: every strain component imposed.
#[test]
fn a_periodic_cell_on_several_processes_agrees_with_the_serial_run() {
    use xper_bodies::TimeFunction::Constant;
    use xper_fracture::MacroDrive::Strain;
    let reference = periodic_cell_agrees(|| [Strain(Constant(0.0)), Strain(Constant(0.0))]);
    assert_eq!(reference.cell.unwrap().strain[1], 0.0);
}

/// Uniaxial macroscopic stress: E_xx imposed, Sigma_yy = Sigma_xy = 0, so E_yy and E_xy are
/// free, shared by every process's solver (their masses split among the processes, their
/// rates averaged after every sweep). The serial run contracts (E_yy < 0); on one process the
/// distributed run is the serial one bit for bit.
#[test]
fn a_periodic_cell_under_a_macroscopic_stress_on_several_processes_agrees_with_the_serial_run() {
    use xper_bodies::TimeFunction::Constant;
    use xper_fracture::MacroDrive::Stress;
    let drives = || [Stress(Constant(0.0)), Stress(Constant(0.0))];
    let reference = periodic_cell_agrees(drives);
    let strain = reference.cell.unwrap().strain;
    assert!(
        strain[1] < -0.1 * strain[0],
        "E_yy {:e} for E_xx {:e}",
        strain[1],
        strain[0]
    );
    let (one, _, _) = distributed(&periodic_model(drives(), 1.666e-4), 1, 250);
    assert_eq!(one.cell.unwrap().strain, strain);
    assert_eq!(one.largest_displacement_difference(&reference), 0.0);
}
