//! The launcher on Linux: rlimits, then namespaces and mounts, then
//! `no_new_privs`, Landlock and seccomp, then `exec`. Every call is one of
//! rustix's or the `landlock` and `seccompiler` crates' safe functions.

use super::{Kind, Layers, SETUP_FAILED, SETUP_MARK, Spec, set_rlimits};
use rustix::fs::{self as rfs, Mode, OFlags};
use rustix::mount::{self, MountFlags, MountPropagationFlags, UnmountFlags};
use rustix::process::{Gid, Uid};
use std::ffi::OsString;
use std::os::fd::AsRawFd;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};

/// `nobody`: who a runner started by root becomes.
const NOBODY: u32 = 65534;

/// Where a runner's new root is mounted before `pivot_root` (a folder
/// every system has; the mount is seen in the launcher's own mount
/// namespace only).
const NEW_ROOT: &str = "/tmp";

/// The runner's path inside its new root.
const RUNNER: &str = "/runner";

fn text(e: impl std::fmt::Display) -> String {
    e.to_string()
}

pub(super) fn launch(spec: &Spec, program: &Path, args: &[OsString]) -> i32 {
    // A runner whose parent (the grader) dies is killed (and cannot undo
    // it: seccomp refuses that `prctl`); a build's guard, instead, sees its
    // parent gone within 10 ms and ends its whole process group (cargo's
    // children do not inherit a parent-death signal).
    let grader = rustix::process::getppid();
    let death = match spec.kind {
        Kind::Build { .. } => rustix::process::Signal::CONT,
        _ => rustix::process::Signal::KILL,
    };
    let _ = rustix::process::set_parent_process_death_signal(Some(death));
    if rustix::process::getppid() != grader {
        return fail("the grader ended before its sandbox was set up");
    }
    // Nothing the grader was given (a terminal, a pipe, a FIFO on fd 7)
    // reaches the program: it keeps its standard input, output and error.
    close_inherited();
    let mut layers = Layers::none("not tried");
    let run = matches!(spec.kind, Kind::Run | Kind::Probe);
    // The program is opened before anything changes (who we are, what we
    // see): a runner without namespaces is started through it.
    let program_fd = match spec.kind {
        Kind::Run => match rfs::open(program, OFlags::PATH | OFlags::CLOEXEC, Mode::empty()) {
            Ok(fd) => Some(fd),
            Err(e) => return fail(&format!("cannot open {}: {e}", program.display())),
        },
        _ => None,
    };
    layers.rlimits = set_rlimits(&spec.limits)
        .map(|()| format!("{:?}", spec.limits))
        .map_err(text);
    if let Err(e) = &layers.rlimits {
        return fail(&format!("cannot set the limits: {e}"));
    }
    let mut exec_path = program.to_path_buf();
    // Without user namespaces (not allowed here) the other layers still
    // hold; a step that fails once inside them leaves a half-made view, and
    // nothing runs in that.
    layers.namespaces = match enter_namespaces() {
        Err(e) => Err(e),
        Ok(()) => {
            let inside = match &spec.kind {
                Kind::Build { writable } => read_only_but(writable),
                Kind::Run => empty_root(program).inspect(|_| {
                    exec_path = PathBuf::from(RUNNER);
                }),
                Kind::Probe => Ok("user, mount and network".to_string()),
            };
            match inside {
                Ok(done) => Ok(done),
                Err(e) => return fail(&e),
            }
        }
    };
    // Root without namespaces: the runner runs as nobody, started through
    // the file opened above (nobody may not walk root's private folders).
    if run && layers.namespaces.is_err() && rustix::process::getuid().is_root() {
        if let Err(e) = become_nobody() {
            return fail(&format!("cannot leave root: {e}"));
        }
        if let Some(fd) = &program_fd {
            exec_path = PathBuf::from(format!("/proc/self/fd/{}", fd.as_raw_fd()));
        }
    }
    if let Err(e) = rustix::thread::set_no_new_privs(true) {
        return fail(&format!("cannot set no_new_privs: {e}"));
    }
    if matches!(spec.kind, Kind::Build { .. }) {
        // Orphans of the build come to the guard (and stay in its group).
        let _ = rustix::process::set_child_subreaper(None);
    }
    if matches!(spec.kind, Kind::Run) {
        // A wall-clock limit that holds without the grader: the alarm stays
        // across exec, and seccomp refuses `alarm`, `setitimer` and a
        // handler for SIGALRM.
        nix::unistd::alarm::set(super::wall_seconds(&spec.limits));
    }
    layers.landlock = landlock(&spec.kind, &exec_path);
    layers.seccomp = seccomp(&spec.kind);
    match &spec.kind {
        Kind::Probe => {
            println!("{}", serde_json::to_string(&layers).unwrap_or_default());
            0
        }
        Kind::Build { .. } => guard(&exec_path, args, grader),
        Kind::Run => {
            let e = std::process::Command::new(&exec_path).args(args).exec();
            fail(&format!("cannot start {}: {e}", program.display()))
        }
    }
}

