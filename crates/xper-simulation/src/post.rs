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
    let source = |micro: Option<MicroVolume>| volume.or(micro).unwrap_or(MicroVolume::Walls);
    let line = match scene {
        AnyScene::Rigid(s) if s.fluid.is_some() => return Err(not_rigid("fluid")),
        AnyScene::Rigid(s) => {
            let payload: Vec<u8> = read_checkpoint(run_dir, what)?;
            let source = xper_rigid::micro::volume_source(source(s.output.micro));
            xper_rigid::micro::post_checkpoint(&payload, source, &out, &label)?
        }
        AnyScene::Rigid3(s) => {
            let payload: Vec<u8> = read_checkpoint(run_dir, what)?;
            let source = xper_rigid3d::micro::volume_source(source(s.output.micro));
            xper_rigid3d::micro::post_checkpoint(&payload, source, &out, &label)?
        }
        AnyScene::Fracture(_) => return Err(not_rigid("fracture")),
    };
    println!("{line}; written to {}", out.display());
    Ok(())
}
