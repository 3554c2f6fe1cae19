//! The warm build: the course's stubs built once into a cache that every
//! `course grade` shares (under a file lock: two runs at once wait for each
//! other's build, and never write into each other's folders), and copied
//! from there into each copy's private build folder, so that a copy's
//! build compiles the student's crate alone (a few seconds) and not
//! spintop's core (a minute or more).

use super::CourseError;
use super::compile::{self, Built};
use super::process::Ctx;
use super::workspace::{Workspace, private_dir};
use std::path::{Path, PathBuf};

/// The units a copy builds itself: their files are not copied.
const OWN_UNITS: [&str; 4] = [
    "spintop_lessons",
    "spintop-lessons",
    "runner",
    "spintop-course-runner",
];

/// The warm cache of the repository `repo` (shared by every grading).
pub(crate) fn cache_dir(repo: &Path) -> PathBuf {
    repo.join("target").join("course-grade").join("cache")
}

/// Seeds the build folder `target` (when it has no build yet) from the
/// repository's warm cache, if one was built, under the cache's lock
/// (shared: several may copy at once, none while it is rebuilt).
pub(crate) fn seed_from_cache(repo: &Path, target: &Path) -> Result<(), CourseError> {
    let cache = cache_dir(repo);
    let warm = cache.join("workspace").join("target");
    if target.join("debug").join("deps").is_dir() || !warm.join("debug").join("deps").is_dir() {
        return Ok(());
    }
    let lock_path = cache.join("lock");
    let Ok(lock) = std::fs::File::open(&lock_path) else {
        return Ok(());
    };
    #[cfg(unix)]
    rustix::fs::flock(&lock, rustix::fs::FlockOperation::LockShared)
        .map_err(|e| CourseError::io(&lock_path)(e.into()))?;
    copy_into(&warm, target)
}

/// Builds the stubs' runner in the cache `cache` (under its lock) and
/// copies its build folder to `into`, a run's own: the warm build every
/// copy of the run starts from.
pub(crate) fn prepare(
    repo: &Path,
    cache: &Path,
    into: &Path,
    launcher: Option<&Path>,
    ctx: &Ctx,
) -> Result<(), CourseError> {
    private_dir(cache)?;
    let lock_path = cache.join("lock");
    let lock = std::fs::File::create(&lock_path).map_err(CourseError::io(&lock_path))?;
    #[cfg(unix)]
    rustix::fs::flock(&lock, rustix::fs::FlockOperation::LockExclusive)
        .map_err(|e| CourseError::io(&lock_path)(e.into()))?;
    let ws = Workspace::at(&cache.join("workspace"));
    ws.lay_out(repo)?;
    write_stubs(repo, &ws)?;
    match compile::build_runner(&ws, launcher, false, 3600, ctx, None)? {
        Built::Programs(_) => {}
        Built::Failed(errors) => {
            let first = errors.first().map(|e| e.to_string()).unwrap_or_default();
            return Err(CourseError::Export(format!(
                "the course's own stubs do not build: {first}"
            )));
        }
        Built::OutOfTime | Built::Bounded(_) => {
            return Err(CourseError::Export(
                "the course's own stubs did not build in time".into(),
            ));
        }
    }
    copy_tree(&ws.target(), into, |_| true)?;
    drop(lock);
    Ok(())
}

/// The repository's stubs as the workspace's course (a file rewritten
/// only when it changed, so that cargo's last build stays fresh).
fn write_stubs(repo: &Path, ws: &Workspace) -> Result<(), CourseError> {
    let from = super::lessons_dir(repo).join("src");
    for path in super::export::rust_files(&from, &["solutions"]) {
        let rel = path.strip_prefix(&from).unwrap_or(&path);
        let text = std::fs::read_to_string(&path).map_err(CourseError::io(&path))?;
        let text = super::strip_solutions(&text);
        let to = ws.course().join("src").join(rel);
        if std::fs::read_to_string(&to).ok().as_deref() != Some(text.as_str()) {
            if let Some(parent) = to.parent() {
                private_dir(parent)?;
            }
            std::fs::write(&to, text).map_err(CourseError::io(&to))?;
        }
    }
    Ok(())
}

/// Copies the warm build `warm` into the build folder `target` when it has
/// no build yet (a workspace kept between gradings has its own), leaving
/// out the units the copy builds itself.
pub(crate) fn copy_into(warm: &Path, target: &Path) -> Result<(), CourseError> {
    if target.join("debug").join("deps").is_dir() {
        return Ok(());
    }
    copy_tree(warm, target, |name| {
        !OWN_UNITS.iter().any(|u| {
            name == *u
                || name.starts_with(&format!("{u}-"))
                || name.starts_with(&format!("lib{u}-"))
        })
    })
}

/// Copies the tree `from` to `to` (folders private), each file keeping its
/// modification time (cargo compares them); entries whose name `keep`
/// refuses are left out. Links are not followed.
fn copy_tree(from: &Path, to: &Path, keep: impl Fn(&str) -> bool) -> Result<(), CourseError> {
    let mut stack: Vec<(PathBuf, PathBuf)> = vec![(from.to_path_buf(), to.to_path_buf())];
    while let Some((src, dst)) = stack.pop() {
        private_dir(&dst)?;
        for entry in std::fs::read_dir(&src).map_err(CourseError::io(&src))? {
            let entry = entry.map_err(CourseError::io(&src))?;
            let name = entry.file_name();
            if !keep(&name.to_string_lossy()) {
                continue;
            }
            let kind = entry.file_type().map_err(CourseError::io(&entry.path()))?;
            let (s, d) = (entry.path(), dst.join(&name));
            if kind.is_dir() {
                stack.push((s, d));
            } else if kind.is_file() {
                std::fs::copy(&s, &d).map_err(CourseError::io(&s))?;
                let modified = entry.metadata().and_then(|m| m.modified());
                if let Ok(time) = modified {
                    let file = std::fs::File::options().write(true).open(&d);
                    let _ = file.and_then(|f| f.set_modified(time));
                }
            }
        }
    }
    Ok(())
}
