//! `checkpoint.bin` of rigid and fluid runs: a layout tag, the hash of the scene it belongs
//! to and the state, by bincode.

use crate::RunError;
use serde::Serialize;
use std::path::Path;

/// FNV-1a hash of a scene's bytes: a checkpoint resumes only the scene it was written for.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf29ce484222325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x100000001b3)
    })
}

/// First field of `checkpoint.bin` of rigid and fluid runs: "XP" and the version of the
/// layout, raised whenever a type the checkpoint holds changes (version 2: `NlgsParams` gained
/// `acceleration`; version 3: `BodySet` keeps the imposed degrees of freedom instead of the
/// inverse masses; version 4: a contact set holds its contacts' rows, keys, gaps and impulses
/// as parallel arrays). bincode is not self-describing, so without it a checkpoint of another
/// build could be misread instead of refused.
pub const CHECKPOINT_TAG: u32 = 0x5850_0004;

/// The bytes of `checkpoint.bin`: the tag, the scene hash and the state, by bincode.
pub fn checkpoint_bytes<T: Serialize>(scene_hash: u64, state: &T) -> Result<Vec<u8>, RunError> {
    bincode::serialize(&(CHECKPOINT_TAG, scene_hash, state))
        .map_err(|e| RunError::Runtime(e.to_string()))
}

/// Reads `dir/checkpoint.bin`, written by [`checkpoint_bytes`], for the scene whose
/// text hashes to `scene_hash`; `what` names the kind of state in the error message.
pub fn read_checkpoint<T: serde::de::DeserializeOwned>(
    dir: &Path,
    scene_hash: u64,
    what: &str,
) -> Result<T, RunError> {
    let path = dir.join("checkpoint.bin");
    let bytes = std::fs::read(&path)
        .map_err(|e| RunError::BadInput(format!("{}: cannot resume: {e}", path.display())))?;
    let tag: Option<u32> = bytes.get(..4).and_then(|b| bincode::deserialize(b).ok());
    if tag != Some(CHECKPOINT_TAG) {
        return Err(RunError::BadInput(format!(
            "{}: not {what} of this version of xper (its layout differs); run the scene again \
             without --resume",
            path.display()
        )));
    }
    let (_, hash, state): (u32, u64, T) = bincode::deserialize(&bytes)
        .map_err(|e| RunError::BadInput(format!("{}: not {what}: {e}", path.display())))?;
    if hash != scene_hash {
        return Err(RunError::BadInput(format!(
            "{}: the checkpoint was written for a different scene file (the scene changed since)",
            path.display()
        )));
    }
    Ok(state)
}
