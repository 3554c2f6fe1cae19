//! The course beside the book: the course the reader stands in (found as
//! [`spintop_course::find_course`] finds it), graded in the background at
//! the start and on every save, its progress while it builds, the hint
//! ladder, and the student's own function of time drawn against the
//! reference.

use spintop_course::building::{Building, Snapshot};
use spintop_course::{self as course, Course, Hint, ProbeSpec, Probed, Status, Watch};
use std::sync::Arc;
use std::time::Instant;

/// A probe's request and what it found.
pub type ProbeReport = (ProbeSpec, Result<Probed, String>);

/// The course's state as `spintop learn` shows it.
#[derive(Default)]
pub struct Panel {
    /// The course graded, once chosen.
    pub(super) course: Option<Course>,
    /// The grader, watching the student's files.
    pub(super) watch: Option<Watch>,
    /// Why nothing is graded, when grading is off.
    pub(super) off: Option<String>,
    /// The last grading.
    pub(super) status: Option<Status>,
    /// When the grading running now started.
    pub(super) grading_since: Option<Instant>,
    /// When the last grading ended.
    pub(super) graded_at: Option<Instant>,
    /// How far the grading running now has got.
    pub(super) building: Option<Arc<Building>>,
    /// Why the grader could not run, if it could not.
    pub(super) error: Option<String>,
    /// The last hint rung shown (`h`).
    pub(super) hint: Option<Hint>,
    /// The hint rungs used, when there is no course folder to keep them in.
    pub(super) hints_used: course::Progress,
    /// The course's progress file as last seen (its time and length), so
    /// that a rung taken in another terminal shows here.
    pub(super) progress_seen: Option<(std::time::SystemTime, u64)>,
    /// The student's function of time being sampled.
    pub(super) probe_rx: Option<std::sync::mpsc::Receiver<ProbeReport>>,
    /// The student's function of time, sampled.
    pub(super) yours: Option<ProbeReport>,
}

impl Panel {
    /// The course graded, if one is.
    pub fn course(&self) -> Option<&Course> {
        self.course.as_ref()
    }

    /// The last grading, if any.
    pub fn status(&self) -> Option<&Status> {
        self.status.as_ref()
    }

    /// How far the grading running now has got, if one runs.
    pub fn grading(&self) -> Option<Snapshot> {
        self.grading_since?;
        Some(
            self.building
                .as_ref()
                .map(|b| b.snapshot())
                .unwrap_or_default(),
        )
    }

    /// When the latest grading ended (with grades, a compile error among
    /// them, or failing to run cargo).
    pub fn graded_at(&self) -> Option<Instant> {
        self.graded_at
    }

    /// Seconds since the latest grading ended.
    pub fn graded_ago(&self) -> Option<u64> {
        self.graded_at.map(|t| t.elapsed().as_secs())
    }

    /// Why the grader could not run, if it could not.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// Why nothing is graded in this session, if grading is off.
    pub fn off(&self) -> Option<&str> {
        self.off.as_deref()
    }

    /// The hint on screen, if any.
    pub fn hint(&self) -> Option<&Hint> {
        self.hint.as_ref()
    }
}
