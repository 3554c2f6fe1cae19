//! Process trees: everything a snippet (or the cargo build of one) starts is
//! bounded, and dies whole.
//!
//! Each tree runs under a supervisor, a second copy of the spintop binary
//! (`spintop book --supervise …`, see [`launcher_args`]), which
//!
//! 1. starts a session of its own (`setsid`): the tree has its own process
//!    group and session, and the terminal's Ctrl-C never reaches it directly;
//! 2. makes itself a child subreaper (`PR_SET_CHILD_SUBREAPER`): a process
//!    whose parent dies, even one that started a session of its own
//!    (`setsid`, a double fork), is adopted by the supervisor instead of by
//!    init, so nothing the program starts can leave the tree;
//! 3. sets the resource limits ([`Bounds`]: address space, CPU seconds, file
//!    size, no core dumps), which the program inherits;
//! 4. runs the program and reaps every process of the tree; when the program
//!    ends, when the server closes the supervisor's standard input (its
//!    control pipe: at a time limit, before a new run, when the server
//!    stops) or when the server dies (the pipe closes with it), it kills
//!    every remaining process of the tree, reaps them all and exits.
//!
//! The server waits for the supervisor's exit before it starts another tree,
//! so "one run at a time" is one process tree at a time. The supervisor
//! exits only once every process of its tree is gone, unless it is itself
//! killed: by the server if it has not ended 2 s after being told to stop,
//! by the kernel's out-of-memory killer, or by the tree itself (it runs as
//! the reader, and so may signal its supervisor). Then the server kills
//! what is left in the tree's session and process group ([`sweep`]); it is
//! a child subreaper too ([`become_subreaper`]), so those orphans come to it
//! and not to init. One that had left the session (`setsid`) before is
//! reached only by [`Slot::sweep_strays`], which kills every process below
//! the server but the running tree: `spintop book` calls it whenever a
//! child ends and at stop. A library user with children of its own (a
//! test) cannot, and has only the session sweep.
//!
//! NOTE: why a supervisor process and not `pre_exec`: setting limits or a
//! session between fork and exec needs `CommandExt::pre_exec`, which is
//! `unsafe`, and this crate forbids `unsafe`. A re-executed copy of the
//! binary does the same with safe calls (rustix's `setsid`, `setrlimit`,
//! `set_child_subreaper`) before it starts the program, and, being a process
//! of the tree that outlives the program, can reap and kill what the program
//! leaves behind. It costs one exec of the spintop binary per tree, a few
//! milliseconds.

use rustix::process::{Pid, Resource, Rlimit, Signal, WaitOptions};
use std::ffi::{OsStr, OsString};
use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::process::{Child, ChildStderr, ChildStdin, ChildStdout, Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, TryLockError};
use std::time::{Duration, Instant};

/// How long a supervisor has, once told to stop, to kill its tree and exit
/// before the server kills its process group itself.
const GRACE: Duration = Duration::from_secs(2);

/// The resource limits of a tree's processes (each process has its own
/// counters; children inherit the limits). Core dumps are always off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Bounds {
    /// Address space (virtual memory) of each process, in bytes.
    pub address_space: Option<u64>,
    /// CPU time of each process, in whole seconds (then SIGXCPU).
    pub cpu_seconds: Option<u64>,
    /// The largest file a process may write, in bytes (then SIGXFSZ).
    pub file_size: Option<u64>,
    /// How many processes and threads the tree may start beyond those its
    /// user has when it starts (RLIMIT_NPROC, which counts every task of
    /// the user; the kernel does not hold root to it).
    pub processes: Option<u64>,
}

impl Bounds {
    /// The bounds as one argument: `as=N,cpu=N,fsize=N` (those set), or
    /// `none`.
    fn to_arg(self) -> String {
        let parts: Vec<String> = [
            ("as", self.address_space),
            ("cpu", self.cpu_seconds),
            ("fsize", self.file_size),
            ("nproc", self.processes),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.map(|v| format!("{k}={v}")))
        .collect();
        if parts.is_empty() {
            "none".into()
        } else {
            parts.join(",")
        }
    }

    fn parse(arg: &str) -> Option<Self> {
        let mut bounds = Self::default();
        if arg == "none" {
            return Some(bounds);
        }
        for part in arg.split(',') {
            let (key, value) = part.split_once('=')?;
            let value = value.parse::<u64>().ok()?;
            match key {
                "as" => bounds.address_space = Some(value),
                "cpu" => bounds.cpu_seconds = Some(value),
                "fsize" => bounds.file_size = Some(value),
                "nproc" => bounds.processes = Some(value),
                _ => return None,
            }
        }
        Some(bounds)
    }

