//! `xper post`: the micromechanical measures of the state a rigid run's checkpoint holds
//! (`xper_nscd::micro`), written beside it: `micro.json`, `forces.csv` (the distribution of
//! normal forces over their mean) and `force_chains.vtu`.

use crate::RunError;
use std::path::Path;
use xper_run::checkpoint::{open, read_checkpoint};
use xper_scene::{parse_any_scene, AnyScene, MicroVolume};

/// Measures the state in `run_dir/checkpoint.bin` (its scene read from the checkpoint) with
/// the volume `volume` (else the scene's `[output] micro`, else the walls' box); writes into
/// `out` (default `run_dir/post`) and prints the main figures.
pub fn post(
    run_dir: &Path,
    out: Option<&Path>,
    volume: Option<MicroVolume>,
) -> Result<(), RunError> {
    let sealed = open(run_dir, "cannot read the checkpoint")?;
    let label = run_dir.join("checkpoint.bin");
    let scene = parse_any_scene(&sealed.header.scene_text, &label).map_err(|e| {
        RunError::BadInput(format!("{}: its scene does not read: {e}", label.display()))
    })?;
    let out = out.map_or_else(|| run_dir.join("post"), Path::to_path_buf);
    let not_rigid = |what: &str| {
        RunError::BadInput(format!(
            "{}: a {what} scene; `xper post` measures rigid scenes (granular packings)",
            label.display()
        ))
    };
    let what = "an xper checkpoint of a rigid scene";
    let line = match scene {
        AnyScene::Rigid(s) if s.fluid.is_some() => return Err(not_rigid("fluid")),
        AnyScene::Rigid(s) => {
            let source = volume.or(s.output.micro).unwrap_or(MicroVolume::Walls);
            let bytes: Vec<u8> = read_checkpoint(run_dir, what)?;
            let world = xper_nscd::World::from_bytes(&bytes).map_err(bad(&label))?;
            let source = xper_rigid::micro::volume_source(source);
            let m = xper_rigid::micro::post(&world, source, &out, &label)?;
            summary(
                world.step,
                m.pressure,
                m.deviator,
                m.solid_fraction,
                m.coordination,
            ) + &format!(", z* {:.4}", m.coordination_without_rattlers)
        }
        AnyScene::Rigid3(s) => {
            let source = volume.or(s.output.micro).unwrap_or(MicroVolume::Walls);
            let bytes: Vec<u8> = read_checkpoint(run_dir, what)?;
            let world = xper_nscd3d::World::from_bytes(&bytes).map_err(bad(&label))?;
            let source = xper_rigid3d::micro::volume_source(source);
            let m = xper_rigid3d::micro::post(&world, source, &out, &label)?;
            summary(
                world.step,
                m.pressure,
                m.deviator,
                m.solid_fraction,
                m.coordination,
            ) + &format!(", z* {:.4}", m.coordination_without_rattlers)
        }
        AnyScene::Fracture(_) => return Err(not_rigid("fracture")),
    };
    println!("{line}; written to {}", out.display());
    Ok(())
}

/// A checkpoint's payload error as a bad input naming the file.
fn bad(label: &Path) -> impl Fn(String) -> RunError + '_ {
    move |e| RunError::BadInput(format!("{}: {e}", label.display()))
}

fn summary(step: u64, p: f64, q: f64, phi: f64, z: f64) -> String {
    format!(
        "step {step}: p {p:.6e} Pa, q/p {:.4}, solid fraction {phi:.4}, z {z:.4}",
        q / p
    )
}