/// A build's guard: starts the build (cargo) as its child, in its own
/// process group, and waits for it; when its parent is no longer the grader
/// (checked every 10 ms: a SIGKILLed grader) it kills its whole process
/// group, itself included, and every process that came to it (it is a
/// child subreaper). Exits with the build's code (128 + a signal's
/// number).
fn guard(program: &Path, args: &[OsString], grader: Option<rustix::process::Pid>) -> i32 {
    // A group of its own (the grader already gives it one): what it kills
    // is the build's and its own, never its starter's.
    if let Err(e) = rustix::process::setpgid(None, None) {
        return fail(&format!("a process group of its own: {e}"));
    }
    let mut child = match std::process::Command::new(program).args(args).spawn() {
        Ok(child) => child,
        Err(e) => return fail(&format!("cannot start {}: {e}", program.display())),
    };
    loop {
        match child.try_wait() {
            Ok(Some(status)) => {
                use std::os::unix::process::ExitStatusExt;
                return status
                    .code()
                    .or(status.signal().map(|s| 128 + s))
                    .unwrap_or(SETUP_FAILED);
            }
            Ok(None) if rustix::process::getppid() == grader => {
                std::thread::sleep(std::time::Duration::from_millis(10));
            }
            _ => {
                kill_adopted();
                let _ = rustix::process::kill_current_process_group(rustix::process::Signal::KILL);
                return SETUP_FAILED;
            }
        }
    }
}

/// Kills this process's children (its own and the orphans it adopted as a
/// subreaper, which may have left its process group), as
/// `/proc/self/task/*/children` lists them.
fn kill_adopted() {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return;
    };
    for task in tasks.flatten() {
        let list = std::fs::read_to_string(task.path().join("children")).unwrap_or_default();
        for pid in list.split_whitespace().filter_map(|p| p.parse().ok()) {
            if let Some(pid) = rustix::process::Pid::from_raw(pid) {
                let _ = rustix::process::kill_process(pid, rustix::process::Signal::KILL);
            }
        }
    }
}

/// Closes every file descriptor above the standard three: those listed in
/// `/proc/self/fd` (the list is read whole first, its own descriptor closed
/// before any is closed), or without `/proc` every one below 1024.
fn close_inherited() {
    let listed: Option<Vec<i32>> = std::fs::read_dir("/proc/self/fd").ok().map(|dir| {
        dir.flatten()
            .filter_map(|e| e.file_name().to_str()?.parse().ok())
            .collect()
    });
    let open = listed.unwrap_or_else(|| (3..1024).collect());
    for fd in open.into_iter().filter(|&fd| fd > 2) {
        // The reader's own descriptor is already closed: EBADF, ignored.
        let _ = nix::unistd::close(fd);
    }
}

fn fail(why: &str) -> i32 {
    eprintln!("spintop course: {SETUP_MARK}: {why}");
    SETUP_FAILED
}

/// Root gives up root: no groups, group and user `nobody`. Dumpable again
/// (a change of user clears it), so that the process may still read its own
/// `/proc/self/fd`.
fn become_nobody() -> std::io::Result<()> {
    rustix::thread::set_thread_groups(&[])?;
    rustix::thread::set_thread_gid(Gid::from_raw(NOBODY))?;
    rustix::thread::set_thread_uid(Uid::from_raw(NOBODY))?;
    rustix::process::set_dumpable_behavior(rustix::process::DumpableBehavior::Dumpable)?;
    Ok(())
}

