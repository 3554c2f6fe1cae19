//! How far a grading has got, for a screen to show while it runs: the
//! first grading of a copy compiles spintop's core and the copy's runner
//! (in the build sandbox), which takes minutes, and "grading…" alone for
//! minutes looks like a hang.
//!
//! The harness reports into a shared [`Building`]: cargo's own count of
//! the units it compiles (its progress line, `Building [==> ] 45/120:
//! nalgebra, syn`, which cargo writes to a pipe when asked to with
//! `CARGO_TERM_PROGRESS_WHEN=always`), the artifacts its JSON messages name
//! as they are done, then the graders run. Nothing here decides a verdict.

use std::io::Read;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// What a grading is doing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Phase {
    /// Not started, or between gradings.
    #[default]
    Idle,
    /// Taking the copy's snapshot and reading it for the source rule.
    Checking,
    /// cargo builds the copy's runner.
    Building,
    /// The graders run, each calling the student's functions in a runner.
    Grading,
}

/// A grading's progress at one moment.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Snapshot {
    /// What it is doing.
    pub phase: Phase,
    /// cargo's count of units compiled and to compile, once it has said.
    pub units: Option<(usize, usize)>,
    /// The units cargo is compiling now, as it names them.
    pub compiling: String,
    /// Artifacts cargo has reported finished (fresh ones included).
    pub artifacts: usize,
    /// Graders done and to run.
    pub graders: (usize, usize),
    /// Time since the grading started.
    pub elapsed: Duration,
}

impl Snapshot {
    /// One line for a status: "compiling 45 of 120 (nalgebra, syn), 1:23".
    pub fn describe(&self) -> String {
        let clock = format!(
            "{}:{:02}",
            self.elapsed.as_secs() / 60,
            self.elapsed.as_secs() % 60
        );
        match self.phase {
            Phase::Idle => format!("starting, {clock}"),
            Phase::Checking => format!("reading the copy's files, {clock}"),
            Phase::Building => match self.units {
                Some((done, total)) if !self.compiling.is_empty() => {
                    format!("compiling {done} of {total} ({}), {clock}", self.compiling)
                }
                Some((done, total)) => format!("compiling {done} of {total}, {clock}"),
                None => format!("building ({} compiled), {clock}", self.artifacts),
            },
            Phase::Grading => format!(
                "running the graders, {} of {}, {clock}",
                self.graders.0, self.graders.1
            ),
        }
    }
}

/// A grading's progress, shared between the harness (which writes it) and
/// a screen (which reads it).
#[derive(Debug, Default)]
pub struct Building {
    state: Mutex<(Option<Instant>, Snapshot)>,
}

impl Building {
    /// A new, idle progress to hand to [`super::Options::progress`].
    pub fn shared() -> Arc<Self> {
        Arc::new(Self::default())
    }

    fn update(&self, f: impl FnOnce(&mut Snapshot)) {
        if let Ok(mut s) = self.state.lock() {
            f(&mut s.1);
        }
    }

    /// The progress now.
    pub fn snapshot(&self) -> Snapshot {
        match self.state.lock() {
            Ok(s) => Snapshot {
                elapsed: s.0.map_or(Duration::ZERO, |t| t.elapsed()),
                ..s.1.clone()
            },
            Err(_) => Snapshot::default(),
        }
    }

    /// A grading starts: the clock from now, nothing done.
    pub(crate) fn start(&self) {
        if let Ok(mut s) = self.state.lock() {
            *s = (Some(Instant::now()), Snapshot::default());
        }
        self.phase(Phase::Checking);
    }

    pub(crate) fn phase(&self, phase: Phase) {
        self.update(|s| s.phase = phase);
    }

    /// cargo reported an artifact finished.
    pub(crate) fn artifact(&self) {
        self.update(|s| s.artifacts += 1);
    }

    /// `total` graders are about to run.
    pub(crate) fn graders(&self, total: usize) {
        self.update(|s| {
            s.phase = Phase::Grading;
            s.graders = (0, total);
        });
    }

    /// One grader finished.
    pub(crate) fn grader_done(&self) {
        self.update(|s| s.graders.0 += 1);
    }

    /// Takes one of cargo's progress lines (`Building [==> ] 45/120: a, b`).
    fn cargo_line(&self, line: &str) {
        let Some(rest) = line.trim_start().strip_prefix("Building [") else {
            return;
        };
        let Some((_, after)) = rest.split_once("] ") else {
            return;
        };
        let (count, names) = after.split_once(':').unwrap_or((after, ""));
        let Some((done, total)) = count.trim().split_once('/') else {
            return;
        };
        if let (Ok(done), Ok(total)) = (done.parse(), total.parse()) {
            self.update(|s| {
                s.units = Some((done, total));
                s.compiling = names.trim().to_string();
            });
        }
    }
}

/// The environment that makes cargo write its progress line to a pipe.
pub(crate) const CARGO_PROGRESS_ENV: [(&str, &str); 2] = [
    ("CARGO_TERM_PROGRESS_WHEN", "always"),
    ("CARGO_TERM_PROGRESS_WIDTH", "100"),
];

/// Reads cargo's error stream in a thread: its progress lines go to
/// `progress`, and at most `cap` bytes of the rest are kept (for the error
/// a failed build ends with).
pub(crate) fn drain_cargo(
    from: Option<impl Read + Send + 'static>,
    cap: usize,
    progress: Arc<Building>,
) -> std::thread::JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut kept = Vec::new();
        let Some(mut from) = from else { return kept };
        let mut pending = Vec::new();
        let mut buf = [0u8; 8192];
        while let Ok(n) = from.read(&mut buf) {
            if n == 0 {
                break;
            }
            pending.extend_from_slice(&buf[..n]);
            // Lines end in \n, progress lines in \r.
            while let Some(at) = pending.iter().position(|b| *b == b'\n' || *b == b'\r') {
                let line: Vec<u8> = pending.drain(..=at).collect();
                let text = String::from_utf8_lossy(&line);
                if text.trim_start().starts_with("Building [") {
                    progress.cargo_line(&text);
                } else if !text.trim().is_empty() && kept.len() < cap {
                    let room = cap - kept.len();
                    let line = text.trim_end_matches('\r');
                    let line = if line.ends_with('\n') {
                        line.to_string()
                    } else {
                        format!("{line}\n")
                    };
                    kept.extend_from_slice(&line.as_bytes()[..line.len().min(room)]);
                }
            }
        }
        kept.extend_from_slice(&pending[..pending.len().min(cap.saturating_sub(kept.len()))]);
        kept
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cargo_progress_lines_are_read_and_the_rest_kept() {
        let progress = Building::shared();
        progress.start();
        progress.phase(Phase::Building);
        let stream: &[u8] = b"   Compiling nalgebra v0.35.0\n    Building [==>   ] 45/120: nalgebra, syn      \r    Building [===>  ] 46/120: syn\rerror[E0308]: mismatched types\n";
        let kept = drain_cargo(Some(stream), 1 << 16, Arc::clone(&progress))
            .join()
            .unwrap();
        let kept = String::from_utf8(kept).unwrap();
        assert!(kept.contains("Compiling nalgebra") && kept.contains("error[E0308]"));
        assert!(!kept.contains("Building ["), "{kept}");
        let s = progress.snapshot();
        assert_eq!(s.units, Some((46, 120)));
        assert_eq!(s.compiling, "syn");
        assert!(s.describe().starts_with("compiling 46 of 120 (syn), 0:0"));
        progress.graders(22);
        progress.grader_done();
        assert!(
            progress
                .snapshot()
                .describe()
                .starts_with("running the graders, 1 of 22")
        );
    }
}
