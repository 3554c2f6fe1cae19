//! Where each assignment of a course stands after one grading.

use super::{Assignment, COURSE};

/// Where an assignment stands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum State {
    /// The stub is untouched (it still panics with `todo!()`).
    NotStarted,
    /// The grader rejected the answer, or the copy breaks the source rule;
    /// the report.
    Failing(Failure),
    /// The grader accepted it.
    Passing,
    /// The lessons crate did not compile: `file:line: message`.
    DoesNotCompile(String),
    /// The grader did not finish within its time limit; why it was stopped.
    TimedOut(String),
    /// The grader did not report (not run).
    Unknown,
}

impl State {
    /// A short word for a status line.
    pub fn word(&self) -> &'static str {
        match self {
            State::NotStarted => "not started",
            State::Failing(_) => "failing",
            State::Passing => "passing",
            State::DoesNotCompile(_) => "does not compile",
            State::TimedOut(_) => "timed out",
            State::Unknown => "not graded",
        }
    }

    /// The report or the reason behind the word, if there is one.
    pub fn reason(&self) -> Option<&str> {
        match self {
            State::Failing(r) => Some(&r.text),
            State::DoesNotCompile(r) | State::TimedOut(r) => Some(r),
            _ => None,
        }
    }

    /// The one-line reason behind the word, from the verdict's structure
    /// (the diagnosis of a failure, the compiler's error, what timed out):
    /// what a CSV cell holds.
    pub fn one_line(&self) -> String {
        match self {
            State::Failing(r) => r.reason.clone(),
            State::DoesNotCompile(r) | State::TimedOut(r) => r.clone(),
            _ => String::new(),
        }
    }

    /// The report a student is shown by someone else's tool (Gradescope):
    /// no text of the student's own code (a panic's message) in it.
    pub fn public(&self) -> Option<&str> {
        match self {
            State::Failing(r) => Some(&r.public),
            State::DoesNotCompile(r) | State::TimedOut(r) => Some(r),
            _ => None,
        }
    }
}

/// A failure's report, in three forms.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Failure {
    /// The whole report (the student's own terminal: `spintop course`).
    pub text: String,
    /// One line: the diagnosis, or why there is no grade.
    pub reason: String,
    /// The whole report without the student's own text (a panic's
    /// message): what a grade book shows.
    pub public: String,
}

impl Failure {
    /// A report in spintop's own words (a refusal, a lost runner): the same
    /// text everywhere, its first line (with the next one, after a colon)
    /// the reason.
    pub fn plain(text: impl Into<String>) -> Self {
        let text = text.into();
        let mut lines = text.lines().map(str::trim);
        let first = lines.next().unwrap_or_default();
        let reason = match (first.ends_with(':'), lines.next()) {
            (true, Some(next)) => format!("{first} {next}"),
            _ => first.to_string(),
        };
        Self {
            reason,
            public: text.clone(),
            text,
        }
    }

    /// A grader's failure: the diagnosis is the reason; a panic's message
    /// is left out of the public report.
    pub fn of(failed: &spintop_grading::Failed) -> Self {
        let mut public = failed.clone();
        if public.actual.starts_with("panicked") {
            public.actual = "your function panicked".into();
        }
        Self {
            text: failed.to_string(),
            reason: failed.diagnosis.clone(),
            public: public.to_string(),
        }
    }
}

impl From<&str> for Failure {
    fn from(text: &str) -> Self {
        Failure::plain(text)
    }
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl std::ops::Deref for Failure {
    type Target = str;
    fn deref(&self) -> &str {
        &self.text
    }
}

/// A place in a file, and what is wrong there (a compile error, a
/// violation of the source rule).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Located {
    /// The file, as cargo or the rule names it.
    pub file: String,
    /// The line (1-based).
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for Located {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.message)
    }
}

/// The course's state after one grading run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Status {
    /// Each assignment of [`COURSE`] with its state, in course order.
    pub states: Vec<(Assignment, State)>,
    /// The seed the graders drew their inputs from.
    pub seed: u64,
    /// The first compile error, when the crate does not compile.
    pub compile_error: Option<Located>,
    /// The first violation of the source rule, when the copy breaks it.
    pub shortcut: Option<Located>,
}

impl Status {
    /// A status with each assignment's state from `state`.
    pub fn new(seed: u64, state: impl Fn(&Assignment) -> State) -> Self {
        Self {
            states: COURSE.iter().map(|a| (*a, state(a))).collect(),
            seed,
            compile_error: None,
            shortcut: None,
        }
    }

    /// How many pass.
    pub fn passing(&self) -> usize {
        self.states
            .iter()
            .filter(|(_, s)| *s == State::Passing)
            .count()
    }

    /// The first assignment in course order that does not pass.
    pub fn next(&self) -> Option<&(Assignment, State)> {
        self.states.iter().find(|(_, s)| *s != State::Passing)
    }

    /// The file to open next: where the crate does not compile or breaks the
    /// rule (`file:line`), else the next assignment's file.
    pub fn next_place(&self) -> Option<String> {
        if let Some(l) = self.compile_error.as_ref().or(self.shortcut.as_ref()) {
            return Some(format!("{}:{}", l.file, l.line));
        }
        None
    }

    /// Why no assignment has a verdict of its own, when the whole copy is
    /// stopped before any grader runs: what the "next:" line says. The
    /// source rule is per copy (its files are built together, so one file's
    /// `std::fs` reaches every assignment), and says so.
    pub fn whole_copy_reason(&self) -> Option<&'static str> {
        if self.compile_error.is_some() {
            Some("the lessons do not compile")
        } else if self.shortcut.is_some() {
            Some(
                "the copy takes a shortcut; the rule is per copy: no assignment is graded until it is gone",
            )
        } else {
            None
        }
    }

    /// The word for `state` in this status: where the source rule refused
    /// the whole copy, an assignment is "copy refused", not "failing" (a
    /// stub it holds was never graded).
    pub fn word_of(&self, state: &State) -> &'static str {
        match state {
            State::Failing(_) if self.shortcut.is_some() => "copy refused",
            other => other.word(),
        }
    }

    /// Whether every assignment has a verdict of its own (none is "does not
    /// compile" or ungraded), so that a partial re-grade can build on it.
    pub fn complete(&self) -> bool {
        self.compile_error.is_none()
            && self.shortcut.is_none()
            && self
                .states
                .iter()
                .all(|(_, s)| !matches!(s, State::DoesNotCompile(_) | State::Unknown))
    }

    /// This status with the assignments graded by `binaries` (all when empty)
    /// taken from `fresh`. A compile error or a shortcut concerns the whole
    /// crate, so it is taken for every assignment.
    pub fn merged(&self, fresh: Status, binaries: &[&str]) -> Status {
        let whole = fresh.compile_error.is_some() || fresh.shortcut.is_some();
        let states = self
            .states
            .iter()
            .zip(fresh.states)
            .map(|((a, old), (_, new))| {
                let regraded = binaries.is_empty() || binaries.contains(&a.binary);
                if regraded || whole {
                    (*a, new)
                } else {
                    (*a, old.clone())
                }
            })
            .collect();
        Status {
            states,
            seed: fresh.seed,
            compile_error: fresh.compile_error,
            shortcut: fresh.shortcut,
        }
    }
}
