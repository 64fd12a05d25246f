//! `--resume` after an edit of the scene file.
//!
//! A checkpoint keeps the text of the scene it was written for ([`crate::checkpoint::Header`]).
//! When the scene's files no longer hash the same, the two texts are compared value by value
//! (comments and layout do not count). An edit of [`COMPATIBLE`] values only (how long the run
//! goes, what it writes and when, the solver's tolerance and iteration limits) continues the
//! run with the new values and lists them; any other difference (bodies, materials, laws, time
//! step, mesh) is refused with the list of differences.

use crate::checkpoint;
use crate::RunError;
use std::collections::BTreeMap;
use std::path::Path;

/// Values a resumed run may take from an edited scene: none changes the state it resumes.
pub const COMPATIBLE: [&str; 10] = [
    "scene.name",
    "scene.duration",
    "scene.steps",
    "output.frame_every",
    "output.checkpoint_every",
    "output.dump_problems",
    "solver.tolerance",
    "solver.max_iterations",
    "solver.check_every",
    "solver.check",
];

/// One value that differs between two scene texts (`None`: absent on that side).
#[derive(Clone, Debug, PartialEq)]
pub struct Change {
    /// Dotted path of the value (`bodies[3].radius`).
    pub path: String,
    pub old: Option<String>,
    pub new: Option<String>,
}

impl Change {
    /// Whether a resume may take the new value.
    pub fn compatible(&self) -> bool {
        COMPATIBLE.contains(&self.path.as_str())
    }
}

impl std::fmt::Display for Change {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let side = |v: &Option<String>| v.clone().unwrap_or_else(|| "(absent)".into());
        write!(
            f,
            "{}: {} -> {}",
            self.path,
            side(&self.old),
            side(&self.new)
        )
    }
}

/// Every value of a TOML text by its dotted path; tables and arrays of tables are opened,
/// other arrays are one value.
fn flatten(text: &str) -> Result<BTreeMap<String, String>, String> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| e.to_string())?;
    let mut out = BTreeMap::new();
    fn walk(prefix: &str, value: &toml::Value, out: &mut BTreeMap<String, String>) {
        match value {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    let path = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    walk(&path, v, out);
                }
            }
            toml::Value::Array(items)
                if items.iter().all(toml::Value::is_table) && !items.is_empty() =>
            {
                for (i, v) in items.iter().enumerate() {
                    walk(&format!("{prefix}[{i}]"), v, out);
                }
            }
            v => {
                out.insert(prefix.to_string(), v.to_string());
            }
        }
    }
    walk("", &toml::Value::Table(table), &mut out);
    Ok(out)
}

/// The values that differ between two scene texts, in path order.
pub fn changes(old: &str, new: &str) -> Result<Vec<Change>, String> {
    let (a, b) = (flatten(old)?, flatten(new)?);
    let mut paths: Vec<&String> = a.keys().chain(b.keys()).collect();
    paths.sort();
    paths.dedup();
    Ok(paths
        .into_iter()
        .filter(|p| a.get(*p) != b.get(*p))
        .map(|p| Change {
            path: p.clone(),
            old: a.get(p).cloned(),
            new: b.get(p).cloned(),
        })
        .collect())
}

/// Decides whether the checkpoint in `dir` resumes the scene whose files hash to `hash` and
/// whose text is `text`: its header with the notes to print (the compatible edits taken), or
/// a bad-input error naming the incompatible differences.
pub fn check_resume(
    dir: &Path,
    hash: u64,
    text: &str,
) -> Result<(checkpoint::Header, Vec<String>), RunError> {
    let header = checkpoint::open(dir, "cannot resume")?.header;
    if header.scene_hash == hash {
        return Ok((header, Vec::new()));
    }
    let file = dir.join("checkpoint.bin");
    let refuse = |why: String| {
        RunError::BadInput(format!(
            "{}: the checkpoint was written for a different scene: {why}; run the scene again \
             without --resume",
            file.display()
        ))
    };
    if header.scene_text == text {
        return Err(refuse("the mesh file changed since".into()));
    }
    let all = changes(&header.scene_text, text).map_err(refuse)?;
    let (fine, wrong): (Vec<&Change>, Vec<&Change>) = all.iter().partition(|c| c.compatible());
    if !wrong.is_empty() {
        const SHOWN: usize = 20;
        let mut list: Vec<String> = wrong.iter().take(SHOWN).map(|c| c.to_string()).collect();
        if wrong.len() > SHOWN {
            list.push(format!("and {} more", wrong.len() - SHOWN));
        }
        return Err(refuse(format!(
            "{} difference(s) a resume cannot follow ({})",
            wrong.len(),
            list.join("; ")
        )));
    }
    let taken: Vec<String> = fine.iter().map(|c| c.to_string()).collect();
    let note = format!(
        "resuming with the scene's edited values: {}",
        if taken.is_empty() {
            "none (comments or layout only)".into()
        } else {
            taken.join("; ")
        }
    );
    Ok((header, vec![note]))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "# a comment\n[scene]\ndt = 1e-3\nduration = 1.0\n\n[solver]\ntolerance = 1e-4\n\n[[bodies]]\nradius = 0.1\n\n[[bodies]]\nradius = 0.2\n";

    #[test]
    fn comments_and_layout_are_no_change() {
        let relaid = "[scene]\ndt=1e-3\nduration=1.0\n[solver]\ntolerance=1e-4\n[[bodies]]\nradius=0.1\n[[bodies]]\nradius=0.2\n";
        assert_eq!(changes(SCENE, relaid).unwrap(), vec![]);
    }

    #[test]
    fn a_longer_run_and_a_tighter_tolerance_are_compatible_a_radius_is_not() {
        let edited = SCENE
            .replace("duration = 1.0", "duration = 2.0")
            .replace("1e-4", "1e-6");
        let c = changes(SCENE, &edited).unwrap();
        assert_eq!(c.len(), 2);
        assert!(c.iter().all(Change::compatible), "{c:?}");
        let c = changes(SCENE, &SCENE.replace("0.2", "0.3")).unwrap();
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].path, "bodies[1].radius");
        assert!(!c[0].compatible());
        assert_eq!(c[0].to_string(), "bodies[1].radius: 0.2 -> 0.3");
        let c = changes(SCENE, &SCENE.replace("duration = 1.0", "steps = 2000")).unwrap();
        assert!(c.iter().all(Change::compatible), "{c:?}");
        let c = changes(SCENE, &SCENE.replace("dt = 1e-3", "dt = 2e-3")).unwrap();
        assert!(!c[0].compatible());
    }
}
