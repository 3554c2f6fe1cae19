//! The process model at its edges: a snippet that attacks its supervisor
//! (holds its control pipe, stops it, kills it), a server killed with
//! SIGKILL or stopped, the stop signals; each as root with real snippets,
//! and as another user with the stand-in cargo (see [`super::fake_cargo`]),
//! in each unit the machine allows. All end-to-end: they compile, or wait
//! for real time limits.

use super::*;
use rustix::process::Signal;

/// F4: each of SIGTERM, SIGINT, SIGHUP and SIGQUIT during a run stops
/// `spintop book` with a word, and no process it started survives it: not
/// the snippet, its `sleep`, or the busy loop it detached; and SIGTERM
/// during a compile leaves no cargo or rustc behind.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_signal_stops_spintop_book_and_leaves_no_process_it_started() {
    use rustix::process::Signal;
    let root = std::env::temp_dir().join(format!("spintop-server-signals-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let site = site(&root);
    let scratch = root.join("scratch");
    for (signal, name) in [
        (Signal::TERM, "SIGTERM"),
        (Signal::INT, "SIGINT"),
        (Signal::HUP, "SIGHUP"),
        (Signal::QUIT, "SIGQUIT"),
    ] {
        let mut book = Book::start(&site, &scratch);
        book.wait_line("▶ is ready");
        for f in ["sleeper.pid", "escapee.pid"] {
            let _ = std::fs::remove_file(scratch.join(f));
        }
        book.run(LEAVES_CHILDREN);
        assert!(
            wait_for(Duration::from_secs(300), || left_children(&scratch).len()
                == 2),
            "{name}: the snippet did not start its children"
        );
        let mut started = descendants(book.child.id() as i32);
        started.extend(left_children(&scratch));
        assert!(started.len() >= 4, "{name}: {started:?}");
        let status = book.stop(signal);
        assert_eq!(status.code(), Some(0), "{name}: {status:?}");
        let last = book.wait_line("stopped");
        assert!(last.contains(&format!("stopped ({name})")), "{last}");
        for pid in started {
            assert!(
                !alive(pid),
                "{name}: {pid} ({}) outlived spintop book",
                cmdline(pid)
            );
        }
    }
    // Mid-compile: a compile-time loop keeps rustc busy.
    let mut book = Book::start(&site, &scratch);
    book.wait_line("▶ is ready");
    book.run(
        "#![allow(long_running_const_eval)]\nconst N: u64 = { let mut i = 0u64; while i < u64::MAX { i += 1; } i };\nfn main() { println!(\"{N}\"); }",
    );
    let server = book.child.id() as i32;
    let mut started = Vec::new();
    assert!(
        wait_for(Duration::from_secs(120), || {
            started = descendants(server);
            started
                .iter()
                .any(|&p| cmdline(p).contains("spintop_snippet_"))
        }),
        "no rustc for the snippet"
    );
    let program = |p: i32| cmdline(p).split(' ').next().unwrap_or("").to_string();
    assert!(
        started.iter().any(|&p| program(p).ends_with("cargo")),
        "no cargo among {started:?}"
    );
    assert_eq!(book.stop(Signal::TERM).code(), Some(0));
    for pid in started {
        assert!(
            !alive(pid),
            "{pid} ({}) outlived spintop book",
            cmdline(pid)
        );
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// A snippet that leaves its session and then kills its own supervisor,
/// found through the machine's `/proc` (the stage's parent): any process
/// of the reader may, outside a PID namespace. What it left is adopted by
/// `spintop book`, a child subreaper, and not by the dead supervisor's
/// session sweep, since it is in a session of its own.
fn kills_its_supervisor() -> String {
    attacker(
        r#"fn main() {
    daemon("escapee");
    let supervisor = parent(&parent(&me()));
    println!("killing my supervisor {supervisor}");
    Command::new("kill").args(["-9", &supervisor]).status().unwrap();
    std::thread::sleep(std::time::Duration::from_secs(30));
}
"#,
    )
}

/// A snippet of `main` and what the attacks share: `parent` and `me`, a
/// process id as the machine's `/proc` numbers it, and `daemon(NAME)`,
/// which starts a process in a session of its own that writes its id to
/// `NAME.pid` and sleeps forever.
fn attacker(main: &str) -> String {
    let helpers = r#"use std::process::Command;
/// The parent of `pid`, as the machine's /proc numbers it.
fn parent(pid: &str) -> String {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    stat[stat.rfind(')').unwrap() + 2..].split(' ').nth(1).unwrap().to_string()
}
/// This process, as the machine's /proc numbers it.
fn me() -> String {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap();
    stat.split(' ').next().unwrap().to_string()
}
/// A daemon in a session of its own; returns once it has written NAME.pid.
fn daemon(name: &str) {
    let script = format!("setsid sh -c 'read -r pid rest < /proc/self/stat; echo $pid > {name}.pid.tmp; mv {name}.pid.tmp {name}.pid; while :; do sleep 1; done' &");
    Command::new("sh").args(["-c", &script]).status().unwrap();
    while std::fs::metadata(format!("{name}.pid")).is_err() {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}
"#;
    format!("{helpers}{main}")
}

/// F2 and F4 for a snippet that kills its supervisor, in each unit where
/// it can name it (a cgroup, the process group; in a PID namespace it has
/// no process id to name): `spintop book` kills what lands on it (so one
/// tree at a time holds), reaps it (no zombie is left on the server), and
/// a stop leaves nothing running.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_snippet_that_kills_its_supervisor_leaves_nothing_running() {
    let root = scratch_root("escape");
    let site = site(&root);
    for unit in [Containment::Cgroup, Containment::Group] {
        let scratch = root.join(format!("scratch-{}", unit.name()));
        let Some(mut book) = book_in_unit(&site, &scratch, unit) else {
            continue;
        };
        book.wait_line("▶ is ready");
        book.run(&kills_its_supervisor());
        let escapee = pid_file(&scratch, "escapee.pid", Duration::from_secs(300))
            .expect("the snippet did not start its escapee");
        let server = book.pid();
        assert!(
            wait_for(Duration::from_secs(5), || !alive(escapee)),
            "{}: {escapee} ({}) outlived its run, under {server}",
            unit.name(),
            cmdline(escapee)
        );
        let zombies = || -> Vec<i32> {
            processes()
                .iter()
                .filter(|&&(_, ppid, state)| ppid == server && state == 'Z')
                .map(|&(pid, _, _)| pid)
                .collect()
        };
        assert!(
            wait_for(Duration::from_secs(5), || zombies().is_empty()),
            "zombies left on the server: {:?}",
            zombies()
        );
        let status = book.stop(Signal::TERM);
        assert_eq!(status.code(), Some(0), "{status:?}");
        let last = book.wait_line("stopped");
        assert!(
            last.contains("nothing it started is left running"),
            "{last}"
        );
        assert!(!alive(escapee));
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// `--open` never puts the address on a command line, where every user can
/// read it (`/proc/PID/cmdline`): the browser's opener gets a file only the
/// reader can read, which forwards to the address, and which is gone once
/// the server stops. The opener here is a stand-in that records what it got.
#[test]
#[ignore = "end-to-end: runs spintop book with its background build"]
fn open_hands_the_browser_a_file_only_the_reader_can_read_not_the_address() {
    use std::os::unix::fs::PermissionsExt;
    let root = std::env::temp_dir().join(format!("spintop-server-open-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let site = site(&root);
    let bin = root.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let record = root.join("record");
    let opener = bin.join("xdg-open");
    std::fs::write(
        &opener,
        "#!/bin/sh\n{ echo \"$*\"; stat -c %a \"$1\"; cat \"$1\"; } > \"$RECORD.tmp\"; mv \"$RECORD.tmp\" \"$RECORD\"\n",
    )
    .unwrap();
    std::fs::set_permissions(&opener, std::fs::Permissions::from_mode(0o755)).unwrap();
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap());
    let options = BookOptions {
        args: vec!["--open".into()],
        env: vec![
            ("PATH".into(), path.into()),
            ("RECORD".into(), record.clone().into()),
        ],
        ..BookOptions::default()
    };
    let mut book = Book::start_with(&site, &root.join("scratch"), options);
    assert!(
        wait_for(Duration::from_secs(20), || record.is_file()),
        "the opener was not called"
    );
    let seen = std::fs::read_to_string(&record).unwrap();
    let mut lines = seen.lines();
    let argument = lines.next().unwrap();
    assert!(
        !argument.contains(&book.token),
        "the token was on a command line: {argument}"
    );
    assert_eq!(lines.next(), Some("600"), "{seen}");
    let address = format!("http://127.0.0.1:{}/?token={}", book.port, book.token);
    assert!(seen.contains(&format!("url={address}")), "{seen}");
    assert_eq!(book.stop(rustix::process::Signal::TERM).code(), Some(0));
    assert!(!Path::new(argument).exists(), "{argument} is left behind");
    let _ = std::fs::remove_dir_all(&root);
}

/// A snippet that attacks its supervisor, found through the machine's
/// `/proc` (the stage's parent; in a PID namespace it has no process id
/// the snippet could name): it opens the supervisor's control pipe for
/// writing and keeps it open, tries to stop the supervisor (SIGSTOP),
/// writes what it managed to `attack`, starts a daemon in a session of its
/// own, writes its own and the daemon's process ids (the machine's), and
/// loops.
fn attacks_its_supervisor() -> String {
    attacker(
        r#"fn main() {
    let me = me();
    let supervisor = parent(&parent(&me));
    let held = std::fs::OpenOptions::new().write(true).open(format!("/proc/{supervisor}/fd/0"));
    let stopped = Command::new("kill")
        .args(["-STOP", &supervisor])
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    std::fs::write(
        "attack",
        format!("held its pipe: {}\nstopped it: {stopped}\n", held.is_ok()),
    )
    .unwrap();
    daemon("daemon");
    std::fs::write("snippet.pid", &me).unwrap();
    loop {
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
}
"#,
    )
}

/// [`attacks_its_supervisor`] as a shell script, for the stand-in cargo.
fn attacks_its_supervisor_script() -> String {
    script(
        r#"parent() { read -r line < "/proc/$1/stat"; set -- ${line##*) }; echo "$2"; }
read -r me rest < /proc/self/stat
supervisor=$(parent "$(parent "$me")")
held=false
if (exec 9>"/proc/$supervisor/fd/0") 2>/dev/null; then exec 9>"/proc/$supervisor/fd/0"; held=true; fi
stopped=false
if kill -STOP "$supervisor" 2>/dev/null; then stopped=true; fi
printf 'held its pipe: %s\nstopped it: %s\n' "$held" "$stopped" > attack
setsid sh -c 'read -r pid rest < /proc/self/stat; echo $pid > daemon.pid.tmp; mv daemon.pid.tmp daemon.pid; while :; do sleep 1; done' &
while [ ! -f daemon.pid ]; do sleep 0.01; done
echo "$me" > snippet.pid
while :; do sleep 1; done
"#,
    )
}

/// The processes of a running attack in `scratch`: the supervisor (a child
/// of `server`), the stage, the snippet and its daemon; once the snippet
/// has written its files (within `limit`: a cold build).
fn attack_tree(scratch: &Path, server: i32, limit: Duration) -> Vec<i32> {
    let snippet = pid_file(scratch, "snippet.pid", limit).expect("the snippet did not start");
    let daemon = pid_file(scratch, "daemon.pid", Duration::from_secs(5)).expect("no daemon");
    let stage = parent_of(snippet).expect("no stage");
    let supervisor = parent_of(stage).expect("no supervisor");
    assert_eq!(
        parent_of(supervisor),
        Some(server),
        "{}",
        cmdline(supervisor)
    );
    let tree = vec![supervisor, stage, snippet, daemon];
    for &pid in &tree {
        assert!(alive(pid), "{pid} is not running");
    }
    tree
}

/// What the attack in `scratch` managed, as it wrote it.
fn attack_report(scratch: &Path) -> String {
    std::fs::read_to_string(scratch.join("attack")).unwrap_or_default()
}

/// SIGKILL of `book` (which runs an attack in `scratch`): every process of
/// the tree is gone within the run's time limit (10 s), and how long that
/// took.
fn sigkill_ends_the_tree(mut book: Book, scratch: &Path, what: &str) -> Duration {
    let tree = attack_tree(scratch, book.pid(), Duration::from_secs(600));
    let report = attack_report(scratch);
    assert!(report.contains("stopped it: false"), "{what}: {report}");
    let killed = Instant::now();
    book.signal(Signal::KILL);
    let _ = book.child.wait();
    let gone = wait_for(Duration::from_secs(10), || !tree.iter().any(|&p| alive(p)));
    let took = killed.elapsed();
    let left: Vec<String> = tree
        .iter()
        .filter(|&&p| alive(p))
        .map(|&p| format!("{p} ({})", cmdline(p)))
        .collect();
    assert!(
        gone,
        "{what}: alive 10 s after SIGKILL of the server: {left:?}"
    );
    eprintln!("{what}: {report:?}; the tree was gone {took:?} after SIGKILL of the server");
    took
}

/// `spintop book` serving `site` with snippets in `scratch`, its trees
/// ended at most as `unit` says; `None`, said, where this machine gives a
/// weaker unit.
fn book_in_unit(site: &Path, scratch: &Path, unit: Containment) -> Option<Book> {
    let options = BookOptions {
        args: vec!["--containment".into(), unit.name().into()],
        ..BookOptions::default()
    };
    let mut book = Book::start_with(site, scratch, options);
    let got = book.unit();
    if got != unit.described() {
        eprintln!("{}: this machine gives {got}: skipped", unit.name());
        return None;
    }
    Some(book)
}

/// The units to try.
const UNITS: [Containment; 3] = [
    Containment::Namespace,
    Containment::Cgroup,
    Containment::Group,
];

/// A snippet that holds its supervisor's control pipe (root may open it;
/// another user may not: the supervisor is not dumpable) and tries to stop
/// it (forbidden to every snippet), then daemonises and loops: SIGKILL of
/// `spintop book` (as the out-of-memory killer would) leaves no process of
/// it, in each unit. As root, with real snippets.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn sigkill_of_the_server_leaves_nothing_of_a_snippet_that_attacks_its_supervisor() {
    let root = scratch_root("sigkill");
    let site = site(&root);
    for unit in UNITS {
        let scratch = root.join(format!("scratch-{}", unit.name()));
        let Some(book) = book_in_unit(&site, &scratch, unit) else {
            continue;
        };
        book.run(&attacks_its_supervisor());
        sigkill_ends_the_tree(book, &scratch, unit.name());
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// The same attack by another user (uid 65534): it cannot even open its
/// supervisor's control pipe, nor stop it, and SIGKILL of its server leaves
/// nothing, in each unit that user may have (not a cgroup here).
#[test]
#[ignore = "end-to-end: another user, real time"]
fn sigkill_of_the_server_leaves_nothing_of_another_users_attacking_snippet() {
    let _one = one_nobody_at_a_time();
    for unit in UNITS {
        let root = scratch_root(&format!("sigkill-nobody-{}", unit.name()));
        let Some(mut book) = nobody_book(&root, unit, None) else {
            return;
        };
        let got = book.unit();
        if got != unit.described() {
            eprintln!("{}: uid {NOBODY} gets {got} here: skipped", unit.name());
            drop(book);
            let _ = std::fs::remove_dir_all(&root);
            continue;
        }
        book.run(&attacks_its_supervisor_script());
        let scratch = root.join("scratch");
        wait_for(Duration::from_secs(30), || {
            scratch.join("snippet.pid").is_file()
        });
        let report = attack_report(&scratch);
        assert!(report.contains("held its pipe: false"), "{report}");
        sigkill_ends_the_tree(book, &scratch, &format!("uid {NOBODY}, {}", unit.name()));
        let _ = std::fs::remove_dir_all(&root);
    }
}

/// While the server is stopped (Ctrl-Z, SIGSTOP), its snippet still ends at
/// the time limit (10 s): the supervisor keeps its own clock. `book` runs
/// `code`, which writes `snippet.pid` and `daemon.pid` into `scratch`.
fn a_stopped_server_still_ends_its_snippet(mut book: Book, scratch: &Path, code: &str) {
    book.run(code);
    let tree = attack_tree(scratch, book.pid(), Duration::from_secs(600));
    // The supervisor's age: its clock started with it.
    let before = age(tree[0]).unwrap();
    let stopped = Instant::now();
    book.signal(Signal::STOP);
    let limit = Duration::from_secs(10);
    let gone = wait_for(limit + Duration::from_secs(3), || {
        !tree.iter().any(|&p| alive(p))
    });
    let took = before + stopped.elapsed();
    book.signal(Signal::CONT);
    assert!(
        gone,
        "alive {took:?} after its supervisor started, the server stopped"
    );
    // Not before its limit (the age is read to 10 ms).
    assert!(took + Duration::from_millis(50) >= limit, "{took:?}");
    eprintln!(
        "the stopped server's snippet was gone {took:?} after its supervisor started (limit {limit:?}; the server stopped {before:?} after it)"
    );
    let status = book.stop(Signal::TERM);
    assert_eq!(status.code(), Some(0), "{status:?}");
    let last = book.wait_line("stopped");
    assert!(
        last.contains("nothing it started is left running"),
        "{last}"
    );
}

#[test]
#[ignore = "end-to-end: compiles snippets, real time"]
fn a_stopped_servers_snippet_still_ends_at_its_limit() {
    let root = scratch_root("stopped");
    let scratch = root.join("scratch");
    let book = Book::start(&site(&root), &scratch);
    a_stopped_server_still_ends_its_snippet(book, &scratch, &attacks_its_supervisor());
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
#[ignore = "end-to-end: another user, real time"]
fn a_stopped_servers_snippet_still_ends_at_its_limit_as_another_user() {
    let _one = one_nobody_at_a_time();
    let root = scratch_root("stopped-nobody");
    let Some(book) = nobody_book(&root, Containment::Group, None) else {
        return;
    };
    let code = attacks_its_supervisor_script();
    a_stopped_server_still_ends_its_snippet(book, &root.join("scratch"), &code);
    let _ = std::fs::remove_dir_all(&root);
}

/// A snippet that holds its supervisor's control pipe (as root may) no
/// longer holds a stop up: SIGTERM ends the tree at once, and `spintop
/// book` says, truly, that nothing it started is left.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn sigterm_with_a_snippet_holding_the_control_pipe_says_nothing_is_left() {
    let root = scratch_root("sigterm-pipe");
    let scratch = root.join("scratch");
    let mut book = Book::start(&site(&root), &scratch);
    book.run(&attacks_its_supervisor());
    let tree = attack_tree(&scratch, book.pid(), Duration::from_secs(600));
    let asked = Instant::now();
    assert_eq!(book.stop(Signal::TERM).code(), Some(0));
    let took = asked.elapsed();
    let last = book.wait_line("stopped");
    assert!(
        last.contains("nothing it started is left running"),
        "{last}"
    );
    for pid in tree {
        assert!(
            !alive(pid),
            "{pid} ({}) outlived spintop book",
            cmdline(pid)
        );
    }
    eprintln!("stopped in {took:?}");
    let _ = std::fs::remove_dir_all(&root);
}

/// A snippet may not stop its supervisor in any unit (a seccomp filter;
/// in a PID namespace it has no process id to name either): the attempt
/// fails, and the run ends at its limit, whole, with the limit's note.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_snippet_cannot_stop_its_supervisor_in_any_unit() {
    for unit in UNITS {
        let s = start_in(&format!("stopsup-{}", unit.name()), limits(), unit);
        let got = s.server.containment();
        if got != unit {
            eprintln!(
                "{}: this machine gives {}: skipped",
                unit.name(),
                got.name()
            );
            continue;
        }
        let scratch = s.root.join("scratch");
        let (status, v) = s.run(&attacks_its_supervisor());
        assert_eq!(status, 200, "{v}");
        assert_eq!(v["error"], "time limit", "{}: {v}", unit.name());
        let shown = v["result"].as_str().unwrap();
        assert!(shown.contains("time limit (3 s)"), "{shown}");
        let report = attack_report(&scratch);
        assert!(
            report.contains("stopped it: false"),
            "{}: {report}",
            unit.name()
        );
        let daemon = pid_file(&scratch, "daemon.pid", Duration::ZERO).unwrap();
        assert!(
            !alive(daemon),
            "{}: the daemon outlived the run",
            unit.name()
        );
    }
}

/// A supervisor that cannot end its tree in time (stopped here from
/// outside, again and again, as another process of the reader may stop it,
/// or slowed by a loaded machine) is killed by the server after its grace,
/// and what is below it first: a daemon in a session of its own, which the
/// supervisor's session and group do not hold, is gone too, even for a
/// library user that cannot sweep its strays. Process group unit, where
/// nothing else would reach that daemon.
#[test]
#[ignore = "end-to-end: compiles snippets"]
fn a_supervisor_too_slow_to_end_its_tree_is_killed_after_what_is_below_it() {
    let s = start_in("slow-supervisor", limits(), Containment::Group);
    let scratch = s.root.join("scratch");
    let me = std::process::id() as i32;
    let started = Instant::now();
    std::thread::scope(|scope| {
        let run = scope.spawn(|| s.run(LEAVES_CHILDREN));
        assert!(
            wait_for(Duration::from_secs(900), || left_children(&scratch).len()
                == 2),
            "the snippet did not start"
        );
        let supervisor = processes()
            .into_iter()
            .find(|&(p, ppid, _)| ppid == me && cmdline(p).contains("--supervise"))
            .map(|(p, _, _)| p)
            .expect("no supervisor");
        let pid = rustix::process::Pid::from_raw(supervisor).unwrap();
        while !run.is_finished() {
            let _ = rustix::process::kill_process(pid, Signal::STOP);
            std::thread::sleep(Duration::from_millis(2));
        }
        let (status, v) = run.join().unwrap();
        assert_eq!(status, 200, "{v}");
    });
    eprintln!(
        "the run with a stopped supervisor ended {:?} after it was asked",
        started.elapsed()
    );
    both_gone(&scratch);
}