    /// Sets the limits on this process (and so on what it starts).
    fn apply(self) -> std::io::Result<()> {
        let limit = |resource, value: Option<u64>| match value {
            Some(v) => rustix::process::setrlimit(
                resource,
                Rlimit {
                    current: Some(v),
                    maximum: Some(v),
                },
            ),
            None => Ok(()),
        };
        limit(Resource::Core, Some(0))?;
        limit(Resource::As, self.address_space)?;
        // NOTE: the soft CPU limit sends SIGXCPU; the hard one, a second
        // later, SIGKILL, for a program that catches SIGXCPU.
        if let Some(s) = self.cpu_seconds {
            rustix::process::setrlimit(
                Resource::Cpu,
                Rlimit {
                    current: Some(s),
                    maximum: Some(s + 1),
                },
            )?;
        }
        limit(Resource::Fsize, self.file_size)?;
        let tasks = self
            .processes
            .map(|extra| tasks_of(rustix::process::getuid().as_raw()) + extra);
        limit(Resource::Nproc, tasks)?;
        Ok(())
    }
}

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

    /// Starts `program args…` under a supervisor with `bounds`: `command`
    /// runs the spintop binary (the supervisor) in the folder and with the
    /// environment the program gets, its arguments not yet given.
    pub fn start(
        &self,
        mut command: Command,
        bounds: Bounds,
        program: &OsStr,
        args: &[&str],
    ) -> std::io::Result<Started> {
        let mut control = lock(&self.control);
        if control.closed {
            return Err(std::io::Error::other("the server is stopping"));
        }
        let mut supervisor = command
            .args(launcher_args(bounds, program, args))
            .stdin(Stdio::piped())
            .spawn()?;
        control.pipe = supervisor.stdin.take();
        control.supervisor = i32::try_from(supervisor.id()).ok();
        Ok(Started { supervisor })
    }

    /// Tells the running tree's supervisor to kill the tree (closes its
    /// control pipe).
    fn stop(&self) {
        lock(&self.control).pipe = None;
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
    /// is gone (its waiter has seen it end): true, or false if that took
    /// longer than `grace` plus [`GRACE`].
    pub fn close(&self, grace: Duration) -> bool {
        {
            let mut control = lock(&self.control);
            control.closed = true;
            control.pipe = None;
        }
        let start = Instant::now();
        while start.elapsed() < grace + GRACE {
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
                    let _ = rustix::process::kill_process_group(group, Signal::KILL);
                }
                group_killed = true;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    }
}

/// The hidden flag of `spintop book` that runs the supervisor.
pub const SUPERVISE_FLAG: &str = "--supervise";

/// The arguments that make the spintop binary supervise `program args…`
/// under `bounds`: `book --supervise BOUNDS PROGRAM ARGS…`.
fn launcher_args(bounds: Bounds, program: &OsStr, args: &[&str]) -> Vec<OsString> {
    let mut out: Vec<OsString> = vec![
        "book".into(),
        SUPERVISE_FLAG.into(),
        bounds.to_arg().into(),
        program.into(),
    ];
    out.extend(args.iter().map(OsString::from));
    out
}

