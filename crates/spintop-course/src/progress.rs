//! The course's progress: hint rungs used and when each assignment first
//! passed, in one small JSON file inside the course (never anywhere else).

use super::{State, Status};
use std::path::Path;

/// The course's small state file: hint rungs used and first-passed times.
#[derive(Debug, Default, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Progress {
    /// Hint rungs used so far, by assignment (function name).
    #[serde(default)]
    pub hints: std::collections::BTreeMap<String, u8>,
    /// When each assignment first passed (seconds since the Unix epoch).
    #[serde(default)]
    pub first_passed: std::collections::BTreeMap<String, u64>,
}

/// Where the course in `dir` keeps its [`Progress`]: the repository's
/// `target/spintop-course.json` for its own lessons/, the course's own
/// `target/` for a student's copy. Never anywhere else.
pub fn progress_path(dir: &Path) -> std::path::PathBuf {
    let parent = dir.parent().filter(|p| {
        dir.file_name().is_some_and(|n| n == "lessons") && p.join("Cargo.toml").is_file()
    });
    parent
        .unwrap_or(dir)
        .join("target")
        .join("spintop-course.json")
}

/// The largest progress file read (a real one is a few hundred bytes).
const MAX_PROGRESS: u64 = 64 * 1024;

/// The course's [`Progress`], or why it could not be read: a missing file
/// is a fresh start; a link, a FIFO, a device or a file larger than 64 kB
/// is refused without being read (a FIFO is not waited on, `/dev/zero` is
/// not read at all).
pub fn read_progress(dir: &Path) -> Result<Progress, String> {
    let path = progress_path(dir);
    let (Some(parent), Some(name)) = (path.parent().and_then(Path::parent), path.file_name())
    else {
        return Ok(Progress::default());
    };
    let rel = Path::new("target").join(name);
    match super::snapshot::read_bounded(parent, &rel, MAX_PROGRESS) {
        Ok(bytes) => {
            serde_json::from_slice(&bytes).map_err(|e| format!("is not a progress file: {e}"))
        }
        Err(super::snapshot::ReadError::Missing) => Ok(Progress::default()),
        Err(e) => Err(format!("is refused: {e}")),
    }
}

/// The course's [`Progress`]; a missing or unreadable file is a fresh start.
pub fn load_progress(dir: &Path) -> Progress {
    read_progress(dir).unwrap_or_default()
}

/// Writes the course's [`Progress`].
pub fn save_progress(dir: &Path, progress: &Progress) -> Result<(), String> {
    let path = progress_path(dir);
    // The file is named, and the folder that refuses it.
    let why =
        |e: std::io::Error| format!("{}: {}", path.display(), super::unwritable_why(&path, &e));
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(why)?;
    }
    let text = serde_json::to_string_pretty(progress).map_err(|e| e.to_string())?;
    std::fs::write(&path, text).map_err(why)
}

/// [`record_passes`] at the present time, kept in the course's progress file
/// (a read-only course still grades: a failed write is not an error).
pub fn record_passes_now(dir: &Path, status: &Status) {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let mut progress = load_progress(dir);
    if record_passes(&mut progress, status, now) {
        let _ = save_progress(dir, &progress);
    }
}

/// Records the first time each assignment of `status` passed (`now` in
/// seconds since the Unix epoch); true when something new was recorded.
pub fn record_passes(progress: &mut Progress, status: &Status, now: u64) -> bool {
    let mut changed = false;
    for (a, s) in &status.states {
        if *s == State::Passing && !progress.first_passed.contains_key(a.function) {
            progress.first_passed.insert(a.function.to_string(), now);
            changed = true;
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{COURSE, lessons_dir};

    #[test]
    fn the_progress_lives_inside_the_project_and_survives_a_round_trip() {
        let repo = crate::repository();
        assert_eq!(
            progress_path(&lessons_dir(repo)),
            repo.join("target/spintop-course.json")
        );
        let dir = std::env::temp_dir().join(format!("spintop-progress-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        assert_eq!(progress_path(&dir), dir.join("target/spintop-course.json"));
        assert_eq!(load_progress(&dir), Progress::default());
        let mut p = Progress::default();
        // A rung used (what `next_hint` records), so the round trip carries one.
        p.hints.insert(COURSE[0].function.to_string(), 1);
        let mut status = Status::new(0, |_| State::Unknown);
        status.states[1].1 = State::Passing;
        assert!(record_passes(&mut p, &status, 1234));
        assert!(
            !record_passes(&mut p, &status, 9999),
            "the first pass is kept"
        );
        save_progress(&dir, &p).unwrap();
        assert_eq!(load_progress(&dir), p);
        assert_eq!(p.first_passed[COURSE[1].function], 1234);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
