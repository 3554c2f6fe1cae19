//! The two processes between the server and a snippet (or a build): the
//! supervisor, which the server starts, and its stage, which starts the
//! program. Both are the spintop binary run again (`spintop book
//! --supervise …`): setting limits or a session between fork and exec
//! needs `CommandExt::pre_exec`, which is `unsafe`, and this crate forbids
//! `unsafe`; a re-executed copy does the same with safe calls before it
//! starts the next process. Each costs one exec, a few milliseconds.
//!
//! The supervisor
//!
//! 1. starts a session of its own (`setsid`): the tree has its own process
//!    group and session, and the terminal's Ctrl-C or Ctrl-Z never reaches
//!    it;
//! 2. sets the resource limits ([`Bounds`]), which the tree inherits;
//! 3. makes the tree's unit ([`super::unit`]): a PID namespace, a cgroup,
//!    or the process group alone;
//! 4. turns itself non-dumpable (`PR_SET_DUMPABLE` 0: a process of the
//!    same user may then neither trace it nor open its `/proc` files, such
//!    as its control pipe), asks for a signal when the server dies
//!    (`PR_SET_PDEATHSIG`: SIGKILL in a namespace, whose init then dies
//!    with it; SIGCONT otherwise, which wakes it if it was stopped, so that
//!    it sees its parent gone and ends the tree first), and checks at once
//!    that the server is still its parent (a server gone before would send
//!    nothing); becomes a child subreaper;
//! 5. starts the stage, moves it into the unit, and tells it to go;
//! 6. ends the whole unit (the stage first) when the stage ends, when the
//!    server says so (a byte on, or the end of, its control pipe), at its
//!    own wall-clock limit (whether or not the server is there to count: a
//!    stopped server's tree still ends on time), or when its parent is no
//!    longer the server (checked every 10 ms); reaps all, and exits with
//!    the program's status. It catches no signal: one that ends it (a
//!    snippet may send SIGTERM or SIGKILL to its supervisor outside a
//!    namespace) leaves the tree to the server's sweep.
//!
//! The stage asks to die with the supervisor (`PR_SET_PDEATHSIG`,
//! SIGKILL), waits for the supervisor's word on a socket (whose end,
//! instead, means the supervisor died before it could ask), becomes a
//! child subreaper, starts the program, reaps every process that comes to
//! it, and when the program ends says which limit ended it, if one did,
//! and exits with its status. In a PID namespace it is the init: its end
//! is the namespace's.

use super::bounds::{Bounds, signal_note};
use super::unit::{Containment, Unit, cgroup_allowed, enter_namespace};
use rustix::process::{Pid, Signal, WaitOptions, WaitStatus};
use std::ffi::{OsStr, OsString};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The hidden flag of `spintop book` that runs the supervisor.
pub const SUPERVISE_FLAG: &str = "--supervise";

/// The first argument after [`SUPERVISE_FLAG`] that runs the stage.
const STAGE: &str = "stage";

/// The only argument after [`SUPERVISE_FLAG`] that checks whether a PID
/// namespace can be made here.
const PROBE: &str = "probe";

/// The supervisor's exit code when its own wall-clock limit ended the tree
/// (as `timeout(1)`'s).
const TIMED_OUT: i32 = 124;

/// What the server asks of one supervisor: one argument,
/// `as=N,cpu=N,fsize=N,nproc=N,time=MS,parent=PID,unit=NAME`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Spec {
    /// The limits of each process of the tree.
    pub(crate) bounds: Bounds,
    /// The supervisor's own wall-clock limit.
    pub(crate) limit: Duration,
    /// The server: the supervisor's parent, with which it dies.
    pub(crate) parent: u32,
    /// How the tree is ended as a unit.
    pub(crate) unit: Containment,
}

impl Spec {
    pub(crate) fn to_arg(self) -> String {
        let mut parts = self.bounds.pairs();
        parts.push(format!("time={}", self.limit.as_millis()));
        parts.push(format!("parent={}", self.parent));
        parts.push(format!("unit={}", self.unit.name()));
        parts.join(",")
    }

