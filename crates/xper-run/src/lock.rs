//! One run per output directory: `xper.lock` names the process that writes there.
//!
//! A run creates the lock before writing anything and removes it when it ends, also when it
//! fails. The lock appears with its content in one step (written to a file of this process,
//! then hard-linked to `xper.lock`, which fails if the lock exists): a run killed while taking
//! it never leaves an empty lock that no later run could judge stale. Where hard links are not
//! supported, the lock is created with `create_new` and then written. A second run into the same directory is refused with the
//! first run's process id, host and start time. A lock left by a run that was killed (its
//! process no longer exists on this host) is taken over with a note.

use crate::RunError;
use std::io::Write;
use std::path::{Path, PathBuf};

/// File name of the lock inside the output directory.
pub const LOCK_FILE: &str = "xper.lock";

/// The lock of an output directory, released when dropped.
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
}

fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| std::env::var("HOSTNAME"))
        .map(|h| h.trim().to_string())
        .unwrap_or_default()
}

/// Whether process `pid` of this host still runs (`None`: this system cannot tell).
fn alive(pid: u32) -> Option<bool> {
    let proc = Path::new("/proc");
    proc.join("self")
        .exists()
        .then(|| proc.join(pid.to_string()).exists())
}

impl OutputLock {
    /// Locks `dir` (which must exist) for this process; `notes` receives the remark of a stale
    /// lock taken over.
    pub fn take(dir: &Path, notes: &mut Vec<String>) -> Result<Self, RunError> {
        let path = dir.join(LOCK_FILE);
        let me = format!(
            "pid {} on host {} since {} s after the Unix epoch\n",
            std::process::id(),
            host(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_secs())
        );
        for _ in 0..2 {
            match create_with(&path, &me) {
                Ok(()) => return Ok(OutputLock { path }),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let holder = std::fs::read_to_string(&path).unwrap_or_default();
                    let holder = holder.trim();
                    let pid = (holder.split_whitespace().nth(1)).and_then(|p| p.parse().ok());
                    let same_host = holder.contains(&format!("on host {} ", host()));
                    // An empty lock more than a few seconds old was left by a run killed
                    // between creating and writing it (where locks are not hard-linked).
                    let abandoned = holder.is_empty()
                        && (std::fs::metadata(&path).and_then(|m| m.modified()).ok())
                            .and_then(|t| t.elapsed().ok())
                            .is_some_and(|age| age.as_secs() >= 10);
                    match pid.filter(|_| same_host).map(alive) {
                        _ if abandoned => {
                            notes.push(format!(
                                "{}: an empty lock left by a run killed while taking it; taken \
                                 over",
                                path.display()
                            ));
                            std::fs::remove_file(&path).map_err(|e| {
                                RunError::Runtime(format!("{}: {e}", path.display()))
                            })?;
                        }
                        Some(Some(false)) => {
                            notes.push(format!(
                                "{}: the run that held it ({holder}) no longer runs; taken over",
                                path.display()
                            ));
                            std::fs::remove_file(&path).map_err(|e| {
                                RunError::Runtime(format!("{}: {e}", path.display()))
                            })?;
                        }
                        _ => {
                            return Err(RunError::BadInput(format!(
                                "{}: another run writes into {} ({}); wait for it to end, \
                                 choose another --out, or delete the lock file if no run \
                                 is using the directory",
                                path.display(),
                                dir.display(),
                                if holder.is_empty() {
                                    "unknown process"
                                } else {
                                    holder
                                }
                            )));
                        }
                    }
                }
                Err(e) => {
                    return Err(RunError::BadInput(format!(
                        "{}: cannot lock the output directory: {e}",
                        path.display()
                    )))
                }
            }
        }
        Err(RunError::Runtime(format!(
            "{}: the lock was taken again while being taken over",
            path.display()
        )))
    }
}

/// Creates `path` holding `text`, failing with `AlreadyExists` if it exists: by a hard link
/// from a file of this process (the lock never exists empty), or by `create_new` where links
/// are not supported.
fn create_with(path: &Path, text: &str) -> std::io::Result<()> {
    let own = path.with_file_name(format!(".{LOCK_FILE}.{}", std::process::id()));
    std::fs::write(&own, text)?;
    let linked = std::fs::hard_link(&own, path);
    let _ = std::fs::remove_file(&own);
    match linked {
        Err(e) if e.kind() != std::io::ErrorKind::AlreadyExists => {
            let mut file = std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(path)?;
            file.write_all(text.as_bytes())
        }
        other => other,
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("xper-lock-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_second_lock_is_refused_while_the_first_is_held_and_granted_after() {
        let d = dir("held");
        let mut notes = Vec::new();
        let first = OutputLock::take(&d, &mut notes).unwrap();
        let err = OutputLock::take(&d, &mut notes).unwrap_err().to_string();
        assert!(
            err.contains("another run") && err.contains(&format!("pid {}", std::process::id()))
        );
        drop(first);
        assert!(!d.join(LOCK_FILE).exists());
        OutputLock::take(&d, &mut notes).unwrap();
        assert!(notes.is_empty());
    }

    #[test]
    fn the_lock_of_a_process_that_no_longer_runs_is_taken_over() {
        if alive(1).is_none() {
            return;
        }
        let d = dir("stale");
        // Process ids are below 2^22 on Linux: this one cannot run.
        let stale = format!("pid 4294967295 on host {} since 0 s\n", host());
        std::fs::write(d.join(LOCK_FILE), stale).unwrap();
        let mut notes = Vec::new();
        let _lock = OutputLock::take(&d, &mut notes).unwrap();
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(notes[0].contains("no longer runs"));
    }

    #[test]
    fn the_lock_appears_with_its_content_and_leaves_no_file_of_its_own() {
        let d = dir("content");
        let lock = OutputLock::take(&d, &mut Vec::new()).unwrap();
        let text = std::fs::read_to_string(d.join(LOCK_FILE)).unwrap();
        assert!(text.starts_with(&format!("pid {} on host ", std::process::id())));
        let names: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, [LOCK_FILE], "only the lock in the directory");
        drop(lock);
    }
}