/// New user, mount and network namespaces, this process root in the first
/// (mapped to who it was), its mounts private to it.
fn enter_namespaces() -> Result<(), String> {
    let (uid, gid) = (rustix::process::getuid(), rustix::process::getgid());
    use rustix::thread::UnshareFlags as U;
    // NOTE: rustix deprecates its safe `unshare` for `unshare_unsafe`, whose
    // one hazard is `CLONE_FILES` (a file table no longer shared with other
    // threads); this process has one thread and asks for no `CLONE_FILES`.
    #[allow(deprecated)]
    rustix::thread::unshare(U::NEWUSER | U::NEWNS | U::NEWNET)
        .map_err(|e| format!("unshare: {e} (unprivileged user namespaces are not allowed here)"))?;
    let write = |file: &str, text: String| {
        std::fs::write(format!("/proc/self/{file}"), text).map_err(|e| format!("{file}: {e}"))
    };
    write("setgroups", "deny".into())?;
    write("uid_map", format!("0 {} 1", uid.as_raw()))?;
    write("gid_map", format!("0 {} 1", gid.as_raw()))?;
    mount::mount_change(
        "/",
        MountPropagationFlags::REC | MountPropagationFlags::PRIVATE,
    )
    .map_err(|e| format!("making the mounts private: {e}"))
}

/// Every mount read-only but `writable` (bound onto itself first, so that
/// it stays writable) and the kernel's own (`/proc`, `/sys`, `/dev`,
/// where no file is written).
fn read_only_but(writable: &Path) -> Result<String, String> {
    // As the mount table names it (no `..`, no link).
    let writable = &writable
        .canonicalize()
        .map_err(|e| format!("{}: {e}", writable.display()))?;
    mount::mount_bind(writable, writable).map_err(|e| format!("{}: {e}", writable.display()))?;
    let table = std::fs::read_to_string("/proc/self/mountinfo").map_err(text)?;
    let kernel = |p: &Path| {
        ["/proc", "/sys"].iter().any(|k| p.starts_with(k))
            || p == Path::new("/dev")
            || p.starts_with("/dev/pts")
    };
    let mut done = 0;
    let mut refused = Vec::new();
    for (point, options) in table.lines().filter_map(mount_line) {
        if point.starts_with(writable) || kernel(&point) {
            continue;
        }
        let mut flags = MountFlags::BIND | MountFlags::RDONLY;
        for (word, flag) in [
            ("nosuid", MountFlags::NOSUID),
            ("nodev", MountFlags::NODEV),
            ("noexec", MountFlags::NOEXEC),
            ("noatime", MountFlags::NOATIME),
            ("nodiratime", MountFlags::NODIRATIME),
            ("relatime", MountFlags::RELATIME),
        ] {
            if options.split(',').any(|o| o == word) {
                flags |= flag;
            }
        }
        match mount::mount_remount(&point, flags, "") {
            Ok(()) => done += 1,
            Err(e) => refused.push(format!("{}: {e}", point.display())),
        }
    }
    if refused.is_empty() {
        Ok(format!(
            "user, mount and network; {done} mounts read-only, {} writable",
            writable.display()
        ))
    } else {
        Err(format!(
            "these mounts stay writable: {}",
            refused.join(", ")
        ))
    }
}

/// A line of `/proc/self/mountinfo`: its mount point and its options.
fn mount_line(line: &str) -> Option<(PathBuf, String)> {
    let fields: Vec<&str> = line.split(' ').collect();
    let point = fields.get(4)?;
    let options = fields.get(5)?;
    Some((PathBuf::from(unescape(point)), options.to_string()))
}

