//! Child processes within time limits: a process group of their own, a
//! wait that kills the whole group at its limit, output drained with a cap;
//! and work shared out over a few threads.

use std::io::Read;
use std::process::{Child, Command, ExitStatus};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// One grading's stop flag and deadline.
#[derive(Debug, Clone, Default)]
pub(crate) struct Ctx {
    /// Set to stop: the running process is killed.
    pub(crate) stop: Option<Arc<AtomicBool>>,
    /// When the whole grading must be done.
    pub(crate) deadline: Option<Instant>,
}

impl Ctx {
    pub(crate) fn stopped(&self) -> bool {
        self.stop
            .as_ref()
            .is_some_and(|s| s.load(Ordering::Relaxed))
    }

    /// The time left before the deadline (a long time without one).
    pub(crate) fn left(&self) -> Duration {
        self.deadline.map_or(Duration::from_secs(24 * 3600), |d| {
            d.saturating_duration_since(Instant::now())
        })
    }
}

/// `work(0)`, …, `work(count − 1)` on at most `jobs` threads at once, each
/// taking the next index when it is free; each result in its place (`None`
/// if its thread died).
pub(crate) fn in_parallel<T: Send>(
    count: usize,
    jobs: usize,
    work: impl Fn(usize) -> T + Sync,
) -> Vec<Option<T>> {
    let slots: Vec<std::sync::Mutex<Option<T>>> =
        (0..count).map(|_| std::sync::Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, count.max(1)) {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= count {
                        break;
                    }
                    let result = work(i);
                    if let Ok(mut slot) = slots[i].lock() {
                        *slot = Some(result);
                    }
                }
            });
        }
    });
    slots
        .into_iter()
        .map(|s| s.into_inner().ok().flatten())
        .collect()
}

/// Starts `cmd` in a process group of its own (so that a time limit ends it
/// and every process it started).
pub(crate) fn spawn_group(cmd: &mut Command) -> std::io::Result<Child> {
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        cmd.process_group(0);
    }
    cmd.spawn()
}

/// Ends `child` and its process group.
pub(crate) fn kill_group(child: &mut Child) {
    #[cfg(unix)]
    {
        let pid = rustix::process::Pid::from_child(child);
        let _ = rustix::process::kill_process_group(pid, rustix::process::Signal::KILL);
    }
    let _ = child.kill();
    let _ = child.wait();
}

/// How a watched wait ended.
#[derive(Debug)]
pub(crate) enum Waited {
    /// The process ended by itself.
    Exited(ExitStatus),
    /// It was killed: at its time limit or a stop (`None`), or because the
    /// watch said why (`Some`).
    Killed(Option<String>),
}

/// Waits for `child` until `limit`, or until the grading is stopped;
/// `None` when it had to be killed.
pub(crate) fn wait_within(child: &mut Child, limit: Duration, ctx: &Ctx) -> Option<ExitStatus> {
    match wait_watched(child, limit, ctx, || None) {
        Waited::Exited(status) => Some(status),
        Waited::Killed(_) => None,
    }
}

/// [`wait_within`], asking `watch` every half second whether the process
/// must be stopped (and why): a build whose files grow past a bound.
pub(crate) fn wait_watched(
    child: &mut Child,
    limit: Duration,
    ctx: &Ctx,
    mut watch: impl FnMut() -> Option<String>,
) -> Waited {
    let start = Instant::now();
    let mut looked = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return Waited::Exited(status),
            Ok(None) if start.elapsed() < limit && !ctx.stopped() => {
                if looked.elapsed() >= Duration::from_millis(500) {
                    looked = Instant::now();
                    if let Some(why) = watch() {
                        kill_group(child);
                        return Waited::Killed(Some(why));
                    }
                }
                std::thread::sleep(Duration::from_millis(10))
            }
            _ => {
                kill_group(child);
                return Waited::Killed(None);
            }
        }
    }
}

/// Reads at most `cap` bytes of `from` in a thread, dropping the rest.
pub(crate) fn drain(
    from: Option<impl Read + Send + 'static>,
    cap: usize,
) -> std::thread::JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut kept = Vec::new();
        let Some(mut from) = from else { return kept };
        let mut buf = [0u8; 8192];
        while let Ok(n) = from.read(&mut buf) {
            if n == 0 {
                break;
            }
            let room = cap.saturating_sub(kept.len());
            kept.extend_from_slice(&buf[..n.min(room)]);
        }
        kept
    })
}
