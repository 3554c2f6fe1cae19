//! Where the reader is: the chapters opened, the last one, and where each
//! was left, kept in one small file (`target/spintop-learn.json`).
//!
//! The file is written while the reader reads, not only on `q`: whenever
//! the place changes (at most a few times a second), whole or not at all
//! (a new file renamed over the old one). So a terminal closed under the
//! reader (the pane killed, the window closed, SIGHUP, even SIGKILL) loses
//! at most the last fraction of a second. A write that fails is said on the
//! screen when it happens and again when the session ends.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The progress file's content: the chapters opened so far, the last one,
/// and where each was left.
#[derive(Debug, Default, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Progress {
    /// File names of the chapters opened.
    pub opened: Vec<String>,
    /// The chapter open when the session ended.
    pub last: Option<String>,
    /// Where each chapter was left: (first line shown, lines of the chapter
    /// at the width it was read at).
    #[serde(default)]
    pub positions: BTreeMap<String, (usize, usize)>,
}

/// Reads the progress file: a missing, unreadable or foreign file is a
/// fresh start, never an error.
pub fn read(path: &Path) -> Progress {
    std::fs::read(path)
        .ok()
        .filter(|b| b.len() < 1 << 20)
        .and_then(|b| serde_json::from_slice(&b).ok())
        .unwrap_or_default()
}

/// Why the place could not be kept.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("your place could not be saved to {path} (reading goes on): {why}")]
pub struct NotKept {
    /// The progress file.
    pub path: String,
    /// The system's reason.
    pub why: String,
}

/// The shortest time between two writes of the file while the place moves.
pub const EVERY: Duration = Duration::from_millis(250);

/// Keeps the progress file up to date with the reader.
#[derive(Debug)]
pub struct Keeper {
    path: PathBuf,
    written: Option<Progress>,
    last_write: Option<Instant>,
    failure: Option<NotKept>,
}

impl Keeper {
    /// Keeps the progress in `path`, which holds `read` now.
    pub fn new(path: PathBuf, read: Progress) -> Self {
        Self {
            path,
            written: Some(read),
            last_write: None,
            failure: None,
        }
    }

    /// The file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes `progress` if it differs from what the file holds and the
    /// last write is [`EVERY`] old; the failure of this write, when it is a
    /// new one (a failure is said once, not every frame).
    pub fn keep(&mut self, progress: &Progress, now: Instant) -> Option<NotKept> {
        if self.written.as_ref() == Some(progress)
            || self
                .last_write
                .is_some_and(|t| now.duration_since(t) < EVERY)
        {
            return None;
        }
        self.last_write = Some(now);
        match self.write(progress) {
            Ok(()) => {
                self.failure = None;
                None
            }
            Err(e) => {
                let new = self.failure.as_ref() != Some(&e);
                self.failure = Some(e.clone());
                new.then_some(e)
            }
        }
    }

    /// Writes `progress` now, whatever was written before.
    pub fn save(&mut self, progress: &Progress) -> Result<(), NotKept> {
        self.write(progress)
            .inspect_err(|e| self.failure = Some(e.clone()))
    }

    /// The last write's failure, if the last write failed.
    pub fn failure(&self) -> Option<&NotKept> {
        self.failure.as_ref()
    }

    fn write(&mut self, progress: &Progress) -> Result<(), NotKept> {
        let bytes = serde_json::to_vec_pretty(progress).unwrap_or_default();
        write_whole(&self.path, &bytes).map_err(|e| NotKept {
            path: self.path.display().to_string(),
            why: spintop_course::unwritable_why(&self.path, &e),
        })?;
        self.written = Some(progress.clone());
        Ok(())
    }
}

/// Writes `bytes` to `path` whole or not at all: to a new file beside it,
/// then renamed over it. A path that is not a regular file (`/dev/null`) is
/// written in place.
fn write_whole(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if path.exists() && !path.is_file() {
        return std::fs::write(path, bytes);
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let name = path
        .file_name()
        .map_or_else(|| "progress".into(), |n| n.to_string_lossy().into_owned());
    let fresh = path.with_file_name(format!(".{name}.{}.new", std::process::id()));
    std::fs::write(&fresh, bytes)
        .and_then(|()| std::fs::rename(&fresh, path))
        .inspect_err(|_| {
            let _ = std::fs::remove_file(&fresh);
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_place_is_written_as_it_moves_at_most_every_quarter_second() {
        let dir = std::env::temp_dir().join(format!("spintop-keep-{}", std::process::id()));
        let path = dir.join("learn.json");
        let mut keeper = Keeper::new(path.clone(), Progress::default());
        let t0 = Instant::now();
        let mut p = Progress {
            last: Some("section-2.md".into()),
            ..Progress::default()
        };
        assert_eq!(keeper.keep(&p, t0), None);
        assert_eq!(read(&path), p);
        p.positions.insert("section-2.md".into(), (40, 400));
        // Too soon: not yet written; a quarter second later, written.
        assert_eq!(keeper.keep(&p, t0 + Duration::from_millis(10)), None);
        assert_ne!(read(&path), p);
        assert_eq!(keeper.keep(&p, t0 + EVERY), None);
        assert_eq!(read(&path), p);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_failed_write_is_said_once() {
        // A path under a regular file cannot be created.
        let file = std::env::temp_dir().join(format!("spintop-keep-file-{}", std::process::id()));
        std::fs::write(&file, b"x").unwrap();
        let mut keeper = Keeper::new(file.join("learn.json"), Progress::default());
        let p = Progress {
            last: Some("preface.md".into()),
            ..Progress::default()
        };
        let t0 = Instant::now();
        let first = keeper.keep(&p, t0).expect("the failure is said");
        assert!(first.to_string().contains("could not be saved"), "{first}");
        assert_eq!(keeper.keep(&p, t0 + EVERY), None, "said once");
        assert!(keeper.failure().is_some());
        assert!(keeper.save(&p).is_err());
        let _ = std::fs::remove_file(&file);
    }
}
