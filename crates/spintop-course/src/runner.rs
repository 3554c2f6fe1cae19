//! A student's runner, running: the program built from the student's crate
//! and `spintop_runner` alone, started in the runner's sandbox, reached
//! through its pipes. The graders call it through [`Remote`]: one line out,
//! one line back, each within the time the grader has left.
//!
//! A runner that dies, hangs, answers what is not an answer or prints
//! without end is **lost**; the grade of the assignment then says why, and
//! the next assignment gets a new runner.

use super::process;
use super::sandbox::{self, Kind, Limits, Spec};
use spintop_grading::{Fault, Remote};
use spintop_runner::{HELLO, MARK, Reply};
use std::cell::{Cell, RefCell};
use std::io::{Read, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

/// The longest line a runner may write (an answer is a few hundred bytes).
const MAX_LINE: usize = 64 * 1024;

/// The most lines a runner may print besides its answers (a `println!` in
/// the student's code) in one assignment.
const MAX_PRINTED: usize = 100_000;

/// How long a runner may take to start.
const START: Duration = Duration::from_secs(10);

/// Why a runner was lost.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Lost {
    /// It gave no answer within the grader's time.
    TimedOut(Duration),
    /// It ended: how (a signal, an exit code) and what that likely was.
    Died(String),
    /// It answered something that is not an answer.
    Garbled(String),
    /// It could not be started (its sandbox, its program).
    NotStarted(String),
}

impl Lost {
    /// The reason, in words a student can act on (no text of the
    /// student's own: a panic message or a print is never repeated).
    pub fn reason(&self) -> String {
        match self {
            Lost::TimedOut(limit) => format!(
                "the grader gave no verdict within {} s and was stopped: a loop that never ends, or an answer far too slow?",
                limit.as_secs().max(1)
            ),
            Lost::Died(how) => format!("your program ended while answering ({how})"),
            Lost::Garbled(what) => format!("your program's answer could not be read ({what})"),
            Lost::NotStarted(why) => format!("the runner could not be started: {why}"),
        }
    }
}

/// One line the runner wrote.
enum Line {
    Text(String),
    TooLong,
}

/// A runner process.
pub(crate) struct Runner {
    child: RefCell<Child>,
    stdin: RefCell<Option<ChildStdin>>,
    lines: Receiver<Line>,
    stderr: RefCell<Option<std::thread::JoinHandle<Vec<u8>>>>,
    deadline: Cell<Instant>,
    limit: Cell<Duration>,
    printed: Cell<usize>,
    lost: RefCell<Option<Lost>>,
    limits: Limits,
    /// Whether it said hello: from then on the student's code may have run,
    /// and nothing on its stderr is the launcher's.
    greeted: Cell<bool>,
}

/// Reads `from` line by line into the channel (a line longer than
/// [`MAX_LINE`] is cut and reported as such).
fn read_lines(mut from: impl Read + Send + 'static) -> Receiver<Line> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut buf = [0u8; 8192];
        let mut line: Vec<u8> = Vec::new();
        let mut too_long = false;
        while let Ok(n) = from.read(&mut buf) {
            if n == 0 {
                break;
            }
            for &b in &buf[..n] {
                if b == b'\n' {
                    let sent = if too_long {
                        tx.send(Line::TooLong)
                    } else {
                        tx.send(Line::Text(String::from_utf8_lossy(&line).into_owned()))
                    };
                    if sent.is_err() {
                        return;
                    }
                    line.clear();
                    too_long = false;
                } else if line.len() < MAX_LINE {
                    line.push(b);
                } else {
                    too_long = true;
                }
            }
        }
    });
    rx
}

impl Runner {
    /// Starts the runner `exe` in its sandbox (through `launcher`, the
    /// spintop binary, when there is one), with `cpu_seconds` of CPU, and
    /// waits for its hello.
    pub(crate) fn start(
        exe: &Path,
        launcher: Option<&Path>,
        cpu_seconds: u64,
    ) -> Result<Self, Lost> {
        let spec = Spec {
            kind: Kind::Run,
            limits: Limits::run(cpu_seconds),
        };
        let mut cmd = sandbox::command(launcher, &spec, exe, &[], &[]);
        cmd.stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        let mut child =
            process::spawn_group(&mut cmd).map_err(|e| Lost::NotStarted(e.to_string()))?;
        if launcher.is_none() {
            sandbox::bound_from_outside(&child, &spec.limits);
        }
        let lines = match child.stdout.take() {
            Some(out) => read_lines(out),
            None => return Err(Lost::NotStarted("no pipe to it".into())),
        };
        let runner = Runner {
            stdin: RefCell::new(child.stdin.take()),
            stderr: RefCell::new(Some(process::drain(child.stderr.take(), 16 * 1024))),
            child: RefCell::new(child),
            lines,
            deadline: Cell::new(Instant::now() + START),
            limit: Cell::new(START),
            printed: Cell::new(0),
            lost: RefCell::new(None),
            limits: spec.limits,
            greeted: Cell::new(false),
        };
        match runner.next_reply() {
            Err(()) => Err(runner
                .lost()
                .unwrap_or(Lost::NotStarted("it said nothing".into()))),
            Ok(_) => Ok(runner),
        }
    }

