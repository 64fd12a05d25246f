//! `checkpoint.bin`: a sealed envelope around the state of every physics.
//!
//! ```text
//! "XPERCKPT" | envelope version (u32 LE) | header length (u64 LE) | header | payload | checksum
//! header   = bincode of Header { scene hash, payload length, rows of each table }
//! checksum = FNV-1a (64 bits) of every byte before it
//! ```
//!
//! The checksum refuses any corrupted or truncated file before a byte of the state is decoded
//! (FNV-1a's step `h = (h ^ b) * p` is a bijection of `h` for an odd `p`, so any single changed
//! byte changes the hash; other corruptions pass with probability about 2^-64). The rows of
//! each table (`series.csv`, ...) at the checkpoint's step let `--resume` cut the tables at
//! exactly that step and refuse tables that end before it: the driver writes the tables
//! before the checkpoint, so an interrupted run leaves tables at least as long as its
//! checkpoint needs. The payload is each physics' own (for rigid and fluid runs a layout tag,
//! the scene hash and the state by bincode, [`checkpoint_bytes`]).

use crate::RunError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// FNV-1a hash of a scene's bytes: a checkpoint resumes only the scene it was written for.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf29ce484222325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x100000001b3)
    })
}

const MAGIC: &[u8; 8] = b"XPERCKPT";
/// Version of the envelope's layout (not of the payload's, which each physics tags).
const ENVELOPE_VERSION: u32 = 1;

/// What the envelope says about its payload.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Hash of the scene the checkpoint was written for ([`fnv1a`] of its files).
    pub scene_hash: u64,
    /// Length of the payload (bytes).
    pub payload_len: u64,
    /// Rows of each table written beside the checkpoint, by file name, at its step.
    pub tables: Vec<(String, u64)>,
    /// The scene file's text, to tell a compatible edit from another scene on `--resume`
    /// ([`crate::resume`]).
    pub scene_text: String,
}

/// A checkpoint read back and verified.
#[derive(Debug)]
pub struct Sealed {
    pub header: Header,
    pub payload: Vec<u8>,
}

/// The bytes of `checkpoint.bin` holding `payload`.
pub fn seal(header_of: Header, payload: &[u8]) -> Result<Vec<u8>, RunError> {
    let header = Header {
        payload_len: payload.len() as u64,
        ..header_of
    };
    let header = bincode::serialize(&header).map_err(|e| RunError::Runtime(e.to_string()))?;
    let mut bytes = Vec::with_capacity(MAGIC.len() + 20 + header.len() + payload.len() + 8);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&ENVELOPE_VERSION.to_le_bytes());
    bytes.extend_from_slice(&(header.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&header);
    bytes.extend_from_slice(payload);
    let checksum = fnv1a(&bytes);
    bytes.extend_from_slice(&checksum.to_le_bytes());
    Ok(bytes)
}

/// Reads and verifies `dir/checkpoint.bin`; `failing` opens the message of a file that
/// cannot be read. Every refusal is [`RunError::BadInput`] naming the file and the reason.
pub fn open(dir: &Path, failing: &str) -> Result<Sealed, RunError> {
    let path = dir.join("checkpoint.bin");
    let bytes = std::fs::read(&path)
        .map_err(|e| RunError::BadInput(format!("{}: {failing}: {e}", path.display())))?;
    unseal(bytes).map_err(|reason| RunError::BadInput(format!("{}: {reason}", path.display())))
}

/// [`open`] on bytes; the error is the reason alone.
pub fn unseal(mut bytes: Vec<u8>) -> Result<Sealed, String> {
    const AGAIN: &str = "run the scene again without --resume";
    if bytes.len() < MAGIC.len() + 20 || &bytes[..MAGIC.len()] != MAGIC {
        return Err(format!(
            "not a checkpoint of this version of xper (no XPERCKPT envelope); {AGAIN}"
        ));
    }
    let (body, tail) = bytes.split_at(bytes.len() - 8);
    let stored = u64::from_le_bytes(tail.try_into().unwrap_or_default());
    if fnv1a(body) != stored {
        return Err(format!(
            "corrupted checkpoint (its checksum does not match its {} bytes: damaged or \
             truncated); {AGAIN}",
            bytes.len()
        ));
    }
    let word = |at: usize, n: usize| &body[at..at + n];
    let version = u32::from_le_bytes(word(8, 4).try_into().unwrap_or_default());
    if version != ENVELOPE_VERSION {
        return Err(format!(
            "checkpoint envelope version {version}, this xper reads {ENVELOPE_VERSION}; {AGAIN}"
        ));
    }
    let header_len = u64::from_le_bytes(word(12, 8).try_into().unwrap_or_default());
    let start = 20usize;
    let header_end = usize::try_from(header_len)
        .ok()
        .and_then(|l| start.checked_add(l))
        .filter(|&end| end <= body.len())
        .ok_or_else(|| format!("checkpoint header of {header_len} bytes exceeds the file"))?;
    let header: Header = bincode::deserialize(&body[start..header_end])
        .map_err(|e| format!("unreadable checkpoint header: {e}"))?;
    if header.payload_len != (body.len() - header_end) as u64 {
        return Err(format!(
            "checkpoint payload of {} bytes, its header says {}",
            body.len() - header_end,
            header.payload_len
        ));
    }
    bytes.truncate(bytes.len() - 8);
    let payload = bytes.split_off(header_end);
    Ok(Sealed { header, payload })
}

