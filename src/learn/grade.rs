//! The course commands and news of [`Learn`]: the grader started on the
//! course the reader stands in, its reports taken, the hint ladder, the
//! probe of the student's function of time (the panel's state is
//! [`super::course`]'s).

use super::course::ProbeReport;
use super::{Learn, Mode};
use spintop_course::building::Building;
use spintop_course::{self as course, Course, Hint, ProbeSpec, Probed, State, Status, Watch};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

impl Learn {
    /// Starts grading `course` in the background, again on every save of a
    /// file under its `src/`, the student's build and runner in the sandbox
    /// that `launcher` (the `spintop` binary) sets up.
    pub fn watch_course(&mut self, course: Course, launcher: Option<PathBuf>) {
        let building = Building::shared();
        let options = course::Options {
            course_arg: course.course_arg(),
            progress: Some(Arc::clone(&building)),
            launcher,
            ..course::Options::default()
        };
        self.course.watch = Some(Watch::with_options(&course.dir, options));
        self.course.building = Some(building);
        self.course.course = Some(course);
    }

    /// Says why nothing is graded in this session (`--no-grading`).
    pub fn grading_off(&mut self, why: impl Into<String>) {
        self.course.off = Some(why.into());
    }

    /// The last grading of the course, if any.
    pub fn course(&self) -> Option<&Status> {
        self.course.status.as_ref()
    }

    /// True while a grading runs.
    pub fn grading(&self) -> bool {
        self.course.grading_since.is_some()
    }

    /// Why the grader could not run, if it could not.
    pub fn course_error(&self) -> Option<&str> {
        self.course.error.as_deref()
    }

    /// Why nothing is graded in this session, if grading is off.
    pub fn grading_off_reason(&self) -> Option<&str> {
        self.course.off.as_deref()
    }

    /// The hint on screen, if any.
    pub fn hint(&self) -> Option<&Hint> {
        self.course.hint.as_ref()
    }

    /// Takes the grader's and the probe's news, and the hint rungs taken
    /// elsewhere.
    pub(super) fn poll_course(&mut self) {
        self.follow_hints();
        let reports = self
            .course
            .watch
            .as_ref()
            .map(|w| w.poll())
            .unwrap_or_default();
        for report in reports {
            self.course_report(report);
        }
        if let Some(report) = self
            .course
            .probe_rx
            .as_ref()
            .and_then(|rx| rx.try_recv().ok())
        {
            self.course.probe_rx = None;
            self.probe_report(report);
        }
    }

    /// Takes one report of the course grader.
    pub fn course_report(&mut self, report: course::Report) {
        match report {
            course::Report::Grading => self.course.grading_since = Some(Instant::now()),
            course::Report::Graded(status) => {
                self.course.grading_since = None;
                self.course.graded_at = Some(Instant::now());
                self.course.error = None;
                if let Some(c) = &self.course.course {
                    course::record_passes_now(&c.dir, &status);
                }
                self.course.status = Some(status);
                self.start_probe();
            }
            course::Report::Failed(e) => {
                // The time shown is the latest grading's, whatever it found.
                self.course.grading_since = None;
                self.course.graded_at = Some(Instant::now());
                self.course.error = Some(e);
            }
        }
    }

    /// The hint on screen follows the course's progress file: a rung taken
    /// in another terminal (`spintop course hint`) shows here at the next
    /// frame (the file is looked at, one `stat`, and read when it changed).
    fn follow_hints(&mut self) {
        let (Some(c), Some(shown)) = (&self.course.course, &self.course.hint) else {
            return;
        };
        let path = course::progress_path(&c.dir);
        let seen = std::fs::metadata(&path)
            .ok()
            .and_then(|m| Some((m.modified().ok()?, m.len())));
        if seen.is_none() || seen == self.course.progress_seen {
            return;
        }
        self.course.progress_seen = seen;
        let progress = course::load_progress(&c.dir);
        if let Some(reached) = course::hint_reached(&progress, shown.assignment)
            && reached.rung != shown.rung
        {
            self.course.hint = Some(reached);
        }
        self.course.hints_used = progress;
    }