    /// Gives the next calls until `limit` from now.
    pub(crate) fn allow(&self, limit: Duration) {
        self.limit.set(limit);
        self.deadline.set(Instant::now() + limit);
        self.printed.set(0);
    }

    /// Why the runner was lost, if it was.
    pub(crate) fn lost(&self) -> Option<Lost> {
        self.lost.borrow().clone()
    }

    /// Marks the runner lost for `why` (the first reason stays) and ends it.
    fn lose(&self, why: Lost) {
        if self.lost.borrow().is_none() {
            *self.lost.borrow_mut() = Some(why);
        }
        self.stdin.borrow_mut().take();
        process::kill_group(&mut self.child.borrow_mut());
    }

    /// How the runner ended, in words: its signal or exit code, and what
    /// its last words (never repeated) say it was.
    fn death(&self) -> String {
        let status = {
            let mut child = self.child.borrow_mut();
            let start = Instant::now();
            loop {
                match child.try_wait() {
                    Ok(Some(s)) => break Some(s),
                    Ok(None) if start.elapsed() < Duration::from_secs(2) => {
                        std::thread::sleep(Duration::from_millis(10))
                    }
                    _ => break None,
                }
            }
        };
        let words = self
            .stderr
            .borrow_mut()
            .take()
            .and_then(|h| h.join().ok())
            .map(|b| String::from_utf8_lossy(&b).into_owned())
            .unwrap_or_default();
        // Before the hello only the launcher and the runner's own start ran:
        // a setup failure is read there and nowhere else (a student's code
        // that prints the launcher's words after it is not believed).
        let setup = (!self.greeted.get()).then_some(words.as_str());
        died_how(status, &words, setup, &self.limits)
    }

    /// The most address space the runner has taken, in bytes (Linux's
    /// `VmPeak`; `None` elsewhere or once it ended).
    fn memory_peak(&self) -> Option<u64> {
        let pid = self.child.borrow().id();
        let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
        vm_peak(&status)
    }

    /// The next reply, skipping what the student printed; `Err` when the
    /// runner is lost (then [`Runner::lost`] says why).
    fn next_reply(&self) -> Result<Option<Reply>, ()> {
        loop {
            let left = self
                .deadline
                .get()
                .saturating_duration_since(Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(Line::Text(line)) if line.contains(MARK) => {
                    if line.ends_with(HELLO) && !self.greeted.get() {
                        self.greeted.set(true);
                        return Ok(None);
                    }
                    return match spintop_runner::parse_reply(&line) {
                        Some(Reply::Refused(why)) => {
                            self.lose(Lost::Garbled(format!("it refused a call: {why}")));
                            Err(())
                        }
                        Some(reply) => Ok(Some(reply)),
                        None => {
                            self.lose(Lost::Garbled("a line that is not an answer".into()));
                            Err(())
                        }
                    };
                }
                Ok(_) => {
                    self.printed.set(self.printed.get() + 1);
                    if self.printed.get() > MAX_PRINTED {
                        self.lose(Lost::Garbled(format!(
                            "it printed more than {MAX_PRINTED} lines: remove the println!"
                        )));
                        return Err(());
                    }
                }
                Err(RecvTimeoutError::Timeout) => {
                    // A program that took (nearly) all the memory it may
                    // is reported as such, not as merely slow.
                    let why = match self.memory_peak() {
                        Some(peak) if peak >= self.limits.memory / 10 * 9 => Lost::Died(format!(
                            "stopped at its time limit, its memory at the {} MiB it may take: an allocation that keeps growing?",
                            self.limits.memory >> 20
                        )),
                        _ => Lost::TimedOut(self.limit.get()),
                    };
                    self.lose(why);
                    return Err(());
                }
                Err(RecvTimeoutError::Disconnected) => {
                    let how = self.death();
                    self.lose(Lost::Died(how));
                    return Err(());
                }
            }
        }
    }
}

