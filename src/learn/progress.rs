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

/// Reads the progress file: a missing one is a fresh start; one that
/// cannot be read is the [`Unreadable`] error (see [`open`]).
pub fn read(path: &Path) -> Progress {
    parse(path).unwrap_or_default()
}

/// The progress file, or why it cannot be read (`None`: there is none).
fn parse(path: &Path) -> Result<Progress, Option<String>> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(None),
        Err(e) => return Err(Some(e.to_string())),
    };
    if bytes.len() >= 1 << 20 {
        return Err(Some(format!("{} bytes, not a progress file", bytes.len())));
    }
    serde_json::from_slice(&bytes).map_err(|e| Some(format!("not a progress file: {e}")))
}

/// Opens the progress file at `path` for a session: what it holds, and
/// what to say about it. A file that cannot be read is never written over
/// unsaid: it is set aside as `<name>.bad` (the reader starts afresh and
/// says which file, why, and where it now is); when it cannot be set aside
/// either, the place is not kept this session (`keep` false), so that the
/// file stays as it is.
pub fn open(path: &Path) -> Opened {
    let why = match parse(path) {
        Ok(progress) => return Opened::fresh(progress),
        Err(None) => return Opened::fresh(Progress::default()),
        // Only a regular file is ever set aside: a device (`/dev/null`,
        // where tests keep their place) is read as a fresh start and
        // written in place, never renamed.
        Err(Some(_)) if !std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) => {
            return Opened::fresh(Progress::default());
        }
        Err(Some(why)) => why,
    };
    let mut bad = path.as_os_str().to_owned();
    bad.push(".bad");
    let bad = PathBuf::from(bad);
    let (said, keep) = match std::fs::rename(path, &bad) {
        Ok(()) => (
            format!(
                "your place could not be read from {} ({why}); the file is set aside as {}, reading starts afresh",
                path.display(),
                file_name(&bad)
            ),
            true,
        ),
        Err(e) => (
            format!(
                "your place could not be read from {} ({why}) nor the file set aside as {} ({e}); it is left as it is, and your place is not kept this session",
                path.display(),
                file_name(&bad)
            ),
            false,
        ),
    };
    Opened {
        progress: Progress::default(),
        said: Some(said),
        keep,
    }
}

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The progress file as a session opens it ([`open`]).
#[derive(Debug)]
pub struct Opened {
    /// What it holds (nothing, when it could not be read).
    pub progress: Progress,
    /// What to tell the reader about it.
    pub said: Option<String>,
    /// False when the file must not be written this session.
    pub keep: bool,
}

impl Opened {
    fn fresh(progress: Progress) -> Self {
        Self {
            progress,
            said: None,
            keep: true,
        }
    }
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

    /// Writes this session's place, merged with what another session (a
    /// second `learn` in the same course) wrote meanwhile: the file as it
    /// is now, with the chapters this session moved in since its last write
    /// taken from this session ([`merged`]). So two sessions keep each
    /// other's places, chapter by chapter, whichever quits last.
    fn write(&mut self, progress: &Progress) -> Result<(), NotKept> {
        let on_disk = parse(&self.path).ok();
        let whole = match (on_disk, &self.written) {
            (Some(disk), Some(base)) if &disk != base => merged(disk, base, progress),
            _ => progress.clone(),
        };
        let bytes = serde_json::to_vec_pretty(&whole).unwrap_or_default();
        write_whole(&self.path, &bytes).map_err(|e| NotKept {
            path: self.path.display().to_string(),
            why: spintop_course::unwritable_why(&self.path, &e),
        })?;
        self.written = Some(progress.clone());
        Ok(())
    }
}

