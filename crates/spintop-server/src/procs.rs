//! What `/proc` says of the machine's processes: the table the supervisor
//! and the server walk to find, count and kill a tree's processes.
//!
//! NOTE: Linux only, as `/proc/PID/stat` is; elsewhere the table is empty,
//! and a tree is reached only through its process group.

use rustix::process::{Pid, Signal};
use std::time::{Duration, Instant};

/// One line of `/proc/PID/stat`, the fields used here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Proc {
    pub(crate) pid: i32,
    pub(crate) ppid: i32,
    pub(crate) pgid: i32,
    pub(crate) sid: i32,
    /// A zombie (`Z`) or dead (`X`) process: it runs no more.
    pub(crate) dead: bool,
}

/// Parses `/proc/PID/stat`: `pid (comm) state ppid pgrp session …`, where
/// `comm` may hold spaces and parentheses (so the last `)` ends it).
pub(crate) fn parse_stat(text: &str) -> Option<Proc> {
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
pub(crate) fn processes() -> Vec<Proc> {
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
pub(crate) fn tasks_of(uid: u32) -> u64 {
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
pub(crate) fn tree(table: &[Proc], root: i32) -> Vec<i32> {
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
pub(crate) fn kill_tree(root: Pid) {
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
}
