//! How a tree is ended as a unit, whoever ends it and however the server
//! ends: the strongest of three that this machine allows ([`Containment`]).
//!
//! - **A PID namespace** (Linux, where the reader may make a user
//!   namespace, or as root): the tree's first process, the supervisor's
//!   stage, is its init. When the init dies, the kernel kills every other
//!   process of the namespace, and no process can leave one; the init dies
//!   with the supervisor (`PR_SET_PDEATHSIG`), which dies with the server.
//!   From inside, the supervisor and the server have no process id: a
//!   snippet can neither signal nor trace them (`kill`, `pidfd_send_signal`
//!   through a `/proc` folder and `ptrace` all name a process in the
//!   caller's namespace or below it).
//! - **A cgroup v2 of its own** (Linux, where the reader may create one
//!   below the server's, as in a systemd user session): `cgroup.kill` kills
//!   every process in it at once, forks under way included. A snippet may
//!   move itself out (the reader owns the parent cgroup), so the
//!   supervisor also kills what is below it by parent links.
//! - **A process group and session, with the supervisor a child
//!   subreaper**: every process below the supervisor and in its session is
//!   killed, again and again until none is left.

use super::procs::kill_tree;
use rustix::process::{Pid, Signal};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// The ways to end a tree as a unit, weakest first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Containment {
    /// The supervisor's process group, session and descendants.
    Group,
    /// A cgroup v2 of the tree's own, ended by `cgroup.kill`.
    Cgroup,
    /// A PID namespace of the tree's own, ended by the kernel when its init
    /// dies.
    Namespace,
}

impl Containment {
    /// Its name in the supervisor's argument and in messages.
    pub fn name(self) -> &'static str {
        match self {
            Self::Group => "group",
            Self::Cgroup => "cgroup",
            Self::Namespace => "namespace",
        }
    }

    /// The containment named `name` (see [`Containment::name`]).
    pub fn named(name: &str) -> Option<Self> {
        [Self::Group, Self::Cgroup, Self::Namespace]
            .into_iter()
            .find(|c| c.name() == name)
    }

    /// What it means for a reader, in a few words.
    pub fn described(self) -> &'static str {
        match self {
            Self::Namespace => "a PID namespace of its own",
            Self::Cgroup => "a cgroup of its own",
            Self::Group => "a process group of its own",
        }
    }
}

/// The cgroup v2 that holds the tree of supervisor `supervisor`: a child of
/// the cgroup this process is in (the supervisor's server's, where the
/// supervisor was born), so that both find it by the supervisor's id.
pub(crate) fn cgroup_of(supervisor: u32) -> Option<PathBuf> {
    Some(own_cgroup()?.join(format!("spintop-book-{supervisor}")))
}

/// The cgroup v2 folder of this process: the cgroup2 mount (from
/// `/proc/self/mountinfo`) and this process's path in it (the `0::` line
/// of `/proc/self/cgroup`).
fn own_cgroup() -> Option<PathBuf> {
    let mounts = std::fs::read_to_string("/proc/self/mountinfo").ok()?;
    // id parent major:minor root mount-point options … - fstype source …
    let mount = mounts.lines().find_map(|line| {
        let (fields, rest) = line.split_once(" - ")?;
        (rest.split_whitespace().next()? == "cgroup2").then_some(())?;
        fields.split_whitespace().nth(4).map(PathBuf::from)
    })?;
    let groups = std::fs::read_to_string("/proc/self/cgroup").ok()?;
    let path = groups.lines().find_map(|l| l.strip_prefix("0::"))?;
    Some(mount.join(path.trim_start_matches('/')))
}

/// Whether this process may create a cgroup below its own that has
/// `cgroup.kill` (Linux 5.14): made and removed at once.
pub(crate) fn cgroup_allowed() -> bool {
    let Some(probe) =
        own_cgroup().map(|c| c.join(format!("spintop-book-probe-{}", std::process::id())))
    else {
        return false;
    };
    if std::fs::create_dir(&probe).is_err() {
        return false;
    }
    let kill = probe.join("cgroup.kill").is_file();
    let _ = std::fs::remove_dir(&probe);
    kill
}

