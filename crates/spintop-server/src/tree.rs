//! Process trees, as the server sees them: one at a time, each under a
//! supervisor (`spintop book --supervise …`, [`super::supervise`]) that
//! bounds it and ends it as a unit ([`super::unit`]).
//!
//! The server waits for the supervisor's exit before it starts another tree,
//! so "one run at a time" is one process tree at a time. It tells a
//! supervisor to end its tree by closing its control pipe (and SIGCONT, in
//! case it was stopped),
//! at the tree's time limit (the supervisor keeps the same limit on its own
//! clock, for a server that is stopped) or when the server stops. The
//! supervisor exits only once its tree is gone, unless it is itself killed:
//! by the server if it has not ended [`GRACE`] after being told to stop
//! (it may be stopped: a snippet outside a PID namespace can signal it;
//! or slow, on a loaded machine), what is below it first,
//! by the kernel's out-of-memory killer, or by the tree itself. Then the
//! server kills what is left in the tree's cgroup, session and process
//! group ([`sweep`]); it is a child subreaper too ([`become_subreaper`]),
//! so those orphans come to it and not to init. One that had left the
//! session (`setsid`) and the cgroup is reached only by
//! [`Slot::sweep_strays`], which kills every process below the server but
//! the running tree: `spintop book` calls it whenever a child ends and at
//! stop. A library user with children of its own (a test) cannot, and has
//! only the sweep. In a PID namespace none of this is needed: the
//! supervisor's death ends the namespace.

use super::bounds::Bounds;
use super::procs::{Proc, kill_tree, processes, tree};
use super::supervise::{Spec, launcher_args, subreaper};
use super::unit::{Containment, cgroup_of, remove_cgroup};
use rustix::process::{Pid, Signal, WaitOptions};
use std::ffi::OsStr;
use std::os::unix::process::ExitStatusExt;
use std::process::{Child, ChildStderr, ChildStdin, ChildStdout, Command, ExitStatus, Stdio};
use std::sync::{Mutex, MutexGuard, TryLockError};
use std::time::{Duration, Instant};

/// How long a supervisor has, once told to stop, to kill its tree and exit
/// before the server kills its process group itself.
const GRACE: Duration = Duration::from_secs(2);

/// How long a stop waits for the tree to be gone: the [`GRACE`], the
/// server's own kill, its sweep (at most 5 s) and the last output (1 s).
pub(crate) const STOP_WAIT: Duration = Duration::from_secs(10);

/// The one process tree a server runs at a time, and the means to stop it.
#[derive(Debug, Default)]
pub struct Slot {
    turn: Mutex<()>,
    control: Mutex<Control>,
}

/// The running tree's control pipe, and whether the server is stopping.
#[derive(Debug, Default)]
struct Control {
    pipe: Option<ChildStdin>,
    /// The running tree's supervisor, a child of this process.
    supervisor: Option<i32>,
    closed: bool,
}

/// A tree started by [`Slot::start`].
#[derive(Debug)]
pub struct Started {
    supervisor: Child,
}