    pub(crate) fn parse(arg: &str) -> Option<Self> {
        let mut bounds = Bounds::default();
        let (mut limit, mut parent, mut unit) = (None, None, None);
        for part in arg.split(',') {
            let (key, value) = part.split_once('=')?;
            match key {
                "unit" => unit = Some(Containment::named(value)?),
                _ => {
                    let value = value.parse::<u64>().ok()?;
                    match key {
                        "time" => limit = Some(Duration::from_millis(value)),
                        "parent" => parent = Some(u32::try_from(value).ok()?),
                        _ if bounds.take(key, value) => {}
                        _ => return None,
                    }
                }
            }
        }
        Some(Self {
            bounds,
            limit: limit?,
            parent: parent?,
            unit: unit?,
        })
    }
}

/// The arguments that make the spintop binary supervise `program args…`
/// as `spec` says: `book --supervise SPEC PROGRAM ARGS…`.
pub(crate) fn launcher_args(spec: Spec, program: &OsStr, args: &[&OsStr]) -> Vec<OsString> {
    let mut out: Vec<OsString> = vec![
        "book".into(),
        SUPERVISE_FLAG.into(),
        spec.to_arg().into(),
        program.into(),
    ];
    out.extend(args.iter().map(OsString::from));
    out
}

/// The strongest containment up to `most` that works here, tried with
/// `launcher` (the spintop binary): a PID namespace if a process can make
/// one (it asks the kernel in a process of its own), else a cgroup if one
/// can be made below this process's, else the process group.
pub(crate) fn strongest(most: Containment, launcher: &Path) -> Containment {
    let namespace = || {
        Command::new(launcher)
            .args(["book", SUPERVISE_FLAG, PROBE])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if most >= Containment::Namespace && cfg!(target_os = "linux") && namespace() {
        Containment::Namespace
    } else if most >= Containment::Cgroup && cgroup_allowed() {
        Containment::Cgroup
    } else {
        Containment::Group
    }
}

/// The supervisor's and the stage's `main`: `args` are what followed
/// [`SUPERVISE_FLAG`]. Returns the exit code: the program's, or 128 + the
/// signal that ended it (after a line on stderr saying which limit that
/// was, if one was); [`TIMED_OUT`] at the supervisor's own limit.
pub fn supervise(args: &[OsString]) -> i32 {
    match args.first().and_then(|a| a.to_str()) {
        Some(PROBE) => probe(),
        Some(STAGE) => stage(&args[1..]),
        _ => supervisor(args),
    }
}

/// `SPEC PROGRAM ARGS…`, parsed.
fn parse_args(args: &[OsString]) -> Option<(Spec, &OsStr, &[OsString])> {
    let (spec, rest) = args.split_first()?;
    let spec = Spec::parse(spec.to_str()?)?;
    let (program, rest) = rest.split_first()?;
    Some((spec, program.as_os_str(), rest))
}

/// The spintop binary this process runs, to start the stage: on Linux the
/// running file itself, even if it was replaced since.
fn this_binary() -> PathBuf {
    if cfg!(target_os = "linux") {
        PathBuf::from("/proc/self/exe")
    } else {
        std::env::current_exe().unwrap_or_else(|_| PathBuf::from("spintop"))
    }
}

/// The supervisor (see the module's docs).
fn supervisor(args: &[OsString]) -> i32 {
    let Some((spec, program, _)) = parse_args(args) else {
        eprintln!("spintop book --supervise: expected SPEC PROGRAM [ARGS…]");
        return 2;
    };
    let start = Instant::now();
    let me = rustix::process::getpid();
    let unit = match set_up(spec, me) {
        Ok(unit) => unit,
        Err(e) => {
            eprintln!("spintop book: cannot bound the snippet's processes: {e}");
            return 2;
        }
    };
    let stage = match start_stage(&unit, args) {
        Ok(stage) => stage,
        Err(e) => {
            unit.remove();
            eprintln!(
                "spintop book: cannot start {}: {e}",
                program.to_string_lossy()
            );
            return 2;
        }
    };
    let (status, why) = watch(spec, start, stage);
    unit.end(me, status.is_none().then_some(stage));
    reap_all(Duration::from_secs(2));
    unit.remove();
    match (status, why) {
        (Some(status), None) => mirror(status),
        (_, Some(Stop::Deadline)) => TIMED_OUT,
        _ => 128 + Signal::KILL.as_raw(),
    }
}

/// Steps 1–4 of the module's docs: session, limits, unit, death with the
/// server. A unit made before a later step fails is removed.
fn set_up(spec: Spec, me: Pid) -> Result<Unit, String> {
    rustix::process::setsid().map_err(|e| format!("cannot start a session: {e}"))?;
    // Before the unit: a user namespace takes its maker's process limit.
    spec.bounds.apply()?;
    let unit = Unit::make(spec.unit, me)?;
    let guarded = dies_with_server(spec, &unit)
        .and_then(|()| subreaper(me).map_err(|e| format!("cannot become a child subreaper: {e}")));
    if let Err(e) = guarded {
        unit.remove();
        return Err(e);
    }
    Ok(unit)
}

/// Step 4: not dumpable, and dies with the server, which must still be
/// its parent once that is asked.
fn dies_with_server(spec: Spec, unit: &Unit) -> Result<(), String> {
    #[cfg(target_os = "linux")]
    {
        use rustix::process::DumpableBehavior;
        rustix::process::set_dumpable_behavior(DumpableBehavior::NotDumpable)
            .map_err(|e| format!("cannot turn off tracing: {e}"))?;
        let signal = match unit {
            Unit::Namespace => Signal::KILL,
            Unit::Cgroup(_) | Unit::Group => Signal::CONT,
        };
        rustix::process::set_parent_process_death_signal(Some(signal))
            .map_err(|e| format!("cannot ask to die with the server: {e}"))?;
    }
    #[cfg(not(target_os = "linux"))]
    let _ = unit;
    if !server_is_parent(spec) {
        return Err("the server is gone".into());
    }
    Ok(())
}

/// Whether this process's parent is still the server (once the server
/// ends, another process adopts it).
fn server_is_parent(spec: Spec) -> bool {
    rustix::process::getppid().map(|p| p.as_raw_nonzero().get()) == i32::try_from(spec.parent).ok()
}

/// Step 5: the stage, in the unit, told to go.
fn start_stage(unit: &Unit, args: &[OsString]) -> Result<Pid, String> {
    let (mut ours, theirs) = std::os::unix::net::UnixStream::pair().map_err(|e| e.to_string())?;
    let child = Command::new(this_binary())
        .arg("book")
        .arg(SUPERVISE_FLAG)
        .arg(STAGE)
        .args(args)
        .stdin(Stdio::from(std::os::fd::OwnedFd::from(theirs)))
        .spawn()
        .map_err(|e| e.to_string())?;
    let stage = i32::try_from(child.id())
        .ok()
        .and_then(Pid::from_raw)
        .ok_or("no process id")?;
    // Dropping a `Child` neither waits nor kills: `watch` reaps it.
    drop(child);
    let told = unit.adopt(stage).and_then(|()| {
        ours.write_all(b"g")
            .map_err(|e| format!("cannot tell the stage to go: {e}"))
    });
    if let Err(e) = told {
        let _ = rustix::process::kill_process(stage, Signal::KILL);
        reap_all(Duration::from_secs(1));
        return Err(e);
    }
    Ok(stage)
}

/// Why the supervisor ended the tree itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stop {
    /// The server said so (its control pipe), or is gone.
    Server,
    /// The supervisor's own wall-clock limit.
    Deadline,
}