/// Enters a user namespace (unless root, who needs none) and a PID
/// namespace: the next process this one starts is the init of a namespace
/// of its own. Only in a process with one thread (a user namespace asks
/// it), and after the resource limits are set (a user namespace takes the
/// process limit its maker has then as its own ceiling).
#[cfg(target_os = "linux")]
pub(crate) fn enter_namespace() -> Result<(), String> {
    use nix::sched::{CloneFlags, unshare};
    let (uid, gid) = (rustix::process::geteuid(), rustix::process::getegid());
    if !uid.is_root() {
        unshare(CloneFlags::CLONE_NEWUSER)
            .map_err(|e| format!("cannot make a user namespace: {e}"))?;
        // This user and group stay themselves inside (no root there).
        let maps = [
            ("/proc/self/setgroups", "deny".to_string()),
            ("/proc/self/uid_map", format!("{0} {0} 1", uid.as_raw())),
            ("/proc/self/gid_map", format!("{0} {0} 1", gid.as_raw())),
        ];
        for (file, text) in maps {
            std::fs::write(file, text).map_err(|e| format!("cannot write {file}: {e}"))?;
        }
    }
    unshare(CloneFlags::CLONE_NEWPID).map_err(|e| format!("cannot make a PID namespace: {e}"))
}

#[cfg(not(target_os = "linux"))]
pub(crate) fn enter_namespace() -> Result<(), String> {
    Err("PID namespaces are Linux's".into())
}

/// The unit of one supervisor's tree, as it was made.
#[derive(Debug)]
pub(crate) enum Unit {
    Namespace,
    Cgroup(PathBuf),
    Group,
}

impl Unit {
    /// Makes the unit `how` in supervisor `me`, before its stage starts.
    pub(crate) fn make(how: Containment, me: Pid) -> Result<Self, String> {
        match how {
            Containment::Namespace => enter_namespace().map(|()| Self::Namespace),
            Containment::Cgroup => {
                let me = me.as_raw_nonzero().get().unsigned_abs();
                let dir = cgroup_of(me).ok_or("no cgroup v2 is mounted")?;
                std::fs::create_dir(&dir)
                    .map(|()| Self::Cgroup(dir.clone()))
                    .map_err(|e| format!("cannot make the cgroup {}: {e}", dir.display()))
            }
            Containment::Group => Ok(Self::Group),
        }
    }

    /// Puts the stage (`stage`, not yet running the program) in the unit:
    /// a cgroup moves it there; a namespace has it already.
    pub(crate) fn adopt(&self, stage: Pid) -> Result<(), String> {
        match self {
            Self::Cgroup(dir) => {
                let procs = dir.join("cgroup.procs");
                std::fs::write(&procs, stage.as_raw_nonzero().get().to_string())
                    .map_err(|e| format!("cannot move the snippet into {}: {e}", dir.display()))
            }
            Self::Namespace | Self::Group => Ok(()),
        }
    }

    /// Kills every process of the unit of supervisor `me`, its stage
    /// `stage` first (so that the stage never reports its program's death
    /// as the program's own end), and waits until they are gone (at most
    /// ten seconds). The supervisor then reaps what came to it.
    pub(crate) fn end(&self, me: Pid, stage: Option<Pid>) {
        if let Some(stage) = stage {
            let _ = rustix::process::kill_process(stage, Signal::KILL);
        }
        if let Self::Cgroup(dir) = self {
            kill_cgroup(dir);
        }
        // Whatever is below the supervisor or in its session: in a
        // namespace, nothing once its init is dead; in a cgroup, what moved
        // itself out.
        kill_tree(me);
    }

    /// Removes what the unit left on the machine (a cgroup's folder).
    pub(crate) fn remove(&self) {
        if let Self::Cgroup(dir) = self {
            remove_cgroup(dir);
        }
    }
}

/// Kills every process of cgroup `dir` (`cgroup.kill`) and waits (at most
/// five seconds) until it is empty.
pub(crate) fn kill_cgroup(dir: &std::path::Path) {
    if std::fs::write(dir.join("cgroup.kill"), "1").is_err() {
        return;
    }
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(5) {
        let events = std::fs::read_to_string(dir.join("cgroup.events")).unwrap_or_default();
        if !events.lines().any(|l| l == "populated 1") {
            return;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Removes cgroup `dir` once it is empty (a cgroup with processes cannot
/// be removed): kills what is in it first.
pub(crate) fn remove_cgroup(dir: &std::path::Path) {
    if dir.is_dir() {
        kill_cgroup(dir);
        let _ = std::fs::remove_dir(dir);
    }
}
