//! The resource limits of a tree's processes, and what is shown when one
//! ends a program.

use super::procs::tasks_of;
use rustix::process::{Resource, Rlimit, Signal};

/// How many of the reader's processes and threads a run leaves to
/// everything else when the reader has a process limit (RLIMIT_NPROC counts
/// every task of a user, the server's connection threads among them): at
/// most [`super::MAX_CONNECTIONS`] connections, each on a thread, and a few
/// more of the server's own.
pub(crate) const LEFT_TO_THE_SERVER: u64 = 96;

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
    /// The bounds as `key=value` pairs (`as`, `cpu`, `fsize`, `nproc`).
    pub(crate) fn pairs(self) -> Vec<String> {
        [
            ("as", self.address_space),
            ("cpu", self.cpu_seconds),
            ("fsize", self.file_size),
            ("nproc", self.processes),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.map(|v| format!("{k}={v}")))
        .collect()
    }

    /// Takes one `key=value` pair of [`Bounds::pairs`]: false if `key` is
    /// not a bound.
    pub(crate) fn take(&mut self, key: &str, value: u64) -> bool {
        match key {
            "as" => self.address_space = Some(value),
            "cpu" => self.cpu_seconds = Some(value),
            "fsize" => self.file_size = Some(value),
            "nproc" => self.processes = Some(value),
            _ => return false,
        }
        true
    }

    /// Sets the limits on this process (and so on what it starts), each
    /// within what the reader's hard limits allow: a hard limit lower than
    /// the bound is kept (it is the stricter), and only root may raise one.
    /// The error says which limit could not be set, and why.
    pub(crate) fn apply(self) -> Result<(), String> {
        set(Resource::Core, "core size", 0, 0)?;
        if let Some(v) = self.address_space {
            set(Resource::As, "memory", v, v)?;
        }
        // NOTE: the soft CPU limit sends SIGXCPU; the hard one, a second
        // later, SIGKILL, for a program that catches SIGXCPU.
        if let Some(s) = self.cpu_seconds {
            set(Resource::Cpu, "CPU time", s, s + 1)?;
        }
        if let Some(v) = self.file_size {
            set(Resource::Fsize, "file size", v, v)?;
        }
        if let Some(extra) = self.processes {
            let uid = rustix::process::getuid();
            let tasks = tasks_of(uid.as_raw());
            let limit = process_limit(tasks, extra, rustix::process::getrlimit(Resource::Nproc));
            if limit < tasks + 4 && !uid.is_root() {
                return Err(format!(
                    "cannot run it: you already run {tasks} processes and threads, and your process limit (ulimit -u) leaves none for a snippet once {LEFT_TO_THE_SERVER} are kept for the book's server; end some programs or raise the limit"
                ));
            }
            set(Resource::Nproc, "process", limit, limit)?;
        }
        Ok(())
    }
}

/// The process limit of a run: `extra` more than the `tasks` the reader
/// has, within the hard limit, and leaving [`LEFT_TO_THE_SERVER`] below
/// the soft one (so that a fork bomb never takes the server's threads).
pub(crate) fn process_limit(tasks: u64, extra: u64, current: Rlimit) -> u64 {
    let mut limit = tasks.saturating_add(extra);
    if let Some(hard) = current.maximum {
        limit = limit.min(hard);
    }
    if let Some(soft) = current.current {
        limit = limit.min(soft.saturating_sub(LEFT_TO_THE_SERVER));
    }
    limit
}

/// Sets `resource` to `soft`/`hard`, each at most the current hard limit
/// (unlimited: `None`).
fn set(resource: Resource, name: &str, soft: u64, hard: u64) -> Result<(), String> {
    let current = rustix::process::getrlimit(resource);
    let within = |v: u64| current.maximum.map_or(v, |m| v.min(m));
    rustix::process::setrlimit(
        resource,
        Rlimit {
            current: Some(within(soft)),
            maximum: Some(within(hard)),
        },
    )
    .map_err(|e| format!("cannot set the snippet's {name} limit: {e}"))
}

/// The line shown when the program was ended by `signal`.
pub(crate) fn signal_note(signal: i32, bounds: Bounds) -> String {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_process_limit_stays_within_the_hard_limit_and_below_the_soft_one() {
        let unlimited = Rlimit {
            current: None,
            maximum: None,
        };
        assert_eq!(process_limit(100, 512, unlimited), 612);
        // A hard limit below tasks + 512: the hard limit (raising it fails).
        let hard = Rlimit {
            current: None,
            maximum: Some(300),
        };
        assert_eq!(process_limit(100, 512, hard), 300);
        // A low soft limit: the server keeps its share below it.
        let soft = Rlimit {
            current: Some(400),
            maximum: Some(4000),
        };
        assert_eq!(process_limit(100, 512, soft), 400 - LEFT_TO_THE_SERVER);
        // Nothing left at all: 0, not an underflow.
        let tiny = Rlimit {
            current: Some(10),
            maximum: Some(10),
        };
        assert_eq!(process_limit(100, 512, tiny), 0);
    }
}