/// First field of the payload of rigid and fluid checkpoints: "XP" and the version of the
/// layout, raised whenever a type the checkpoint holds changes (version 2: `NlgsParams` gained
/// `acceleration`; version 3: `BodySet` keeps the imposed degrees of freedom instead of the
/// inverse masses; version 4: a contact set holds its contacts' rows, keys, gaps and impulses
/// as parallel arrays; version 5: `NlgsParams` gained `check` and `StepParams` `detection`;
/// version 6: `World` gained `events` and `Drive` the pressure; version 7: `World` gained the
/// periodic `cell`). bincode is not
/// self-describing, so without it a checkpoint of another build could be misread instead of
/// refused.
pub const CHECKPOINT_TAG: u32 = 0x5850_0007;

/// The payload of a rigid or fluid checkpoint: the tag, the scene hash and the state, by
/// bincode.
pub fn checkpoint_bytes<T: Serialize>(scene_hash: u64, state: &T) -> Result<Vec<u8>, RunError> {
    bincode::serialize(&(CHECKPOINT_TAG, scene_hash, state))
        .map_err(|e| RunError::Runtime(e.to_string()))
}

/// Reads `dir/checkpoint.bin`, verified by [`open`], whose payload [`checkpoint_bytes`] wrote;
/// `what` names the kind of state in the error message. Whether it belongs to the scene is the
/// driver's decision ([`crate::resume::check_resume`]); its payload must name the scene its
/// envelope names.
pub fn read_checkpoint<T: serde::de::DeserializeOwned>(
    dir: &Path,
    what: &str,
) -> Result<T, RunError> {
    let path = dir.join("checkpoint.bin");
    let sealed = open(dir, "cannot resume")?;
    let (scene_hash, bytes) = (sealed.header.scene_hash, sealed.payload);
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
            "{}: the checkpoint's state belongs to another scene than its envelope says",
            path.display()
        )));
    }
    Ok(state)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Vec<u8> {
        let header = Header {
            scene_hash: 7,
            payload_len: 0,
            tables: vec![("series.csv".into(), 12)],
            scene_text: "[scene]\n".into(),
        };
        seal(header, &(0..200u8).collect::<Vec<_>>()).unwrap()
    }

    #[test]
    fn a_sealed_checkpoint_opens_with_its_header_and_payload() {
        let s = unseal(sample()).unwrap();
        assert_eq!(s.payload, (0..200u8).collect::<Vec<_>>());
        assert_eq!(s.header.tables, vec![("series.csv".to_string(), 12)]);
        assert_eq!((s.header.scene_hash, s.header.payload_len), (7, 200));
    }

    #[test]
    fn every_flipped_byte_and_every_truncation_is_refused() {
        let good = sample();
        for at in 0..good.len() {
            for flip in [0x01u8, 0x80, 0xff] {
                let mut bad = good.clone();
                bad[at] ^= flip;
                assert!(unseal(bad).is_err(), "byte {at} ^ {flip:#x} accepted");
            }
        }
        for len in 0..good.len() {
            assert!(
                unseal(good[..len].to_vec()).is_err(),
                "cut at {len} accepted"
            );
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]

        #[test]
        fn any_damage_to_a_sealed_checkpoint_is_refused(
            edits in proptest::collection::vec((0usize..4096, 0u8..=255, 0u8..3), 1..6),
        ) {
            let good = sample();
            let mut bad = good.clone();
            for (at, value, op) in edits {
                let at = at % bad.len().max(1);
                match op {
                    0 if !bad.is_empty() => bad[at] ^= value.max(1),
                    1 => bad.insert(at, value),
                    _ if !bad.is_empty() => {
                        bad.remove(at);
                    }
                    _ => {}
                }
            }
            if bad != good {
                proptest::prop_assert!(unseal(bad).is_err());
            }
        }
    }
}
