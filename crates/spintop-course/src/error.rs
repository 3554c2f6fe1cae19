//! The course's errors: why a grading could not be done at all (what a
//! grading finds wrong with a copy is a state in its status instead).

use std::path::{Path, PathBuf};

/// Why a grading, an export or a snapshot could not be done.
#[derive(Debug, thiserror::Error)]
pub enum CourseError {
    /// A file or folder of spintop's own could not be read or written.
    #[error("{}: {}", path.display(), super::unwritable_why(path, source))]
    Io {
        /// Where.
        path: PathBuf,
        /// What.
        source: std::io::Error,
    },
    /// Cargo could not be started.
    #[error("cannot run cargo: {0}")]
    Cargo(std::io::Error),
    /// The grading could not run at all (cargo not found in the sandbox, a
    /// sandbox that could not be set up): the launcher's words. Not a state
    /// of the student's code.
    #[error("the grading could not run, so nothing was graded: {0}")]
    CannotGrade(String),
    /// The copy could not be snapshotted.
    #[error(transparent)]
    Snapshot(#[from] super::snapshot::SnapshotError),
    /// The sandbox could not be started.
    #[error(transparent)]
    Sandbox(#[from] super::sandbox::SandboxError),
    /// An export failed (its own words).
    #[error("{0}")]
    Export(String),
}

impl CourseError {
    /// True when the grading itself could not run (cargo or the sandbox,
    /// a folder it may not write), as against spintop's own files.
    pub fn is_grading_failure(&self) -> bool {
        matches!(
            self,
            CourseError::CannotGrade(_) | CourseError::Cargo(_) | CourseError::Sandbox(_)
        )
    }

    /// A closure that makes an I/O error at `path`.
    pub(crate) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> CourseError + '_ {
        move |source| CourseError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}
