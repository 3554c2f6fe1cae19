//! Watch mode: the course graded again on every save, in the background,
//! re-running only the graders of the assignments in the saved file.

use super::Status;
use super::harness::{self, Options};
use super::{COURSE, State};
use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The modification time of each of the student's files (`src/**/*.rs` of
/// the lessons crate in `dir`), by path under `src/`.
pub fn sources_stamps(dir: &Path) -> std::collections::BTreeMap<String, std::time::SystemTime> {
    let src = dir.join("src");
    super::export::rust_files(&src, &[])
        .into_iter()
        .filter_map(|p| {
            let time = std::fs::metadata(&p).ok()?.modified().ok()?;
            let rel = p.strip_prefix(&src).ok()?;
            Some((rel.to_string_lossy().into_owned(), time))
        })
        .collect()
}

/// The test binaries whose graders can change when the files `changed` (paths
/// under `src/`) do: those of the assignments in them, or every one (an empty
/// list) when another file changed (`lib.rs`, a helper).
pub fn binaries_for(changed: &[String]) -> Vec<&'static str> {
    let mut binaries = Vec::new();
    for file in changed {
        let mut owners = COURSE
            .iter()
            .filter(|a| a.file.strip_prefix("lessons/src/") == Some(file.as_str()))
            .map(|a| a.binary)
            .peekable();
        if owners.peek().is_none() {
            return Vec::new();
        }
        binaries.extend(owners);
    }
    binaries.sort_unstable();
    binaries.dedup();
    binaries
}

/// What a [`Watch`] reports.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Report {
    /// A grading run started (a file was saved, or the watch began).
    Grading,
    /// A grading run ended.
    Graded(Status),
    /// Cargo could not be run.
    Failed(String),
}

/// Grades the course in the background, once at the start and again each
/// time a file under `src/` of the lessons crate is saved (polled every
/// 200 ms); a save re-grades only the graders of the assignments in the saved
/// file (see [`binaries_for`]). The grading runs stop with the watch:
/// dropping it ends the thread and kills a cargo or a grader still running.
pub struct Watch {
    reports: std::sync::mpsc::Receiver<Report>,
    stop: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Watch {
    /// Starts watching the lessons crate in `dir`; `options` say how to
    /// grade (their binaries and stop flag are the watch's own).
    pub fn with_options(dir: &Path, options: Options) -> Self {
        let (tx, reports) = std::sync::mpsc::channel();
        let stop = Arc::new(AtomicBool::new(false));
        let stop_thread = Arc::clone(&stop);
        let dir = dir.to_path_buf();
        let thread = std::thread::spawn(move || {
            let mut graded: Option<(std::collections::BTreeMap<_, _>, Status)> = None;
            while !stop_thread.load(Ordering::Relaxed) {
                let stamps = sources_stamps(&dir);
                let binaries = match &graded {
                    None => Some(Vec::new()),
                    // After a compile error or a failed run, everything again.
                    Some((old, status)) if *old != stamps && !status.complete() => Some(Vec::new()),
                    Some((old, _)) if *old != stamps => {
                        let changed: Vec<String> = stamps
                            .iter()
                            .filter(|(f, t)| old.get(*f) != Some(t))
                            .map(|(f, _)| f.clone())
                            .chain(old.keys().filter(|f| !stamps.contains_key(*f)).cloned())
                            .collect();
                        Some(binaries_for(&changed))
                    }
                    Some(_) => None,
                };
                if let Some(binaries) = binaries {
                    if tx.send(Report::Grading).is_err() {
                        return;
                    }
                    let opts = Options {
                        binaries: binaries.clone(),
                        stop: Some(Arc::clone(&stop_thread)),
                        ..options.clone()
                    };
                    let result = harness::grade(&dir, &opts);
                    if stop_thread.load(Ordering::Relaxed) {
                        return;
                    }
                    let report = match result {
                        Ok(fresh) => {
                            let status = match &graded {
                                Some((_, old)) => old.merged(fresh, &binaries),
                                None => fresh,
                            };
                            graded = Some((stamps, status.clone()));
                            Report::Graded(status)
                        }
                        Err(e) => {
                            // Try again on the next save, from scratch.
                            graded = Some((stamps, Status::new(0, |_| State::Unknown)));
                            Report::Failed(e.to_string())
                        }
                    };
                    if tx.send(report).is_err() {
                        return;
                    }
                }
                std::thread::sleep(std::time::Duration::from_millis(200));
            }
        });
        Watch {
            reports,
            stop,
            thread: Some(thread),
        }
    }

    /// Starts watching the lessons crate in `dir`, graded as `spintop course`
    /// grades it.
    pub fn start(dir: &Path) -> Self {
        let options = Options {
            course_arg: super::course_arg_for(dir),
            ..Options::default()
        };
        Self::with_options(dir, options)
    }

    /// The reports since the last call, oldest first.
    pub fn poll(&self) -> Vec<Report> {
        self.reports.try_iter().collect()
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_save_regrades_only_the_graders_of_the_saved_file() {
        assert_eq!(binaries_for(&["ch2.rs".into()]), vec!["ch2"]);
        // numerics.rs holds three assignments of one grader binary.
        assert_eq!(binaries_for(&["numerics.rs".into()]), vec!["numerics"]);
        assert_eq!(
            binaries_for(&["ch4.rs".into(), "ch2.rs".into()]),
            vec!["ch2", "ch4"]
        );
        // lib.rs (or any file without an assignment) can change every grader.
        assert!(binaries_for(&["lib.rs".into()]).is_empty());
        assert!(binaries_for(&["ch2.rs".into(), "helpers.rs".into()]).is_empty());
    }

    #[test]
    fn a_partial_regrade_keeps_the_other_verdicts() {
        let passing = |names: &'static [&'static str]| {
            move |a: &crate::Assignment| {
                if names.contains(&a.function) {
                    State::Passing
                } else {
                    State::NotStarted
                }
            }
        };
        let before = Status::new(1, passing(&["larmor_rate", "torque_rate"]));
        assert_eq!(before.passing(), 2);
        // A run of the ch4 graders alone: one passes, ch2's are not run.
        let fresh = Status::new(2, |a| match (a.binary, a.function) {
            ("ch4", "precession_tilt") => State::Passing,
            ("ch4", _) => State::NotStarted,
            _ => State::Unknown,
        });
        let after = before.merged(fresh.clone(), &["ch4"]);
        assert_eq!(after.passing(), 3);
        assert_eq!(after.seed, 2);
        // Merging it as if every grader had run forgets ch2's verdicts.
        assert_eq!(before.merged(fresh, &[]).passing(), 1);
        // A compile error concerns every assignment.
        let mut broken = Status::new(3, |a| {
            if a.binary == "ch4" {
                State::DoesNotCompile("src/ch4.rs:3: mismatched types".into())
            } else {
                State::Unknown
            }
        });
        broken.compile_error = Some(crate::Located {
            file: "src/ch4.rs".into(),
            line: 3,
            message: "mismatched types".into(),
        });
        let merged = before.merged(broken, &["ch4"]);
        assert!(!merged.complete());
        assert_eq!(merged.passing(), 0);
        assert_eq!(merged.next_place().as_deref(), Some("src/ch4.rs:3"));
    }
}