/// `disk` (the file as another session left it) with what this session
/// changed since `base` (what it last wrote, or read at its start): the
/// chapters whose place it moved, the chapters it opened, and its last
/// chapter.
fn merged(disk: Progress, base: &Progress, ours: &Progress) -> Progress {
    let mut whole = disk;
    for (chapter, place) in &ours.positions {
        if base.positions.get(chapter) != Some(place) {
            whole.positions.insert(chapter.clone(), *place);
        }
    }
    for chapter in &ours.opened {
        if !whole.opened.contains(chapter) {
            whole.opened.push(chapter.clone());
        }
    }
    if ours.last != base.last || whole.last.is_none() {
        whole.last.clone_from(&ours.last);
    }
    whole
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

    /// Two sessions in one course (two terminals): each keeps the place
    /// it moved, whichever writes last. Found by a student-reviewer: the
    /// session that quit last wrote its whole stale view, and the other's
    /// place in Section 4.1 (line 776) went back to 0.
    #[test]
    fn two_sessions_keep_each_others_places() {
        let dir = std::env::temp_dir().join(format!("spintop-keep-two-{}", std::process::id()));
        let path = dir.join("learn.json");
        let start = Progress {
            opened: vec!["section-4-1.md".into()],
            last: Some("section-4-1.md".into()),
            positions: BTreeMap::from([("section-4-1.md".into(), (0, 795))]),
        };
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(&path, serde_json::to_vec(&start).unwrap()).unwrap();
        let mut first = Keeper::new(path.clone(), read(&path));
        let mut second = Keeper::new(path.clone(), read(&path));
        // The first goes to the end of Section 4.1 and quits.
        let mut a = start.clone();
        a.positions.insert("section-4-1.md".into(), (776, 795));
        first.save(&a).unwrap();
        // The second, which still sees 4.1 at line 0, reads Section 5.
        let mut b = start.clone();
        b.opened.push("section-5.md".into());
        b.last = Some("section-5.md".into());
        b.positions.insert("section-5.md".into(), (27, 1243));
        second.save(&b).unwrap();
        let kept = read(&path);
        assert_eq!(kept.positions["section-4-1.md"], (776, 795), "{kept:?}");
        assert_eq!(kept.positions["section-5.md"], (27, 1243), "{kept:?}");
        assert_eq!(kept.opened, ["section-4-1.md", "section-5.md"]);
        assert_eq!(kept.last.as_deref(), Some("section-5.md"));
        // And the first, moving again, keeps the second's chapter.
        a.positions.insert("section-4-1.md".into(), (700, 795));
        first.save(&a).unwrap();
        let kept = read(&path);
        assert_eq!(kept.positions["section-4-1.md"], (700, 795));
        assert_eq!(kept.positions["section-5.md"], (27, 1243));
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

    #[test]
    fn an_unreadable_file_is_said_and_set_aside_not_written_over() {
        let dir = std::env::temp_dir().join(format!("spintop-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("learn.json");
        std::fs::write(&path, b"{garbage\n").unwrap();
        let opened = open(&path);
        assert_eq!(opened.progress, Progress::default());
        assert!(opened.keep);
        let said = opened.said.expect("said");
        assert!(
            said.contains(&path.display().to_string()) && said.contains("learn.json.bad"),
            "{said}"
        );
        assert_eq!(
            std::fs::read(dir.join("learn.json.bad")).unwrap(),
            b"{garbage\n"
        );
        assert!(!path.exists());
        // A good file, and none, are read without a word.
        let good = Progress {
            last: Some("section-2.md".into()),
            ..Progress::default()
        };
        std::fs::write(&path, serde_json::to_vec(&good).unwrap()).unwrap();
        let opened = open(&path);
        assert_eq!((opened.progress, opened.said), (good, None));
        assert_eq!(open(&dir.join("none.json")).said, None);
        // A device is never set aside (renamed): /dev/null stays itself.
        let null = Path::new("/dev/null");
        if null.exists() {
            let opened = open(null);
            assert_eq!((opened.said, opened.keep), (None, true));
            assert!(!Path::new("/dev/null.bad").exists());
            assert!(
                !std::fs::metadata(null).unwrap().is_file(),
                "still a device"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
