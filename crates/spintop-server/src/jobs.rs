//! The one ▶ run that may be going on: starting it, saying how it goes,
//! and what is busy when another is asked for.

use super::run::{Outcome, Stage};
use super::{Inner, Reply, WarmState, json, lock, reason};
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Instant;

/// Where the one ▶ run that may be going on is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Phase {
    /// Waiting for the background build (or another tree) to end.
    Waiting,
    /// Cargo compiles it.
    Compiling,
    /// The program runs.
    Running,
}

/// The state of the one ▶ run that may be going on, and the last outcome.
#[derive(Debug)]
pub(super) struct Job {
    running: bool,
    phase: Phase,
    since: Instant,
    progress: String,
    last: Option<Outcome>,
}

impl Default for Job {
    fn default() -> Self {
        Self {
            running: false,
            phase: Phase::Waiting,
            since: Instant::now(),
            progress: String::new(),
            last: None,
        }
    }
}

impl Inner {
    /// What is busy, for how long, and its limit: the 429 answer.
    pub(super) fn busy(&self, job: &Job) -> Reply {
        let limits = self.config.runner.limits;
        let secs = job.since.elapsed().as_secs();
        let what = match job.phase {
            Phase::Waiting => {
                format!("is waiting for the background build of spintop ({secs} s so far)")
            }
            Phase::Compiling => {
                let limit = if self.shared.warm.load(Ordering::SeqCst) {
                    limits.compile_warm
                } else {
                    limits.compile
                };
                format!(
                    "is compiling ({secs} s so far; the compile limit is {} s)",
                    limit.as_secs()
                )
            }
            Phase::Running => format!(
                "is running ({secs} s so far; the time limit is {} s)",
                limits.run.as_secs()
            ),
        };
        json(
            429,
            serde_json::json!({
                "result": format!("busy: another snippet {what}; press ▶ again when it has finished"),
                "error": "busy",
            }),
        )
    }

    /// `/evaluate.json`: start a run, answer within [`super::Limits::answer_within`].
    pub(super) fn evaluate(self: &Arc<Self>, body: &[u8]) -> Reply {
        #[derive(serde::Deserialize)]
        struct Params {
            code: String,
            #[serde(default)]
            edition: Option<String>,
        }
        let params: Params = match serde_json::from_slice(body) {
            Ok(p) => p,
            Err(e) => return reason(400, &format!("malformed request: {e}")),
        };
        {
            let mut job = lock(&self.job);
            if job.running {
                return self.busy(&job);
            }
            *job = Job {
                running: true,
                progress: "waiting for its turn".into(),
                ..Job::default()
            };
        }
        let inner = Arc::clone(self);
        let edition = params.edition.unwrap_or_else(|| "2024".into());
        let answer_within = self.config.runner.limits.answer_within;
        let (done_tx, done_rx) = std::sync::mpsc::channel();
        // The run on a thread of its own: this connection answers within
        // `answer_within` (202 and "pending" if the run goes on), and other
        // connections meanwhile are told "busy", not queued.
        let spawned = std::thread::Builder::new().spawn(move || {
            let outcome =
                inner
                    .config
                    .runner
                    .run(&params.code, &edition, &inner.shared, &mut |stage| {
                        let mut job = lock(&inner.job);
                        match stage {
                            Stage::Compiling => {
                                job.phase = Phase::Compiling;
                                job.since = Instant::now();
                                job.progress = "compiling".into();
                            }
                            Stage::Line(line) => {
                                let secs = job.since.elapsed().as_secs();
                                job.progress = format!("{line} ({secs} s)");
                            }
                            Stage::Running => {
                                job.phase = Phase::Running;
                                job.since = Instant::now();
                                job.progress = "running".into();
                            }
                        }
                    });
            let mut job = lock(&inner.job);
            job.running = false;
            job.last = Some(outcome.clone());
            drop(job);
            let _ = done_tx.send(outcome);
        });
        if let Err(e) = spawned {
            lock(&self.job).running = false;
            return unavailable(&e);
        }
        match done_rx.recv_timeout(answer_within) {
            Ok(outcome) => json(200, outcome_json(&outcome)),
            Err(_) => {
                // What holds it up: only a build of spintop itself takes
                // minutes.
                let phase = lock(&self.job).phase;
                let result = match phase {
                    Phase::Running => format!(
                        "running… (its time limit is {} s)",
                        self.config.runner.limits.run.as_secs()
                    ),
                    Phase::Compiling if self.shared.warm.load(Ordering::SeqCst) => {
                        "compiling…".to_string()
                    }
                    Phase::Waiting | Phase::Compiling => "compiling… (the first run builds spintop for the book: a minute or two on a small machine; later runs take a second or two)".to_string(),
                };
                json(
                    202,
                    serde_json::json!({ "result": result, "pending": true }),
                )
            }
        }
    }

    /// `/evaluate/status`: the run's progress, or its outcome once done.
    pub(super) fn status(&self) -> Reply {
        let job = lock(&self.job);
        let value = match (&job.running, &job.last) {
            (true, _) => {
                let progress = match (job.phase, lock(&self.warm).clone()) {
                    (Phase::Waiting, WarmState::Building { started, progress }) => format!(
                        "waiting for the background build of spintop ({} s): {progress}",
                        started.elapsed().as_secs()
                    ),
                    _ => job.progress.clone(),
                };
                serde_json::json!({ "done": false, "progress": progress })
            }
            (false, Some(outcome)) => {
                let mut v = outcome_json(outcome);
                v["done"] = serde_json::Value::Bool(true);
                v
            }
            (false, None) => serde_json::json!({ "done": true, "result": "" }),
        };
        drop(job);
        json(200, value)
    }
}

/// 503: the system refused the server a thread (`e`), as under a fork bomb
/// that took the reader's process limit; the server goes on serving.
pub(super) fn unavailable(e: &std::io::Error) -> Reply {
    reason(
        503,
        &format!(
            "the server cannot start a thread now ({e}): the reader's process limit, or the machine's, is reached; try again in a moment"
        ),
    )
}

/// The playground's answer shape: `result` is what the page shows.
fn outcome_json(outcome: &Outcome) -> serde_json::Value {
    serde_json::json!({
        "result": outcome.shown(),
        "error": outcome.error_kind(),
        "success": outcome.success(),
    })
}