/// Step 6: waits for the stage to end (its status), or for a reason to end
/// it, checking every 10 ms; reaps what comes to the supervisor meanwhile.
fn watch(spec: Spec, start: Instant, stage: Pid) -> (Option<WaitStatus>, Option<Stop>) {
    loop {
        loop {
            match rustix::process::waitpid(None, WaitOptions::NOHANG) {
                Ok(Some((pid, status))) if pid == stage => return (Some(status), None),
                Ok(Some(_)) => {}
                Ok(None) => break,
                Err(rustix::io::Errno::INTR) => {}
                // No child at all: the stage is gone unseen.
                Err(_) => return (None, Some(Stop::Server)),
            }
        }
        if control_closed() || !server_is_parent(spec) {
            return (None, Some(Stop::Server));
        }
        if start.elapsed() >= spec.limit {
            return (None, Some(Stop::Deadline));
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// Whether the control pipe (standard input) has a byte or has ended.
fn control_closed() -> bool {
    use rustix::event::{PollFd, PollFlags, poll};
    use std::os::fd::AsFd;
    let stdin = std::io::stdin();
    let fd = stdin.as_fd();
    let mut fds = [PollFd::new(&fd, PollFlags::IN)];
    let zero = rustix::event::Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    matches!(poll(&mut fds, Some(&zero)), Ok(n) if n > 0)
}

/// Reaps every child that has ended, until none is left or `limit` has
/// passed.
fn reap_all(limit: Duration) {
    let start = Instant::now();
    while start.elapsed() < limit {
        match rustix::process::waitpid(None, WaitOptions::NOHANG) {
            Ok(Some(_)) | Err(rustix::io::Errno::INTR) => {}
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(_) => return,
        }
    }
}

/// An exit code that says what `status` says: the code, or 128 + the signal.
fn mirror(status: WaitStatus) -> i32 {
    status
        .exit_status()
        .unwrap_or_else(|| 128 + status.terminating_signal().unwrap_or(0))
}

/// The stage (see the module's docs): `args` are `SPEC PROGRAM ARGS…`.
fn stage(args: &[OsString]) -> i32 {
    let Some((spec, program, rest)) = parse_args(args) else {
        eprintln!("spintop book --supervise stage: expected SPEC PROGRAM [ARGS…]");
        return 2;
    };
    #[cfg(target_os = "linux")]
    if rustix::process::set_parent_process_death_signal(Some(Signal::KILL)).is_err() {
        return 2;
    }
    // The supervisor's word; the socket's end instead means it is gone,
    // and so the death signal above will never come.
    let mut go = [0u8; 1];
    if !matches!(std::io::stdin().read(&mut go), Ok(1)) || go[0] != b'g' {
        return 2;
    }
    if subreaper(rustix::process::getpid()).is_err() {
        return 2;
    }
    if let Err(e) = forbid_stopping() {
        eprintln!("spintop book: cannot bound the snippet's processes: {e}");
        return 2;
    }
    let child = match Command::new(program)
        .args(rest)
        .stdin(Stdio::null())
        .spawn()
    {
        Ok(c) => c,
        Err(e) => {
            eprintln!("cannot start {}: {e}", program.to_string_lossy());
            return 2;
        }
    };
    let program_pid = i32::try_from(child.id()).ok().and_then(Pid::from_raw);
    drop(child);
    let status = loop {
        match rustix::process::wait(WaitOptions::empty()) {
            Ok(Some((pid, s))) if Some(pid) == program_pid => break s,
            Ok(_) | Err(rustix::io::Errno::INTR) => {}
            Err(_) => return 2,
        }
    };
    if let Some(signal) = status.terminating_signal() {
        eprintln!("{}", signal_note(signal, spec.bounds));
    }
    mirror(status)
}

/// Forbids this process and all it starts to stop a process (SIGSTOP,
/// SIGTSTP, SIGTTIN, SIGTTOU, by any of the system calls that send a
/// signal) or to trace one, with a seccomp filter that no process can
/// remove: a stopped supervisor cannot end its tree, and a snippet runs as
/// the reader, whose processes may otherwise signal each other. (In a PID
/// namespace the supervisor has no process id to name; outside one, this
/// is what keeps it running.) Such calls fail with EPERM. Also sets
/// `no_new_privs`: a set-user-ID program started below gains nothing.
///
/// NOTE: where seccompiler knows no filter for the machine
/// (x86_64, aarch64 and riscv64 only), nothing is forbidden.
#[cfg(target_os = "linux")]
fn forbid_stopping() -> Result<(), String> {
    use seccompiler::{
        BpfProgram, SeccompAction, SeccompCmpArgLen, SeccompCmpOp, SeccompCondition, SeccompFilter,
        SeccompRule, TargetArch,
    };
    let Ok(arch) = TargetArch::try_from(std::env::consts::ARCH) else {
        return Ok(());
    };
    let stops = [libc::SIGSTOP, libc::SIGTSTP, libc::SIGTTIN, libc::SIGTTOU];
    // Each system call that sends a signal, and which argument the signal is.
    let senders = [
        (libc::SYS_kill, 1),
        (libc::SYS_tkill, 1),
        (libc::SYS_tgkill, 2),
        (libc::SYS_rt_sigqueueinfo, 1),
        (libc::SYS_rt_tgsigqueueinfo, 2),
        (libc::SYS_pidfd_send_signal, 1),
    ];
    let mut rules = std::collections::BTreeMap::new();
    for (call, arg) in senders {
        let any_stop = stops
            .iter()
            .map(|&signal| {
                let cmp = SeccompCondition::new(
                    arg,
                    SeccompCmpArgLen::Dword,
                    SeccompCmpOp::Eq,
                    signal.unsigned_abs().into(),
                )?;
                SeccompRule::new(vec![cmp])
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| e.to_string())?;
        rules.insert(call, any_stop);
    }
    // No rule: every call.
    rules.insert(libc::SYS_ptrace, Vec::new());
    let filter = SeccompFilter::new(
        rules,
        SeccompAction::Allow,
        SeccompAction::Errno(libc::EPERM.unsigned_abs()),
        arch,
    )
    .map_err(|e| e.to_string())?;
    let program = BpfProgram::try_from(filter).map_err(|e| e.to_string())?;
    seccompiler::apply_filter(&program).map_err(|e| format!("cannot set its seccomp filter: {e}"))
}

#[cfg(not(target_os = "linux"))]
fn forbid_stopping() -> Result<(), String> {
    Ok(())
}

/// `probe`: whether this process can make a PID namespace (see
/// [`enter_namespace`]) and start a process in it: exit code 0 if so.
fn probe() -> i32 {
    if enter_namespace().is_err() {
        return 1;
    }
    let ran = Command::new(this_binary())
        .arg("--version")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status();
    i32::from(!ran.is_ok_and(|s| s.success()))
}

/// Makes this process (`me`) a child subreaper: orphans below it come to
/// it, not to init.
///
/// NOTE: Linux only, as the `/proc` walk of the process table is.
/// Elsewhere the tree still has its own session and limits and dies with
/// its process group, but a process that leaves both can outlive it.
pub(crate) fn subreaper(me: Pid) -> rustix::io::Result<()> {
    #[cfg(target_os = "linux")]
    return rustix::process::set_child_subreaper(Some(me));
    #[cfg(not(target_os = "linux"))]
    {
        let _ = me;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_spec_round_trips_through_its_argument() {
        for bounds in [
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
            for unit in [
                Containment::Group,
                Containment::Cgroup,
                Containment::Namespace,
            ] {
                let spec = Spec {
                    bounds,
                    limit: Duration::from_millis(10_500),
                    parent: 4242,
                    unit,
                };
                assert_eq!(Spec::parse(&spec.to_arg()), Some(spec));
            }
        }
        assert_eq!(Spec::parse("as=x,time=1,parent=1,unit=group"), None);
        assert_eq!(Spec::parse("nice=3,time=1,parent=1,unit=group"), None);
        assert_eq!(Spec::parse("time=1,parent=1,unit=jail"), None);
        assert_eq!(Spec::parse("as=1,parent=1,unit=group"), None, "no time");
    }
}