/// The supervisor's `main`: `args` are what followed [`SUPERVISE_FLAG`].
/// Returns the exit code: the program's, or 128 + the signal that ended it
/// (after a line on stderr saying which limit that was, if one was).
pub fn supervise(args: &[OsString]) -> i32 {
    let parsed = args.split_first().and_then(|(bounds, rest)| {
        let bounds = Bounds::parse(bounds.to_str()?)?;
        let (program, rest) = rest.split_first()?;
        Some((bounds, program, rest))
    });
    let Some((bounds, program, rest)) = parsed else {
        eprintln!("spintop book --supervise: expected BOUNDS PROGRAM [ARGS…]");
        return 2;
    };
    // 1-3: session, subreaper, limits; each must hold, or nothing runs.
    let me = rustix::process::getpid();
    let setup = rustix::process::setsid()
        .map(drop)
        .and_then(|()| subreaper(me))
        .map_err(std::io::Error::from)
        .and_then(|()| bounds.apply());
    if let Err(e) = setup {
        eprintln!("spintop book: cannot bound the snippet's processes: {e}");
        return 2;
    }
    // 4. The program, its output straight to the server's pipes.
    let child = match std::process::Command::new(program)
        .args(rest)
        .stdin(std::process::Stdio::null())
        .spawn()
    {
        Ok(c) => c,
        Err(e) => {
            eprintln!("cannot start {}: {e}", program.to_string_lossy());
            return 2;
        }
    };
    let program_pid = Pid::from_raw(child.id() as i32);
    // Dropping a `Child` neither waits nor kills: the loop below reaps it.
    drop(child);
    let stopped = Arc::new(AtomicBool::new(false));
    {
        let stopped = Arc::clone(&stopped);
        // The control pipe: any byte, or its end, stops the tree.
        std::thread::spawn(move || {
            let mut byte = [0u8; 1];
            let _ = std::io::stdin().read(&mut byte);
            stopped.store(true, Ordering::SeqCst);
            kill_tree(me);
        });
    }
    let mut status = None;
    loop {
        match rustix::process::wait(WaitOptions::empty()) {
            Ok(Some((pid, s))) if Some(pid) == program_pid => {
                status = Some(s);
                // The program is done: what it left behind goes with it.
                kill_tree(me);
            }
            Ok(_) => {}
            Err(rustix::io::Errno::INTR) => {}
            // ECHILD: every process of the tree is gone.
            Err(_) => break,
        }
    }
    let Some(status) = status else {
        return 2;
    };
    if let Some(code) = status.exit_status() {
        return code;
    }
    let signal = status.terminating_signal().unwrap_or(0);
    if !stopped.load(Ordering::SeqCst) {
        eprintln!("{}", signal_note(signal, bounds));
    }
    128 + signal
}

/// The line shown when the program was ended by `signal`.
fn signal_note(signal: i32, bounds: Bounds) -> String {
    let size = |b: u64| {
        if b.is_multiple_of(1 << 20) {
            format!("{} MiB", b >> 20)
        } else {
            format!("{b} bytes")
        }
    };
    if signal == Signal::XCPU.as_raw() {
        format!(
            "[stopped: the program used its {} s of CPU time]",
            bounds.cpu_seconds.unwrap_or(0)
        )
    } else if signal == Signal::XFSZ.as_raw() {
        format!(
            "[stopped: the program wrote a file past the {} limit]",
            size(bounds.file_size.unwrap_or(0))
        )
    } else if signal == Signal::KILL.as_raw() && bounds.cpu_seconds.is_some() {
        format!(
            "[stopped: the program was killed (signal 9); it may have outlived its {} s of CPU time]",
            bounds.cpu_seconds.unwrap_or(0)
        )
    } else {
        let memory = bounds
            .address_space
            .map(|b| format!(" (its memory limit is {})", size(b)))
            .unwrap_or_default();
        format!("[stopped: the program was ended by signal {signal}{memory}]")
    }
}

/// One line of `/proc/PID/stat`, the fields used here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Proc {
    pid: i32,
    ppid: i32,
    pgid: i32,
    sid: i32,
    /// A zombie (`Z`) or dead (`X`) process: it runs no more.
    dead: bool,
}

/// Parses `/proc/PID/stat`: `pid (comm) state ppid pgrp session …`, where
/// `comm` may hold spaces and parentheses (so the last `)` ends it).
fn parse_stat(text: &str) -> Option<Proc> {
    let (pid, rest) = text.split_once(" (")?;
    let after = &rest[rest.rfind(')')? + 1..];
    let mut fields = after.split_whitespace();
    let state = fields.next()?;
    let mut number = || fields.next()?.parse::<i32>().ok();
    Some(Proc {
        pid: pid.trim().parse().ok()?,
        ppid: number()?,
        pgid: number()?,
        sid: number()?,
        dead: state == "Z" || state == "X",
    })
}

/// Every process this user can see.
fn processes() -> Vec<Proc> {
    let Ok(dir) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    dir.flatten()
        .filter(|e| {
            e.file_name()
                .to_string_lossy()
                .bytes()
                .all(|b| b.is_ascii_digit())
        })
        .filter_map(|e| std::fs::read_to_string(e.path().join("stat")).ok())
        .filter_map(|text| parse_stat(&text))
        .collect()
}