/// How a tree ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ended {
    /// The program ended; the supervisor's status mirrors its status.
    Exited(ExitStatus),
    /// It outlived its time limit and was killed, whole.
    TimedOut,
    /// The server is stopping: it was killed, whole.
    Stopped,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Slot {
    /// Waits until no other tree runs: hold the guard while starting and
    /// waiting for one.
    pub fn turn(&self) -> MutexGuard<'_, ()> {
        lock(&self.turn)
    }

    /// Whether the server is stopping (then no tree starts).
    pub fn closed(&self) -> bool {
        lock(&self.control).closed
    }

    /// Starts `program args…` under a supervisor with `bounds`, ended as
    /// `unit` says and at `limit` by the supervisor's own clock: `command`
    /// runs the spintop binary (the supervisor) in the folder and with the
    /// environment the program gets, its arguments not yet given. Call
    /// [`Started::wait`] on the thread that called this: the supervisor
    /// dies with the thread that started it (`PR_SET_PDEATHSIG`).
    pub fn start(
        &self,
        mut command: Command,
        (bounds, limit, unit): (Bounds, Duration, Containment),
        program: &OsStr,
        args: &[&OsStr],
    ) -> std::io::Result<Started> {
        let mut control = lock(&self.control);
        if control.closed {
            return Err(std::io::Error::other("the server is stopping"));
        }
        let spec = Spec {
            bounds,
            limit,
            parent: std::process::id(),
            unit,
        };
        let mut supervisor = command
            .args(launcher_args(spec, program, args))
            .stdin(Stdio::piped())
            .spawn()?;
        control.pipe = supervisor.stdin.take();
        control.supervisor = i32::try_from(supervisor.id()).ok();
        Ok(Started { supervisor })
    }

    /// Tells the running tree's supervisor to kill the tree: closes its
    /// control pipe, and wakes it (SIGCONT) if another process of the
    /// reader stopped it. (A snippet may hold the pipe open only as root:
    /// the supervisor is not dumpable. Then the server's own kill, after
    /// [`GRACE`], ends the tree.)
    fn stop(&self) {
        let mut control = lock(&self.control);
        control.pipe = None;
        if let Some(pid) = control.supervisor.and_then(Pid::from_raw) {
            let _ = rustix::process::kill_process(pid, Signal::CONT);
        }
    }

    /// For a process that runs nothing but this slot's trees (`spintop
    /// book`): kills every process below this one that is not the running
    /// tree, and reaps those of them that have ended; returns how many
    /// living ones it found (0: nothing but the running tree is left).
    ///
    /// A tree that kills its own supervisor (any process of the reader
    /// may) leaves its processes to this process, a child subreaper, and
    /// [`sweep`] finds those only in the supervisor's session and group:
    /// one that had started a session of its own is left running, and when
    /// it ends, unreaped. Not for a process with children of its own
    /// besides the trees (such as a test harness): it would kill and reap
    /// them too.
    pub fn sweep_strays(&self) -> usize {
        // Held throughout, so that no supervisor starts unseen meanwhile.
        let control = lock(&self.control);
        let me = rustix::process::getpid().as_raw_nonzero().get();
        let table = processes();
        let mut living = 0;
        for stray in table
            .iter()
            .filter(|p| p.ppid == me && Some(p.pid) != control.supervisor)
        {
            let Some(pid) = Pid::from_raw(stray.pid) else {
                continue;
            };
            if stray.dead {
                let _ = rustix::process::waitpid(Some(pid), WaitOptions::NOHANG);
                continue;
            }
            living += 1;
            let _ = rustix::process::kill_process(pid, Signal::KILL);
            for below in tree(&table, stray.pid)
                .into_iter()
                .filter_map(Pid::from_raw)
            {
                let _ = rustix::process::kill_process(below, Signal::KILL);
            }
        }
        living
    }

    /// Stops the running tree and refuses new ones; returns once the tree
    /// is gone (its waiter has seen it end and swept it): true, or false if
    /// that took longer than [`STOP_WAIT`].
    pub fn close(&self) -> bool {
        lock(&self.control).closed = true;
        self.stop();
        let start = Instant::now();
        while start.elapsed() < STOP_WAIT {
            // Free, or poisoned by a panic: nobody holds a tree.
            if !matches!(self.turn.try_lock(), Err(TryLockError::WouldBlock)) {
                return true;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        false
    }
}

impl Started {
    /// The tree's standard output (the program's and its children's), if
    /// the supervisor's command piped it.
    pub fn stdout(&mut self) -> Option<ChildStdout> {
        self.supervisor.stdout.take()
    }

    /// The tree's standard error, if piped.
    pub fn stderr(&mut self) -> Option<ChildStderr> {
        self.supervisor.stderr.take()
    }

    /// Waits for the tree to end, `tick` called every 10 ms meanwhile. At
    /// `limit`, or when the slot is closed, it is stopped; if its supervisor
    /// has not ended [`GRACE`] later, its process group is killed. Returns
    /// once the supervisor has ended; what it may have left is swept.
    pub fn wait(mut self, slot: &Slot, limit: Duration, mut tick: impl FnMut()) -> Ended {
        let start = Instant::now();
        let leader = self.supervisor.id();
        let mut stop_sent: Option<(Instant, Ended)> = None;
        let mut group_killed = false;
        loop {
            tick();
            let status = self.supervisor.try_wait();
            if !matches!(status, Ok(None)) {
                {
                    let mut control = lock(&slot.control);
                    control.pipe = None;
                    control.supervisor = None;
                }
                // A supervisor that ended by a signal (ours or another's)
                // may have left its tree behind.
                let clean = matches!(status, Ok(Some(s)) if s.signal().is_none());
                if !clean {
                    sweep(leader);
                }
                return match (stop_sent, status) {
                    (Some((_, why)), _) => why,
                    // The supervisor's own clock ended it.
                    (None, _) if start.elapsed() >= limit => Ended::TimedOut,
                    (None, Ok(Some(s))) => Ended::Exited(s),
                    (None, _) => Ended::Stopped,
                };
            }
            if stop_sent.is_none() {
                let why = if slot.closed() {
                    Some(Ended::Stopped)
                } else if start.elapsed() >= limit {
                    Some(Ended::TimedOut)
                } else {
                    None
                };
                if let Some(why) = why {
                    slot.stop();
                    stop_sent = Some((Instant::now(), why));
                }
            }
            if let Some((sent, _)) = stop_sent
                && !group_killed
                && sent.elapsed() > GRACE
            {
                if let Some(group) = i32::try_from(leader).ok().and_then(Pid::from_raw) {
                    // What is below it first (a slow supervisor, on a
                    // loaded machine, may be killing it still): killed
                    // after it, a daemon in a session of its own would
                    // land on this process, out of the sweep's reach.
                    kill_tree(group);
                    let _ = rustix::process::kill_process_group(group, Signal::KILL);
                }
                group_killed = true;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    }
}

/// Makes this process a child subreaper: orphans below it come to it, not
/// to init.
pub fn become_subreaper() {
    let _ = subreaper(rustix::process::getpid());
}

/// After a supervisor `leader` has ended (or was killed): kills whatever is
/// left in its cgroup, session and process group, and reaps those of them
/// this process adopted (as a subreaper), never a child it started itself.
pub fn sweep(leader: u32) {
    if let Some(cgroup) = cgroup_of(leader) {
        remove_cgroup(&cgroup);
    }
    let Ok(leader) = i32::try_from(leader) else {
        return;
    };
    if let Some(group) = Pid::from_raw(leader) {
        let _ = rustix::process::kill_process_group(group, Signal::KILL);
    }
    let me = rustix::process::getpid().as_raw_nonzero().get();
    let start = Instant::now();
    loop {
        let table = processes();
        let left: Vec<&Proc> = table
            .iter()
            .filter(|p| p.pid != leader && (p.sid == leader || p.pgid == leader))
            .collect();
        for p in &left {
            if let Some(pid) = Pid::from_raw(p.pid) {
                if p.dead && p.ppid == me {
                    let _ = rustix::process::waitpid(Some(pid), WaitOptions::NOHANG);
                } else if !p.dead {
                    let _ = rustix::process::kill_process(pid, Signal::KILL);
                }
            }
        }
        if left.iter().all(|p| p.dead && p.ppid != me) || start.elapsed() > Duration::from_secs(5) {
            return;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}