impl Drop for Runner {
    fn drop(&mut self) {
        self.stdin.borrow_mut().take();
        process::kill_group(&mut self.child.borrow_mut());
    }
}

/// `VmPeak` of a `/proc/PID/status` text, in bytes.
fn vm_peak(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmPeak:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// How a runner ended, in words.
/// `setup` is the launcher's stderr when the student's code never ran (no
/// hello), the only place a setup failure is looked for.
fn died_how(
    status: Option<std::process::ExitStatus>,
    last_words: &str,
    setup: Option<&str>,
    limits: &Limits,
) -> String {
    let signal = {
        #[cfg(unix)]
        {
            use std::os::unix::process::ExitStatusExt;
            status.and_then(|s| s.signal())
        }
        #[cfg(not(unix))]
        {
            None::<i32>
        }
    };
    let likely = if last_words.contains("overflowed its stack") {
        "a recursion without end: a stack overflow".to_string()
    } else if last_words.contains("memory allocation of") {
        format!(
            "more memory than the {} MiB it may take",
            limits.memory >> 20
        )
    } else if signal == Some(24) {
        format!("more than its {} s of CPU time", limits.cpu_seconds)
    } else if let Some(line) = setup
        .filter(|_| status.and_then(|s| s.code()) == Some(sandbox::SETUP_FAILED))
        .and_then(|w| w.lines().find(|l| l.contains(sandbox::SETUP_MARK)))
    {
        // The launcher's own words (the student's program never started).
        line.trim().to_string()
    } else {
        "a recursion without end, more memory than it may take, or an abort?".to_string()
    };
    let how = match (signal, status.and_then(|s| s.code())) {
        (Some(sig), _) => format!("killed by signal {sig}"),
        (None, Some(code)) => format!("exit code {code}"),
        _ => "it ended".to_string(),
    };
    format!("{how}: {likely}")
}

impl Remote for Runner {
    fn call(&self, name: &str, args: &[f64]) -> Result<Vec<f64>, Fault> {
        if self.lost.borrow().is_some() {
            return Err(Fault::Lost);
        }
        let line = spintop_runner::request(name, args) + "\n";
        let sent = match self.stdin.borrow_mut().as_mut() {
            Some(pipe) => pipe.write_all(line.as_bytes()).and_then(|()| pipe.flush()),
            None => Err(std::io::Error::other("closed")),
        };
        if sent.is_err() {
            let how = self.death();
            self.lose(Lost::Died(how));
            return Err(Fault::Lost);
        }
        match self.next_reply() {
            Ok(Some(Reply::Answer(numbers))) => Ok(numbers),
            Ok(Some(Reply::Panicked(message))) => Err(Fault::Panicked(message)),
            Ok(_) => {
                self.lose(Lost::Garbled("a second hello".into()));
                Err(Fault::Lost)
            }
            Err(()) => Err(Fault::Lost),
        }
    }

    fn garbled(&self, name: &str) {
        self.lose(Lost::Garbled(format!(
            "its answer to {name} has not the numbers of the function's value"
        )));
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;
    use std::os::unix::process::ExitStatusExt;

    /// A student's code that prints the launcher's words and exits with its
    /// code after the hello is not believed: its text never becomes a
    /// reason. Before the hello (the launcher's own failure), it is.
    #[test]
    fn a_setup_failure_is_read_only_before_the_student_code_ran() {
        let exit_125 = Some(std::process::ExitStatus::from_raw(
            sandbox::SETUP_FAILED << 8,
        ));
        let words = format!("spintop course: {}: =HYPERLINK(\"x\")", sandbox::SETUP_MARK);
        let limits = Limits::run(1);
        let after = died_how(exit_125, &words, None, &limits);
        assert!(!after.contains("HYPERLINK"), "{after}");
        assert!(!after.contains(sandbox::SETUP_MARK), "{after}");
        let before = died_how(exit_125, &words, Some(&words), &limits);
        assert!(before.contains(sandbox::SETUP_MARK), "{before}");
    }

    #[test]
    fn the_memory_peak_is_read_from_proc_status() {
        let status = "Name:\trunner\nVmPeak:\t  1048000 kB\nVmSize:\t 4000 kB\n";
        assert_eq!(vm_peak(status), Some(1_048_000 * 1024));
        assert_eq!(vm_peak("Name: x\n"), None);
        // This process's own, which has at least its code mapped.
        let own = std::fs::read_to_string("/proc/self/status").unwrap();
        assert!(vm_peak(&own).is_some_and(|b| b > 1 << 20));
    }
}