/// The tasks (processes and threads) of real user `uid`, as RLIMIT_NPROC
/// counts them.
fn tasks_of(uid: u32) -> u64 {
    let Ok(dir) = std::fs::read_dir("/proc") else {
        return 0;
    };
    dir.flatten()
        .filter_map(|e| std::fs::read_to_string(e.path().join("status")).ok())
        .filter_map(|status| {
            let field = |name: &str| {
                status
                    .lines()
                    .find_map(|l| l.strip_prefix(name))
                    .and_then(|v| v.split_whitespace().next())
                    .and_then(|v| v.parse::<u64>().ok())
            };
            (field("Uid:")? == u64::from(uid)).then(|| field("Threads:"))?
        })
        .sum()
}

/// The living processes below `root` (by parent links), or in `root`'s
/// session or process group, `root` itself excluded.
fn tree(table: &[Proc], root: i32) -> Vec<i32> {
    let mut found: Vec<i32> = table
        .iter()
        .filter(|p| p.pid != root && (p.sid == root || p.pgid == root))
        .map(|p| p.pid)
        .collect();
    let mut frontier = vec![root];
    while let Some(parent) = frontier.pop() {
        for p in table.iter().filter(|p| p.ppid == parent) {
            if !found.contains(&p.pid) {
                found.push(p.pid);
            }
            frontier.push(p.pid);
        }
    }
    let living = |pid: &i32| table.iter().any(|p| p.pid == *pid && !p.dead);
    found.retain(living);
    found
}

/// Kills (SIGKILL) every living process of `root`'s tree, again and again
/// until none is left (a process may fork before its signal arrives), for at
/// most ten seconds.
fn kill_tree(root: Pid) {
    let root = root.as_raw_nonzero().get();
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(10) {
        let victims = tree(&processes(), root);
        if victims.is_empty() {
            return;
        }
        for pid in victims.into_iter().filter_map(Pid::from_raw) {
            let _ = rustix::process::kill_process(pid, Signal::KILL);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Makes this process a child subreaper: orphans below it come to it, not
/// to init.
pub fn become_subreaper() {
    let _ = subreaper(rustix::process::getpid());
}

/// `PR_SET_CHILD_SUBREAPER` for `me` (this process).
///
/// NOTE: Linux only, as the `/proc` walk of [`kill_tree`] is. Elsewhere the
/// tree still has its own session and limits and dies with its process
/// group, but a process that leaves both can outlive it.
fn subreaper(me: Pid) -> rustix::io::Result<()> {
    #[cfg(target_os = "linux")]
    return rustix::process::set_child_subreaper(Some(me));
    #[cfg(not(target_os = "linux"))]
    {
        let _ = me;
        Ok(())
    }
}

/// After a supervisor `leader` has ended (or was killed): kills whatever is
/// left in its session and process group, and reaps those of them this
/// process adopted (as a subreaper), never a child it started itself.
pub fn sweep(leader: u32) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stat_line_with_spaces_and_parentheses_in_the_name_parses() {
        let line = "4242 (a (b) c) S 17 4242 4000 0 -1 4194560 101 0 0 0 0 0 0 0 20 0 1 0";
        assert_eq!(
            parse_stat(line),
            Some(Proc {
                pid: 4242,
                ppid: 17,
                pgid: 4242,
                sid: 4000,
                dead: false
            })
        );
        let zombie = "7 (sleep) Z 1 7 7 0";
        assert!(parse_stat(zombie).unwrap().dead);
    }

    #[test]
    fn the_tree_is_the_descendants_and_the_session_without_the_dead() {
        let p = |pid, ppid, pgid, sid, dead| Proc {
            pid,
            ppid,
            pgid,
            sid,
            dead,
        };
        let table = [
            p(10, 1, 10, 10, false),  // the root
            p(11, 10, 10, 10, false), // its child
            p(12, 11, 12, 12, false), // a grandchild in a session of its own
            p(13, 1, 10, 10, false),  // adopted by init, still in the session
            p(14, 10, 10, 10, true),  // a zombie
            p(20, 1, 20, 20, false),  // unrelated
        ];
        let mut got = tree(&table, 10);
        got.sort();
        assert_eq!(got, [11, 12, 13]);
    }

    #[test]
    fn bounds_round_trip_through_their_argument() {
        for b in [
            Bounds::default(),
            Bounds {
                address_space: Some(4 << 30),
                cpu_seconds: Some(11),
                file_size: Some(64 << 20),
                processes: Some(512),
            },
            Bounds {
                cpu_seconds: Some(3),
                ..Bounds::default()
            },
        ] {
            assert_eq!(Bounds::parse(&b.to_arg()), Some(b));
        }
        assert_eq!(Bounds::parse("as=x"), None);
        assert_eq!(Bounds::parse("nice=3"), None);
    }
}