    /// The assignment the course panel's diagnosis and `h`'s hint are for:
    /// the first of this chapter's assignments that fails, else the course's
    /// first failing one, else the first of this chapter's not passing yet,
    /// else the course's next one.
    pub fn hint_target(&self) -> Option<&'static course::Assignment> {
        let title = &self.chapters[self.current].title;
        let state = |a: &course::Assignment| {
            self.course.status.as_ref().and_then(|s| {
                s.states
                    .iter()
                    .find(|(b, _)| b.function == a.function)
                    .map(|(_, st)| st.clone())
            })
        };
        let passing = |a: &course::Assignment| state(a) == Some(State::Passing);
        let failing = |a: &course::Assignment| {
            matches!(
                state(a),
                Some(State::Failing(_) | State::DoesNotCompile(_) | State::TimedOut(_))
            )
        };
        let here = |a: &&course::Assignment| title.starts_with(a.chapter);
        let all = || course::COURSE.iter();
        // A wrong answer anywhere is what the student is working on: its
        // diagnosis comes before a stub of the chapter on screen.
        all()
            .filter(here)
            .find(|a| failing(a))
            .or_else(|| all().find(|a| failing(a)))
            .or_else(|| all().filter(here).find(|a| !passing(a)))
            .or_else(|| all().find(|a| !passing(a)))
    }

    /// The next hint rung (`h`): for [`Self::hint_target`], kept in the
    /// course's progress file when the course is being graded.
    pub(super) fn next_hint(&mut self) {
        let Some(a) = self.hint_target() else {
            self.course.hint = None;
            return;
        };
        let dir = self.course.course.as_ref().map(|c| c.dir.clone());
        let mut progress = match &dir {
            Some(dir) => course::load_progress(dir),
            None => self.course.hints_used.clone(),
        };
        self.course.hint = Some(course::next_hint(&mut progress, a));
        self.course.hints_used = progress.clone();
        if let Some(dir) = &dir
            && let Err(e) = course::save_progress(dir, &progress)
        {
            self.refuse(format!("cannot keep the hint: {e}"));
        }
        // The hint shows under the diagnosis; the panel scrolls to it when
        // it is below the first screen (a rung is never spent unseen).
        let lines = super::view::course_lines(self, self.size.0);
        let hint = lines.iter().position(|l| {
            l.spans
                .first()
                .is_some_and(|s| s.content.starts_with("hint "))
        });
        let scroll = hint.map_or(0, |k| {
            crate::term::popup::scroll_to(
                self.size,
                super::view::COURSE_WIDTH,
                &lines,
                k..(k + 2).min(lines.len()),
            )
        });
        self.mode = Mode::Course(scroll);
    }

    /// Samples the student's function of time of this chapter, if it has one
    /// that the student has started (passing or failing), in the background;
    /// the scene then draws it against the reference.
    pub fn start_probe(&mut self) {
        let (Some(c), Some(status)) = (&self.course.course, &self.course.status) else {
            return;
        };
        let Some(spec) = ProbeSpec::for_chapter(&self.chapters[self.current].title) else {
            return;
        };
        let started = status.states.iter().any(|(a, st)| {
            a.function == spec.function && matches!(st, State::Passing | State::Failing(_))
        });
        if !started {
            return;
        }
        let (tx, rx) = std::sync::mpsc::channel();
        let dir = c.dir.clone();
        std::thread::spawn(move || {
            let _ = tx.send((spec, course::probe(&dir, &spec)));
        });
        self.course.probe_rx = Some(rx);
    }

    /// Takes a probe's report (from the background, or from a test).
    pub fn probe_report(&mut self, report: ProbeReport) {
        self.course.yours = Some(report);
    }

    /// The student's function of time of this chapter against the reference,
    /// when it has been sampled.
    pub fn yours(&self) -> Option<(&ProbeSpec, &Result<Probed, String>)> {
        let (spec, probed) = self.course.yours.as_ref()?;
        let here = ProbeSpec::for_chapter(&self.chapters[self.current].title)?;
        (*spec == here).then_some((spec, probed))
    }
}