/// A mount point as mountinfo escapes it (`\040` for a space).
fn unescape(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let octal = bytes.get(i + 1..i + 4).and_then(|d| {
            std::str::from_utf8(d)
                .ok()
                .and_then(|d| u8::from_str_radix(d, 8).ok())
        });
        match (bytes[i], octal) {
            (b'\\', Some(b)) => {
                out.push(b);
                i += 4;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The runner's root: an empty, read-only file system that holds the
/// program (`/runner`) and nothing else, made this process's root.
fn empty_root(program: &Path) -> Result<String, String> {
    // Opened in this mount namespace, before the new root hides the path
    // (the program may live under the folder the root is mounted on).
    let file = rfs::open(program, OFlags::PATH | OFlags::CLOEXEC, Mode::empty())
        .map_err(|e| format!("{}: {e}", program.display()))?;
    fn step(what: &'static str) -> impl Fn(rustix::io::Errno) -> String {
        move |e| format!("{what}: {e}")
    }
    mount::mount(
        "tmpfs",
        NEW_ROOT,
        "tmpfs",
        MountFlags::NOSUID | MountFlags::NODEV,
        Some(c"size=64k,mode=0755"),
    )
    .map_err(step("a new root"))?;
    let inside = format!("{NEW_ROOT}{RUNNER}");
    std::fs::File::create(&inside).map_err(|e| format!("{inside}: {e}"))?;
    let source = format!("/proc/self/fd/{}", file.as_raw_fd());
    mount::mount_bind(&source, &inside).map_err(step("the runner into its root"))?;
    drop(file);
    mount::mount_remount(
        &inside,
        MountFlags::BIND | MountFlags::RDONLY | MountFlags::NOSUID | MountFlags::NODEV,
        "",
    )
    .map_err(step("the runner read-only"))?;
    let old = format!("{NEW_ROOT}/old");
    std::fs::create_dir(&old).map_err(|e| format!("{old}: {e}"))?;
    rustix::process::pivot_root(NEW_ROOT, &old).map_err(step("pivot_root"))?;
    rustix::process::chdir("/").map_err(step("chdir"))?;
    mount::unmount("/old", UnmountFlags::DETACH).map_err(step("leaving the old root"))?;
    std::fs::remove_dir("/old").map_err(|e| format!("/old: {e}"))?;
    mount::mount_remount(
        "/",
        MountFlags::RDONLY | MountFlags::NOSUID | MountFlags::NODEV,
        "",
    )
    .map_err(step("the new root read-only"))?;
    Ok("user, mount and network; an empty read-only root holding the runner alone".into())
}

/// Landlock: a build writes below its folder only; a runner reads and runs
/// itself and nothing else. `Err` when the kernel enforces nothing.
fn landlock(kind: &Kind, program: &Path) -> Result<String, String> {
    use landlock::{
        ABI, Access, AccessFs, Ruleset, RulesetAttr, RulesetCreatedAttr, RulesetStatus,
        path_beneath_rules,
    };
    let abi = ABI::V5;
    let all = AccessFs::from_all(abi);
    let created = Ruleset::default()
        .handle_access(all)
        .map_err(text)?
        .create()
        .map_err(text)?;
    let ruleset = match kind {
        Kind::Build { writable } => created
            .add_rules(path_beneath_rules(["/"], AccessFs::from_read(abi)))
            .map_err(text)?
            .add_rules(path_beneath_rules([writable], all))
            .map_err(text)?
            .add_rules(path_beneath_rules(["/dev/null"], AccessFs::WriteFile))
            .map_err(text)?,
        Kind::Run => created
            .add_rules(path_beneath_rules(
                [program],
                AccessFs::Execute | AccessFs::ReadFile,
            ))
            .map_err(text)?,
        // Probing: whether the kernel enforces a ruleset at all.
        Kind::Probe => created
            .add_rules(path_beneath_rules(["/"], AccessFs::from_read(abi)))
            .map_err(text)?,
    };
    let status = ruleset.restrict_self().map_err(text)?;
    match status.ruleset {
        RulesetStatus::NotEnforced => Err("this kernel has no Landlock".into()),
        RulesetStatus::PartiallyEnforced => Ok("partly enforced (an older Landlock)".into()),
        RulesetStatus::FullyEnforced => Ok("enforced".into()),
    }
}

/// The calls refused outright (no argument looked at): for every program,
/// those that reach other processes, keys, BPF, modules; for a runner also
/// sockets, signals, new processes, mounts and memory files.
fn denied_calls(runner: bool) -> Vec<i64> {
    let mut denied: Vec<i64> = vec![
        libc::SYS_ptrace,
        libc::SYS_process_vm_readv,
        libc::SYS_process_vm_writev,
        libc::SYS_keyctl,
        libc::SYS_add_key,
        libc::SYS_request_key,
        libc::SYS_bpf,
        libc::SYS_perf_event_open,
        libc::SYS_userfaultfd,
        libc::SYS_io_uring_setup,
        libc::SYS_open_by_handle_at,
        libc::SYS_name_to_handle_at,
        libc::SYS_kexec_load,
        libc::SYS_init_module,
        libc::SYS_finit_module,
    ];
    if runner {
        denied.extend([
            libc::SYS_socket,
            libc::SYS_socketpair,
            libc::SYS_connect,
            libc::SYS_bind,
            libc::SYS_listen,
            libc::SYS_kill,
            libc::SYS_tkill,
            libc::SYS_tgkill,
            libc::SYS_rt_sigqueueinfo,
            libc::SYS_rt_tgsigqueueinfo,
            libc::SYS_pidfd_open,
            libc::SYS_pidfd_send_signal,
            libc::SYS_pidfd_getfd,
            libc::SYS_clone,
            libc::SYS_clone3,
            libc::SYS_unshare,
            libc::SYS_setns,
            libc::SYS_mount,
            libc::SYS_umount2,
            libc::SYS_pivot_root,
            libc::SYS_chroot,
            libc::SYS_personality,
            // The new mount API and memory-backed files: nothing to mount,
            // and no file (executable or not) outside the empty root.
            libc::SYS_fsopen,
            libc::SYS_fsconfig,
            libc::SYS_fsmount,
            libc::SYS_fspick,
            libc::SYS_open_tree,
            libc::SYS_move_mount,
            libc::SYS_mount_setattr,
            libc::SYS_memfd_create,
            libc::SYS_memfd_secret,
            // The launcher's wall-clock alarm stays.
            libc::SYS_setitimer,
        ]);
        #[cfg(target_arch = "x86_64")]
        denied.extend([libc::SYS_fork, libc::SYS_vfork, libc::SYS_alarm]);
    }
    denied
}

/// The system calls a sandbox's program may not make (each fails with
/// EPERM): no `ptrace` or reading another process's memory, no socket but a
/// local one for a build and none for a runner, and for a runner no signal
/// to anyone and no new process or thread.
fn seccomp(kind: &Kind) -> Result<String, String> {
    use seccompiler::{
        SeccompAction, SeccompCmpArgLen, SeccompCmpOp, SeccompCondition, SeccompFilter,
        SeccompRule, TargetArch,
    };
    let arch = TargetArch::try_from(std::env::consts::ARCH).map_err(text)?;
    let runner = matches!(kind, Kind::Run | Kind::Probe);
    let denied = denied_calls(runner);
    let mut rules: std::collections::BTreeMap<i64, Vec<SeccompRule>> =
        denied.into_iter().map(|s| (s, Vec::new())).collect();
    // No `prctl` that would let the program outlive the grader or be read
    // from outside: not its parent-death signal, its dumpable flag or a
    // subreaper's role (builds and runners alike).
    let mut prctl = Vec::new();
    for option in [
        libc::PR_SET_PDEATHSIG,
        libc::PR_SET_DUMPABLE,
        libc::PR_SET_CHILD_SUBREAPER,
        libc::PR_SET_PTRACER,
    ] {
        let is = SeccompCondition::new(0, SeccompCmpArgLen::Dword, SeccompCmpOp::Eq, option as u64)
            .map_err(text)?;
        prctl.push(SeccompRule::new(vec![is]).map_err(text)?);
    }
    rules.insert(libc::SYS_prctl, prctl);
    if runner {
        // No handler for (or ignoring of) the wall-clock alarm's SIGALRM.
        let alarm = SeccompCondition::new(
            0,
            SeccompCmpArgLen::Dword,
            SeccompCmpOp::Eq,
            libc::SIGALRM as u64,
        )
        .map_err(text)?;
        rules.insert(
            libc::SYS_rt_sigaction,
            vec![SeccompRule::new(vec![alarm]).map_err(text)?],
        );
    }
    if !runner {
        // A build's socket: a local one only (no internet, no netlink).
        let local = SeccompCondition::new(
            0,
            SeccompCmpArgLen::Dword,
            SeccompCmpOp::Ne,
            libc::AF_UNIX as u64,
        )
        .map_err(text)?;
        rules.insert(
            libc::SYS_socket,
            vec![SeccompRule::new(vec![local]).map_err(text)?],
        );
    }
    let filter = SeccompFilter::new(
        rules,
        SeccompAction::Allow,
        SeccompAction::Errno(libc::EPERM as u32),
        arch,
    )
    .map_err(text)?;
    let program: seccompiler::BpfProgram = filter.try_into().map_err(text)?;
    seccompiler::apply_filter(&program).map_err(text)?;
    Ok(if runner {
        "no socket, ptrace, signal, new process, mount or memfd; no prctl of its parent-death signal".into()
    } else {
        "no internet socket, no ptrace, no prctl of its parent-death signal".into()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mount_line_gives_its_point_and_options() {
        let line =
            "36 35 98:0 / /work/my\\040course rw,nosuid,relatime shared:1 - ext4 /dev/vda rw";
        assert_eq!(
            mount_line(line),
            Some((
                PathBuf::from("/work/my course"),
                "rw,nosuid,relatime".into()
            ))
        );
        assert_eq!(unescape("a\\134b"), "a\\b");
    }
}
